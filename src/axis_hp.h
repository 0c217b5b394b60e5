/* SPDX-License-Identifier: BSD-3-Clause */
/* The HP-MLADRC estimator's sample hook, inline in the family's tick
 * (axis_adrc.c); its other hooks are in axis_hp.c (axis_internal.h). */
#ifndef LADRC_AXIS_HP_H
#define LADRC_AXIS_HP_H

#include "axis_internal.h"
#include "estimator_hp_internal.h"

/* z3 holds f - d_hat seen through the observer's lag, plus what the fed
 * rate h put in; the shadow, a twin of the observer on a still plant told
 * d_hat - f_known and the same h, holds exactly the parts of z3 that d_hat,
 * h and the known f_known put there (the observer is linear), so the
 * difference is the observer's view of the unknown f alone and the fit does
 * not chase its own output. The rate and the acting torque are not used. */
static inline ladrc_real_t axis_hp_sample(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t acting_Nm)
{
    (void)rate_rad_s;
    (void)acting_Nm;
    ladrc_leso_twin_t *shadow = &axis->part.hp.shadow;
    (void)ladrc_leso_step_twin(&axis->leso, shadow, LADRC_R(0.0), LADRC_R(0.0),
                               axis->d_hat_rad_s2 - axis->f_known_rad_s2, axis->f_rate_rad_s3);
    (void)ladrc_hp_step(&axis->part.hp.est, axis->leso.z3 - shadow->z3);
    /* What the weight moved in or out of d_hat leaves or enters z3 at once,
     * in both observers (the sample stays as it was). */
    const ladrc_real_t handover = hp_handover(&axis->part.hp.est);
    if (handover != LADRC_R(0.0)) { /* only while the weight moves */
        ladrc_leso_hand_over(&axis->leso, handover);
        ladrc_leso_twin_hand_over(shadow, handover);
    }
    return hp_estimate(&axis->part.hp.est);
}

#endif /* LADRC_AXIS_HP_H */
