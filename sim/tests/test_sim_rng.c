/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator RNG: published reference outputs, determinism, and the moments
 * of the uniform and normal deviates. */
#include "unity.h"
#include "plant/rng.h"

#include <math.h>
#include <stdint.h>

/* Sample size of the statistical checks. Each bound below is 5 standard
 * errors of the statistic for N samples of a correct generator: a false
 * failure has probability below 1e-6 per check, while the checks are
 * deterministic for the fixed seeds used (they pass or fail every run). */
#define N_SAMPLES 100000
#define SIGMAS 5.0

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_splitmix64_gives_the_published_outputs_from_zero(void)
{
    uint64_t x = 0;
    TEST_ASSERT_TRUE(sim_rng_splitmix64(&x) == UINT64_C(0xE220A8397B1DCDAF));
    TEST_ASSERT_TRUE(sim_rng_splitmix64(&x) == UINT64_C(0x6E789E6AA1B965F4));
    TEST_ASSERT_TRUE(sim_rng_splitmix64(&x) == UINT64_C(0x06C45D188009454F));
    TEST_ASSERT_TRUE(sim_rng_splitmix64(&x) == UINT64_C(0xF88BB8A8724C81EC));
}

static void test_seeding_fills_the_state_with_four_splitmix_outputs(void)
{
    sim_rng_t r;
    sim_rng_seed(&r, 0);
    TEST_ASSERT_TRUE(r.s[0] == UINT64_C(0xE220A8397B1DCDAF));
    TEST_ASSERT_TRUE(r.s[1] == UINT64_C(0x6E789E6AA1B965F4));
    TEST_ASSERT_TRUE(r.s[2] == UINT64_C(0x06C45D188009454F));
    TEST_ASSERT_TRUE(r.s[3] == UINT64_C(0xF88BB8A8724C81EC));
    TEST_ASSERT_EQUAL_INT(0, r.has_spare);
}

static void test_xoshiro256starstar_gives_the_published_outputs_from_state_1_2_3_4(void)
{
    /* the reference vector of the algorithm's authors for s = {1, 2, 3, 4} */
    static const uint64_t expected[10] = {UINT64_C(11520),
                                          UINT64_C(0),
                                          UINT64_C(1509978240),
                                          UINT64_C(1215971899390074240),
                                          UINT64_C(1216172134540287360),
                                          UINT64_C(607988272756665600),
                                          UINT64_C(16172922978634559625),
                                          UINT64_C(8476171486693032832),
                                          UINT64_C(10595114339597558777),
                                          UINT64_C(2904607092377533576)};
    sim_rng_t r = {.s = {1, 2, 3, 4}, .spare = 0.0, .has_spare = 0};
    for (int i = 0; i < 10; ++i) {
        TEST_ASSERT_TRUE(sim_rng_next(&r) == expected[i]);
    }
}

static void test_same_seed_gives_the_same_sequence(void)
{
    sim_rng_t a, b;
    sim_rng_seed(&a, 12345);
    sim_rng_seed(&b, 12345);
    for (int i = 0; i < 1000; ++i) {
        TEST_ASSERT_TRUE(sim_rng_next(&a) == sim_rng_next(&b));
        TEST_ASSERT_TRUE(sim_rng_gauss(&a) == sim_rng_gauss(&b));
        TEST_ASSERT_TRUE(sim_rng_uniform(&a) == sim_rng_uniform(&b));
    }
    /* reseeding restarts the sequence, spare normal deviate included */
    sim_rng_t c;
    sim_rng_seed(&c, 12345);
    const double first = sim_rng_gauss(&c);
    (void)sim_rng_gauss(&c);
    (void)sim_rng_gauss(&c); /* leaves a spare */
    sim_rng_seed(&c, 12345);
    TEST_ASSERT_TRUE(sim_rng_gauss(&c) == first);
}

static void test_different_seeds_give_different_sequences(void)
{
    /* neighbouring seeds, the worst case for a weak seeding: two equal
     * 64-bit outputs at the same position have probability 2^-64 each */
    static const uint64_t seeds[][2] = {{0, 1}, {1, 2}, {42, 43}, {0, UINT64_MAX}};
    for (unsigned k = 0; k < sizeof seeds / sizeof seeds[0]; ++k) {
        sim_rng_t a, b;
        sim_rng_seed(&a, seeds[k][0]);
        sim_rng_seed(&b, seeds[k][1]);
        for (int i = 0; i < 1000; ++i) {
            TEST_ASSERT_TRUE(sim_rng_next(&a) != sim_rng_next(&b));
        }
    }
}

static void test_uniform_is_in_range_with_the_mean_variance_and_spread_of_u01(void)
{
    static const uint64_t seeds[] = {1, 2024, UINT64_C(0xDEADBEEF)};
    for (unsigned k = 0; k < sizeof seeds / sizeof seeds[0]; ++k) {
        sim_rng_t r;
        sim_rng_seed(&r, seeds[k]);
        enum { BINS = 10 };
        long count[BINS] = {0};
        double sum = 0.0, sum2 = 0.0;
        for (int i = 0; i < N_SAMPLES; ++i) {
            const double u = sim_rng_uniform(&r);
            TEST_ASSERT_TRUE(u >= 0.0 && u < 1.0);
            sum += u;
            sum2 += (u - 0.5) * (u - 0.5);
            ++count[(int)(u * BINS)];
        }
        const double n = N_SAMPLES;
        const double mean = sum / n;
        const double var = sum2 / n - (mean - 0.5) * (mean - 0.5);
        /* mean: standard error sqrt(1/12 / N) = 9.1e-4 */
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(1.0 / 12.0 / n), 0.5, mean);
        /* variance: standard error sqrt((mu4 - sigma^4) / N) with mu4 = 1/80,
         * sigma^4 = 1/144, i.e. 2.4e-4 */
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt((1.0 / 80.0 - 1.0 / 144.0) / n), 1.0 / 12.0, var);
        /* each tenth holds N/10 values, binomial standard error sqrt(N p (1-p)) = 95 */
        for (int b = 0; b < BINS; ++b) {
            TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(n * 0.1 * 0.9), n / BINS, (double)count[b]);
        }
    }
}

static void test_gauss_has_the_mean_variance_kurtosis_and_tails_of_a_standard_normal(void)
{
    static const uint64_t seeds[] = {1, 2024, UINT64_C(0xDEADBEEF)};
    for (unsigned k = 0; k < sizeof seeds / sizeof seeds[0]; ++k) {
        sim_rng_t r;
        sim_rng_seed(&r, seeds[k]);
        double sum = 0.0, sum2 = 0.0, sum3 = 0.0, sum4 = 0.0;
        long beyond_2 = 0;
        double lag_sum = 0.0, prev = 0.0;
        for (int i = 0; i < N_SAMPLES; ++i) {
            const double g = sim_rng_gauss(&r);
            TEST_ASSERT_TRUE(isfinite(g));
            sum += g;
            sum2 += g * g;
            sum3 += g * g * g;
            sum4 += g * g * g * g;
            beyond_2 += fabs(g) > 2.0;
            lag_sum += g * prev; /* pairs share one polar draw: check they are uncorrelated */
            prev = g;
        }
        const double n = N_SAMPLES;
        /* standard errors for N(0,1): mean 1/sqrt(N) = 3.2e-3; E[g^2] sqrt(2/N)
         * = 4.5e-3; E[g^3] sqrt(15/N) = 1.2e-2; E[g^4] sqrt((105 - 9)/N) = 3.1e-2;
         * E[g_k g_k-1] 1/sqrt(N) */
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS / sqrt(n), 0.0, sum / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(2.0 / n), 1.0, sum2 / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(15.0 / n), 0.0, sum3 / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(96.0 / n), 3.0, sum4 / n);
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS / sqrt(n), 0.0, lag_sum / n);
        /* P(|g| > 2) = erfc(2 / sqrt 2) = 0.0455, binomial standard error 6.6e-4 */
        const double p2 = erfc(sqrt(2.0));
        TEST_ASSERT_FLOAT_WITHIN(SIGMAS * sqrt(p2 * (1.0 - p2) / n), p2, beyond_2 / n);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_splitmix64_gives_the_published_outputs_from_zero);
    RUN_TEST(test_seeding_fills_the_state_with_four_splitmix_outputs);
    RUN_TEST(test_xoshiro256starstar_gives_the_published_outputs_from_state_1_2_3_4);
    RUN_TEST(test_same_seed_gives_the_same_sequence);
    RUN_TEST(test_different_seeds_give_different_sequences);
    RUN_TEST(test_uniform_is_in_range_with_the_mean_variance_and_spread_of_u01);
    RUN_TEST(test_gauss_has_the_mean_variance_kurtosis_and_tails_of_a_standard_normal);
    return UNITY_END();
}
