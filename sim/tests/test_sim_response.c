/* SPDX-License-Identifier: BSD-3-Clause */
/* The field's views of a log (log/response.h) on systems whose answers are
 * known: the step response deconvolved from a closed loop flown with a
 * pilot's steps and gyro noise, the frequency response of a known filter,
 * and the noise against throttle of a tone that grows with throttle. */
#include "unity.h"
#include "run/fft.h"
#include "log/response.h"
#include "plant/rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define DT_S 0.001
#define FLIGHT_S 120.0 /* two minutes: some 230 windows of 2 s every 0.5 s */

/* |got - want| <= tol, printing the three when not (the shim has no double asserts). */
#define TEST_ASSERT_DOUBLE_WITHIN(tol, want, got) check_within((tol), (want), (got), #got, __LINE__)
static void check_within(double tol, double want, double got, const char *what, int line)
{
    if (!(fabs(got - want) <= tol)) {
        printf("line %d: %s = %.6g, expected %.6g +- %.3g\n", line, what, got, want, tol);
    }
    TEST_ASSERT_TRUE_MESSAGE(fabs(got - want) <= tol, what);
}

void setUp(void)
{
}
void tearDown(void)
{
}

/* A closed rate loop of known response: a second-order loop (natural
 * frequency wn, damping zeta, discretised by forward Euler at 1 kHz) behind
 * `delay` ticks, the measured rate plus white gyro noise. */
typedef struct {
    double wn_rad_s, zeta;
    int delay;
    double y, v;     /* rate, its derivative */
    double hist[64]; /* the reference, delayed */
    long long k;
} loop_t;

static double loop_step(loop_t *l, double ref)
{
    l->hist[l->k % 64] = ref;
    const double r = l->k >= l->delay ? l->hist[(l->k - l->delay) % 64] : 0.0;
    const double acc = l->wn_rad_s * l->wn_rad_s * (r - l->y) - 2.0 * l->zeta * l->wn_rad_s * l->v;
    l->y += DT_S * l->v;
    l->v += DT_S * acc;
    l->k++;
    return l->y;
}

/* The loop's exact step response over n ticks (the truth the deconvolution should find). */
static void loop_truth(loop_t proto, double *step, int n)
{
    loop_t l = proto;
    for (int i = 0; i < n; ++i) {
        step[i] = loop_step(&l, 1.0);
    }
}

static void sample_init(sim_log_sample_t *s)
{
    memset(s, 0, sizeof *s);
    s->throttle = 0.5;
}

/* A pilot's steps (steps = 1: a new rate every 0.15-0.8 s, uniform in
 * +-400 deg/s) or white noise (steps = 0: 200 deg/s rms, a new value every
 * tick), on every axis (independent), flown through the loop with gyro noise. */
static sim_response_t *fly(loop_t proto, int steps, double noise_deg_s, uint64_t seed)
{
    sim_response_t *r = sim_response_new(DT_S);
    TEST_ASSERT_NOT_NULL(r);
    sim_rng_t rng;
    sim_rng_seed(&rng, seed);
    loop_t loops[3] = {proto, proto, proto};
    double ref[3] = {0.0, 0.0, 0.0}, next_s[3] = {0.0, 0.0, 0.0};
    sim_log_sample_t s;
    sample_init(&s);
    const unsigned has = SIM_LOG_HAS_GYRO | SIM_LOG_HAS_REF_RATE | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_THROTTLE;
    const long long n = (long long)(FLIGHT_S / DT_S);
    for (long long k = 0; k < n; ++k) {
        const double t = k * DT_S;
        for (int a = 0; a < 3; ++a) {
            if (!steps) {
                ref[a] = 200.0 * DEG * sim_rng_gauss(&rng);
            } else if (t >= next_s[a]) {
                ref[a] = (2.0 * sim_rng_uniform(&rng) - 1.0) * 400.0 * DEG;
                next_s[a] = t + 0.15 + 0.65 * sim_rng_uniform(&rng);
            }
            s.ref_rate_rad_s[a] = ref[a];
            s.gyro_rad_s[a] = loop_step(&loops[a], ref[a]) + noise_deg_s * DEG * sim_rng_gauss(&rng);
            s.command[a] = 0.0;
        }
        s.t_s = t;
        sim_response_push(r, &s, has);
    }
    return r;
}

/* The figures of the deconvolved step against the truth's. Tolerances: the
 * regulariser passes the input's content up to 25 Hz, so the step found is
 * the truth through a low-pass there (an edge some 0.35 / 25 Hz = 14 ms
 * wide, +2-10 % on a rise of 30-70 ms, a rounded peak), and the Hann taper
 * multiplies the gyro after the loop's lag, not the setpoint before it,
 * which reads low by about the loop's mean delay over the window's taper
 * (measured: steady 0.966 and rise -9 % for the slow loop, 0.989 and 0 %
 * for the fast one): 15 % on the rise time, 5 ms on the delay, 5 points of
 * overshoot, 5 % on the steady value. */
#define RISE_TOL 0.15
#define DELAY_TOL_S 0.005
#define OVERSHOOT_TOL 0.05
#define STEADY_TOL 0.05

static void check_step(loop_t proto, double noise_deg_s)
{
    sim_response_t *r = fly(proto, 1, noise_deg_s, 7);
    static double truth[1024];
    sim_step_response_t got, want;
    sim_response_step(r, 0, &got);
    TEST_ASSERT_TRUE(got.n <= 1024);
    loop_truth(proto, truth, got.n);
    /* the deconvolved step starts at t = 0 with the ref's own sample: the loop's output lags one tick more */
    sim_step_figures(truth, got.n, DT_S, &want);
    printf("windows %d (rejected %d): steady %.3f, rise %.1f ms (truth %.1f), delay %.1f ms (%.1f), overshoot %.1f %% "
           "(%.1f)\n",
           got.windows, got.rejected, got.steady, 1e3 * got.rise_s, 1e3 * want.rise_s, 1e3 * got.delay_s,
           1e3 * want.delay_s, 100.0 * got.overshoot, 100.0 * want.overshoot);
    TEST_ASSERT_TRUE_MESSAGE(got.windows > 150, "most windows pass the 20 deg/s gate and the quality check");
    TEST_ASSERT_DOUBLE_WITHIN(STEADY_TOL, 1.0, got.steady);
    TEST_ASSERT_DOUBLE_WITHIN(RISE_TOL * want.rise_s, want.rise_s, got.rise_s);
    TEST_ASSERT_DOUBLE_WITHIN(DELAY_TOL_S, want.delay_s, got.delay_s);
    TEST_ASSERT_DOUBLE_WITHIN(OVERSHOOT_TOL, want.overshoot, got.overshoot);
    /* the spread over windows is small against the step, and not zero (noise) */
    double spread = 0.0;
    for (int i = 0; i < got.n; ++i) {
        spread = fmax(spread, got.spread[i]);
    }
    TEST_ASSERT_TRUE(spread > 0.0 && spread < 0.3);
    sim_response_free(r);
}

static void test_the_step_of_a_well_damped_loop_with_delay_is_recovered(void)
{
    const loop_t l = {.wn_rad_s = 2.0 * PI * 6.0, .zeta = 0.9, .delay = 10};
    check_step(l, 3.0);
}

static void test_the_step_of_an_underdamped_loop_shows_its_overshoot(void)
{
    const loop_t l = {.wn_rad_s = 2.0 * PI * 8.0, .zeta = 0.45, .delay = 4};
    check_step(l, 3.0);
}

static void test_a_flight_under_20_deg_s_gives_no_window(void)
{
    /* hovering: the setpoint within +-15 deg/s */
    const loop_t l = {.wn_rad_s = 2.0 * PI * 6.0, .zeta = 0.9, .delay = 10};
    sim_response_t *r = sim_response_new(DT_S);
    loop_t lp = l;
    sim_log_sample_t s;
    sample_init(&s);
    for (long long k = 0; k < 20000; ++k) {
        s.ref_rate_rad_s[0] = 15.0 * DEG * sin(2.0 * PI * 0.5 * k * DT_S);
        s.gyro_rad_s[0] = loop_step(&lp, s.ref_rate_rad_s[0]);
        sim_response_push(r, &s, SIM_LOG_HAS_GYRO | SIM_LOG_HAS_REF_RATE);
    }
    sim_step_response_t got;
    sim_response_step(r, 0, &got);
    TEST_ASSERT_EQUAL_INT(0, got.windows);
    TEST_ASSERT_TRUE(isnan(got.rise_s) && isnan(got.mean[0]));
    TEST_ASSERT_EQUAL_INT(0, (int)sim_response_freq_segments(r, 0));
    sim_response_free(r);
}

/* The frequency response of the loop, exactly: y/r = wn^2 dt^2 z^-(d+1) / den(z)
 * for the Euler scheme above (y' = v, v' = wn^2 (r - y) - 2 zeta wn v), times
 * z: a tick's sample is the rate after that tick's update. */
static void loop_exact(const loop_t *l, double hz, double *gain, double *phase)
{
    const double w = 2.0 * PI * hz * DT_S, a = l->wn_rad_s * DT_S, b = 2.0 * l->zeta * l->wn_rad_s * DT_S;
    /* y[k+1] = y + dt v; v[k+1] = v + dt (wn^2 (r[k-d] - y) - 2 zeta wn v):
     * (z - 1) Y = dt V; (z - 1 + b) V = dt wn^2 (z^-d R - Y) => Y (z-1)(z-1+b) / dt^2 + wn^2 Y = wn^2 z^-d R */
    const double zr = cos(w), zi = sin(w);
    const double p_r = zr - 1.0, p_i = zi, q_r = zr - 1.0 + b, q_i = zi;
    const double den_r = p_r * q_r - p_i * q_i + a * a, den_i = p_r * q_i + p_i * q_r;
    const double num_r = a * a * cos(-w * (l->delay - 1)), num_i = a * a * sin(-w * (l->delay - 1));
    const double mag2 = den_r * den_r + den_i * den_i;
    const double h_r = (num_r * den_r + num_i * den_i) / mag2, h_i = (num_i * den_r - num_r * den_i) / mag2;
    *gain = sqrt(h_r * h_r + h_i * h_i);
    *phase = atan2(h_i, h_r);
}

/* Tolerances where the coherence exceeds 0.9: Welch's H1 of 1 s segments
 * against the exact response, the input white (a pilot's steps, whose
 * spectrum falls as 1/f^2, leak into the lowest bins through the Hann
 * window: 4 deg of phase at 2 Hz on this loop); its bias is the leakage of
 * a response that dies out in 0.1 s (well under 1 % here) and its scatter
 * sqrt((1 - coh) / (2 n coh)) over n some 200 segments: at coherence 0.9,
 * 1.7 %. 5 % on the gain and 3 deg on the phase hold both with margin. */
#define GAIN_TOL 0.05
#define PHASE_TOL_DEG 3.0

static void test_the_frequency_response_of_a_known_loop_within_tolerance_where_coherent(void)
{
    const loop_t l = {.wn_rad_s = 2.0 * PI * 8.0, .zeta = 0.45, .delay = 4};
    sim_response_t *r = fly(l, 0, 3.0, 11);
    const int bins = sim_response_freq_bins(r);
    TEST_ASSERT_EQUAL_INT(513, bins);
    TEST_ASSERT_TRUE(sim_response_freq_segments(r, 0) > 150);
    int checked = 0;
    for (int k = 1; k < bins; ++k) {
        double hz, gain, phase, coh, g0, p0;
        sim_response_freq(r, 0, k, &hz, &gain, &phase, &coh);
        if (!(coh > 0.9)) {
            continue;
        }
        loop_exact(&l, hz, &g0, &p0);
        TEST_ASSERT_DOUBLE_WITHIN(GAIN_TOL * g0, g0, gain);
        const double dphase = remainder(phase - p0, 2.0 * PI) / DEG;
        TEST_ASSERT_DOUBLE_WITHIN(PHASE_TOL_DEG, 0.0, dphase);
        checked++;
    }
    /* coherent from the lowest bins up past the loop's bandwidth (8 Hz), to where the
     * loop's roll-off leaves the gyro noise (3 deg/s) dominant */
    TEST_ASSERT_TRUE_MESSAGE(checked >= 30, "coherence above 0.9 over at least 30 bins");
    sim_response_free(r);
}

/* A 120 Hz tone on the gyro whose amplitude is 10 deg/s times the throttle,
 * the throttle ramping 0 to 1: each tenth's spectrum holds the tone at its
 * mean amplitude there. The tone's rms from the PSD: the sum over its peak's
 * bins (Hann: the line spreads over 4) within 10 % (the throttle changes
 * by 1/30 of a bin within a segment). */
#define TONE_RMS_TOL 0.10

static void test_the_noise_against_throttle_puts_a_growing_tone_in_its_bins(void)
{
    sim_response_t *r = sim_response_new(DT_S);
    sim_log_sample_t s;
    sample_init(&s);
    const long long n = 60000;
    for (long long k = 0; k < n; ++k) {
        s.throttle = (double)k / (double)n;
        for (int a = 0; a < 3; ++a) {
            s.gyro_rad_s[a] = 10.0 * DEG * s.throttle * sin(2.0 * PI * 120.0 * k * DT_S);
            s.command[a] = 0.01 * s.throttle * sin(2.0 * PI * 120.0 * k * DT_S);
        }
        sim_response_push(r, &s, SIM_LOG_HAS_GYRO | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_THROTTLE);
    }
    const int bins = sim_response_noise_bins(r);
    const double df = sim_response_noise_hz(r, 1);
    TEST_ASSERT_TRUE(isnan(sim_response_noise_psd(r, SIM_NOISE_GYRO_RAW, 0, 5, 10)));
    for (int b = 1; b < SIM_RESPONSE_THROTTLE_BINS; ++b) {
        TEST_ASSERT_TRUE(sim_response_noise_segments(r, b) > 40);
        int peak = 0;
        double power = 0.0;
        for (int k = 0; k < bins; ++k) {
            const double p = sim_response_noise_psd(r, SIM_NOISE_GYRO, 1, b, k);
            if (p > sim_response_noise_psd(r, SIM_NOISE_GYRO, 1, b, peak)) {
                peak = k;
            }
        }
        TEST_ASSERT_DOUBLE_WITHIN(df, 120.0, sim_response_noise_hz(r, peak));
        for (int k = peak - 3; k <= peak + 3; ++k) {
            power += sim_response_noise_psd(r, SIM_NOISE_GYRO, 1, b, k) * df;
        }
        const double want_rms = 10.0 * DEG * (b + 0.5) / SIM_RESPONSE_THROTTLE_BINS / sqrt(2.0);
        TEST_ASSERT_DOUBLE_WITHIN(TONE_RMS_TOL * want_rms, want_rms, sqrt(power));
    }
    sim_response_free(r);
}

static void test_the_fft_inverts_itself_and_matches_a_direct_dft(void)
{
    enum { N = 64 };
    double tw_re[N / 2], tw_im[N / 2], re[N], im[N], x[N];
    sim_fft_twiddles(N, tw_re, tw_im);
    for (int i = 0; i < N; ++i) {
        x[i] = sin(0.3 * i) + 0.1 * i;
        re[i] = x[i];
        im[i] = 0.0;
    }
    sim_fft(N, tw_re, tw_im, re, im);
    for (int k = 0; k < N; ++k) { /* a direct DFT, to rounding (1e-9 over 64 terms of size 7) */
        double dr = 0.0, di = 0.0;
        for (int j = 0; j < N; ++j) {
            dr += x[j] * cos(2.0 * PI * j * k / N);
            di -= x[j] * sin(2.0 * PI * j * k / N);
        }
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, dr, re[k]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-9, di, im[k]);
    }
    sim_fft_inverse(N, tw_re, tw_im, re, im);
    for (int i = 0; i < N; ++i) {
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, x[i], re[i]);
        TEST_ASSERT_DOUBLE_WITHIN(1e-12, 0.0, im[i]);
    }
    TEST_ASSERT_EQUAL_INT(4096, sim_fft_size(2501));
    TEST_ASSERT_EQUAL_INT(1024, sim_fft_size(1024));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_the_fft_inverts_itself_and_matches_a_direct_dft);
    RUN_TEST(test_the_step_of_a_well_damped_loop_with_delay_is_recovered);
    RUN_TEST(test_the_step_of_an_underdamped_loop_shows_its_overshoot);
    RUN_TEST(test_a_flight_under_20_deg_s_gives_no_window);
    RUN_TEST(test_the_frequency_response_of_a_known_loop_within_tolerance_where_coherent);
    RUN_TEST(test_the_noise_against_throttle_puts_a_growing_tone_in_its_bins);
    return UNITY_END();
}
