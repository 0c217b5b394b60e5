/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file mixer.h
 * @brief Plus-frame quadrotor mixer: thrust and body torques in, rotor speeds
 *        squared out, with rotor limits applied by priority and the thrust and
 *        torques actually achieved reported back.
 *
 * Rotors 1..4 are array indices 0..3 (PAPER.md section 1): rotors 1 and 3 lie
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
 * [w2_min, w2_max]. Each w^2 is split into collective c = a/4, a yaw part
 * +-r/4 and a roll/pitch part; priorities, highest first:
 *   1. roll and pitch: if their spread over the rotors exceeds w2_max - w2_min,
 *      both are scaled by the same factor (their ratio, i.e. the torque
 *      direction, is kept);
 *   2. yaw: the largest share in [0, 1] of the yaw part that still fits beside
 *      roll and pitch is kept;
 *   3. thrust: the collective moves to the value nearest the request that puts
 *      every rotor within the limits.
 * The achieved thrust and torques of an axis that step 1, 2 or 3 changed come
 * from the forward model of the final w^2; an axis that was not changed
 * reports its request itself, bit for bit. So achieved != requested exactly
 * when the axis was cut back: a PID or observer comparing applied with
 * commanded torque never mistakes rounding for saturation (the rotors of an
 * axis left alone give its request up to float rounding of w^2). Bit i of
 * `saturated` (LADRC_MIXER_SAT_*) is set exactly when achieved != requested.
 *
 * Mode LADRC_MIXER_IDEAL applies no limits (w^2 may be negative, as the
 * paper's rotor 2 is in its simulation) and reports the request as achieved.
 *
 * Thrust that holds altitude at a tilt (paper eq. 4): U_L = m g / (cos phi cos theta),
 * with cos phi cos theta floored at cos(tilt_max_rad).
 *
 * The mixer is memoryless apart from the last good output, which a step with
 * non-finite input returns again (LADRC_FAULT_INPUT). No gains, no time step.
 */
#ifndef LADRC_MIXER_H
#define LADRC_MIXER_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    LADRC_MIXER_SATURATE = 0, /**< rotor limits applied with priorities */
    LADRC_MIXER_IDEAL = 1     /**< no limits: the paper's ideal actuators */
} ladrc_mixer_mode_t;

/** Bits of ladrc_mixer_output_t.saturated: achieved value differs from the request. */
enum {
    LADRC_MIXER_SAT_ROLL = 1u << 0,
    LADRC_MIXER_SAT_PITCH = 1u << 1,
    LADRC_MIXER_SAT_YAW = 1u << 2,
    LADRC_MIXER_SAT_THRUST = 1u << 3
};

typedef struct {
    ladrc_real_t kL_N_s2;        /**< rotor thrust coefficient kL (N s^2), > 0 */
    ladrc_real_t arm_m;          /**< rotor arm length l from the centre (m), > 0 */
    ladrc_real_t b_Nm_s2;        /**< rotor drag-torque coefficient b (N m s^2), > 0 */
    ladrc_real_t mass_kg;        /**< vehicle mass m (kg), > 0 */
    ladrc_real_t g_m_s2;         /**< gravity g (m/s^2), > 0 */
    ladrc_real_t w2_min_rad2_s2; /**< lowest rotor speed squared, >= 0 (any finite value if IDEAL) */
    ladrc_real_t w2_max_rad2_s2; /**< highest rotor speed squared, finite, > w2_min_rad2_s2 */
    ladrc_real_t tilt_max_rad;   /**< tilt beyond which thrust_from_tilt stops growing, in (0, pi/2) */
    ladrc_mixer_mode_t mode;     /**< saturate (flight) or ideal (paper) */
} ladrc_mixer_config_t;

/** One mix: what the motors get and what the airframe gets from it. */
typedef struct {
    ladrc_real_t w2_rad2_s2[4]; /**< rotor speeds squared, rotors 1..4 */
    ladrc_real_t w_rad_s[4];    /**< sqrt(max(w^2, 0)) */
    ladrc_real_t thrust_N;      /**< achieved U_L (the request if not cut back) */
    ladrc_real_t torque_Nm[3];  /**< achieved roll, pitch, yaw torque (the request if not cut back) */
    uint8_t saturated;          /**< LADRC_MIXER_SAT_* bits */
    ladrc_fault_t faults;       /**< flags of the step that returned this output */
} ladrc_mixer_output_t;

/** Mixer state; owned by the caller. Constants derived at init, plus the last good output. */
typedef struct {
    ladrc_real_t kL_N_s2, lkL_Nm_s2, b_Nm_s2; /**< forward-model coefficients */
    ladrc_real_t a4_per_N;      /**< 1 / (4 kL) */
    ladrc_real_t p2_per_Nm;     /**< 1 / (2 l kL) */
    ladrc_real_t r4_per_Nm;     /**< 1 / (4 b) */
    ladrc_real_t weight_N;      /**< m g */
    ladrc_real_t cos_tilt_min;  /**< cos(tilt_max_rad) */
    ladrc_real_t thrust_max_N;  /**< m g / cos(tilt_max_rad): thrust_from_tilt's cap */
    ladrc_real_t w2_min_rad2_s2, w2_max_rad2_s2; /**< rotor limits; ideal mode: -+ the largest finite value */
    ladrc_mixer_mode_t mode;
    ladrc_mixer_output_t out;   /**< last good output */
} ladrc_mixer_t;

/** Validates every field (LADRC_ERR_MIXER_KL_N_S2, _ARM_M, _B_NM_S2, _MASS_KG, _G_M_S2,
 *  _MODE, _W2_MIN, _W2_MAX, _TILT_MAX_RAD, checked in that order; LADRC_ERR_NULL), derives
 *  the constants and resets. On a config error *mx is zeroed: every step then outputs
 *  w^2 = 0 (its achieved values mean nothing; do not fly a rejected mixer). */
ladrc_status_t ladrc_mixer_init(ladrc_mixer_t *mx, const ladrc_mixer_config_t *cfg);

/** Sets the held output to the mix of level hover (U_L = m g, no torque) and clears faults. */
void ladrc_mixer_reset(ladrc_mixer_t *mx);

/**
 * Thrust that holds altitude at the given attitude: m g / max(cos(roll) cos(pitch),
 * cos(tilt_max_rad)) in N. Non-finite angles give m g (level hover).
 */
ladrc_real_t ladrc_mixer_thrust_from_tilt(const ladrc_mixer_t *mx, ladrc_real_t roll_rad,
                                          ladrc_real_t pitch_rad);

/**
 * Step 1, pure: allocation (paper eq. 33), no limits.
 * @param thrust_N   requested U_L (N)
 * @param torque_Nm  requested roll, pitch, yaw torque (N m)
 * @param w2_rad2_s2 out: rotor speeds squared, may be negative or beyond the limits
 */
void ladrc_mixer_allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                          const ladrc_real_t torque_Nm[3], ladrc_real_t w2_rad2_s2[4]);

/**
 * Step 2, pure: rotor limits by priority (roll/pitch, then yaw, then thrust; see
 * the file comment), achieved values and saturation bits. Inputs must be finite
 * (ladrc_mixer_step checks them): a non-finite w^2, or limits that overflow, leave
 * *out untouched. out->faults is set to LADRC_FAULT_NONE.
 * @param w2_rad2_s2 allocation of the request, from ladrc_mixer_allocate
 * @param thrust_N, torque_Nm the request that was allocated (reported back unchanged
 *        on the axes that were not cut back)
 */
void ladrc_mixer_saturate(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                          ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                          ladrc_mixer_output_t *out);

/** Forward model: thrust (N) and roll, pitch, yaw torque (N m) of the given w^2. */
void ladrc_mixer_forward(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                         ladrc_real_t *thrust_N, ladrc_real_t torque_Nm[3]);

/**
 * One mix: allocate, then saturate; the result is held in the state and copied to
 * *out (out may be NULL). A non-finite request returns the held output again with
 * LADRC_FAULT_INPUT; a finite request too large to mix in range (overflow) does the
 * same with LADRC_FAULT_STATE. The held output starts as hover (see reset).
 * @return the step's fault flags
 */
ladrc_fault_t ladrc_mixer_step(ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                               const ladrc_real_t torque_Nm[3], ladrc_mixer_output_t *out);

/** Fault flags of the latest step. */
ladrc_fault_t ladrc_mixer_get_faults(const ladrc_mixer_t *mx);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_MIXER_H */
