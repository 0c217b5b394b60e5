/* SPDX-License-Identifier: BSD-3-Clause */
/* A bad value in one column of a summed field (log/log.h's `A+B+C` map
 * items, the Betaflight preset's axisP+axisI+axisD+axisF command): the
 * reader's error is at the cell that holds it, its line and column, and
 * names that column, whichever term of the sum it is, in the generic and
 * the Betaflight forms, for a value beyond range, a non-finite one and text. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include "unity.h"
#include "log/log.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

/* The byte column (1-based) of the n-th cell (0-based) of the given line of text. */
static int cell_column(const char *text, int line, int n)
{
    const char *p = text;
    for (int l = 1; l < line; ++l) {
        p = strchr(p, '\n') + 1;
    }
    const char *start = p;
    for (int k = 0; k < n; ++k) {
        p = strchr(p, ',') + 1;
        while (*p == ' ') {
            ++p; /* blackbox_decode writes a space after each comma */
        }
    }
    return (int)(p - start) + 1;
}

/* text read in format with the map items given: refused at line, at the
 * n-th cell of that line, with a message holding every needle. */
static void expect_at(const char *text, sim_log_format_t format, const char *const *map, int n_map, int line, int cell,
                      const char *needle1, const char *needle2)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = format;
    o.dt_s = 0.001;
    for (int i = 0; i < n_map; ++i) {
        o.map[i] = map[i];
    }
    o.n_map = n_map;
    FILE *f = fmemopen((void *)(uintptr_t)text, strlen(text), "r");
    TEST_ASSERT_NOT_NULL(f);
    sim_log_error_t err;
    memset(&err, 0, sizeof err);
    sim_log_t *log = sim_log_open_stream(f, "sum.csv", &o, &err);
    int rc = log == NULL ? -1 : 1;
    sim_log_sample_t s;
    while (rc == 1) {
        rc = sim_log_next(log, &s, &err);
    }
    sim_log_close(log);
    fclose(f);
    char shown[512];
    sim_log_error_format(&err, shown, sizeof shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(-1, rc, text);
    TEST_ASSERT_EQUAL_INT_MESSAGE(line, err.line, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(cell_column(text, line, cell), err.column, shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle1), shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle2), shown);
}

/* command[0] the sum of columns a, b and c (cells 2, 3, 4), the bad value
 * in row 3 of the column at `cell`. */
static void expect_generic(const char *bad, int cell, const char *column, const char *needle)
{
    static const char *const map[] = {"command[0]=a+b+c"};
    char text[256];
    const char *row3[3] = {"0.3", "0.3", "0.3"};
    row3[cell - 2] = bad;
    snprintf(text, sizeof text, "time,gyro[0],a,b,c\n0,1,0.1,0.1,0.1\n0.001,1,0.2,0.2,0.2\n0.002,1,%s,%s,%s\n", row3[0],
             row3[1], row3[2]);
    expect_at(text, SIM_LOG_GENERIC, map, 1, 4, cell, column, needle);
}

static void test_generic_sum_beyond_range_told_at_its_column(void)
{
    expect_generic("1e300", 4, "'c'", "beyond the reader's range");
    expect_generic("-2e15", 3, "'b'", "beyond the reader's range");
    expect_generic("1e300", 2, "'a'", "beyond the reader's range");
}

static void test_generic_sum_not_a_number_told_at_its_column(void)
{
    expect_generic("inf", 4, "'c'", "not a finite number");
    expect_generic("x", 3, "'b'", "not a finite number");
    expect_generic("", 4, "'c'", "empty cell");
}

static void test_generic_summed_time_beyond_range_told_at_its_column(void)
{
    static const char *const map[] = {"time=t_s+t_offset_s"};
    static const char text[] = "t_s,t_offset_s,gyro[0]\n0,0,1\n0.001,0,1\n0.002,1e300,1\n";
    expect_at(text, SIM_LOG_GENERIC, map, 1, 4, 1, "'t_offset_s'", "beyond the reader's range");
}

/* A blackbox_decode CSV whose row 3 holds `bad` in the cell of `column`
 * (one of axisP/I/D[0], which the preset sums into command[0]). */
static void expect_betaflight(const char *column, const char *bad, const char *needle)
{
    static const char header[] = "loopIteration, time (us), axisP[0], axisP[1], axisP[2], axisI[0], axisI[1], "
                                 "axisI[2], axisD[0], axisD[1], gyroADC[0], gyroADC[1], gyroADC[2]";
    static const char *const cells[] = {"axisP[0]", "axisI[0]", "axisD[0]"};
    static const int cell_of[] = {2, 5, 8};
    int which = -1;
    for (int k = 0; k < 3; ++k) {
        which = strcmp(column, cells[k]) == 0 ? k : which;
    }
    TEST_ASSERT_TRUE(which >= 0);
    const char *v[3] = {"10", "20", "30"};
    v[which] = bad;
    char text[1024];
    snprintf(text, sizeof text,
             "%s\n0, 0, 1, 2, 3, 4, 5, 6, 7, 8, 1, 2, 3\n1, 1000, 1, 2, 3, 4, 5, 6, 7, 8, 1, 2, 3\n"
             "2, 2000, %s, 2, 3, %s, 5, 6, %s, 8, 1, 2, 3\n",
             header, v[0], v[1], v[2]);
    char quoted[32];
    snprintf(quoted, sizeof quoted, "'%s'", column);
    expect_at(text, SIM_LOG_BETAFLIGHT, NULL, 0, 4, cell_of[which], quoted, needle);
}

static void test_betaflight_pid_sum_told_at_its_column(void)
{
    expect_betaflight("axisD[0]", "1e300", "beyond the reader's range");
    expect_betaflight("axisI[0]", "-1e300", "beyond the reader's range");
    expect_betaflight("axisP[0]", "1e300", "beyond the reader's range");
    expect_betaflight("axisD[0]", "nan", "not a finite number");
    expect_betaflight("axisI[0]", "12a", "not a finite number");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_generic_sum_beyond_range_told_at_its_column);
    RUN_TEST(test_generic_sum_not_a_number_told_at_its_column);
    RUN_TEST(test_generic_summed_time_beyond_range_told_at_its_column);
    RUN_TEST(test_betaflight_pid_sum_told_at_its_column);
    return UNITY_END();
}
