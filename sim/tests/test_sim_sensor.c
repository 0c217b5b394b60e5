/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator sensor: argument checks, exact pass-through without noise, the
 * delay line, and the noise statistics. */
#include "unity.h"
#include "plant/sensor.h"

#include <math.h>

/* Noise statistics over N samples; bounds are 5 standard errors of each
 * statistic for a correct generator (false failure below 1e-6 per check;
 * the seeds are fixed, so each check passes or fails every run). */
#define N_SAMPLES 100000
#define SIGMAS 5.0

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_bad_arguments_are_rejected(void)
{
    sim_sensor_t s;
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(NULL, 0.0, 0.0, 0, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, -1e-3, 0.0, 0, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, 0.0, -1e-3, 0, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, NAN, 0.0, 0, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, 0.0, INFINITY, 0, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, 0.0, 0.0, -1, 1));
    TEST_ASSERT_EQUAL_INT(-1, sim_sensor_init(&s, 0.0, 0.0, SIM_SENSOR_MAX_DELAY + 1, 1));
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 0.0, 0.0, SIM_SENSOR_MAX_DELAY, 1));
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 1e-3, 1e-2, 0, 1));
}

static void truth_at(int k, double angle[3], double rate[3])
{
    for (int i = 0; i < 3; ++i) {
        angle[i] = sin(0.01 * k + i) + 1e-3 * k;
        rate[i] = cos(0.02 * k - i) - 1e-3 * k;
    }
}

static void test_without_noise_or_delay_the_truth_passes_exactly(void)
{
    sim_sensor_t s;
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 0.0, 0.0, 0, 7));
    for (int k = 0; k < 1000; ++k) {
        double angle[3], rate[3], am[3], rm[3];
        truth_at(k, angle, rate);
        if (k == 5) {
            angle[0] = -0.0; /* bit for bit, sign of zero included */
        }
        sim_sensor_measure(&s, angle, rate, am, rm);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(am[i] == angle[i] && rm[i] == rate[i]);
            TEST_ASSERT_TRUE(signbit(am[i]) == signbit(angle[i]));
        }
    }
}

static void test_delay_returns_the_truth_of_n_calls_ago_and_repeats_the_first_at_start(void)
{
    static const int delays[] = {1, 3, 17, SIM_SENSOR_MAX_DELAY};
    for (unsigned d = 0; d < sizeof delays / sizeof delays[0]; ++d) {
        const int n = delays[d];
        sim_sensor_t s;
        TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 0.0, 0.0, n, 7));
        for (int k = 0; k < 500; ++k) {
            double angle[3], rate[3], am[3], rm[3], expect_a[3], expect_r[3];
            truth_at(k, angle, rate);
            sim_sensor_measure(&s, angle, rate, am, rm);
            truth_at(k >= n ? k - n : 0, expect_a, expect_r);
            for (int i = 0; i < 3; ++i) {
                TEST_ASSERT_TRUE(am[i] == expect_a[i] && rm[i] == expect_r[i]);
            }
        }
    }
}

static void test_noise_has_the_configured_std_and_is_white_and_zero_mean(void)
{
    const double angle_std = sqrt(0.001) * 3.14159265358979323846 / 180.0; /* the paper's 0.001 deg^2 */
    const double rate_std = 0.05;
    sim_sensor_t s;
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, angle_std, rate_std, 2, 2024));
    double sum[6] = {0}, sum2[6] = {0}, lag[6] = {0}, prev[6] = {0}, cross = 0.0;
    for (int k = 0; k < N_SAMPLES; ++k) {
        double angle[3], rate[3], am[3], rm[3];
        truth_at(k, angle, rate);
        sim_sensor_measure(&s, angle, rate, am, rm);
        double expect_a[3], expect_r[3];
        truth_at(k >= 2 ? k - 2 : 0, expect_a, expect_r);
        double e[6];
        for (int i = 0; i < 3; ++i) {
            e[i] = (am[i] - expect_a[i]) / angle_std;
            e[3 + i] = (rm[i] - expect_r[i]) / rate_std;
        }
        for (int c = 0; c < 6; ++c) {
            sum[c] += e[c];
            sum2[c] += e[c] * e[c];
            lag[c] += e[c] * prev[c];
            prev[c] = e[c];
        }
        cross += e[0] * e[3];
    }
    const double n = N_SAMPLES;
    for (int c = 0; c < 6; ++c) {
        /* normalised noise: mean 0 (standard error 1/sqrt(N) = 3.2e-3),
         * variance 1 (sqrt(2/N) = 4.5e-3, i.e. the std within 0.23% per
         * sigma), lag-1 correlation 0 (1/sqrt(N)) */
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS / sqrt(n), 0.0, sum[c] / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(2.0 / n), 1.0, sum2[c] / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS / sqrt(n), 0.0, lag[c] / n);
    }
    /* angle and rate noise independent */
    TEST_ASSERT_FLOAT_WITHIN(SIGMAS / sqrt(n), 0.0, cross / n);
}

static void test_same_seed_same_noise_and_one_quantity_does_not_shift_the_other(void)
{
    sim_sensor_t a, b, c;
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&a, 1e-3, 1e-2, 0, 99));
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&b, 1e-3, 1e-2, 0, 99));
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&c, 1e-3, 0.0, 0, 99)); /* rate noise off */
    for (int k = 0; k < 1000; ++k) {
        double angle[3], rate[3], aa[3], ar[3], ba[3], br[3], ca[3], cr[3];
        truth_at(k, angle, rate);
        sim_sensor_measure(&a, angle, rate, aa, ar);
        sim_sensor_measure(&b, angle, rate, ba, br);
        sim_sensor_measure(&c, angle, rate, ca, cr);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(aa[i] == ba[i] && ar[i] == br[i]);
            TEST_ASSERT_TRUE(ca[i] == aa[i]);   /* same angle noise */
            TEST_ASSERT_TRUE(cr[i] == rate[i]); /* rate exact */
        }
    }
}

static void test_reinit_restarts_the_delay_line_and_the_noise(void)
{
    sim_sensor_t s;
    double angle[3], rate[3], first_a[3], first_r[3], am[3], rm[3];
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 1e-3, 1e-2, 4, 5));
    truth_at(100, angle, rate);
    sim_sensor_measure(&s, angle, rate, first_a, first_r);
    for (int k = 0; k < 10; ++k) {
        truth_at(k, angle, rate);
        sim_sensor_measure(&s, angle, rate, am, rm);
    }
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, 1e-3, 1e-2, 4, 5));
    truth_at(100, angle, rate);
    sim_sensor_measure(&s, angle, rate, am, rm);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(am[i] == first_a[i] && rm[i] == first_r[i]);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_bad_arguments_are_rejected);
    RUN_TEST(test_without_noise_or_delay_the_truth_passes_exactly);
    RUN_TEST(test_delay_returns_the_truth_of_n_calls_ago_and_repeats_the_first_at_start);
    RUN_TEST(test_noise_has_the_configured_std_and_is_white_and_zero_mean);
    RUN_TEST(test_same_seed_same_noise_and_one_quantity_does_not_shift_the_other);
    RUN_TEST(test_reinit_restarts_the_delay_line_and_the_noise);
    return UNITY_END();
}
