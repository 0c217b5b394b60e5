/* SPDX-License-Identifier: BSD-3-Clause */
/* The HP-MLADRC estimator's sample hook, inline in the family's tick
 * (axis_adrc.c); its other hooks are in axis_hp.c (axis_internal.h). */
#ifndef LADRC_AXIS_HP_H
#define LADRC_AXIS_HP_H

#include "axis_internal.h"
#include "estimator_hp_internal.h"
#include "estimator_lp_internal.h"

/* OBSERVER: z3 holds f - d_hat seen through the observer's lag, plus what
 * the fed rate h put in; the shadow, a twin of the observer on a still plant
 * told d_hat - f_known and the same h, holds exactly the parts of z3 that
 * d_hat, h and the known f_known put there (the observer is linear), so the
 * difference is the observer's view of the unknown f alone and the fit does
 * not chase its own output. The rate and the acting torque are not used.
 * GYRO: the sample s is the measured acceleration minus the known input;
 * the fit takes s less the known part f_known (the whole tone, far above the
 * noise, and no drag or coupling that moves with the manoeuvres) and LP takes
 * s minus the fit's estimate (LP tracks what the fit leaves). d_hat is their
 * sum; with the gate shut the fit's estimate is 0 and LP sees s: LP-MLADRC. */
static inline ladrc_real_t axis_hp_sample(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t acting_Nm)
{
    ladrc_hp_estimator_t *est = &axis->part.hp.est;
    if (axis->part.hp.gyro) {
        ladrc_lp_estimator_t *lp = &axis->part.hp.source.lp;
        const ladrc_real_t fitted = hp_estimate(est); /* applied over the step the rate saw */
        (void)ladrc_lp_step(lp, rate_rad_s, axis->b0 * acting_Nm + fitted);
        (void)ladrc_hp_step(est, lp_sample(lp) + fitted - axis->f_known_rad_s2);
        /* what the weight brings in, LP gives up at once */
        const ladrc_real_t handover = hp_handover(est);
        if (handover != LADRC_R(0.0)) {
            ladrc_lp_hand_over(lp, -handover);
        }
        return lp_estimate(lp) + hp_estimate(est);
    }
    ladrc_leso_twin_t *shadow = &axis->part.hp.source.shadow;
    (void)ladrc_leso_step_twin(&axis->leso, shadow, LADRC_R(0.0), LADRC_R(0.0),
                               axis->d_hat_rad_s2 - axis->f_known_rad_s2, axis->f_rate_rad_s3);
    (void)ladrc_hp_step(est, axis->leso.z3 - shadow->z3);
    /* What the weight moved in or out of d_hat leaves or enters z3 at once,
     * in both observers (the sample stays as it was). */
    const ladrc_real_t handover = hp_handover(est);
    if (handover != LADRC_R(0.0)) { /* only while the weight moves */
        ladrc_leso_hand_over(&axis->leso, handover);
        ladrc_leso_twin_hand_over(shadow, handover);
    }
    return hp_estimate(est);
}

#endif /* LADRC_AXIS_HP_H */
