/* SPDX-License-Identifier: BSD-3-Clause */
/* The PID baseline as an axis (axis.h, pid.h): no shaper, no observer. */
#include "axis_internal.h"

ladrc_status_t axis_pid_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_pid_config_t pid_cfg = {.dt_s = cfg->dt_s,
                                        .kp = cfg->pid_kp,
                                        .ki = cfg->pid_ki,
                                        .kd = cfg->pid_kd,
                                        .d_filter_tau_s = cfg->pid_d_filter_tau_s,
                                        .i_limit_Nm = cfg->pid_i_limit_Nm,
                                        .u_min_Nm = axis_command_min(cfg),
                                        .u_max_Nm = axis_command_max(cfg),
                                        .wrap_angle = cfg->wrap_angle};
    axis->model = 0u; /* no observer to tell (axis.h) */
    return ladrc_pid_init(&axis->part.pid, &pid_cfg);
}

void axis_pid_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_pid_reset(&axis->part.pid, angle_rad);
}

ladrc_fault_t axis_pid_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s,
                            int has_rate)
{
    axis->ref.r = ref_rad;
    return ladrc_pid_step(&axis->part.pid, ref_rad, angle_rad, has_rate ? &rate_rad_s : NULL, &axis->output_Nm);
}

void axis_pid_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm)
{
    ladrc_pid_set_applied(&axis->part.pid, torque_Nm);
}

/* No observer: the last measured angle, its filtered rate, and 0. */
void axis_pid_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                       ladrc_real_t *disturbance_rad_s2)
{
    *angle_rad = axis->part.pid.prev_meas_rad;
    *rate_rad_s = axis->part.pid.d_filtered_rad_s;
    *disturbance_rad_s2 = LADRC_R(0.0);
}
