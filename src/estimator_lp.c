/* SPDX-License-Identifier: BSD-3-Clause */
/* LP disturbance estimator: measured acceleration minus known input, tracked
 * by a one-parameter bounded-gain RLS (see estimator.h). */
#include "ladrc/estimator.h"

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
    const ladrc_rls_config_t rls_cfg = {1u, cfg->dt_s, cfg->lambda0_per_s, cfg->k0_per_s,
                                        cfg->k0_per_s};
    const ladrc_status_t status = ladrc_rls_init(&est->rls, &rls_cfg);
    if (status != LADRC_OK) {
        return status;
    }
    est->dt_s = cfg->dt_s;
    ladrc_lp_reset(est);
    return LADRC_OK;
}

void ladrc_lp_reset(ladrc_lp_estimator_t *est)
{
    LADRC_ASSERT(est != NULL);
    ladrc_rls_reset(&est->rls, NULL);
    est->prev_rate_rad_s = LADRC_R(0.0);
    est->has_prev_rate = 0u;
    est->faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_lp_step(ladrc_lp_estimator_t *est, ladrc_real_t rate_rad_s,
                            ladrc_real_t accel_known)
{
    LADRC_ASSERT(est != NULL);
    if (!(ladrc_is_finite(rate_rad_s) && ladrc_is_finite(accel_known))) {
        est->has_prev_rate = 0u; /* a difference across the gap would be wrong */
        est->faults = LADRC_FAULT_INPUT;
        return est->faults;
    }
    est->faults = LADRC_FAULT_NONE;
    if (est->has_prev_rate) {
        const ladrc_real_t sample = (rate_rad_s - est->prev_rate_rad_s) / est->dt_s - accel_known;
        const ladrc_real_t one = LADRC_R(1.0);
        est->faults = ladrc_rls_update(&est->rls, &one, sample);
    }
    est->prev_rate_rad_s = rate_rad_s;
    est->has_prev_rate = 1u;
    return est->faults;
}

ladrc_real_t ladrc_lp_get_estimate(const ladrc_lp_estimator_t *est)
{
    return ladrc_rls_get_theta(&est->rls)[0];
}
