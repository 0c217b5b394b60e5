/* SPDX-License-Identifier: BSD-3-Clause */
/* The estimators' columns of the time series (docs/csv-format.md): a short
 * run of each controller driven through the runner's parts, every row's
 * hp_* and lp_* cells against what the library's getters report at that
 * tick, and nan where the axis has no such estimator. */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include "unity.h"
#include "run/runner_parts.h"
#include "scenario/scenario.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define TICKS 4000 /* 4 s at 1 ms */
#define VALUES (3 * (4 + 4 * LADRC_HP_MAX_TONES))
#define ROW_MAX (RUNNER_CSV_FIELDS_MAX * SIM_NUMFMT_MAX)

/* A tone from 1 s on, HP's gate has something to engage on; a motor lag
 * (modelled), so that HP's estimate and its command differ. */
static const char SCENARIO[] = "[run]\nduration_s = 4\ncontrol_dt_s = 0.001\n"
                               "controllers = HP-MLADRC LP-MLADRC LADRC\n"
                               "[reference]\nroll = 5\npitch = 3*sin(t)\n"
                               "[disturbance]\nroll = 1 .. : 10 - 60*sin(3*t)\npitch = 0.5 .. : 5\n"
                               "[rotors]\nmotor_tau_s = 0.015\n";

static sim_scenario_t sc;
static attitude_run_t run; /* large: its line buffer */
static double expected[TICKS][VALUES];
static char row[ROW_MAX];

static char path[64]; /* the test's time series, removed after it */

void setUp(void)
{
    path[0] = '\0';
}
void tearDown(void)
{
    if (path[0] != '\0')
        remove(path);
}

/* The tick's estimator values as the getters give them, in the columns' order. */
static void read_getters(const ladrc_attitude_t *att, double *v)
{
    int n = 0;
    const ladrc_hp_estimator_t *hp[3];
    for (int i = 0; i < 3; ++i)
        hp[i] = ladrc_axis_get_hp(&att->axis[i]);
    for (int i = 0; i < 3; ++i)
        v[n++] = hp[i] ? (double)ladrc_hp_get_weight(hp[i]) : NAN;
    for (int i = 0; i < 3; ++i)
        v[n++] = hp[i] ? (double)ladrc_hp_get_active_tones(hp[i]) : NAN;
    /* per tone: frequency, amplitude, gate evidence and coherence (docs/csv-format.md) */
    for (unsigned k = 0; k < LADRC_HP_MAX_TONES; ++k) {
        ladrc_real_t (*const getters[])(const ladrc_hp_estimator_t *, unsigned) = {
            ladrc_hp_get_freq, ladrc_hp_get_amplitude, ladrc_hp_get_evidence, ladrc_hp_get_coherence};
        for (size_t g = 0; g < sizeof getters / sizeof getters[0]; ++g) {
            for (int i = 0; i < 3; ++i)
                v[n++] = hp[i] && k < ladrc_hp_get_active_tones(hp[i]) ? (double)getters[g](hp[i], k) : NAN;
        }
    }
    for (int i = 0; i < 3; ++i)
        v[n++] = hp[i] ? (double)ladrc_hp_get_estimate(hp[i]) : NAN;
    for (int i = 0; i < 3; ++i) {
        const ladrc_lp_estimator_t *lp = ladrc_axis_get_lp(&att->axis[i]);
        v[n++] = lp ? (double)ladrc_lp_get_estimate(lp) : NAN;
    }
    TEST_ASSERT_EQUAL_INT(VALUES, n);
}

/* Flies ctrl for TICKS ticks as the runner does, writing csv_path and
 * keeping each tick's getter values. */
static void fly(sim_controller_id_t ctrl, const char *csv_path)
{
    static sim_metrics_t m;
    char err[256] = "";
    sim_run_spec_t spec = {.ctrl = ctrl, .csv_path = csv_path, .metrics = &m, .err = err, .err_len = sizeof err};
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, runner_run_open(&sc, &run, &spec), err);
    static instants_t at;
    static disturbance_batch_t batch;
    runner_disturbance_batch_init(&batch, &sc);
    at.first = at.n = 0;
    for (long k = 0; k < TICKS; ++k) {
        if (k - at.first >= at.n)
            runner_instants_fill(&at, &sc, k, TICKS);
        const int j = (int)(k - at.first);
        ladrc_real_t ref[3];
        double ref_rad[3], dist[3], w2[4];
        for (int i = 0; i < 3; ++i) {
            ref[i] = at.ref[i][j];
            ref_rad[i] = (double)ref[i];
            dist[i] = at.dist[i][j];
        }
        TEST_ASSERT_EQUAL_INT_MESSAGE(1, runner_run_tick(&sc, &run, at.t_s[j], ref, ref_rad, dist, w2),
                                      sim_controller_name(ctrl));
        read_getters(&run.att, expected[k]);
        runner_disturbance_batch_fill(&batch, &run.plant, sc.control_dt_s, sc.plant_substeps);
        batch_reader_t reader = {.b = &batch, .next = 0};
        sim_plant_step(&run.plant, w2, sc.control_dt_s, sc.plant_substeps, runner_read_batch, &reader);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, runner_run_close(&sc, &run), err);
}

/* Index of name among the header's columns; fails when it is absent. */
static int column(const char *header, const char *name)
{
    int index = 0;
    const size_t n = strlen(name);
    for (const char *p = header; *p != '\0' && *p != '\n'; ++index) {
        const size_t len = strcspn(p, ",\n");
        if (len == n && strncmp(p, name, n) == 0)
            return index;
        p += len + (p[len] == ',');
    }
    TEST_FAIL_MESSAGE(name);
    return -1;
}

/* The columns {prefix}{axis}{unit} of roll, pitch and yaw into col[*n..]. */
static void axis_columns(const char *header, const char *prefix, const char *unit, int *col, int *n)
{
    static const char *const AXES[3] = {"roll", "pitch", "yaw"};
    for (int i = 0; i < 3; ++i) {
        char name[64];
        snprintf(name, sizeof name, "%s%s%s", prefix, AXES[i], unit);
        col[(*n)++] = column(header, name);
    }
}

/* The columns of the values, in read_getters' order (docs/csv-format.md). */
static void value_columns(const char *header, int *col)
{
    int n = 0;
    axis_columns(header, "hp_weight_", "_frac", col, &n);
    axis_columns(header, "hp_tones_", "_count", col, &n);
    static const char *const families[][2] = {
        {"hp_freq", "_rad_s"}, {"hp_amp", "_rad_s2"}, {"hp_evidence", "_ratio"}, {"hp_coherence", "_frac"}};
    for (int k = 1; k <= LADRC_HP_MAX_TONES; ++k) {
        for (size_t f = 0; f < sizeof families / sizeof families[0]; ++f) {
            char prefix[32];
            snprintf(prefix, sizeof prefix, "%s%d_", families[f][0], k);
            axis_columns(header, prefix, families[f][1], col, &n);
        }
    }
    axis_columns(header, "hp_est_", "_rad_s2", col, &n);
    axis_columns(header, "lp_est_", "_rad_s2", col, &n);
    TEST_ASSERT_EQUAL_INT(VALUES, n);
}

/* Field index of a line (no newline). */
static const char *field(const char *line, int index, size_t *len)
{
    for (int i = 0; i < index; ++i) {
        line = strchr(line, ',');
        TEST_ASSERT_NOT_NULL(line);
        ++line;
    }
    *len = strcspn(line, ",\n");
    return line;
}

/* Every row of csv_path holds the getters' values as %.6g text, the text
 * the runner writes (numfmt.h); returns the rows. */
static int check_rows(const char *csv_path)
{
    FILE *f = fopen(csv_path, "r");
    TEST_ASSERT_NOT_NULL(f);
    static char header[RUNNER_CSV_HEADER_MAX];
    TEST_ASSERT_NOT_NULL(fgets(header, sizeof header, f));
    int col[VALUES];
    value_columns(header, col);
    int rows = 0;
    while (fgets(row, sizeof row, f) != NULL) {
        TEST_ASSERT_TRUE(rows < TICKS);
        for (int v = 0; v < VALUES; ++v) {
            char want[32], msg[64 + 2 * SIM_NUMFMT_MAX]; /* %.6g: at most 13 characters */
            snprintf(want, sizeof want, "%.6g", expected[rows][v]);
            size_t len;
            const char *cell = field(row, col[v], &len);
            if (len != strlen(want) || strncmp(cell, want, len) != 0) {
                snprintf(msg, sizeof msg, "row %d, column %d: '%.*s', the library's %s", rows + 2, col[v] + 1,
                         (int)(len < SIM_NUMFMT_MAX ? len : SIM_NUMFMT_MAX), cell, want);
                TEST_FAIL_MESSAGE(msg);
            }
        }
        ++rows;
    }
    fclose(f);
    return rows;
}

/* A new file name of our own in the test's folder into path (runner_open_csv
 * replaces the file). */
static void temp_path(const char *name)
{
    snprintf(path, sizeof path, "estimators_%s_XXXXXX", name);
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    close(fd);
}

static void load(void)
{
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_parse(&sc, SCENARIO, "estimators.ini", &perr), perr.message);
}

static void test_hp_columns_hold_the_library_values_and_the_gate_engages(void)
{
    load();
    temp_path("hp");
    fly(SIM_CTRL_HP_MLADRC, path);
    TEST_ASSERT_EQUAL_INT(TICKS, check_rows(path));
    /* not a vacuous comparison: the gate engaged on roll, a tone was fitted,
     * and LP's cells are nan on HP's axes */
    double max_weight = 0.0, max_amp = 0.0;
    for (int k = 0; k < TICKS; ++k) {
        max_weight = fmax(max_weight, expected[k][0]);
        if (expected[k][3] >= 1.0)
            max_amp = fmax(max_amp, expected[k][9]);
        TEST_ASSERT_TRUE(isnan(expected[k][VALUES - 3]));
    }
    TEST_ASSERT_TRUE(max_weight > 0.5);
    TEST_ASSERT_TRUE(max_amp > 10.0);
}

static void test_lp_columns_hold_the_library_values_and_hp_cells_are_nan(void)
{
    load();
    temp_path("lp");
    fly(SIM_CTRL_LP_MLADRC, path);
    TEST_ASSERT_EQUAL_INT(TICKS, check_rows(path));
    double max_est = 0.0;
    for (int k = 0; k < TICKS; ++k) {
        for (int v = 0; v < VALUES - 3; ++v)
            TEST_ASSERT_TRUE(isnan(expected[k][v]));
        max_est = fmax(max_est, fabs(expected[k][VALUES - 3]));
    }
    TEST_ASSERT_TRUE(max_est > 10.0); /* roll's tone, seen */
}

static void test_plain_ladrc_writes_nan_in_every_estimator_cell(void)
{
    load();
    temp_path("ladrc");
    fly(SIM_CTRL_LADRC, path);
    TEST_ASSERT_EQUAL_INT(TICKS, check_rows(path));
    for (int v = 0; v < VALUES; ++v)
        TEST_ASSERT_TRUE(isnan(expected[TICKS - 1][v]));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hp_columns_hold_the_library_values_and_the_gate_engages);
    RUN_TEST(test_lp_columns_hold_the_library_values_and_hp_cells_are_nan);
    RUN_TEST(test_plain_ladrc_writes_nan_in_every_estimator_cell);
    return UNITY_END();
}
