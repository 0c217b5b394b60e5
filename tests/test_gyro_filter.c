/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the gyro filter stage (gyro_filter.c): notch and low-pass
 * responses against their closed forms, the RPM bank, moving centres, the
 * fade and the Nyquist guard, init errors, faults, reset and channels. */
#include "unity.h"
#include "ladrc/gyro_filter.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DT_S 1e-3

/* Gains are measured on the running filter: a steady sinusoid of amplitude 1,
 * SETTLE_TICKS to let the transient die (the slowest section here, a Q = 5
 * notch at 50 Hz, has its poles at radius 1 - sin(w0)/(2 Q) = 1 - 0.016:
 * e^-32 after 2000 ticks), then a least-squares fit of a cos + b sin at the
 * input's frequency over FIT_TICKS. */
#define SETTLE_TICKS 2000
#define FIT_TICKS 4000

/* Measured against the closed form of the design (computed in double): the
 * float filter rounds its input (2^-24 relative) and each of its few
 * operations; the fit averages that over 4000 ticks. Measured below 2e-6;
 * 1e-4 of the unit amplitude leaves a margin of 50x. */
#define DESIGN_GAIN_TOL 1e-4

/* A notch's gain at its own centre. The design's is 0; the float notch's
 * zero lands off the centre by the rounding of w0 = 2 pi f0 dt and cos(w0),
 * a few 1e-8 rad, and |H| near the centre is that offset over alpha sin(w0)
 * (0.035 for 100 Hz, Q = 5, 1 kHz): about 1e-6, -120 dB (measured -111 dB).
 * -80 dB holds that with a margin of 30 dB and is far below the 40 dB asked. */
#define NOTCH_DEPTH_DB (-80.0)

/* Far from its centre a notch passes: gain within 1 % of 1 (the design's at
 * 10 and 400 Hz is 0.9998). */
#define FAR_GAIN_TOL 0.01

/* Where the notch's -3 dB points lie against f0 +- f0 / (2 Q). The bilinear
 * notch's are where |cos w - cos w0| = alpha sin w: at f0 = 100 Hz, Q = 5,
 * 1 kHz, 91.03 and 109.72 Hz against 90 and 110. The prewarping keeps the
 * centre but narrows the width by sin(w0) / w0 (6.5 % here) and the analog
 * edges are not symmetric either (f0 / (8 Q^2), 0.5 %): together 1 % of f0.
 * 1.5 % of f0 (1.5 Hz) brackets both. */
#define EDGE_TOL_F0 0.015

/* Low-pass DC gain. b0 + b1 + b2 = 1 + a1 + a2 exactly (the numerator is
 * taken from the rounded denominator), so what is left is the fixed point of
 * the float recurrence: a few eps of rounding per tick, divided by
 * 1 + a1 + a2 (0.08 for the second order at 50 Hz, 1 kHz): 3 eps / 0.08 =
 * 4.5e-6 (measured 1e-6). */
#define DC_GAIN_TOL 1e-5

/* Every line of the RPM bank's signal loses at least 20 dB (the requirement).
 * The design takes a static line out completely (measured -110 dB and below);
 * the margin is for a line moving with its notch. */
#define BANK_ATTENUATION_DB 20.0

void setUp(void)
{
}
void tearDown(void)
{
}

/* Big states: static, not on the stack of a small board. */
static ladrc_gyro_filter_t gf;
static ladrc_gyro_filter_t gf2;
static ladrc_gyro_filter_t gf3;

static double db(double gain)
{
    return 20.0 * log10(gain);
}

static ladrc_gyro_filter_config_t config(uint8_t channels)
{
    ladrc_gyro_filter_config_t cfg;
    ladrc_gyro_filter_config_default(&cfg, (ladrc_real_t)DT_S, channels);
    return cfg;
}

static ladrc_gyro_filter_config_t notch_config(double f0_hz, double q)
{
    ladrc_gyro_filter_config_t cfg = config(1u);
    cfg.n_notches = 1u;
    cfg.notch_hz[0] = (ladrc_real_t)f0_hz;
    cfg.notch_q = (ladrc_real_t)q;
    return cfg;
}

static ladrc_gyro_filter_config_t rpm_config(uint8_t channels, uint8_t rotors, uint8_t harmonics)
{
    ladrc_gyro_filter_config_t cfg = config(channels);
    cfg.rpm_rotors = rotors;
    cfg.rpm_harmonics = harmonics;
    cfg.rpm_q = LADRC_R(5.0);
    cfg.rpm_min_hz = LADRC_R(50.0);
    cfg.rpm_fade_hz = LADRC_R(20.0);
    return cfg;
}

static void init_ok(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_gyro_filter_init(f, cfg));
}

/* Least-squares amplitude of y ~ a cos(w k) + b sin(w k). */
typedef struct {
    double cc, ss, cs, yc, ys;
} fit_t;

static void fit_add(fit_t *fit, double w_rad, int k, double y)
{
    const double c = cos(w_rad * k);
    const double s = sin(w_rad * k);
    fit->cc += c * c;
    fit->ss += s * s;
    fit->cs += c * s;
    fit->yc += y * c;
    fit->ys += y * s;
}

static double fit_amplitude(const fit_t *fit)
{
    const double det = fit->cc * fit->ss - fit->cs * fit->cs;
    const double a = (fit->yc * fit->ss - fit->ys * fit->cs) / det;
    const double b = (fit->ys * fit->cc - fit->yc * fit->cs) / det;
    return sqrt(a * a + b * b);
}

/* Gain of channel 0 of f (from rest on 0) for a steady sinusoid at freq_hz. */
static double steady_gain(ladrc_gyro_filter_t *f, double freq_hz)
{
    const double w = 2.0 * PI * freq_hz * DT_S;
    const ladrc_real_t zero[LADRC_GYRO_FILTER_MAX_CHANNELS] = {0};
    fit_t fit = {0};
    int k;
    ladrc_gyro_filter_reset(f, zero);
    for (k = 0; k < SETTLE_TICKS + FIT_TICKS; ++k) {
        ladrc_real_t x[LADRC_GYRO_FILTER_MAX_CHANNELS] = {0};
        ladrc_real_t y[LADRC_GYRO_FILTER_MAX_CHANNELS];
        x[0] = (ladrc_real_t)sin(w * k);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(f, x, y));
        if (k >= SETTLE_TICKS) {
            fit_add(&fit, w, k, (double)y[0]);
        }
    }
    return fit_amplitude(&fit);
}

/* |H| of the bilinear notch at f0 with quality q, at freq_hz (gyro_filter.h). */
static double notch_design_gain(double f0_hz, double q, double freq_hz)
{
    const double w0 = 2.0 * PI * f0_hz * DT_S;
    const double w = 2.0 * PI * freq_hz * DT_S;
    const double alpha = sin(w0) / (2.0 * q);
    const double d = cos(w) - cos(w0);
    return fabs(d) / sqrt(d * d + alpha * alpha * sin(w) * sin(w));
}

/* The notch's -3 dB frequencies (Hz): cos w - cos w0 = -+alpha sin w, i.e.
 * w = acos(cos w0 / sqrt(1 + alpha^2)) -+ atan(alpha). */
static void notch_design_edges(double f0_hz, double q, double *lo_hz, double *hi_hz)
{
    const double w0 = 2.0 * PI * f0_hz * DT_S;
    const double alpha = sin(w0) / (2.0 * q);
    const double mid = acos(cos(w0) / sqrt(1.0 + alpha * alpha));
    *lo_hz = (mid - atan(alpha)) / (2.0 * PI * DT_S);
    *hi_hz = (mid + atan(alpha)) / (2.0 * PI * DT_S);
}

/* |H| of the bilinear Butterworth low-pass of the given order: exactly
 * 1 / sqrt(1 + (tan(w/2) / tan(wc/2))^(2 order)). */
static double lowpass_design_gain(double fc_hz, int order, double freq_hz)
{
    const double r = tan(PI * freq_hz * DT_S) / tan(PI * fc_hz * DT_S);
    return 1.0 / sqrt(1.0 + pow(r, 2.0 * order));
}

/* ------------------------------------------------------------ the notch */

static void test_a_notch_removes_its_centre(void)
{
    /* given: one notch at 100 Hz, Q = 5, at 1 kHz */
    const ladrc_gyro_filter_config_t cfg = notch_config(100.0, 5.0);
    init_ok(&gf, &cfg);
    /* when / then */
    TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, 100.0)));
}

static void test_a_notch_passes_frequencies_far_from_its_centre(void)
{
    const ladrc_gyro_filter_config_t cfg = notch_config(100.0, 5.0);
    const double far[] = {2.0, 10.0, 400.0, 440.0};
    size_t i;
    init_ok(&gf, &cfg);
    for (i = 0; i < sizeof far / sizeof far[0]; ++i) {
        const double g = steady_gain(&gf, far[i]);
        TEST_ASSERT_FLOAT_WITHIN(FAR_GAIN_TOL, 1.0, g);
        TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, notch_design_gain(100.0, 5.0, far[i]), g);
    }
}

static void test_a_notch_has_its_minus_3_db_points_near_f0_plus_minus_f0_over_2q(void)
{
    const double f0 = 100.0;
    const double q = 5.0;
    const double half = f0 / (2.0 * q);
    const double tol = EDGE_TOL_F0 * f0;
    const double half_power = sqrt(0.5);
    double lo, hi;
    const ladrc_gyro_filter_config_t cfg = notch_config(f0, q);
    init_ok(&gf, &cfg);
    /* then: the -3 dB crossings lie within the tolerance of f0 -+ f0 / (2 Q) */
    TEST_ASSERT_GREATER_THAN_FLOAT(half_power, steady_gain(&gf, f0 - half - tol));
    TEST_ASSERT_LESS_THAN_FLOAT(half_power, steady_gain(&gf, f0 - half + tol));
    TEST_ASSERT_LESS_THAN_FLOAT(half_power, steady_gain(&gf, f0 + half - tol));
    TEST_ASSERT_GREATER_THAN_FLOAT(half_power, steady_gain(&gf, f0 + half + tol));
    /* and exactly at the design's edges the gain is 1 / sqrt(2) */
    notch_design_edges(f0, q, &lo, &hi);
    TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, half_power, steady_gain(&gf, lo));
    TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, half_power, steady_gain(&gf, hi));
    TEST_ASSERT_FLOAT_WITHIN(tol, f0 - half, lo);
    TEST_ASSERT_FLOAT_WITHIN(tol, f0 + half, hi);
}

static void test_a_notch_follows_its_closed_form_across_the_band(void)
{
    /* given: notches across the band, Q from 2 to 10 */
    const double f0s[] = {20.0, 100.0, 250.0, 420.0};
    const double qs[] = {2.0, 5.0, 10.0};
    size_t i, j;
    for (i = 0; i < sizeof f0s / sizeof f0s[0]; ++i) {
        for (j = 0; j < sizeof qs / sizeof qs[0]; ++j) {
            const ladrc_gyro_filter_config_t cfg = notch_config(f0s[i], qs[j]);
            const double probes[] = {0.5 * f0s[i], 0.97 * f0s[i], 1.03 * f0s[i], 0.5 * (f0s[i] + 500.0)};
            size_t p;
            init_ok(&gf, &cfg);
            TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, f0s[i])));
            for (p = 0; p < sizeof probes / sizeof probes[0]; ++p) {
                TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, notch_design_gain(f0s[i], qs[j], probes[p]),
                                         steady_gain(&gf, probes[p]));
            }
        }
    }
}

static void test_fixed_notches_chain(void)
{
    /* given: two fixed notches, 60 and 180 Hz */
    ladrc_gyro_filter_config_t cfg = notch_config(60.0, 4.0);
    cfg.n_notches = 2u;
    cfg.notch_hz[1] = LADRC_R(180.0);
    init_ok(&gf, &cfg);
    /* then: both centres removed, the gain elsewhere the product of both */
    TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, 60.0)));
    TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, 180.0)));
    TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL,
                             notch_design_gain(60.0, 4.0, 120.0) * notch_design_gain(180.0, 4.0, 120.0),
                             steady_gain(&gf, 120.0));
}

/* --------------------------------------------------------- the low-pass */

static void check_lowpass(int order)
{
    /* given: a low-pass at 50 Hz */
    ladrc_gyro_filter_config_t cfg = config(1u);
    const double probes[] = {5.0, 25.0, 100.0, 200.0, 400.0};
    const ladrc_real_t rest[1] = {LADRC_R(0.0)};
    ladrc_real_t out = LADRC_R(0.0);
    size_t i;
    int k;
    cfg.lpf_order = (uint8_t)order;
    cfg.lpf_cutoff_hz = LADRC_R(50.0);
    init_ok(&gf, &cfg);
    /* then: -3 dB at the cutoff, the closed form elsewhere */
    TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, sqrt(0.5), steady_gain(&gf, 50.0));
    for (i = 0; i < sizeof probes / sizeof probes[0]; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, lowpass_design_gain(50.0, order, probes[i]),
                                 steady_gain(&gf, probes[i]));
    }
    /* then: DC gain 1 (a constant after a step from 0) */
    ladrc_gyro_filter_reset(&gf, rest);
    for (k = 0; k < SETTLE_TICKS; ++k) {
        const ladrc_real_t x = LADRC_R(0.37);
        (void)ladrc_gyro_filter_step(&gf, &x, &out);
    }
    TEST_ASSERT_FLOAT_WITHIN(DC_GAIN_TOL * 0.37, 0.37, out);
}

static void test_a_first_order_low_pass_is_3_db_down_at_its_cutoff_with_dc_gain_1(void)
{
    check_lowpass(1);
}

static void test_a_second_order_low_pass_is_3_db_down_at_its_cutoff_with_dc_gain_1(void)
{
    check_lowpass(2);
}

static void test_the_chain_is_notches_then_low_pass(void)
{
    /* given: a fixed notch at 150 Hz, an RPM notch at 80 Hz, a second-order low-pass at 120 Hz */
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 1u);
    const ladrc_real_t rotor = LADRC_R(80.0);
    cfg.n_notches = 1u;
    cfg.notch_hz[0] = LADRC_R(150.0);
    cfg.notch_q = LADRC_R(5.0);
    cfg.lpf_order = 2u;
    cfg.lpf_cutoff_hz = LADRC_R(120.0);
    init_ok(&gf, &cfg);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, &rotor));
    /* then: the gain is the product of the three sections' */
    TEST_ASSERT_EQUAL_UINT8(3u, gf.n_sections);
    TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL,
                             notch_design_gain(150.0, 5.0, 30.0) * notch_design_gain(80.0, 5.0, 30.0) *
                                 lowpass_design_gain(120.0, 2, 30.0),
                             steady_gain(&gf, 30.0));
    TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, 80.0)));
    TEST_ASSERT_LESS_THAN_FLOAT(NOTCH_DEPTH_DB, db(steady_gain(&gf, 150.0)));
}

/* ------------------------------------------------------------- RPM bank */

static void test_an_rpm_bank_takes_every_line_of_four_rotors_out(void)
{
    /* given: 4 rotors at 80..125 Hz, 3 harmonics each, and a signal of their 12 lines (amplitude 1
     * each, phases spread) plus a 20 Hz line the bank must let through */
    static const double rotor_hz[4] = {80.0, 95.0, 110.0, 125.0};
    static double y[SETTLE_TICKS + 2 * FIT_TICKS];
    const ladrc_gyro_filter_config_t cfg = rpm_config(1u, 4u, 3u);
    ladrc_real_t rotors[4];
    fit_t pass = {0};
    int r, h, k;
    for (r = 0; r < 4; ++r) {
        rotors[r] = (ladrc_real_t)rotor_hz[r];
    }
    init_ok(&gf, &cfg);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, rotors));
    /* when */
    for (k = 0; k < SETTLE_TICKS + 2 * FIT_TICKS; ++k) {
        double x = sin(2.0 * PI * 20.0 * DT_S * k);
        ladrc_real_t xin, out;
        for (r = 0; r < 4; ++r) {
            for (h = 1; h <= 3; ++h) {
                x += sin(2.0 * PI * rotor_hz[r] * h * DT_S * k + r + 0.5 * h);
            }
        }
        xin = (ladrc_real_t)x;
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, &xin, &out));
        y[k] = (double)out;
        if (k >= SETTLE_TICKS) {
            fit_add(&pass, 2.0 * PI * 20.0 * DT_S, k, y[k]);
        }
    }
    /* then: every line at least 20 dB down (fits over 8000 ticks: lines 10 Hz apart leak 4e-3 of
     * each other's amplitude into a fit, which the attenuated lines make negligible) */
    for (r = 0; r < 4; ++r) {
        for (h = 1; h <= 3; ++h) {
            const double w = 2.0 * PI * rotor_hz[r] * h * DT_S;
            fit_t fit = {0};
            for (k = SETTLE_TICKS; k < SETTLE_TICKS + 2 * FIT_TICKS; ++k) {
                fit_add(&fit, w, k, y[k]);
            }
            TEST_ASSERT_LESS_THAN_FLOAT(-BANK_ATTENUATION_DB, db(fit_amplitude(&fit)));
        }
    }
    /* then: the 20 Hz line passes with the product of the 12 notches' gains there (0.99) */
    {
        double g = 1.0;
        for (r = 0; r < 4; ++r) {
            for (h = 1; h <= 3; ++h) {
                g *= notch_design_gain(rotor_hz[r] * h, 5.0, 20.0);
            }
        }
        TEST_ASSERT_FLOAT_WITHIN(4.0 * DESIGN_GAIN_TOL, g, fit_amplitude(&pass));
    }
}

/* Runs a sinusoid whose frequency moves from f_from_hz at rate_hz_s (clamped at f_to_hz) through a
 * one-rotor, one-harmonic bank told that frequency every tick; returns output power over input power
 * after the first 200 ticks, and checks every output finite. */
static double swept_attenuation_db(double f_from_hz, double f_to_hz, double rate_hz_s, int ticks)
{
    const ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 1u);
    double phase = 0.0, p_in = 0.0, p_out = 0.0;
    int k;
    init_ok(&gf, &cfg);
    for (k = 0; k < ticks; ++k) {
        double hz = f_from_hz + rate_hz_s * k * DT_S;
        ladrc_real_t rotor, x, out;
        hz = (rate_hz_s > 0.0) ? fmin(hz, f_to_hz) : fmax(hz, f_to_hz);
        rotor = (ladrc_real_t)hz;
        x = (ladrc_real_t)sin(phase);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, &rotor));
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, &x, &out));
        TEST_ASSERT_TRUE(isfinite((double)out));
        if (k >= 200) {
            p_in += (double)x * (double)x;
            p_out += (double)out * (double)out;
        }
        phase += 2.0 * PI * hz * DT_S;
    }
    return 10.0 * log10(p_out / p_in);
}

static void test_moving_centres_follow_a_swept_line(void)
{
    /* when: a motor spooling 100 -> 400 Hz at 50, 200 and 1000 Hz/s (a racer's punch-out), and down
     * again; then: the line stays at least 20 dB down (measured 45, 36 and 32 dB: the notch, about
     * 20 Hz wide, lags the line by its settling time of 1 / alpha = 20 ticks) */
    TEST_ASSERT_LESS_THAN_FLOAT(-BANK_ATTENUATION_DB, swept_attenuation_db(100.0, 400.0, 50.0, 3000));
    TEST_ASSERT_LESS_THAN_FLOAT(-BANK_ATTENUATION_DB, swept_attenuation_db(100.0, 400.0, 200.0, 1500));
    TEST_ASSERT_LESS_THAN_FLOAT(-BANK_ATTENUATION_DB, swept_attenuation_db(100.0, 400.0, 1000.0, 500));
    TEST_ASSERT_LESS_THAN_FLOAT(-BANK_ATTENUATION_DB, swept_attenuation_db(400.0, 100.0, -1000.0, 500));
}

/* A deterministic pseudo-random sequence in [0, 1) (no libc rand state). */
static double lcg_uniform(unsigned long *seed)
{
    *seed = (*seed * 1103515245ul + 12345ul) & 0x7ffffffful;
    return (double)*seed / 2147483648.0;
}

/* Runs 4 rotors x 4 harmonics and a low-pass on 3 channels for 20000 ticks on inputs within +-1,
 * the rotor speeds within 0..300 Hz (off, fading and on, some harmonics past the guard) moved each
 * tick by next_speed; checks every output finite and returns the largest |output|. */
static double peak_with_moving_centres(void (*next_speed)(unsigned long *, int, ladrc_real_t *))
{
    ladrc_gyro_filter_config_t cfg = rpm_config(3u, 4u, 4u);
    ladrc_real_t rotors[4] = {LADRC_R(100.0), LADRC_R(120.0), LADRC_R(140.0), LADRC_R(160.0)};
    unsigned long seed = 7ul;
    double peak = 0.0;
    int k, i;
    cfg.lpf_order = 2u;
    cfg.lpf_cutoff_hz = LADRC_R(200.0);
    init_ok(&gf, &cfg);
    for (k = 0; k < 20000; ++k) {
        ladrc_real_t x[3], y[3];
        next_speed(&seed, k, rotors);
        for (i = 0; i < 3; ++i) {
            x[i] = (ladrc_real_t)(2.0 * lcg_uniform(&seed) - 1.0);
        }
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, rotors));
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
        for (i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(isfinite((double)y[i]));
            peak = fmax(peak, fabs((double)y[i]));
        }
    }
    return peak;
}

/* A random walk of up to 5 Hz per tick (5000 Hz/s, beyond any motor), and every 500 ticks one
 * rotor's telemetry glitching to a random speed for one tick. */
static void walk_with_glitches(unsigned long *seed, int k, ladrc_real_t *rotors)
{
    static ladrc_real_t walk[4];
    int i;
    if (k == 0) {
        memcpy(walk, rotors, sizeof walk);
    }
    for (i = 0; i < 4; ++i) {
        walk[i] = (ladrc_real_t)fmin(300.0, fmax(0.0, (double)walk[i] + 10.0 * lcg_uniform(seed) - 5.0));
        rotors[i] = (k % 500 == 100 * i) ? (ladrc_real_t)(300.0 * lcg_uniform(seed)) : walk[i];
    }
}

/* Every speed drawn anew every tick: no physical rotor. */
static void jump_every_tick(unsigned long *seed, int k, ladrc_real_t *rotors)
{
    int i;
    (void)k;
    for (i = 0; i < 4; ++i) {
        rotors[i] = (ladrc_real_t)(300.0 * lcg_uniform(seed));
    }
}

static void test_centres_moving_fast_and_glitching_stay_bounded(void)
{
    /* then: the outputs stay on the scale of the input (measured peak 1.9, 5.4 over 400000 ticks);
     * a chain of notches whose centres move has no gain bound of its own, 20 is a generous one */
    TEST_ASSERT_LESS_THAN_FLOAT(20.0, peak_with_moving_centres(walk_with_glitches));
}

/* A chain whose RPM notches are held within LADRC_GYRO_FILTER_RPM_GAIN_BOUND times the input's
 * envelope (8 on inputs within +-1) and end in a second-order Butterworth low-pass, whose
 * impulse response sums to less than 1.25 in magnitude (4 % overshoot): 10. */
#define SWITCHED_CHAIN_BOUND (1.25 * (double)LADRC_GYRO_FILTER_RPM_GAIN_BOUND)

static void test_centres_jumping_at_random_every_tick_stay_bounded(void)
{
    /* then: no fault, and the outputs within the bound whatever the centres do (direct form I
     * switched at random between stable sections amplifies without a bound of its own: peaks of
     * 7e5 in 100000 ticks before the RPM notches' outputs were held) */
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(SWITCHED_CHAIN_BOUND, peak_with_moving_centres(jump_every_tick));
}

/* Flies f and a twin whose rotors sit at steady from the start on the same inputs: for the first
 * adversarial_ticks the rotors of f follow next_speed, then steady. Checks that no step of f
 * faults and every output stays within SWITCHED_CHAIN_BOUND times the input's amplitude; returns
 * the largest |f - twin| from settle_ticks after the rotors steadied. */
static double recovery_gap(const ladrc_gyro_filter_config_t *cfg,
                           void (*next_speed)(unsigned long *, int, ladrc_real_t *), const ladrc_real_t *steady,
                           int adversarial_ticks, int settle_ticks)
{
    ladrc_real_t rotors[LADRC_GYRO_FILTER_MAX_ROTORS];
    unsigned long seed = 11ul;
    double gap = 0.0;
    init_ok(&gf, cfg);
    init_ok(&gf2, cfg);
    for (int k = 0; k < adversarial_ticks + 2 * settle_ticks; ++k) {
        ladrc_real_t x[LADRC_GYRO_FILTER_MAX_CHANNELS], y[LADRC_GYRO_FILTER_MAX_CHANNELS],
            y_twin[LADRC_GYRO_FILTER_MAX_CHANNELS];
        memcpy(rotors, steady, (size_t)cfg->rpm_rotors * sizeof rotors[0]);
        if (k < adversarial_ticks) {
            next_speed(&seed, k, rotors);
        }
        for (unsigned ch = 0u; ch < cfg->channels; ++ch) {
            x[ch] = (ladrc_real_t)sin(2.0 * PI * (37.0 + 11.0 * ch) * DT_S * k);
        }
        (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
        (void)ladrc_gyro_filter_set_rotor_hz(&gf2, steady);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf2, x, y_twin));
        for (unsigned ch = 0u; ch < cfg->channels; ++ch) {
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT(SWITCHED_CHAIN_BOUND, fabs((double)y[ch]));
            if (k >= adversarial_ticks + settle_ticks) {
                gap = fmax(gap, fabs((double)y[ch] - (double)y_twin[ch]));
            }
        }
    }
    return gap;
}

/* Speeds drawn anew each tick over 20..450 Hz: corrupted ESC telemetry. */
static void garbage_telemetry(unsigned long *seed, int k, ladrc_real_t *rotors)
{
    (void)k;
    for (unsigned i = 0u; i < LADRC_GYRO_FILTER_MAX_ROTORS; ++i) {
        rotors[i] = (ladrc_real_t)(20.0 + 430.0 * lcg_uniform(seed));
    }
}

/* Telemetry alternating 100 and 200 Hz every tick on every rotor. */
static void alternating_telemetry(unsigned long *seed, int k, ladrc_real_t *rotors)
{
    (void)seed;
    for (unsigned i = 0u; i < LADRC_GYRO_FILTER_MAX_ROTORS; ++i) {
        rotors[i] = (k % 2 == 0) ? LADRC_R(100.0) : LADRC_R(200.0);
    }
}

/* Once the speeds settle the bank is a stable filter again: its gap to a twin that never saw the
 * garbage decays with its slowest notch (Q 5 at 100-160 Hz: 10-16 ms); 0.2 s after, 12 time
 * constants, only float rounding is left (1e-4 on outputs of order 1). */
#define RECOVERY_SETTLE_TICKS 200
#define RECOVERY_GAP_MAX 1e-4

static void test_the_rpm_bank_recovers_by_itself_after_a_second_of_garbage_telemetry(void)
{
    ladrc_gyro_filter_config_t cfg = config(1u);
    const ladrc_real_t steady[2] = {LADRC_R(150.0), LADRC_R(160.0)};
    cfg.rpm_rotors = 2u;
    cfg.rpm_harmonics = 1u;
    cfg.rpm_q = LADRC_R(5.0);
    cfg.rpm_min_hz = LADRC_R(20.0);
    cfg.rpm_fade_hz = LADRC_R(10.0);
    TEST_ASSERT_LESS_THAN_FLOAT(RECOVERY_GAP_MAX,
                                recovery_gap(&cfg, garbage_telemetry, steady, 1000, RECOVERY_SETTLE_TICKS));
}

static void test_alternating_telemetry_on_a_full_bank_stays_bounded_and_recovers(void)
{
    /* 4 rotors x 3 harmonics and 4 fixed notches on 3 channels, the speeds flipping 100/200 Hz
     * every tick for 2 s */
    ladrc_gyro_filter_config_t cfg = rpm_config(3u, 4u, 3u);
    const ladrc_real_t steady[4] = {LADRC_R(100.0), LADRC_R(110.0), LADRC_R(120.0), LADRC_R(130.0)};
    cfg.n_notches = 4u;
    cfg.notch_q = LADRC_R(5.0);
    for (unsigned i = 0u; i < 4u; ++i) {
        cfg.notch_hz[i] = (ladrc_real_t)(60.0 + 70.0 * i);
    }
    TEST_ASSERT_LESS_THAN_FLOAT(RECOVERY_GAP_MAX,
                                recovery_gap(&cfg, alternating_telemetry, steady, 2000, RECOVERY_SETTLE_TICKS));
}

static void test_a_rotor_with_a_bad_speed_keeps_its_notches_and_the_others_move(void)
{
    const ladrc_gyro_filter_config_t cfg = rpm_config(1u, 3u, 2u);
    const ladrc_real_t good[3] = {LADRC_R(100.0), LADRC_R(120.0), LADRC_R(140.0)};
    const ladrc_real_t bad[4] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY, LADRC_R(-1.0)};
    size_t i;
    init_ok(&gf, &cfg);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, good));
    for (i = 0; i < 4; ++i) {
        /* given */
        ladrc_gyro_filter_section_t before[2];
        const ladrc_real_t moved[3] = {LADRC_R(110.0), bad[i], LADRC_R(150.0)};
        memcpy(before, &gf.section[2], sizeof before); /* rotor 1: sections 2 and 3 */
        /* when / then: an input fault, rotor 1 unchanged, rotors 0 and 2 moved */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_gyro_filter_set_rotor_hz(&gf, moved));
        TEST_ASSERT_EQUAL_MEMORY(before, &gf.section[2], sizeof before);
        TEST_ASSERT_TRUE(gf.section[0].a1 != gf.section[2].a1);
        {
            ladrc_gyro_filter_t expected;
            const ladrc_real_t again[3] = {LADRC_R(110.0), LADRC_R(120.0), LADRC_R(150.0)};
            init_ok(&expected, &cfg);
            (void)ladrc_gyro_filter_set_rotor_hz(&expected, again);
            TEST_ASSERT_EQUAL_MEMORY(expected.section, gf.section, sizeof gf.section);
        }
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, good));
    }
}

static void test_rpm_notches_are_off_until_the_first_rotor_speed_and_then_exact_at_zero_weight(void)
{
    /* given: an RPM bank never told a speed */
    const ladrc_gyro_filter_config_t cfg = rpm_config(1u, 2u, 3u);
    ladrc_real_t x, y;
    int k;
    init_ok(&gf, &cfg);
    TEST_ASSERT_TRUE(ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u) == LADRC_R(0.0));
    /* then: the output is the input, bit for bit */
    for (k = 0; k < 200; ++k) {
        x = (ladrc_real_t)sin(0.7 * k);
        (void)ladrc_gyro_filter_step(&gf, &x, &y);
        TEST_ASSERT_EQUAL_MEMORY(&x, &y, sizeof x);
    }
    /* and rotors too slow for any harmonic to reach rpm_min_hz (3 x 10 Hz < 50 Hz) keep it so */
    {
        const ladrc_real_t slow[2] = {LADRC_R(10.0), LADRC_R(0.0)};
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, slow));
    }
    for (k = 0; k < 200; ++k) {
        x = (ladrc_real_t)sin(0.3 * k);
        (void)ladrc_gyro_filter_step(&gf, &x, &y);
        TEST_ASSERT_EQUAL_MEMORY(&x, &y, sizeof x);
    }
}

static void test_the_fade_weights_a_notch_linearly_from_min_to_min_plus_fade(void)
{
    /* given: min 100 Hz, fade 50 Hz, harmonics 1 and 2 of one rotor */
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 2u);
    const double rotor_hz[] = {90.0, 100.0, 112.5, 125.0, 150.0, 160.0};
    const double weight1[] = {0.0, 0.0, 0.25, 0.5, 1.0, 1.0};
    size_t i;
    cfg.rpm_min_hz = LADRC_R(100.0);
    cfg.rpm_fade_hz = LADRC_R(50.0);
    init_ok(&gf, &cfg);
    for (i = 0; i < sizeof rotor_hz / sizeof rotor_hz[0]; ++i) {
        const ladrc_real_t hz = (ladrc_real_t)rotor_hz[i];
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, &hz));
        /* then: harmonic 1 fades in, harmonic 2 (180 Hz and above) is fully on */
        TEST_ASSERT_FLOAT_WITHIN(4.0 * LADRC_REAL_EPS, weight1[i], ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u));
        TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 2u));
    }
    /* then: at half weight a steady line at the notch's centre keeps half its amplitude
     * (out = x + w (notched - x), the notched part 0 there), times harmonic 2's gain there */
    {
        const ladrc_real_t hz = LADRC_R(125.0);
        (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
        TEST_ASSERT_FLOAT_WITHIN(DESIGN_GAIN_TOL, 0.5 * notch_design_gain(250.0, 5.0, 125.0), steady_gain(&gf, 125.0));
    }
}

static void test_without_a_fade_a_notch_is_fully_on_from_min(void)
{
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 1u);
    ladrc_real_t hz = LADRC_R(50.0);
    cfg.rpm_fade_hz = LADRC_R(0.0);
    init_ok(&gf, &cfg);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u));
    hz = LADRC_R(49.99);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u));
}

static void test_a_notch_fading_in_and_out_makes_no_step_in_a_passing_signal(void)
{
    /* given: a 15 Hz line, and one rotor whose notch goes 40 -> 80 -> 40 Hz through the fade
     * (50..70 Hz) and, with no fade, jumps on and off every 50 ticks */
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 1u);
    double worst = 0.0;
    int pass, k;
    for (pass = 0; pass < 2; ++pass) {
        cfg.rpm_fade_hz = (pass == 0) ? LADRC_R(20.0) : LADRC_R(0.0);
        init_ok(&gf, &cfg);
        for (k = 0; k < 4000; ++k) {
            const double t = k * DT_S;
            const double hz = (pass == 0) ? 60.0 - 20.0 * cos(2.0 * PI * t) : (((k / 50) % 2 != 0) ? 80.0 : 40.0);
            const ladrc_real_t rotor = (ladrc_real_t)hz;
            const ladrc_real_t x = (ladrc_real_t)sin(2.0 * PI * 15.0 * t);
            ladrc_real_t y;
            (void)ladrc_gyro_filter_set_rotor_hz(&gf, &rotor);
            (void)ladrc_gyro_filter_step(&gf, &x, &y);
            if (k >= 100) {
                worst = fmax(worst, fabs((double)y - (double)x));
            }
        }
    }
    /* then: the output never leaves the input by more than the notch's own effect at 15 Hz: its gain
     * there is 0.98 at 80 Hz (Q = 5) with a phase of about 0.05 rad, so 0.07 of the amplitude; with
     * the history recording the input while off, re-entry adds no step on top (0.1 bounds both) */
    TEST_ASSERT_LESS_THAN_FLOAT(0.1, worst);
}

static void test_notches_at_or_above_the_nyquist_guard_are_off(void)
{
    /* given: 1 kHz, so the guard is at 0.9 * 500 = 450 Hz; one rotor, 3 harmonics */
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 3u);
    ladrc_real_t hz;
    ladrc_real_t x, y;
    init_ok(&gf, &cfg);
    TEST_ASSERT_FLOAT_WITHIN(1e-3, 450.0, gf.centre_max_hz);
    /* when: 200 Hz: harmonics at 200 and 400 on, 600 off */
    hz = LADRC_R(200.0);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 2u));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 3u));
    /* when: 449 Hz: the first just inside, the others out; 450 Hz: all out */
    hz = LADRC_R(449.0);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 2u));
    hz = LADRC_R(450.0);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, &hz);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 1u));
    /* when: an absurd but finite speed: all off, no overflow, the signal passes untouched */
    hz = LADRC_REAL_MAX;
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_set_rotor_hz(&gf, &hz));
    x = LADRC_R(0.25);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, &x, &y));
    TEST_ASSERT_EQUAL_MEMORY(&x, &y, sizeof x);
    /* and a fixed notch there is refused */
    cfg = notch_config(450.0, 5.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GYRO_NOTCH_HZ, ladrc_gyro_filter_init(&gf, &cfg));
    cfg = notch_config(449.0, 5.0);
    init_ok(&gf, &cfg);
}

/* ----------------------------------------------------------- init */

static void test_init_reports_the_first_bad_field_in_the_documented_order(void)
{
    /* given: every field bad */
    ladrc_gyro_filter_config_t cfg = config(1u);
    const ladrc_status_t order[] = {LADRC_ERR_DT_S,
                                    LADRC_ERR_GYRO_CHANNELS,
                                    LADRC_ERR_GYRO_LPF_ORDER,
                                    LADRC_ERR_GYRO_LPF_CUTOFF_HZ,
                                    LADRC_ERR_GYRO_N_NOTCHES,
                                    LADRC_ERR_GYRO_NOTCH_HZ,
                                    LADRC_ERR_GYRO_NOTCH_Q,
                                    LADRC_ERR_GYRO_RPM_ROTORS,
                                    LADRC_ERR_GYRO_RPM_HARMONICS,
                                    LADRC_ERR_GYRO_RPM_MIN_HZ,
                                    LADRC_ERR_GYRO_RPM_FADE_HZ,
                                    LADRC_ERR_GYRO_RPM_Q,
                                    LADRC_OK};
    size_t i;
    cfg.dt_s = (ladrc_real_t)NAN;
    cfg.channels = 0u;
    cfg.lpf_order = 3u;
    cfg.lpf_cutoff_hz = (ladrc_real_t)NAN;
    cfg.n_notches = 5u;
    cfg.notch_hz[0] = (ladrc_real_t)NAN;
    cfg.notch_q = LADRC_R(0.0);
    cfg.rpm_rotors = 9u;
    cfg.rpm_harmonics = 0u;
    cfg.rpm_min_hz = LADRC_R(-1.0);
    cfg.rpm_fade_hz = (ladrc_real_t)INFINITY;
    cfg.rpm_q = (ladrc_real_t)NAN;
    for (i = 0; i < sizeof order / sizeof order[0]; ++i) {
        /* when / then: the next field in the order is named; mend it */
        TEST_ASSERT_EQUAL_INT(order[i], ladrc_gyro_filter_init(&gf, &cfg));
        switch (order[i]) {
        case LADRC_ERR_DT_S:
            cfg.dt_s = (ladrc_real_t)DT_S;
            break;
        case LADRC_ERR_GYRO_CHANNELS:
            cfg.channels = 3u;
            break;
        case LADRC_ERR_GYRO_LPF_ORDER:
            cfg.lpf_order = 2u;
            break;
        case LADRC_ERR_GYRO_LPF_CUTOFF_HZ:
            cfg.lpf_cutoff_hz = LADRC_R(150.0);
            break;
        case LADRC_ERR_GYRO_N_NOTCHES:
            cfg.n_notches = 1u;
            break;
        case LADRC_ERR_GYRO_NOTCH_HZ:
            cfg.notch_hz[0] = LADRC_R(120.0);
            break;
        case LADRC_ERR_GYRO_NOTCH_Q:
            cfg.notch_q = LADRC_R(3.0);
            break;
        case LADRC_ERR_GYRO_RPM_ROTORS:
            cfg.rpm_rotors = 4u;
            break;
        case LADRC_ERR_GYRO_RPM_HARMONICS:
            cfg.rpm_harmonics = 3u;
            break;
        case LADRC_ERR_GYRO_RPM_MIN_HZ:
            cfg.rpm_min_hz = LADRC_R(80.0);
            break;
        case LADRC_ERR_GYRO_RPM_FADE_HZ:
            cfg.rpm_fade_hz = LADRC_R(40.0);
            break;
        case LADRC_ERR_GYRO_RPM_Q:
            cfg.rpm_q = LADRC_R(5.0);
            break;
        default:
            break;
        }
    }
    TEST_ASSERT_EQUAL_UINT8(1u + 12u + 1u, gf.n_sections);
}

/* Sets one field of a valid config (all stages on) to a bad value and checks the status. */
typedef enum {
    F_DT,
    F_CHANNELS,
    F_LPF_ORDER,
    F_LPF_CUTOFF,
    F_N_NOTCHES,
    F_NOTCH_HZ,
    F_NOTCH_Q,
    F_ROTORS,
    F_HARMONICS,
    F_MIN,
    F_FADE,
    F_RPM_Q
} field_t;

static void expect_bad(field_t field, double value, ladrc_status_t status)
{
    ladrc_gyro_filter_config_t cfg = rpm_config(3u, 4u, 3u);
    cfg.lpf_order = 2u;
    cfg.lpf_cutoff_hz = LADRC_R(150.0);
    cfg.n_notches = 2u;
    cfg.notch_hz[0] = LADRC_R(60.0);
    cfg.notch_hz[1] = LADRC_R(120.0);
    init_ok(&gf, &cfg);
    switch (field) {
    case F_DT:
        cfg.dt_s = (ladrc_real_t)value;
        break;
    case F_CHANNELS:
        cfg.channels = (uint8_t)value;
        break;
    case F_LPF_ORDER:
        cfg.lpf_order = (uint8_t)value;
        break;
    case F_LPF_CUTOFF:
        cfg.lpf_cutoff_hz = (ladrc_real_t)value;
        break;
    case F_N_NOTCHES:
        cfg.n_notches = (uint8_t)value;
        break;
    case F_NOTCH_HZ:
        cfg.notch_hz[1] = (ladrc_real_t)value; /* the last one read */
        break;
    case F_NOTCH_Q:
        cfg.notch_q = (ladrc_real_t)value;
        break;
    case F_ROTORS:
        cfg.rpm_rotors = (uint8_t)value;
        break;
    case F_HARMONICS:
        cfg.rpm_harmonics = (uint8_t)value;
        break;
    case F_MIN:
        cfg.rpm_min_hz = (ladrc_real_t)value;
        break;
    case F_FADE:
        cfg.rpm_fade_hz = (ladrc_real_t)value;
        break;
    case F_RPM_Q:
        cfg.rpm_q = (ladrc_real_t)value;
        break;
    }
    TEST_ASSERT_EQUAL_INT(status, ladrc_gyro_filter_init(&gf, &cfg));
}

static void test_init_rejects_each_bad_field(void)
{
    const double bad_real[] = {0.0, -1.0, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad_real / sizeof bad_real[0]; ++i) {
        expect_bad(F_DT, bad_real[i], LADRC_ERR_DT_S);
        expect_bad(F_LPF_CUTOFF, bad_real[i], LADRC_ERR_GYRO_LPF_CUTOFF_HZ);
        expect_bad(F_NOTCH_HZ, bad_real[i], LADRC_ERR_GYRO_NOTCH_HZ);
        expect_bad(F_NOTCH_Q, bad_real[i], LADRC_ERR_GYRO_NOTCH_Q);
        expect_bad(F_MIN, bad_real[i], LADRC_ERR_GYRO_RPM_MIN_HZ);
        expect_bad(F_RPM_Q, bad_real[i], LADRC_ERR_GYRO_RPM_Q);
    }
    expect_bad(F_DT, 2.0, LADRC_ERR_DT_S);
    expect_bad(F_CHANNELS, 0.0, LADRC_ERR_GYRO_CHANNELS);
    expect_bad(F_CHANNELS, 7.0, LADRC_ERR_GYRO_CHANNELS);
    expect_bad(F_LPF_ORDER, 3.0, LADRC_ERR_GYRO_LPF_ORDER);
    /* the cutoff: Nyquist itself and beyond; so close to 0 or to Nyquist that the section rounds
     * to one with a pole on the unit circle */
    expect_bad(F_LPF_CUTOFF, 500.0, LADRC_ERR_GYRO_LPF_CUTOFF_HZ);
    expect_bad(F_LPF_CUTOFF, 600.0, LADRC_ERR_GYRO_LPF_CUTOFF_HZ);
    expect_bad(F_LPF_CUTOFF, 1e-30, LADRC_ERR_GYRO_LPF_CUTOFF_HZ);
    expect_bad(F_LPF_CUTOFF, 500.0 * (1.0 - (double)LADRC_REAL_EPS), LADRC_ERR_GYRO_LPF_CUTOFF_HZ);
    expect_bad(F_N_NOTCHES, 5.0, LADRC_ERR_GYRO_N_NOTCHES);
    expect_bad(F_NOTCH_HZ, 450.0, LADRC_ERR_GYRO_NOTCH_HZ);
    /* a Q so high that alpha vanishes against 1: the notch's poles round onto the unit circle */
    expect_bad(F_NOTCH_Q, 1e30, LADRC_ERR_GYRO_NOTCH_Q);
    expect_bad(F_ROTORS, 9.0, LADRC_ERR_GYRO_RPM_ROTORS);
    expect_bad(F_HARMONICS, 0.0, LADRC_ERR_GYRO_RPM_HARMONICS);
    expect_bad(F_HARMONICS, 5.0, LADRC_ERR_GYRO_RPM_HARMONICS);
    expect_bad(F_MIN, 450.0, LADRC_ERR_GYRO_RPM_MIN_HZ);
    expect_bad(F_FADE, -1.0, LADRC_ERR_GYRO_RPM_FADE_HZ);
    expect_bad(F_FADE, (double)NAN, LADRC_ERR_GYRO_RPM_FADE_HZ);
    expect_bad(F_FADE, (double)INFINITY, LADRC_ERR_GYRO_RPM_FADE_HZ);
    expect_bad(F_FADE, (double)LADRC_REAL_MIN / 8.0, LADRC_ERR_GYRO_RPM_FADE_HZ); /* 1 / fade overflows */
    expect_bad(F_RPM_Q, 1e30, LADRC_ERR_GYRO_RPM_Q);
}

static void test_init_checks_the_narrowest_rpm_notch_at_both_ends(void)
{
    /* given: rpm_min_hz at a quarter of the rate (sin w0 = 1, the widest) and a Q where alpha there is
     * 0.45 eps (1 - alpha still rounds below 1) but at the guard, sin(0.9 pi) = 0.31 times that, rounds
     * to 1: only the guard's end fails */
    ladrc_gyro_filter_config_t cfg = rpm_config(1u, 1u, 1u);
    cfg.rpm_min_hz = LADRC_R(250.0);
    cfg.rpm_q = (ladrc_real_t)(1.0 / (0.9 * (double)LADRC_REAL_EPS));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GYRO_RPM_Q, ladrc_gyro_filter_init(&gf, &cfg));
    /* and a low minimum with that Q fails at the minimum's end */
    cfg.rpm_min_hz = LADRC_R(1.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GYRO_RPM_Q, ladrc_gyro_filter_init(&gf, &cfg));
    cfg.rpm_q = LADRC_R(100.0);
    init_ok(&gf, &cfg);
}

static void test_init_does_not_read_the_fields_of_stages_that_are_off(void)
{
    ladrc_gyro_filter_config_t cfg = config(2u);
    cfg.lpf_cutoff_hz = (ladrc_real_t)NAN;
    cfg.notch_hz[0] = (ladrc_real_t)NAN;
    cfg.notch_q = (ladrc_real_t)NAN;
    cfg.rpm_harmonics = 0u;
    cfg.rpm_q = (ladrc_real_t)NAN;
    cfg.rpm_min_hz = (ladrc_real_t)NAN;
    cfg.rpm_fade_hz = (ladrc_real_t)NAN;
    init_ok(&gf, &cfg);
    TEST_ASSERT_EQUAL_UINT8(0u, gf.n_sections);
    /* a fixed notch reads only the first n_notches centres */
    cfg = notch_config(100.0, 5.0);
    cfg.notch_hz[1] = (ladrc_real_t)NAN;
    init_ok(&gf, &cfg);
}

static void test_init_rejects_null_pointers(void)
{
    const ladrc_gyro_filter_config_t cfg = config(1u);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_gyro_filter_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_gyro_filter_init(&gf, NULL));
}

static void test_a_filter_init_refused_is_zeroed_and_its_steps_write_nothing(void)
{
    /* given: a filter that ran, then an init that failed */
    ladrc_gyro_filter_config_t cfg = notch_config(100.0, 5.0);
    ladrc_real_t x = LADRC_R(1.0);
    ladrc_real_t y = LADRC_R(-7.0);
    static const ladrc_gyro_filter_t zero;
    init_ok(&gf, &cfg);
    (void)ladrc_gyro_filter_step(&gf, &x, &y);
    cfg.notch_q = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GYRO_NOTCH_Q, ladrc_gyro_filter_init(&gf, &cfg));
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(&zero, &gf, sizeof gf);
    y = LADRC_R(-7.0);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(&gf, &x, &y));
    TEST_ASSERT_TRUE(y == LADRC_R(-7.0));
}

static void test_config_default_turns_every_stage_off_and_each_can_be_switched_on(void)
{
    const double steps[] = {1e-3, 1.25e-4, 0.01};
    const double expected_hz[] = {100.0, 100.0, 10.0};
    size_t i;
    for (i = 0; i < 3; ++i) {
        ladrc_gyro_filter_config_t cfg;
        ladrc_gyro_filter_config_default(&cfg, (ladrc_real_t)steps[i], 3u);
        TEST_ASSERT_EQUAL_UINT8(0u, cfg.lpf_order);
        TEST_ASSERT_EQUAL_UINT8(0u, cfg.n_notches);
        TEST_ASSERT_EQUAL_UINT8(0u, cfg.rpm_rotors);
        TEST_ASSERT_EQUAL_UINT8(3u, cfg.channels);
        TEST_ASSERT_FLOAT_WITHIN(1e-4 * expected_hz[i], expected_hz[i], cfg.lpf_cutoff_hz);
        TEST_ASSERT_FLOAT_WITHIN(1e-4 * expected_hz[i], expected_hz[i], cfg.rpm_min_hz);
        init_ok(&gf, &cfg);
        cfg.lpf_order = 2u;
        init_ok(&gf, &cfg);
        cfg.rpm_rotors = 4u;
        init_ok(&gf, &cfg);
        cfg.n_notches = 1u;
        cfg.notch_hz[0] = cfg.rpm_min_hz; /* the one field left to set */
        init_ok(&gf, &cfg);
    }
}

/* ------------------------------------------------------------- faults */

static ladrc_gyro_filter_config_t full_config(uint8_t channels)
{
    ladrc_gyro_filter_config_t cfg = rpm_config(channels, 2u, 2u);
    cfg.n_notches = 1u;
    cfg.notch_hz[0] = LADRC_R(170.0);
    cfg.notch_q = LADRC_R(3.0);
    cfg.lpf_order = 2u;
    cfg.lpf_cutoff_hz = LADRC_R(200.0);
    return cfg;
}

static ladrc_real_t signal_at(int k, int ch)
{
    return (ladrc_real_t)(sin(0.37 * k + ch) + 0.3 * sin(1.9 * k - ch) + 0.1 * ch);
}

static void test_a_non_finite_input_holds_its_channel_and_the_rest_runs_as_if_it_were_skipped(void)
{
    /* given: a 3-channel filter whose channel 1 sees bursts of NaN and +-inf; a 3-channel filter on
     * the clean samples; and a 1-channel filter on channel 1's good samples only */
    const ladrc_gyro_filter_config_t cfg3 = full_config(3u);
    const ladrc_gyro_filter_config_t cfg1 = full_config(1u);
    const ladrc_real_t rotors[2] = {LADRC_R(90.0), LADRC_R(130.0)};
    const ladrc_real_t bad[3] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY};
    int k;
    init_ok(&gf, &cfg3);
    init_ok(&gf2, &cfg3);
    init_ok(&gf3, &cfg1);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf2, rotors);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf3, rotors);
    for (k = 0; k < 600; ++k) {
        ladrc_real_t x[3] = {signal_at(k, 0), signal_at(k, 1), signal_at(k, 2)};
        ladrc_real_t y[3], y_clean[3], y_one;
        const int burst = (k >= 100 && k < 103) || (k >= 300 && k < 310) || k == 450;
        (void)ladrc_gyro_filter_step(&gf2, x, y_clean);
        if (burst) {
            const ladrc_real_t held = gf.out[1];
            x[1] = bad[k % 3];
            /* when / then: an input fault; channel 1 writes its latest output */
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_gyro_filter_step(&gf, x, y));
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, gf.faults);
            TEST_ASSERT_EQUAL_MEMORY(&held, &y[1], sizeof held);
        } else {
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
            (void)ladrc_gyro_filter_step(&gf3, &x[1], &y_one);
            /* then: channel 1 as if the bad samples never came, bit for bit */
            TEST_ASSERT_EQUAL_MEMORY(&y_one, &y[1], sizeof y_one);
        }
        /* then: the other channels never noticed */
        TEST_ASSERT_EQUAL_MEMORY(&y_clean[0], &y[0], sizeof y[0]);
        TEST_ASSERT_EQUAL_MEMORY(&y_clean[2], &y[2], sizeof y[2]);
    }
}

static void test_a_huge_sample_is_an_input_fault_and_never_latches(void)
{
    /* given: 2 channels, and a 1-channel filter on channel 0's good samples only */
    const ladrc_gyro_filter_config_t cfg = full_config(2u);
    const ladrc_gyro_filter_config_t cfg1 = full_config(1u);
    const ladrc_real_t rotors[2] = {LADRC_R(90.0), LADRC_R(130.0)};
    const ladrc_real_t huge[3] = {LADRC_REAL_MAX, -LADRC_REAL_MAX, LADRC_GYRO_FILTER_INPUT_MAX * LADRC_R(1.0001)};
    int k;
    init_ok(&gf, &cfg);
    init_ok(&gf3, &cfg1);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf3, rotors);
    for (k = 0; k < 300; ++k) {
        ladrc_real_t x[2] = {signal_at(k, 0), signal_at(k, 1)};
        ladrc_real_t y[2], y_ref;
        if (k >= 100 && k < 103) {
            const ladrc_real_t held = gf.out[0];
            /* when: samples finite but beyond the bound, which could overflow the history */
            x[0] = huge[k - 100];
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_gyro_filter_step(&gf, x, y));
            TEST_ASSERT_EQUAL_MEMORY(&held, &y[0], sizeof held);
            continue;
        }
        /* then: every good tick as if the huge ones had been skipped */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
        (void)ladrc_gyro_filter_step(&gf3, &x[0], &y_ref);
        TEST_ASSERT_EQUAL_MEMORY(&y_ref, &y[0], sizeof y_ref);
    }
    /* and the bound itself is taken */
    {
        const ladrc_real_t x[2] = {LADRC_GYRO_FILTER_INPUT_MAX, -LADRC_GYRO_FILTER_INPUT_MAX};
        ladrc_real_t y[2];
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
        TEST_ASSERT_TRUE(isfinite((double)y[0]) && isfinite((double)y[1]));
    }
}

/* White-box: a history no sample within the bound can make, which overflows the first section
 * (a notch at 170 Hz: b1 x1 + b2 x2 = (2 cos(w0) g + g) LADRC_REAL_MAX = 1.7 LADRC_REAL_MAX). */
static void corrupt_channel(ladrc_gyro_filter_t *f, unsigned ch)
{
    f->hist[ch][0].x1 = -LADRC_REAL_MAX;
    f->hist[ch][0].x2 = LADRC_REAL_MAX;
}

static void test_a_state_that_would_overflow_is_held_with_a_state_fault(void)
{
    /* given: 2 channels running, channel 0's history corrupted */
    const ladrc_gyro_filter_config_t cfg = full_config(2u);
    const ladrc_gyro_filter_config_t cfg1 = full_config(1u);
    const ladrc_real_t rotors[2] = {LADRC_R(90.0), LADRC_R(130.0)};
    ladrc_gyro_filter_history_t before[LADRC_GYRO_FILTER_MAX_STAGES];
    ladrc_real_t x[2], y[2], y_ref, held;
    const ladrc_real_t zero[2] = {LADRC_R(0.0), LADRC_R(0.0)};
    int k;
    init_ok(&gf, &cfg);
    init_ok(&gf3, &cfg1);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf3, rotors);
    for (k = 0; k < 100; ++k) {
        x[0] = signal_at(k, 0);
        x[1] = signal_at(k, 1);
        (void)ladrc_gyro_filter_step(&gf, x, y);
        (void)ladrc_gyro_filter_step(&gf3, &x[1], &y_ref);
    }
    corrupt_channel(&gf, 0u);
    memcpy(before, gf.hist[0], sizeof before);
    held = gf.out[0];
    /* when */
    x[0] = signal_at(k, 0);
    x[1] = signal_at(k, 1);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(&gf, x, y));
    (void)ladrc_gyro_filter_step(&gf3, &x[1], &y_ref);
    /* then: channel 0's whole history and its output held; channel 1 ran on */
    TEST_ASSERT_EQUAL_MEMORY(before, gf.hist[0], sizeof before);
    TEST_ASSERT_EQUAL_MEMORY(&held, &y[0], sizeof held);
    TEST_ASSERT_EQUAL_MEMORY(&y_ref, &y[1], sizeof y_ref);
    /* then: a reset mends it */
    ladrc_gyro_filter_reset(&gf, zero);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, x, y));
}

static void test_a_state_fault_and_an_input_fault_on_one_tick_are_both_raised(void)
{
    ladrc_gyro_filter_config_t cfg = full_config(2u);
    const ladrc_real_t x[2] = {LADRC_R(0.5), (ladrc_real_t)NAN};
    ladrc_real_t y[2];
    init_ok(&gf, &cfg);
    corrupt_channel(&gf, 0u);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE | LADRC_FAULT_INPUT, ladrc_gyro_filter_step(&gf, x, y));
    TEST_ASSERT_TRUE(y[0] == LADRC_R(0.0));
    TEST_ASSERT_TRUE(y[1] == LADRC_R(0.0));
}

/* ------------------------------------------------------------- reset */

static void test_reset_puts_each_channel_at_rest_on_its_value(void)
{
    /* given: a filter in motion */
    const ladrc_gyro_filter_config_t cfg = full_config(3u);
    const ladrc_real_t rotors[2] = {LADRC_R(90.0), LADRC_R(130.0)};
    const ladrc_real_t rest[3] = {LADRC_R(0.5), LADRC_R(-2.0), LADRC_R(0.0)};
    int k, ch;
    init_ok(&gf, &cfg);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    for (k = 0; k < 300; ++k) {
        const ladrc_real_t x[3] = {signal_at(k, 0), signal_at(k, 1), signal_at(k, 2)};
        ladrc_real_t y[3];
        (void)ladrc_gyro_filter_step(&gf, x, y);
    }
    /* when */
    ladrc_gyro_filter_reset(&gf, rest);
    /* then: held on its value it stays there, to the float recurrence's fixed point (8 eps) */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, gf.faults);
    for (k = 0; k < 300; ++k) {
        ladrc_real_t y[3];
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&gf, rest, y));
        for (ch = 0; ch < 3; ++ch) {
            TEST_ASSERT_FLOAT_WITHIN(8.0 * LADRC_REAL_EPS * fabs((double)rest[ch]), rest[ch], y[ch]);
        }
    }
    /* and the RPM centres stayed */
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 1u, 2u));
}

static void test_reset_on_a_non_finite_value_rests_that_channel_on_its_latest_output(void)
{
    const ladrc_gyro_filter_config_t cfg = full_config(2u);
    const ladrc_real_t rest[2] = {LADRC_R(1.0), (ladrc_real_t)NAN};
    ladrc_real_t last;
    int k;
    init_ok(&gf, &cfg);
    for (k = 0; k < 50; ++k) {
        const ladrc_real_t x[2] = {signal_at(k, 0), signal_at(k, 1)};
        ladrc_real_t y[2];
        (void)ladrc_gyro_filter_step(&gf, x, y);
    }
    last = gf.out[1];
    ladrc_gyro_filter_reset(&gf, rest);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, gf.faults);
    TEST_ASSERT_EQUAL_MEMORY(&last, &gf.hist[1][0].x1, sizeof last);
    TEST_ASSERT_EQUAL_MEMORY(&last, &gf.hist[1][gf.n_sections - 1u].y2, sizeof last);
    TEST_ASSERT_TRUE(gf.out[0] == LADRC_R(1.0));
}

static void run_sequence(ladrc_gyro_filter_t *f, ladrc_real_t *out, int n)
{
    int k;
    for (k = 0; k < n; ++k) {
        const ladrc_real_t rotors[2] = {(ladrc_real_t)(80.0 + 0.05 * k), (ladrc_real_t)(140.0 - 0.05 * k)};
        const ladrc_real_t x[2] = {signal_at(k, 0), signal_at(k, 1)};
        (void)ladrc_gyro_filter_set_rotor_hz(f, rotors);
        (void)ladrc_gyro_filter_step(f, x, &out[2 * k]);
    }
}

static void test_a_run_repeats_bitwise_after_reset(void)
{
    static ladrc_real_t first[2 * 500], second[2 * 500];
    const ladrc_gyro_filter_config_t cfg = full_config(2u);
    const ladrc_real_t zero[2] = {LADRC_R(0.0), LADRC_R(0.0)};
    init_ok(&gf, &cfg);
    run_sequence(&gf, first, 500);
    ladrc_gyro_filter_reset(&gf, zero);
    run_sequence(&gf, second, 500);
    TEST_ASSERT_EQUAL_MEMORY(first, second, sizeof first);
}

/* ------------------------------------------------------------- channels */

static void test_channels_are_independent(void)
{
    /* given: six channels with different signals, and one single-channel filter per channel */
    const ladrc_gyro_filter_config_t cfg6 = full_config(6u);
    const ladrc_gyro_filter_config_t cfg1 = full_config(1u);
    const ladrc_real_t rotors[2] = {LADRC_R(90.0), LADRC_R(130.0)};
    static ladrc_real_t y6[300][6];
    int ch, k;
    init_ok(&gf, &cfg6);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    for (k = 0; k < 300; ++k) {
        ladrc_real_t x[6];
        for (ch = 0; ch < 6; ++ch) {
            x[ch] = (ch == 3) ? LADRC_R(0.0) : signal_at(k * (ch + 1), ch);
        }
        (void)ladrc_gyro_filter_step(&gf, x, y6[k]);
    }
    /* then: each channel equals its lone filter, bit for bit */
    for (ch = 0; ch < 6; ++ch) {
        init_ok(&gf2, &cfg1);
        (void)ladrc_gyro_filter_set_rotor_hz(&gf2, rotors);
        for (k = 0; k < 300; ++k) {
            const ladrc_real_t x = (ch == 3) ? LADRC_R(0.0) : signal_at(k * (ch + 1), ch);
            ladrc_real_t y;
            (void)ladrc_gyro_filter_step(&gf2, &x, &y);
            TEST_ASSERT_EQUAL_MEMORY(&y, &y6[k][ch], sizeof y);
        }
    }
}

static void test_the_filter_runs_in_place(void)
{
    const ladrc_gyro_filter_config_t cfg = full_config(3u);
    int k;
    init_ok(&gf, &cfg);
    init_ok(&gf2, &cfg);
    for (k = 0; k < 100; ++k) {
        ladrc_real_t buf[3] = {signal_at(k, 0), signal_at(k, 1), signal_at(k, 2)};
        ladrc_real_t out[3];
        (void)ladrc_gyro_filter_step(&gf2, buf, out);
        (void)ladrc_gyro_filter_step(&gf, buf, buf);
        TEST_ASSERT_EQUAL_MEMORY(out, buf, sizeof out);
    }
}

static void test_the_weight_getter_refuses_what_is_not_a_notch(void)
{
    const ladrc_gyro_filter_config_t cfg = rpm_config(1u, 2u, 3u);
    const ladrc_real_t rotors[2] = {LADRC_R(100.0), LADRC_R(100.0)};
    init_ok(&gf, &cfg);
    (void)ladrc_gyro_filter_set_rotor_hz(&gf, rotors);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, ladrc_gyro_filter_get_rpm_weight(&gf, 1u, 3u));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 2u, 1u));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 0u));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_gyro_filter_get_rpm_weight(&gf, 0u, 4u));
}

static void test_functions_tolerate_null_pointers(void)
{
    const ladrc_gyro_filter_config_t cfg = notch_config(100.0, 5.0);
    ladrc_real_t x = LADRC_R(1.0);
    ladrc_real_t y = LADRC_R(-7.0);
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    init_ok(&gf, &cfg);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(NULL, &x, &y));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(&gf, NULL, &y));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(&gf, &x, NULL));
    TEST_ASSERT_TRUE(y == LADRC_R(-7.0));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_set_rotor_hz(NULL, &x));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_set_rotor_hz(&gf, NULL));
    ladrc_gyro_filter_reset(NULL, &x);
    ladrc_gyro_filter_reset(&gf, NULL);
    TEST_ASSERT_TRUE(ladrc_gyro_filter_get_rpm_weight(NULL, 0u, 1u) == LADRC_R(0.0));
    ladrc_gyro_filter_config_default(NULL, LADRC_R(0.001), 1u); /* nothing happens */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_notch_removes_its_centre);
    RUN_TEST(test_a_notch_passes_frequencies_far_from_its_centre);
    RUN_TEST(test_a_notch_has_its_minus_3_db_points_near_f0_plus_minus_f0_over_2q);
    RUN_TEST(test_a_notch_follows_its_closed_form_across_the_band);
    RUN_TEST(test_fixed_notches_chain);
    RUN_TEST(test_a_first_order_low_pass_is_3_db_down_at_its_cutoff_with_dc_gain_1);
    RUN_TEST(test_a_second_order_low_pass_is_3_db_down_at_its_cutoff_with_dc_gain_1);
    RUN_TEST(test_the_chain_is_notches_then_low_pass);
    RUN_TEST(test_an_rpm_bank_takes_every_line_of_four_rotors_out);
    RUN_TEST(test_moving_centres_follow_a_swept_line);
    RUN_TEST(test_centres_moving_fast_and_glitching_stay_bounded);
    RUN_TEST(test_centres_jumping_at_random_every_tick_stay_bounded);
    RUN_TEST(test_the_rpm_bank_recovers_by_itself_after_a_second_of_garbage_telemetry);
    RUN_TEST(test_alternating_telemetry_on_a_full_bank_stays_bounded_and_recovers);
    RUN_TEST(test_a_rotor_with_a_bad_speed_keeps_its_notches_and_the_others_move);
    RUN_TEST(test_rpm_notches_are_off_until_the_first_rotor_speed_and_then_exact_at_zero_weight);
    RUN_TEST(test_the_fade_weights_a_notch_linearly_from_min_to_min_plus_fade);
    RUN_TEST(test_without_a_fade_a_notch_is_fully_on_from_min);
    RUN_TEST(test_a_notch_fading_in_and_out_makes_no_step_in_a_passing_signal);
    RUN_TEST(test_notches_at_or_above_the_nyquist_guard_are_off);
    RUN_TEST(test_init_reports_the_first_bad_field_in_the_documented_order);
    RUN_TEST(test_init_rejects_each_bad_field);
    RUN_TEST(test_init_checks_the_narrowest_rpm_notch_at_both_ends);
    RUN_TEST(test_init_does_not_read_the_fields_of_stages_that_are_off);
    RUN_TEST(test_init_rejects_null_pointers);
    RUN_TEST(test_a_filter_init_refused_is_zeroed_and_its_steps_write_nothing);
    RUN_TEST(test_config_default_turns_every_stage_off_and_each_can_be_switched_on);
    RUN_TEST(test_a_non_finite_input_holds_its_channel_and_the_rest_runs_as_if_it_were_skipped);
    RUN_TEST(test_a_huge_sample_is_an_input_fault_and_never_latches);
    RUN_TEST(test_a_state_that_would_overflow_is_held_with_a_state_fault);
    RUN_TEST(test_a_state_fault_and_an_input_fault_on_one_tick_are_both_raised);
    RUN_TEST(test_reset_puts_each_channel_at_rest_on_its_value);
    RUN_TEST(test_reset_on_a_non_finite_value_rests_that_channel_on_its_latest_output);
    RUN_TEST(test_a_run_repeats_bitwise_after_reset);
    RUN_TEST(test_channels_are_independent);
    RUN_TEST(test_the_filter_runs_in_place);
    RUN_TEST(test_the_weight_getter_refuses_what_is_not_a_notch);
    RUN_TEST(test_functions_tolerate_null_pointers);
    return UNITY_END();
}
