/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file axis.h
 * @brief One attitude axis behind one config and one state: LADRC (reference
 *        shaping + LESO + control law), the PID baseline, the cascaded
 *        attitude P / rate PID of the common flight stacks (cascaded.h) or
 *        the INDI baseline (indi.h). The command of every variant is a
 *        torque in N m.
 *
 * Sign convention: positive torque accelerates the angle positively; angles
 * in rad (roll = phi about body X, pitch = theta about Y, yaw = psi about Z).
 *
 * LADRC tick k, measured angle y_k, raw reference ref_k (docs/method.md eq. 9-14):
 *
 *     LESO   z   <- step(y_k, applied torque of tick k-1, d_hat_k-1, h_k-1)  (leso.h)
 *     shaper (r, r', r'') <- TD(ref_k) | Levant(ref_k) | (ref_k, 0, 0)
 *     d_hat_k <- LP(rate_k) | HP(z3 - z3_shadow) | 0 (plain LADRC)        (estimator.h)
 *     law    u0 = wc^2 (r - z1) + 2 wc (r' - z2) + r''
 *            u_k = clamp((u0 - z3 - d_hat_k) / b0, u_min_Nm, u_max_Nm)
 *
 * with b0 in rad/s^2 per N m (1/J for an axis of inertia J: the paper's b0 = 1
 * on an acceleration command). The estimate d_hat enters the LESO as a known
 * acceleration, so z3 carries only what the estimator misses. h is the known
 * rate of change of the total disturbance (the coupling feed of attitude.h),
 * 0 unless set. The LESO is fed the torque actually applied: u_k itself
 * unless the caller reports another value with ladrc_axis_set_applied (e.g.
 * after the mixer saturated), so saturation never winds the observer up.
 *
 * Actuator model (motor_tau_s = tau, delay_ticks = d; LADRC family only).
 * Motors answer a torque request with a first-order lag and measurements
 * arrive d ticks late; the observer, the LP estimator and the acceleration
 * of the coupling feed (ladrc_axis_get_accel) take as known input the torque
 * ACTUALLY ACTING over the step they describe. With a_k the applied torque
 * the axis holds at tick k (what set_applied reported, else its command),
 * the observer step of tick k is fed
 *
 *     v_k    = a_k-1-d                    (delay line, below)
 *     ubar_k = m_k + g (v_k - m_k)        mean acting torque over the step
 *     m_k+1  = m_k + alpha (v_k - m_k)    acting torque at the step's end
 *     alpha  = 1 - exp(-h / tau),  g = 1 - alpha tau / h   (tau = 0: 1, 1)
 *
 * the exact solution of m' = (v - m) / tau for v held over the step (ZOH)
 * and its exact mean. The observer takes ubar_k, not m_k: its own ZOH
 * discretisation (leso.h) assumes the input constant over the step, and the
 * constant that gives the step's velocity change exactly is the mean (the
 * lag state at either end would over- or under-state it by up to
 * alpha (v - m)). A measurement d ticks old is thereby compared with a model
 * driven by the torque of d ticks before, so the observer compares like with
 * like: z estimates the state of d ticks ago and the law acts on it (no
 * prediction across the delay). ladrc_axis_get_accel gives b0 ubar of the
 * step the next tick's observer will take.
 *
 * The delay line has LADRC_DELAY_SLOTS (S) slots whatever d. Up to d = S it
 * is a ring of the last d torques: v_k is a_k-1-d exactly. Beyond (e.g.
 * 20-50 ms at 1-8 kHz, d up to LADRC_MAX_DELAY_TICKS) each slot holds the
 * mean of a block of m = ceil(2 d / (2 S - 1)) ticks, and v_k is the line
 * through the means of the two blocks whose centres bracket tick k-1-d
 * (the mean of a block stands for its centre). A torque ramp comes out
 * exactly d ticks late; a smooth torque within |a''| m^2 / 6 (a'' per
 * tick^2: the mean's error m^2 / 24 plus the interpolation's m^2 / 8), a
 * sine of amplitude A at w within A (w h m)^2 / 6 (at d = 400, m = 13:
 * 1.7e-3 A for 10 Hz at 8 kHz). The motor lag after it smooths further.
 * tau = 0 and d = 0 bypass the
 * model: the arithmetic is today's, bit for bit. The PID and CASCADED
 * variants have no observer and ignore the model. INDI pairs the same
 * acting torque with the acceleration measured over the same step (indi.h):
 * it reads the model too.
 *
 * Wrapped angles (wrap_angle = 1, e.g. yaw): the measured angle lives on a
 * circle of 2 pi. Each tick the measurement is moved by whole turns to
 * within pi of z1 (the innovation y - z1 is taken modulo 2 pi into
 * (-pi, pi]), so z1 stays continuous while y wraps; the raw reference is
 * moved by whole turns to within pi of the shaper's r (a reference crossing
 * +-pi is no 2 pi step for the TD or Levant), and the law's error r - z1 is
 * taken modulo 2 pi. When z1 and r are both beyond +pi (or -pi) they, and
 * the shaper's state, are shifted by one turn (exactly, their difference
 * unchanged), so a yaw turning for hours keeps full float resolution. Each
 * of these steps returns its input bit for bit while no wrap is needed.
 * PID wraps its error and its measured difference (pid.h); CASCADED
 * unwraps the raw reference for its shaper as LADRC does, wraps its error
 * and its angle difference (cascaded.h) and moves r (with the shaper's
 * state) back by a turn once it lies beyond +-pi; INDI moves the raw
 * reference to within pi of r, wraps r - theta and shifts r and the
 * shaper's state by a turn once r is beyond +-pi.
 *
 * RATE-ADRC tick (docs/method.md, "Rate-loop ADRC"): the disturbance
 * rejection sits on the rate loop, under an attitude P loop, as the flight
 * stacks place their rate PID. With the measured rate w_k and the acting
 * torque ubar_k of the actuator model (as the LADRC family),
 *
 *     ESO    (z1, z2) <- step(w_k, ubar_k)                 (reso.h, bandwidth wo_rad_s)
 *     shaper (r, r', r'') <- TD(ref_k) | Levant(ref_k) | (ref_k, 0, 0)
 *     w_ref  = clamp(k_att (r - angle_k) + r', +-radrc_rate_max_rad_s)
 *            (acro: clamp(ref_k, +-radrc_rate_max_rad_s), ref_k in rad/s)
 *     u_k    = clamp((k_w (w_ref - z1) + r'' - z2) / b0, u_min_Nm, u_max_Nm)
 *            (r'' the shaper's acceleration; 0 in acro and while w_ref is
 *            at its bound)
 *
 * so the rate loop is k_w / (s + k_w) once z2 cancels f. Without a measured
 * rate (NULL, or a bad one) it holds its command and raises
 * LADRC_FAULT_RATE, as INDI; the shaper and the actuator model move on. In
 * acro, a reference beyond rate_limit_rad_s is a bad input (held,
 * LADRC_FAULT_INPUT); a wrapped angle only matters outside acro.
 *
 * CASCADED tick (cascaded.h): the shaper gives (r, r') from the raw
 * reference as for LADRC (TD by default), then the attitude P loop and the
 * rate PID give the torque. Without a measured rate (NULL) the rate is a
 * filtered difference of the measured angle (cas_rate_filter_tau_s). As
 * PX4's rate controller: the integrator step shrinks with the rate error
 * (cas_i_relax_rad_s), a feed-forward gain acts on the rate setpoint
 * (cas_rate_ff), r' enters the setpoint only where cas_setpoint_ff is 1, and
 * the integrator holds while landed (ladrc_axis_set_landed) and while the
 * applied torque (ladrc_axis_set_applied) is limited in the direction it
 * would push, the form PX4's allocator saturation flags take here.
 *
 * Faults: a reference or angle that is not finite or lies beyond
 * angle_limit_rad leaves every state untouched, holds the previous command
 * and raises LADRC_FAULT_INPUT; the next good tick continues from the held
 * state. A rate that is not finite or beyond rate_limit_rad_s raises
 * LADRC_FAULT_RATE and the tick runs without it; an applied torque that is
 * not finite or beyond applied_limit_Nm raises LADRC_FAULT_APPLIED and the
 * axis's own command is used. Should a tick still make the command
 * non-finite (no input inside the ranges does), the command is held, the
 * observer and estimator restart from the measured angle and
 * LADRC_FAULT_STATE is raised: no fault outlives the tick that caused it.
 */
#ifndef LADRC_AXIS_H
#define LADRC_AXIS_H

#include "ladrc/cascaded.h"
#include "ladrc/estimator.h"
#include "ladrc/indi.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/pid.h"
#include "ladrc/reso.h"
#include "ladrc/td.h"
#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* LADRC_MAX_DELAY_TICKS and LADRC_MOTOR_TAU_MAX_S: types.h (the HP estimator advances over them too). */

/* LADRC_WITH_<NAME>, the variants and shapers built: types.h (the ABI guard reads them). */

/** The controller behind an axis. */
typedef enum {
    LADRC_VARIANT_LADRC = 0,     /**< traditional LADRC: TD + LESO + control law */
    LADRC_VARIANT_LP_MLADRC = 1, /**< LADRC + LP estimator (needs the measured rate) */
    LADRC_VARIANT_HP_MLADRC = 2, /**< LADRC + HP estimator (angle only) */
    LADRC_VARIANT_PID = 3,       /**< PID baseline (pid.h) */
    LADRC_VARIANT_CASCADED = 4,  /**< attitude P -> rate PID, as PX4 / ArduPilot / Betaflight (cascaded.h) */
    LADRC_VARIANT_INDI = 5,      /**< INDI baseline (indi.h; needs the measured rate) */
    LADRC_VARIANT_RATE_ADRC = 6, /**< attitude P -> rate loop ADRC on the gyro (reso.h; needs the measured rate) */
    LADRC_VARIANT_COUNT = 7      /**< number of variants (not a variant) */
} ladrc_variant_t;

/** 1 for the variants with an extended state observer (LADRC, LP-MLADRC,
 *  HP-MLADRC, numbered 0..2): the LESO, the coupling feed and the observer
 *  getters' LESO readings apply to them only (INDI reads the actuator model
 *  but has no LESO). One comparison (it sits on every
 *  tick's path), for a variant that init accepted.
 *  @param v  the variant
 *  @return 1 with an observer, 0 without */
static inline int ladrc_variant_has_observer(ladrc_variant_t v)
{
    return (v <= LADRC_VARIANT_HP_MLADRC) ? 1 : 0; /* v >= 0: a variant init accepted */
}

/** What HP-MLADRC's fit samples (hp_sample). */
typedef enum {
    LADRC_HP_SAMPLE_OBSERVER = 0, /**< the LESO's view of the unknown f, from the angle alone (the paper's) */
    LADRC_HP_SAMPLE_GYRO = 1      /**< the measured acceleration from the rate, less the known input: the fit
                                       takes the tones, an LP estimator what the fit leaves; the axis flies as
                                       LP-MLADRC until the fit locks on a steady tone (needs the rate on every
                                       tick; a tick without one holds both estimates) */
} ladrc_hp_sample_t;

/** How an axis shapes its raw reference into (r, r', r''). */
typedef enum {
    LADRC_SHAPER_TD = 0,    /**< Han's tracking differentiator gives r, r', r'' */
    LADRC_SHAPER_NONE = 1,  /**< raw reference, r' = r'' = 0 */
    LADRC_SHAPER_LEVANT = 2 /**< Levant's robust exact differentiator (levant.h) */
} ladrc_shaper_t;

/**
 * Axis configuration; can live in flash. Only the fields the variant uses
 * are read and validated: LADRC reads the common fields, wc_rad_s .. td_h0_s;
 * PID reads the common fields and pid_*; CASCADED the common fields, the
 * shaper's (shaper, td_* or levant_*) and cas_*; INDI the common fields, b0,
 * the shaper's fields, the actuator model and indi_*; RATE-ADRC the common
 * fields, wo_rad_s (its rate observer's bandwidth), b0, the shaper's fields
 * (not in acro), the actuator model and radrc_*.
 */
typedef struct {
    ladrc_variant_t variant; /**< the controller */
    ladrc_real_t dt_s;       /**< fixed control step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t u_min_Nm;   /**< torque command lower bound (N m), < 0, may be -INFINITY */
    ladrc_real_t u_max_Nm;   /**< torque command upper bound (N m), > 0; the command also
                                       stays within +-applied_limit_Nm */
    /* Plausible ranges (finite; angle and rate >= 1e-3, applied > 0): a sample
     * beyond is a bad input, held and flagged like a NaN. The defaults are far
     * beyond any real flight. */
    ladrc_real_t angle_limit_rad;  /**< |reference| and |measured angle| (rad), 1e-3..1e6; default 1000 */
    ladrc_real_t rate_limit_rad_s; /**< |measured rate| (rad/s); default 100 */
    ladrc_real_t applied_limit_Nm; /**< |applied torque| (N m); default 1e4 rad/s^2 times the inertia */
    /* LADRC */
    ladrc_real_t wc_rad_s;                /**< controller bandwidth (rad/s), > 0; closed loop (s + wc)^2 */
    ladrc_real_t wo_rad_s;                /**< observer bandwidth (rad/s), > 0 */
    ladrc_real_t b0;                      /**< rad/s^2 per N m (1/J), |b0| in [1e-3, 1e7] (J from 1e-7 to
                                       1000 kg m^2) */
    ladrc_leso_method_t leso_method;      /**< LESO discretisation */
    ladrc_shaper_t shaper;                /**< reference shaper */
    ladrc_real_t td_accel_rad_s2;         /**< TD acceleration bound (rad/s^2), > 0 (shaper TD only) */
    ladrc_real_t td_h0_s;                 /**< TD filter factor (s), >= dt_s (shaper TD only) */
    ladrc_levant_method_t levant_method;  /**< shaper LEVANT only */
    ladrc_real_t levant_lipschitz_rad_s4; /**< bound on |r''''| (rad/s^4), > 0 (shaper LEVANT only) */
    /* PID */
    ladrc_real_t pid_kp;             /**< N m / rad */
    ladrc_real_t pid_ki;             /**< N m / (rad s) */
    ladrc_real_t pid_kd;             /**< N m s / rad */
    ladrc_real_t pid_d_filter_tau_s; /**< derivative filter time constant (s), 0 = none */
    ladrc_real_t pid_i_limit_Nm;     /**< |integral| bound (N m), INFINITY = none */
    /* LP-MLADRC (estimator.h) */
    ladrc_real_t lp_lambda0_per_s; /**< maximum forgetting rate (1/s); paper 100 */
    ladrc_real_t lp_k0_per_s;      /**< gain bound (1/s); paper 300 */
    /* HP-MLADRC (estimator.h) */
    ladrc_hp_freq_mode_t hp_freq_mode;              /**< known or online frequencies */
    uint8_t hp_n_tones;                             /**< tones modelled, 1..LADRC_HP_MAX_TONES */
    ladrc_real_t hp_freq_rad_s[LADRC_HP_MAX_TONES]; /**< KNOWN: the disturbance frequencies;
                                        ONLINE: first guesses (rad/s) */
    ladrc_real_t hp_freq_min_rad_s;                 /**< ONLINE search range, lower end (rad/s) */
    ladrc_real_t hp_freq_max_rad_s;                 /**< ONLINE search range, upper end (rad/s) */
    ladrc_real_t hp_lambda0_per_s;                  /**< fastest forgetting of the fit (1/s) */
    ladrc_real_t hp_freq_lambda0_per_s;             /**< ONLINE forgetting of the frequency fits (1/s) */
    ladrc_real_t hp_freq_filter_rad_s;              /**< ONLINE derivative filter bandwidth (rad/s) */
    uint16_t hp_fit_decimation;                     /**< ticks per sample of the fit (an axis alone fits on the
                                        first tick of each block; the attitude layer staggers its
                                        axes over the block) */
    ladrc_hp_sample_t hp_sample;                    /**< what the fit samples; GYRO also reads lp_lambda0_per_s
                                        and lp_k0_per_s */
    /* Actuator model (LADRC family; see above), default 0 and 0: none */
    ladrc_real_t motor_tau_s; /**< first-order lag of the torque (s), 0..LADRC_MOTOR_TAU_MAX_S, 0 = none */
    uint16_t delay_ticks;     /**< transport delay (whole ticks), 0..LADRC_MAX_DELAY_TICKS */
    uint8_t wrap_angle;       /**< 1: the angle lives on a circle of 2 pi (yaw); 0: a line */
    /* INDI (indi.h); b0 is its control effectiveness, the shaper gives r, r', r'' */
    ladrc_real_t indi_att_kp_per_s;  /**< k_att (1/s): attitude error -> rate setpoint */
    ladrc_real_t indi_rate_kp_per_s; /**< k_rate (1/s): rate error -> acceleration */
    ladrc_real_t indi_filter_rad_s;  /**< w_f (rad/s): the acceleration and torque filter */
    /* CASCADED (cascaded.h) */
    ladrc_real_t cas_att_kp;            /**< attitude P gain (1/s), > 0, cas_att_kp * dt_s < 1 */
    ladrc_real_t cas_rate_max_rad_s;    /**< rate setpoint bound (rad/s), > 0, <= rate_limit_rad_s */
    ladrc_real_t cas_rate_kp;           /**< rate P gain (N m s/rad), >= 0 */
    ladrc_real_t cas_rate_ki;           /**< rate I gain (N m/rad), >= 0 */
    ladrc_real_t cas_rate_kd;           /**< rate D gain on the measured rate (N m s^2/rad), >= 0 */
    ladrc_real_t cas_d_filter_tau_s;    /**< D low-pass time constant (s), >= 0, 0 = none */
    ladrc_real_t cas_i_limit_Nm;        /**< |integral| bound (N m), INFINITY = none */
    ladrc_real_t cas_rate_filter_tau_s; /**< low pass of the angle's difference when no rate is
                                        given (s), >= 0 */
    /* RATE-ADRC (see above); wo_rad_s is its rate observer's bandwidth, b0 its gain */
    ladrc_real_t radrc_kp_per_s;       /**< k_w (1/s): rate error -> acceleration, the rate loop's
                                           crossover; > 0, times dt_s < 1 */
    ladrc_real_t radrc_att_kp_per_s;   /**< k_att (1/s): attitude error -> rate setpoint; > 0,
                                           times dt_s < 1 (not read in acro) */
    ladrc_real_t radrc_rate_max_rad_s; /**< |rate setpoint| bound (rad/s), > 0, <= rate_limit_rad_s */
    uint8_t radrc_acro;                /**< 1: the reference of ladrc_axis_step is a rate setpoint
                                           (rad/s, within rate_limit_rad_s), no attitude loop;
                                           0: an angle (rad) */
    /* CASCADED, the rest of PX4's rate loop (cascaded.h) */
    ladrc_real_t cas_i_relax_rad_s; /**< rate error at which the integrator step reaches 0
                                         (rad/s), > 0, INFINITY = no relax; default 400 deg/s */
    ladrc_real_t cas_rate_ff;       /**< rate-setpoint feed-forward gain (N m s/rad), >= 0
                                         (PX4's MC_ROLLRATE_FF); default 0 */
    uint8_t cas_setpoint_ff;        /**< 1: the shaped reference's rate r' is fed into the rate
                                         setpoint, 0: not; default 1 (the attitude default: yaw
                                         only, as PX4) */
    /* INDI, adaptive effectiveness (indi.h); the adapt_ fields are read only with indi_adapt = 1 */
    uint8_t indi_adapt;                      /**< 1: b0 adapted online by normalised LMS, 0: fixed;
                                                  default 0 */
    ladrc_real_t indi_adapt_mu;              /**< LMS step (dimensionless, per update), in (0, 1] */
    ladrc_real_t indi_adapt_jerk_min_rad_s3; /**< least |b0 du_f| / dt_s (rad/s^3) that updates, > 0 */
    ladrc_real_t indi_adapt_min_ratio;       /**< lower bound of the estimate / b0, in (0, 1] */
    ladrc_real_t indi_adapt_max_ratio;       /**< upper bound of the estimate / b0, >= 1, finite */
} ladrc_axis_config_t;

/** Actuator model state of an axis (see above). */
typedef struct {
    /** d <= LADRC_DELAY_SLOTS: the applied torques of the last d ticks; else
     *  the means of the last LADRC_DELAY_SLOTS blocks of block_ticks ticks */
    ladrc_real_t delayed_Nm[LADRC_DELAY_SLOTS];
    ladrc_real_t block_sum_Nm; /**< d > slots: sum of the torques of the block being filled */
    ladrc_real_t inv_block;    /**< 1 / block_ticks */
    ladrc_real_t inv_2block;   /**< 1 / (2 block_ticks) */
    ladrc_real_t lag_Nm;       /**< m: acting torque at the start of the next observer step */
    ladrc_real_t alpha;        /**< 1 - exp(-h / tau) */
    ladrc_real_t mean_gain;    /**< g = 1 - alpha tau / h */
    uint16_t delay_ticks;      /**< d */
    uint16_t block_ticks;      /**< ticks per slot: 1 for d <= slots, else ceil(2 d / (2 slots - 1)) */
    uint16_t fill;             /**< d > slots: ticks summed into the block being filled, 0..block_ticks - 1 */
    uint8_t head;              /**< slot of the oldest torque (a_k-1-d) or block */
} ladrc_actuator_t;

/** Axis state; owned by the caller, read through the getters. */
typedef struct {
    ladrc_variant_t variant; /**< of the config */
    ladrc_shaper_t shaper;   /**< of the config */
    /** @{ */
    ladrc_real_t u_min_Nm, u_max_Nm; /**< command bounds, within +-applied_limit_Nm (N m) */
    /** @} */
    /** @{ */
    ladrc_real_t angle_limit_rad, rate_limit_rad_s, applied_limit_Nm; /**< plausible ranges */
    /** @} */
    /** @{ */
    ladrc_real_t kp, kd, b0;      /**< wc^2, 2 wc, b0 */
    ladrc_real_t approach_rad_s2; /**< LADRC family, RATE-ADRC: 2 a, a half the torque bounds' acceleration (rad/s^2) */
    ladrc_real_t linear_rad;      /**< LADRC family, RATE-ADRC: |error| up to which the loop is linear (rad) */
    /** @} */
    ladrc_leso_t leso; /**< the LADRC family (not PID, not INDI) */
#if LADRC_WITH_TD || LADRC_WITH_LEVANT
    union {
#if LADRC_WITH_TD
        ladrc_td_t td; /**< shaper TD */
#endif
#if LADRC_WITH_LEVANT
        ladrc_levant_t levant; /**< shaper LEVANT */
#endif
    } shaping; /**< by shaper */
#endif
#if LADRC_WITH_PID || LADRC_WITH_CASCADED || LADRC_WITH_LP_MLADRC || LADRC_WITH_HP_MLADRC || LADRC_WITH_INDI ||        \
    LADRC_WITH_RATE_ADRC
    union {
#if LADRC_WITH_PID
        ladrc_pid_t pid; /**< PID */
#endif
#if LADRC_WITH_CASCADED
        ladrc_cascaded_t cas; /**< CASCADED */
#endif
#if LADRC_WITH_LP_MLADRC
        ladrc_lp_estimator_t lp; /**< LP-MLADRC */
#endif
#if LADRC_WITH_HP_MLADRC
        struct {
            ladrc_hp_estimator_t est; /**< the estimator */
            union {
                ladrc_leso_twin_t shadow; /**< OBSERVER: the LESO's view of a still plant, z3 caused by d_hat alone */
                ladrc_lp_estimator_t lp;  /**< GYRO: the LP estimator beside the fit, on what the fit leaves */
            } source;                     /**< by hp_sample */
            uint8_t gyro;                 /**< hp_sample is LADRC_HP_SAMPLE_GYRO */
        } hp;                             /**< HP-MLADRC */
#endif
#if LADRC_WITH_INDI
        ladrc_indi_t indi; /**< INDI */
#endif
#if LADRC_WITH_RATE_ADRC
        struct {
            ladrc_reso_t eso;            /**< the rate observer: z1 ~ rate, z2 ~ f */
            ladrc_real_t angle_rad;      /**< last measured angle */
            ladrc_real_t rate_sp_rad_s;  /**< rate setpoint of the latest tick */
            ladrc_real_t k_att;          /**< radrc_att_kp_per_s */
            ladrc_real_t rate_max_rad_s; /**< radrc_rate_max_rad_s */
            uint8_t acro;                /**< radrc_acro */
        } radrc;                         /**< RATE-ADRC */
#endif
    } part; /**< by variant */
#endif
    ladrc_ref_t ref;             /**< shaped reference of the latest tick */
    ladrc_real_t d_hat_rad_s2;   /**< estimator output applied over the current step */
    ladrc_real_t f_rate_rad_s3;  /**< known rate of change of f for the next LESO step */
    ladrc_real_t f_known_rad_s2; /**< known part of f (HP: kept out of the estimator's sample) */
    ladrc_real_t output_Nm;      /**< latest command */
    ladrc_real_t applied_Nm;     /**< torque applied since the latest tick */
    ladrc_actuator_t act;        /**< actuator model (used when model is 1) */
    uint8_t model;               /**< 1: motor_tau_s > 0 or delay_ticks > 0 (LADRC family, INDI) */
    uint8_t wrap;                /**< wrap_angle */
    ladrc_fault_t faults;        /**< flags of the latest tick */
    uint32_t consecutive_faults; /**< ticks in a row with LADRC_FAULT_INPUT or _STATE */
    uint8_t landed;              /**< ladrc_axis_set_landed: the ground takes the torque */
    ladrc_real_t gain_scale;     /**< ladrc_axis_set_gain_scale: the plant gain over b0 (1 after init) */
    ladrc_real_t command_Nm;     /**< landed or scaled: the latest command returned (N m), output_Nm / gain_scale */
    uint8_t adjusted;            /**< 1: landed or gain_scale != 1 (the tick's end takes their path) */
    uint8_t restart;             /**< the next good tick restarts first: 1 afresh, 2 engaging engage_Nm */
    ladrc_real_t engage_Nm;      /**< restart 2: the other controller's last command (N m) */
} ladrc_axis_t;

/**
 * Fills cfg with the paper's settings for a variant: wc = 15, wo = 75,
 * b0 = 1 / inertia_kg_m2, ZOH LESO, TD shaping (R = 20 rad/s^2, h0 = dt_s);
 * PID kp = 20, ki = 20, kd = 0.05, no derivative filter; no torque or
 * integral limits (ideal actuators, as in the paper: set real ones for flight).
 * CASCADED, by loop shaping on the paper's bandwidths: the rate loop
 * crosses over at wr = wo = 75 rad/s (cas_rate_kp = J wr: kp / (J s) has
 * unit gain at wr), the bandwidth over which LADRC's observer rejects
 * disturbances; cas_att_kp = wr / 4 = 18.75 /s (the usual separation of a
 * cascade: the P parts alone give s^2 + wr s + wr att_kp = (s + wr / 2)^2,
 * critically damped); cas_rate_ki = kp wr / 5 (integral corner a fifth
 * below the crossover, 11 deg of phase there); cas_rate_kd = kp / (4 wr)
 * (a quarter of the P torque in quadrature at wr: 14 deg of lead against
 * lags) through a low pass at 8 wr (cas_d_filter_tau_s = 1 / (8 wr), also
 * cas_rate_filter_tau_s); rate setpoint bound 220 deg/s (PX4's default
 * MC_ROLLRATE_MAX); no integral limit. TD shaping as LADRC.
 * LP and HP shape the reference with Levant (implicit, L = 1000 rad/s^4).
 * LP: lambda0 = 100 /s, k0 = 300 /s (paper). HP: up to two tones found
 * online in [0.3, 40] rad/s (first guesses 3 and 8 rad/s), the fit forgetting
 * at most 8 /s and sampling every 4 ms (at least every tick), the frequency
 * fits forgetting 2 /s behind a 20 rad/s derivative filter (a known
 * frequency: set hp_freq_mode). Plausible ranges: angles 1000 rad, rates
 * 100 rad/s, applied torque 1e4 rad/s^2 * inertia_kg_m2.
 * INDI, by the rule that it differs from LADRC only in how it learns the
 * disturbance: the same closed loop from the reference, (s + wc)^2, so
 * k_att = k_rate = wc = 15 /s, the same TD shaping, and the acceleration
 * filter at the observer's bandwidth, w_f = wo = 75 rad/s (the observer's
 * noise budget; F d then follows d with the lag 2 / w_f = 27 ms).
 * CASCADED's PX4 rate-loop fields follow PX4's defaults: integrator relax
 * at 400 deg/s (cas_i_relax_rad_s = 6.98 rad/s), no rate feed-forward gain
 * (cas_rate_ff = 0); cas_setpoint_ff = 1 (r' fed forward; this function
 * does not know the axis: ladrc_attitude_config_default turns it off on
 * roll and pitch, PX4 feeding forward the yaw rate only).
 * INDI's adaptation is off (indi_adapt = 0: b0 fixed, today's law); when
 * turned on: indi_adapt_mu = 0.005 (a time constant of 200 excited ticks,
 * 0.2 s at 1 kHz), indi_adapt_jerk_min_rad_s3 = 50, bounds [b0 / 4, 4 b0].
 * RATE-ADRC, by CASCADED's loop shaping: the rate loop crosses over at
 * wr = 75 rad/s (radrc_kp_per_s = wr), its observer's double pole four
 * times above (wo_rad_s = 4 wr = 300 rad/s), k_att = wr / 4 = 18.75 /s (the
 * cascade's separation), the rate setpoint bound 220 deg/s, TD shaping as
 * LADRC, not acro.
 * @param cfg            out: the config; NULL: nothing happens
 * @param variant        the variant, copied (every field is filled whatever it is)
 * @param dt_s           control step (s), copied unchecked (init checks it)
 * @param inertia_kg_m2  the axis's inertia J (kg m^2), copied unchecked into b0 = 1 / J
 */
void ladrc_axis_config_default(ladrc_axis_config_t *cfg, ladrc_variant_t variant, ladrc_real_t dt_s,
                               ladrc_real_t inertia_kg_m2);

/**
 * Validates the fields the variant reads (the status names the first bad
 * one: the common fields, then the variant's, then its actuator model,
 * shaper and estimator) and resets at angle 0. The modules' own statuses
 * pass through (leso.h, td.h, levant.h, pid.h, cascaded.h, indi.h,
 * estimator.h); the checks on an axis are sometimes tighter.
 * @param[out] axis  the axis to set up
 * @param[in]  cfg   its configuration
 * @retval LADRC_OK                      set up
 * @retval LADRC_ERR_NULL                axis or cfg is NULL
 * @retval LADRC_ERR_DT_S                dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S];
 *                                       HP: also its fit period above LADRC_DT_MAX_S
 * @retval LADRC_ERR_U_LIMITS            not u_min_Nm < 0 < u_max_Nm (NaN included)
 * @retval LADRC_ERR_INPUT_LIMITS        angle or rate limit not finite or below 1e-3, angle limit
 *                                       above 1e6 rad, applied_limit_Nm not finite or not > 0
 * @retval LADRC_ERR_WRAP_ANGLE          wrap_angle not 0 or 1
 * @retval LADRC_ERR_VARIANT             variant not a ladrc_variant_t
 * @retval LADRC_ERR_VARIANT_NOT_BUILT   variant left out of this build
 * @retval LADRC_ERR_WC_RAD_S            LADRC family: wc_rad_s not finite, not > 0, or wc dt >= 1
 * @retval LADRC_ERR_B0                  LADRC family, INDI: |b0| outside [1e-3, 1e7]
 * @retval LADRC_ERR_LESO_EULER_UNSTABLE LADRC family, Euler LESO: wo dt above 0.88 / (1 + 3.6 wc dt)
 * @retval LADRC_ERR_WO_RAD_S            LADRC family: wo_rad_s not finite or not > 0
 * @retval LADRC_ERR_LESO_METHOD         LADRC family: leso_method not a ladrc_leso_method_t
 * @retval LADRC_ERR_MOTOR_TAU_S         LADRC family, INDI: motor_tau_s not finite or outside
 *                                       0..LADRC_MOTOR_TAU_MAX_S
 * @retval LADRC_ERR_DELAY_TICKS         LADRC family, INDI: delay_ticks above LADRC_MAX_DELAY_TICKS
 * @retval LADRC_ERR_SHAPER              all but PID: shaper not a ladrc_shaper_t
 * @retval LADRC_ERR_SHAPER_NOT_BUILT    all but PID: shaper left out of this build
 * @retval LADRC_ERR_TD_ACCEL_RAD_S2     shaper TD: td_accel_rad_s2 not finite or not > 0
 * @retval LADRC_ERR_TD_H0_S             shaper TD: td_h0_s not finite or < dt_s
 * @retval LADRC_ERR_LEVANT_LIPSCHITZ    shaper LEVANT: levant_lipschitz_rad_s4 not finite, not > 0
 *                                       or above 10 / dt_s^2
 * @retval LADRC_ERR_LEVANT_METHOD       shaper LEVANT: levant_method not a ladrc_levant_method_t
 * @retval LADRC_ERR_LEVANT_RANGE        shaper LEVANT: per-sample coefficients out of range
 * @retval LADRC_ERR_HP_SAMPLE           HP: hp_sample not a ladrc_hp_sample_t
 * @retval LADRC_ERR_EST_LAMBDA0         LP, HP: forgetting rate not finite or not > 0 (HP: or times
 *                                       its fit period > 1)
 * @retval LADRC_ERR_EST_K0              LP, HP GYRO: lp_k0_per_s not finite or not > 0
 * @retval LADRC_ERR_RLS_LAMBDA0         LP, HP GYRO: lp_lambda0_per_s * dt_s > 1
 * @retval LADRC_ERR_HP_FREQ_MODE        HP: hp_freq_mode not a ladrc_hp_freq_mode_t
 * @retval LADRC_ERR_FEATURE_NOT_BUILT   HP: ONLINE left out of this build
 * @retval LADRC_ERR_HP_N_TONES          HP: hp_n_tones outside 1..LADRC_HP_MAX_TONES
 * @retval LADRC_ERR_HP_FREQ_RAD_S       HP: a modelled hp_freq_rad_s not finite, not > 0, or >= pi / dt_s
 * @retval LADRC_ERR_HP_FREQ_RANGE       HP ONLINE: the search range (ladrc_hp_init)
 * @retval LADRC_ERR_HP_FIT_DECIMATION   HP: hp_fit_decimation (ladrc_hp_init)
 * @retval LADRC_ERR_HP_SAMPLE_LAG       HP: wo_rad_s below a tenth of the fastest tone
 * @retval LADRC_ERR_HP_FREQ_LAMBDA0     HP ONLINE: hp_freq_lambda0_per_s (ladrc_hp_init)
 * @retval LADRC_ERR_HP_FREQ_FILTER      HP ONLINE: hp_freq_filter_rad_s (ladrc_hp_init)
 * @retval LADRC_ERR_PID_KP              PID: pid_kp not finite or < 0
 * @retval LADRC_ERR_PID_KI              PID: pid_ki not finite or < 0
 * @retval LADRC_ERR_PID_KD              PID: pid_kd not finite or < 0
 * @retval LADRC_ERR_PID_D_TAU_S         PID: pid_d_filter_tau_s not finite or < 0
 * @retval LADRC_ERR_PID_I_LIMIT_NM      PID: pid_i_limit_Nm NaN or < 0
 * @retval LADRC_ERR_CAS_ATT_KP          CASCADED: cas_att_kp (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_RATE_MAX        CASCADED: cas_rate_max_rad_s (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_RATE_KP         CASCADED: cas_rate_kp (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_RATE_KI         CASCADED: cas_rate_ki (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_RATE_KD         CASCADED: cas_rate_kd (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_D_TAU_S         CASCADED: cas_d_filter_tau_s not finite or < 0
 * @retval LADRC_ERR_CAS_RATE_TAU_S      CASCADED: cas_rate_filter_tau_s not finite or < 0
 * @retval LADRC_ERR_CAS_I_LIMIT_NM      CASCADED: cas_i_limit_Nm NaN or < 0
 * @retval LADRC_ERR_CAS_I_RELAX         CASCADED: cas_i_relax_rad_s NaN, not > 0 or with an
 *                                       infinite inverse (INFINITY accepted: no relax)
 * @retval LADRC_ERR_CAS_RATE_FF         CASCADED: cas_rate_ff (ladrc_cascaded_init)
 * @retval LADRC_ERR_CAS_SETPOINT_FF     CASCADED: cas_setpoint_ff not 0 or 1
 * @retval LADRC_ERR_INDI_ATT_KP         INDI: indi_att_kp_per_s (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_RATE_KP        INDI: indi_rate_kp_per_s (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_FILTER         INDI: indi_filter_rad_s (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_ADAPT          INDI: indi_adapt not 0 or 1
 * @retval LADRC_ERR_INDI_ADAPT_MU       INDI adapt: indi_adapt_mu (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_ADAPT_EXCITATION INDI adapt: indi_adapt_jerk_min_rad_s3 (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_ADAPT_MIN      INDI adapt: indi_adapt_min_ratio (ladrc_indi_init)
 * @retval LADRC_ERR_INDI_ADAPT_MAX      INDI adapt: indi_adapt_max_ratio (ladrc_indi_init)
 */
ladrc_status_t ladrc_axis_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);

/** Restarts at rest on angle_rad (reference shaper and observer start there).
 *  @param axis       the axis; NULL: nothing happens
 *  @param angle_rad  the angle to rest on (rad); non-finite or beyond
 *                    angle_limit_rad: 0 */
void ladrc_axis_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad);

/**
 * One tick. Non-finite or implausible inputs: see the file comment (state
 * held, LADRC_FAULT_INPUT / _RATE / _STATE raised).
 * @param axis        the axis
 * @param ref_rad     the raw reference (rad)
 * @param angle_rad   the measured angle (rad)
 * @param rate_rad_s  the measured rate (rad/s), or NULL without one: PID uses
 *                    it for its derivative, CASCADED for its rate loop,
 *                    LP-MLADRC for its disturbance sample (without a rate LP
 *                    holds its estimate) and INDI for its rate loop and
 *                    acceleration (without a rate INDI holds its command and
 *                    raises LADRC_FAULT_RATE), as RATE-ADRC for its observer;
 *                    LADRC and HP-MLADRC ignore it
 * @param torque_Nm   out: the torque command (N m)
 * @return the tick's fault flags (also ladrc_axis_get_faults); axis or
 *         torque_Nm NULL: LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_axis_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                              const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm);

/** Reports the torque actually applied since the last tick (N m), e.g. after
 *  mixer saturation. Not finite or beyond applied_limit_Nm: ignored,
 *  LADRC_FAULT_APPLIED raised.
 *  @param axis       the axis; NULL: nothing happens
 *  @param torque_Nm  the applied torque (N m) */
void ladrc_axis_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm);

/** Whether the vehicle is landed (0: flying, anything else: landed); held
 *  until set again, kept by ladrc_axis_reset, off after init. While landed
 *  the ground takes the torque: the torque the axis takes as acting (its
 *  applied torque, whatever set_applied reports) is 0, so that no observer,
 *  estimator or INDI filter learns the torque the ground resists as a
 *  disturbance; and the PID and CASCADED integrators hold their value (PX4
 *  does not integrate on the ground; cascaded.h). The law still acts.
 *  @param axis    the axis; NULL: nothing happens
 *  @param landed  0: flying, else landed */
void ladrc_axis_set_landed(ladrc_axis_t *axis, uint8_t landed);

/** Smallest gain scale ladrc_axis_set_gain_scale takes. */
#define LADRC_GAIN_SCALE_MIN LADRC_R(0.1)
/** Largest gain scale ladrc_axis_set_gain_scale takes. */
#define LADRC_GAIN_SCALE_MAX LADRC_R(10.0)

/**
 * The plant's gain now, as a factor of the b0 configured (the torque per
 * command grows with throttle on rotors whose thrust curve the mixer does not
 * undo, and with the battery's voltage; ladrc_attitude_set_operating_point
 * works it out). Every variant then computes its command as for b0 and
 * divides it by the scale, and takes the torque reported applied times the
 * scale: the loop is the one designed for b0 whatever the plant's gain
 * (its internal torques, ladrc_axis_get_acting_Nm's included, are in b0's
 * units). Held until set again; 1 after init, kept by reset.
 * @param axis   the axis; NULL: nothing happens
 * @param scale  the factor; not finite or outside [LADRC_GAIN_SCALE_MIN,
 *               LADRC_GAIN_SCALE_MAX]: ignored (the last good one kept)
 */
void ladrc_axis_set_gain_scale(ladrc_axis_t *axis, ladrc_real_t scale);

/**
 * Bumpless engage from another controller: restarts the axis (as
 * ladrc_axis_reset on angle_rad) as if torque_Nm had been acting for a
 * while and the axis were at rate_rad_s: the actuator model's delayed and
 * lagged torque at torque_Nm, the shaper at rest on the reference (so that
 * it asks for no acceleration), and what stands for the disturbance preset
 * so that the next tick continues the torque: the LESO's z2 at the rate and
 * z3 at the law's output less b0 torque_Nm, RATE-ADRC's observer at (rate,
 * -b0 torque_Nm), INDI's torque filter at it, the PID and CASCADED integrals
 * at it. What the error asks for on top is the new controller's own answer
 * (none while the other tracked the reference).
 * @param axis        the axis; NULL: nothing happens
 * @param ref_rad     the raw reference of the next tick (rad); non-finite or
 *                    beyond the limit: the angle
 * @param angle_rad   the measured angle (rad); non-finite or beyond the limit: 0
 * @param rate_rad_s  the measured rate (rad/s), or NULL (non-finite or beyond
 *                    the limit: none)
 * @param torque_Nm   the other controller's last command (N m), clamped to the
 *                    command bounds; non-finite or beyond applied_limit_Nm: 0
 */
void ladrc_axis_engage(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s,
                       ladrc_real_t torque_Nm);

/** Known rate of change of the total disturbance for the next tick (rad/s^3),
 *  the coupling feed; held until set again.
 *  @param axis         the axis; NULL: nothing happens
 *  @param rate_rad_s3  the rate (rad/s^3); non-finite: 0 used */
void ladrc_axis_set_disturbance_rate(ladrc_axis_t *axis, ladrc_real_t rate_rad_s3);

/**
 * Part of the total disturbance f that is known for the next tick (rad/s^2),
 * e.g. drag and coupling computed from the estimated rates (attitude.h does
 * this); held until set again; non-finite: 0 used. Only HP-MLADRC reads it:
 * its shadow observer is told -f_known (and the fed rate h), so that
 *     sample = z3 - z3_shadow = L(s) (f - f_known),  L = wo^3 / (s + wo)^3
 * and the fit sees only what is not already known. Other variants ignore it.
 * @param axis            the axis; NULL: nothing happens
 * @param f_known_rad_s2  the known part (rad/s^2); non-finite: 0 used
 */
void ladrc_axis_set_known_disturbance(ladrc_axis_t *axis, ladrc_real_t f_known_rad_s2);

/** Torque (N m) the next tick's observer step takes as acting: the applied
 *  torque without a model, else its delayed and lagged mean (see above).
 *  @param axis  the axis; NULL: 0
 *  @return the acting torque (N m) */
ladrc_real_t ladrc_axis_get_acting_Nm(const ladrc_axis_t *axis);

/** Angular acceleration the model expects over the observer's next step
 *  (rad/s^2): b0 * acting torque + z3 + d_hat. PID, CASCADED: 0. INDI: G *
 *  acting torque + its filtered disturbance. RATE-ADRC: b0 * acting torque + z2.
 *  @param axis  the axis; NULL: 0
 *  @return the expected acceleration (rad/s^2) */
ladrc_real_t ladrc_axis_get_accel(const ladrc_axis_t *axis);

/** Control effectiveness the axis's law divides by (rad/s^2 per N m): INDI
 *  its G (b0, or the online estimate with indi_adapt, indi.h); the LADRC
 *  family and RATE-ADRC b0; PID and CASCADED have none: 0.
 *  @param axis  the axis; NULL: 0
 *  @return the effectiveness (rad/s^2 per N m) */
ladrc_real_t ladrc_axis_get_effectiveness(const ladrc_axis_t *axis);

/** Fault flags of the latest tick (and of set_applied since).
 *  @param axis  the axis
 *  @return the flags; axis NULL: LADRC_FAULT_STATE */
ladrc_fault_t ladrc_axis_get_faults(const ladrc_axis_t *axis);

/** Ticks in a row that raised LADRC_FAULT_INPUT or LADRC_FAULT_STATE.
 *  @param axis  the axis; NULL: 0
 *  @return the count (ticks) */
uint32_t ladrc_axis_get_consecutive_faults(const ladrc_axis_t *axis);

/** Shaped reference of the latest tick (PID: raw reference, zero derivatives).
 *  @param axis  the axis
 *  @param ref   out: (r, r', r'') in rad, rad/s, rad/s^2; axis or ref NULL:
 *               nothing written */
void ladrc_axis_get_reference(const ladrc_axis_t *axis, ladrc_ref_t *ref);

/** Observer estimates: angle (rad), rate (rad/s), total disturbance z3 + d_hat
 *  (rad/s^2). PID has no observer: last measured angle, its filtered rate, and 0;
 *  CASCADED: last measured angle, the rate its rate loop used, and 0;
 *  INDI: last angle and rate measured with a rate, and omegadot_f - G u_f
 *  (G = b0 unless adapted, ladrc_axis_get_effectiveness);
 *  RATE-ADRC: last measured angle, its observer's z1 and z2.
 *  Any pointer NULL: nothing written.
 *  @param axis                the axis
 *  @param angle_rad           out: angle (rad)
 *  @param rate_rad_s          out: rate (rad/s)
 *  @param disturbance_rad_s2  out: total disturbance (rad/s^2) */
void ladrc_axis_get_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                             ladrc_real_t *disturbance_rad_s2);

/** The HP estimator of an HP-MLADRC axis, read-only (valid while axis is),
 *  for diagnostics through the estimator.h getters (weight, tones, fit);
 *  NULL for another variant.
 *  @param axis  the axis; NULL: NULL
 *  @return the estimator or NULL */
const ladrc_hp_estimator_t *ladrc_axis_get_hp(const ladrc_axis_t *axis);

/** The LP estimator of an LP-MLADRC axis or of an HP-MLADRC axis on the
 *  gyro (LADRC_HP_SAMPLE_GYRO), read-only (valid while axis is); NULL otherwise.
 *  @param axis  the axis; NULL: NULL
 *  @return the estimator or NULL */
const ladrc_lp_estimator_t *ladrc_axis_get_lp(const ladrc_axis_t *axis);

#if LADRC_WITH_HP_MLADRC
/** The HP estimator's config an HP-MLADRC axis builds from its own (what
 *  ladrc_axis_init uses; its sample comes through the axis's LESO, so the
 *  lag undone is wo_rad_s's), e.g. to run the estimator alone. Copies
 *  without checking (ladrc_hp_init checks).
 *  @param cfg  the axis config
 *  @param hp   out: the estimator config; cfg or hp NULL: nothing written */
void ladrc_axis_hp_config(const ladrc_axis_config_t *cfg, ladrc_hp_config_t *hp);
#endif

#ifdef __cplusplus
}
#endif

#endif /* LADRC_AXIS_H */
