/* SPDX-License-Identifier: BSD-3-Clause */
/* The INDI baseline as an axis (axis.h, indi.h): shaper, actuator model and
 * the incremental law on the measured rate. */
#include "axis_internal.h"

ladrc_status_t axis_indi_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_indi_config_t indi_cfg = {.dt_s = cfg->dt_s,
                                          .b0 = cfg->b0,
                                          .att_kp_per_s = cfg->indi_att_kp_per_s,
                                          .rate_kp_per_s = cfg->indi_rate_kp_per_s,
                                          .filter_rad_s = cfg->indi_filter_rad_s,
                                          .adapt = cfg->indi_adapt,
                                          .adapt_mu = cfg->indi_adapt_mu,
                                          .adapt_jerk_min_rad_s3 = cfg->indi_adapt_jerk_min_rad_s3,
                                          .adapt_min_ratio = cfg->indi_adapt_min_ratio,
                                          .adapt_max_ratio = cfg->indi_adapt_max_ratio};
    ladrc_status_t status = ladrc_indi_init(&axis->part.indi, &indi_cfg);
    if (status == LADRC_OK) {
        status = axis_actuator_init(axis, cfg);
    }
    if (status == LADRC_OK) {
        status = axis_shaper_init(axis, cfg);
    }
    if (status == LADRC_OK) {
        axis->b0 = cfg->b0;
        axis->kp = LADRC_R(0.0);
        axis->kd = LADRC_R(0.0);
    }
    return status;
}

void axis_indi_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_indi_reset(&axis->part.indi);
    axis->part.indi.angle_rad = angle_rad;
    axis_shaper_reset(axis, angle_rad);
}

/* The tick on finite ref and angle (indi.h); without a rate the command is
 * held and LADRC_FAULT_RATE raised, while the reference, the actuator model
 * and the filters' gap move on with time. Returns the tick's faults. */
ladrc_fault_t axis_indi_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s,
                             int has_rate)
{
    ladrc_indi_t *indi = &axis->part.indi;
    ladrc_ref_t *ref = &axis->ref;
    if (axis->wrap) {
        ref_rad = ladrc_unwrap_near(ref_rad, ref->r);
    }
    const ladrc_real_t acting_Nm = axis_advance_actuator(axis);
    ladrc_fault_t faults = axis_shape_reference(axis, ref_rad);
    if (!ladrc_indi_measure(indi, acting_Nm, has_rate ? &rate_rad_s : NULL)) {
        return (ladrc_fault_t)(faults | LADRC_FAULT_RATE);
    }
    indi->angle_rad = angle_rad;
    const ladrc_real_t error_rad = axis_wrapped_error(axis, angle_rad);
    const ladrc_real_t u = ladrc_indi_command(indi, error_rad, ref->dr, ref->ddr, rate_rad_s);
    if (!ladrc_is_finite(u)) { /* u sums both filters: they are finite when it is */
        /* Held; the filters restart at rest (the next rate seeds again). */
        ladrc_indi_reset(indi);
        indi->angle_rad = angle_rad;
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->output_Nm = ladrc_clamp(u, axis->u_min_Nm, axis->u_max_Nm);
    return faults;
}

/* G * acting torque + the filtered disturbance omegadot_f - G u_f (G = b0
 * unless adapted). */
ladrc_real_t axis_indi_accel(const ladrc_axis_t *axis)
{
    const ladrc_indi_t *indi = &axis->part.indi;
    return ladrc_indi_get_effectiveness(indi) * axis_acting_Nm(axis) + ladrc_indi_get_disturbance(indi);
}

ladrc_real_t axis_indi_effectiveness(const ladrc_axis_t *axis)
{
    return ladrc_indi_get_effectiveness(&axis->part.indi);
}

/* The last angle and rate measured with a rate, and omegadot_f - b0 u_f. */
void axis_indi_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                        ladrc_real_t *disturbance_rad_s2)
{
    *angle_rad = axis->part.indi.angle_rad;
    *rate_rad_s = axis->part.indi.rate_last_rad_s;
    *disturbance_rad_s2 = ladrc_indi_get_disturbance(&axis->part.indi);
}
