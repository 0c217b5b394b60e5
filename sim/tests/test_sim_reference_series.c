/* SPDX-License-Identifier: BSD-3-Clause */
/* [reference] series: recorded angles added to the references. A step given
 * as a series flies bit for bit as the same step given as a signal; a file
 * whose columns are not angles, and series options without a file, are
 * refused at their place. */
#define _POSIX_C_SOURCE 200809L
#include "unity.h"
#include "run/runner.h"
#include "scenario/scenario.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char dir[64];

void setUp(void)
{
    snprintf(dir, sizeof dir, "refseries_XXXXXX"); /* in the build folder, as the other tests */
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
}

void tearDown(void)
{
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    TEST_ASSERT_EQUAL_INT(0, system(cmd));
}

static void write_text(const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    TEST_ASSERT_NOT_NULL(f);
    fputs(text, f);
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

/* The file's bytes (malloc'd, NUL-terminated). */
static char *read_text(const char *path)
{
    FILE *f = fopen(path, "rb");
    TEST_ASSERT_NOT_NULL(f);
    fseek(f, 0, SEEK_END);
    const long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    TEST_ASSERT_NOT_NULL(buf);
    TEST_ASSERT_EQUAL_INT((int)n, (int)fread(buf, 1, (size_t)n, f));
    buf[n] = '\0';
    fclose(f);
    return buf;
}

#define RUN_HEAD "[run]\nduration_s = 1.5\ncontrollers = LADRC CASCADED\n[sensors]\nrate_noise_std_deg_s = 0.2\n"

/* Flies `scenario` (written in dir as name) with controller c into csv; returns the time series. */
static char *fly(const char *name, const char *scenario, sim_controller_id_t c)
{
    write_text(name, scenario);
    char path[256], csv[256], err[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    snprintf(csv, sizeof csv, "%s/%s.csv", dir, name);
    static sim_scenario_t sc;
    sim_parse_error_t perr;
    if (sim_scenario_load(&sc, path, &perr) != 0) {
        printf("%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
    }
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_load(&sc, path, &perr));
    sim_metrics_t m;
    TEST_ASSERT_EQUAL_INT(0, sim_run_attitude(&sc, c, csv, NULL, &m, err, sizeof err));
    return read_text(csv);
}

static void test_a_step_as_a_series_flies_as_the_same_step_as_a_signal(void)
{
    /* held rows: 0 up to 0.4 s, then 8 deg roll, -5 deg pitch, 20 deg yaw (the signal
     * `0.4 .. : 8` starts after 0.4 s: the row between two ticks) */
    write_text("steps.csv", "# the steps\nt [s], roll [deg], pitch [deg], yaw [deg]\n0, 0, 0, 0\n0.4005, 8, -5, 20\n");
    const sim_controller_id_t ctrls[2] = {SIM_CTRL_LADRC, SIM_CTRL_CASCADED};
    for (int k = 0; k < 2; ++k) {
        char *as_signal =
            fly("signal.ini", RUN_HEAD "[reference]\nroll = 0.4 .. : 8\npitch = 0.4 .. : -5\nyaw = 0.4 .. : 20\n",
                ctrls[k]);
        char *as_series =
            fly("series.ini", RUN_HEAD "[reference]\nseries = steps.csv\nseries_interp = hold\nseries_end = hold\n",
                ctrls[k]);
        TEST_ASSERT_TRUE(strlen(as_signal) > 1000);
        TEST_ASSERT_TRUE_MESSAGE(strcmp(as_signal, as_series) == 0, "the same time series, bit for bit");
        free(as_signal);
        free(as_series);
    }
}

static void test_a_series_adds_to_the_signals(void)
{
    /* a 3 deg signal plus a 5 deg series flies as an 8 deg signal */
    write_text("five.csv", "t [s], roll [rad]\n0, 0\n0.4005, 0.0872664626\n");
    char *sum =
        fly("sum.ini",
            RUN_HEAD "[reference]\nroll = 0.4 .. : 3\nseries = five.csv\nseries_interp = hold\nseries_end = hold\n",
            SIM_CTRL_LADRC);
    char *eight = fly("eight.ini", RUN_HEAD "[reference]\nroll = 0.4 .. : 8\n", SIM_CTRL_LADRC);
    /* 3 deg plus 5 deg (in double) rounds to the float of 8 deg: the reference
     * column after the step agrees */
    const char *a = strstr(sum, "\n0.5"), *b = strstr(eight, "\n0.5");
    TEST_ASSERT_NOT_NULL(a);
    TEST_ASSERT_NOT_NULL(b);
    char ra[64], rb[64];
    sscanf(a + 1, "%*[^,],%63[^,]", ra);
    sscanf(b + 1, "%*[^,],%63[^,]", rb);
    TEST_ASSERT_TRUE_MESSAGE(strcmp(ra, rb) == 0, "the reference column agrees");
    free(sum);
    free(eight);
}

static void expect_refused(const char *scenario, int line, int column, const char *words)
{
    write_text("bad.ini", scenario);
    char path[256];
    snprintf(path, sizeof path, "%s/bad.ini", dir);
    static sim_scenario_t sc;
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_load(&sc, path, &perr));
    printf("%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
    TEST_ASSERT_EQUAL_INT(line, perr.line);
    TEST_ASSERT_EQUAL_INT(column, perr.column);
    TEST_ASSERT_NOT_NULL(strstr(perr.message, words));
}

static void test_a_series_of_rates_is_refused_at_its_unit(void)
{
    write_text("rates.csv", "t [s], roll [deg/s]\n0, 0\n2, 10\n");
    expect_refused(RUN_HEAD "[reference]\nseries = rates.csv\n", 1, 13, "angle");
}

static void test_series_options_need_a_file(void)
{
    expect_refused(RUN_HEAD "[reference]\nroll = 5\nseries_end = hold\n", 8, 1, "applies only with a series file");
}

static void test_a_series_shorter_than_the_run_is_refused_unless_asked(void)
{
    write_text("short.csv", "t [s], roll [deg]\n0, 0\n1, 10\n");
    expect_refused(RUN_HEAD "[reference]\nseries = short.csv\n", 7, 10, "series_end");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_step_as_a_series_flies_as_the_same_step_as_a_signal);
    RUN_TEST(test_a_series_adds_to_the_signals);
    RUN_TEST(test_a_series_of_rates_is_refused_at_its_unit);
    RUN_TEST(test_series_options_need_a_file);
    RUN_TEST(test_a_series_shorter_than_the_run_is_refused_unless_asked);
    return UNITY_END();
}
