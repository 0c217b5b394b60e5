/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file estimator.h
 * @brief Adaptive disturbance estimators of the modified LADRC (PAPER.md
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
 * HP ("high precision", angle only): the sample is the LESO's view of f
 * alone, s_k = z3_k - z3_shadow_k, where the shadow is an identical observer
 * of a still plant told the same d_hat: its z3 is the part of z3 that d_hat
 * caused, so the fit never chases its own output (no adaptation loop through
 * the observer). The sample lags f by the observer's wo^3 / (s + wo)^3, which
 * the estimate undoes at the modelled frequency. Model
 *     d(t) = c + a cos(psi) + b sin(psi),   psi' = w
 * with (c, a, b) from a three-parameter RLS and psi kept as a unit phasor
 * rotated by w h each tick (bounded, no time variable). The frequency w is
 * given (KNOWN, the paper's assumption) or estimated (ONLINE) from decimated
 * samples x_j (mean of `decimation` ticks, period T) by the linear prediction
 *     x_j - 2 x_j-1 + x_j-2 = -kappa x_j-1 + kappa c,   kappa = 4 sin^2(w T / 2)
 * solved by a two-parameter RLS (the second difference keeps the regression
 * well scaled where 2 cos(w T) would sit within float resolution of 2).
 * The (c, a, b) fit and the gate take every fit_decimation-th sample: the
 * sample is smooth (it comes through the observer, bandwidth wo), so a few
 * milliseconds between fit samples lose little, and the fit's cost is shared
 * by that many ticks; the estimate itself is evaluated every tick.
 * Both fits keep about one period of the modelled tone in memory while the
 * model explains the signal (enough to tell the bias, the tone and a
 * neighbouring tone apart), and forget at the configured maximum rate while it
 * does not (start-up, a frequency jump). A confidence gate compares the
 * model's prediction error power with the sample's power around its bias,
 * both averaged over a period: the compensation weight ramps towards 1 only
 * while the model explains more than 99.5% of it, and towards 0 (plain LADRC)
 * below 97%, at most 1 per second.
 */
#ifndef LADRC_ESTIMATOR_H
#define LADRC_ESTIMATOR_H

#include "ladrc/rls.h"
#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    ladrc_real_t dt_s;          /**< fixed step h (s), > 0 */
    ladrc_real_t lambda0_per_s; /**< maximum forgetting rate (1/s), > 0; paper 100 */
    ladrc_real_t k0_per_s;      /**< bound on the continuous-time gain P (1/s), > 0; paper 300 */
} ladrc_lp_config_t;

typedef struct {
    ladrc_rls_t rls;            /**< one parameter: d_hat */
    ladrc_real_t dt_s;
    ladrc_real_t prev_rate_rad_s;
    uint8_t has_prev_rate;
    ladrc_fault_t faults;
} ladrc_lp_estimator_t;

/** Validates (LADRC_ERR_DT_S, LADRC_ERR_EST_LAMBDA0, LADRC_ERR_EST_K0) and resets. */
ladrc_status_t ladrc_lp_init(ladrc_lp_estimator_t *est, const ladrc_lp_config_t *cfg);

/** Forgets the estimate (d_hat = 0) and the rate history. */
void ladrc_lp_reset(ladrc_lp_estimator_t *est);

/**
 * One tick.
 * @param rate_rad_s     measured angular rate now
 * @param accel_known    acceleration the known input gave over the last step,
 *                       b0 * applied torque (rad/s^2)
 * A non-finite argument holds the estimate and raises LADRC_FAULT_INPUT; the
 * next finite rate restarts the difference.
 */
ladrc_fault_t ladrc_lp_step(ladrc_lp_estimator_t *est, ladrc_real_t rate_rad_s,
                            ladrc_real_t accel_known);

/** Current estimate d_hat (rad/s^2). */
ladrc_real_t ladrc_lp_get_estimate(const ladrc_lp_estimator_t *est);

typedef enum {
    LADRC_HP_FREQ_KNOWN = 0, /**< the disturbance frequency is given (paper) */
    LADRC_HP_FREQ_ONLINE = 1 /**< estimated online within [freq_min, freq_max] */
} ladrc_hp_freq_mode_t;

typedef struct {
    ladrc_real_t dt_s;               /**< fixed step h (s), > 0 */
    ladrc_hp_freq_mode_t freq_mode;
    ladrc_real_t freq_rad_s;         /**< KNOWN: the frequency; ONLINE: the first guess (rad/s), > 0 */
    ladrc_real_t freq_min_rad_s;     /**< ONLINE search range (rad/s), 0 < min < max */
    ladrc_real_t freq_max_rad_s;     /**< ONLINE: max * T < pi/2 with T = decimation * dt_s */
    ladrc_real_t lambda0_per_s;      /**< forgetting rate of the (c, a, b) RLS (1/s), > 0 */
    ladrc_real_t freq_lambda0_per_s; /**< forgetting rate of the frequency RLS (1/s), > 0 */
    uint16_t decimation;             /**< ticks per frequency sample, >= 1 */
    ladrc_real_t sample_lag_wo_rad_s;/**< samples come through a LESO of this bandwidth, whose z3
                                          lags f by wo^3 / (s + wo)^3: undone at w; 0 = no lag */
    uint16_t fit_decimation;         /**< ticks per sample of the (c, a, b) fit and the gate, >= 1;
                                          the tone may turn at most pi/2 per fit sample */
    uint16_t fit_phase;              /**< which tick of each fit_decimation block fits, < fit_decimation
                                          (give the axes of one controller different phases so a
                                          tick carries at most one fit) */
} ladrc_hp_config_t;

typedef struct {
    ladrc_rls_t amp;                 /**< theta = (c, a, b) */
    ladrc_rls_t freq;                /**< theta = (kappa, kappa c) */
    ladrc_real_t dt_s;
    ladrc_real_t freq_min_rad_s, freq_max_rad_s;
    ladrc_real_t lambda0_max;        /**< configured forgetting rate of the (c, a, b) RLS */
    ladrc_real_t freq_lambda0_max;   /**< configured forgetting rate of the frequency RLS */
    ladrc_real_t period_rate_per_s;  /**< w / 2 pi, at most lambda0_max: one period's memory */
    ladrc_real_t freq_period_rate_per_s; /**< the same, at most freq_lambda0_max */
    ladrc_real_t w_rad_s;            /**< frequency in use */
    ladrc_real_t cos_psi, sin_psi;   /**< phase as a unit phasor */
    ladrc_real_t cos_step, sin_step; /**< rotation by w h */
    ladrc_real_t lag_wo_rad_s;       /**< bandwidth of the sample's lag, 0 = none */
    ladrc_real_t lead_re, lead_im;   /**< (1 + j w / wo)^3: undoes the lag at w */
    ladrc_real_t dec_sum;            /**< sum of the current decimation block */
    ladrc_real_t x1, x2;             /**< the two previous decimated samples */
    ladrc_real_t sig_power;          /**< gate: sample power around the bias, over a period */
    ladrc_real_t err_power;          /**< gate: prediction error power, over a period */
    ladrc_real_t weight;             /**< compensation weight in [0, 1] */
    ladrc_real_t estimate;           /**< weight * model: the applied d_hat (rad/s^2) */
    uint16_t decimation, dec_count;
    uint16_t fit_decimation, fit_count; /**< the fit takes the sample of every fit_decimation-th tick */
    uint16_t fit_phase;              /**< fit when fit_count equals it */
    uint16_t dec_delay;              /**< ticks before the first frequency block starts (fit_phase) */
    uint8_t n_dec_samples;           /**< decimated samples seen, saturates at 2 */
    uint8_t online;
    uint8_t memory;                  /**< memory the RLS were given last (estimator_hp.c) */
    ladrc_fault_t faults;
} ladrc_hp_estimator_t;

/** Validates (LADRC_ERR_DT_S, _HP_FREQ_MODE, _HP_FREQ_RAD_S, _HP_FREQ_RANGE, _EST_LAMBDA0,
 *  _HP_DECIMATION) and resets. */
ladrc_status_t ladrc_hp_init(ladrc_hp_estimator_t *est, const ladrc_hp_config_t *cfg);

/** Forgets the model and the frequency history; the phase restarts at 0 and the
 *  frequency at the configured one. */
void ladrc_hp_reset(ladrc_hp_estimator_t *est, ladrc_real_t freq_rad_s);

/**
 * One tick on the disturbance sample (rad/s^2): f as the axis's observer sees
 * it, without the compensation's part (see above).
 * Non-finite: held, LADRC_FAULT_INPUT (the phase still advances, so the model
 * stays in step with time).
 */
ladrc_fault_t ladrc_hp_step(ladrc_hp_estimator_t *est, ladrc_real_t sample_rad_s2);

/** Applied estimate d_hat (rad/s^2): weight times the model at the current phase. */
ladrc_real_t ladrc_hp_get_estimate(const ladrc_hp_estimator_t *est);

/** Frequency in use (rad/s). */
ladrc_real_t ladrc_hp_get_freq(const ladrc_hp_estimator_t *est);

/** Amplitude sqrt(a^2 + b^2) of the modelled sinusoid (rad/s^2). */
ladrc_real_t ladrc_hp_get_amplitude(const ladrc_hp_estimator_t *est);

/** Compensation weight in [0, 1] set by the confidence gate. */
ladrc_real_t ladrc_hp_get_weight(const ladrc_hp_estimator_t *est);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_ESTIMATOR_H */
