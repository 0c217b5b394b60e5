/* SPDX-License-Identifier: BSD-3-Clause */
/* The cascaded attitude P / rate PID baseline as an axis (axis.h, cascaded.h). */
#include "axis_internal.h"

ladrc_status_t axis_cascaded_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_cascaded_config_t cas_cfg = {.dt_s = cfg->dt_s,
                                             .att_kp_per_s = cfg->cas_att_kp,
                                             .rate_max_rad_s = cfg->cas_rate_max_rad_s,
                                             .rate_kp = cfg->cas_rate_kp,
                                             .rate_ki = cfg->cas_rate_ki,
                                             .rate_kd = cfg->cas_rate_kd,
                                             .d_filter_tau_s = cfg->cas_d_filter_tau_s,
                                             .rate_filter_tau_s = cfg->cas_rate_filter_tau_s,
                                             .i_limit_Nm = cfg->cas_i_limit_Nm,
                                             .rate_limit_rad_s = cfg->rate_limit_rad_s,
                                             .u_min_Nm = axis_command_min(cfg),
                                             .u_max_Nm = axis_command_max(cfg),
                                             .wrap_angle = cfg->wrap_angle,
                                             .i_relax_rad_s = cfg->cas_i_relax_rad_s,
                                             .rate_ff = cfg->cas_rate_ff,
                                             .setpoint_ff = cfg->cas_setpoint_ff};
    axis->model = 0u; /* no observer to tell (axis.h) */
    ladrc_status_t status = ladrc_cascaded_init(&axis->part.cas, &cas_cfg);
    if (status == LADRC_OK) {
        status = axis_shaper_init(axis, cfg);
    }
    return status;
}

void axis_cascaded_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_cascaded_reset(&axis->part.cas, angle_rad);
    axis_shaper_reset(axis, angle_rad);
}

/* The tick on finite ref and angle; returns the state fault, if any. A
 * wrapped axis unwraps the raw reference near r for the shaper, and moves r
 * back by a turn once it lies beyond +-pi (exact: r is within 3 pi, the
 * shift is Sterbenz-exact); the error and the angle difference are wrapped
 * by the cascaded module itself. */
ladrc_fault_t axis_cascaded_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                                 ladrc_real_t rate_rad_s, int has_rate)
{
    if (axis->wrap) {
        ref_rad = ladrc_unwrap_near(ref_rad, axis->ref.r);
    }
    ladrc_fault_t faults = axis_shape_reference(axis, ref_rad);
    if (axis->wrap && !ladrc_in_half_turn(axis->ref.r)) {
        axis_shift_reference(axis, (axis->ref.r > LADRC_R(0.0)) ? -LADRC_TWO_PI : LADRC_TWO_PI);
    }
    ladrc_cascaded_t *cas = &axis->part.cas;
    ladrc_real_t torque_Nm;
    if (ladrc_cascaded_step(cas, &axis->ref, angle_rad, has_rate ? &rate_rad_s : NULL, &torque_Nm) !=
        LADRC_FAULT_NONE) {
        /* The axis holds its command; the loops restart from the measurement. */
        ladrc_cascaded_reset(cas, angle_rad);
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->output_Nm = torque_Nm;
    return faults;
}

void axis_cascaded_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm)
{
    ladrc_cascaded_set_applied(&axis->part.cas, torque_Nm);
}

void axis_cascaded_set_landed(ladrc_axis_t *axis, uint8_t landed)
{
    ladrc_cascaded_set_landed(&axis->part.cas, landed);
}

/* No observer: the last measured angle, the rate its rate loop used, and 0. */
void axis_cascaded_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                            ladrc_real_t *disturbance_rad_s2)
{
    *angle_rad = axis->part.cas.prev_angle_rad;
    *rate_rad_s = axis->part.cas.rate_rad_s;
    *disturbance_rad_s2 = LADRC_R(0.0);
}
