/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file pid.h
 * @brief PID baseline on one attitude axis: angle error in rad in, torque in
 *        N m out; derivative on measurement, optional first-order derivative
 *        filter, integrator clamp and integrator freeze while the applied
 *        torque is saturated in the error's direction.
 *
 * Discrete time, fixed step h = dt_s, e_k = ref_k - y_k:
 *
 *     D input  m_k = measured rate, or (y_k - y_k-1) / h without one
 *     filter   d_k = d_k-1 + (m_k - d_k-1) h / (tau + h)     (tau = 0: d_k = m_k)
 *     integral I_k = clamp(I_k-1 + ki h e_k, +-i_limit)     unless frozen
 *     output   u_k = clamp(kp e_k + I_k - kd d_k, u_min, u_max)
 *
 * Frozen: the previous tick's applied torque was below the unclamped command
 * and e_k > 0, or above it and e_k < 0 (integrating would push further into
 * saturation); or the vehicle is landed (ladrc_pid_set_landed). The applied torque is the clamped output unless the caller
 * reports another one with ladrc_pid_set_applied (e.g. after the mixer).
 * The comparison is exact: a mixer that did not saturate must report the
 * command itself (or not call set_applied), not a recomputed torque with
 * rounding error, or the integrator freezes spuriously.
 * wrap_angle = 1 (an angle on a circle, e.g. yaw): e_k and the measured
 * difference y_k - y_k-1 are taken modulo 2 pi into (-pi, pi]
 * (ladrc_wrap_pi), so a measurement that wraps at +-pi is no 2 pi step for
 * the error nor for the derivative; both are bit for bit the plain ones
 * while no wrap is needed.
 * First step after init (or after a reset with a non-finite measurement):
 * no previous measurement, so the finite difference is 0.
 * Gains are continuous-time. Paper baseline: kp = 20, ki = 20, kd = 0.05.
 */
#ifndef LADRC_PID_H
#define LADRC_PID_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** PID configuration (ladrc_pid_init validates it); can live in flash. */
typedef struct {
    ladrc_real_t dt_s;           /**< fixed step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t kp;             /**< N m / rad, >= 0 */
    ladrc_real_t ki;             /**< N m / (rad s), >= 0 */
    ladrc_real_t kd;             /**< N m s / rad, >= 0 */
    ladrc_real_t d_filter_tau_s; /**< derivative filter time constant (s), 0 = unfiltered */
    ladrc_real_t i_limit_Nm;     /**< |integral term| bound (N m), >= 0 (may be INFINITY) */
    ladrc_real_t u_min_Nm;       /**< output lower bound (N m), may be -INFINITY */
    ladrc_real_t u_max_Nm;       /**< output upper bound (N m), > u_min_Nm, may be INFINITY */
    uint8_t wrap_angle;          /**< 1: the angle lives on a circle of 2 pi; 0: a line */
} ladrc_pid_config_t;

/** PID state; owned by the caller. */
typedef struct {
    ladrc_real_t dt_s; /**< fixed step (s) */
    /** @{ */
    ladrc_real_t kp, kd; /**< the config's kp (N m / rad) and kd (N m s / rad) */
    /** @} */
    ladrc_real_t ki_dt;   /**< ki h: integral gain per sample (N m / rad) */
    ladrc_real_t d_alpha; /**< h / (tau + h), derived at init */
    ladrc_real_t d_keep;  /**< 1 - d_alpha */
    /** @{ */
    ladrc_real_t i_limit_Nm, u_min_Nm, u_max_Nm; /**< the config's bounds (N m) */
    /** @} */
    ladrc_real_t integral_Nm;      /**< integral term (N m) */
    ladrc_real_t d_filtered_rad_s; /**< filtered derivative of the measurement (rad/s) */
    ladrc_real_t prev_meas_rad;    /**< last finite measurement */
    ladrc_real_t unclamped_Nm;     /**< last command before clamping */
    ladrc_real_t output_Nm;        /**< last command after clamping */
    ladrc_real_t applied_Nm;       /**< torque applied since the last step */
    uint8_t has_prev_meas;         /**< 0 until a first measurement was seen */
    uint8_t wrap;                  /**< wrap_angle */
    uint8_t landed;                /**< 1: the integrator holds (ladrc_pid_set_landed) */
    ladrc_fault_t faults;          /**< flags of the latest step */
} ladrc_pid_t;

/** First-order low pass, backward Euler, written as a blend so that
 *  alpha = h / (tau + h) = 1 (tau = 0) gives the input exactly:
 *  y_k = keep y_k-1 + alpha x_k, keep = 1 - alpha. Shared by PID's and the
 *  cascaded controller's derivative filters. No finiteness check.
 *  @param keep   1 - alpha
 *  @param alpha  h / (tau + h), in (0, 1]
 *  @param prev   the filter's previous output (unit of the input)
 *  @param in     the new input
 *  @return the new output, keep prev + alpha in */
static inline ladrc_real_t ladrc_lowpass_blend(ladrc_real_t keep, ladrc_real_t alpha, ladrc_real_t prev,
                                               ladrc_real_t in)
{
    return keep * prev + alpha * in;
}

/** Conditional integration: 1 when integrating error would push the command
 *  further into the saturation the last applied torque hit (applied below
 *  the unclamped command and error > 0, or above it and error < 0).
 *  NaN in any argument: 0 (integrate).
 *  @param error         the error about to be integrated (its sign counts)
 *  @param applied_Nm    the torque applied after the last command (N m)
 *  @param unclamped_Nm  the last command before clamping (N m)
 *  @return 1: do not integrate; 0: integrate */
static inline int ladrc_integrator_frozen(ladrc_real_t error, ladrc_real_t applied_Nm, ladrc_real_t unclamped_Nm)
{
    return (error > LADRC_R(0.0) && applied_Nm < unclamped_Nm) || (error < LADRC_R(0.0) && applied_Nm > unclamped_Nm);
}

/**
 * Validates every field in the order below and resets (ladrc_pid_reset at 0).
 * i_limit_Nm may be +INFINITY and u_min_Nm / u_max_Nm -INFINITY / +INFINITY
 * (no clamp); NaN is rejected. On a config error (not LADRC_ERR_NULL) *pid
 * is zeroed: its output stays 0.
 * @param[out] pid  the controller to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                  set up
 * @retval LADRC_ERR_NULL            pid or cfg is NULL
 * @retval LADRC_ERR_DT_S            dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_PID_KP          kp not finite or < 0
 * @retval LADRC_ERR_PID_KI          ki not finite or < 0
 * @retval LADRC_ERR_PID_KD          kd not finite or < 0
 * @retval LADRC_ERR_PID_D_TAU_S     d_filter_tau_s not finite or < 0
 * @retval LADRC_ERR_PID_I_LIMIT_NM  i_limit_Nm NaN or < 0
 * @retval LADRC_ERR_U_LIMITS        u_min_Nm or u_max_Nm NaN, or u_min_Nm >= u_max_Nm
 * @retval LADRC_ERR_WRAP_ANGLE      wrap_angle not 0 or 1
 */
ladrc_status_t ladrc_pid_init(ladrc_pid_t *pid, const ladrc_pid_config_t *cfg);

/** Clears integral, derivative filter, faults and history; meas_rad seeds the derivative.
 *  The held output becomes 0 clamped into [u_min_Nm, u_max_Nm]. A non-finite meas_rad
 *  seeds nothing (the next good measurement does) and raises LADRC_FAULT_INPUT.
 *  @param pid       the controller; NULL: nothing happens
 *  @param meas_rad  the measured angle (rad) */
void ladrc_pid_reset(ladrc_pid_t *pid, ladrc_real_t meas_rad);

/**
 * One tick. rate_rad_s may be NULL (no rate sensor: differentiate meas_rad);
 * torque_Nm receives the command (N m), within [u_min_Nm, u_max_Nm].
 * Non-finite ref/meas: state held, last command given, LADRC_FAULT_INPUT;
 * the next good step continues as if the bad samples had been skipped.
 * Non-finite *rate_rad_s: the finite difference is used, LADRC_FAULT_RATE.
 * An update that would overflow the state (huge finite inputs): state held,
 * last command given, LADRC_FAULT_STATE.
 * @param pid         the controller
 * @param ref_rad     the reference (rad)
 * @param meas_rad    the measured angle (rad)
 * @param rate_rad_s  the measured rate (rad/s), or NULL
 * @param torque_Nm   out: the command (N m)
 * @return the tick's fault flags (also ladrc_pid_get_faults); pid or
 *         torque_Nm NULL: LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_pid_step(ladrc_pid_t *pid, ladrc_real_t ref_rad, ladrc_real_t meas_rad,
                             const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm);

/** Reports the torque actually applied after the last step (N m). A non-finite
 *  value is ignored (the clamped output counts) and adds LADRC_FAULT_APPLIED to the
 *  step's flags (set_applied never clears a flag).
 *  @param pid         the controller; NULL: nothing happens
 *  @param applied_Nm  the applied torque (N m) */
void ladrc_pid_set_applied(ladrc_pid_t *pid, ladrc_real_t applied_Nm);

/** Takes over from another controller: restarts as ladrc_pid_reset on
 *  meas_rad, with the derivative filter at the measured rate and the
 *  integral at torque_Nm + kd rate, so that a first step at zero error
 *  continues torque_Nm (the error's P part is the PID's own).
 *  @param pid        the controller; NULL: nothing happens
 *  @param meas_rad   the measured angle (rad)
 *  @param rate_rad_s the measured rate (rad/s); 0 without one
 *  @param torque_Nm  the other controller's last command (N m), within the
 *                    output bounds */
void ladrc_pid_engage(ladrc_pid_t *pid, ladrc_real_t meas_rad, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm);

/** Landed (1) or in the air (0): while landed the integrator holds, as the
 *  flight stacks hold theirs on the ground; other values are taken as 1.
 *  Kept by reset (the vehicle's, not the loop's); init clears it.
 *  @param pid     the controller; NULL: nothing happens
 *  @param landed  1 or 0 */
void ladrc_pid_set_landed(ladrc_pid_t *pid, uint8_t landed);

/** Fault flags of the latest step or set_applied call.
 *  @param pid  the controller
 *  @return the flags; pid NULL: LADRC_FAULT_STATE */
ladrc_fault_t ladrc_pid_get_faults(const ladrc_pid_t *pid);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_PID_H */
