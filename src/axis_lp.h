/* SPDX-License-Identifier: BSD-3-Clause */
/* The LP-MLADRC estimator's sample hook, inline in the family's tick
 * (axis_adrc.c); its other hooks are in axis_lp.c (axis_internal.h). */
#ifndef LADRC_AXIS_LP_H
#define LADRC_AXIS_LP_H

#include "axis_internal.h"
#include "estimator_lp_internal.h"

/* A tick without a rate (NaN) is a gap: LP holds and restarts its
 * difference. The rate is as old as the angle: the torque that acted over
 * its difference is the observer's. */
static inline ladrc_real_t axis_lp_sample(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t acting_Nm)
{
    (void)ladrc_lp_step(&axis->part.lp, rate_rad_s, axis->b0 * acting_Nm);
    return lp_estimate(&axis->part.lp);
}

#endif /* LADRC_AXIS_LP_H */
