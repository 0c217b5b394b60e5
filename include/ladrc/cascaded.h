/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file cascaded.h
 * @brief Cascaded attitude / rate controller on one axis, the structure the
 *        common flight stacks fly (PX4, ArduPilot, Betaflight): a P loop on
 *        the attitude error gives a rate setpoint, a PID loop on the rate
 *        gives the torque. Angle in rad in, torque in N m out.
 *
 * Structure. PX4 splits it in two modules: mc_att_control turns the
 * attitude error into a body-rate setpoint with a proportional gain per
 * axis (MC_ROLL_P, ...), adds the setpoint's own rate as feed-forward and
 * limits the result to the maximum body rates (MC_ROLLRATE_MAX, default
 * 220 deg/s); mc_rate_control runs a PID on the rate error with the
 * derivative taken on the measured (filtered) rate, not on the error, so a
 * setpoint jump gives no derivative kick, a clamp on the integrator
 * (MC_RR_INT_LIM) and no integration while the control allocator reports
 * the axis saturated in the direction the integrator would push. ArduPilot
 * (AC_AttitudeControl + AC_PID) and Betaflight (angle mode over the rate
 * PID) have the same cascade. This module is that structure on one axis,
 * written from the equations below.
 *
 * Tick k, fixed step h = dt_s, shaped reference (r_k, r'_k) (the axis's
 * shaper: Han's TD by default, axis.h), measured angle y_k:
 *
 *   attitude loop (mc_att_control)
 *     e_k     = r_k - y_k                                (mod 2 pi when wrapped)
 *     w_sp,k  = clamp(att_kp e_k + r'_k, +-rate_max)     rate setpoint, rad/s
 *   rate (measured, or from the angle when no gyro is given)
 *     m_k     = measured rate, or
 *     m_k     = m_k-1 + a_w ((y_k - y_k-1) / h - m_k-1),  a_w = h / (tau_w + h),
 *               clamped to +-rate_limit (the axis's plausible range)
 *   rate loop (mc_rate_control)
 *     D_k     = D_k-1 + a_d ((m_k - m_k-1) / h - D_k-1),   a_d = h / (tau_d + h)
 *     e_w,k   = w_sp,k - m_k
 *     I_k     = clamp(I_k-1 + ki h e_w,k, +-i_limit)      unless frozen
 *     u_k     = clamp(kp e_w,k + I_k - kd D_k, u_min, u_max)
 *
 * (tau = 0: a = 1, the unfiltered difference.) Frozen: the previous tick's
 * applied torque (its command, or what ladrc_cascaded_set_applied reported,
 * e.g. after the mixer) lies below the unclamped command and e_w > 0, or
 * above it and e_w < 0 (pid.h's rule). The first tick after a reset has no
 * previous angle or rate: both differences are 0.
 *
 * Reference feed-forward: r' comes from the reference shaper of the axis
 * rather than a difference of the raw reference: the TD's r' is the exact
 * derivative of the r the P loop tracks (so a ramp is followed without the
 * P loop's lag), it is bounded by the shaper's acceleration limit and
 * free of noise (a filtered difference of a stepped reference would spike);
 * it also gives every variant of the library the same shaped reference.
 * With shaper NONE r' = 0 and the attitude loop is a plain P.
 *
 * Linear loop (no clamps), rigid axis J theta'' = u + J d: with a rate
 * sensor and the continuous-time equivalents (small h),
 *     u = -(kp + ki / s + kd s / (tau_d s + 1)) s theta
 *         + (kp + ki / s) att_kp (r - theta) + (kp + ki / s) r'
 * The integrator acts on the rate error; in steady state e_w = 0, so the
 * rate is zero and w_sp = att_kp e = 0: no steady-state angle error under
 * a constant disturbance.
 */
#ifndef LADRC_CASCADED_H
#define LADRC_CASCADED_H

#include "ladrc/pid.h"
#include "ladrc/td.h"
#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    ladrc_real_t dt_s;              /**< fixed step (s) */
    ladrc_real_t att_kp_per_s;      /**< attitude P gain (1/s), > 0, att_kp dt < 1 */
    ladrc_real_t rate_max_rad_s;    /**< |rate setpoint| bound (rad/s), > 0, <= rate_limit_rad_s */
    ladrc_real_t rate_kp;           /**< N m s / rad, >= 0 */
    ladrc_real_t rate_ki;           /**< N m / rad, >= 0 */
    ladrc_real_t rate_kd;           /**< N m s^2 / rad, >= 0 */
    ladrc_real_t d_filter_tau_s;    /**< derivative filter (s), >= 0, 0 = none */
    ladrc_real_t rate_filter_tau_s; /**< filter of the rate from the angle (no gyro) (s), >= 0 */
    ladrc_real_t i_limit_Nm;        /**< |integral| bound (N m), >= 0, INFINITY = none */
    ladrc_real_t rate_limit_rad_s;  /**< plausible |rate| (rad/s), finite, > 0 */
    ladrc_real_t u_min_Nm;          /**< output bounds (N m), u_min < 0 < u_max, may be infinite */
    ladrc_real_t u_max_Nm;
    uint8_t wrap_angle; /**< 1: e and y_k - y_k-1 are taken modulo 2 pi */
} ladrc_cascaded_config_t;

/** Cascaded state; owned by the caller. */
typedef struct {
    ladrc_real_t dt_s, inv_dt;
    ladrc_real_t att_kp_per_s, rate_max_rad_s;
    ladrc_real_t rate_kp, rate_ki_dt, rate_kd;
    ladrc_real_t d_alpha, d_keep; /**< derivative filter */
    ladrc_real_t w_alpha, w_keep; /**< rate-from-angle filter */
    ladrc_real_t i_limit_Nm, rate_limit_rad_s, u_min_Nm, u_max_Nm;
    ladrc_real_t integral_Nm;    /**< I_k */
    ladrc_real_t rate_rad_s;     /**< m_k: the rate the latest tick used */
    ladrc_real_t accel_rad_s2;   /**< D_k: filtered derivative of the rate */
    ladrc_real_t prev_angle_rad; /**< y_k */
    ladrc_real_t rate_sp_rad_s;  /**< w_sp,k */
    ladrc_real_t unclamped_Nm;   /**< latest command before clamping */
    ladrc_real_t output_Nm;      /**< latest command */
    ladrc_real_t applied_Nm;     /**< torque applied since the latest tick */
    uint8_t has_prev;            /**< 0 until a first tick ran */
    uint8_t wrap;
} ladrc_cascaded_t;

/** Validates (LADRC_ERR_DT_S, _CAS_ATT_KP, _CAS_RATE_MAX, _CAS_RATE_KP,
 *  _CAS_RATE_KI, _CAS_RATE_KD, _CAS_D_TAU_S, _CAS_RATE_TAU_S, _CAS_I_LIMIT_NM,
 *  _U_LIMITS, _WRAP_ANGLE in that order; _NULL) and resets at angle 0. The
 *  gain checks also refuse gains whose terms could leave the real type for
 *  rates inside +-2 rate_limit_rad_s. */
ladrc_status_t ladrc_cascaded_init(ladrc_cascaded_t *c, const ladrc_cascaded_config_t *cfg);

/** Restarts at rest: integral, filters and commands 0, previous angle
 *  angle_rad (finite: the caller checks). */
void ladrc_cascaded_reset(ladrc_cascaded_t *c, ladrc_real_t angle_rad);

/**
 * One tick on finite inputs (the axis checks them): shaped reference ref,
 * measured angle, measured rate (NULL: from the angle); torque_Nm receives
 * the command (N m). Returns 0, or LADRC_FAULT_STATE when the update would
 * leave the real type: the state and the command are then left as they
 * were (the axis restarts it).
 */
ladrc_fault_t ladrc_cascaded_step(ladrc_cascaded_t *c, const ladrc_ref_t *ref, ladrc_real_t angle_rad,
                                  const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm);

/** Torque actually applied since the latest tick (finite: the caller checks). */
void ladrc_cascaded_set_applied(ladrc_cascaded_t *c, ladrc_real_t applied_Nm);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_CASCADED_H */
