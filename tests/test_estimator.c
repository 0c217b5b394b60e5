/* SPDX-License-Identifier: BSD-3-Clause */
/* LP and HP disturbance estimators fed known signals (no loop): convergence,
 * frequency tracking, the gate, validation and faults. */
#include "unity.h"
#include "ladrc/axis.h"
#include "ladrc/estimator.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3
#define PI 3.14159265358979
/* Accuracy targets for the online HP estimator. */
#define FREQ_REL_TOL 0.02
#define AMP_REL_TOL 0.05
/* Time allowed to reach them, noise-free, from a first guess of 3 rad/s: 2 s
 * or half a period, whichever is longer (a slow tone shows its derivatives
 * only after the start's transient has left the filter; measured 4.7 s at
 * 0.5 rad/s, 0.3 to 1.3 s from 0.785 to 30 rad/s). */
#define CONVERGE_S 2.0
#define CONVERGE_PERIODS 0.5
/* After the paper's jump from 0.785 to 3 rad/s: the change restarts the fit
 * at once and the frequency fit once the change has passed its filter
 * (1 s); measured 1.2 s to be back within the targets. */
#define REJUMP_S 2.0
/* With noise, accuracy is judged after the start-up transient. */
#define NOISY_SETTLE_S 5.0

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_hp_config_t hp_config(ladrc_hp_freq_mode_t mode, double freq)
{
    /* the axis defaults: one place says what a sensible HP setting is */
    ladrc_axis_config_t axis;
    ladrc_axis_config_default(&axis, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, 1.0f);
    ladrc_hp_config_t cfg;
    ladrc_axis_hp_config(&axis, &cfg);
    cfg.freq_mode = mode;
    cfg.sample_lag_wo_rad_s = 0.0f; /* the samples come straight, not through a LESO */
    cfg.freq_rad_s[0] = (ladrc_real_t)freq;
    if (mode == LADRC_HP_FREQ_KNOWN) {
        cfg.n_tones = 1u;
    }
    return cfg;
}

/* Whether tone k of est has frequency w and amplitude a within the targets. */
static int tone_is(const ladrc_hp_estimator_t *est, unsigned k, double w, double a)
{
    return fabs(ladrc_hp_get_freq(est, k) - w) < FREQ_REL_TOL * w &&
           fabs(ladrc_hp_get_amplitude(est, k) - a) < AMP_REL_TOL * a;
}

/* Runs HP on c + A sin(w t + p) and returns the last time (s) it was outside
 * the tolerances, or -1 if it never got inside within n ticks. */
static double hp_convergence_time(double c, double a, double w, int n, ladrc_hp_estimator_t *est)
{
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(est, &cfg));
    double last_out = 0.0;
    int inside = 0;
    for (int k = 0; k < n; ++k) {
        const double t = k * DT_S;
        ladrc_hp_step(est, (ladrc_real_t)(c + a * sin(w * t + 0.3)));
        inside = ladrc_hp_get_active_tones(est) == 1u && tone_is(est, 0u, w, a);
        if (!inside) {
            last_out = t + DT_S;
        }
    }
    return inside ? last_out : -1.0;
}

/* One tick of the LP command's lead: the compensation it gives (rad/s^2). */
/* LP with the paper's forgetting behind a 30 ms motor lag and 2 ticks of delay. */
static ladrc_lp_config_t lp_config_behind_motors(void)
{
    const ladrc_lp_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                   .lambda0_per_s = 100.0f,
                                   .k0_per_s = 300.0f,
                                   .act_tau_s = 0.03f,
                                   .act_delay_ticks = 2u};
    return cfg;
}

static ladrc_real_t lp_lead(ladrc_lp_estimator_t *est)
{
    ladrc_real_t command_rad_s2 = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_lp_step_lead(est, &command_rad_s2));
    return command_rad_s2;
}

static void test_hp_online_finds_frequency_and_amplitude_across_the_range(void)
{
    const double freqs[] = {0.5, 0.785, 1.0, 3.0, 10.0, 30.0};
    for (unsigned i = 0; i < sizeof freqs / sizeof freqs[0]; ++i) {
        ladrc_hp_estimator_t est;
        const double t = hp_convergence_time(20.0, 120.0, freqs[i], 10000, &est);
        const double allowed = fmax(CONVERGE_S, CONVERGE_PERIODS * 2.0 * PI / freqs[i]);
        char msg[96];
        snprintf(msg, sizeof msg, "w %.3f rad/s: within 2%%/5%% from %.3f s, w_hat %.4f, A_hat %.2f", freqs[i], t,
                 ladrc_hp_get_freq(&est, 0u), ladrc_hp_get_amplitude(&est, 0u));
        TEST_MESSAGE(msg);
        TEST_ASSERT_TRUE_MESSAGE(t >= 0.0, msg);
        TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((float)allowed, (float)t, msg);
    }
}

static void test_hp_online_frequency_is_exact_for_a_lone_tone_whatever_its_bias(void)
{
    /* The derivative fit pairs x1, x3 and x5 so that a tone's ratio is exact
     * at every instant: after 10 s only float rounding is left (measured
     * 2e-6 relative; 1e-4 is the bar). */
    const double freqs[] = {0.5, 3.0, 30.0};
    const double biases[] = {0.0, -500.0};
    for (unsigned i = 0; i < 3u; ++i) {
        for (unsigned j = 0; j < 2u; ++j) {
            ladrc_hp_estimator_t est;
            (void)hp_convergence_time(biases[j], 120.0, freqs[i], 10000, &est);
            TEST_ASSERT_FLOAT_WITHIN(1e-4 * freqs[i], freqs[i], ladrc_hp_get_freq(&est, 0u));
        }
    }
}

static void test_hp_online_resolves_two_tones(void)
{
    /* given 120 sin(3 t) + 30 sin(8 t) over a bias: the fit of x5 on x3 and
     * x1 finds both, and the model holds both at their amplitudes */
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    for (int k = 0; k < 8000; ++k) {
        const double t = k * DT_S;
        ladrc_hp_step(&est, (ladrc_real_t)(20.0 + 120.0 * sin(3.0 * t) + 30.0 * sin(8.0 * t + 1.0)));
    }
    TEST_ASSERT_EQUAL_UINT(2u, ladrc_hp_get_active_tones(&est));
    TEST_ASSERT_TRUE(tone_is(&est, 0u, 3.0, 120.0));
    TEST_ASSERT_TRUE(tone_is(&est, 1u, 8.0, 30.0));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, ladrc_hp_get_weight(&est));
}

static void test_hp_online_reconverges_after_the_papers_frequency_jump(void)
{
    /* given the paper's Table 2 change from 0.25 pi to 3 rad/s at 12 s */
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    ladrc_hp_init(&est, &cfg);
    double t_back = -1.0;
    for (int k = 0; k < 25000; ++k) {
        const double t = k * DT_S;
        const double d = (t <= 12.0) ? 20.0 - 120.0 * sin(0.25 * PI * t) : 20.0 - 120.0 * sin(3.0 * t);
        ladrc_hp_step(&est, (ladrc_real_t)d);
        const int ok = t > 12.0 && ladrc_hp_get_active_tones(&est) == 1u && tone_is(&est, 0u, 3.0, 120.0);
        if (!ok) {
            t_back = -1.0;
        } else if (t_back < 0.0) {
            t_back = t - 12.0;
        }
    }
    char msg[64];
    snprintf(msg, sizeof msg, "back within 2%%/5%% %.3f s after the jump", t_back);
    TEST_MESSAGE(msg);
    /* then it is back within the accuracy targets and stays there */
    TEST_ASSERT_TRUE_MESSAGE(t_back >= 0.0 && t_back < REJUMP_S, msg);
}

static void hp_known_fits_with_fit_decimation(uint16_t fit_decimation)
{
    ladrc_hp_estimator_t est;
    ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    cfg.fit_decimation = fit_decimation;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    for (int k = 0; k < 3000; ++k) {
        ladrc_hp_step(&est, (ladrc_real_t)(20.0 + 120.0 * sin(3.0 * k * DT_S)));
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 3.0f, ladrc_hp_get_freq(&est, 0u));
    TEST_ASSERT_FLOAT_WITHIN(AMP_REL_TOL * 120.0, 120.0f, ladrc_hp_get_amplitude(&est, 0u));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, ladrc_hp_get_weight(&est));
    /* the applied estimate is the model: within 1% of the signal's amplitude */
    const double d_now = 20.0 + 120.0 * sin(3.0 * 2999 * DT_S); /* phase of the last sample */
    TEST_ASSERT_FLOAT_WITHIN(1.2, d_now, ladrc_hp_get_estimate(&est));
}

static void test_hp_known_frequency_fits_the_amplitude_and_opens_the_gate(void)
{
    /* every tick, the 4 ms default at 1 kHz, and a sample every 20 ms */
    hp_known_fits_with_fit_decimation(1u);
    hp_known_fits_with_fit_decimation(4u);
    hp_known_fits_with_fit_decimation(20u);
}

static void test_hp_fits_on_the_tick_its_phase_names(void)
{
    /* given two estimators fitting every 4th tick, at phases 0 and 3 */
    ladrc_hp_estimator_t first, last;
    ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    cfg.fit_decimation = 4u;
    ladrc_hp_init(&first, &cfg);
    cfg.fit_phase = 3u;
    ladrc_hp_init(&last, &cfg);
    /* when ticks 0..2 see a sample */
    for (int k = 0; k < 3; ++k) {
        ladrc_hp_step(&first, 50.0f);
        ladrc_hp_step(&last, 50.0f);
    }
    /* then only phase 0 has fitted (on tick 0), phase 3 fits on tick 3 */
    TEST_ASSERT_TRUE(ladrc_hp_get_bias(&first) > 0.0f);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_bias(&last));
    ladrc_hp_step(&last, 50.0f);
    TEST_ASSERT_TRUE(ladrc_hp_get_bias(&last) > 0.0f);
}

static void test_hp_undoes_the_observer_lag_of_its_samples(void)
{
    /* given samples that are the tone seen through a triple lag at 75 rad/s
     * (what a LESO's z3 shows): at 20 rad/s 0.9x amplitude and 0.78 rad late */
    const double w = 20.0, wo = 75.0;
    const double gain = pow(1.0 + (w / wo) * (w / wo), -1.5);
    const double lag = 3.0 * atan(w / wo);
    ladrc_hp_estimator_t est;
    ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, w);
    cfg.sample_lag_wo_rad_s = (ladrc_real_t)wo;
    ladrc_hp_init(&est, &cfg);
    for (int k = 0; k < 3000; ++k) {
        ladrc_hp_step(&est, (ladrc_real_t)(120.0 * gain * sin(w * k * DT_S - lag)));
    }
    /* then the estimate is the tone itself, on time: within 1% of 120 (float
     * fit noise 0.1%, first-order phasor renormalisation well below) */
    TEST_ASSERT_FLOAT_WITHIN(1.2, 120.0 * sin(w * 2999 * DT_S), ladrc_hp_get_estimate(&est));
}

static void test_hp_undoes_the_block_mean_and_the_age_of_its_samples(void)
{
    /* given per-tick samples of a 30 rad/s tone half a tick old (a rate
     * difference) and a fit on the mean of each block of 8 ticks, told the
     * age of that mean (4 ticks): at 30 rad/s the block's mean is 3.5 ticks
     * late (0.105 rad) and 0.7 % small */
    const double w = 30.0;
    const unsigned n = 8u;
    ladrc_hp_estimator_t est;
    ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, w);
    cfg.fit_decimation = (uint16_t)n;
    cfg.sample_block_mean = 1u;
    cfg.sample_age_s = (ladrc_real_t)(0.5 * n * DT_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    for (int k = 0; k < 6000; ++k) {
        ladrc_hp_step(&est, (ladrc_real_t)(120.0 * sin(w * (k - 0.5) * DT_S)));
    }
    /* then the estimate is the tone on time: within 1 % of 120 (uncorrected,
     * the 0.105 rad of phase alone would leave 12.6) */
    TEST_ASSERT_FLOAT_WITHIN(1.2, 120.0 * sin(w * 5999 * DT_S), ladrc_hp_get_estimate(&est));
    /* and an age the fastest tone turns more than pi/2 in is refused */
    cfg.sample_age_s = (ladrc_real_t)(0.6 * 3.14159265 / w);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_SAMPLE_LAG, ladrc_hp_init(&est, &cfg));
    cfg.sample_age_s = 0.0f;
    cfg.sample_block_mean = 2u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_SAMPLE_LAG, ladrc_hp_init(&est, &cfg));
}

static void test_lp_gives_its_sample_and_hands_over_past_its_lead(void)
{
    const ladrc_lp_config_t cfg = lp_config_behind_motors();
    ladrc_lp_estimator_t est;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_lp_init(&est, &cfg));
    /* the first rate gives no sample; the second its difference minus the known input */
    (void)ladrc_lp_step(&est, 0.0f, 0.0f);
    TEST_ASSERT_FALSE(
        ladrc_is_finite(ladrc_lp_get_sample(&est))); /* NaN: no sample (a bit test, as under -ffast-math) */
    (void)ladrc_lp_step(&est, 0.002f, -1.0f);
    TEST_ASSERT_FLOAT_WITHIN(1e-3, 0.002 / DT_S + 1.0, ladrc_lp_get_sample(&est));
    for (int k = 0; k < 500; ++k) {
        (void)ladrc_lp_step(&est, 0.002f, (ladrc_real_t)(-10.0 - 5.0 * sin(0.02 * k)));
        (void)lp_lead(&est);
    }
    /* handed over, the estimate and the command move by exactly what was
     * given up, at once: no step through the lead (whose gain there is 4) */
    ladrc_lp_estimator_t moved = est;
    const double d_before = ladrc_lp_get_estimate(&est);
    const double c_before = lp_lead(&est);
    ladrc_lp_hand_over(&moved, -6.0f);
    TEST_ASSERT_FLOAT_WITHIN(1e-5, d_before - 6.0, ladrc_lp_get_estimate(&moved));
    TEST_ASSERT_FLOAT_WITHIN(1e-4, c_before - 6.0, lp_lead(&moved));
    /* a non-finite hand-over changes nothing */
    ladrc_lp_estimator_t kept = moved;
    ladrc_lp_hand_over(&moved, (ladrc_real_t)NAN);
    TEST_ASSERT_TRUE(ladrc_lp_get_estimate(&kept) == ladrc_lp_get_estimate(&moved));
    TEST_ASSERT_TRUE(lp_lead(&kept) == lp_lead(&moved));
}

static void test_hp_hands_over_what_the_weight_moves(void)
{
    /* given a locked model, the handover of each tick is the change of the
     * estimate the weight made: (w_k - w_k-1) * model; 0 while it stands */
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    ladrc_hp_init(&est, &cfg);
    double handed = 0.0;
    for (int k = 0; k < 3000; ++k) {
        ladrc_hp_step(&est, (ladrc_real_t)(20.0 + 120.0 * sin(3.0 * k * DT_S)));
        handed += ladrc_hp_get_handover(&est);
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 1.0f, ladrc_hp_get_weight(&est));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_handover(&est));
    /* when the tone stops, the change drops the weight on that fit sample and
     * hands the whole estimate back at once */
    const float before = (float)ladrc_hp_get_estimate(&est);
    int k = 3000;
    while (ladrc_hp_get_weight(&est) > 0.0f && k < 3500) {
        ladrc_hp_step(&est, 0.0f);
        ++k;
    }
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_weight(&est));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_estimate(&est));
    TEST_ASSERT_TRUE(k < 3100); /* within 0.1 s of the stop */
    TEST_ASSERT_TRUE(fabsf(before) > 1.0f);
    TEST_ASSERT_TRUE(fabs(handed) > 0.0);
}

/* HP online on 20 + 120 sin(3 t) plus seeded uniform white noise of the
 * given RMS; returns the worst frequency error after 5 s and the largest
 * |d_hat| over the run. */
static void hp_with_noise(double noise_rms, double *worst_freq_err, double *max_estimate, ladrc_hp_estimator_t *est)
{
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 1.0);
    ladrc_hp_init(est, &cfg);
    unsigned state = 987654321u;
    *worst_freq_err = 0.0;
    *max_estimate = 0.0;
    for (int k = 0; k < 15000; ++k) {
        state = state * 1664525u + 1013904223u;
        const double noise = ((state >> 8) / 16777216.0 - 0.5) * noise_rms * 3.4641016;
        ladrc_hp_step(est, (ladrc_real_t)(20.0 + 120.0 * sin(3.0 * k * DT_S) + noise));
        *max_estimate = fmax(*max_estimate, fabs(ladrc_hp_get_estimate(est)));
        if (k * DT_S > NOISY_SETTLE_S) {
            *worst_freq_err = fmax(*worst_freq_err, fabs(ladrc_hp_get_freq(est, 0u) - 3.0));
        }
    }
}

static void test_hp_online_stays_bounded_with_noise(void)
{
    /* given white noise of 5 and 20 rad/s^2 RMS per sample on the samples
     * (tone to noise power 290:1 and 18:1), where the frequency estimate
     * wanders: the applied estimate never exceeds the signal's own peak (140)
     * plus the noise's peak (uniform: sqrt(3) RMS) */
    const double levels[] = {5.0, 20.0};
    for (unsigned i = 0; i < 2u; ++i) {
        ladrc_hp_estimator_t est;
        double worst, peak;
        hp_with_noise(levels[i], &worst, &peak, &est);
        char msg[128];
        snprintf(msg, sizeof msg,
                 "noise %.0f RMS: largest |d_hat| %.1f, worst |w_hat - 3| after 5 s %.3f rad/s, weight %.2f", levels[i],
                 peak, worst, ladrc_hp_get_weight(&est));
        TEST_MESSAGE(msg);
        TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE((float)(140.0 + 1.7320508 * levels[i]), (float)peak, msg);
    }
}

static void test_hp_gate_stays_shut_on_noise_without_a_tone(void)
{
    /* given white noise: no model explains it, so nothing is compensated */
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    ladrc_hp_init(&est, &cfg);
    unsigned state = 12345u;
    float max_weight = 0.0f;
    for (int k = 0; k < 10000; ++k) {
        state = state * 1664525u + 1013904223u; /* LCG: uniform in [-5, 5) */
        const double noise = ((state >> 8) / 16777216.0 - 0.5) * 10.0;
        ladrc_hp_step(&est, (ladrc_real_t)noise);
        max_weight = fmaxf(max_weight, (float)ladrc_hp_get_weight(&est));
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, max_weight);
}

static void test_hp_non_finite_samples_are_skipped_and_flagged(void)
{
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    ladrc_hp_init(&est, &cfg);
    for (int k = 0; k < 1000; ++k) {
        ladrc_hp_step(&est, (ladrc_real_t)(120.0 * sin(3.0 * k * DT_S)));
    }
    const float amp = (float)ladrc_hp_get_amplitude(&est, 0u);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_hp_step(&est, (ladrc_real_t)NAN));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_hp_step(&est, (ladrc_real_t)INFINITY));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, amp, (float)ladrc_hp_get_amplitude(&est, 0u));
    TEST_ASSERT_FLOAT_IS_DETERMINATE(ladrc_hp_get_estimate(&est));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_hp_step(&est, 1.0f));
}

static void test_hp_getters_of_tones_out_of_range_give_zero(void)
{
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    ladrc_hp_init(&est, &cfg);
    TEST_ASSERT_EQUAL_UINT(1u, ladrc_hp_get_active_tones(&est));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_freq(&est, 1u));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_hp_get_amplitude(&est, 1u));
    TEST_ASSERT_EQUAL_INT(0, ladrc_hp_tone_locked(&est, 1u));
}

static void test_hp_fit_is_readable_and_its_trace_stays_within_the_bound(void)
{
    /* given the paper's tone with noise: the fit read through the estimator
     * has a bias and a cosine and sine per active tone, and tr(P) never
     * leaves (0, p_bound] on any tick */
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    const ladrc_rls_t *fit = ladrc_hp_get_fit(&est);
    TEST_ASSERT_NOT_NULL(fit);
    const double bound = (double)ladrc_rls_get_p_bound(fit);
    TEST_ASSERT_TRUE(bound > 0.0);
    unsigned state = 2463534242u;
    double worst = 0.0;
    for (int k = 0; k < 5000; ++k) {
        state ^= state << 13; /* xorshift32: uniform in [-5, 5) */
        state ^= state >> 17;
        state ^= state << 5;
        const double noise = ((state >> 8) / 16777216.0 - 0.5) * 10.0;
        ladrc_hp_step(&est, (ladrc_real_t)(20.0 + 120.0 * sin(3.0 * k * DT_S) + noise));
        const double tr = (double)ladrc_rls_get_p_norm(fit);
        TEST_ASSERT_TRUE(tr > 0.0 && tr <= bound);
        worst = fmax(worst, tr);
    }
    TEST_ASSERT_EQUAL_UINT(1u + 2u * ladrc_hp_get_active_tones(&est), fit->n_params);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, ladrc_hp_get_bias(&est), ladrc_rls_get_theta(fit)[0]);
    TEST_ASSERT_TRUE(worst <= bound);
}

static void test_hp_invalid_fields_are_rejected(void)
{
    ladrc_hp_estimator_t est;
    const ladrc_hp_config_t good = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    ladrc_hp_config_t cfg = good;
    cfg.dt_s = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_mode = (ladrc_hp_freq_mode_t)4;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_MODE, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.n_tones = 0u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_N_TONES, ladrc_hp_init(&est, &cfg));
    cfg.n_tones = LADRC_HP_MAX_TONES + 1u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_N_TONES, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_rad_s[0] = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_RAD_S, ladrc_hp_init(&est, &cfg));
    cfg.freq_rad_s[0] = 4000.0f; /* more than half a turn per tick */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_RAD_S, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_rad_s[cfg.n_tones - 1u] = -1.0f; /* every modelled tone is read */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_RAD_S, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_min_rad_s = cfg.freq_max_rad_s;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_RANGE, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_max_rad_s = 4000.0f; /* more than half a turn per tick */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_RANGE, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.lambda0_per_s = -1.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_EST_LAMBDA0, ladrc_hp_init(&est, &cfg));
    cfg.lambda0_per_s = 1000.0f; /* more than one memory per fit sample */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_EST_LAMBDA0, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_lambda0_per_s = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_LAMBDA0, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_filter_rad_s = 100.0f; /* 100 rad/s * 4 ms is too coarse for the filter */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FREQ_FILTER, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.sample_lag_wo_rad_s = -75.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_SAMPLE_LAG, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.fit_decimation = 0u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FIT_DECIMATION, ladrc_hp_init(&est, &cfg));
    cfg.fit_decimation = 4u;
    cfg.fit_phase = 4u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FIT_DECIMATION, ladrc_hp_init(&est, &cfg));
    cfg.fit_phase = 0u;
    cfg.fit_decimation = 40u; /* 40 rad/s * 40 ms > pi / 2 */
    cfg.freq_filter_rad_s = 1.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_FIT_DECIMATION, ladrc_hp_init(&est, &cfg));
    cfg.freq_mode = LADRC_HP_FREQ_KNOWN; /* 3 rad/s * 40 ms is fine */
    cfg.n_tones = 1u;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    cfg = good;
    cfg.freq_mode = LADRC_HP_FREQ_KNOWN;
    cfg.freq_max_rad_s = (ladrc_real_t)NAN; /* the range is not read in KNOWN mode */
    cfg.freq_filter_rad_s = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_hp_init(NULL, &good));
}

static void test_lp_tracks_the_measured_acceleration_minus_the_known_input(void)
{
    /* given a rate whose derivative is 30 rad/s^2, of which 10 came from the input */
    ladrc_lp_estimator_t est;
    const ladrc_lp_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                   .lambda0_per_s = 100.0f,
                                   .k0_per_s = 300.0f,
                                   .act_tau_s = 0.0f,
                                   .act_delay_ticks = 0u};
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_lp_init(&est, &cfg));
    for (int k = 0; k < 200; ++k) {
        ladrc_lp_step(&est, (ladrc_real_t)(30.0 * k * DT_S), 10.0f);
    }
    /* then after 200 ms (15 time constants of 75 rad/s) d_hat = 20; the float
     * difference of rates near 6 rad/s carries 5e-4 rad/s^2 of rounding */
    TEST_ASSERT_FLOAT_WITHIN(1e-2f, 20.0f, ladrc_lp_get_estimate(&est));
}

static void test_lp_bandwidth_is_lambda0_k0_over_their_sum(void)
{
    /* a step of the sample reaches 1 - 1/e after 1/75 s = 13 ms (discrete
     * gain per tick 0.075: 1 - 0.925^13 = 0.637, one tick = 5% of the rise) */
    ladrc_lp_estimator_t est;
    const ladrc_lp_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                   .lambda0_per_s = 100.0f,
                                   .k0_per_s = 300.0f,
                                   .act_tau_s = 0.0f,
                                   .act_delay_ticks = 0u};
    ladrc_lp_init(&est, &cfg);
    for (int k = 0; k < 1000; ++k) { /* let P settle on a zero sample */
        ladrc_lp_step(&est, 0.0f, 0.0f);
    }
    double rate = 0.0;
    int k63 = -1;
    for (int k = 1; k <= 100 && k63 < 0; ++k) {
        rate += 1.0 * DT_S; /* sample = 1 rad/s^2 */
        ladrc_lp_step(&est, (ladrc_real_t)rate, 0.0f);
        if (ladrc_lp_get_estimate(&est) >= 1.0 - exp(-1.0)) {
            k63 = k;
        }
    }
    char msg[48];
    snprintf(msg, sizeof msg, "63%% reached at tick %d", k63);
    TEST_ASSERT_TRUE_MESSAGE(k63 >= 12 && k63 <= 14, msg);
}

static void test_lp_rate_gap_restarts_the_difference(void)
{
    ladrc_lp_estimator_t est;
    const ladrc_lp_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                   .lambda0_per_s = 100.0f,
                                   .k0_per_s = 300.0f,
                                   .act_tau_s = 0.0f,
                                   .act_delay_ticks = 0u};
    ladrc_lp_init(&est, &cfg);
    ladrc_lp_step(&est, 0.0f, 0.0f);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_lp_step(&est, (ladrc_real_t)NAN, 0.0f));
    /* a jump across the gap is not a sample: no 1000 rad/s^2 spike */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_lp_step(&est, 1.0f, 0.0f));
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, ladrc_lp_get_estimate(&est));
}

static void test_lp_invalid_fields_are_rejected(void)
{
    ladrc_lp_estimator_t est;
    const ladrc_lp_config_t good = {.dt_s = (ladrc_real_t)DT_S,
                                    .lambda0_per_s = 100.0f,
                                    .k0_per_s = 300.0f,
                                    .act_tau_s = 0.0f,
                                    .act_delay_ticks = 0u};
    ladrc_lp_config_t cfg = good;
    cfg.dt_s = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_lp_init(&est, &cfg));
    cfg = good;
    cfg.lambda0_per_s = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_EST_LAMBDA0, ladrc_lp_init(&est, &cfg));
    cfg = good;
    cfg.k0_per_s = (ladrc_real_t)INFINITY;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_EST_K0, ladrc_lp_init(&est, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_lp_init(&est, NULL));
}

/* ---- the command advanced over an actuator --------------------------------- */

/* The command's phasor against the estimate's: both are sums of the same
 * fitted tone, so their ratio is the constant (1 + j w tau) e^{j w d h}
 * exactly, up to the float rounding of a few products and of the lock-in's
 * sums over 4000 ticks (relative 1e-4 leaves room tenfold). */
#define ADVANCE_PHASOR_TOL 1e-4
/* The bounded lead's response to a step of d_hat: N at once, then towards 1
 * with the time constant tau' / N; after 20 such time constants within
 * float rounding of 1 (relative 1e-5). */
#define LEAD_SETTLED_TOL 1e-5

/* Lock-in: phasor (cos, sin coefficients) of x_k on the tone w over n ticks. */
static void lock_in(const double *x, int n, double w, double *re, double *im)
{
    double c = 0.0, s = 0.0;
    for (int k = 0; k < n; ++k) {
        c += x[k] * cos(w * DT_S * k);
        s += x[k] * sin(w * DT_S * k);
    }
    *re = 2.0 * c / n;
    *im = 2.0 * s / n;
}

static void test_hp_command_is_the_estimate_turned_by_the_inverse_actuator(void)
{
    /* given: a known 3 rad/s tone, the command advanced over 30 ms and 2 ticks */
    const double w = 3.0, tau = 0.03;
    const int d = 2;
    ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, w);
    cfg.act_tau_s = (ladrc_real_t)tau;
    cfg.act_delay_ticks = (uint16_t)d;
    static ladrc_hp_estimator_t est;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    /* when: it converges on 2 + 5 sin(w t), then a whole number of periods is read */
    const int n_conv = 6000, n = 4189; /* 4189 ticks: two periods of 3 rad/s to 1e-4 */
    static double e[4189], c[4189];
    for (int k = 0; k < n_conv + n; ++k) {
        const double t = DT_S * k;
        (void)ladrc_hp_step(&est, (ladrc_real_t)(2.0 + 5.0 * sin(w * t)));
        if (k >= n_conv) {
            e[k - n_conv] = ladrc_hp_get_estimate(&est) - ladrc_hp_get_bias(&est);
            c[k - n_conv] = ladrc_hp_get_command(&est) - ladrc_hp_get_bias(&est);
        }
    }
    TEST_ASSERT_EQUAL_FLOAT(1.0f, ladrc_hp_get_weight(&est));
    double er, ei, cr, ci;
    lock_in(e, n, w, &er, &ei);
    lock_in(c, n, w, &cr, &ci);
    /* then: command / estimate = (1 + j w tau) e^{j w d h}, as phasors a - j b */
    const double complex_e_re = er, complex_e_im = -ei, complex_c_re = cr, complex_c_im = -ci;
    const double den = complex_e_re * complex_e_re + complex_e_im * complex_e_im;
    const double ratio_re = (complex_c_re * complex_e_re + complex_c_im * complex_e_im) / den;
    const double ratio_im = (complex_c_im * complex_e_re - complex_c_re * complex_e_im) / den;
    const double ph = w * d * DT_S;
    const double want_re = cos(ph) - w * tau * sin(ph), want_im = sin(ph) + w * tau * cos(ph);
    printf("command / estimate %.6f %+.6fj, want %.6f %+.6fj\n", ratio_re, ratio_im, want_re, want_im);
    TEST_ASSERT_FLOAT_WITHIN(ADVANCE_PHASOR_TOL, want_re, ratio_re);
    TEST_ASSERT_FLOAT_WITHIN(ADVANCE_PHASOR_TOL, want_im, ratio_im);
}

/* The command's phasor turned over a long delay (binary powers of the
 * tick's turn) against cos and sin of w (d - 1) h in double: each of the
 * log2 d squarings doubles the error before it and adds a rounding, so the
 * angle and the modulus are off by about d eps of the real type, plus the
 * rounding of the tick's turn w h itself times d - 1; 2 d eps (float: 9.5e-5
 * at d = 400, measured up to 9e-6 there). */
#define HP_TURN_TOL_PER_TICK (2.0 * (sizeof(ladrc_real_t) == sizeof(float) ? 1.1920929e-7 : 2.220446e-16))

static void test_hp_command_turned_over_a_long_delay_is_the_trig_formula(void)
{
    static const int delays[] = {9, 100, 400};
    static const double freqs[] = {3.0, 30.0, 100.0};
    for (unsigned i = 0u; i < 3u; ++i) {
        for (unsigned j = 0u; j < 3u; ++j) {
            /* given: a known tone, the command advanced over d ticks, no lag */
            const int d = delays[i];
            ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_KNOWN, freqs[j]);
            cfg.act_delay_ticks = (uint16_t)d;
            static ladrc_hp_estimator_t est;
            /* when */
            TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
            /* then: cmd = lead e^{j w (d - 1) h} */
            const ladrc_hp_tone_t *t = &est.tone[0];
            const double ph = (double)cfg.freq_rad_s[0] * DT_S * (d - 1);
            const double re = t->lead_re * cos(ph) - t->lead_im * sin(ph);
            const double im = t->lead_im * cos(ph) + t->lead_re * sin(ph);
            const double tol = HP_TURN_TOL_PER_TICK * d * hypot(t->lead_re, t->lead_im);
            printf("HP turn d %d w %g: error %.2e %.2e, tolerance %.2e\n", d, freqs[j], (double)t->cmd_re - re,
                   (double)t->cmd_im - im, tol);
            TEST_ASSERT_FLOAT_WITHIN(tol, re, (double)t->cmd_re);
            TEST_ASSERT_FLOAT_WITHIN(tol, im, (double)t->cmd_im);
        }
    }
}

static void test_hp_without_actuator_command_is_the_estimate_bit_for_bit(void)
{
    /* given: the same estimator with no actuator to advance over */
    const ladrc_hp_config_t cfg = hp_config(LADRC_HP_FREQ_ONLINE, 3.0);
    static ladrc_hp_estimator_t est;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_hp_init(&est, &cfg));
    int differ = 0;
    for (int k = 0; k < 5000; ++k) {
        /* when */
        (void)ladrc_hp_step(&est, (ladrc_real_t)(1.0 + 4.0 * sin(3.0 * DT_S * k)));
        const ladrc_real_t command = ladrc_hp_get_command(&est), estimate = ladrc_hp_get_estimate(&est);
        differ |= memcmp(&command, &estimate, sizeof command) != 0;
    }
    /* then */
    TEST_ASSERT_EQUAL_INT(0, differ);
    TEST_ASSERT_TRUE(ladrc_hp_get_weight(&est) > 0.0f); /* it did compensate */
}

static void test_lp_lead_is_n_at_once_and_unity_at_dc(void)
{
    /* given: LP with a 30 ms lag and 2 ticks to lead over, on a sample step */
    const double tau_eff = 0.03 + 2.0 * DT_S;
    const ladrc_lp_config_t cfg = lp_config_behind_motors();
    ladrc_lp_estimator_t est;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_lp_init(&est, &cfg));
    /* when: a still rate and a known input of -10 rad/s^2 (sample 10,
     * exact in float) for long enough for the RLS and the lead to settle */
    double command = 0.0;
    for (int k = 0; k < 3000; ++k) {
        (void)ladrc_lp_step(&est, 0.0f, -10.0f);
        command = lp_lead(&est);
    }
    const double settled = command;
    /* then: unit DC gain */
    TEST_ASSERT_FLOAT_WITHIN(LEAD_SETTLED_TOL * 10.0, ladrc_lp_get_estimate(&est), settled);
    /* and: a change of d_hat passes N-fold at first (one tick) */
    const double before = ladrc_lp_get_estimate(&est);
    (void)ladrc_lp_step(&est, 0.0f, -30.0f);
    const double jump = ladrc_lp_get_estimate(&est) - before;
    const double lead_jump = lp_lead(&est) - settled;
    printf("d_hat moved %.4f, command %.4f (N = %.1f, tau' = %.3f s)\n", jump, lead_jump, (double)LADRC_LP_LEAD_MAX,
           tau_eff);
    TEST_ASSERT_TRUE(jump > 1.0);
    TEST_ASSERT_FLOAT_WITHIN(LEAD_SETTLED_TOL * 30.0 * LADRC_LP_LEAD_MAX, LADRC_LP_LEAD_MAX * jump, lead_jump);
    /* and: back to d_hat within float rounding after 20 tau' / N */
    for (int k = 0; k < (int)(20.0 * tau_eff / LADRC_LP_LEAD_MAX / DT_S) + 3000; ++k) {
        (void)ladrc_lp_step(&est, 0.0f, -30.0f);
        command = lp_lead(&est);
    }
    TEST_ASSERT_FLOAT_WITHIN(LEAD_SETTLED_TOL * 30.0, ladrc_lp_get_estimate(&est), command);
    /* and: without an actuator the lead is d_hat itself */
    const ladrc_lp_config_t plain_cfg = {.dt_s = (ladrc_real_t)DT_S,
                                         .lambda0_per_s = 100.0f,
                                         .k0_per_s = 300.0f,
                                         .act_tau_s = 0.0f,
                                         .act_delay_ticks = 0u};
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_lp_init(&est, &plain_cfg));
    int differ = 0;
    for (int k = 0; k < 100; ++k) {
        (void)ladrc_lp_step(&est, 0.0f, (ladrc_real_t)(-10.0 * k));
        const ladrc_real_t lead = lp_lead(&est), d_hat = ladrc_lp_get_estimate(&est);
        differ |= memcmp(&lead, &d_hat, sizeof lead) != 0;
    }
    TEST_ASSERT_EQUAL_INT(0, differ);
    /* and: the field checks */
    ladrc_lp_config_t bad = cfg;
    bad.act_tau_s = -1.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MOTOR_TAU_S, ladrc_lp_init(&est, &bad));
    bad = cfg;
    bad.act_delay_ticks = (uint16_t)(LADRC_MAX_DELAY_TICKS + 1u);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DELAY_TICKS, ladrc_lp_init(&est, &bad));
    ladrc_hp_config_t hbad = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    static ladrc_hp_estimator_t hp;
    hbad.act_tau_s = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MOTOR_TAU_S, ladrc_hp_init(&hp, &hbad));
    hbad = hp_config(LADRC_HP_FREQ_KNOWN, 3.0);
    hbad.act_delay_ticks = (uint16_t)(LADRC_MAX_DELAY_TICKS + 1u);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DELAY_TICKS, ladrc_hp_init(&hp, &hbad));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hp_online_finds_frequency_and_amplitude_across_the_range);
    RUN_TEST(test_hp_online_frequency_is_exact_for_a_lone_tone_whatever_its_bias);
    RUN_TEST(test_hp_online_resolves_two_tones);
    RUN_TEST(test_hp_online_reconverges_after_the_papers_frequency_jump);
    RUN_TEST(test_hp_known_frequency_fits_the_amplitude_and_opens_the_gate);
    RUN_TEST(test_hp_fits_on_the_tick_its_phase_names);
    RUN_TEST(test_hp_undoes_the_observer_lag_of_its_samples);
    RUN_TEST(test_hp_undoes_the_block_mean_and_the_age_of_its_samples);
    RUN_TEST(test_lp_gives_its_sample_and_hands_over_past_its_lead);
    RUN_TEST(test_hp_hands_over_what_the_weight_moves);
    RUN_TEST(test_hp_online_stays_bounded_with_noise);
    RUN_TEST(test_hp_gate_stays_shut_on_noise_without_a_tone);
    RUN_TEST(test_hp_non_finite_samples_are_skipped_and_flagged);
    RUN_TEST(test_hp_getters_of_tones_out_of_range_give_zero);
    RUN_TEST(test_hp_fit_is_readable_and_its_trace_stays_within_the_bound);
    RUN_TEST(test_hp_invalid_fields_are_rejected);
    RUN_TEST(test_lp_tracks_the_measured_acceleration_minus_the_known_input);
    RUN_TEST(test_lp_bandwidth_is_lambda0_k0_over_their_sum);
    RUN_TEST(test_lp_rate_gap_restarts_the_difference);
    RUN_TEST(test_lp_invalid_fields_are_rejected);
    RUN_TEST(test_hp_command_is_the_estimate_turned_by_the_inverse_actuator);
    RUN_TEST(test_hp_command_turned_over_a_long_delay_is_the_trig_formula);
    RUN_TEST(test_hp_without_actuator_command_is_the_estimate_bit_for_bit);
    RUN_TEST(test_lp_lead_is_n_at_once_and_unity_at_dc);
    return UNITY_END();
}
