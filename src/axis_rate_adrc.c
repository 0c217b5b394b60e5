/* SPDX-License-Identifier: BSD-3-Clause */
/* The rate-loop ADRC as an axis (axis.h): attitude P on the shaped reference
 * (or an acro rate setpoint), a second-order ESO on the measured rate
 * (reso.h) and a P law on the rate error. */
#include "axis_internal.h"

/* k_w dt and k_att dt below 1: each P loop's sampled pole 1 - k dt stays
 * inside the unit circle with room (the rate loop also carries the ESO). */
#define RADRC_GAIN_DT_LIMIT LADRC_R(1.0)

static int gain_is_valid(ladrc_real_t k_per_s, ladrc_real_t dt_s)
{
    return ladrc_is_positive(k_per_s) && k_per_s * dt_s < RADRC_GAIN_DT_LIMIT;
}

ladrc_status_t axis_rate_adrc_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (!axis_b0_is_valid(cfg->b0)) {
        return LADRC_ERR_B0;
    }
    if (!gain_is_valid(cfg->radrc_kp_per_s, cfg->dt_s)) {
        return LADRC_ERR_RADRC_KP;
    }
    if (cfg->radrc_acro > 1u) {
        return LADRC_ERR_RADRC_ACRO;
    }
    if (!cfg->radrc_acro && !gain_is_valid(cfg->radrc_att_kp_per_s, cfg->dt_s)) {
        return LADRC_ERR_RADRC_ATT_KP;
    }
    if (!(ladrc_is_positive(cfg->radrc_rate_max_rad_s) && cfg->radrc_rate_max_rad_s <= cfg->rate_limit_rad_s)) {
        return LADRC_ERR_RADRC_RATE_MAX;
    }
    const ladrc_reso_config_t eso_cfg = {.dt_s = cfg->dt_s, .wo_rad_s = cfg->wo_rad_s, .b0 = cfg->b0};
    ladrc_status_t status = ladrc_reso_init(&axis->part.radrc.eso, &eso_cfg);
    if (status == LADRC_OK) {
        status = axis_actuator_init(axis, cfg);
    }
    if (status == LADRC_OK && !cfg->radrc_acro) {
        status = axis_shaper_init(axis, cfg);
    }
    if (status == LADRC_OK) {
        axis->shaper = cfg->radrc_acro ? LADRC_SHAPER_NONE : cfg->shaper;
        axis->b0 = cfg->b0;
        axis->kp = cfg->radrc_kp_per_s;
        axis->kd = LADRC_R(0.0);
        axis->part.radrc.k_att = cfg->radrc_att_kp_per_s;
        axis->part.radrc.rate_max_rad_s = cfg->radrc_rate_max_rad_s;
        axis_approach_init(axis, cfg, cfg->radrc_att_kp_per_s);
        axis->part.radrc.acro = cfg->radrc_acro;
    }
    return status;
}

void axis_rate_adrc_engage(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm)
{
    /* u = (k_w (w_ref - z1) + r'' - z2) / b0 with w_ref near the rate */
    axis->part.radrc.eso.z1 = rate_rad_s;
    axis->part.radrc.eso.z2 = -axis->b0 * torque_Nm;
}

void axis_rate_adrc_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_reso_reset(&axis->part.radrc.eso, LADRC_R(0.0));
    axis->part.radrc.angle_rad = angle_rad;
    axis->part.radrc.rate_sp_rad_s = LADRC_R(0.0);
    if (!axis->part.radrc.acro) {
        axis_shaper_reset(axis, angle_rad);
    }
}

/* The attitude P loop's rate setpoint before its bound (rad/s): k_att times
 * the angle error (wrapped on a wrapped axis, whose r is then kept within a
 * turn as INDI keeps it), beyond linear_rad the braking rate instead
 * (axis_shared.h), plus the shaped rate r'. */
static ladrc_real_t attitude_rate(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    const ladrc_real_t error_rad = axis_wrapped_error(axis, angle_rad);
    const ladrc_real_t closing = (ladrc_fabs(error_rad) > axis->linear_rad) ? axis_braking_rate(axis, error_rad)
                                                                            : axis->part.radrc.k_att * error_rad;
    return closing + axis->ref.dr;
}

/* The tick on a plausible ref and angle (axis.h): without a rate the command
 * is held and LADRC_FAULT_RATE raised, while the shaper and the actuator
 * model move on with time. Returns the tick's faults. */
ladrc_fault_t axis_rate_adrc_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                                  ladrc_real_t rate_rad_s, int has_rate)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    const int acro = axis->part.radrc.acro;
    if (acro) {
        if (!ladrc_within(ref_rad, axis->rate_limit_rad_s)) {
            return LADRC_FAULT_INPUT; /* a rate setpoint no gyro could confirm: held */
        }
        axis->ref.r = ref_rad;
    } else {
        if (axis->wrap) {
            ref_rad = ladrc_unwrap_near(ref_rad, axis->ref.r);
        }
        faults = axis_shape_reference(axis, ref_rad);
    }
    const ladrc_real_t acting_Nm = axis_advance_actuator(axis);
    axis->part.radrc.angle_rad = angle_rad;
    if (!has_rate) {
        return (ladrc_fault_t)(faults | LADRC_FAULT_RATE);
    }
    ladrc_reso_t *eso = &axis->part.radrc.eso;
    const ladrc_real_t setpoint = acro ? ref_rad : attitude_rate(axis, angle_rad);
    const ladrc_real_t max = axis->part.radrc.rate_max_rad_s;
    const ladrc_real_t rate_sp = ladrc_clamp(setpoint, -max, max);
    /* The shaped acceleration r'' fed forward while the setpoint is within
     * its bound (beyond it the bound, not r, is what the rate should follow;
     * r'' is 0 in acro). */
    const ladrc_real_t accel_ff = (rate_sp == setpoint) ? axis->ref.ddr : LADRC_R(0.0);
    const ladrc_real_t u = (ladrc_reso_step(eso, rate_rad_s, acting_Nm, LADRC_R(0.0), LADRC_R(0.0)) == LADRC_FAULT_NONE)
                               ? (axis->kp * (rate_sp - eso->z1) + accel_ff - eso->z2) / axis->b0
                               : (ladrc_real_t)NAN;
    if (!ladrc_is_finite(u)) {
        /* Held; the observer restarts on the measured rate. */
        ladrc_reso_reset(eso, rate_rad_s);
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->part.radrc.rate_sp_rad_s = rate_sp;
    axis->output_Nm = ladrc_clamp(u, axis->u_min_Nm, axis->u_max_Nm);
    return faults;
}

/* b0 * acting torque + the observer's disturbance z2. */
ladrc_real_t axis_rate_adrc_accel(const ladrc_axis_t *axis)
{
    return axis->b0 * axis_acting_Nm(axis) + axis->part.radrc.eso.z2;
}

/* The last measured angle, the observer's rate z1 and disturbance z2. */
void axis_rate_adrc_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                             ladrc_real_t *disturbance_rad_s2)
{
    *angle_rad = axis->part.radrc.angle_rad;
    *rate_rad_s = axis->part.radrc.eso.z1;
    *disturbance_rad_s2 = axis->part.radrc.eso.z2;
}
