/* SPDX-License-Identifier: BSD-3-Clause */
/* Incremental nonlinear dynamic inversion on one axis (see indi.h). */
#include "ladrc/indi.h"
#include "require.h"

#include <stddef.h>

/* |b0| for an inertia between 1e-7 and 1000 kg m^2, as on every axis (axis.c). */
#define INDI_B0_MIN LADRC_R(1e-3)
#define INDI_B0_MAX LADRC_R(1e7)
/* k dt below 1 for both gains: then (k_att + k_rate) dt < 2, the Jury bound
 * of the sampled loop (z - 1)^2 + (h C + h^2 K / 2)(z - 1) + h^2 K with
 * C = k_att + k_rate, K = k_att k_rate (the double integrator held over each
 * step under this feedback); the same bound as LADRC's wc dt < 1. */
#define INDI_K_DT_LIMIT LADRC_R(1.0)

/* Largest normalised LMS step: mu = 1 moves G onto the sample's ratio at
 * once; beyond, the step would overshoot it. */
#define INDI_ADAPT_MU_MAX LADRC_R(1.0)

/* A gain in 1/s: finite, > 0 and below 1 / dt_s. */
static int gain_ok(ladrc_real_t k, ladrc_real_t dt_s)
{
    return ladrc_is_positive(k) && k * dt_s < INDI_K_DT_LIMIT;
}

/* |g| within the range every axis accepts for b0 (J = 1 / g then stays
 * far inside the real type). */
static int effectiveness_ok(ladrc_real_t g)
{
    return ladrc_fabs(g) >= INDI_B0_MIN && ladrc_fabs(g) <= INDI_B0_MAX;
}

/* The adaptation's fields (read with adapt = 1 only), in their order. */
static ladrc_status_t check_adapt(const ladrc_indi_config_t *cfg)
{
    if (!(ladrc_is_positive(cfg->adapt_mu) && cfg->adapt_mu <= INDI_ADAPT_MU_MAX)) {
        return LADRC_ERR_INDI_ADAPT_MU;
    }
    const ladrc_real_t du_min = cfg->adapt_jerk_min_rad_s3 * cfg->dt_s / ladrc_fabs(cfg->b0);
    if (!(ladrc_is_positive(cfg->adapt_jerk_min_rad_s3) && ladrc_is_positive(du_min) &&
          ladrc_is_positive(du_min * du_min))) {
        return LADRC_ERR_INDI_ADAPT_EXCITATION;
    }
    const ladrc_real_t lo = cfg->adapt_min_ratio;
    if (!(ladrc_is_positive(lo) && lo <= LADRC_R(1.0) && effectiveness_ok(cfg->b0 * lo))) {
        return LADRC_ERR_INDI_ADAPT_MIN;
    }
    const ladrc_real_t hi = cfg->adapt_max_ratio;
    if (!(ladrc_is_finite(hi) && hi >= LADRC_R(1.0) && effectiveness_ok(cfg->b0 * hi))) {
        return LADRC_ERR_INDI_ADAPT_MAX;
    }
    return LADRC_OK;
}

ladrc_status_t ladrc_indi_init(ladrc_indi_t *indi, const ladrc_indi_config_t *cfg)
{
    if (indi == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!(ladrc_fabs(cfg->b0) >= INDI_B0_MIN && ladrc_fabs(cfg->b0) <= INDI_B0_MAX)) {
        return LADRC_ERR_B0;
    }
    if (!gain_ok(cfg->att_kp_per_s, cfg->dt_s)) {
        return LADRC_ERR_INDI_ATT_KP;
    }
    if (!gain_ok(cfg->rate_kp_per_s, cfg->dt_s)) {
        return LADRC_ERR_INDI_RATE_KP;
    }
    if (!(ladrc_is_positive(cfg->filter_rad_s) && cfg->filter_rad_s * cfg->dt_s <= LADRC_INDI_FILTER_WH_MAX)) {
        return LADRC_ERR_INDI_FILTER;
    }
    if (cfg->adapt > 1u) {
        return LADRC_ERR_INDI_ADAPT;
    }
    if (cfg->adapt) {
        const ladrc_status_t status = check_adapt(cfg);
        if (status != LADRC_OK) {
            return status;
        }
    }
    indi->inv_dt = LADRC_R(1.0) / cfg->dt_s;
    indi->b0 = cfg->b0;
    indi->adapt = cfg->adapt;
    if (cfg->adapt) {
        const ladrc_real_t a = cfg->b0 * cfg->adapt_min_ratio, b = cfg->b0 * cfg->adapt_max_ratio;
        indi->g_lo = (a < b) ? a : b; /* b0 < 0: the ratios swap ends */
        indi->g_hi = (a < b) ? b : a;
        indi->mu = cfg->adapt_mu;
        indi->du_min_Nm = cfg->adapt_jerk_min_rad_s3 * cfg->dt_s / ladrc_fabs(cfg->b0);
        indi->du_min_sq = indi->du_min_Nm * indi->du_min_Nm;
    } else {
        indi->g_lo = cfg->b0; /* G never moves */
        indi->g_hi = cfg->b0;
        indi->mu = LADRC_R(0.0);
        indi->du_min_Nm = LADRC_R(0.0);
        indi->du_min_sq = LADRC_R(0.0);
    }
    indi->k_att = cfg->att_kp_per_s;
    indi->k_rate = cfg->rate_kp_per_s;
    indi->alpha = -ladrc_expm1(-cfg->filter_rad_s * cfg->dt_s);
    ladrc_indi_reset(indi);
    return LADRC_OK;
}

void ladrc_indi_reset(ladrc_indi_t *indi)
{
    LADRC_REQUIRE_VOID(indi != NULL);
    indi->g = indi->b0;
    indi->j = LADRC_R(1.0) / indi->b0;
    indi->accel.s1 = LADRC_R(0.0);
    indi->accel.s2 = LADRC_R(0.0);
    indi->torque.s1 = LADRC_R(0.0);
    indi->torque.s2 = LADRC_R(0.0);
    indi->rate_last_rad_s = LADRC_R(0.0);
    indi->gap_torque_Nm = LADRC_R(0.0);
    indi->angle_rad = LADRC_R(0.0);
    indi->gap_ticks = 0u;
    indi->has_rate_last = 0u;
}

void ladrc_indi_engage(ladrc_indi_t *indi, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s,
                       ladrc_real_t torque_Nm)
{
    LADRC_REQUIRE_VOID(indi != NULL);
    ladrc_indi_reset(indi);
    indi->angle_rad = angle_rad;
    indi->torque.s1 = torque_Nm;
    indi->torque.s2 = torque_Nm;
    if (rate_rad_s != NULL) {
        indi->rate_last_rad_s = *rate_rad_s;
        indi->has_rate_last = 1u;
    }
}

/* Filter step (both filters, one formula). */
static void lowpass_step(ladrc_indi_lowpass_t *f, ladrc_real_t alpha, ladrc_real_t x)
{
    f->s1 += alpha * (x - f->s1);
    f->s2 += alpha * (f->s1 - f->s2);
}

/* The normalised LMS step on G (indi.h) for the filters' increments du_f
 * (N m) and domegadot_f (rad/s^2). Too small an increment (NaN included):
 * no step; a result that is not finite: G kept. */
static void adapt_step(ladrc_indi_t *indi, ladrc_real_t du_Nm, ladrc_real_t daccel_rad_s2)
{
    if (!(ladrc_fabs(du_Nm) >= indi->du_min_Nm)) {
        return;
    }
    const ladrc_real_t residual = indi->g * du_Nm - daccel_rad_s2;
    const ladrc_real_t g = indi->g - indi->mu * residual * du_Nm / (du_Nm * du_Nm + indi->du_min_sq);
    if (!ladrc_is_finite(g)) {
        return;
    }
    indi->g = ladrc_clamp(g, indi->g_lo, indi->g_hi);
    indi->j = LADRC_R(1.0) / indi->g;
}

int ladrc_indi_measure(ladrc_indi_t *indi, ladrc_real_t acting_Nm, const ladrc_real_t *rate_rad_s)
{
    LADRC_REQUIRE(indi != NULL, 0);
    /* The step just ended joins the interval since the last rate. */
    const uint32_t n = (indi->gap_ticks < UINT32_MAX) ? indi->gap_ticks + 1u : UINT32_MAX;
    const ladrc_real_t torque_sum = indi->gap_torque_Nm + acting_Nm;
    if (rate_rad_s == NULL) {
        indi->gap_ticks = n;
        indi->gap_torque_Nm = torque_sum;
        return 0;
    }
    if (indi->has_rate_last) {
        ladrc_real_t accel = (*rate_rad_s - indi->rate_last_rad_s) * indi->inv_dt;
        ladrc_real_t torque = torque_sum;
        if (n > 1u) {
            /* Means over the n steps of a gap: they obey the same identity. */
            const ladrc_real_t inv_n = LADRC_R(1.0) / (ladrc_real_t)n;
            accel *= inv_n;
            torque *= inv_n;
        }
        const ladrc_real_t accel_before = indi->accel.s2, torque_before = indi->torque.s2;
        lowpass_step(&indi->accel, indi->alpha, accel);
        lowpass_step(&indi->torque, indi->alpha, torque);
        if (indi->adapt) {
            adapt_step(indi, indi->torque.s2 - torque_before, indi->accel.s2 - accel_before);
        }
    }
    indi->rate_last_rad_s = *rate_rad_s;
    indi->gap_ticks = 0u;
    indi->gap_torque_Nm = LADRC_R(0.0);
    indi->has_rate_last = 1u;
    return 1;
}

ladrc_real_t ladrc_indi_command(const ladrc_indi_t *indi, ladrc_real_t error_rad, ladrc_real_t ref_rate_rad_s,
                                ladrc_real_t ref_accel_rad_s2, ladrc_real_t rate_rad_s)
{
    LADRC_REQUIRE(indi != NULL, LADRC_R(0.0));
    const ladrc_real_t rate_ref = indi->k_att * error_rad + ref_rate_rad_s;
    const ladrc_real_t rate_ref_dot = indi->k_att * (ref_rate_rad_s - rate_rad_s) + ref_accel_rad_s2;
    const ladrc_real_t nu = indi->k_rate * (rate_ref - rate_rad_s) + rate_ref_dot;
    return indi->torque.s2 + indi->j * (nu - indi->accel.s2);
}

ladrc_real_t ladrc_indi_get_disturbance(const ladrc_indi_t *indi)
{
    LADRC_REQUIRE(indi != NULL, LADRC_R(0.0));
    return indi->accel.s2 - indi->g * indi->torque.s2;
}

ladrc_real_t ladrc_indi_get_effectiveness(const ladrc_indi_t *indi)
{
    LADRC_REQUIRE(indi != NULL, LADRC_R(0.0));
    return indi->g;
}
