/* SPDX-License-Identifier: BSD-3-Clause */
/* The gyro filter stage proposed from a spectrum (log/filter_proposal.h)
 * on synthetic gyro noise with known lines, the stage's response against
 * the library's documented corners, and the phase probe of a chain
 * (log/log_noise.h) on a known delay. */
#include "unity.h"
#include "log/airframe.h"
#include "log/filter_proposal.h"
#include "log/log_noise.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DT_S 0.001
#define SECONDS 60.0
/* The spectrum's bins are fs / 1024 = 0.98 Hz apart: a line's centre is found within one bin. */
#define CENTRE_TOL_HZ 0.98
/* The bisection on the low-pass corner ends on the budget; the corner and
 * the sections' coefficients are then rounded to ladrc_real_t (float:
 * 6e-8 relative), which moves the phase at the crossover by 1e-5 deg (8e-6
 * measured): 1e-4 deg. */
#define BUDGET_TOL_DEG 1e-4
/* The band holds the two lines (0.625 (rad/s)^2) over the white floor's
 * 0.0076 (rad/s)^2 there: notching the lines alone removes up to 19 dB;
 * 15 dB leaves room for their skirts the notches' width misses. */
#define BAND_ATTENUATION_MIN_DB 15.0
/* The bilinear low-pass is -3 dB at its corner exactly (prewarped); its
 * coefficients are float (6e-8 relative each), and the gain there moves by a
 * few of them: 1e-6. */
#define RESPONSE_TOL 1e-6
/* A pure delay of 3 ticks is -0.09 rad at 30 rad/s. The windows of x and
 * of the delayed y are 3 samples apart, so the stream's much stronger
 * content below the probe (a 1.6 Hz corner) leaks into the two by
 * different amounts: 2.6 % of the phase measured; 0.005 rad (5.6 %) allows
 * it and still tells 3 ticks from 2 or 4 (0.03 rad apart). */
#define PHASE_TOL_RAD 0.005

static sim_spectrum_t spectra[3];

void setUp(void)
{
}
void tearDown(void)
{
}

/* A uniform deviate in [-0.5, 0.5) of a fixed generator (xorshift64*). */
static double uniform(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return (double)((*s * 2685821657736338717ull) >> 11) / 9007199254740992.0 - 0.5;
}

/* Three axes of white noise (0.2 rad/s rms) and lines at the given
 * frequencies (rad/s amplitude each). */
static void synthetic(const double *hz, const double *amp, int n_lines)
{
    uint64_t seed = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&spectra[i], 1.0 / DT_S);
    }
    for (long k = 0; k < (long)(SECONDS / DT_S); ++k) {
        const double t = (double)k * DT_S;
        for (int i = 0; i < 3; ++i) {
            double x = 0.2 * sqrt(12.0) * uniform(&seed);
            for (int j = 0; j < n_lines; ++j) {
                x += amp[j] * sin(2.0 * PI * hz[j] * t + 0.7 * i + j);
            }
            sim_spectrum_push(&spectra[i], x);
        }
    }
}

static void test_notches_at_the_lines_and_a_lowpass_within_the_budget(void)
{
    const double hz[2] = {70.3, 161.1}, amp[2] = {1.0, 0.5};
    synthetic(hz, amp, 2);
    static sim_filter_proposal_t p;
    char why[256];
    TEST_ASSERT_EQUAL_INT(0, sim_filter_propose(spectra, DT_S, 0.0, 0, 30.0, &p, why, sizeof why));
    TEST_ASSERT_EQUAL_UINT(2, p.cfg.n_notches);
    TEST_ASSERT_EQUAL_UINT(0, p.cfg.rpm_rotors);
    for (int j = 0; j < 2; ++j) {
        double nearest = INFINITY;
        for (int k = 0; k < p.cfg.n_notches; ++k) {
            nearest = fmin(nearest, fabs((double)p.cfg.notch_hz[k] - hz[j]));
        }
        TEST_ASSERT_TRUE_MESSAGE(nearest <= CENTRE_TOL_HZ, "a notch at each line");
    }
    TEST_ASSERT_TRUE(p.cfg.notch_q >= SIM_FILTER_Q_MIN && p.cfg.notch_q <= SIM_FILTER_Q_MAX);
    TEST_ASSERT_TRUE(p.band_lo_hz < hz[0] && p.band_hi_hz > hz[1]);
    /* the low-pass is the lowest within the budget: on it, not below it */
    TEST_ASSERT_EQUAL_UINT(2, p.cfg.lpf_order);
    TEST_ASSERT_FLOAT_WITHIN(BUDGET_TOL_DEG, SIM_FILTER_PHASE_BUDGET_DEG, sim_filter_phase_cost_deg(&p.cfg, 0.0, 30.0));
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(sim_filter_band_attenuation_db(&p.cfg, 0.0, &spectra[i], p.band_lo_hz, p.band_hi_hz) >=
                         BAND_ATTENUATION_MIN_DB);
    }
}

static void test_lines_on_the_rotor_harmonics_go_to_the_rpm_bank(void)
{
    const double hz[3] = {80.0, 160.0, 123.4}, amp[3] = {1.0, 0.6, 0.4};
    synthetic(hz, amp, 3);
    static sim_filter_proposal_t p;
    char why[256];
    TEST_ASSERT_EQUAL_INT(0, sim_filter_propose(spectra, DT_S, 80.0, 4, 30.0, &p, why, sizeof why));
    TEST_ASSERT_EQUAL_UINT(4, p.cfg.rpm_rotors);
    TEST_ASSERT_EQUAL_UINT(2, p.cfg.rpm_harmonics);
    TEST_ASSERT_EQUAL_UINT(1, p.cfg.n_notches); /* the line off the harmonics */
    TEST_ASSERT_FLOAT_WITHIN(CENTRE_TOL_HZ, 123.4, (double)p.cfg.notch_hz[0]);
    double g, ph;
    TEST_ASSERT_EQUAL_INT(0, sim_filter_response(&p.cfg, 80.0, 160.0, &g, &ph));
    TEST_ASSERT_TRUE_MESSAGE(g < 1e-6, "the RPM notch's zero at the second harmonic");
}

static void test_white_noise_gives_no_notch(void)
{
    synthetic(NULL, NULL, 0);
    static sim_filter_proposal_t p;
    char why[256];
    TEST_ASSERT_EQUAL_INT(0, sim_filter_propose(spectra, DT_S, 0.0, 0, 30.0, &p, why, sizeof why));
    TEST_ASSERT_EQUAL_UINT(0, p.cfg.n_notches);
    TEST_ASSERT_EQUAL_INT(0, p.n_lines);
    double lo, hi;
    sim_airframe_floor_band(1.0 / DT_S, &lo, &hi);
    TEST_ASSERT_EQUAL_FLOAT(lo, p.band_lo_hz);
    TEST_ASSERT_EQUAL_FLOAT(hi, p.band_hi_hz);
}

static void test_a_log_that_tells_no_crossover_gets_no_lowpass(void)
{
    /* a still log tells no lag, so no crossover (NaN): no low-pass is proposed, not a NaN corner
     * the gyro filter would refuse */
    synthetic(NULL, NULL, 0);
    static sim_filter_proposal_t p;
    char why[256];
    TEST_ASSERT_EQUAL_INT(0, sim_filter_propose(spectra, DT_S, 0.0, 0, NAN, &p, why, sizeof why));
    TEST_ASSERT_EQUAL_UINT(0, p.cfg.lpf_order);
    ladrc_gyro_filter_t f;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_gyro_filter_init(&f, &p.cfg));
}

/* The crossover of an identified lag and delay; none (NAN) for a lag or a
 * delay the identification could not tell (a log where nothing moves gave
 * -2000 rad/s from a delay of -1 tick). */
static void test_the_crossover_estimate_only_from_an_identified_lag_and_delay(void)
{
    TEST_ASSERT_TRUE(fabs(sim_filter_crossover_estimate(0.03, 2, 1e-3) - 1.0 / (0.03 + 2.5e-3)) < 1e-9);
    TEST_ASSERT_TRUE(isnan(sim_filter_crossover_estimate(NAN, 2, 1e-3)));
    TEST_ASSERT_TRUE(isnan(sim_filter_crossover_estimate(0.03, -1, 1e-3)));
    TEST_ASSERT_TRUE(isnan(sim_filter_crossover_estimate(-0.01, 2, 1e-3)));
    TEST_ASSERT_TRUE(isnan(sim_filter_crossover_estimate(0.03, 2, 0.0)));
}

static void test_too_short_a_log_is_refused(void)
{
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&spectra[i], 1.0 / DT_S);
    }
    static sim_filter_proposal_t p;
    char why[256] = "";
    TEST_ASSERT_EQUAL_INT(-1, sim_filter_propose(spectra, DT_S, 0.0, 0, 30.0, &p, why, sizeof why));
    TEST_ASSERT_NOT_NULL(strstr(why, "shorter than one spectrum segment"));
}

static void test_response_matches_the_documented_corners(void)
{
    ladrc_gyro_filter_config_t cfg;
    ladrc_gyro_filter_config_default(&cfg, DT_S, 3);
    cfg.lpf_order = 2;
    cfg.lpf_cutoff_hz = 100.0;
    double g, ph;
    TEST_ASSERT_EQUAL_INT(0, sim_filter_response(&cfg, 0.0, 100.0, &g, &ph));
    TEST_ASSERT_FLOAT_WITHIN(RESPONSE_TOL, 1.0 / sqrt(2.0), g);
    TEST_ASSERT_FLOAT_WITHIN(RESPONSE_TOL, -PI / 2.0, ph); /* a second-order Butterworth's -90 deg at its corner */
    cfg.lpf_order = 0;
    cfg.n_notches = 1;
    cfg.notch_hz[0] = 150.0;
    TEST_ASSERT_EQUAL_INT(0, sim_filter_response(&cfg, 0.0, 150.0, &g, &ph));
    TEST_ASSERT_TRUE(g < 1e-6);
    cfg.notch_q = -1.0; /* refused by the library */
    TEST_ASSERT_EQUAL_INT(-1, sim_filter_response(&cfg, 0.0, 150.0, &g, &ph));
}

static void test_phase_probe_of_a_delayed_stream(void)
{
    static sim_phase_probe_t probe;
    const double w_rad_s = 30.0;
    sim_phase_probe_init(&probe, w_rad_s, DT_S);
    uint64_t seed = 12345u;
    double x[4] = {0, 0, 0, 0};
    double smooth = 0.0;
    for (int k = 0; k < 20000; ++k) {
        smooth = 0.99 * smooth + uniform(&seed); /* content at the probe's frequency */
        memmove(x + 1, x, 3 * sizeof x[0]);
        x[0] = smooth;
        sim_phase_probe_push(&probe, smooth, x[3]); /* y three ticks behind */
    }
    TEST_ASSERT_FLOAT_WITHIN(PHASE_TOL_RAD, -3.0 * w_rad_s * DT_S, sim_phase_probe_rad(&probe));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_notches_at_the_lines_and_a_lowpass_within_the_budget);
    RUN_TEST(test_lines_on_the_rotor_harmonics_go_to_the_rpm_bank);
    RUN_TEST(test_white_noise_gives_no_notch);
    RUN_TEST(test_a_log_that_tells_no_crossover_gets_no_lowpass);
    RUN_TEST(test_the_crossover_estimate_only_from_an_identified_lag_and_delay);
    RUN_TEST(test_too_short_a_log_is_refused);
    RUN_TEST(test_response_matches_the_documented_corners);
    RUN_TEST(test_phase_probe_of_a_delayed_stream);
    return UNITY_END();
}
