/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file mixer.h
 * @brief Plus-frame quadrotor mixer: thrust and body torques in, rotor speeds
 *        squared out, with rotor limits applied by priority and the thrust and
 *        torques actually achieved reported back.
 *
 * Rotors 1..4 are array indices 0..3 (docs/method.md section 1): rotors 1 and 3 lie
 * on the body X arm and make pitch, 2 and 4 on the Y arm and make roll; 2 and 4
 * spin against 1 and 3, so their drag makes yaw. Roll = phi about body X,
 * pitch = theta about Y, yaw = psi about Z; a positive torque accelerates its
 * angle positively. Forward model (w_i^2 in rad^2/s^2):
 *
 *     U_L   = kL (w1^2 + w2^2 + w3^2 + w4^2)
 *     tau_x = l kL (w2^2 - w4^2)
 *     tau_y = l kL (w3^2 - w1^2)
 *     tau_z = b (-w1^2 + w2^2 - w3^2 + w4^2)
 *
 * Allocation, its exact inverse (paper eq. 33), with a = U_L/kL,
 * p = tau_x/(l kL), q = tau_y/(l kL), r = tau_z/b:
 *
 *     w1^2 = a/4 - q/2 - r/4    w2^2 = a/4 + p/2 + r/4
 *     w3^2 = a/4 + q/2 - r/4    w4^2 = a/4 - p/2 + r/4
 *
 * Saturation (mode LADRC_MIXER_SATURATE), only when some w^2 lies outside
 * [w2_min, w2_max]. First each request is limited to the most the rotors can
 * give at all: roll and pitch together to l kL (w2_max - w2_min) (both scaled
 * by one factor, so their ratio is kept), yaw to 2 b (w2_max - w2_min), thrust
 * to [4 kL w2_min, 4 kL w2_max]. In exact arithmetic this changes nothing below;
 * in float it keeps every part of w^2 on the scale of the rotor range, so that
 * a huge request (up to the largest float) cannot swamp the others in
 * rounding. Each w^2 is then split into collective c = a/4, a yaw part +-r/4
 * and a roll/pitch part; priorities, highest first:
 *   1. roll and pitch: if their spread over the rotors exceeds w2_max - w2_min,
 *      both are scaled by the same factor (their ratio, i.e. the torque
 *      direction, is kept);
 *   2. yaw: the largest share in [0, 1] of the yaw part that still fits beside
 *      roll and pitch is kept;
 *   3. thrust: the collective moves to the value nearest the request that puts
 *      every rotor within the limits.
 *
 * Achieved values and saturation bits, in both modes and on every step: the
 * thrust and torques are the forward model of the w^2 the step outputs. An
 * axis whose forward model agrees with its request within float rounding
 * (|achieved - requested| <= 8 eps coef sum|w_i^2| + 16 x the smallest
 * subnormal, with eps the epsilon of ladrc_real_t and coef = kL for thrust,
 * l kL for roll and pitch, b for yaw: the allocation and the forward model
 * round by at most about 4.5 eps coef sum|w_i^2|) reports its request itself,
 * bit for bit, and its bit stays clear; any other axis reports the forward
 * model and has its bit of `saturated` (LADRC_MIXER_SAT_*) set. So bit i is
 * set exactly when achieved != requested, and the achieved values are always
 * what the rotors give: a PID or observer comparing applied with commanded
 * torque never mistakes rounding for saturation, nor saturation for success.
 *
 * Mode LADRC_MIXER_IDEAL applies no limits (w^2 may be negative, as the
 * paper's rotor 2 is in its simulation); its achieved values are the request
 * (its forward model agrees within the tolerance above). A request whose w^2
 * would pass +-(largest float)/4 (where the forward model's sums could
 * overflow) is refused with LADRC_FAULT_STATE.
 *
 * Motor commands. A rotor's ESC takes a command c in [0, 1], and real rotors'
 * thrust is not linear in it: between linear and quadratic, thrust / thrust
 * at full command = (1 - k) c + k c^2, k = thrust_curve (PX4's THR_MDL_FAC,
 * ArduPilot's MOT_THST_EXPO; ladrc_mixer_set_thrust_curve, 0 after init).
 * ladrc_mixer_command inverts that curve for a
 * rotor's w^2 (proportional to its thrust), so that the commands it gives
 * make the thrusts the mix asked for: the torque per unit of command is then
 * the same at every throttle. With k = 0 the command is w^2 / w2_max.
 *
 * Thrust that holds altitude at a tilt (paper eq. 4): U_L = m g / (cos phi cos theta),
 * with cos phi cos theta floored at cos(tilt_max_rad).
 *
 * The mixer is memoryless apart from the last good output, which a step with
 * non-finite input returns again (LADRC_FAULT_INPUT). No gains, no time step.
 *
 * Config bounds (LADRC_MIXER_*_MIN, _MAX below): init accepts each physical
 * field only within a plausible range, wide enough for any multirotor from a
 * 20 g micro (kL ~ 3e-8 N s^2, l ~ 0.03 m, b ~ 1e-9 N m s^2, rotors up to
 * ~6000 rad/s, w^2 ~ 4e7) to a 50 kg heavy lifter (kL ~ 3e-3 N s^2, l ~ 1.5 m,
 * rotors ~200 rad/s) with a factor of 6 or more to spare, and narrow enough that
 * every constant init derives (1/(4 kL), 1/(2 l kL), 1/(4 b), m g, the request
 * limits above) and the forward model of any w^2 the mixer outputs stay finite
 * and normal in float. Init checks those derived constants too.
 */
#ifndef LADRC_MIXER_H
#define LADRC_MIXER_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @name Bounds of the config fields that ladrc_mixer_init accepts (inclusive)
 *  @{ */
#define LADRC_MIXER_KL_MIN_N_S2 LADRC_R(1e-10) /**< kL_N_s2 lowest (N s^2) */
#define LADRC_MIXER_KL_MAX_N_S2 LADRC_R(0.1)   /**< kL_N_s2 highest (N s^2) */
#define LADRC_MIXER_ARM_MIN_M LADRC_R(1e-3)    /**< arm_m shortest (m) */
#define LADRC_MIXER_ARM_MAX_M LADRC_R(10.0)    /**< arm_m longest (m) */
#define LADRC_MIXER_B_MIN_NM_S2 LADRC_R(1e-13) /**< b_Nm_s2 lowest (N m s^2) */
#define LADRC_MIXER_B_MAX_NM_S2 LADRC_R(0.1)   /**< b_Nm_s2 highest (N m s^2) */
#define LADRC_MIXER_MASS_MIN_KG LADRC_R(1e-3)  /**< mass_kg lowest (kg) */
#define LADRC_MIXER_MASS_MAX_KG LADRC_R(1e3)   /**< mass_kg highest (kg) */
#define LADRC_MIXER_G_MIN_M_S2 LADRC_R(0.1)    /**< g_m_s2 lowest (m/s^2) */
#define LADRC_MIXER_G_MAX_M_S2 LADRC_R(100.0)  /**< g_m_s2 highest (m/s^2) */
/** w2_max_rad2_s2 lowest in saturate mode (rad^2/s^2; top speed 10 rad/s) */
#define LADRC_MIXER_W2_MAX_MIN_RAD2_S2 LADRC_R(1e2)
/** w2_max_rad2_s2 highest in saturate mode (rad^2/s^2; top speed 1e5 rad/s) */
#define LADRC_MIXER_W2_MAX_MAX_RAD2_S2 LADRC_R(1e10)
/** @} */

/** Whether the mixer applies rotor limits. */
typedef enum {
    LADRC_MIXER_SATURATE = 0, /**< rotor limits applied with priorities */
    LADRC_MIXER_IDEAL = 1     /**< no limits: the paper's ideal actuators */
} ladrc_mixer_mode_t;

/** Bits of ladrc_mixer_output_t.saturated: achieved value differs from the request. */
enum {
    LADRC_MIXER_SAT_ROLL = 1u << 0,  /**< roll torque */
    LADRC_MIXER_SAT_PITCH = 1u << 1, /**< pitch torque */
    LADRC_MIXER_SAT_YAW = 1u << 2,   /**< yaw torque */
    LADRC_MIXER_SAT_THRUST = 1u << 3 /**< thrust */
};

/** Mixer configuration (ladrc_mixer_init validates it); can live in flash. */
typedef struct {
    ladrc_real_t kL_N_s2;        /**< rotor thrust coefficient kL (N s^2), in [1e-10, 0.1] */
    ladrc_real_t arm_m;          /**< rotor arm length l from the centre (m), in [1e-3, 10] */
    ladrc_real_t b_Nm_s2;        /**< rotor drag-torque coefficient b (N m s^2), in [1e-13, 0.1] */
    ladrc_real_t mass_kg;        /**< vehicle mass m (kg), in [1e-3, 1e3] */
    ladrc_real_t g_m_s2;         /**< gravity g (m/s^2), in [0.1, 100] */
    ladrc_real_t w2_min_rad2_s2; /**< lowest rotor speed squared (rad^2/s^2), >= 0 (IDEAL: any finite value, unused) */
    ladrc_real_t w2_max_rad2_s2; /**< highest rotor speed squared (rad^2/s^2), > w2_min_rad2_s2 and in [1e2, 1e10]
                                      (IDEAL: any finite value > w2_min_rad2_s2, unused) */
    ladrc_real_t tilt_max_rad;   /**< tilt beyond which thrust_from_tilt stops growing (rad), in (0, pi/2) */
    ladrc_mixer_mode_t mode;     /**< saturate (flight) or ideal (paper) */
} ladrc_mixer_config_t;

/** One mix: what the motors get and what the airframe gets from it. */
typedef struct {
    ladrc_real_t w2_rad2_s2[4]; /**< rotor speeds squared (rad^2/s^2), rotors 1..4 */
    ladrc_real_t w_rad_s[4];    /**< rotor speeds sqrt(max(w^2, 0)) (rad/s) */
    ladrc_real_t thrust_N;      /**< achieved U_L: forward model of w2_rad2_s2 (the request if within rounding) */
    ladrc_real_t torque_Nm[3];  /**< achieved roll, pitch, yaw torque, likewise */
    uint8_t saturated;          /**< LADRC_MIXER_SAT_* bits */
    ladrc_fault_t faults;       /**< flags of the step that returned this output */
} ladrc_mixer_output_t;

/** Mixer state; owned by the caller. Constants derived at init, plus the last good output. */
typedef struct {
    /** @{ */
    ladrc_real_t kL_N_s2, lkL_Nm_s2, b_Nm_s2; /**< forward-model coefficients kL (N s^2), l kL (N m s^2), b (N m s^2) */
    /** @} */
    ladrc_real_t a4_per_N;     /**< 1 / (4 kL) */
    ladrc_real_t p2_per_Nm;    /**< 1 / (2 l kL) */
    ladrc_real_t r4_per_Nm;    /**< 1 / (4 b) */
    ladrc_real_t weight_N;     /**< m g */
    ladrc_real_t cos_tilt_min; /**< cos(tilt_max_rad) */
    ladrc_real_t thrust_max_N; /**< m g / cos(tilt_max_rad): thrust_from_tilt's cap */
    /** @{ */
    ladrc_real_t w2_min_rad2_s2,
        w2_max_rad2_s2; /**< rotor limits (rad^2/s^2); ideal mode: -+ (largest finite value)/4 */
    /** @} */
    ladrc_real_t rp_limit_Nm;  /**< l kL (w2_max - w2_min): most roll or pitch torque (0 if ideal) */
    ladrc_real_t yaw_limit_Nm; /**< 2 b (w2_max - w2_min): most yaw torque (0 if ideal) */
    /** @{ */
    ladrc_real_t thrust_lo_N, thrust_hi_N; /**< 4 kL w2_min, 4 kL w2_max: thrust range (0 if ideal) */
    /** @} */
    ladrc_mixer_mode_t mode;     /**< of the config */
    ladrc_real_t thrust_curve;   /**< ladrc_mixer_set_thrust_curve's k, 0 after init */
    ladrc_real_t command_per_w2; /**< 1 / w2_max of the config (1/(rad^2/s^2)) */
    ladrc_mixer_output_t out;    /**< last good output */
} ladrc_mixer_t;

/** Validates every field against its bounds (LADRC_ERR_MIXER_KL_N_S2, _ARM_M, _B_NM_S2,
 *  _MASS_KG, _G_M_S2, _MODE, _W2_MIN, _W2_MAX, _TILT_MAX_RAD, checked in that order;
 *  LADRC_ERR_NULL), derives the constants and checks that each is finite and > 0 (a
 *  failure is reported with the status of the last field, in that order, the constant
 *  depends on; the bounds above make that unreachable, the check stays should they be
 *  widened), then resets. On a config error *mx is zeroed: every step then outputs
 *  w^2 = 0 and achieved values 0 (do not fly a rejected mixer).
 *  @param[out] mx   the mixer to set up
 *  @param[in]  cfg  its configuration
 *  @retval LADRC_OK                     set up
 *  @retval LADRC_ERR_NULL               mx or cfg is NULL
 *  @retval LADRC_ERR_MIXER_KL_N_S2      kL_N_s2 outside [LADRC_MIXER_KL_MIN_N_S2, LADRC_MIXER_KL_MAX_N_S2]
 *  @retval LADRC_ERR_MIXER_ARM_M        arm_m outside [LADRC_MIXER_ARM_MIN_M, LADRC_MIXER_ARM_MAX_M]
 *  @retval LADRC_ERR_MIXER_B_NM_S2      b_Nm_s2 outside [LADRC_MIXER_B_MIN_NM_S2, LADRC_MIXER_B_MAX_NM_S2]
 *  @retval LADRC_ERR_MIXER_MASS_KG      mass_kg outside [LADRC_MIXER_MASS_MIN_KG, LADRC_MIXER_MASS_MAX_KG]
 *  @retval LADRC_ERR_MIXER_G_M_S2       g_m_s2 outside [LADRC_MIXER_G_MIN_M_S2, LADRC_MIXER_G_MAX_M_S2]
 *  @retval LADRC_ERR_MIXER_MODE         mode not a ladrc_mixer_mode_t
 *  @retval LADRC_ERR_MIXER_W2_MIN       w2_min_rad2_s2 not finite, or < 0 in saturate mode
 *  @retval LADRC_ERR_MIXER_W2_MAX       w2_max_rad2_s2 not > w2_min_rad2_s2 or, saturating, outside
 *                                       [LADRC_MIXER_W2_MAX_MIN_RAD2_S2, LADRC_MIXER_W2_MAX_MAX_RAD2_S2]
 *  @retval LADRC_ERR_MIXER_TILT_MAX_RAD tilt_max_rad not in (0, pi/2) */
ladrc_status_t ladrc_mixer_init(ladrc_mixer_t *mx, const ladrc_mixer_config_t *cfg);

/** Sets the held output to the mix of level hover (U_L = m g, no torque) and clears faults.
 *  @param mx  the mixer; NULL: nothing happens */
void ladrc_mixer_reset(ladrc_mixer_t *mx);

/**
 * Thrust that holds altitude at the given attitude: m g / max(cos(roll) cos(pitch),
 * cos(tilt_max_rad)). Non-finite angles give m g (level hover).
 * @param mx         the mixer; NULL: 0
 * @param roll_rad   roll angle (rad)
 * @param pitch_rad  pitch angle (rad)
 * @return the thrust (N)
 */
ladrc_real_t ladrc_mixer_thrust_from_tilt(const ladrc_mixer_t *mx, ladrc_real_t roll_rad, ladrc_real_t pitch_rad);

/**
 * Step 1, pure: allocation (paper eq. 33), no limits. Non-finite inputs
 * give non-finite outputs (ladrc_mixer_step checks them).
 * @param mx         the mixer; mx, torque_Nm or w2_rad2_s2 NULL: nothing written
 * @param thrust_N   requested U_L (N)
 * @param torque_Nm  requested roll, pitch, yaw torque (N m)
 * @param w2_rad2_s2 out: rotor speeds squared, may be negative or beyond the limits
 */
void ladrc_mixer_allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                          ladrc_real_t w2_rad2_s2[4]);

/**
 * Step 2, pure: rotor limits by priority (roll/pitch, then yaw, then thrust; see
 * the file comment), achieved values and saturation bits. If w^2 lies outside the
 * limits, the request is limited and allocated again (scale-safe, file comment), so
 * w^2 must be the allocation of that request. Inputs must be finite (ladrc_mixer_step
 * checks them): a non-finite w^2 or request, or in ideal mode a w^2 beyond the
 * range, leaves *out untouched. out->faults is set to LADRC_FAULT_NONE.
 * @param mx         the mixer; any pointer NULL: nothing written
 * @param w2_rad2_s2 allocation of the request (rad^2/s^2), from ladrc_mixer_allocate
 * @param thrust_N, torque_Nm the request that was allocated (N, N m; reported back
 *        bit for bit on the axes whose rotors give it within rounding)
 * @param out        out: the achieved mix
 */
void ladrc_mixer_saturate(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4], ladrc_real_t thrust_N,
                          const ladrc_real_t torque_Nm[3], ladrc_mixer_output_t *out);

/** Forward model: thrust and roll, pitch, yaw torque of the given w^2; no
 *  finiteness check (non-finite in, non-finite out).
 *  @param mx          the mixer; any pointer NULL: nothing written
 *  @param w2_rad2_s2  rotor speeds squared (rad^2/s^2)
 *  @param thrust_N    out: thrust (N)
 *  @param torque_Nm   out: roll, pitch, yaw torque (N m) */
void ladrc_mixer_forward(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4], ladrc_real_t *thrust_N,
                         ladrc_real_t torque_Nm[3]);

/**
 * One mix: allocate, then saturate; the result is held in the state and copied to
 * *out (out may be NULL). A non-finite request returns the held output again with
 * LADRC_FAULT_INPUT. In saturate mode every finite request, up to the largest float,
 * is mixed (limited as the file comment says). In ideal mode a finite request whose
 * w^2 would pass +-(largest float)/4 returns the held output with LADRC_FAULT_STATE.
 * The held output starts as hover (see reset). A NULL mx or torque_Nm (a
 * programmer error, LADRC_ASSERT) returns LADRC_FAULT_STATE with asserts off,
 * the state untouched.
 * @param mx         the mixer
 * @param thrust_N   requested thrust U_L (N)
 * @param torque_Nm  requested roll, pitch, yaw torque (N m)
 * @param out        out: the mix, or NULL
 * @return the step's fault flags
 */
ladrc_fault_t ladrc_mixer_step(ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                               ladrc_mixer_output_t *out);

/** Sets the rotors' thrust curve k (file comment) that ladrc_mixer_command
 *  inverts; 0 after init (thrust linear in the command).
 *  @param mx  the mixer; NULL: LADRC_ERR_NULL
 *  @param k   the curve, in [0, 1]
 *  @retval LADRC_OK                     set
 *  @retval LADRC_ERR_NULL               mx is NULL
 *  @retval LADRC_ERR_MIXER_THRUST_CURVE k not finite or outside [0, 1] (the curve kept) */
ladrc_status_t ladrc_mixer_set_thrust_curve(ladrc_mixer_t *mx, ladrc_real_t k);

/**
 * The ESC command of one rotor for its w^2: the c in [0, 1] whose thrust on
 * the curve (1 - k) c + k c^2 (file comment) is w^2 / w2_max of the full
 * thrust, c = 2 f / ((1 - k) + sqrt((1 - k)^2 + 4 k f)) with f = w^2 / w2_max
 * clamped to [0, 1] (no cancellation at any k). Saturate mode only.
 * @param mx          the mixer; NULL, or ideal mode: 0
 * @param w2_rad2_s2  the rotor's speed squared (rad^2/s^2), e.g. out.w2_rad2_s2[i]; not finite: 0
 * @return the command in [0, 1]
 */
ladrc_real_t ladrc_mixer_command(const ladrc_mixer_t *mx, ladrc_real_t w2_rad2_s2);

/** Fault flags of the latest step.
 *  @param mx  the mixer
 *  @return the flags; mx NULL: LADRC_FAULT_STATE */
ladrc_fault_t ladrc_mixer_get_faults(const ladrc_mixer_t *mx);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_MIXER_H */
