/* SPDX-License-Identifier: BSD-3-Clause */
/* The Betaflight form under every unit flag of blackbox_decode (log/log_units.h,
 * the preset of log/log_map.c): `time (us|ms|s)`, `gyroADC[i]` raw, `(deg/s)`
 * or `(rad/s)` all read as the same samples; a log decoded with --raw, a
 * column missing and a column in a unit the term cannot take are refused
 * with the column, the field and how a log gets it. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include "unity.h"
#include "log/log.h"
#include "log/log_units.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define PI 3.14159265358979323846
#define ROWS 6
#define DT_S 0.001
/* blackbox_decode prints the converted gyro with 2 decimals: the same
 * log in rad/s and in deg/s differ by the rounding of those, at most
 * half of 0.01 (rad/s) = 0.005 rad/s. */
#define RAD_S_PRINT_TOL 0.005
/* Values of order 1-1000 through one product with a unit factor: ulps. */
#define ROUND_TOL 1e-12

void setUp(void)
{
}
void tearDown(void)
{
}

static double gyro_deg_s(int row, int axis)
{
    return 10.0 * (axis + 1) * row - 25.0;
}

/* A blackbox_decode CSV: time and gyro in the units named, in the flag's form. */
static void write_log(char *buf, size_t len, const char *time_unit, const char *gyro_unit)
{
    const char *t_suffix = time_unit[0] != '\0' ? " (" : "";
    const char *t_close = time_unit[0] != '\0' ? ")" : "";
    const char *g_suffix = gyro_unit[0] != '\0' ? " (" : "";
    const char *g_close = gyro_unit[0] != '\0' ? ")" : "";
    size_t n = (size_t)snprintf(buf, len, "loopIteration, time%s%s%s, axisP[0], axisP[1], axisP[2]", t_suffix,
                                time_unit, t_close);
    for (int i = 0; i < 3; ++i) {
        n += (size_t)snprintf(buf + n, len - n, ", gyroADC[%d]%s%s%s", i, g_suffix, gyro_unit, g_close);
    }
    n += (size_t)snprintf(buf + n, len - n, ", vbatLatest (V)\n");
    for (int r = 0; r < ROWS; ++r) {
        const long long t_us = 1000000LL + 1000LL * r;
        if (strcmp(time_unit, "s") == 0) {
            n += (size_t)snprintf(buf + n, len - n, "%d, %.6f", r, t_us / 1e6);
        } else if (strcmp(time_unit, "ms") == 0) {
            n += (size_t)snprintf(buf + n, len - n, "%d, %.3f", r, t_us / 1e3);
        } else {
            n += (size_t)snprintf(buf + n, len - n, "%d, %lld", r, t_us);
        }
        n += (size_t)snprintf(buf + n, len - n, ", %d, %d, %d", r, 2 * r, -r);
        for (int i = 0; i < 3; ++i) {
            const double g = gyro_deg_s(r, i);
            if (strcmp(gyro_unit, "rad/s") == 0) {
                n += (size_t)snprintf(buf + n, len - n, ", %.2f", g * PI / 180.0);
            } else if (strcmp(gyro_unit, "deg/s") == 0) {
                n += (size_t)snprintf(buf + n, len - n, ", %.2f", g);
            } else {
                n += (size_t)snprintf(buf + n, len - n, ", %d", (int)g);
            }
        }
        n += (size_t)snprintf(buf + n, len - n, ", 16.4\n");
    }
}

/* Every tick of text: their count, or -1 with err. */
static int read_text(const char *text, const char *const *map, int n_map, sim_log_sample_t *s, sim_log_error_t *err)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_BETAFLIGHT;
    o.dt_s = DT_S;
    for (int i = 0; i < n_map; ++i) {
        o.map[i] = map[i];
    }
    o.n_map = n_map;
    FILE *f = fmemopen((void *)(uintptr_t)text, strlen(text), "r");
    TEST_ASSERT_NOT_NULL(f);
    sim_log_t *log = sim_log_open_stream(f, "bf.csv", &o, err);
    int n = 0, rc = log != NULL ? 1 : -1;
    while (rc == 1 && n < ROWS + 1) {
        rc = sim_log_next(log, &s[n], err);
        n += rc == 1;
    }
    sim_log_close(log);
    fclose(f);
    return rc < 0 ? -1 : n;
}

static void check_samples(const char *time_unit, const char *gyro_unit, double tol)
{
    char text[2048], what[64];
    sim_log_sample_t s[ROWS + 1];
    sim_log_error_t err;
    write_log(text, sizeof text, time_unit, gyro_unit);
    snprintf(what, sizeof what, "time (%s), gyro (%s)", time_unit, gyro_unit);
    TEST_ASSERT_EQUAL_INT_MESSAGE(ROWS, read_text(text, NULL, 0, s, &err), err.message);
    for (int r = 0; r < ROWS; ++r) {
        /* the tick on each row: the time in whole microseconds whatever its unit */
        TEST_ASSERT_TRUE_MESSAGE(fabs(s[r].t_s - r * DT_S) <= ROUND_TOL, what);
        for (int i = 0; i < 3; ++i) {
            const double want = gyro_deg_s(r, i) * PI / 180.0;
            TEST_ASSERT_TRUE_MESSAGE(fabs(s[r].gyro_rad_s[i] - want) <= tol, what);
        }
        TEST_ASSERT_TRUE_MESSAGE(fabs(s[r].command[1] - 2e-3 * r) <= ROUND_TOL, what);
    }
}

static void test_every_unit_flag_reads_the_same_samples(void)
{
    static const char *const TIMES[] = {"us", "ms", "s"};
    for (int t = 0; t < 3; ++t) {
        check_samples(TIMES[t], "", ROUND_TOL);      /* --unit-rotation raw (the default): deg/s */
        check_samples(TIMES[t], "deg/s", ROUND_TOL); /* whole deg/s printed exactly */
        check_samples(TIMES[t], "rad/s", RAD_S_PRINT_TOL);
    }
}

static void expect_refusal(const char *text, const char *const *map, int n_map, const char *needle, const char *also)
{
    sim_log_sample_t s[ROWS + 1];
    sim_log_error_t err;
    char shown[600];
    memset(&err, 0, sizeof err);
    TEST_ASSERT_EQUAL_INT(-1, read_text(text, map, n_map, s, &err));
    sim_log_error_format(&err, shown, sizeof shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(1, err.line, shown); /* the header's line */
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle), shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, also), shown);
}

static void test_raw_decoding_is_refused_naming_the_flag(void)
{
    static const char text[] = "loopIteration, time, axisP[0], axisP[1], axisP[2], gyroADC[0], gyroADC[1], gyroADC[2]\n"
                               "0, 1000, 1, 2, 3, 4, 5, 6\n1, X, 0, 0, 0, 1, 1, 1\n";
    expect_refusal(text, NULL, 0, "--raw", "'time (us)'");
}

static void test_a_missing_column_names_the_switch_that_logs_it(void)
{
    static const char no_gyro[] = "loopIteration, time (us), axisP[0], axisP[1], axisP[2]\n0, 1000, 1, 2, 3\n"
                                  "1, 2000, 1, 2, 3\n";
    expect_refusal(no_gyro, NULL, 0, "gyroADC[0] (deg/s)", "blackbox_disable_gyro");
    static const char no_pid[] = "loopIteration, time (us), gyroADC[0], gyroADC[1], gyroADC[2]\n0, 1000, 1, 2, 3\n"
                                 "1, 2000, 1, 2, 3\n";
    expect_refusal(no_pid, NULL, 0, "axisP[0]", "blackbox_disable_pids");
    /* a mapped gyroUnfilt, required: how Betaflight before 4.3 logs it */
    char text[2048];
    write_log(text, sizeof text, "us", "deg/s");
    static const char *const map[] = {"gyro_raw[0]=gyroUnfilt[0]*deg"};
    expect_refusal(text, map, 1, "gyroUnfilt[0]", "GYRO_SCALED");
}

static void test_a_unit_the_term_cannot_take_is_named(void)
{
    char text[2048];
    write_log(text, sizeof text, "us", "rad/s");
    /* a term without a unit takes only its own name: the log's column is quoted */
    static const char *const plain[] = {"gyro[1]=gyroADC[1]*deg"};
    expect_refusal(text, plain, 1, "'gyroADC[1] (rad/s)'", "gyro[1]");
    /* a voltage is no rate */
    static const char *const volts[] = {"gyro[1]=vbatLatest (deg/s)*deg"};
    expect_refusal(text, volts, 1, "'vbatLatest (V)'", "not convertible");
}

static void test_unit_split_and_factors(void)
{
    size_t base, unit_len;
    const char *unit;
    static const char name[] = "gyroADC[0] (rad/s)";
    sim_log_unit_split(name, strlen(name), &base, &unit, &unit_len);
    TEST_ASSERT_EQUAL_INT(10, (int)base);
    TEST_ASSERT_EQUAL_INT(5, (int)unit_len);
    TEST_ASSERT_EQUAL_INT(0, memcmp(unit, "rad/s", 5));
    sim_log_unit_split("motor[0]", 8, &base, &unit, &unit_len); /* no unit */
    TEST_ASSERT_EQUAL_INT(8, (int)base);
    TEST_ASSERT_EQUAL_INT(0, (int)unit_len);
    sim_log_unit_split("f(x)", 4, &base, &unit, &unit_len); /* no blank before '(': a name */
    TEST_ASSERT_EQUAL_INT(0, (int)unit_len);
    double f = 0.0;
    /* the time's factors are exact: whole microseconds stay whole */
    TEST_ASSERT_EQUAL_INT(0, sim_log_unit_factor("s", 1, "us", 2, &f));
    TEST_ASSERT_TRUE(f == 1e6);
    TEST_ASSERT_EQUAL_INT(0, sim_log_unit_factor("ms", 2, "us", 2, &f));
    TEST_ASSERT_TRUE(f == 1e3);
    TEST_ASSERT_EQUAL_INT(0, sim_log_unit_factor("rad/s", 5, "deg/s", 5, &f));
    TEST_ASSERT_TRUE(fabs(f - 180.0 / PI) <= ROUND_TOL);
    TEST_ASSERT_EQUAL_INT(-1, sim_log_unit_factor("V", 1, "deg/s", 5, &f));
    TEST_ASSERT_EQUAL_INT(-1, sim_log_unit_factor("furlong", 7, "m", 1, &f));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_unit_flag_reads_the_same_samples);
    RUN_TEST(test_raw_decoding_is_refused_naming_the_flag);
    RUN_TEST(test_a_missing_column_names_the_switch_that_logs_it);
    RUN_TEST(test_a_unit_the_term_cannot_take_is_named);
    RUN_TEST(test_unit_split_and_factors);
    return UNITY_END();
}
