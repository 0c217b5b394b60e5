/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file types.h
 * @brief The real type, status codes, fault flags and small numeric helpers
 *        shared by every ladrc module.
 *
 * `ladrc_real_t` is `float` by default (single-precision FPU of a Cortex-M4F)
 * and `double` when the library is built with `LADRC_REAL_DOUBLE` defined.
 * Write literals as `LADRC_R(0.5)` so they take the right type in both builds.
 */
#ifndef LADRC_TYPES_H
#define LADRC_TYPES_H

/*
 * Build configuration hook. Compile the library and every file that
 * includes ladrc headers with -DLADRC_CONFIG=my_ladrc_config.h (a header
 * name without quotes, found on the include path) and this header includes
 * it first. It may define:
 *   LADRC_ASSERT(cond)   the check of programmer errors (NULL pointers);
 *                        e.g. assert(cond) after #include <assert.h>
 *   LADRC_SQRT(x), LADRC_FABS(x), LADRC_EXP(x), LADRC_EXPM1(x), LADRC_COS(x),
 *   LADRC_SIN(x), LADRC_ASIN(x), LADRC_CBRT(x)
 *                        the math functions on ladrc_real_t (default: the
 *                        <math.h> function of the real type, e.g. sqrtf)
 * CMake: -DLADRC_CONFIG_HEADER=path/to/my_ladrc_config.h sets both.
 * Avoid directory or file names that are macros (e.g. "unix" with gnu99).
 */
#ifdef LADRC_CONFIG
#define LADRC_STRINGIFY_(x) #x
#define LADRC_STRINGIFY(x) LADRC_STRINGIFY_(x)
#include LADRC_STRINGIFY(LADRC_CONFIG)
#endif

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifdef LADRC_REAL_DOUBLE
/** The real type of every quantity: double in this build. */
typedef double ladrc_real_t;
/** A literal of the real type. */
#define LADRC_R(x) (x)
#define LADRC_REAL_MAX DBL_MAX
#define LADRC_REAL_MIN DBL_MIN
#define LADRC_REAL_EPS DBL_EPSILON
#else
/** The real type of every quantity: float by default, double with LADRC_REAL_DOUBLE. */
typedef float ladrc_real_t;
/** A literal of the real type: appends the f suffix so float builds never promote to double. */
#define LADRC_R(x) (x##f)
/** Largest finite ladrc_real_t. */
#define LADRC_REAL_MAX FLT_MAX
/** Smallest positive normal ladrc_real_t. */
#define LADRC_REAL_MIN FLT_MIN
/** Distance from 1 to the next ladrc_real_t. */
#define LADRC_REAL_EPS FLT_EPSILON
#endif

/** Programmer-error check (null pointers in debug builds); never used on flight data.
 *  Override by defining LADRC_ASSERT in the LADRC_CONFIG header (or before
 *  including any ladrc header, with the same definition for the library).
 *  LADRC_ASSERTS_ENABLED is 1 when it is defined, 0 when it does nothing:
 *  with asserts on, passing NULL is a programmer error that the assert
 *  catches; with them off, the functions return LADRC_ERR_NULL or do nothing. */
#ifndef LADRC_ASSERT
#define LADRC_ASSERT(cond) ((void)0)
#define LADRC_ASSERTS_ENABLED 0 /**< 1: LADRC_ASSERT checks, 0: it does nothing */
#elif !defined(LADRC_ASSERTS_ENABLED)
#define LADRC_ASSERTS_ENABLED 1
#endif

/*
 * Variants and shapers built (1) or left out (0). The CMake list options
 * LADRC_VARIANTS (default: all seven) and LADRC_SHAPERS (default: TD;LEVANT)
 * define those left out as 0 for the library and everything that links it,
 * so that e.g. an HP-MLADRC firmware carries no PID, CASCADED, INDI, LP or
 * TD code and its axis state no space for them; init refuses a variant or
 * shaper left out with LADRC_ERR_VARIANT_NOT_BUILT / _SHAPER_NOT_BUILT.
 * Without CMake everything is built unless defined 0 (or 1, nothing else)
 * before this header; a library and the code using it must see the same
 * definitions (the state's layout depends on them: the ABI guard below).
 */
#ifndef LADRC_WITH_LADRC
#define LADRC_WITH_LADRC 1 /**< 1: the LADRC variant built, 0: left out */
#endif
#ifndef LADRC_WITH_LP_MLADRC
#define LADRC_WITH_LP_MLADRC 1 /**< 1: the LP-MLADRC variant built, 0: left out */
#endif
#ifndef LADRC_WITH_HP_MLADRC
#define LADRC_WITH_HP_MLADRC 1 /**< 1: the HP-MLADRC variant built, 0: left out */
#endif
#ifndef LADRC_WITH_PID
#define LADRC_WITH_PID 1 /**< 1: the PID variant built, 0: left out */
#endif
#ifndef LADRC_WITH_CASCADED
#define LADRC_WITH_CASCADED 1 /**< 1: the CASCADED variant built, 0: left out */
#endif
#ifndef LADRC_WITH_INDI
#define LADRC_WITH_INDI 1 /**< 1: the INDI variant built, 0: left out */
#endif
#ifndef LADRC_WITH_RATE_ADRC
#define LADRC_WITH_RATE_ADRC 1 /**< 1: the RATE-ADRC variant built, 0: left out */
#endif
#ifndef LADRC_WITH_TD
#define LADRC_WITH_TD 1 /**< 1: the TD shaper built, 0: left out */
#endif
#ifndef LADRC_WITH_LEVANT
#define LADRC_WITH_LEVANT 1 /**< 1: the Levant shaper built, 0: left out */
#endif
/*
 * The HP estimator's online frequency search (LADRC_HP_FREQ_ONLINE,
 * estimator.h) built (1) or left out (0), by the CMake option LADRC_HP_ONLINE
 * (default ON) as the variants are. Left out, the estimator knows its
 * frequencies only: its state has no room for the search, and ladrc_hp_init
 * (so the axis and attitude inits) refuses LADRC_HP_FREQ_ONLINE with
 * LADRC_ERR_FEATURE_NOT_BUILT.
 */
#ifndef LADRC_WITH_HP_ONLINE
#define LADRC_WITH_HP_ONLINE 1 /**< 1: the HP online frequency search built, 0: left out */
#endif

/*
 * ABI guard. The functions every user of a module calls (the inits, the
 * config defaults and the tuning helpers) carry the real type in their
 * symbol names: ladrc_pid_init is ladrc_pid_init_float, or
 * ladrc_pid_init_double with LADRC_REAL_DOUBLE. Those of the axis and the
 * attitude controller, whose states' layout depends on the variants built,
 * carry the variant and shaper set as well: _v then LADRC_WITH_ of LADRC,
 * LP_MLADRC, HP_MLADRC, PID, CASCADED, INDI, RATE_ADRC, then _s then those of TD,
 * LEVANT, then _o then LADRC_WITH_HP_ONLINE, then _t then LADRC_HP_MAX_TONES
 * (ladrc_axis_init_float_v1111111_s11_o1_t2 for everything built,
 * ladrc_axis_init_float_v0010000_s01_o0_t1 for HP-MLADRC + Levant without the
 * online frequency search and one tone); the HP estimator's init, whose
 * state depends on both, carries _o and _t (ladrc_hp_init_float_o1_t2), the
 * RLS's and the LP estimator's _t (ladrc_rls_init_float_t2). A library and
 * an application built with another real type or set fail to link
 * ("undefined reference to ladrc_axis_init_float_v1111111_s11_o1_t2") instead
 * of reading misplaced fields. Call the functions by their plain names.
 */
/** @cond LADRC_INTERNAL */
#define LADRC_ABI_CAT_(a, b) a##b
#define LADRC_ABI_CAT(a, b) LADRC_ABI_CAT_(a, b)
#ifdef LADRC_REAL_DOUBLE
#define LADRC_ABI_REAL_ _double
#else
#define LADRC_ABI_REAL_ _float
#endif
#define LADRC_ABI_SET_PASTE_(a, b, c, d, e, f, r, g, h, o, t) _v##a##b##c##d##e##f##r##_s##g##h##_o##o##_t##t
#define LADRC_ABI_SET_EXPAND_(a, b, c, d, e, f, r, g, h, o, t) LADRC_ABI_SET_PASTE_(a, b, c, d, e, f, r, g, h, o, t)
/** The variant and shaper set, the online search and the most tones as a
 *  symbol-name suffix, e.g. _v1111111_s11_o1_t2 (LADRC_HP_MAX_TONES, rls.h,
 *  must then be a plain whole number). */
#define LADRC_ABI_SET_                                                                                                 \
    LADRC_ABI_SET_EXPAND_(LADRC_WITH_LADRC, LADRC_WITH_LP_MLADRC, LADRC_WITH_HP_MLADRC, LADRC_WITH_PID,                \
                          LADRC_WITH_CASCADED, LADRC_WITH_INDI, LADRC_WITH_RATE_ADRC, LADRC_WITH_TD,                   \
                          LADRC_WITH_LEVANT, LADRC_WITH_HP_ONLINE, LADRC_HP_MAX_TONES)
#define LADRC_ABI_HP_PASTE_(o, t) _o##o##_t##t
#define LADRC_ABI_HP_EXPAND_(o, t) LADRC_ABI_HP_PASTE_(o, t)
/** The online search and the most tones as a symbol-name suffix, e.g. _o1_t2. */
#define LADRC_ABI_HP_ LADRC_ABI_HP_EXPAND_(LADRC_WITH_HP_ONLINE, LADRC_HP_MAX_TONES)
#define LADRC_ABI_TONES_PASTE_(t) _t##t
#define LADRC_ABI_TONES_EXPAND_(t) LADRC_ABI_TONES_PASTE_(t)
/** The most tones as a symbol-name suffix, e.g. _t2: the size of every RLS. */
#define LADRC_ABI_TONES_ LADRC_ABI_TONES_EXPAND_(LADRC_HP_MAX_TONES)
#define LADRC_ABI_NAME_(name) LADRC_ABI_CAT(name, LADRC_ABI_REAL_)
/* One paste of the three parts: a name passed through two nested pastes trips
 * some preprocessors (cppcheck's) on the macro's own name. */
#define LADRC_ABI_CAT3_(a, b, c) a##b##c
#define LADRC_ABI_CAT3(a, b, c) LADRC_ABI_CAT3_(a, b, c)
#define LADRC_ABI_SET_NAME_(name) LADRC_ABI_CAT3(name, LADRC_ABI_REAL_, LADRC_ABI_SET_)
#define ladrc_attitude_config_default LADRC_ABI_SET_NAME_(ladrc_attitude_config_default)
#define ladrc_attitude_init LADRC_ABI_SET_NAME_(ladrc_attitude_init)
#define ladrc_axis_config_default LADRC_ABI_SET_NAME_(ladrc_axis_config_default)
#define ladrc_axis_init LADRC_ABI_SET_NAME_(ladrc_axis_init)
#define ladrc_cascaded_init LADRC_ABI_NAME_(ladrc_cascaded_init)
#define ladrc_gyro_filter_config_default LADRC_ABI_NAME_(ladrc_gyro_filter_config_default)
#define ladrc_gyro_filter_init LADRC_ABI_NAME_(ladrc_gyro_filter_init)
#define ladrc_hp_init LADRC_ABI_CAT3(ladrc_hp_init, LADRC_ABI_REAL_, LADRC_ABI_HP_)
#define ladrc_indi_init LADRC_ABI_NAME_(ladrc_indi_init)
#define ladrc_leso_init LADRC_ABI_NAME_(ladrc_leso_init)
#define ladrc_levant_init LADRC_ABI_NAME_(ladrc_levant_init)
#define ladrc_lp_init LADRC_ABI_CAT3(ladrc_lp_init, LADRC_ABI_REAL_, LADRC_ABI_TONES_)
#define ladrc_mixer_init LADRC_ABI_NAME_(ladrc_mixer_init)
#define ladrc_pid_init LADRC_ABI_NAME_(ladrc_pid_init)
#define ladrc_reso_init LADRC_ABI_NAME_(ladrc_reso_init)
#define ladrc_rls_init LADRC_ABI_CAT3(ladrc_rls_init, LADRC_ABI_REAL_, LADRC_ABI_TONES_)
#define ladrc_rls1_init LADRC_ABI_NAME_(ladrc_rls1_init)
#define ladrc_td_init LADRC_ABI_NAME_(ladrc_td_init)
#define ladrc_tune_b0_from_inertia LADRC_ABI_NAME_(ladrc_tune_b0_from_inertia)
#define ladrc_tune_wc_from_settling LADRC_ABI_NAME_(ladrc_tune_wc_from_settling)
#define ladrc_tune_wc_from_settling_exact LADRC_ABI_NAME_(ladrc_tune_wc_from_settling_exact)
#define ladrc_tune_wo_from_wc LADRC_ABI_NAME_(ladrc_tune_wo_from_wc)
/** @endcond */

/**
 * Result of an init or a configuration helper. Each error names the one
 * configuration field that is wrong, so a caller can report it directly.
 */
typedef enum {
    LADRC_OK = 0,          /**< accepted */
    LADRC_ERR_NULL,        /**< a pointer argument is NULL */
    LADRC_ERR_DT_S,        /**< dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S] (1e-6..1 s) */
    LADRC_ERR_WO_RAD_S,    /**< wo_rad_s not finite or not > 0 */
    LADRC_ERR_WC_RAD_S,    /**< wc_rad_s not finite, not > 0, or wc_rad_s * dt_s >= 1 (the sampled loop is unstable) */
    LADRC_ERR_B0,          /**< b0 not finite or zero; on an axis, |b0| outside [1e-3, 1e7] */
    LADRC_ERR_LESO_METHOD, /**< leso_method not a ladrc_leso_method_t */
    LADRC_ERR_LESO_EULER_UNSTABLE, /**< Euler LESO with wo_rad_s * dt_s >= 2 (observer poles outside the unit circle); on an axis, wo dt above 0.88 / (1 + 3.6 wc dt) (the loop's) */
    LADRC_ERR_SHAPER,              /**< shaper not a ladrc_shaper_t */
    LADRC_ERR_TD_ACCEL_RAD_S2,     /**< td_accel_rad_s2 not finite or not > 0 */
    LADRC_ERR_TD_H0_S,             /**< td_h0_s not finite or < dt_s */
    LADRC_ERR_VARIANT,             /**< variant not a ladrc_variant_t */
    LADRC_ERR_U_LIMITS, /**< u_min_Nm / u_max_Nm NaN or u_min_Nm >= u_max_Nm (infinite = no limit); on an axis, not u_min_Nm < 0 < u_max_Nm */
    LADRC_ERR_PID_KP,          /**< kp not finite or < 0 */
    LADRC_ERR_PID_KI,          /**< ki not finite or < 0 */
    LADRC_ERR_PID_KD,          /**< kd not finite or < 0 */
    LADRC_ERR_PID_D_TAU_S,     /**< d_filter_tau_s not finite or < 0 */
    LADRC_ERR_PID_I_LIMIT_NM,  /**< i_limit_Nm NaN or < 0 (INFINITY = no clamp) */
    LADRC_ERR_SETTLING_TIME_S, /**< settling_time_s not finite or not > 0 */
    LADRC_ERR_PLANT_ORDER,     /**< plant order outside 1..3 */
    LADRC_ERR_INERTIA_KG_M2,   /**< inertia not finite or not > 0 */
    LADRC_ERR_WO_RATIO,        /**< observer-to-controller bandwidth ratio not finite or not > 0 */
    LADRC_ERR_RLS_N_PARAMS,    /**< rls n_params outside 1..LADRC_RLS_MAX_PARAMS */
    LADRC_ERR_RLS_LAMBDA0,     /**< rls lambda0_per_s not finite, < 0, or lambda0_per_s * dt_s > 1 */
    LADRC_ERR_RLS_P_BOUND,     /**< rls p_bound not finite or not > 0 */
    LADRC_ERR_RLS_P_INITIAL,   /**< rls p_initial not finite, not > 0, or n_params * p_initial > p_bound */
    LADRC_ERR_MIXER_KL_N_S2,   /**< mixer kL_N_s2 (thrust coefficient) outside [1e-10, 0.1] N s^2 */
    LADRC_ERR_MIXER_ARM_M,     /**< mixer arm_m (rotor arm length l) outside [1e-3, 10] m */
    LADRC_ERR_MIXER_B_NM_S2,   /**< mixer b_Nm_s2 (drag coefficient) outside [1e-13, 0.1] N m s^2 */
    LADRC_ERR_MIXER_MASS_KG,   /**< mixer mass_kg outside [1e-3, 1e3] kg */
    LADRC_ERR_MIXER_G_M_S2,    /**< mixer g_m_s2 outside [0.1, 100] m/s^2 */
    LADRC_ERR_MIXER_MODE,      /**< mixer mode not a ladrc_mixer_mode_t */
    LADRC_ERR_MIXER_W2_MIN,    /**< mixer w2_min_rad2_s2 not finite, or < 0 outside ideal mode */
    LADRC_ERR_MIXER_W2_MAX,    /**< mixer w2_max_rad2_s2 not > w2_min_rad2_s2 or, unless ideal, outside [1e2, 1e10] */
    LADRC_ERR_MIXER_TILT_MAX_RAD, /**< mixer tilt_max_rad not in (0, pi/2) */
    LADRC_ERR_EST_LAMBDA0,        /**< estimator forgetting rate not finite or not > 0 */
    LADRC_ERR_EST_K0,             /**< estimator gain bound k0 not finite or not > 0 */
    LADRC_ERR_HP_FREQ_MODE,       /**< hp freq_mode not a ladrc_hp_freq_mode_t */
    LADRC_ERR_HP_FREQ_RAD_S,      /**< hp freq_rad_s of a modelled tone not finite, not > 0, or >= pi / dt_s */
    LADRC_ERR_HP_FREQ_RANGE,      /**< hp online range: need 0 < min < max, max dt_s < pi */
    LADRC_ERR_HP_N_TONES,         /**< hp n_tones outside 1..LADRC_HP_MAX_TONES */
    LADRC_ERR_HP_SAMPLE_LAG,      /**< hp sample_lag_wo_rad_s not finite, < 0, or below a tenth of the fastest tone */
    LADRC_ERR_DRAG_NMS,           /**< attitude drag_Nms not finite, < 0, or drag_Nms / J * dt_s > 2 on an axis */
    LADRC_ERR_COUPLING_FEED,      /**< attitude coupling_feed not 0 or 1 */
    LADRC_ERR_LEVANT_METHOD,      /**< Levant method not a ladrc_levant_method_t */
    LADRC_ERR_LEVANT_GAINS,       /**< Levant gains not a ladrc_levant_gains_t */
    LADRC_ERR_LEVANT_LIPSCHITZ,   /**< lipschitz_rad_s4 not finite or not > 0; on an axis, above 10 / dt_s^2 */
    LADRC_ERR_LEVANT_L1,          /**< Levant l1 not finite or not > 0 */
    LADRC_ERR_LEVANT_L2,          /**< Levant l2 not finite or not > 0 */
    LADRC_ERR_LEVANT_L3,          /**< Levant l3 not finite or not > 0 */
    LADRC_ERR_LEVANT_L4,          /**< Levant l4 not finite or not > 0 */
    LADRC_ERR_LEVANT_RANGE,       /**< Levant per-sample coefficients overflow or vanish for this dt_s */
    LADRC_ERR_HP_FIT_DECIMATION,  /**< hp fit_decimation < 1, fit_phase >= fit_decimation, or the tone
                                       turns too far per fit sample */
    LADRC_ERR_HP_FREQ_LAMBDA0,    /**< hp freq_lambda0_per_s not finite, not > 0, or above 1 / T */
    LADRC_ERR_HP_FREQ_FILTER,     /**< hp freq_filter_rad_s not finite, not > 0, or too fast for the fit sample */
    LADRC_ERR_INPUT_LIMITS, /**< angle_limit_rad or rate_limit_rad_s not finite or below 1e-3, angle_limit_rad above 1e6, or applied_limit_Nm not finite or not > 0 */
    LADRC_ERR_INERTIA_TRIANGLE, /**< attitude inertias no rigid body has (each must be <= the sum of the other two) */
    LADRC_ERR_MOTOR_TAU_S,      /**< axis motor_tau_s not finite, < 0, or above LADRC_MOTOR_TAU_MAX_S */
    LADRC_ERR_DELAY_TICKS,      /**< axis delay_ticks above LADRC_MAX_DELAY_TICKS */
    LADRC_ERR_WRAP_ANGLE,       /**< axis (or pid) wrap_angle not 0 or 1 */
    LADRC_ERR_INDI_ATT_KP,      /**< indi_att_kp_per_s not finite, not > 0, or times dt_s >= 1 */
    LADRC_ERR_INDI_RATE_KP,     /**< indi_rate_kp_per_s not finite, not > 0, or times dt_s >= 1 */
    LADRC_ERR_INDI_FILTER,      /**< indi_filter_rad_s not finite, not > 0, or times dt_s > pi */
    LADRC_ERR_CAS_ATT_KP,       /**< cas_att_kp not finite, not > 0, or cas_att_kp * dt_s >= 1 */
    LADRC_ERR_CAS_RATE_MAX,     /**< cas_rate_max_rad_s not finite and > 0, or above rate_limit_rad_s */
    LADRC_ERR_CAS_RATE_KP, /**< cas_rate_kp not finite, < 0, or its term beyond the real type for rates within +-2 rate_limit_rad_s */
    LADRC_ERR_CAS_RATE_KI, /**< cas_rate_ki not finite, < 0, or its step beyond the real type (as kp) */
    LADRC_ERR_CAS_RATE_KD, /**< cas_rate_kd not finite, < 0, or its term beyond the real type for rate steps of 2 rate_limit_rad_s */
    LADRC_ERR_CAS_D_TAU_S,       /**< cas_d_filter_tau_s not finite or < 0 */
    LADRC_ERR_CAS_RATE_TAU_S,    /**< cas_rate_filter_tau_s not finite or < 0 */
    LADRC_ERR_CAS_I_LIMIT_NM,    /**< cas_i_limit_Nm NaN or < 0 (INFINITY = no clamp) */
    LADRC_ERR_VARIANT_NOT_BUILT, /**< axis variant left out of this build (LADRC_VARIANTS, axis.h) */
    LADRC_ERR_SHAPER_NOT_BUILT,  /**< axis shaper left out of this build (LADRC_SHAPERS, axis.h) */
    LADRC_ERR_FEATURE_NOT_BUILT, /**< hp freq_mode ONLINE: the online search is left out of this build (LADRC_HP_ONLINE) */
    LADRC_ERR_RADRC_KP,          /**< radrc_kp_per_s not finite, not > 0, or times dt_s >= 1 */
    LADRC_ERR_RADRC_ATT_KP,      /**< radrc_att_kp_per_s not finite, not > 0, or times dt_s >= 1 */
    LADRC_ERR_RADRC_RATE_MAX,    /**< radrc_rate_max_rad_s not finite and > 0, or above rate_limit_rad_s */
    LADRC_ERR_RADRC_ACRO,        /**< radrc_acro not 0 or 1 */
    LADRC_ERR_HP_SAMPLE,         /**< hp_sample not a ladrc_hp_sample_t */
    LADRC_ERR_GYRO_CHANNELS,     /**< gyro filter channels outside 1..LADRC_GYRO_FILTER_MAX_CHANNELS */
    LADRC_ERR_GYRO_LPF_ORDER,    /**< gyro filter lpf_order not 0, 1 or 2 */
    LADRC_ERR_GYRO_LPF_CUTOFF_HZ, /**< gyro filter lpf_cutoff_hz not finite or not in (0, 0.5 / dt_s) */
    LADRC_ERR_GYRO_N_NOTCHES,     /**< gyro filter n_notches above LADRC_GYRO_FILTER_MAX_NOTCHES */
    LADRC_ERR_GYRO_NOTCH_HZ,      /**< gyro filter notch_hz not finite or not in (0, 0.45 / dt_s) */
    LADRC_ERR_GYRO_NOTCH_Q,    /**< gyro filter notch_q not finite, not > 0, or too high or too low to round stable */
    LADRC_ERR_GYRO_RPM_ROTORS, /**< gyro filter rpm_rotors above LADRC_GYRO_FILTER_MAX_ROTORS */
    LADRC_ERR_GYRO_RPM_HARMONICS, /**< gyro filter rpm_harmonics outside 1..LADRC_GYRO_FILTER_MAX_HARMONICS */
    LADRC_ERR_GYRO_RPM_MIN_HZ,    /**< gyro filter rpm_min_hz not finite or not in (0, 0.45 / dt_s) */
    LADRC_ERR_GYRO_RPM_FADE_HZ,   /**< gyro filter rpm_fade_hz not finite, < 0, or its inverse not finite */
    LADRC_ERR_GYRO_RPM_Q,         /**< gyro filter rpm_q not finite, not > 0, or too high or too low to round stable */
    LADRC_ERR_ATTITUDE_FRAME,     /**< attitude frame not a ladrc_attitude_frame_t */
    LADRC_ERR_YAW_WEIGHT,         /**< attitude yaw_weight not finite or not in (0, 1] (quaternion frame) */
    LADRC_ERR_CAS_I_RELAX, /**< cas_i_relax_rad_s NaN, not > 0, or with an infinite inverse (INFINITY = no relax) */
    LADRC_ERR_CAS_RATE_FF, /**< cas_rate_ff not finite, < 0, or its term beyond the real type for setpoints within +-cas_rate_max_rad_s */
    LADRC_ERR_CAS_SETPOINT_FF, /**< cas_setpoint_ff not 0 or 1 */
    LADRC_ERR_INDI_ADAPT,      /**< indi_adapt not 0 or 1 */
    LADRC_ERR_INDI_ADAPT_MU,   /**< indi_adapt_mu not finite or not in (0, 1] */
    LADRC_ERR_INDI_ADAPT_EXCITATION, /**< indi_adapt_jerk_min_rad_s3 not finite, not > 0, or its torque threshold jerk_min dt_s / |b0| vanishes */
    LADRC_ERR_INDI_ADAPT_MIN,     /**< indi_adapt_min_ratio not finite, not in (0, 1], or |b0| times it below 1e-3 */
    LADRC_ERR_INDI_ADAPT_MAX,     /**< indi_adapt_max_ratio not finite, below 1, or |b0| times it above 1e7 */
    LADRC_ERR_SPOOL_UP_S,         /**< attitude spool_up_s not finite, < 0, or above LADRC_SPOOL_UP_MAX_S */
    LADRC_ERR_MIXER_THRUST_CURVE, /**< mixer thrust_curve not finite or outside [0, 1] */
    LADRC_ERR_GAIN_SCHEDULE,      /**< attitude gain schedule fields out of range (ladrc_attitude_init) */
    LADRC_STATUS_COUNT            /**< number of status codes (not a status) */
} ladrc_status_t;

/** Short, stable text for a status code.
 *  @param status  any value (one outside the enum has a text too)
 *  @return "LADRC_ERR_DT_S: ..." (the name alone with LADRC_STATUS_TEXTS
 *          names); never NULL */
const char *ladrc_status_str(ladrc_status_t status);

/**
 * Fault flags raised by a step. They describe the latest step only; a
 * module also counts consecutive faulty steps so a caller can fail over.
 */
enum {
    LADRC_FAULT_NONE = 0u,       /**< no fault */
    LADRC_FAULT_INPUT = 1u << 0, /**< reference or measured angle not finite or beyond angle_limit_rad: state held */
    LADRC_FAULT_RATE = 1u << 1,  /**< measured rate not finite or beyond rate_limit_rad_s: step ran without it */
    LADRC_FAULT_APPLIED =
        1u << 2,                /**< applied command not finite or beyond applied_limit_Nm: own command used instead */
    LADRC_FAULT_STATE = 1u << 3 /**< an update would have made the state non-finite: state held */
};
/** Fault flags: LADRC_FAULT_* bits, or-ed. */
typedef uint8_t ladrc_fault_t;

/*
 * Finiteness tests. The default ones rest on IEEE semantics (isfinite, and
 * x * 0 == 0 for a finite x). -ffast-math and -ffinite-math-only let the
 * compiler assume that no value is NaN or infinite and fold those tests to
 * "finite", which would let a NaN measurement through. Under those flags
 * (__FINITE_MATH_ONLY__, which -ffast-math sets) the tests read the exponent
 * bits instead: all ones is an infinity or a NaN, whatever the flags.
 */
/** @cond LADRC_INTERNAL */
#if (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__) || defined(__FAST_MATH__)
#define LADRC_FINITE_BY_BITS 1
#else
#define LADRC_FINITE_BY_BITS 0
#endif
/** @endcond */

#if LADRC_FINITE_BY_BITS
#ifdef LADRC_REAL_DOUBLE
/* 1 if the exponent field of x is not all ones. */
static inline int ladrc_finite_bits_(ladrc_real_t x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return ((u & UINT64_C(0x7ff0000000000000)) != UINT64_C(0x7ff0000000000000)) ? 1 : 0;
}
#else
static inline int ladrc_finite_bits_(ladrc_real_t x)
{
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return ((u & UINT32_C(0x7f800000)) != UINT32_C(0x7f800000)) ? 1 : 0;
}
#endif

/** Whether x is neither NaN nor infinite.
 *  @param x  any value
 *  @return 1 finite, 0 NaN or infinite */
static inline int ladrc_is_finite(ladrc_real_t x)
{
    return ladrc_finite_bits_(x);
}

static inline int ladrc_all_finite2(ladrc_real_t a, ladrc_real_t b)
{
    return ladrc_finite_bits_(a) & ladrc_finite_bits_(b);
}

static inline int ladrc_all_finite3(ladrc_real_t a, ladrc_real_t b, ladrc_real_t c)
{
    return ladrc_finite_bits_(a) & ladrc_finite_bits_(b) & ladrc_finite_bits_(c);
}

static inline int ladrc_all_finite4(ladrc_real_t a, ladrc_real_t b, ladrc_real_t c, ladrc_real_t d)
{
    return ladrc_finite_bits_(a) & ladrc_finite_bits_(b) & ladrc_finite_bits_(c) & ladrc_finite_bits_(d);
}
#else
/** Whether x is neither NaN nor infinite.
 *  @param x  any value
 *  @return 1 finite, 0 NaN or infinite */
static inline int ladrc_is_finite(ladrc_real_t x)
{
    return isfinite(x) ? 1 : 0;
}

/* In one comparison: x * 0 is 0 for a finite x and NaN for an infinity or
 * a NaN, so the sum is 0 exactly when all are finite. Cheaper than
 * ladrc_is_finite per value on the hot paths. */
/** Whether both arguments are finite.
 *  @param a, b  any values
 *  @return 1 all finite, 0 otherwise */
static inline int ladrc_all_finite2(ladrc_real_t a, ladrc_real_t b)
{
    return (a * LADRC_R(0.0) + b * LADRC_R(0.0) == LADRC_R(0.0)) ? 1 : 0;
}

/** Whether all three arguments are finite.
 *  @param a, b, c  any values
 *  @return 1 all finite, 0 otherwise */
static inline int ladrc_all_finite3(ladrc_real_t a, ladrc_real_t b, ladrc_real_t c)
{
    return (a * LADRC_R(0.0) + b * LADRC_R(0.0) + c * LADRC_R(0.0) == LADRC_R(0.0)) ? 1 : 0;
}

/** Whether all four arguments are finite.
 *  @param a, b, c, d  any values
 *  @return 1 all finite, 0 otherwise */
static inline int ladrc_all_finite4(ladrc_real_t a, ladrc_real_t b, ladrc_real_t c, ladrc_real_t d)
{
    return (a * LADRC_R(0.0) + b * LADRC_R(0.0) + c * LADRC_R(0.0) + d * LADRC_R(0.0) == LADRC_R(0.0)) ? 1 : 0;
}
#endif

/** x limited to [lo, hi] (lo <= hi).
 *  @param x   the value; NaN stays NaN
 *  @param lo  lower bound
 *  @param hi  upper bound
 *  @return lo, x or hi */
static inline ladrc_real_t ladrc_clamp(ladrc_real_t x, ladrc_real_t lo, ladrc_real_t hi)
{
    return (x < lo) ? lo : ((x > hi) ? hi : x);
}

/** The sign of x.
 *  @param x  the value
 *  @return 1, -1, or 0 for 0 and NaN */
static inline ladrc_real_t ladrc_sign(ladrc_real_t x)
{
    return (x > LADRC_R(0.0)) ? LADRC_R(1.0) : ((x < LADRC_R(0.0)) ? LADRC_R(-1.0) : LADRC_R(0.0));
}

/* The math functions on ladrc_real_t; a LADRC_CONFIG header may replace any of them. */
/** The square root on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_SQRT
#ifdef LADRC_REAL_DOUBLE
#define LADRC_SQRT(x) sqrt(x)
#else
#define LADRC_SQRT(x) sqrtf(x)
#endif
#endif
/** The absolute value on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_FABS
#ifdef LADRC_REAL_DOUBLE
#define LADRC_FABS(x) fabs(x)
#else
#define LADRC_FABS(x) fabsf(x)
#endif
#endif
/** The exponential on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_EXP
#ifdef LADRC_REAL_DOUBLE
#define LADRC_EXP(x) exp(x)
#else
#define LADRC_EXP(x) expf(x)
#endif
#endif
/** The exp(x) - 1 on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_EXPM1
#ifdef LADRC_REAL_DOUBLE
#define LADRC_EXPM1(x) expm1(x)
#else
#define LADRC_EXPM1(x) expm1f(x)
#endif
#endif
/** The cosine on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_COS
#ifdef LADRC_REAL_DOUBLE
#define LADRC_COS(x) cos(x)
#else
#define LADRC_COS(x) cosf(x)
#endif
#endif
/** The sine on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_SIN
#ifdef LADRC_REAL_DOUBLE
#define LADRC_SIN(x) sin(x)
#else
#define LADRC_SIN(x) sinf(x)
#endif
#endif
/** The arc sine on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_ASIN
#ifdef LADRC_REAL_DOUBLE
#define LADRC_ASIN(x) asin(x)
#else
#define LADRC_ASIN(x) asinf(x)
#endif
#endif
/** The cube root on ladrc_real_t; a LADRC_CONFIG header may replace it. */
#ifndef LADRC_CBRT
#ifdef LADRC_REAL_DOUBLE
#define LADRC_CBRT(x) cbrt(x)
#else
#define LADRC_CBRT(x) cbrtf(x)
#endif
#endif

/** LADRC_SQRT as a function: the square root.
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_sqrt(ladrc_real_t x)
{
    return LADRC_SQRT(x);
}
/** LADRC_FABS as a function: the absolute value.
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_fabs(ladrc_real_t x)
{
    return LADRC_FABS(x);
}
/** LADRC_EXP as a function: the exponential.
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_exp(ladrc_real_t x)
{
    return LADRC_EXP(x);
}
/** LADRC_EXPM1 as a function: the exp(x) - 1.
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_expm1(ladrc_real_t x)
{
    return LADRC_EXPM1(x);
}
/** LADRC_COS as a function: the cosine (x in rad).
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_cos(ladrc_real_t x)
{
    return LADRC_COS(x);
}
/** LADRC_SIN as a function: the sine (x in rad).
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_sin(ladrc_real_t x)
{
    return LADRC_SIN(x);
}
/** LADRC_ASIN as a function: the arc sine (result in rad).
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_asin(ladrc_real_t x)
{
    return LADRC_ASIN(x);
}
/** LADRC_CBRT as a function: the cube root.
 *  @param x  the argument
 *  @return the result, as the C library gives it for non-finite x */
static inline ladrc_real_t ladrc_cbrt(ladrc_real_t x)
{
    return LADRC_CBRT(x);
}

/** Whether x is finite and strictly positive: the check most config fields need.
 *  @param x  any value
 *  @return 1 finite and > 0, 0 otherwise (NaN included) */
static inline int ladrc_is_positive(ladrc_real_t x)
{
#if LADRC_FINITE_BY_BITS
    return (ladrc_finite_bits_(x) && x > LADRC_R(0.0)) ? 1 : 0;
#else
    /* Two comparisons, both false for NaN: small enough to be inlined. */
    return (x > LADRC_R(0.0) && x <= LADRC_REAL_MAX) ? 1 : 0;
#endif
}

/** 1 if x is finite and |x| <= limit (limit finite, > 0): a sample inside its
 *  plausible range. One comparison, false for NaN and for an infinity.
 *  @param x      any value
 *  @param limit  the bound, finite, > 0
 *  @return 1 within, 0 not (NaN and infinities included) */
static inline int ladrc_within(ladrc_real_t x, ladrc_real_t limit)
{
#if LADRC_FINITE_BY_BITS
    return (ladrc_finite_bits_(x) && ladrc_fabs(x) <= limit) ? 1 : 0;
#else
    return (ladrc_fabs(x) <= limit) ? 1 : 0;
#endif
}

/** @{ */
/** Shortest and longest control step every init accepts, s: 1 MHz to 1 Hz.
 *  Outside, the per-step constants the modules derive (h^3 / 6, 1 / h^2,
 *  powers of wo h) underflow or overflow in float. */
#define LADRC_DT_MIN_S LADRC_R(1e-6)
#define LADRC_DT_MAX_S LADRC_R(1.0)
/** @} */

/** 1 if dt_s is a control step every module can discretise (finite, in
 *  [LADRC_DT_MIN_S, LADRC_DT_MAX_S]).
 *  @param dt_s  the step (s)
 *  @return 1 valid, 0 not (NaN included) */
static inline int ladrc_dt_is_valid(ladrc_real_t dt_s)
{
    return (ladrc_is_finite(dt_s) && dt_s >= LADRC_DT_MIN_S && dt_s <= LADRC_DT_MAX_S) ? 1 : 0;
}

/** Largest actuator delay an axis models (ticks): 50 ms at an 8 kHz loop. */
#define LADRC_MAX_DELAY_TICKS 400u
/** Slots of an axis's delay line (axis.h), its fixed memory: a delay of up to
 *  this many ticks is held tick by tick (exact), a longer one as means of
 *  blocks of ticks. At least 8 (the exact delays of earlier releases), at
 *  most 255. */
#ifndef LADRC_DELAY_SLOTS
#define LADRC_DELAY_SLOTS 32u
#endif
#if LADRC_DELAY_SLOTS < 8 || LADRC_DELAY_SLOTS > 255
#error "LADRC_DELAY_SLOTS must be between 8 and 255"
#endif
/** Largest motor lag an axis models (s): a large airframe's slow rotor, twenty times an ESC's lag. */
#define LADRC_MOTOR_TAU_MAX_S LADRC_R(1.0)

/** @{ */
/** pi and 2 pi in the real type (rad). LADRC_TWO_PI is the one period every wrap
 *  and every shift by a turn uses, so that they agree to the last bit. */
#define LADRC_PI LADRC_R(3.14159265358979323846)
#define LADRC_TWO_PI LADRC_R(6.28318530717958647692)
/** @} */

/** x into (-pi, pi] by whole turns of LADRC_TWO_PI, for any x (the out-of-line
 *  branch of ladrc_wrap_pi, src/angle.c). Beyond 1e9 turns no fraction of
 *  a turn is left to resolve in either real type: 0. NaN and infinities
 *  give NaN.
 *  @param x  an angle (rad)
 *  @return the wrapped angle (rad) */
ladrc_real_t ladrc_wrap_pi_far(ladrc_real_t x);

/** Whether x lies in (-pi, pi].
 *  @param x  an angle (rad)
 *  @return 1 inside, 0 outside or NaN */
static inline int ladrc_in_half_turn(ladrc_real_t x)
{
    return (x > -LADRC_PI && x <= LADRC_PI) ? 1 : 0;
}

/** An angle difference into (-pi, pi]: x itself, bit for bit, when it is
 *  already there (two comparisons on the common path), else x minus whole
 *  turns of LADRC_TWO_PI. NaN stays NaN.
 *  @param x  an angle difference (rad)
 *  @return the wrapped difference (rad) */
static inline ladrc_real_t ladrc_wrap_pi(ladrc_real_t x)
{
    return ladrc_in_half_turn(x) ? x : ladrc_wrap_pi_far(x);
}

/** The angle x moved by whole turns to within pi of near (x - near wrapped,
 *  added to near): x itself, bit for bit, when it is already there.
 *  Non-finite x or near: NaN.
 *  @param x     an angle (rad)
 *  @param near  the angle to come near (rad)
 *  @return x moved by whole turns (rad) */
static inline ladrc_real_t ladrc_unwrap_near(ladrc_real_t x, ladrc_real_t near)
{
    const ladrc_real_t d = x - near;
    return ladrc_in_half_turn(d) ? x : near + ladrc_wrap_pi_far(d);
}

#ifdef __cplusplus
}
#endif

#endif /* LADRC_TYPES_H */
