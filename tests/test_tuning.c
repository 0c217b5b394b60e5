/* SPDX-License-Identifier: BSD-3-Clause */
/* Tuning helpers: the paper's rule, the exact settling rule, wo and b0. */
#include "unity.h"
#include "ladrc/tuning.h"

#include <math.h>

/* Results are one or two float operations from exact: 1e-6 relative. */
#define REL_TOL 1e-6f

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_paper_rule_gives_its_polynomial_over_the_settling_time(void)
{
    const float expected_numerators[] = {3.11f, 4.99f, 6.73f}; /* N = 1, 2, 3 */
    for (int order = 1; order <= 3; ++order) {
        ladrc_real_t wc = 0.0f;
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_tune_wc_from_settling(0.5f, order, &wc));
        const float expected = expected_numerators[order - 1] / 0.5f;
        TEST_ASSERT_FLOAT_WITHIN(REL_TOL * expected, expected, wc);
    }
}

static void test_exact_constant_is_the_two_percent_settling_of_a_double_pole(void)
{
    /* (1 + x) exp(-x) is the step error of (s + wc)^2 at x = wc t */
    const double x = LADRC_SETTLING_2PCT_WC;
    TEST_ASSERT_FLOAT_WITHIN(1e-7, 0.02, (1.0 + x) * exp(-x));
    ladrc_real_t wc = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_tune_wc_from_settling_exact(0.4f, &wc));
    TEST_ASSERT_FLOAT_WITHIN(REL_TOL * 14.58f, 5.8339217f / 0.4f, wc);
}

static void test_wo_and_b0_follow_their_definitions(void)
{
    ladrc_real_t wo = 0.0f;
    ladrc_real_t b0 = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_tune_wo_from_wc(15.0f, 5.0f, &wo));
    TEST_ASSERT_FLOAT_WITHIN(REL_TOL * 75.0f, 75.0f, wo);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_tune_b0_from_inertia(5.445e-3f, &b0));
    TEST_ASSERT_FLOAT_WITHIN(REL_TOL * 183.65f, 1.0f / 5.445e-3f, b0);
}

static void test_invalid_arguments_are_rejected_and_leave_the_output_alone(void)
{
    const float bad[] = {0.0f, -1.0f, NAN, INFINITY};
    ladrc_real_t out = 42.0f;
    for (unsigned i = 0; i < 4; ++i) {
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_SETTLING_TIME_S, ladrc_tune_wc_from_settling(bad[i], 2, &out));
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_SETTLING_TIME_S, ladrc_tune_wc_from_settling_exact(bad[i], &out));
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_WC_RAD_S, ladrc_tune_wo_from_wc(bad[i], 5.0f, &out));
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_WO_RATIO, ladrc_tune_wo_from_wc(15.0f, bad[i], &out));
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_INERTIA_KG_M2, ladrc_tune_b0_from_inertia(bad[i], &out));
    }
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_PLANT_ORDER, ladrc_tune_wc_from_settling(0.5f, 0, &out));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_PLANT_ORDER, ladrc_tune_wc_from_settling(0.5f, 4, &out));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 42.0f, out);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_tune_wc_from_settling(0.5f, 2, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_tune_wc_from_settling_exact(0.5f, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_tune_wo_from_wc(15.0f, 5.0f, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_tune_b0_from_inertia(1.0f, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_paper_rule_gives_its_polynomial_over_the_settling_time);
    RUN_TEST(test_exact_constant_is_the_two_percent_settling_of_a_double_pole);
    RUN_TEST(test_wo_and_b0_follow_their_definitions);
    RUN_TEST(test_invalid_arguments_are_rejected_and_leave_the_output_alone);
    return UNITY_END();
}
