/* SPDX-License-Identifier: BSD-3-Clause */
/* Predicted command noise (margins.h, cmd_noise_Nm) against the same loop
 * flown with white measurement noise, and the tuner's noise cap. */
#include "unity.h"
#include "ladrc/margins.h"
#include "../margins_internal.h" /* margins_fft */

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846

/* Flown samples per case: 2^18 ticks (262 s at 1 kHz) after a settling run. */
#define LOG2_N 18
#define N_SAMPLES (1L << LOG2_N)
#define SETTLE_TICKS 20000L
/* Tolerance of the prediction against the flight. The flight's mean square
 * above the corner is an estimate over N samples of a coloured process: its
 * relative standard deviation is sqrt(2 / N_eff), N_eff the number of
 * independent spectral bins in the band (some 0.96 N here, the band's share
 * of the spectrum, less where a resonance concentrates the power: at worst
 * a few thousand bins), so the RMS scatters by sqrt(1 / (2 N_eff)), below
 * 1.5 % even at 2000 bins. The float controller's rounding (relative 6e-8)
 * and the measured response's 1e-4 add nothing visible. 5 % is over three
 * standard deviations of the worst case. */
#define NOISE_REL_TOL 0.05

static ladrc_margins_workspace_t ws;
static ladrc_margins_result_t res;
static double cmd[N_SAMPLES];
static double fre[N_SAMPLES], fim[N_SAMPLES];

void setUp(void)
{
}
void tearDown(void)
{
}

/* A small Gaussian generator of its own (xorshift64*, Box-Muller). */
static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static double uniform01(void)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return ((double)((rng_state * 2685821657736338717u) >> 11) + 0.5) / 9007199254740992.0;
}
static double gauss(void)
{
    return sqrt(-2.0 * log(uniform01())) * cos(2.0 * PI * uniform01());
}

/* RMS of x above f_hz: the periodogram's bins from the corner to the
 * Nyquist frequency (an ideal high-pass, as the prediction's band). */
static double rms_above(const double *x, long n, double dt, double f_hz)
{
    for (long i = 0; i < n; ++i) {
        fre[i] = x[i];
        fim[i] = 0.0;
    }
    margins_fft(fre, fim, (int)n);
    const long m0 = (long)ceil(f_hz * dt * (double)n);
    double sum = 0.0;
    for (long m = m0; m <= n / 2; ++m) {
        const double p = fre[m] * fre[m] + fim[m] * fim[m];
        sum += (m == n / 2) ? p : 2.0 * p;
    }
    return sqrt(sum) / (double)n;
}

/* The rigid axis with a first-order torque lag and no drag, exactly
 * discretised (zero-order hold), measured delay ticks late; the controller
 * (the library's own) sees the measurements plus white noise. */
typedef struct {
    double theta, omega, tau;
    double hist[64][2];
    int head;
} flight_t;

static double fly(const ladrc_axis_config_t *cfg, const ladrc_margins_plant_t *p, double sa, double sr)
{
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, cfg));
    const double t = p->dt_s, j = p->inertia_kg_m2 * p->inertia_factor, lag = p->motor_tau_s;
    const double a = exp(-t / lag), g = lag * (1.0 - a);
    flight_t f;
    memset(&f, 0, sizeof f);
    for (long k = 0; k < SETTLE_TICKS + N_SAMPLES; ++k) {
        f.hist[f.head][0] = f.theta;
        f.hist[f.head][1] = f.omega;
        const int idx = (f.head - p->delay_ticks + 64) % 64;
        f.head = (f.head + 1) % 64;
        const ladrc_real_t rate = (ladrc_real_t)(f.hist[idx][1] + sr * gauss());
        const double angle = f.hist[idx][0] + sa * gauss();
        ladrc_real_t u_f;
        (void)ladrc_axis_step(&axis, LADRC_R(0.0), (ladrc_real_t)angle, &rate, &u_f);
        const double u = (double)u_f;
        if (k >= SETTLE_TICKS)
            cmd[k - SETTLE_TICKS] = u;
        /* tau' = (u - tau) / lag, omega' = tau / J, theta' = omega over one held tick */
        const double theta = f.theta + f.omega * t + (f.tau * lag * (t - g) + u * (t * t / 2.0 - lag * (t - g))) / j;
        const double omega = f.omega + (f.tau * g + u * (t - g)) / j;
        f.tau = a * f.tau + (1.0 - a) * u;
        f.theta = theta;
        f.omega = omega;
    }
    return rms_above(cmd, N_SAMPLES, t, 20.0);
}

static ladrc_margins_plant_t test_plant(void)
{
    const ladrc_margins_plant_t p = {.dt_s = 0.001,
                                     .inertia_kg_m2 = 5.445e-3,
                                     .inertia_factor = 1.0,
                                     .drag_Nm_s = 0.0,
                                     .motor_tau_s = 0.005,
                                     .delay_ticks = 1};
    return p;
}

static void check_case(ladrc_variant_t variant, double wc, double sa, double sr, const char *what)
{
    const ladrc_margins_plant_t p = test_plant();
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, variant, (ladrc_real_t)p.dt_s, (ladrc_real_t)p.inertia_kg_m2);
    if (variant == LADRC_VARIANT_LADRC) {
        cfg.wc_rad_s = (ladrc_real_t)wc;
        cfg.wo_rad_s = (ladrc_real_t)(5.0 * wc);
    }
    const ladrc_margins_controller_t ctl = {.axis = &cfg, .use_rate = 1};
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    req.angle_noise_std_rad = sa;
    req.rate_noise_std_rad_s = sr;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
    TEST_ASSERT_TRUE(res.stable);
    const double predicted = res.cmd_noise_Nm;
    const double flown = fly(&cfg, &p, sa, sr);
    printf("%s: predicted %.5g N m, flown %.5g N m (%+.2f %%)\n", what, predicted, flown,
           100.0 * (predicted / flown - 1.0));
    TEST_ASSERT_TRUE(predicted > 0.0);
    TEST_ASSERT_FLOAT_WITHIN(NOISE_REL_TOL * flown, flown, predicted);
}

/* LADRC reads the angle alone: the rate's noise does not reach it. */
static void test_ladrc_angle_noise_matches_the_flight(void)
{
    check_case(LADRC_VARIANT_LADRC, 20.0, 1e-3, 0.0, "LADRC wc 20, angle noise");
}

static void test_ladrc_angle_and_rate_noise_match_the_flight(void)
{
    check_case(LADRC_VARIANT_LADRC, 30.0, 1e-3, 0.01, "LADRC wc 30, angle and rate noise");
}

static void test_cascaded_noise_matches_the_flight(void)
{
    check_case(LADRC_VARIANT_CASCADED, 0.0, 1e-3, 0.02, "CASCADED default, angle and rate noise");
}

static void test_cascaded_rate_noise_matches_the_flight(void)
{
    check_case(LADRC_VARIANT_CASCADED, 0.0, 0.0, 0.02, "CASCADED default, rate noise");
}

static void test_no_noise_predicts_zero_and_bad_noise_is_refused(void)
{
    const ladrc_margins_plant_t p = test_plant();
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)p.dt_s, (ladrc_real_t)p.inertia_kg_m2);
    const ladrc_margins_controller_t ctl = {.axis = &cfg, .use_rate = 1};
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    TEST_ASSERT_TRUE((LADRC_MARGINS_NOISE_CORNER_HZ) == (req.noise_corner_hz));
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
    TEST_ASSERT_TRUE((0.0) == (res.cmd_noise_Nm));
    req.rate_noise_std_rad_s = -1.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_loop(&ws, &req, &res));
    req.rate_noise_std_rad_s = 0.01;
    req.noise_corner_hz = 500.0; /* the Nyquist frequency: no band */
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_loop(&ws, &req, &res));
    req.noise_corner_hz = 0.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_loop(&ws, &req, &res));
    /* Noise off: the corner is not looked at. */
    req.rate_noise_std_rad_s = 0.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_loop(&ws, &req, &res));
}

/* A coloured rate noise (rate_noise_psd) flat at white noise's density is
 * that white noise: the same prediction to the rounding of the sums (the
 * bins' linear interpolation of a flat PSD is exact; 1e-9 relative).
 * Zero below 100 Hz, it predicts less; a bad PSD is refused. */
#define PSD_REL_TOL 1e-9
static void test_a_coloured_rate_noise_is_its_spectrum(void)
{
    const ladrc_margins_plant_t p = test_plant();
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_CASCADED, (ladrc_real_t)p.dt_s, (ladrc_real_t)p.inertia_kg_m2);
    const ladrc_margins_controller_t ctl = {.axis = &cfg, .use_rate = 1};
    static ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    const double sr = 0.02, fs = 1.0 / p.dt_s;
    req.rate_noise_std_rad_s = sr;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
    const double white = res.cmd_noise_Nm;
    req.rate_noise_std_rad_s = 0.0;
    req.rate_noise_psd_bins = LADRC_MARGINS_NOISE_PSD_BINS;
    req.rate_noise_bin_hz = 0.5 * fs / (LADRC_MARGINS_NOISE_PSD_BINS - 1);
    for (int k = 0; k < LADRC_MARGINS_NOISE_PSD_BINS; ++k) {
        req.rate_noise_psd[k] = 2.0 * sr * sr / fs; /* one-sided: the variance over fs / 2 */
    }
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
    TEST_ASSERT_FLOAT_WITHIN(PSD_REL_TOL * white, white, res.cmd_noise_Nm);
    for (int k = 0; k < LADRC_MARGINS_NOISE_PSD_BINS; ++k) {
        if ((double)k * req.rate_noise_bin_hz < 100.0) {
            req.rate_noise_psd[k] = 0.0;
        }
    }
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
    TEST_ASSERT_TRUE(res.cmd_noise_Nm > 0.0 && res.cmd_noise_Nm < white);
    req.rate_noise_psd[3] = -1.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_loop(&ws, &req, &res));
    req.rate_noise_psd[3] = 0.0;
    req.rate_noise_psd_bins = 1;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_loop(&ws, &req, &res));
}

/* The cap lowers the bandwidth until the noise fits; a cap no setting meets
 * reports the closest miss. */
static void test_the_tuners_cap_lowers_the_bandwidth(void)
{
    const ladrc_margins_plant_t p = test_plant();
    ladrc_axis_config_t cfg, tuned;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)p.dt_s, (ladrc_real_t)p.inertia_kg_m2);
    const ladrc_margins_controller_t ctl = {.axis = &cfg, .use_rate = 1};
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    req.angle_noise_std_rad = 1e-3;
    req.rate_noise_std_rad_s = 0.02;
    static ladrc_margins_tuning_t free_tune, capped;
    const ladrc_margins_targets_t none = {.pm_min_deg = 45.0, .gm_min_db = 6.0};
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_tune(&ws, &ctl, &req, &none, &tuned, &free_tune));
    TEST_ASSERT_TRUE(free_tune.cmd_noise_Nm > 0.0);
    TEST_ASSERT_TRUE((free_tune.margins.cmd_noise_Nm) == (free_tune.cmd_noise_Nm));
    const ladrc_margins_targets_t half = {
        .pm_min_deg = 45.0, .gm_min_db = 6.0, .cmd_noise_max_Nm = 0.5 * free_tune.cmd_noise_Nm};
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_tune(&ws, &ctl, &req, &half, &tuned, &capped));
    printf("cap: free crossover %.4g rad/s noise %.4g N m; capped at %.4g: crossover %.4g rad/s noise %.4g N m\n",
           free_tune.margins.wc_rad_s, free_tune.cmd_noise_Nm, half.cmd_noise_max_Nm, capped.margins.wc_rad_s,
           capped.cmd_noise_Nm);
    TEST_ASSERT_TRUE(capped.met);
    TEST_ASSERT_TRUE(capped.cmd_noise_Nm <= half.cmd_noise_max_Nm);
    TEST_ASSERT_TRUE(capped.margins.wc_rad_s < free_tune.margins.wc_rad_s);
    /* Infinite or zero cap: none. */
    const ladrc_margins_targets_t inf_cap = {.pm_min_deg = 45.0, .gm_min_db = 6.0, .cmd_noise_max_Nm = INFINITY};
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_tune(&ws, &ctl, &req, &inf_cap, &tuned, &capped));
    TEST_ASSERT_TRUE((free_tune.wc_rad_s) == (capped.wc_rad_s));
    /* A cap below anything the search reaches: not met, a stable miss reported. */
    const ladrc_margins_targets_t tiny = {.pm_min_deg = 45.0, .gm_min_db = 6.0, .cmd_noise_max_Nm = 1e-12};
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_TARGETS_NOT_MET,
                          ladrc_margins_tune(&ws, &ctl, &req, &tiny, &tuned, &capped));
    TEST_ASSERT_FALSE(capped.met);
    TEST_ASSERT_TRUE(capped.margins.stable);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ladrc_angle_noise_matches_the_flight);
    RUN_TEST(test_ladrc_angle_and_rate_noise_match_the_flight);
    RUN_TEST(test_cascaded_noise_matches_the_flight);
    RUN_TEST(test_cascaded_rate_noise_matches_the_flight);
    RUN_TEST(test_no_noise_predicts_zero_and_bad_noise_is_refused);
    RUN_TEST(test_the_tuners_cap_lowers_the_bandwidth);
    RUN_TEST(test_a_coloured_rate_noise_is_its_spectrum);
    return UNITY_END();
}
