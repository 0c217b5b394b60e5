/* SPDX-License-Identifier: BSD-3-Clause */
/* LP-MLADRC: the LADRC axis with the LP estimator (axis.h, estimator.h). */
#include "axis_internal.h"
#include "estimator_lp_internal.h"

ladrc_status_t axis_lp_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    return axis_lp_configure(&axis->part.lp, cfg);
}

void axis_lp_restart(ladrc_axis_t *axis)
{
    ladrc_lp_reset(&axis->part.lp);
}

ladrc_real_t axis_lp_preset(ladrc_axis_t *axis, ladrc_real_t f_rad_s2)
{
    ladrc_lp_hand_over(&axis->part.lp, f_rad_s2); /* the estimate at f at once */
    return lp_estimate(&axis->part.lp);
}

ladrc_real_t axis_lp_command(ladrc_axis_t *axis)
{
    return lp_lead_step(&axis->part.lp);
}
