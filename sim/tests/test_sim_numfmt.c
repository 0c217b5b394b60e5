/* SPDX-License-Identifier: BSD-3-Clause */
/* Time-series number formatting: the same text as printf's %.6g, %.7g and
 * %.4f for every value, ties, exponent changes and special values included. */
#include "unity.h"
#include "run/numfmt.h"
#include "plant/rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

static int mismatches;

static void check_g(double x, int precision)
{
    char want[SIM_NUMFMT_MAX], got[SIM_NUMFMT_MAX];
    const int n_want = snprintf(want, sizeof want, "%.*g", precision, x);
    const int n_got = sim_fmt_g(got, x, precision);
    if (n_want != n_got || strcmp(want, got) != 0) {
        if (++mismatches <= 5) {
            char message[3 * SIM_NUMFMT_MAX];
            snprintf(message, sizeof message, "%%.%dg of %.17g: printf '%s', got '%s'", precision, x, want, got);
            TEST_MESSAGE(message);
        }
    }
}

static void check_f4(double x)
{
    char want[SIM_NUMFMT_MAX], got[SIM_NUMFMT_MAX];
    const int n_want = snprintf(want, sizeof want, "%.4f", x);
    const int n_got = sim_fmt_f4(got, x);
    if (n_want != n_got || strcmp(want, got) != 0) {
        if (++mismatches <= 5) {
            char message[3 * SIM_NUMFMT_MAX];
            snprintf(message, sizeof message, "%%.4f of %.17g: printf '%s', got '%s'", x, want, got);
            TEST_MESSAGE(message);
        }
    }
}

static void test_g_matches_printf_on_values_of_every_magnitude(void)
{
    sim_rng_t rng;
    sim_rng_seed(&rng, 6u);
    mismatches = 0;
    for (int i = 0; i < 200000; ++i) {
        /* mantissa in [1, 10), decimal exponent -40 .. 40, either sign */
        const double mant = 1.0 + 9.0 * sim_rng_uniform(&rng);
        const int exp10 = (int)(81.0 * sim_rng_uniform(&rng)) - 40;
        const double x = (sim_rng_uniform(&rng) < 0.5 ? -1.0 : 1.0) * mant * pow(10.0, exp10);
        check_g(x, 6);
        check_g(x, 7);
        check_g(x, 1 + i % 15);
    }
    TEST_ASSERT_EQUAL_INT(0, mismatches);
}

static void test_g_matches_printf_at_ties_and_exponent_changes(void)
{
    mismatches = 0;
    static const double edges[] = {0.5,          1.5,
                                   2.5,          0.125,
                                   0.0625,       1234565.0,
                                   123456.5,     1.234565,
                                   9999995.0,    999999.5,
                                   9.999995,     0.9999995,
                                   99999.95,     1e-4,
                                   9.9999995e-5, 1e-5,
                                   1e15,         1e16,
                                   1e21,         1e22,
                                   1e23,         1e-22,
                                   1e-23,        1e300,
                                   4.9e-324,     1.7976931348623157e308,
                                   100000.0,     1000000.0,
                                   10000000.0,   123456.0,
                                   0.1,          0.3,
                                   2.0 / 3.0};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; ++i) {
        for (int p = 1; p <= 15; ++p) {
            check_g(edges[i], p);
            check_g(-edges[i], p);
            check_g(nextafter(edges[i], 0.0), p);
            check_g(nextafter(edges[i], 1e308), p);
        }
    }
    /* every decimal half-way value of 6 digits around 1 and 1e5 */
    for (int k = 0; k < 20000; ++k) {
        check_g((100000.0 + k + 0.5) / 1e5, 6);
        check_g((100000.0 + k + 0.5), 6);
        check_g((100000.0 + k + 0.5) * 1e-9, 6);
    }
    TEST_ASSERT_EQUAL_INT(0, mismatches);
}

static void test_g_and_f4_pass_zeros_and_non_finite_values_like_printf(void)
{
    mismatches = 0;
    static const double special[] = {0.0, -0.0, INFINITY, -INFINITY, NAN, -NAN};
    for (size_t i = 0; i < sizeof special / sizeof special[0]; ++i) {
        check_g(special[i], 6);
        check_f4(special[i]);
    }
    TEST_ASSERT_EQUAL_INT(0, mismatches);
}

static void test_f4_matches_printf_on_tick_times_and_random_values(void)
{
    mismatches = 0;
    for (long k = 0; k <= 200000; ++k) {
        check_f4((double)k * 0.001); /* the runner's t = k dt */
        check_f4((double)k * 1e-4);
        check_f4((double)k * 0.00005); /* ties of the 4th decimal */
        check_f4(-(double)k * 0.00005);
    }
    sim_rng_t rng;
    sim_rng_seed(&rng, 7u);
    for (int i = 0; i < 100000; ++i) {
        const double x = (sim_rng_uniform(&rng) - 0.5) * pow(10.0, (int)(30.0 * sim_rng_uniform(&rng)) - 10);
        check_f4(x);
    }
    check_f4(1e11);
    check_f4(-1e300);
    TEST_ASSERT_EQUAL_INT(0, mismatches);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_g_matches_printf_on_values_of_every_magnitude);
    RUN_TEST(test_g_matches_printf_at_ties_and_exponent_changes);
    RUN_TEST(test_g_and_f4_pass_zeros_and_non_finite_values_like_printf);
    RUN_TEST(test_f4_matches_printf_on_tick_times_and_random_values);
    return UNITY_END();
}
