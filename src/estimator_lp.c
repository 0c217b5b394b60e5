/* SPDX-License-Identifier: BSD-3-Clause */
/* LP disturbance estimator: measured acceleration minus known input, tracked
 * by a one-parameter bounded-gain RLS (see estimator.h; rls.h, ladrc_rls1_t). */
#include "estimator_lp_internal.h"
#include "rls1_internal.h"
#include "require.h"

ladrc_status_t ladrc_lp_init(ladrc_lp_estimator_t *est, const ladrc_lp_config_t *cfg)
{
    if (est == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!ladrc_is_positive(cfg->lambda0_per_s)) {
        return LADRC_ERR_EST_LAMBDA0;
    }
    if (!ladrc_is_positive(cfg->k0_per_s)) {
        return LADRC_ERR_EST_K0;
    }
    /* Starting at the bound gives the fastest first estimate. */
    const ladrc_rls_config_t rls_cfg = {.n_params = 1u,
                                        .dt_s = cfg->dt_s,
                                        .lambda0_per_s = cfg->lambda0_per_s,
                                        .p_bound = cfg->k0_per_s,
                                        .p_initial = cfg->k0_per_s};
    const ladrc_status_t status = ladrc_rls1_init(&est->rls, &rls_cfg);
    if (status != LADRC_OK) {
        return status;
    }
    if (!(ladrc_is_finite(cfg->act_tau_s) && cfg->act_tau_s >= LADRC_R(0.0) &&
          cfg->act_tau_s <= LADRC_MOTOR_TAU_MAX_S)) {
        return LADRC_ERR_MOTOR_TAU_S;
    }
    if (cfg->act_delay_ticks > LADRC_MAX_DELAY_TICKS) {
        return LADRC_ERR_DELAY_TICKS;
    }
    est->dt_s = cfg->dt_s;
    /* tau' = tau + d h: the lag and the delay as one first-order lag. */
    const ladrc_real_t tau = cfg->act_tau_s + (ladrc_real_t)cfg->act_delay_ticks * cfg->dt_s;
    est->lead = (tau > LADRC_R(0.0)) ? 1u : 0u;
    est->lead_beta = est->lead ? -ladrc_expm1(-LADRC_LP_LEAD_MAX * cfg->dt_s / tau) : LADRC_R(1.0);
    ladrc_lp_reset(est);
    return LADRC_OK;
}

void ladrc_lp_reset(ladrc_lp_estimator_t *est)
{
    LADRC_REQUIRE_VOID(est != NULL);
    ladrc_rls1_reset(&est->rls);
    est->prev_rate_rad_s = LADRC_R(0.0);
    est->has_prev_rate = 0u;
    est->lead_x = LADRC_R(0.0);
    est->sample_rad_s2 = LADRC_R(0.0);
    est->has_sample = 0u;
    est->faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_lp_step(ladrc_lp_estimator_t *est, ladrc_real_t rate_rad_s, ladrc_real_t accel_known)
{
    LADRC_REQUIRE(est != NULL, LADRC_FAULT_STATE);
    est->has_sample = 0u;
    if (!(ladrc_is_finite(rate_rad_s) && ladrc_is_finite(accel_known))) {
        est->has_prev_rate = 0u; /* a difference across the gap would be wrong */
        est->faults = LADRC_FAULT_INPUT;
        return est->faults;
    }
    est->faults = LADRC_FAULT_NONE;
    if (est->has_prev_rate) {
        const ladrc_real_t sample = (rate_rad_s - est->prev_rate_rad_s) / est->dt_s - accel_known;
        est->faults = rls1_update(&est->rls, sample);
        est->sample_rad_s2 = sample;
        est->has_sample = ladrc_is_finite(sample) ? 1u : 0u;
    }
    est->prev_rate_rad_s = rate_rad_s;
    est->has_prev_rate = 1u;
    return est->faults;
}

ladrc_real_t ladrc_lp_get_estimate(const ladrc_lp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return lp_estimate(est);
}

ladrc_real_t ladrc_lp_get_sample(const ladrc_lp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, (ladrc_real_t)NAN);
    return lp_sample(est);
}

void ladrc_lp_hand_over(ladrc_lp_estimator_t *est, ladrc_real_t delta)
{
    LADRC_REQUIRE_VOID(est != NULL);
    if (ladrc_is_finite(delta) && ladrc_is_finite(est->lead_x + delta)) {
        const ladrc_real_t moved = est->rls.theta + delta;
        if (ladrc_is_finite(moved)) {
            est->rls.theta = moved;
        }
        est->lead_x += delta;
    }
}

ladrc_fault_t ladrc_lp_step_lead(ladrc_lp_estimator_t *est, ladrc_real_t *command_rad_s2)
{
    LADRC_REQUIRE(est != NULL && command_rad_s2 != NULL, LADRC_FAULT_STATE);
    *command_rad_s2 = lp_lead_step(est);
    return LADRC_FAULT_NONE;
}
