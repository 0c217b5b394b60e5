/* SPDX-License-Identifier: BSD-3-Clause */
/* The replay's setpoint smoothing (log/setpoint_smooth.h): a radio link's
 * steps learned and low-passed as Betaflight's automatic RC smoothing does;
 * a setpoint that is already smooth, or a scripted step sequence, passed
 * unchanged; yaw smoothed across its wrap at +-pi without a sweep. */
#include "unity.h"
#include "log/setpoint_smooth.h"
#include "run/spectrum.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define DT_S 0.001
#define LINK_HZ 150.0
/* 1000 / 150 ticks per frame: intervals of 6 and 7 ticks averaging 6.67;
 * the mean over the training's intervals is within a tick of it over 64: 2.5 %. */
#define LINK_REL_TOL 0.025
/* A second-order Butterworth at 0.375 x 150 = 56.25 Hz passes
 * 1 / sqrt(1 + (150 / 56.25)^4) = 0.139 at the link's rate, less above;
 * the band above 100 Hz keeps at most that share (0.16 allows the bins'
 * spread over the Hann window). */
#define HIGH_BAND_MAX_SHARE 0.16

void setUp(void)
{
}
void tearDown(void)
{
}

/* A pilot's stick: a rate of 2 rad/s at 1.3 Hz, sampled by a 150 Hz link. */
static double stick_rate(long long k, double link_hz)
{
    const double frame_t = floor((double)k * DT_S * link_hz) / link_hz;
    return 2.0 * sin(2.0 * PI * 1.3 * frame_t);
}

static void test_a_link_is_learned_and_its_steps_smoothed(void)
{
    static setpoint_smooth_t s;
    static sim_spectrum_t raw, smooth;
    setpoint_smooth_init(&s, DT_S);
    sim_spectrum_init(&raw, 1.0 / DT_S);
    sim_spectrum_init(&smooth, 1.0 / DT_S);
    double angle = 0.0, prev_smoothed = 0.0;
    for (long long k = 0; k < 20000; ++k) {
        const double rate[3] = {stick_rate(k, LINK_HZ), 0.5 * stick_rate(k, LINK_HZ), 0.0};
        angle += rate[0] * DT_S;
        double ref[3] = {angle, 0.5 * angle, 0.0};
        setpoint_smooth_step(&s, rate, ref);
        if (k > 2000) { /* learned by then: 256 intervals on two axes take 0.86 s */
            sim_spectrum_push(&raw, rate[0]);
            sim_spectrum_push(&smooth, (ref[0] - prev_smoothed) / DT_S);
        }
        prev_smoothed = ref[0];
    }
    TEST_ASSERT_EQUAL_INT(SETPOINT_SMOOTH_ON, s.state);
    TEST_ASSERT_FLOAT_WITHIN(LINK_REL_TOL * LINK_HZ, LINK_HZ, s.link_hz);
    TEST_ASSERT_FLOAT_WITHIN(LINK_REL_TOL * 0.375 * LINK_HZ, 0.375 * LINK_HZ, s.cutoff_hz);
    const double before = sim_spectrum_band_rms(&raw, 100.0, INFINITY);
    const double after = sim_spectrum_band_rms(&smooth, 100.0, INFINITY);
    TEST_ASSERT_TRUE(before > 0.0);
    TEST_ASSERT_TRUE(after < HIGH_BAND_MAX_SHARE * before);
}

static void test_a_setpoint_stepping_every_tick_passes_unchanged(void)
{
    static setpoint_smooth_t s;
    setpoint_smooth_init(&s, DT_S);
    for (long long k = 0; k < 5000; ++k) {
        const double t = (double)k * DT_S;
        const double rate[3] = {cos(3.0 * t), sin(2.0 * t), 0.3 + 0.1 * t};
        double ref[3] = {sin(3.0 * t) / 3.0, -cos(2.0 * t) / 2.0, 0.3 * t};
        const double copy[3] = {ref[0], ref[1], ref[2]};
        setpoint_smooth_step(&s, rate, ref);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(copy[i] == ref[i]); /* bit for bit: nothing applied */
        }
    }
    TEST_ASSERT_EQUAL_INT(SETPOINT_SMOOTH_ALREADY, s.state);
}

static void test_scripted_steps_are_not_a_link(void)
{
    static setpoint_smooth_t s;
    setpoint_smooth_init(&s, DT_S);
    for (long long k = 0; k < 200000; ++k) {
        const double level = (double)((k / 500) % 3) - 1.0; /* a step every 0.5 s */
        const double logged[3] = {0.2 * level, 0.0, 0.0};   /* an angle setpoint: its steps counted on it */
        double ref[3] = {logged[0], logged[1], logged[2]};
        setpoint_smooth_step(&s, logged, ref);
        TEST_ASSERT_TRUE(0.2 * level == ref[0]);
    }
    TEST_ASSERT_EQUAL_INT(SETPOINT_SMOOTH_NO_LINK, s.state);
}

static void test_yaw_is_smoothed_across_its_wrap(void)
{
    static setpoint_smooth_t s;
    setpoint_smooth_init(&s, DT_S);
    double yaw = 3.0, max_gap = 0.0;
    for (long long k = 0; k < 6000; ++k) {
        const double rate[3] = {0.0, 0.0, stick_rate(k, LINK_HZ) > 0 ? 1.0 : 1.0 + 0.1 * stick_rate(k, LINK_HZ)};
        yaw += rate[2] * DT_S;
        const double wrapped = yaw - 2.0 * PI * floor((yaw + PI) / (2.0 * PI));
        double ref[3] = {0.0, 0.0, wrapped};
        setpoint_smooth_step(&s, rate, ref);
        max_gap = fmax(max_gap, fabs(ref[2] - wrapped));
    }
    TEST_ASSERT_EQUAL_INT(SETPOINT_SMOOTH_ON, s.state);
    /* 1.2 rad/s at most through a filter of 2.8 ms group delay: the lag is
     * under 0.01 rad; a sweep across the wrap would be 2 pi */
    TEST_ASSERT_TRUE(max_gap < 0.01);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_link_is_learned_and_its_steps_smoothed);
    RUN_TEST(test_a_setpoint_stepping_every_tick_passes_unchanged);
    RUN_TEST(test_scripted_steps_are_not_a_link);
    RUN_TEST(test_yaw_is_smoothed_across_its_wrap);
    return UNITY_END();
}
