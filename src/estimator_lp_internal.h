/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the LP estimator's getters and its command's lead compute, for the
 * axes that own an LP estimator too (axis_lp.h, axis_hp.h, axis_hp.c): no
 * call and no NULL test on their tick's path. Not installed.
 */
#ifndef LADRC_ESTIMATOR_LP_INTERNAL_H
#define LADRC_ESTIMATOR_LP_INTERNAL_H

#include "ladrc/estimator.h"

/* d_hat (rad/s^2). */
static inline ladrc_real_t lp_estimate(const ladrc_lp_estimator_t *est)
{
    return est->rls.theta;
}

/* The latest step's sample (rad/s^2), NAN when it took none. */
static inline ladrc_real_t lp_sample(const ladrc_lp_estimator_t *est)
{
    return est->has_sample ? est->sample_rad_s2 : (ladrc_real_t)NAN;
}

/* One tick of the command's lead over the actuator on the current d_hat
 * (estimator.h); returns the compensation the command carries (rad/s^2):
 * d_hat itself without an actuator. */
static inline ladrc_real_t lp_lead_step(ladrc_lp_estimator_t *est)
{
    const ladrc_real_t d_hat = est->rls.theta;
    if (!est->lead) {
        return d_hat;
    }
    const ladrc_real_t fast = d_hat - est->lead_x;
    est->lead_x += est->lead_beta * fast;
    return d_hat + (LADRC_LP_LEAD_MAX - LADRC_R(1.0)) * fast;
}

#endif /* LADRC_ESTIMATOR_LP_INTERNAL_H */
