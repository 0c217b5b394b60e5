/* SPDX-License-Identifier: BSD-3-Clause */
/* Third-order LESO: ZOH current observer and explicit Euler (see leso.h). */
#include "ladrc/leso.h"
#include "require.h"

/* Euler's error poles sit at 1 - wo h: inside the unit circle only below 2. */
#define LESO_EULER_WOH_LIMIT LADRC_R(2.0)

ladrc_status_t ladrc_leso_init(ladrc_leso_t *obs, const ladrc_leso_config_t *cfg)
{
    if (obs == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!ladrc_is_positive(cfg->wo_rad_s)) {
        return LADRC_ERR_WO_RAD_S;
    }
    if (!ladrc_is_finite(cfg->b0) || cfg->b0 == LADRC_R(0.0)) {
        return LADRC_ERR_B0;
    }
    const ladrc_real_t h = cfg->dt_s;
    const ladrc_real_t wo = cfg->wo_rad_s;
    if (cfg->method == LADRC_LESO_ZOH) {
        /* expm1 keeps 1 - beta accurate when wo h is small. */
        const ladrc_real_t one_minus_beta = -ladrc_expm1(-wo * h);
        const ladrc_real_t beta = LADRC_R(1.0) - one_minus_beta;
        const ladrc_real_t omb2 = one_minus_beta * one_minus_beta;
        obs->l1 = LADRC_R(1.0) - beta * beta * beta;
        obs->l2 = LADRC_R(1.5) * omb2 * (LADRC_R(1.0) + beta) / h;
        obs->l3 = omb2 * one_minus_beta / (h * h);
    } else if (cfg->method == LADRC_LESO_EULER) {
        if (!(wo * h < LESO_EULER_WOH_LIMIT)) {
            return LADRC_ERR_LESO_EULER_UNSTABLE;
        }
        obs->l1 = LADRC_R(3.0) * wo * h;
        obs->l2 = LADRC_R(3.0) * wo * wo * h;
        obs->l3 = wo * wo * wo * h;
    } else {
        return LADRC_ERR_LESO_METHOD;
    }
    obs->h_s = h;
    obs->h2_2 = LADRC_R(0.5) * h * h;
    obs->h3_6 = h * h * h / LADRC_R(6.0);
    obs->b0 = cfg->b0;
    obs->method = cfg->method;
    ladrc_leso_reset(obs, LADRC_R(0.0));
    return LADRC_OK;
}

void ladrc_leso_reset(ladrc_leso_t *obs, ladrc_real_t y0)
{
    LADRC_REQUIRE_VOID(obs != NULL);
    obs->z1 = ladrc_is_finite(y0) ? y0 : LADRC_R(0.0);
    obs->z2 = LADRC_R(0.0);
    obs->z3 = LADRC_R(0.0);
    obs->faults = LADRC_FAULT_NONE;
}

/* One tick of the estimate (*z1, *z2, *z3) with obs's gains; it is kept when
 * an argument or the result is not finite. Every argument reaches the result
 * through +, - and * only (b0 != 0, h > 0), where an infinity or a NaN never
 * turns finite again: the arguments are checked only when the result is bad,
 * to tell an input fault from a state fault. */
static ladrc_fault_t advance(const ladrc_leso_t *obs, ladrc_real_t *z1_io, ladrc_real_t *z2_io, ladrc_real_t *z3_io,
                             ladrc_real_t y, ladrc_real_t u, ladrc_real_t accel_known, ladrc_real_t f_rate_known)
{
    const ladrc_real_t h = obs->h_s;
    const ladrc_real_t a = obs->b0 * u + accel_known;
    const ladrc_real_t g = f_rate_known;
    ladrc_real_t p1;
    ladrc_real_t p2;
    ladrc_real_t p3;
    ladrc_real_t err;
    if (obs->method == LADRC_LESO_ZOH) {
        /* Predict with the exact ZOH model, then correct with the newest y. */
        const ladrc_real_t acc = *z3_io + a;
        p1 = *z1_io + h * *z2_io + obs->h2_2 * acc + obs->h3_6 * g;
        p2 = *z2_io + h * acc + obs->h2_2 * g;
        p3 = *z3_io + h * g;
        err = y - p1;
    } else {
        /* Explicit Euler: the correction uses the error of the old estimate. */
        p1 = *z1_io + h * *z2_io;
        p2 = *z2_io + h * (*z3_io + a);
        p3 = *z3_io + h * g;
        err = y - *z1_io;
    }
    const ladrc_real_t z1 = p1 + obs->l1 * err;
    const ladrc_real_t z2 = p2 + obs->l2 * err;
    const ladrc_real_t z3 = p3 + obs->l3 * err;
    if (!ladrc_all_finite3(z1, z2, z3)) {
        const int inputs_finite = ladrc_all_finite4(y, u, accel_known, f_rate_known);
        return inputs_finite ? LADRC_FAULT_STATE : LADRC_FAULT_INPUT;
    }
    *z1_io = z1;
    *z2_io = z2;
    *z3_io = z3;
    return LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_leso_step(ladrc_leso_t *obs, ladrc_real_t y, ladrc_real_t u, ladrc_real_t accel_known,
                              ladrc_real_t f_rate_known)
{
    LADRC_REQUIRE(obs != NULL, LADRC_FAULT_STATE);
    obs->faults = advance(obs, &obs->z1, &obs->z2, &obs->z3, y, u, accel_known, f_rate_known);
    return obs->faults;
}

ladrc_fault_t ladrc_leso_step_twin(const ladrc_leso_t *obs, ladrc_leso_twin_t *twin, ladrc_real_t y, ladrc_real_t u,
                                   ladrc_real_t accel_known, ladrc_real_t f_rate_known)
{
    LADRC_REQUIRE(obs != NULL && twin != NULL, LADRC_FAULT_STATE);
    return advance(obs, &twin->z1, &twin->z2, &twin->z3, y, u, accel_known, f_rate_known);
}

/* z3 -= accel, kept finite (shared by the observer and its twins). */
static void hand_over(ladrc_real_t *z3, ladrc_real_t accel_rad_s2)
{
    const ladrc_real_t z = *z3 - accel_rad_s2;
    if (ladrc_is_finite(z)) {
        *z3 = z;
    }
}

void ladrc_leso_hand_over(ladrc_leso_t *obs, ladrc_real_t accel_rad_s2)
{
    LADRC_REQUIRE_VOID(obs != NULL);
    hand_over(&obs->z3, accel_rad_s2);
}

void ladrc_leso_twin_hand_over(ladrc_leso_twin_t *twin, ladrc_real_t accel_rad_s2)
{
    LADRC_REQUIRE_VOID(twin != NULL);
    hand_over(&twin->z3, accel_rad_s2);
}

void ladrc_leso_twin_reset(ladrc_leso_twin_t *twin, ladrc_real_t y0)
{
    LADRC_REQUIRE_VOID(twin != NULL);
    twin->z1 = ladrc_is_finite(y0) ? y0 : LADRC_R(0.0);
    twin->z2 = LADRC_R(0.0);
    twin->z3 = LADRC_R(0.0);
}
