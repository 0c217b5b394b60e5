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
 * axis (MC_ROLL_P, ...), adds the yaw setpoint's rate as feed-forward (on
 * yaw only: roll and pitch get no setpoint rate) and limits the result to
 * the maximum body rates (MC_ROLLRATE_MAX, default 220 deg/s);
 * mc_rate_control runs a PID on the rate error with the derivative taken
 * on the measured (filtered) rate, not on the error, so a setpoint jump
 * gives no derivative kick, plus a feed-forward gain on the rate setpoint
 * (MC_ROLLRATE_FF, MC_PITCHRATE_FF, MC_YAWRATE_FF, default 0), a clamp on
 * the integrator (MC_RR_INT_LIM), an integrator step scaled down as the
 * rate error grows (to 0 at 400 deg/s, so a flip does not wind it up), no
 * integration while landed, and none while the control allocator reports
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
 *     w_sp,k  = clamp(att_kp e_k + s r'_k, +-rate_max)   rate setpoint, rad/s;
 *               s = setpoint_ff (1: r' fed forward, 0: not)
 *   rate (measured, or from the angle when no gyro is given)
 *     m_k     = measured rate, or
 *     m_k     = m_k-1 + a_w ((y_k - y_k-1) / h - m_k-1),  a_w = h / (tau_w + h),
 *               clamped to +-rate_limit (the axis's plausible range)
 *   rate loop (mc_rate_control)
 *     D_k     = D_k-1 + a_d ((m_k - m_k-1) / h - D_k-1),   a_d = h / (tau_d + h)
 *     e_w,k   = w_sp,k - m_k
 *     u_k     = clamp(kp e_w,k + I_k-1 - kd D_k + k_ff w_sp,k, u_min, u_max)
 *     I_k     = clamp(I_k-1 + g(e_w,k) ki h e_w,k, +-i_limit)   unless frozen
 *     g(e)    = max(0, 1 - (e / e_relax)^2)                     the relax factor
 *
 * (tau = 0: a = 1, the unfiltered difference.) The command takes the
 * integral of the errors before this tick and this tick's error enters the
 * integral after it, as PX4 integrates (first order, after the output).
 * Frozen: the previous tick's applied torque (its command, or what
 * ladrc_cascaded_set_applied reported, e.g. after the mixer) lies below its
 * unclamped command and e_w > 0, or above it and e_w < 0 (pid.h's rule):
 * the library's form of PX4's allocator saturation flags, read from the
 * torque the mixer delivered; or the vehicle is landed
 * (ladrc_cascaded_set_landed). The first tick after a reset has no
 * previous angle or rate: both differences are 0.
 *
 * Integrator relax: g is 1 at small errors (0.94 at 100 deg/s, 0.75 at
 * 200 deg/s) and 0 from e_relax on (PX4: 400 deg/s); e_relax = INFINITY
 * turns it off (g = 1 exactly).
 *
 * Reference feed-forward: r' comes from the reference shaper of the axis
 * rather than a difference of the raw reference: the TD's r' is the exact
 * derivative of the r the P loop tracks (so a ramp is followed without the
 * P loop's lag), it is bounded by the shaper's acceleration limit and
 * free of noise (a filtered difference of a stepped reference would spike);
 * it also gives every variant of the library the same shaped reference.
 * With shaper NONE r' = 0 and the attitude loop is a plain P. PX4 feeds the
 * setpoint's rate forward on yaw only: ladrc_attitude_config_default sets
 * setpoint_ff to 0 on roll and pitch and leaves it 1 on yaw; a single axis
 * (ladrc_axis_config_default) keeps 1. Without it a ramp is followed with
 * the P loop's lag v / att_kp.
 *
 * Linear loop (no clamps, g = 1, k_ff = 0), rigid axis J theta'' = u + J d:
 * with a rate sensor and the continuous-time equivalents (small h),
 *     u = -(kp + ki / s + kd s / (tau_d s + 1)) s theta
 *         + (kp + ki / s) att_kp (r - theta) + s_ff (kp + ki / s) r'
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

/** Cascaded configuration (ladrc_cascaded_init validates it). */
typedef struct {
    ladrc_real_t dt_s;              /**< fixed step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t att_kp_per_s;      /**< attitude P gain (1/s), > 0, att_kp dt < 1 */
    ladrc_real_t rate_max_rad_s;    /**< |rate setpoint| bound (rad/s), > 0, <= rate_limit_rad_s */
    ladrc_real_t rate_kp;           /**< N m s / rad, >= 0 */
    ladrc_real_t rate_ki;           /**< N m / rad, >= 0 */
    ladrc_real_t rate_kd;           /**< N m s^2 / rad, >= 0 */
    ladrc_real_t d_filter_tau_s;    /**< derivative filter (s), >= 0, 0 = none */
    ladrc_real_t rate_filter_tau_s; /**< filter of the rate from the angle (no gyro) (s), >= 0 */
    ladrc_real_t i_limit_Nm;        /**< |integral| bound (N m), >= 0, INFINITY = none */
    ladrc_real_t rate_limit_rad_s;  /**< plausible |rate| (rad/s), finite, > 0 */
    ladrc_real_t u_min_Nm;          /**< output lower bound (N m), < u_max_Nm, may be -INFINITY */
    ladrc_real_t u_max_Nm;          /**< output upper bound (N m), may be INFINITY */
    uint8_t wrap_angle;             /**< 1: e and y_k - y_k-1 are taken modulo 2 pi */
    ladrc_real_t i_relax_rad_s;     /**< e_relax (rad/s): the rate error at which the integrator
                                         stops (PX4: 400 deg/s); > 0 with a finite inverse,
                                         INFINITY = no relax */
    ladrc_real_t rate_ff;           /**< k_ff (N m s / rad), >= 0: torque per rad/s of rate setpoint */
    uint8_t setpoint_ff;            /**< 1: the shaped reference's r' is fed into the rate setpoint, 0: not */
} ladrc_cascaded_config_t;

/** Cascaded state; owned by the caller. */
typedef struct {
    /** @{ */
    ladrc_real_t dt_s, inv_dt; /**< step h (s) and 1 / h (1/s) */
    /** @} */
    /** @{ */
    ladrc_real_t att_kp_per_s, rate_max_rad_s; /**< of the config */
    /** @} */
    /** @{ */
    ladrc_real_t rate_kp, rate_ki_dt, rate_kd; /**< rate gains; ki per sample (ki h) */
    /** @} */
    ladrc_real_t inv_relax_s_rad; /**< 1 / e_relax (s/rad); 0: no relax */
    ladrc_real_t rate_ff;         /**< k_ff (N m s / rad) */
    /** @{ */
    ladrc_real_t d_alpha, d_keep; /**< derivative filter */
    /** @} */
    /** @{ */
    ladrc_real_t w_alpha, w_keep; /**< rate-from-angle filter */
    /** @} */
    /** @{ */
    ladrc_real_t i_limit_Nm, rate_limit_rad_s, u_min_Nm, u_max_Nm; /**< of the config */
    /** @} */
    ladrc_real_t integral_Nm;    /**< I_k */
    ladrc_real_t rate_rad_s;     /**< m_k: the rate the latest tick used */
    ladrc_real_t accel_rad_s2;   /**< D_k: filtered derivative of the rate */
    ladrc_real_t prev_angle_rad; /**< y_k */
    ladrc_real_t rate_sp_rad_s;  /**< w_sp,k */
    ladrc_real_t unclamped_Nm;   /**< latest command before clamping */
    ladrc_real_t output_Nm;      /**< latest command */
    ladrc_real_t applied_Nm;     /**< torque applied since the latest tick */
    uint8_t has_prev;            /**< 0 until a first tick ran */
    uint8_t wrap;                /**< wrap_angle */
    uint8_t setpoint_ff;         /**< of the config */
    uint8_t landed;              /**< 1: the integrator holds (ladrc_cascaded_set_landed) */
} ladrc_cascaded_t;

/** Validates (LADRC_ERR_DT_S, _CAS_ATT_KP, _CAS_RATE_MAX, _CAS_RATE_KP,
 *  _CAS_RATE_KI, _CAS_RATE_KD, _CAS_D_TAU_S, _CAS_RATE_TAU_S, _CAS_I_LIMIT_NM,
 *  _CAS_I_RELAX, _CAS_RATE_FF, _CAS_SETPOINT_FF, _U_LIMITS, _WRAP_ANGLE in
 *  that order; _NULL) and resets at angle 0, not landed. The gain checks
 *  also refuse gains whose terms could leave the real type for rates inside
 *  +-2 rate_limit_rad_s (the feed-forward for setpoints inside
 *  +-rate_max_rad_s).
 *  @param[out] c    the controller to set up
 *  @param[in]  cfg  its configuration
 *  @retval LADRC_OK                 set up
 *  @retval LADRC_ERR_NULL           c or cfg is NULL
 *  @retval LADRC_ERR_DT_S           dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 *  @retval LADRC_ERR_CAS_ATT_KP     att_kp_per_s not finite, not > 0, or times dt_s >= 1
 *  @retval LADRC_ERR_CAS_RATE_MAX   rate_max_rad_s not finite and > 0, or above rate_limit_rad_s
 *  @retval LADRC_ERR_CAS_RATE_KP    rate_kp not finite, < 0, or its term beyond the real type
 *  @retval LADRC_ERR_CAS_RATE_KI    rate_ki not finite, < 0, or its step beyond the real type
 *  @retval LADRC_ERR_CAS_RATE_KD    rate_kd not finite, < 0, or its term beyond the real type
 *  @retval LADRC_ERR_CAS_D_TAU_S    d_filter_tau_s not finite or < 0
 *  @retval LADRC_ERR_CAS_RATE_TAU_S rate_filter_tau_s not finite or < 0
 *  @retval LADRC_ERR_CAS_I_LIMIT_NM i_limit_Nm NaN or < 0
 *  @retval LADRC_ERR_CAS_I_RELAX    i_relax_rad_s NaN, not > 0, or with an infinite inverse
 *                                   (INFINITY is accepted: no relax)
 *  @retval LADRC_ERR_CAS_RATE_FF    rate_ff not finite, < 0, or its term beyond the real type
 *  @retval LADRC_ERR_CAS_SETPOINT_FF setpoint_ff not 0 or 1
 *  @retval LADRC_ERR_U_LIMITS       u_min_Nm or u_max_Nm NaN, or u_min_Nm >= u_max_Nm
 *  @retval LADRC_ERR_WRAP_ANGLE     wrap_angle not 0 or 1 */
ladrc_status_t ladrc_cascaded_init(ladrc_cascaded_t *c, const ladrc_cascaded_config_t *cfg);

/** Restarts at rest: integral, filters and commands 0, previous angle
 *  angle_rad. The landed flag is the vehicle's, not the loop's: kept.
 *  @param c          the controller; NULL: nothing happens
 *  @param angle_rad  the measured angle (rad), finite (not checked: the axis checks) */
void ladrc_cascaded_reset(ladrc_cascaded_t *c, ladrc_real_t angle_rad);

/** Takes over from another controller: restarts as ladrc_cascaded_reset on
 *  angle_rad, with the rate at rate_rad_s and the integral at torque_Nm, so
 *  that a first tick at zero rate error continues torque_Nm.
 *  @param c          the loop; NULL: nothing happens
 *  @param angle_rad  the measured angle (rad)
 *  @param rate_rad_s the measured rate (rad/s); 0 without one
 *  @param torque_Nm  the other controller's last command (N m), within the
 *                    output bounds */
void ladrc_cascaded_engage(ladrc_cascaded_t *c, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s,
                           ladrc_real_t torque_Nm);

/**
 * One tick on finite inputs (the axis checks them): shaped reference ref,
 * measured angle, measured rate (NULL: from the angle); torque_Nm receives
 * the command (N m). Returns 0, or LADRC_FAULT_STATE when the update would
 * leave the real type: the state and the command are then left as they
 * were (the axis restarts it).
 * @param c           the controller
 * @param ref         the shaped reference (rad, rad/s; ddr unused)
 * @param angle_rad   the measured angle (rad), finite (not checked)
 * @param rate_rad_s  the measured rate (rad/s), finite, or NULL
 * @param torque_Nm   out: the command (N m)
 * @return 0 or LADRC_FAULT_STATE; c, ref or torque_Nm NULL:
 *         LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_cascaded_step(ladrc_cascaded_t *c, const ladrc_ref_t *ref, ladrc_real_t angle_rad,
                                  const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm);

/** Torque actually applied since the latest tick.
 *  @param c           the controller; NULL: nothing happens
 *  @param applied_Nm  the applied torque (N m), finite (not checked: the axis checks) */
void ladrc_cascaded_set_applied(ladrc_cascaded_t *c, ladrc_real_t applied_Nm);

/** Whether the vehicle is on the ground. While landed the integrator holds
 *  its value (PX4 does not integrate while landed: ground contact would
 *  wind it up); the P, D and feed-forward terms still act. Held until set
 *  again and kept by ladrc_cascaded_reset; init starts not landed.
 *  @param c       the controller; NULL: nothing happens
 *  @param landed  0: flying, anything else: landed */
void ladrc_cascaded_set_landed(ladrc_cascaded_t *c, uint8_t landed);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_CASCADED_H */
