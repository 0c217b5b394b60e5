/* SPDX-License-Identifier: BSD-3-Clause */
/* Second-order ESO on a measured rate, ZOH current observer (see reso.h). */
#include "ladrc/reso.h"
#include "require.h"

ladrc_status_t ladrc_reso_init(ladrc_reso_t *obs, const ladrc_reso_config_t *cfg)
{
    if (obs == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    const ladrc_real_t h = cfg->dt_s;
    const ladrc_real_t wo = cfg->wo_rad_s;
    if (!ladrc_is_positive(wo)) {
        return LADRC_ERR_WO_RAD_S;
    }
    if (!ladrc_is_finite(cfg->b0) || cfg->b0 == LADRC_R(0.0)) {
        return LADRC_ERR_B0;
    }
    /* expm1 keeps 1 - beta accurate when wo h is small. */
    const ladrc_real_t one_minus_beta = -ladrc_expm1(-wo * h);
    const ladrc_real_t beta = LADRC_R(1.0) - one_minus_beta;
    obs->l1 = LADRC_R(1.0) - beta * beta;
    obs->l2 = one_minus_beta * one_minus_beta / h;
    obs->h_s = h;
    obs->h2_2 = LADRC_R(0.5) * h * h;
    obs->b0 = cfg->b0;
    ladrc_reso_reset(obs, LADRC_R(0.0));
    return LADRC_OK;
}

void ladrc_reso_reset(ladrc_reso_t *obs, ladrc_real_t w0_rad_s)
{
    LADRC_REQUIRE_VOID(obs != NULL);
    obs->z1 = ladrc_is_finite(w0_rad_s) ? w0_rad_s : LADRC_R(0.0);
    obs->z2 = LADRC_R(0.0);
    obs->faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_reso_step(ladrc_reso_t *obs, ladrc_real_t rate_rad_s, ladrc_real_t u, ladrc_real_t accel_known,
                              ladrc_real_t f_rate_known)
{
    LADRC_REQUIRE(obs != NULL, LADRC_FAULT_STATE);
    const ladrc_real_t h = obs->h_s;
    /* Predict with the exact ZOH model, then correct with the newest rate. */
    const ladrc_real_t p1 = obs->z1 + h * (obs->z2 + obs->b0 * u + accel_known) + obs->h2_2 * f_rate_known;
    const ladrc_real_t p2 = obs->z2 + h * f_rate_known;
    const ladrc_real_t err = rate_rad_s - p1;
    const ladrc_real_t z1 = p1 + obs->l1 * err;
    const ladrc_real_t z2 = p2 + obs->l2 * err;
    /* +, - and * only: a non-finite argument never gives a finite result, so
     * the arguments are checked only to tell an input from a state fault. */
    if (!(ladrc_is_finite(z1) && ladrc_is_finite(z2))) {
        obs->faults =
            ladrc_all_finite4(rate_rad_s, u, accel_known, f_rate_known) ? LADRC_FAULT_STATE : LADRC_FAULT_INPUT;
        return obs->faults;
    }
    obs->z1 = z1;
    obs->z2 = z2;
    obs->faults = LADRC_FAULT_NONE;
    return LADRC_FAULT_NONE;
}

ladrc_real_t ladrc_reso_get_rate(const ladrc_reso_t *obs)
{
    LADRC_REQUIRE(obs != NULL, LADRC_R(0.0));
    return obs->z1;
}

ladrc_real_t ladrc_reso_get_disturbance(const ladrc_reso_t *obs)
{
    LADRC_REQUIRE(obs != NULL, LADRC_R(0.0));
    return obs->z2;
}
