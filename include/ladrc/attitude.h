/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file attitude.h
 * @brief Three axes (roll, pitch, yaw) ticked together, with the paper's
 *        decoupling-free coupling feed (docs/method.md section 4).
 *
 * The cross-axis coupling of the rigid body stays in each axis's total
 * disturbance f, but its rate of change h = f' is partly known from the other
 * axes' estimates, so it is fed to each LESO as a known input:
 *
 *     h_roll  = (Jy - Jz)/Jx (pitch'' yaw'  + pitch' yaw'' ) - kt/Jx roll''
 *     h_pitch = (Jz - Jx)/Jy (roll''  yaw'  + roll'  yaw'' ) - kt/Jy pitch''
 *     h_yaw   = (Jx - Jy)/Jz (roll''  pitch' + roll' pitch'') - kt/Jz yaw''
 *
 * with rates from each LESO's z2 and accelerations b0 * acting torque + z3 +
 * d_hat (ladrc_axis_get_accel: the applied torque through the axis's
 * actuator model, motor_tau_s and delay_ticks, when it has one), computed at the start of each tick from the
 * previous tick's estimates. The feed only applies to LADRC-family axes; a
 * PID or CASCADED axis contributes zero acceleration and receives no feed.
 *
 * One tick: ladrc_attitude_step -> mixer -> ladrc_attitude_set_applied with
 * the torques actually achieved (so saturation never winds an observer up).
 *
 * Two frames (docs/method.md, "Quaternion attitude"):
 * - LADRC_FRAME_EULER, the paper's: each axis takes its own Euler angle and
 *   reference (ladrc_attitude_step). Singular at +-90 deg pitch, and the
 *   errors of different axes mix at large tilt.
 * - LADRC_FRAME_QUATERNION, as flight stacks take attitude: the measured
 *   attitude and the reference are unit quaternions
 *   (ladrc_attitude_step_quat). Each axis works on its body angle, the sum
 *   of the body-frame rotation increments between measured attitudes
 *   (wrapped into (-pi, pi], so every axis needs wrap_angle = 1), whose
 *   rate is the gyro's body rate; its raw reference is that body angle plus
 *   the attitude error with tilt priority (quat.h). Valid through any
 *   attitude; the coupling feed's body rates are then exact.
 *
 * The layer owns its axes and, on the tick's path, reads their estimates and
 * writes their fed rate and applied torque directly, with the results of
 * ladrc_axis_get_accel, ladrc_axis_set_disturbance_rate and
 * ladrc_axis_set_applied (which it still calls for a PID axis or a
 * non-finite torque).
 */
#ifndef LADRC_ATTITUDE_H
#define LADRC_ATTITUDE_H

#include "ladrc/axis.h"
#include "ladrc/quat.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Indices of the axes in the attitude layer's arrays. */
enum {
    LADRC_ROLL = 0,  /**< roll, phi about body X */
    LADRC_PITCH = 1, /**< pitch, theta about body Y */
    LADRC_YAW = 2,   /**< yaw, psi about body Z */
    LADRC_AXES = 3   /**< number of axes (not an axis) */
};

/** How the attitude layer takes the attitude and its reference. */
typedef enum {
    LADRC_FRAME_EULER = 0,     /**< per Euler angle (the paper's): ladrc_attitude_step */
    LADRC_FRAME_QUATERNION = 1 /**< unit quaternions, tilt priority: ladrc_attitude_step_quat */
} ladrc_attitude_frame_t;

/** Flight phases (docs/method.md section 9), ladrc_attitude_get_phase. */
typedef enum {
    LADRC_PHASE_DISARMED = 0, /**< motors off: torque 0, the axes not stepped; arming starts them afresh */
    LADRC_PHASE_SPOOL_UP = 1, /**< armed, the motors spinning up: torque 0 for spool_up_s, the axes as landed */
    LADRC_PHASE_LANDED = 2,   /**< on the ground: the law acts, the ground takes the torque (ladrc_axis_set_landed) */
    LADRC_PHASE_FLYING = 3    /**< in the air (init's phase) */
} ladrc_phase_t;

/** PX4's default weight of yaw against tilt (MC_YAW_WEIGHT). */
#define LADRC_YAW_WEIGHT_DEFAULT LADRC_R(0.4)
/** Default spool-up (s): PX4 spools up over 1 s (COM_SPOOLUP_TIME), Betaflight at once. */
#define LADRC_SPOOL_UP_DEFAULT_S LADRC_R(0.5)
/** Longest spool-up init accepts (s). */
#define LADRC_SPOOL_UP_MAX_S LADRC_R(10.0)

/** Attitude configuration (ladrc_attitude_init validates it); can live in flash. */
typedef struct {
    ladrc_axis_config_t axis[LADRC_AXES];   /**< roll, pitch, yaw; equal dt_s */
    ladrc_real_t inertia_kg_m2[LADRC_AXES]; /**< Jx, Jy, Jz the feed assumes (kg m^2), > 0, a rigid body's */
    ladrc_real_t drag_Nms;                  /**< rotational drag kt (N m s), >= 0 */
    uint8_t coupling_feed;                  /**< 1: feed h to the observers, 0: off */
    ladrc_attitude_frame_t frame;           /**< how attitude is taken; QUATERNION needs wrap_angle = 1
                                                 on every axis */
    ladrc_real_t yaw_weight;                /**< QUATERNION: weight of yaw against tilt in the error,
                                                 (0, 1], 1 = none (quat.h) */
    ladrc_real_t spool_up_s;                /**< time from arming to control (s), >= 0, at most
                                                 LADRC_SPOOL_UP_MAX_S; default 0.5 */
    /* The plant-gain schedule (ladrc_attitude_set_operating_point), off by default */
    ladrc_real_t gain_thrust_curve;  /**< k of the rotors' thrust curve (1 - k) c + k c^2 that the mixer
                                          leaves (0: the torque per command does not change with throttle) */
    ladrc_real_t gain_full_thrust_N; /**< thrust at full command (N), > 0 when gain_thrust_curve > 0 */
    ladrc_real_t gain_ref_thrust_N;  /**< thrust at which b0 holds (N, e.g. hover), > 0 when gain_thrust_curve > 0 */
    ladrc_real_t gain_ref_voltage_V; /**< pack voltage at which b0 holds (V); 0: no voltage schedule */
} ladrc_attitude_config_t;

/** Attitude state; owned by the caller. */
typedef struct {
    ladrc_real_t coupling[LADRC_AXES];       /**< (Jy-Jz)/Jx, (Jz-Jx)/Jy, (Jx-Jy)/Jz */
    ladrc_real_t drag_per_s[LADRC_AXES];     /**< kt / J per axis (1/s) */
    ladrc_real_t feed_rad_s3[LADRC_AXES];    /**< h fed at the latest tick (rad/s^3) */
    ladrc_real_t body_angle_rad[LADRC_AXES]; /**< QUATERNION: the body angles the axes take (rad) */
    ladrc_quat_t attitude;                   /**< QUATERNION: the latest good measured attitude */
    ladrc_real_t yaw_weight;                 /**< of the config */
    uint8_t coupling_feed;                   /**< of the config */
    uint8_t frame;                           /**< of the config */
    uint8_t has_attitude;                    /**< QUATERNION: 1 once a good attitude was measured */
    uint8_t phase;                           /**< ladrc_phase_t */
    uint8_t landed;                          /**< the caller's landed input */
    uint8_t restart;                         /**< 1: the axes restart at the next tick (the feed off for it) */
    uint32_t spool_ticks;                    /**< SPOOL_UP: ticks left */
    uint32_t spool_up_ticks;                 /**< spool_up_s in ticks */
    ladrc_real_t engage_Nm[LADRC_AXES];      /**< the other controller's last command (N m) */
    ladrc_real_t gain_curve;                 /**< gain_thrust_curve */
    ladrc_real_t gain_per_full_N;            /**< 2 k / gain_full_thrust_N (1/N) */
    ladrc_real_t gain_ref_inv;               /**< 1 / the curve's slope at gain_ref_thrust_N */
    ladrc_real_t gain_ref_voltage_V;         /**< of the config */
    ladrc_axis_t axis[LADRC_AXES];           /**< roll, pitch, yaw */
} ladrc_attitude_t;

/**
 * Fills cfg with ladrc_axis_config_default for each axis (inertia from
 * inertia_kg_m2), the given drag and the feed on, wrap_angle on for yaw
 * (off for roll and pitch), the Euler frame and yaw weight
 * LADRC_YAW_WEIGHT_DEFAULT. CASCADED's setpoint feed-forward as PX4 flies
 * it: cas_setpoint_ff 0 on roll and pitch, 1 on yaw (PX4's attitude
 * controller feeds forward the yaw setpoint's rate only; cascaded.h); the
 * other variants do not read it. Copies without checking (init checks).
 * @param cfg            out: the config; cfg or inertia_kg_m2 NULL: nothing happens
 * @param variant        the variant of every axis
 * @param dt_s           control step (s)
 * @param inertia_kg_m2  Jx, Jy, Jz (kg m^2)
 * @param drag_Nms       rotational drag kt (N m s)
 */
void ladrc_attitude_config_default(ladrc_attitude_config_t *cfg, ladrc_variant_t variant, ladrc_real_t dt_s,
                                   const ladrc_real_t inertia_kg_m2[LADRC_AXES], ladrc_real_t drag_Nms);

/** Switches cfg to the quaternion frame: frame QUATERNION, wrap_angle on
 *  every axis (the body angles live on a circle); the yaw weight is left.
 *  @param cfg  the config; NULL: nothing happens */
void ladrc_attitude_config_quaternion(ladrc_attitude_config_t *cfg);

/**
 * Validates the vehicle fields in the order below, then each axis in turn
 * (ladrc_axis_init, whose statuses pass through).
 * @param[out] att          the controller to set up
 * @param[in]  cfg          its configuration
 * @param[out] failed_axis  the index of the axis whose config was rejected,
 *                          else -1 (also for a vehicle field); may be NULL
 * @retval LADRC_OK                   set up
 * @retval LADRC_ERR_NULL             att or cfg is NULL
 * @retval LADRC_ERR_INERTIA_KG_M2    an inertia not finite or not > 0
 * @retval LADRC_ERR_INERTIA_TRIANGLE an inertia above the sum of the other two
 * @retval LADRC_ERR_DRAG_NMS         drag_Nms not finite, < 0, or drag_Nms / J * dt_s > 2
 * @retval LADRC_ERR_COUPLING_FEED    coupling_feed not 0 or 1
 * @retval LADRC_ERR_ATTITUDE_FRAME   frame not a ladrc_attitude_frame_t
 * @retval LADRC_ERR_YAW_WEIGHT       QUATERNION: yaw_weight not finite or not in (0, 1]
 * @retval LADRC_ERR_WRAP_ANGLE       QUATERNION: an axis (*failed_axis) with wrap_angle 0
 * @retval LADRC_ERR_SPOOL_UP_S       spool_up_s not finite, < 0 or above LADRC_SPOOL_UP_MAX_S
 * @retval LADRC_ERR_GAIN_SCHEDULE    gain_thrust_curve not finite or outside [0, 1]; with it > 0, the
 *                                    thrusts not finite and > 0; gain_ref_voltage_V not finite or < 0
 * @retval LADRC_ERR_DT_S             an axis's dt_s differs from roll's (or, from
 *                                    ladrc_axis_init, is invalid)
 * @return any other status of ladrc_axis_init, for axis *failed_axis
 */
ladrc_status_t ladrc_attitude_init(ladrc_attitude_t *att, const ladrc_attitude_config_t *cfg, int *failed_axis);

/** Restarts every axis at rest on the given angles and clears the feed.
 *  QUATERNION: the angles are the body angles to restart from (0 0 0 will
 *  do: only their changes matter) and the next good attitude measured is
 *  taken as the start, with no increment.
 *  @param att        the controller; att or angle_rad NULL: nothing happens
 *  @param angle_rad  roll, pitch, yaw to rest on (rad); non-finite or beyond
 *                    an axis's angle_limit_rad: 0 */
void ladrc_attitude_reset(ladrc_attitude_t *att, const ladrc_real_t angle_rad[LADRC_AXES]);

/**
 * One tick of the three axes: the coupling feed (when on), then each axis's step
 * (non-finite inputs as ladrc_axis_step).
 * @param att         the controller
 * @param ref_rad     references (rad)
 * @param angle_rad   measured angles (rad)
 * @param rate_rad_s  measured body rates (rad/s), or NULL
 * @param torque_Nm   out: torque commands (N m)
 * @return the union of the axes' fault flags; att, ref_rad, angle_rad or
 *         torque_Nm NULL, or the QUATERNION frame: LADRC_FAULT_STATE,
 *         nothing changes
 */
ladrc_fault_t ladrc_attitude_step(ladrc_attitude_t *att, const ladrc_real_t ref_rad[LADRC_AXES],
                                  const ladrc_real_t angle_rad[LADRC_AXES], const ladrc_real_t *rate_rad_s,
                                  ladrc_real_t torque_Nm[LADRC_AXES]);

/**
 * One tick in the QUATERNION frame: the body angles move by the rotation
 * from the previous good attitude to this one, the error with tilt priority
 * gives each axis its raw reference (body angle + error, wrapped), then the
 * tick of ladrc_attitude_step. An attitude that is not finite or has no
 * norm (ladrc_quat_normalise) is a bad input on every axis: each holds and
 * raises LADRC_FAULT_INPUT, the body angles stay; a bad reference alone
 * holds the axes while the body angles follow the attitude. Quaternions of
 * any norm are normalised.
 * @param att         the controller
 * @param q_ref       the reference attitude
 * @param q_meas      the measured attitude (body to world)
 * @param rate_rad_s  measured body rates (rad/s), or NULL
 * @param torque_Nm   out: torque commands (N m)
 * @return the union of the axes' fault flags; a pointer but rate_rad_s NULL,
 *         or the EULER frame: LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_attitude_step_quat(ladrc_attitude_t *att, const ladrc_quat_t *q_ref, const ladrc_quat_t *q_meas,
                                       const ladrc_real_t *rate_rad_s, ladrc_real_t torque_Nm[LADRC_AXES]);

/**
 * Flight phases (docs/method.md section 9). Init leaves the controller
 * FLYING and not landed, as it always flew. Disarming stops it (torque 0,
 * the axes not stepped; in the quaternion frame the body angles still
 * follow the attitude). Arming from DISARMED spools up for spool_up_s
 * (torque 0), its first tick restarting every axis on its measurement, so
 * nothing learnt in one flight reaches the next; then LANDED or FLYING, as
 * the landed input says. While landed (and spooling up) every axis takes the
 * ground's reaction: the torque it takes as acting is 0, so no observer or
 * estimator learns the torque the ground resists, and the integrators hold
 * (ladrc_axis_set_landed). Arming while armed, or disarming while disarmed,
 * does nothing.
 * @param att  the controller; NULL: nothing happens
 */
void ladrc_attitude_arm(ladrc_attitude_t *att);

/** Disarms (above). @param att  the controller; NULL: nothing happens */
void ladrc_attitude_disarm(ladrc_attitude_t *att);

/** The landed input, from the caller's land detector (above): 1 on the
 *  ground, 0 in the air; other values are taken as 1.
 *  @param att     the controller; NULL: nothing happens
 *  @param landed  1 or 0 */
void ladrc_attitude_set_landed(ladrc_attitude_t *att, uint8_t landed);

/** The phase. @param att  the controller; NULL: LADRC_PHASE_DISARMED
 *  @return the ladrc_phase_t */
ladrc_phase_t ladrc_attitude_get_phase(const ladrc_attitude_t *att);

/**
 * Bumpless engage from another controller: the next tick restarts every
 * axis on its measurement (angle and, when given, rate) with torque_Nm as the
 * command already acting, and the disturbance estimates (LADRC family,
 * RATE-ADRC, INDI) or integrators (PID, CASCADED) preset so that its first
 * command continues torque_Nm (ladrc_axis_engage). To hand back, give the
 * other controller this one's last command the same way.
 * @param att        the controller; att or torque_Nm NULL: nothing happens
 * @param torque_Nm  the other controller's last roll, pitch, yaw command (N m);
 *                   a non-finite one is taken as 0
 */
void ladrc_attitude_engage(ladrc_attitude_t *att, const ladrc_real_t torque_Nm[LADRC_AXES]);

/**
 * The plant-gain schedule (docs/method.md section 9): b0 follows the thrust
 * and the pack's voltage. On rotors whose thrust is (1 - k) c + k c^2 of the
 * command c (the part of the curve the mixer does not undo), a mixer that
 * takes thrust as linear gives the command c = T / T_full for the thrust T
 * asked, and the torque per command there goes with the curve's slope,
 * (1 - k) + 2 k T / T_full; rotor speeds go with the voltage, so torques
 * with its square.
 * Every axis's gain scale (ladrc_axis_set_gain_scale) becomes
 *     slope(T) / slope(T_ref) * (V / V_ref)^2
 * clamped to [LADRC_GAIN_SCALE_MIN, LADRC_GAIN_SCALE_MAX]; without a
 * schedule configured it stays 1. Call once per tick, before the step, with
 * the thrust asked of the mixer.
 * @param att        the controller; NULL: nothing happens
 * @param thrust_N   the collective thrust (N); not finite or < 0: the thrust part kept
 * @param voltage_V  the pack's voltage (V); not finite or not > 0: the voltage part left out
 */
void ladrc_attitude_set_operating_point(ladrc_attitude_t *att, ladrc_real_t thrust_N, ladrc_real_t voltage_V);

/** Reports the torques the mixer achieved to each axis (ladrc_axis_set_applied).
 *  @param att        the controller; att or torque_Nm NULL: nothing happens
 *  @param torque_Nm  roll, pitch, yaw torque (N m); non-finite or beyond an
 *                    axis's applied_limit_Nm: ignored, LADRC_FAULT_APPLIED */
void ladrc_attitude_set_applied(ladrc_attitude_t *att, const ladrc_real_t torque_Nm[LADRC_AXES]);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_ATTITUDE_H */
