/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file pid.c
 * @brief PID baseline: derivative on measurement, first-order derivative
 *        filter, integrator clamp and conditional integration (freeze).
 */
#include "ladrc/pid.h"
#include "require.h"

#include <stddef.h>

/* Finite and >= 0 (gains, time constants). */
static int is_non_negative(ladrc_real_t x)
{
    return ladrc_is_finite(x) && x >= LADRC_R(0.0);
}

/* Clears integral, filter and the command history; the measurement history is the caller's. */
static void clear_dynamic_state(ladrc_pid_t *pid)
{
    /* 0 N m clamped into the output range, so a held output is always within it. */
    const ladrc_real_t rest_Nm = ladrc_clamp(LADRC_R(0.0), pid->u_min_Nm, pid->u_max_Nm);

    pid->integral_Nm = LADRC_R(0.0);
    pid->d_filtered_rad_s = LADRC_R(0.0);
    /* unclamped == applied: the first step sees no saturation. */
    pid->unclamped_Nm = rest_Nm;
    pid->output_Nm = rest_Nm;
    pid->applied_Nm = rest_Nm;
    pid->faults = LADRC_FAULT_NONE;
}

ladrc_status_t ladrc_pid_init(ladrc_pid_t *pid, const ladrc_pid_config_t *cfg)
{
    const ladrc_pid_t zero = {0};

    if (pid == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    /* A rejected config leaves an all-zero instance: u_min = u_max = 0 clamps
     * every step's output to 0. */
    *pid = zero;
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!is_non_negative(cfg->kp)) {
        return LADRC_ERR_PID_KP;
    }
    if (!is_non_negative(cfg->ki)) {
        return LADRC_ERR_PID_KI;
    }
    if (!is_non_negative(cfg->kd)) {
        return LADRC_ERR_PID_KD;
    }
    if (!is_non_negative(cfg->d_filter_tau_s)) {
        return LADRC_ERR_PID_D_TAU_S;
    }
    /* +INFINITY means no clamp; NaN fails the comparison. */
    if (!(cfg->i_limit_Nm >= LADRC_R(0.0))) {
        return LADRC_ERR_PID_I_LIMIT_NM;
    }
    /* Infinite bounds mean no clamp; NaN fails the comparison, and so do
     * u_min = +inf and u_max = -inf. */
    if (!(cfg->u_min_Nm < cfg->u_max_Nm)) {
        return LADRC_ERR_U_LIMITS;
    }
    if (cfg->wrap_angle > 1u) {
        return LADRC_ERR_WRAP_ANGLE;
    }

    pid->dt_s = cfg->dt_s;
    pid->kp = cfg->kp;
    pid->ki_dt = cfg->ki * cfg->dt_s;
    pid->kd = cfg->kd;
    pid->d_alpha = cfg->dt_s / (cfg->d_filter_tau_s + cfg->dt_s);
    pid->d_keep = LADRC_R(1.0) - pid->d_alpha;
    pid->i_limit_Nm = cfg->i_limit_Nm;
    pid->u_min_Nm = cfg->u_min_Nm;
    pid->u_max_Nm = cfg->u_max_Nm;
    pid->wrap = cfg->wrap_angle;
    clear_dynamic_state(pid);
    pid->prev_meas_rad = LADRC_R(0.0);
    pid->has_prev_meas = 0u;
    return LADRC_OK;
}

void ladrc_pid_reset(ladrc_pid_t *pid, ladrc_real_t meas_rad)
{
    LADRC_REQUIRE_VOID(pid != NULL);
    clear_dynamic_state(pid);
    if (ladrc_is_finite(meas_rad)) {
        pid->prev_meas_rad = meas_rad;
        pid->has_prev_meas = 1u;
    } else {
        /* Never seed the derivative with a bad sample: wait for a good one. */
        pid->prev_meas_rad = LADRC_R(0.0);
        pid->has_prev_meas = 0u;
        pid->faults = LADRC_FAULT_INPUT;
    }
}

/* One tick on pid's state: sets output_Nm and faults. */
static void update(ladrc_pid_t *pid, ladrc_real_t ref_rad, ladrc_real_t meas_rad, const ladrc_real_t *rate_rad_s)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    ladrc_real_t error_rad;
    ladrc_real_t d_in_rad_s;
    ladrc_real_t d_rad_s;
    ladrc_real_t integral_Nm;
    ladrc_real_t unclamped_Nm;

    if (!ladrc_is_finite(ref_rad) || !ladrc_is_finite(meas_rad)) {
        faults = LADRC_FAULT_INPUT;
    }
    /* Derivative on measurement: a reference step gives no derivative kick. */
    if (rate_rad_s != NULL && ladrc_is_finite(*rate_rad_s)) {
        d_in_rad_s = *rate_rad_s;
    } else {
        if (rate_rad_s != NULL) {
            faults |= LADRC_FAULT_RATE;
        }
        /* 0 on the first sample: nothing to difference yet. */
        ladrc_real_t diff_rad = meas_rad - pid->prev_meas_rad;
        if (pid->wrap) {
            diff_rad = ladrc_wrap_pi(diff_rad);
        }
        d_in_rad_s = (pid->has_prev_meas != 0u) ? diff_rad / pid->dt_s : LADRC_R(0.0);
    }
    if ((faults & LADRC_FAULT_INPUT) != 0u) {
        pid->faults = faults;
        return;
    }

    error_rad = ref_rad - meas_rad;
    if (pid->wrap) {
        error_rad = ladrc_wrap_pi(error_rad);
    }
    /* Written as a blend so that alpha = 1 (tau = 0) gives d = m exactly. */
    d_rad_s = ladrc_lowpass_blend(pid->d_keep, pid->d_alpha, pid->d_filtered_rad_s, d_in_rad_s);

    integral_Nm = pid->integral_Nm;
    if (!pid->landed && !ladrc_integrator_frozen(error_rad, pid->applied_Nm, pid->unclamped_Nm)) {
        integral_Nm = ladrc_clamp(integral_Nm + pid->ki_dt * error_rad, -pid->i_limit_Nm, pid->i_limit_Nm);
    }
    unclamped_Nm = pid->kp * error_rad + integral_Nm - pid->kd * d_rad_s;

    /* Huge finite inputs can overflow; keep the last good state and output. */
    if (!ladrc_all_finite3(d_rad_s, integral_Nm, unclamped_Nm)) {
        pid->faults = (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
        return;
    }

    pid->d_filtered_rad_s = d_rad_s;
    pid->integral_Nm = integral_Nm;
    pid->prev_meas_rad = meas_rad;
    pid->has_prev_meas = 1u;
    pid->unclamped_Nm = unclamped_Nm;
    pid->output_Nm = ladrc_clamp(unclamped_Nm, pid->u_min_Nm, pid->u_max_Nm);
    pid->applied_Nm = pid->output_Nm;
    pid->faults = faults;
}

ladrc_fault_t ladrc_pid_step(ladrc_pid_t *pid, ladrc_real_t ref_rad, ladrc_real_t meas_rad,
                             const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm)
{
    LADRC_REQUIRE(pid != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    update(pid, ref_rad, meas_rad, rate_rad_s);
    *torque_Nm = pid->output_Nm;
    return pid->faults;
}

void ladrc_pid_engage(ladrc_pid_t *pid, ladrc_real_t meas_rad, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm)
{
    LADRC_REQUIRE_VOID(pid != NULL);
    ladrc_pid_reset(pid, meas_rad);
    pid->d_filtered_rad_s = rate_rad_s;
    pid->integral_Nm = ladrc_clamp(torque_Nm + pid->kd * rate_rad_s, -pid->i_limit_Nm, pid->i_limit_Nm);
    pid->unclamped_Nm = torque_Nm;
    pid->output_Nm = torque_Nm;
    pid->applied_Nm = torque_Nm;
}

void ladrc_pid_set_landed(ladrc_pid_t *pid, uint8_t landed)
{
    LADRC_REQUIRE_VOID(pid != NULL);
    pid->landed = (landed != 0u) ? 1u : 0u;
}

void ladrc_pid_set_applied(ladrc_pid_t *pid, ladrc_real_t applied_Nm)
{
    LADRC_REQUIRE_VOID(pid != NULL);
    if (ladrc_is_finite(applied_Nm)) {
        pid->applied_Nm = applied_Nm;
    } else {
        /* The clamped output stands in for the unknown applied torque. */
        pid->applied_Nm = pid->output_Nm;
        pid->faults = (ladrc_fault_t)(pid->faults | LADRC_FAULT_APPLIED);
    }
}

ladrc_fault_t ladrc_pid_get_faults(const ladrc_pid_t *pid)
{
    LADRC_REQUIRE(pid != NULL, LADRC_FAULT_STATE);
    return pid->faults;
}
