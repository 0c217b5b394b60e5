/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file estimator.h
 * @brief Adaptive disturbance estimators of the modified LADRC (docs/method.md
 *        section 5), both on top of the bounded-gain RLS of rls.h. Their
 *        estimate d_hat (rad/s^2) enters the LESO as a known acceleration and
 *        the control law as u = (u0 - z3 - d_hat) / b0, so the LESO's z3 only
 *        carries what the estimator misses and nothing is compensated twice.
 *
 * LP ("low precision", W = 1): the disturbance sample is the measured angular
 * acceleration minus the known input, s_k = (rate_k - rate_k-1) / h - a_k-1,
 * independent of d_hat (no adaptation loop). A one-parameter RLS with the
 * paper's forgetting (lambda0 = 100 /s, k0 = 300 /s) makes d_hat a
 * first-order tracker of s with bandwidth lambda0 k0 / (lambda0 + k0) = 75 rad/s.
 *
 * Through the actuator (act_tau_s = tau, act_delay_ticks = d): the
 * compensation the command carries (ladrc_lp_step_lead) is d_hat through
 * the bounded lead
 *     (1 + tau' s) / (1 + tau' s / N),   tau' = tau + d h,   N = LADRC_LP_LEAD_MAX
 * which undoes the lag 1 / (1 + tau' s) (the first-order view of
 * exp(-s d h) / (1 + tau s)) up to a few rad/s and amplifies what is faster
 * (the sample's noise) by at most N. Discretised as
 *     x_k = x_k-1 + beta (d_hat_k - x_k-1),   command_k = d_hat_k + (N - 1) (d_hat_k - x_k-1)
 * with beta = 1 - exp(-N h / tau'): a unit DC gain (ladrc_lp_step_lead). d_hat
 * itself stays the observer's known input. tau = 0 and d = 0: command =
 * d_hat, bit for bit.
 *
 * HP ("high precision", angle only): the sample is the LESO's view of the
 * unknown part of f, s_k = z3_k - z3_shadow_k, where the shadow is a twin of
 * the axis's observer on a still plant, told d_hat minus the known part of f
 * and the same fed rate h (axis.h): the observer is linear, so the shadow's
 * z3 holds exactly what d_hat, h and the known part put into z3, and the fit
 * never chases its own output (no adaptation loop through the observer) nor
 * the drag and coupling that move with the reference. The sample lags the
 * unknown f by the observer's wo^3 / (s + wo)^3, which the estimate undoes
 * per tone.
 *
 * HP on the gyro (the axis's hp_sample = LADRC_HP_SAMPLE_GYRO, axis.h): the
 * sample is LP's, s_k above, minus the known part of f; the axis runs an LP
 * estimator on s_k minus the fit's estimate, so that LP tracks what the fit
 * leaves, and d_hat is their sum. The sample is noisy (a gyro's noise,
 * differenced), so the fit takes the mean of each block of fit_decimation
 * samples (sample_block_mean; the differences telescope, dividing white
 * noise by the block's length), n h / 2 old (sample_age_s) and with the
 * block mean's gain at each tone, both undone per tone; its gate settles
 * when the fit removes at least half the power its tones claim, since the
 * noise keeps its prior error above the 1 % share a clean sample reaches.
 *
 * Through the actuator (act_tau_s = tau, act_delay_ticks = d): what the
 * command asks for acts through A(jw) = exp(-jw d h) / (1 + jw tau) (a
 * first-order lag and d ticks of delay, the axis's actuator model; the
 * delay may sit in the measurement instead: the sample, and so the
 * estimate, is then d ticks old, which needs the same advance). The
 * estimate itself (d_hat, the observer's known input) stays the disturbance;
 * the COMMAND's compensation (ladrc_hp_get_command) turns and scales each
 * tone's phasor by 1 / A(jw) at the tone's frequency, so that what acts
 * cancels the tone in phase:
 *     command = weight (c + sum_k Re[(a_k - j b_k) lead_k (1 + jw_k tau) e^{jw_k d h} e^{j psi_k}])
 * The bias passes unchanged (A(0) = 1). The constant per tone is computed
 * when its frequency changes; w tau is bounded by HP_LEAD_RATIO_MAX (10:
 * 84 deg of lead, a tenfold gain). tau = 0 and d = 0: command = estimate,
 * bit for bit, nothing computed.
 *
 * Model, n active tones (1..n_tones, n_tones <= LADRC_HP_MAX_TONES):
 *     d(t) = c + sum_k (a_k cos(psi_k) + b_k sin(psi_k)),   psi_k' = w_k
 * (c, a_1, b_1, ..., a_n, b_n) from one RLS (rls.h) on every
 * fit_decimation-th sample (period T); each psi_k is kept as a unit phasor
 * rotated by w_k h every tick (bounded, no time variable). The fit forgets at
 *     lambda = min(lambda0, w_k / FIT_MEMORY_RAD, |w_j - w_k| / SEPARATION_MEMORY_RAD)
 * over the significant tones: at least a fraction of a radian of the slowest
 * tone's phase (to tell the bias and that tone apart) and a radian of the
 * relative phase of two tones (to tell them apart), and otherwise as short
 * as lambda0 allows, so a change is followed within about 1 / lambda0.
 *
 * Gate: the frequency itself is checked. At the right frequency the fitted
 * phasor P_k = a_k - j b_k stands still; at w_k + dw it turns at dw. Its
 * averaged turn rate (slip), plus the averaged relative rate at which its
 * size changes (a decaying transient does not stand still either), must stay
 * below a tenth of lambda (a phase error under 0.1 rad) for the tone to be
 * locked. The compensation weight moves at a bounded rate towards 1 while
 * every significant tone (a real share of the sample's power) is locked and
 * no change is under way, else towards 0 (plain LADRC): d_hat = weight * model.
 * A clean sample (the observer's) locks once the fit predicts it and, ONLINE,
 * the frequency fit sees a clean model of the active tones.
 * A noisy sample (the gyro's block mean) is judged on the tone's band:
 * - the phasor's mean M over a window of at least one period of the tone
 *   and three fit memories, its mean power Q and its noise power s2 (from
 *   the changes of its increments, which a smooth motion of P does not
 *   have: under noise alone P wanders as a first-order process of rate
 *   lambda, whose increments are uncorrelated);
 * - evidence: |M|^2 at least 256 times the power s2 beta / (beta + lambda)
 *   white noise alone gives the mean over a window of rate beta. White
 *   noise alone would pass 16 times it with probability e^-16 per window;
 *   turbulence, whose phasor wanders more slowly than its increments tell,
 *   passed 16 times it for 78-188 s and 64 times it for 18 s per hour of
 *   simulated flight, 256 times it never (docs/hp-gate.md); coherence:
 *   |M|^2 at least half of Q - s2 (a tone off its frequency by dw keeps
 *   1 / (1 + (dw W)^2) of it);
 * - the slip bar widened by three times the slip the noise gives;
 * - no clean model of other tones from the frequency fit (under noise it sees
 *   none and the band decides).
 *   Locked, a tone stays so while the evidence keeps a quarter of its bar,
 *   the coherence 0.25 and the slip three times its bar. Vibration far from
 *   the tone does not enter its band: the fit's phasor only carries what lies
 *   within about lambda of the tone. The smallest tone it engages on is
 *   A = 16 sqrt(G beta) for a sample noise of one-sided density G
 *   ((rad/s^2)^2/Hz) at the tone and beta = 1 / W (ladrc_hp_get_evidence and
 *   ladrc_hp_get_coherence report both per tone).
 *
 * Changes: a short average of the fit's prior error power far above its long
 * average (a frequency jump, an onset, a stop, a bias step) restarts the fit
 * on fresh data instead of waiting for its memory to fade and discards the
 * compensation at once (the model no longer describes the disturbance, so
 * it is not handed over to the observer: after a stop, the observer has
 * nothing to unlearn), holding it back for a moment.
 *
 * ONLINE frequencies: for each tone, a bias-free least squares on
 * state-variable-filtered derivatives of the part of the sample the other
 * tones do not explain,
 *     w_k^2 = avg(x3 x1) / avg(x1 x1) with the sign flipped,
 * x1 and x3 the first and third derivative of that signal through
 * (wf / (s + wf))^4, the averages forgetting at freq_lambda0. It is exact for
 * one tone whatever its amplitude, phase and bias (a bias step only kicks
 * it briefly). Tones start one at a time: the first is active from the
 * start; another starts, at the frequency its filter sees in what the active
 * tones leave unexplained, when that residue keeps a real share of the
 * sample's power; a tone that stays insignificant, or that runs onto another
 * tone's frequency, stops (the fit is restarted with its current values for
 * the remaining tones). The search is built with LADRC_WITH_HP_ONLINE (types.h,
 * CMake LADRC_HP_ONLINE); without it only KNOWN frequencies are accepted.
 */
#ifndef LADRC_ESTIMATOR_H
#define LADRC_ESTIMATOR_H

#include "ladrc/rls.h"
#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** LP estimator configuration (ladrc_lp_init validates it). */
typedef struct {
    ladrc_real_t dt_s;          /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t lambda0_per_s; /**< maximum forgetting rate (1/s), > 0, lambda0 h <= 1; paper 100 */
    ladrc_real_t k0_per_s;      /**< bound on the continuous-time gain P (1/s), > 0; paper 300 */
    ladrc_real_t act_tau_s;     /**< the command acts through this first-order lag (s),
                                     0..LADRC_MOTOR_TAU_MAX_S, 0 = none */
    uint16_t act_delay_ticks;   /**< and this delay (ticks), 0..LADRC_MAX_DELAY_TICKS */
} ladrc_lp_config_t;

/** Largest gain of the LP command's lead (its high-frequency gain N): see
 *  above; the measured trade-off is in docs (README, LP-MLADRC under lag). */
#ifndef LADRC_LP_LEAD_MAX
#define LADRC_LP_LEAD_MAX LADRC_R(4.0)
#endif

/** LP estimator state; owned by the caller, read through the getters. */
typedef struct {
    ladrc_rls1_t rls;             /**< one parameter, regressor 1: d_hat */
    ladrc_real_t dt_s;            /**< fixed step h (s) */
    ladrc_real_t prev_rate_rad_s; /**< the previous finite rate (rad/s) */
    ladrc_real_t lead_x;          /**< the lead's low-pass state x (rad/s^2) */
    ladrc_real_t lead_beta;       /**< beta = 1 - exp(-N h / tau') */
    ladrc_real_t sample_rad_s2;   /**< the latest sample (rad/s^2) */
    uint8_t has_sample;           /**< 1: the latest step took a sample */
    uint8_t lead;                 /**< 1: act_tau_s > 0 or act_delay_ticks > 0 */
    uint8_t has_prev_rate;        /**< 0 until a finite rate was seen */
    ladrc_fault_t faults;         /**< flags of the latest step */
} ladrc_lp_estimator_t;

/**
 * Validates cfg in the order below and resets (ladrc_lp_reset).
 * @param[out] est  the estimator to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK              set up
 * @retval LADRC_ERR_NULL        est or cfg is NULL
 * @retval LADRC_ERR_DT_S        dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_EST_LAMBDA0 lambda0_per_s not finite or not > 0
 * @retval LADRC_ERR_EST_K0      k0_per_s not finite or not > 0
 * @retval LADRC_ERR_RLS_LAMBDA0 lambda0_per_s * dt_s > 1 (the RLS's check)
 * @retval LADRC_ERR_MOTOR_TAU_S act_tau_s not finite or outside 0..LADRC_MOTOR_TAU_MAX_S
 * @retval LADRC_ERR_DELAY_TICKS act_delay_ticks above LADRC_MAX_DELAY_TICKS
 */
ladrc_status_t ladrc_lp_init(ladrc_lp_estimator_t *est, const ladrc_lp_config_t *cfg);

/** Forgets the estimate (d_hat = 0), the rate history and the lead.
 *  @param est  the estimator; NULL: nothing happens */
void ladrc_lp_reset(ladrc_lp_estimator_t *est);

/**
 * One tick.
 * A non-finite argument holds the estimate and raises LADRC_FAULT_INPUT; the
 * next finite rate restarts the difference.
 * @param est            the estimator
 * @param rate_rad_s     measured angular rate now (rad/s)
 * @param accel_known    acceleration the known input gave over the last step,
 *                       b0 * applied torque (rad/s^2)
 * @return the step's fault flags (also est->faults); est NULL:
 *         LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_lp_step(ladrc_lp_estimator_t *est, ladrc_real_t rate_rad_s, ladrc_real_t accel_known);

/** Current estimate d_hat.
 *  @param est  the estimator; NULL: 0
 *  @return d_hat (rad/s^2) */
ladrc_real_t ladrc_lp_get_estimate(const ladrc_lp_estimator_t *est);

/** The latest step's sample: the measured acceleration minus the known
 *  input (rad/s^2), what the estimate tracks (HP-MLADRC on the gyro fits
 *  its tones to it, axis.h).
 *  @param est  the estimator; NULL: NAN
 *  @return the sample (rad/s^2); NAN when the latest step took no sample
 *          (the first rate, a gap, a non-finite input) */
ladrc_real_t ladrc_lp_get_sample(const ladrc_lp_estimator_t *est);

/** Moves the estimate and its lead's state by delta (rad/s^2): what another
 *  estimator takes over from this one at once (HP-MLADRC on the gyro, as its
 *  gate opens), without a step through the lead.
 *  @param est    the estimator; NULL: nothing happens
 *  @param delta  the move (rad/s^2); non-finite: nothing happens */
void ladrc_lp_hand_over(ladrc_lp_estimator_t *est, ladrc_real_t delta);

/** One tick of the command's lead over the actuator (see above) on the
 *  current d_hat; call once per tick after ladrc_lp_step. command_rad_s2
 *  receives the compensation the command should carry (rad/s^2): d_hat
 *  itself without an actuator (then nothing is computed).
 *  @param est             the estimator
 *  @param command_rad_s2  out: the compensation (rad/s^2)
 *  @return 0 (no input to fault on); est or command_rad_s2 NULL:
 *          LADRC_FAULT_STATE, nothing changes */
ladrc_fault_t ladrc_lp_step_lead(ladrc_lp_estimator_t *est, ladrc_real_t *command_rad_s2);

/** Where the HP estimator's frequencies come from. */
typedef enum {
    LADRC_HP_FREQ_KNOWN = 0, /**< the disturbance frequencies are given (paper) */
    LADRC_HP_FREQ_ONLINE = 1 /**< estimated online within [freq_min, freq_max] */
} ladrc_hp_freq_mode_t;

/** HP estimator configuration (ladrc_hp_init validates it). */
typedef struct {
    ladrc_real_t dt_s;                           /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_hp_freq_mode_t freq_mode;              /**< known or online frequencies */
    uint8_t n_tones;                             /**< tones modelled at most, 1..LADRC_HP_MAX_TONES */
    ladrc_real_t freq_rad_s[LADRC_HP_MAX_TONES]; /**< KNOWN: the frequencies; ONLINE: the first
                                          guesses (rad/s), > 0; the first n_tones are read */
    ladrc_real_t freq_min_rad_s;                 /**< ONLINE search range, lower end (rad/s), > 0 */
    ladrc_real_t freq_max_rad_s;                 /**< ONLINE search range, upper end (rad/s), > min, max h < pi */
    ladrc_real_t lambda0_per_s;                  /**< fastest forgetting of the fit (1/s), > 0, lambda0 T <= 1 */
    ladrc_real_t freq_lambda0_per_s;             /**< ONLINE: forgetting of the frequency averages (1/s) */
    ladrc_real_t freq_filter_rad_s;              /**< ONLINE: bandwidth wf of the derivative filter (rad/s) */
    ladrc_real_t sample_lag_wo_rad_s;            /**< samples come through a LESO of this bandwidth, whose z3
                                          lags f by wo^3 / (s + wo)^3: undone per tone; 0 = no lag;
                                          otherwise at least a tenth of the fastest tone */
    ladrc_real_t sample_age_s;                   /**< samples are this much older than their tick (s), >= 0:
                                          undone per tone; the fastest tone turns at most pi/2 in it */
    uint8_t sample_block_mean;                   /**< 1: the fit takes the mean of the samples of each block
                                          of fit_decimation ticks (noise averaged; its gain at each
                                          tone undone), 0: the fit tick's sample alone */
    uint16_t fit_decimation;                     /**< ticks per fit sample (T = fit_decimation dt_s), >= 1;
                                          every tone turns less than pi/2 per fit sample */
    uint16_t fit_phase;                          /**< which tick of each block fits, < fit_decimation
                                          (give the axes of one controller different phases so a
                                          tick carries at most one fit) */
    ladrc_real_t act_tau_s;                      /**< the command acts through this first-order lag (s),
                                          0..LADRC_MOTOR_TAU_MAX_S (axis.h), 0 = none */
    uint16_t act_delay_ticks;                    /**< and this delay (ticks), 0..LADRC_MAX_DELAY_TICKS */
} ladrc_hp_config_t;

/** One tone. */
typedef struct {
    ladrc_real_t w_rad_s; /**< frequency in use (rad/s) */
    /** @{ */
    ladrc_real_t cos_psi, sin_psi; /**< phase as a unit phasor */
    /** @} */
    /** @{ */
    ladrc_real_t cos_step, sin_step; /**< rotation by w h */
    /** @} */
    /** @{ */
    ladrc_real_t lead_re, lead_im; /**< (1 + j w / wo)^3: undoes the sample's lag at w */
    /** @} */
    /** @{ */
    ladrc_real_t cmd_re, cmd_im; /**< lead (1 + j w tau) e^{j w (d - 1) h}: also undoes the
                                          actuator's (read one turn w h late) */
    /** @} */
    /** @{ */
    ladrc_real_t prev_a, prev_b; /**< fitted (a, b) at the previous fit sample */
    /** @} */
    ladrc_real_t slip_rad_s;  /**< averaged turn rate of the fitted phasor */
    ladrc_real_t drift_per_s; /**< averaged relative rate of change of its size */
    /** @{ */
    ladrc_real_t mean_a, mean_b; /**< the fitted phasor's mean over the gate's window */
    /** @} */
    /** @{ */
    ladrc_real_t prev_da, prev_db; /**< the fitted phasor's previous increment */
    /** @} */
    ladrc_real_t mean_power;  /**< the mean of its squared size over the window */
    ladrc_real_t noise_power; /**< its noise power, from its increments */
    ladrc_real_t evidence;    /**< |mean|^2 over the mean's noise power, over GATE_EVIDENCE_ON */
    ladrc_real_t coherence;   /**< |mean|^2 over the mean squared size less the noise */
    uint16_t gate_samples;    /**< fit samples in the gate's means since the tone (re)started */
    uint8_t significant;      /**< carries a real share of the sample's power */
    uint8_t locked;           /**< significant and its band evidence and coherence pass */
} ladrc_hp_tone_t;

/** What a tone's constants follow from besides its frequency (from the
 *  config): needed again only when a frequency changes (ONLINE). */
typedef struct {
    ladrc_real_t dt_s;         /**< fixed step h (s) */
    ladrc_real_t lag_wo_rad_s; /**< bandwidth of the sample's lag, 0 = none */
    ladrc_real_t age_s;        /**< the sample's age (s) */
    ladrc_real_t act_tau_s;    /**< actuator lag the command is advanced over (s) */
    uint16_t block_ticks;      /**< ticks each fit sample averages, 1 = none */
    uint16_t act_delay_ticks;  /**< actuator delay the command is advanced over (ticks) */
} ladrc_hp_tone_basis_t;

/** HP estimator state; owned by the caller, read through the getters. */
typedef struct {
    ladrc_rls_t fit;                          /**< theta = (c, a_1, b_1, ..., a_n, b_n), n = n_active */
    ladrc_real_t phi[LADRC_RLS_MAX_PARAMS];   /**< the fit's regressors at the latest fit sample */
    ladrc_hp_tone_t tone[LADRC_HP_MAX_TONES]; /**< the first n_active are in the fit */
    ladrc_real_t fit_period_s;                /**< T = fit_decimation h (s) */
    ladrc_real_t lambda0_max;                 /**< configured fastest forgetting of the fit */
    ladrc_real_t fit_rate_per_s;              /**< forgetting rate of the fit outside changes */
    ladrc_real_t sample_mean;                 /**< the sample's mean, averaged */
    ladrc_real_t sig_power;                   /**< the sample's power around its mean, averaged */
    /** @{ */
    ladrc_real_t err_fast, err_slow; /**< short and long averages of the fit's prior error power */
    /** @} */
    ladrc_real_t weight;    /**< compensation weight in [0, 1] */
    ladrc_real_t estimate;  /**< the applied d_hat (rad/s^2) */
    ladrc_real_t command;   /**< advance: the compensation the command carries (rad/s^2) */
    ladrc_real_t handover;  /**< part of estimate's latest change due to the weight */
    ladrc_real_t block_sum; /**< sample_block_mean: the block's samples so far, summed (rad/s^2) */
    uint16_t block_n;       /**< sample_block_mean: how many */
    uint8_t block_mean;     /**< sample_block_mean */
#if LADRC_WITH_HP_ONLINE
    /* The ONLINE frequency search (estimator_hp_freq.c): left out with
     * LADRC_WITH_HP_ONLINE 0 (types.h). */
    ladrc_hp_tone_basis_t basis; /**< what the tones' constants follow from */
    /** @{ */
    ladrc_real_t freq_min_rad_s, freq_max_rad_s; /**< the search range (rad/s) */
    /** @} */
    ladrc_real_t freq_lambda0_per_s;              /**< forgetting of the frequency averages (1/s) */
    ladrc_real_t filter_rad_s;                    /**< derivative filter bandwidth wf */
    ladrc_real_t spec_x[6];                       /**< derivative filter: x and its first five derivatives */
    ladrc_real_t spec_x1_prev[2];                 /**< x1 one and two fit samples ago */
    ladrc_real_t spec_x3_prev;                    /**< x3 one fit sample ago */
    ladrc_real_t spec_avg[6];                     /**< averages of x1 x1, x3 x1, x3 x3, x5 x1, x5 x3, x5 x5 */
    ladrc_real_t found_rad_s[LADRC_HP_MAX_TONES]; /**< frequencies of the latest clean model */
    uint16_t spec_restart_left;                   /**< fit samples until the frequency fit's averages restart */
    uint16_t spec_count;                          /**< fit samples in the frequency fit's averages since their start */
    uint16_t hold;                                /**< fit samples since the last tone started or stopped */
    uint8_t spec_decide;                          /**< fit samples since the frequency fit's model was last judged */
    uint8_t online;                               /**< 1: freq_mode ONLINE */
    uint8_t clean;                                /**< the frequency fit sees as many clean tones as are active */
    uint8_t contradicts; /**< the frequency fit sees a clean model with other tones than the active */
#endif
    /** @{ */
    uint16_t fit_decimation, fit_count, fit_phase; /**< ticks per fit sample, tick in the block, tick that fits */
    /** @} */
    uint16_t change_left; /**< fit samples left of a change's hold */
    uint16_t engaged;     /**< fit samples in a row with the weight at 1 */
    /** @{ */
    uint8_t n_tones, n_active; /**< tones configured, tones in the fit */
    /** @} */
    uint8_t advance;      /**< 1: act_tau_s > 0 or act_delay_ticks > 0 (the command is advanced) */
    ladrc_fault_t faults; /**< flags of the latest step */
} ladrc_hp_estimator_t;

/**
 * Validates cfg in the order below (the ONLINE fields only for ONLINE) and
 * resets (ladrc_hp_reset). T = fit_decimation dt_s is the fit period.
 * @param[out] est  the estimator to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                    set up
 * @retval LADRC_ERR_NULL              est or cfg is NULL
 * @retval LADRC_ERR_DT_S              dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S];
 *                                     or (after the others) T above LADRC_DT_MAX_S
 * @retval LADRC_ERR_HP_FREQ_MODE      freq_mode not a ladrc_hp_freq_mode_t
 * @retval LADRC_ERR_FEATURE_NOT_BUILT ONLINE with LADRC_WITH_HP_ONLINE 0
 * @retval LADRC_ERR_HP_N_TONES        n_tones outside 1..LADRC_HP_MAX_TONES
 * @retval LADRC_ERR_HP_FREQ_RAD_S     one of the first n_tones freq_rad_s not finite, not > 0, or >= pi / dt_s
 * @retval LADRC_ERR_HP_FREQ_RANGE     ONLINE: not 0 < freq_min_rad_s < freq_max_rad_s < pi / dt_s
 * @retval LADRC_ERR_EST_LAMBDA0       lambda0_per_s not finite, not > 0, or lambda0_per_s T > 1
 * @retval LADRC_ERR_HP_FIT_DECIMATION fit_decimation 0, fit_phase >= fit_decimation, or a tone
 *                                     turns pi/2 or more per T
 * @retval LADRC_ERR_MOTOR_TAU_S       act_tau_s not finite or outside 0..LADRC_MOTOR_TAU_MAX_S
 * @retval LADRC_ERR_DELAY_TICKS       act_delay_ticks above LADRC_MAX_DELAY_TICKS
 * @retval LADRC_ERR_HP_SAMPLE_LAG     sample_lag_wo_rad_s not finite, < 0, or below a tenth of the fastest tone;
 *                                     sample_age_s not finite, < 0, or the fastest tone turns more than pi/2
 *                                     in it; sample_block_mean not 0 or 1
 * @retval LADRC_ERR_HP_FREQ_LAMBDA0   ONLINE: freq_lambda0_per_s not finite, not > 0, or times T > 1
 * @retval LADRC_ERR_HP_FREQ_FILTER    ONLINE: freq_filter_rad_s not finite, not > 0, or times T >= 0.2
 */
ladrc_status_t ladrc_hp_init(ladrc_hp_estimator_t *est, const ladrc_hp_config_t *cfg);

/** Forgets the model and the frequency averages; phases restart at 0, the
 *  frequencies stay where they are, ONLINE mode goes back to one active tone.
 *  @param est  the estimator; NULL: nothing happens */
void ladrc_hp_reset(ladrc_hp_estimator_t *est);

/**
 * One tick on the disturbance sample (rad/s^2): the unknown part of f as the
 * axis's observer sees it, or the gyro's (see above).
 * Not finite or beyond 1e6 rad/s^2 (no multirotor comes near): held,
 * LADRC_FAULT_INPUT (the phases still advance, so the model stays in step
 * with time). Should the estimate still turn non-finite, the estimator resets
 * (as ladrc_hp_reset) and raises LADRC_FAULT_STATE.
 * @param est            the estimator
 * @param sample_rad_s2  the disturbance sample (rad/s^2)
 * @return the step's fault flags (also est->faults); est NULL:
 *         LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_hp_step(ladrc_hp_estimator_t *est, ladrc_real_t sample_rad_s2);

/** Applied estimate d_hat: weight times the bias and the active tones.
 *  @param est  the estimator; NULL: 0
 *  @return d_hat (rad/s^2) */
ladrc_real_t ladrc_hp_get_estimate(const ladrc_hp_estimator_t *est);

/** The compensation the command should carry after the latest step
 *  (rad/s^2): the estimate with each tone advanced over the actuator (see
 *  above), computed by the step in the same pass as the estimate; the
 *  estimate itself when there is no actuator to advance over.
 *  @param est  the estimator; NULL: 0
 *  @return the compensation (rad/s^2) */
ladrc_real_t ladrc_hp_get_command(const ladrc_hp_estimator_t *est);

/**
 * Part of the latest change of the estimate that came from the gate's weight
 * moving, not from the model (rad/s^2): (weight_k - weight_k-1) * model_k;
 * 0 when a change discarded the model. An observer whose z3 already holds the
 * disturbance must hand that part over to the known input at once
 * (z3 -= handover), or z3 + d_hat counts it twice for the observer's
 * settling time: engaging and releasing the compensation is then bumpless.
 * @param est  the estimator; NULL: 0
 * @return the weight's part of the change (rad/s^2)
 */
ladrc_real_t ladrc_hp_get_handover(const ladrc_hp_estimator_t *est);

/** Tones in the model now (KNOWN: n_tones).
 *  @param est  the estimator; NULL: 0
 *  @return the active tones */
unsigned ladrc_hp_get_active_tones(const ladrc_hp_estimator_t *est);

/** Frequency of active tone k.
 *  @param est  the estimator; NULL: 0
 *  @param k    the tone, from 0
 *  @return its frequency (rad/s); 0 for k >= the active tones */
ladrc_real_t ladrc_hp_get_freq(const ladrc_hp_estimator_t *est, unsigned k);

/** Amplitude sqrt(a_k^2 + b_k^2) of active tone k.
 *  @param est  the estimator; NULL: 0
 *  @param k    the tone, from 0
 *  @return its amplitude (rad/s^2); 0 for k >= the active tones */
ladrc_real_t ladrc_hp_get_amplitude(const ladrc_hp_estimator_t *est, unsigned k);

/** Whether active tone k is significant and its phasor stands still (locked).
 *  @param est  the estimator; NULL: 0
 *  @param k    the tone, from 0
 *  @return 1 locked, 0 not (or k >= the active tones) */
int ladrc_hp_tone_locked(const ladrc_hp_estimator_t *est, unsigned k);

/** The gate's band evidence for active tone k: the power of its fitted
 *  phasor's mean over the gate's window against the power noise alone
 *  would give that mean, as a fraction of the bar a tone must clear to
 *  lock (1: at the bar; see "Gate" above).
 *  @param est  the estimator; NULL: 0
 *  @param k    the tone, from 0
 *  @return the evidence over its bar; 0 for k >= the active tones */
ladrc_real_t ladrc_hp_get_evidence(const ladrc_hp_estimator_t *est, unsigned k);

/** The gate's coherence for active tone k: the power of its fitted
 *  phasor's mean over the window against its mean power less the noise's
 *  (1: the phasor stands still; a tone off its frequency by dw keeps
 *  1 / (1 + (dw W)^2) of it over a window W).
 *  @param est  the estimator; NULL: 0
 *  @param k    the tone, from 0
 *  @return the coherence, in [0, 1]; 0 for k >= the active tones */
ladrc_real_t ladrc_hp_get_coherence(const ladrc_hp_estimator_t *est, unsigned k);

/** Compensation weight set by the gate.
 *  @param est  the estimator; NULL: 0
 *  @return the weight, in [0, 1] */
ladrc_real_t ladrc_hp_get_weight(const ladrc_hp_estimator_t *est);

/** Fitted bias c.
 *  @param est  the estimator; NULL: 0
 *  @return c (rad/s^2) */
ladrc_real_t ladrc_hp_get_bias(const ladrc_hp_estimator_t *est);

/** The fit of the bias and the tones, read-only (valid while est is), for
 *  diagnostics through the rls.h getters: e.g. tr(P), ladrc_rls_get_p_norm,
 *  against its bound, ladrc_rls_get_p_bound.
 *  @param est  the estimator
 *  @return the fit; est NULL: NULL */
const ladrc_rls_t *ladrc_hp_get_fit(const ladrc_hp_estimator_t *est);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_ESTIMATOR_H */
