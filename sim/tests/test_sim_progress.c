/* SPDX-License-Identifier: BSD-3-Clause */
/* The progress line of ladrc_sil: the time left from the pace so far, its
 * wording, and no estimate before anything is done. */
#include "unity.h"
#include "run/progress.h"

#include <math.h>

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_time_left_is_the_pace_so_far_applied_to_the_rest(void)
{
    TEST_ASSERT_TRUE(sim_progress_eta_s(0.25, 10.0) == 30.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(0.5, 10.0) == 10.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(1.0, 10.0) == 0.0);
    /* not yet known */
    TEST_ASSERT_TRUE(sim_progress_eta_s(0.0, 10.0) == -1.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(-0.5, 10.0) == -1.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(1.5, 10.0) == -1.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(NAN, 10.0) == -1.0);
    TEST_ASSERT_TRUE(sim_progress_eta_s(0.5, -1.0) == -1.0);
}

static void test_durations_are_written_in_the_unit_that_fits(void)
{
    static const struct {
        double s;
        const char *text;
    } cases[] = {
        {.s = 0.0, .text = "0 s"},           {.s = 4.4, .text = "4 s"},           {.s = 59.4, .text = "59 s"},
        {.s = 59.6, .text = "1 min 00 s"},   {.s = 125.0, .text = "2 min 05 s"},  {.s = 3599.4, .text = "59 min 59 s"},
        {.s = 3599.6, .text = "1 h 00 min"}, {.s = 7620.0, .text = "2 h 07 min"}, {.s = 90000.0, .text = "25 h 00 min"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char buf[32];
        sim_progress_duration(buf, sizeof buf, cases[i].s);
        TEST_ASSERT_EQUAL_STRING(cases[i].text, buf);
    }
}

static void test_the_line_shows_the_estimate_once_there_is_one(void)
{
    char buf[128];
    sim_progress_text(buf, sizeof buf, 0.28, 4, 16, 2.04);
    TEST_ASSERT_EQUAL_STRING(" 28% (4 of 16 runs done, 2.0 s, about 5 s left)", buf);
    sim_progress_text(buf, sizeof buf, 0.01, 0, 4, 60.0);
    TEST_ASSERT_EQUAL_STRING("  1% (0 of 4 runs done, 60.0 s, about 1 h 39 min left)", buf);
    sim_progress_text(buf, sizeof buf, 0.0, 0, 4, 1.5);
    TEST_ASSERT_EQUAL_STRING("  0% (0 of 4 runs done, 1.5 s)", buf);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_time_left_is_the_pace_so_far_applied_to_the_rest);
    RUN_TEST(test_durations_are_written_in_the_unit_that_fits);
    RUN_TEST(test_the_line_shows_the_estimate_once_there_is_one);
    return UNITY_END();
}
