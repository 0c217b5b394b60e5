/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Status code texts, in flash: one pool of strings and a table of 16-bit
 * offsets into it. Each text is the enum name itself, followed by ": " and an
 * explanation unless the library is built with LADRC_STATUS_NAMES_ONLY (CMake
 * option LADRC_STATUS_TEXTS=names), which keeps only the names.
 */
#include "ladrc/types.h"

#include <stddef.h>

/* X(code, explanation), in the order of ladrc_status_t. */
#define LADRC_STATUS_LIST(X)                                                                                           \
    X(LADRC_OK, "no error")                                                                                            \
    X(LADRC_ERR_NULL, "a pointer argument is NULL")                                                                    \
    X(LADRC_ERR_DT_S, "dt_s must be finite and within 1e-6..1 s")                                                      \
    X(LADRC_ERR_WO_RAD_S, "wo_rad_s must be finite and > 0")                                                           \
    X(LADRC_ERR_WC_RAD_S, "wc_rad_s must be finite, > 0 and below 1 / dt_s")                                           \
    X(LADRC_ERR_B0, "b0 must be finite and non-zero; on an axis |b0| within 1e-3..1e7")                                \
    X(LADRC_ERR_LESO_METHOD, "leso_method is not a ladrc_leso_method_t")                                               \
    X(LADRC_ERR_LESO_EULER_UNSTABLE,                                                                                   \
      "Euler LESO needs wo_rad_s * dt_s < 2, on an axis <= 0.88 / (1 + 3.6 wc_rad_s * dt_s)")                          \
    X(LADRC_ERR_SHAPER, "shaper is not a ladrc_shaper_t")                                                              \
    X(LADRC_ERR_TD_ACCEL_RAD_S2, "td accel_rad_s2 must be finite and > 0")                                             \
    X(LADRC_ERR_TD_H0_S, "td h0_s must be finite and >= dt_s")                                                         \
    X(LADRC_ERR_VARIANT, "variant is not a ladrc_variant_t")                                                           \
    X(LADRC_ERR_U_LIMITS, "u_min_Nm < u_max_Nm required, neither NaN; on an axis u_min_Nm < 0 < u_max_Nm")             \
    X(LADRC_ERR_PID_KP, "kp must be finite and >= 0")                                                                  \
    X(LADRC_ERR_PID_KI, "ki must be finite and >= 0")                                                                  \
    X(LADRC_ERR_PID_KD, "kd must be finite and >= 0")                                                                  \
    X(LADRC_ERR_PID_D_TAU_S, "d_filter_tau_s must be finite and >= 0")                                                 \
    X(LADRC_ERR_PID_I_LIMIT_NM, "i_limit_Nm must be >= 0 and not NaN")                                                 \
    X(LADRC_ERR_SETTLING_TIME_S, "settling_time_s must be finite and > 0")                                             \
    X(LADRC_ERR_PLANT_ORDER, "plant order must be 1, 2 or 3")                                                          \
    X(LADRC_ERR_INERTIA_KG_M2, "inertia_kg_m2 must be finite and > 0")                                                 \
    X(LADRC_ERR_WO_RATIO, "the observer/controller bandwidth ratio must be finite and > 0")                            \
    X(LADRC_ERR_RLS_N_PARAMS, "rls n_params must be 1..LADRC_RLS_MAX_PARAMS")                                          \
    X(LADRC_ERR_RLS_LAMBDA0, "rls lambda0_per_s must be finite, >= 0 and <= 1 / dt_s")                                 \
    X(LADRC_ERR_RLS_P_BOUND, "rls p_bound must be finite and > 0")                                                     \
    X(LADRC_ERR_RLS_P_INITIAL, "rls p_initial must be finite, > 0 and <= p_bound / n_params")                          \
    X(LADRC_ERR_MIXER_KL_N_S2, "mixer kL_N_s2 must lie in [1e-10, 0.1] N s^2")                                         \
    X(LADRC_ERR_MIXER_ARM_M, "mixer arm_m must lie in [1e-3, 10] m")                                                   \
    X(LADRC_ERR_MIXER_B_NM_S2, "mixer b_Nm_s2 must lie in [1e-13, 0.1] N m s^2")                                       \
    X(LADRC_ERR_MIXER_MASS_KG, "mixer mass_kg must lie in [1e-3, 1e3] kg")                                             \
    X(LADRC_ERR_MIXER_G_M_S2, "mixer g_m_s2 must lie in [0.1, 100] m/s^2")                                             \
    X(LADRC_ERR_MIXER_MODE, "mixer mode is not a ladrc_mixer_mode_t")                                                  \
    X(LADRC_ERR_MIXER_W2_MIN, "mixer w2_min_rad2_s2 must be finite, and >= 0 unless ideal")                            \
    X(LADRC_ERR_MIXER_W2_MAX, "mixer w2_max_rad2_s2 must be > w2_min_rad2_s2 and, unless ideal, in [1e2, 1e10]")       \
    X(LADRC_ERR_MIXER_TILT_MAX_RAD, "mixer tilt_max_rad must lie in (0, pi/2)")                                        \
    X(LADRC_ERR_EST_LAMBDA0, "estimator lambda0_per_s must be finite and > 0")                                         \
    X(LADRC_ERR_EST_K0, "estimator k0_per_s must be finite and > 0")                                                   \
    X(LADRC_ERR_HP_FREQ_MODE, "hp freq_mode is not a ladrc_hp_freq_mode_t")                                            \
    X(LADRC_ERR_HP_FREQ_RAD_S, "hp freq_rad_s of each modelled tone must be finite, > 0 and < pi / dt_s")              \
    X(LADRC_ERR_HP_FREQ_RANGE, "hp needs 0 < freq_min < freq_max and freq_max dt_s < pi")                              \
    X(LADRC_ERR_HP_N_TONES, "hp n_tones must be 1..LADRC_HP_MAX_TONES")                                                \
    X(LADRC_ERR_HP_SAMPLE_LAG,                                                                                         \
      "hp sample_lag_wo_rad_s must be finite, >= 0 and 0 or above a tenth of the fastest tone")                        \
    X(LADRC_ERR_DRAG_NMS, "drag_Nms must be finite, >= 0 and at most 2 J / dt_s on every axis")                        \
    X(LADRC_ERR_COUPLING_FEED, "coupling_feed must be 0 or 1")                                                         \
    X(LADRC_ERR_LEVANT_METHOD, "method is not a ladrc_levant_method_t")                                                \
    X(LADRC_ERR_LEVANT_GAINS, "gains is not a ladrc_levant_gains_t")                                                   \
    X(LADRC_ERR_LEVANT_LIPSCHITZ, "lipschitz_rad_s4 must be finite and > 0, on an axis <= 10 / dt_s^2")                \
    X(LADRC_ERR_LEVANT_L1, "l1 must be finite and > 0")                                                                \
    X(LADRC_ERR_LEVANT_L2, "l2 must be finite and > 0")                                                                \
    X(LADRC_ERR_LEVANT_L3, "l3 must be finite and > 0")                                                                \
    X(LADRC_ERR_LEVANT_L4, "l4 must be finite and > 0")                                                                \
    X(LADRC_ERR_LEVANT_RANGE, "dt_s and the gains give per-sample coefficients out of range")                          \
    X(LADRC_ERR_HP_FIT_DECIMATION,                                                                                     \
      "hp needs 1 <= fit_decimation, fit_phase < fit_decimation, freq * fit_decimation * dt_s < pi/2")                 \
    X(LADRC_ERR_HP_FREQ_LAMBDA0, "hp freq_lambda0_per_s must be finite, > 0 and at most 1 / (fit_decimation * dt_s)")  \
    X(LADRC_ERR_HP_FREQ_FILTER, "hp freq_filter_rad_s must be finite, > 0 and < 0.2 / (fit_decimation * dt_s)")        \
    X(LADRC_ERR_INPUT_LIMITS,                                                                                          \
      "angle_limit_rad and rate_limit_rad_s must be finite and >= 1e-3, applied_limit_Nm finite and > 0")              \
    X(LADRC_ERR_INERTIA_TRIANGLE, "each inertia must be at most the sum of the other two (a rigid body)")              \
    X(LADRC_ERR_MOTOR_TAU_S, "motor_tau_s must be finite, >= 0 and at most LADRC_MOTOR_TAU_MAX_S (1 s)")               \
    X(LADRC_ERR_DELAY_TICKS, "delay_ticks must be at most LADRC_MAX_DELAY_TICKS (400)")                                \
    X(LADRC_ERR_WRAP_ANGLE, "wrap_angle must be 0 or 1")                                                               \
    X(LADRC_ERR_INDI_ATT_KP, "indi_att_kp_per_s must be finite, > 0 and below 1 / dt_s")                               \
    X(LADRC_ERR_INDI_RATE_KP, "indi_rate_kp_per_s must be finite, > 0 and below 1 / dt_s")                             \
    X(LADRC_ERR_INDI_FILTER, "indi_filter_rad_s must be finite, > 0 and at most pi / dt_s")                            \
    X(LADRC_ERR_CAS_ATT_KP, "cas_att_kp must be finite, > 0 and below 1 / dt_s")                                       \
    X(LADRC_ERR_CAS_RATE_MAX, "cas_rate_max_rad_s must be finite, > 0 and at most rate_limit_rad_s")                   \
    X(LADRC_ERR_CAS_RATE_KP,                                                                                           \
      "cas_rate_kp must be finite, >= 0 and its term finite for rates within +-2 rate_limit_rad_s")                    \
    X(LADRC_ERR_CAS_RATE_KI,                                                                                           \
      "cas_rate_ki must be finite, >= 0 and its step finite for rates within +-2 rate_limit_rad_s")                    \
    X(LADRC_ERR_CAS_RATE_KD,                                                                                           \
      "cas_rate_kd must be finite, >= 0 and its term finite for rate steps of 2 rate_limit_rad_s")                     \
    X(LADRC_ERR_CAS_D_TAU_S, "cas_d_filter_tau_s must be finite and >= 0")                                             \
    X(LADRC_ERR_CAS_RATE_TAU_S, "cas_rate_filter_tau_s must be finite and >= 0")                                       \
    X(LADRC_ERR_CAS_I_LIMIT_NM, "cas_i_limit_Nm must be >= 0 and not NaN")                                             \
    X(LADRC_ERR_VARIANT_NOT_BUILT, "variant is left out of this build of the library (LADRC_VARIANTS)")                \
    X(LADRC_ERR_SHAPER_NOT_BUILT, "shaper is left out of this build of the library (LADRC_SHAPERS)")                   \
    X(LADRC_ERR_FEATURE_NOT_BUILT,                                                                                     \
      "hp freq_mode ONLINE: the online frequency search is left out of this build of the library (LADRC_HP_ONLINE)")   \
    X(LADRC_ERR_RADRC_KP, "radrc_kp_per_s must be finite, > 0 and radrc_kp_per_s * dt_s < 1")                          \
    X(LADRC_ERR_RADRC_ATT_KP, "radrc_att_kp_per_s must be finite, > 0 and radrc_att_kp_per_s * dt_s < 1")              \
    X(LADRC_ERR_RADRC_RATE_MAX, "radrc_rate_max_rad_s must be finite, > 0 and <= rate_limit_rad_s")                    \
    X(LADRC_ERR_RADRC_ACRO, "radrc_acro must be 0 or 1")                                                               \
    X(LADRC_ERR_HP_SAMPLE, "hp_sample must be LADRC_HP_SAMPLE_OBSERVER or LADRC_HP_SAMPLE_GYRO")                       \
    X(LADRC_ERR_GYRO_CHANNELS, "gyro filter channels must be 1..LADRC_GYRO_FILTER_MAX_CHANNELS")                       \
    X(LADRC_ERR_GYRO_LPF_ORDER, "gyro filter lpf_order must be 0, 1 or 2")                                             \
    X(LADRC_ERR_GYRO_LPF_CUTOFF_HZ, "gyro filter lpf_cutoff_hz must be finite and within (0, 0.5 / dt_s)")             \
    X(LADRC_ERR_GYRO_N_NOTCHES, "gyro filter n_notches must be at most LADRC_GYRO_FILTER_MAX_NOTCHES")                 \
    X(LADRC_ERR_GYRO_NOTCH_HZ, "gyro filter notch_hz must be finite and within (0, 0.45 / dt_s)")                      \
    X(LADRC_ERR_GYRO_NOTCH_Q,                                                                                          \
      "gyro filter notch_q must be finite, > 0 and neither too high nor too low for a stable notch")                   \
    X(LADRC_ERR_GYRO_RPM_ROTORS, "gyro filter rpm_rotors must be at most LADRC_GYRO_FILTER_MAX_ROTORS")                \
    X(LADRC_ERR_GYRO_RPM_HARMONICS, "gyro filter rpm_harmonics must be 1..LADRC_GYRO_FILTER_MAX_HARMONICS")            \
    X(LADRC_ERR_GYRO_RPM_MIN_HZ, "gyro filter rpm_min_hz must be finite and within (0, 0.45 / dt_s)")                  \
    X(LADRC_ERR_GYRO_RPM_FADE_HZ, "gyro filter rpm_fade_hz must be finite, >= 0, and 0 or with a finite inverse")      \
    X(LADRC_ERR_GYRO_RPM_Q,                                                                                            \
      "gyro filter rpm_q must be finite, > 0 and neither too high nor too low for a stable notch")                     \
    X(LADRC_ERR_ATTITUDE_FRAME, "attitude frame must be LADRC_FRAME_EULER or LADRC_FRAME_QUATERNION")                  \
    X(LADRC_ERR_YAW_WEIGHT, "yaw_weight must be finite and in (0, 1]")                                                 \
    X(LADRC_ERR_CAS_I_RELAX, "cas_i_relax_rad_s must be > 0 with a finite inverse (INFINITY: no relax)")               \
    X(LADRC_ERR_CAS_RATE_FF,                                                                                           \
      "cas_rate_ff must be finite, >= 0 and its term finite for setpoints within +-cas_rate_max_rad_s")                \
    X(LADRC_ERR_CAS_SETPOINT_FF, "cas_setpoint_ff must be 0 or 1")                                                     \
    X(LADRC_ERR_INDI_ADAPT, "indi_adapt must be 0 or 1")                                                               \
    X(LADRC_ERR_INDI_ADAPT_MU, "indi_adapt_mu must be finite and in (0, 1]")                                           \
    X(LADRC_ERR_INDI_ADAPT_EXCITATION,                                                                                 \
      "indi_adapt_jerk_min_rad_s3 must be finite, > 0 and give a torque threshold > 0")                                \
    X(LADRC_ERR_INDI_ADAPT_MIN, "indi_adapt_min_ratio must be finite, in (0, 1] and |b0| times it >= 1e-3")            \
    X(LADRC_ERR_INDI_ADAPT_MAX, "indi_adapt_max_ratio must be finite, >= 1 and |b0| times it <= 1e7")                  \
    X(LADRC_ERR_SPOOL_UP_S, "spool_up_s must be finite and within [0, LADRC_SPOOL_UP_MAX_S]")                          \
    X(LADRC_ERR_MIXER_THRUST_CURVE, "mixer thrust_curve must be finite and within [0, 1]")                             \
    X(LADRC_ERR_GAIN_SCHEDULE,                                                                                         \
      "gain_thrust_curve must be in [0, 1] (> 0: both thrusts finite and > 0), gain_ref_voltage_V >= 0")

#ifdef LADRC_STATUS_NAMES_ONLY
#define STATUS_TEXT(code, explanation) #code
#else
#define STATUS_TEXT(code, explanation) #code ": " explanation
#endif

/* The list must follow the enum: each code's position in the list is checked
 * against its value at compile time (a negative array size otherwise). */
#define POSITION(code, explanation) position_##code,
enum { LADRC_STATUS_LIST(POSITION) list_length };
#define CHECK_POSITION(code, explanation) typedef char check_##code[(position_##code == (int)code) ? 1 : -1];
LADRC_STATUS_LIST(CHECK_POSITION)
typedef char check_list_length[(list_length == (int)LADRC_STATUS_COUNT) ? 1 : -1];

/* One array per text, so offsetof gives each text's place in the pool. */
#define POOL_MEMBER(code, explanation) char code[sizeof STATUS_TEXT(code, explanation)];
#define POOL_TEXT(code, explanation) .code = STATUS_TEXT(code, explanation),
#define POOL_OFFSET(code, explanation) (uint16_t) offsetof(status_pool_t, code),

typedef struct {
    LADRC_STATUS_LIST(POOL_MEMBER)
    char unknown[sizeof STATUS_TEXT(LADRC_ERR_UNKNOWN, "not a ladrc_status_t")];
} status_pool_t;

static const status_pool_t pool = {LADRC_STATUS_LIST(POOL_TEXT) /* each code's text, then the fallback */
                                       .unknown = STATUS_TEXT(LADRC_ERR_UNKNOWN, "not a ladrc_status_t")};

static const uint16_t offsets[LADRC_STATUS_COUNT] = {LADRC_STATUS_LIST(POOL_OFFSET)};

const char *ladrc_status_str(ladrc_status_t status)
{
    if ((unsigned)status >= (unsigned)LADRC_STATUS_COUNT) {
        return pool.unknown;
    }
    return (const char *)&pool + offsets[status];
}
