/* SPDX-License-Identifier: BSD-3-Clause */
/* LP-MLADRC: the LADRC axis with the LP estimator (axis.h, estimator.h). */
#include "axis_internal.h"

ladrc_status_t axis_lp_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_lp_config_t lp = {.dt_s = cfg->dt_s,
                                  .lambda0_per_s = cfg->lp_lambda0_per_s,
                                  .k0_per_s = cfg->lp_k0_per_s,
                                  .act_tau_s = cfg->motor_tau_s,
                                  .act_delay_ticks = cfg->delay_ticks};
    return ladrc_lp_init(&axis->part.lp, &lp);
}

void axis_lp_restart(ladrc_axis_t *axis)
{
    ladrc_lp_reset(&axis->part.lp);
}

ladrc_real_t axis_lp_command(ladrc_axis_t *axis)
{
    ladrc_real_t command_rad_s2;
    (void)ladrc_lp_step_lead(&axis->part.lp, &command_rad_s2);
    return command_rad_s2;
}
