/* SPDX-License-Identifier: BSD-3-Clause */
/* The tables and metrics.csv of a diverged run and of a run that never
 * settles: words where there is no result, never numbers. */
#include "unity.h"
#include "report/report.h"
#include "scenario/scenario.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static sim_scenario_t sc;
static sim_metrics_t m[2]; /* PID diverged, LADRC healthy but never settled on roll */

void setUp(void)
{
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        0, sim_scenario_parse(&sc, "[run]\nduration_s = 2\ncontrollers = PID LADRC\n", "report.ini", &perr),
        perr.message);
    memset(m, 0, sizeof m);
    for (int c = 0; c < 2; ++c) { /* numbers that must not show where the run diverged */
        m[c].finite = 1;
        m[c].has_estimate = c == 1;
        m[c].diverged_axis = -1;
        m[c].diverged_at_s = m[c].diverged_error_deg = NAN;
        for (int i = 0; i < 3; ++i) {
            m[c].error_deg[i].n = 10;
            m[c].error_deg[i].mean = 12.5;
            m[c].max_error_deg[i] = 12.5;
            m[c].band_deg[i] = 12.5;
            m[c].settle_s[i] = 0.25;
        }
        for (int r = 0; r < 4; ++r) {
            m[c].rotor_w2[r].n = 10;
            m[c].rotor_w2[r].mean = 125.0;
        }
    }
    m[0].diverged = 1;
    m[0].diverged_at_s = 1.25;
    m[0].diverged_axis = 1;
    m[0].diverged_error_deg = 91.5;
    m[1].settle_s[0] = SIM_NOT_SETTLED;
}
void tearDown(void)
{
}

/* The text a writer produces, through a temporary file (C99). */
static void capture(int csv, char *buf, size_t len)
{
    FILE *f = tmpfile();
    TEST_ASSERT_NOT_NULL(f);
    const sim_scenario_result_t res = {.sc = &sc, .attitude = m, .diff = NULL};
    if (csv) {
        TEST_ASSERT_EQUAL_INT(0, sim_report_metrics_csv(f, &res, 1));
    } else {
        sim_report_tables(f, &res);
    }
    rewind(f);
    const size_t n = fread(buf, 1, len - 1, f);
    buf[n] = '\0';
    fclose(f);
}

static void test_metrics_csv_says_diverged_for_every_statistic_of_a_diverged_run(void)
{
    static char text[16384];
    capture(1, text, sizeof text);
    int stats = 0;
    for (char *line = strtok(text, "\n"); line != NULL; line = strtok(NULL, "\n")) {
        if (strncmp(line, "report,PID,", 11) != 0) {
            continue;
        }
        const char *table = line + 11;
        const char *value = strrchr(line, ',') + 1;
        if (*table != '-') { /* tables 4, 5 and 7 (PID has no 6) */
            TEST_ASSERT_EQUAL_STRING_MESSAGE("diverged", value, line);
            stats++;
        }
    }
    TEST_ASSERT_EQUAL_INT(3 * 7 + 4 * 3, stats);
    capture(1, text, sizeof text);
    TEST_ASSERT_NOT_NULL(strstr(text, "report,PID,-,diverged,-,1\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,PID,-,diverged_at_s,pitch,1.25\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,PID,-,diverged_error_deg,pitch,91.5\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,LADRC,-,diverged,-,0\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,LADRC,-,diverged_at_s,-,-\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,LADRC,5,settling_s,roll,not_settled\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,LADRC,5,settling_s,pitch,0.25\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,LADRC,4,error_mean_deg,roll,12.5\n"));
}

static void test_a_non_finite_divergence_has_a_nan_error(void)
{
    m[0].finite = 0;
    m[0].diverged_error_deg = NAN;
    static char text[16384];
    capture(1, text, sizeof text);
    TEST_ASSERT_NOT_NULL(strstr(text, "report,PID,-,finite,-,0\n"));
    TEST_ASSERT_NOT_NULL(strstr(text, "report,PID,-,diverged_error_deg,pitch,nan\n"));
    char why[160];
    sim_report_divergence_text(why, sizeof why, &sc, &m[0]);
    TEST_ASSERT_EQUAL_STRING("diverged at t = 1.2500 s: the state turned non-finite (pitch angle or rate)", why);
}

static void test_tables_print_words_not_numbers(void)
{
    static char text[16384];
    capture(0, text, sizeof text);
    TEST_ASSERT_NOT_NULL(strstr(text, "PID: DIVERGED: diverged at t = 1.2500 s on pitch: |tracking error| 91.5 deg "
                                      "exceeds diverge_limit_deg = 90"));
    /* every row of tables 4, 5, 7: PID's cell is the word; 6: PID has no estimate */
    int rows = 0;
    for (char *line = strtok(text, "\n"); line != NULL; line = strtok(NULL, "\n")) {
        if (strncmp(line, "roll ", 5) == 0 || strncmp(line, "pitch ", 6) == 0 || strncmp(line, "yaw ", 4) == 0 ||
            (line[0] >= '1' && line[0] <= '4' && line[1] == ' ')) {
            const int roll = strncmp(line, "roll ", 5) == 0;
            char *cell = strstr(line, " | ") + 3;
            char *ladrc = strstr(cell, " | ");
            TEST_ASSERT_NOT_NULL_MESSAGE(ladrc, line);
            *ladrc = '\0'; /* PID's cell alone */
            TEST_ASSERT_TRUE_MESSAGE(strncmp(cell, "diverged ", 9) == 0 || strncmp(cell, "(no estimate)", 13) == 0,
                                     cell);
            TEST_ASSERT_NULL_MESSAGE(strpbrk(cell, "0123456789"), cell); /* no number of PID's ... */
            if (roll && strstr(ladrc + 3, "not settled") != NULL) {
                rows += 100; /* ... and LADRC's roll settling time is a word */
            }
            rows++;
        }
    }
    TEST_ASSERT_EQUAL_INT(3 * 3 + 4 + 100, rows);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_metrics_csv_says_diverged_for_every_statistic_of_a_diverged_run);
    RUN_TEST(test_a_non_finite_divergence_has_a_nan_error);
    RUN_TEST(test_tables_print_words_not_numbers);
    return UNITY_END();
}
