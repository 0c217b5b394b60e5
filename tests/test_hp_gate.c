/* SPDX-License-Identifier: BSD-3-Clause */
/* HP-MLADRC on the gyro: its gate on a realistic sensor (estimator.h
 * "Gate"). The small plant of test_gyro_quad.h with the library's online
 * search (first guess 3 rad/s). The gyro carries white noise and two rotor
 * lines, the plant a turbulence: white noise through a
 * first-order low-pass, so its phasor at any frequency wanders slowly, the
 * hardest case for a gate that looks for a phasor standing still. Against
 * LP-MLADRC with the same gains on the same noise. */
#include "unity.h"
#include "test_axis_command.h"
#include "test_gyro_quad.h"
#include "test_noise.h"
#include "test_plant.h"
#include "ladrc/axis.h"

#include <math.h>
#include <stdio.h>

/* The tone: 20 rad/s^2 at 6 rad/s (the search must find it from 3 rad/s)
 * from ONSET_S to STOP_S. */
#define TONE_RAD_S2 20.0
#define TONE_W_RAD_S 6.0
#define ONSET_S 2.0
#define STOP_S 40.0
/* The gate opens within this of the onset (measured 6.6 s: the search
 * moves the tone from 3 to 6 rad/s through the turbulence, then a window of
 * a period, 1.05 s). */
#define ENGAGE_MAX_S 8.0
/* Engaged, the error's component at the tone is at most this share of
 * LP-MLADRC's (the acceptance asks 0.3x; measured 0.008x) and the whole
 * error at most 2 % above it (measured 0.092x). */
#define BAND_RATIO_MAX 0.3
#define WHOLE_RATIO_MAX 1.02
/* It lets go within two periods of the tone's end, 2.1 s (measured 1.25 s). */
#define LET_GO_PERIODS 2.0
/* Tone-free, the gate may be open at most 1 s per hour (the acceptance);
 * the host flies 20 min, the cross build (under qemu, 0.1 s per simulated
 * second) 60 s. Measured: never open. */
#ifndef FREE_FLIGHT_S
#define FREE_FLIGHT_S 1200.0
#endif
#define FALSE_OPEN_S_PER_H 1.0

void setUp(void)
{
}
void tearDown(void)
{
}

typedef struct {
    double amp, stop_s; /* tone amp sin(w t) over (ONSET_S, stop_s] */
} tone_t;

typedef struct {
    double engaged_s; /* from the onset until the weight first reaches 1 (HUGE_VAL: never) */
    double open_s;    /* time with the weight above 0 */
    double let_go_s;  /* from the stop until the weight is 0 (HUGE_VAL: never) */
    double band_rad;  /* amplitude of the angle error at the tone over the window */
    double rms_rad;   /* RMS angle error over the window */
} flight_t;

/* Flies duration_s; the window for the error runs from from_s to to_s
 * (whole periods of the tone). */
static flight_t fly(ladrc_variant_t variant, const tone_t *tone, double duration_s, double from_s, double to_s)
{
    const ladrc_axis_config_t cfg = test_gyro_quad_config(variant);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    unsigned seed = 2463534242u;
    test_gyro_quad_air_t air = {0.0, 0.0, 0.0, 0.0};
    flight_t f = {.engaged_s = HUGE_VAL, .open_s = 0.0, .let_go_s = HUGE_VAL, .band_rad = 0.0, .rms_rad = 0.0};
    double sum_sq = 0.0, re = 0.0, im = 0.0;
    long samples = 0;
    const long n = (long)(duration_s / DT_S + 0.5);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * DT_S;
        const ladrc_real_t angle = (ladrc_real_t)(air.y_rad + ANGLE_NOISE_RAD * test_gaussian(&seed));
        const ladrc_real_t rate =
            (ladrc_real_t)(air.w_rad_s + GYRO_NOISE_RAD_S * test_gaussian(&seed) + test_gyro_quad_lines_rad_s(t));
        const double u = axis_command_with_rate(&axis, 0.0f, angle, rate);
        const ladrc_hp_estimator_t *hp = ladrc_axis_get_hp(&axis);
        if (hp != NULL) {
            const double weight = (double)ladrc_hp_get_weight(hp);
            f.open_s += (weight > 0.0) ? DT_S : 0.0;
            if (t > ONSET_S && t <= tone->stop_s && weight >= 1.0 && f.engaged_s == HUGE_VAL) {
                f.engaged_s = t - ONSET_S;
            }
            if (t > tone->stop_s && weight == 0.0 && f.let_go_s == HUGE_VAL) {
                f.let_go_s = t - tone->stop_s;
            }
        }
        test_gyro_quad_air_step(&air, u, (t > ONSET_S && t <= tone->stop_s) ? tone->amp * sin(TONE_W_RAD_S * t) : 0.0,
                                &seed);
        TEST_ASSERT_TRUE_MESSAGE(isfinite(air.y_rad) && fabs(air.y_rad) < 1.0, "diverged");
        if (t >= from_s && t < to_s) {
            sum_sq += air.y_rad * air.y_rad;
            re += air.y_rad * cos(TONE_W_RAD_S * t);
            im += air.y_rad * sin(TONE_W_RAD_S * t);
            samples++;
        }
    }
    if (samples > 0) {
        f.rms_rad = sqrt(sum_sq / (double)samples);
        f.band_rad = 2.0 * sqrt(re * re + im * im) / (double)samples;
    }
    return f;
}

/* The window after the gate has had ENGAGE_MAX_S: whole periods of the tone. */
static double window_end(double from_s)
{
    const double period_s = 2.0 * PI / TONE_W_RAD_S;
    return from_s + floor((STOP_S - from_s) / period_s) * period_s;
}

static void test_a_tone_in_turbulence_and_vibration_engages_and_leaves_a_fraction_of_lps_error(void)
{
    const tone_t tone = {.amp = TONE_RAD_S2, .stop_s = STOP_S};
    const double from_s = ONSET_S + ENGAGE_MAX_S;
    const double to_s = window_end(from_s);
    const flight_t hp = fly(LADRC_VARIANT_HP_MLADRC, &tone, STOP_S, from_s, to_s);
    const flight_t lp = fly(LADRC_VARIANT_LP_MLADRC, &tone, STOP_S, from_s, to_s);
    char msg[160];
    snprintf(msg, sizeof msg, "engaged %.2f s after the onset; at the tone HP %.5f deg, LP %.5f deg (%.3fx); RMS %.3fx",
             hp.engaged_s, hp.band_rad / DEG, lp.band_rad / DEG, hp.band_rad / lp.band_rad, hp.rms_rad / lp.rms_rad);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.engaged_s <= ENGAGE_MAX_S, msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.band_rad <= BAND_RATIO_MAX * lp.band_rad, msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.rms_rad <= WHOLE_RATIO_MAX * lp.rms_rad, msg);
}

static void test_the_gate_lets_go_within_two_periods_of_the_tones_end(void)
{
    const tone_t tone = {.amp = TONE_RAD_S2, .stop_s = 20.0};
    const flight_t hp = fly(LADRC_VARIANT_HP_MLADRC, &tone, 25.0, 0.0, 0.0);
    char msg[96];
    snprintf(msg, sizeof msg, "engaged %.2f s after the onset, let go %.3f s after the end", hp.engaged_s, hp.let_go_s);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.engaged_s <= ENGAGE_MAX_S, msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.let_go_s <= LET_GO_PERIODS * 2.0 * PI / TONE_W_RAD_S, msg);
}

static void test_without_a_tone_the_gate_stays_shut_in_turbulence_and_vibration(void)
{
    const tone_t none = {.amp = 0.0, .stop_s = 0.0};
    const flight_t hp = fly(LADRC_VARIANT_HP_MLADRC, &none, FREE_FLIGHT_S, 0.0, 0.0);
    char msg[96];
    snprintf(msg, sizeof msg, "open %.3f s in %.0f s of tone-free flight", hp.open_s, FREE_FLIGHT_S);
    TEST_MESSAGE(msg);
    TEST_ASSERT_TRUE_MESSAGE(hp.open_s <= FALSE_OPEN_S_PER_H * FREE_FLIGHT_S / 3600.0, msg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_tone_in_turbulence_and_vibration_engages_and_leaves_a_fraction_of_lps_error);
    RUN_TEST(test_the_gate_lets_go_within_two_periods_of_the_tones_end);
    RUN_TEST(test_without_a_tone_the_gate_stays_shut_in_turbulence_and_vibration);
    return UNITY_END();
}
