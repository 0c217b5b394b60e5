/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Self-test of the Unity-compatible runner: a failing assertion must end
 * its test at once and be counted; ignores and passes must be counted too.
 * The inner tests below fail on purpose; this program checks the counters
 * and exits 0 only if they are exactly as Unity would report them.
 */
#include "unity.h"

#include <stdio.h>

static int reached_after_abort;
static int teardown_runs;

void setUp(void)
{
}
void tearDown(void)
{
    teardown_runs++;
}

static void fails_int(void)
{
    TEST_ASSERT_EQUAL_INT(1, 2);
    reached_after_abort = 1;
}

static void fails_float_precision(void)
{
    TEST_ASSERT_EQUAL_FLOAT(1.0f, 1.001f); /* outside 1e-5 relative */
    reached_after_abort = 1;
}

static void fails_nan_threshold(void)
{
    TEST_ASSERT_LESS_THAN_FLOAT(1.0f, (float)NAN); /* NaN is never less */
    reached_after_abort = 1;
}

static void is_ignored(void)
{
    TEST_IGNORE_MESSAGE("ignored on purpose");
    reached_after_abort = 1;
}

static void passes(void)
{
    const int ints[3] = {1, 2, 3};
    const float floats[2] = {1.0f, -2.5f};
    TEST_ASSERT_EQUAL_FLOAT(1.0f, 1.000001f);
    TEST_ASSERT_FLOAT_WITHIN(0.1f, 1.0f, 1.05f);
    TEST_ASSERT_LESS_THAN_FLOAT(1.0f, 0.5f); /* actual < threshold */
    TEST_ASSERT_GREATER_THAN(3, 4);          /* actual > threshold */
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(1.0f, 1.0f);
    TEST_ASSERT_FLOAT_IS_NOT_DETERMINATE((float)INFINITY);
    TEST_ASSERT_EQUAL_INT_ARRAY(ints, ints, 3);
    TEST_ASSERT_EQUAL_FLOAT_ARRAY(floats, floats, 2);
    TEST_ASSERT_EQUAL_STRING("abc", "abc");
    TEST_ASSERT_EQUAL_HEX8(0x1ff, 0xff); /* compared as 8 bits */
    TEST_PASS();
    reached_after_abort = 1;
}

int main(void)
{
    int failures;
    int ok;

    UNITY_BEGIN();
    RUN_TEST(fails_int);
    RUN_TEST(fails_float_precision);
    RUN_TEST(fails_nan_threshold);
    RUN_TEST(is_ignored);
    RUN_TEST(passes);
    failures = UNITY_END();

    ok = failures == 3 && Unity.NumberOfTests == 5u && Unity.TestIgnores == 1u && teardown_runs == 5 &&
         !reached_after_abort;
    printf("unity_compat selftest: %s (the FAIL lines above are expected)\n", ok ? "OK" : "BROKEN");
    return ok ? 0 : 1;
}
