/* SPDX-License-Identifier: BSD-3-Clause */
/* [run] log (sim/run/runner_log.c, docs/csv-format.md): a short run of INDI
 * writing the three forms, flown through the runner's parts so that what
 * the controller was given each tick is read back from it (INDI's
 * estimate is the last angle and rate it got; without an actuator model its
 * acting torque is the applied one). The headers exactly, one row per tick,
 * the generic form's inputs and command equal to the controller's, the
 * Betaflight form's integers, the PX4 topics against the generic form;
 * nothing after a divergence; a log that cannot be written named. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "unity.h"
#include "run/runner.h"
#include "run/runner_parts.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define TICKS 1500 /* 1.5 s at 1 ms */
#define FIELDS_MAX 40
#define LINE_MAX_BYTES 4096

/* Noise and a low-pass on the gyro (the controller's rate is not the raw
 * one), rotor limits, a reference that moves, a chirp on yaw. */
static const char SCENARIO[] = "[run]\nduration_s = 1.5\ncontrollers = INDI\nlog = betaflight, px4, generic\n"
                               "[rotors]\nideal = no\nw2_max_rad2_s2 = 2e5\n"
                               "[sensors]\nangle_noise_std_deg = 0.05\nrate_noise_std_deg_s = 2\n"
                               "[filter]\nlpf_order = 2\nlpf_hz = 80\n"
                               "[reference]\nroll = 0.2 .. : 10\npitch = 5*sin(3*t)\n"
                               "[excitation]\naxis = yaw\namplitude = 0.1\nstart_s = 0.3\nduration_s = 1\n";

static const char *const PX4_TOPICS[8] = {
    "vehicle_angular_velocity", "sensor_combined",         "vehicle_attitude", "vehicle_attitude_setpoint",
    "vehicle_rates_setpoint",   "vehicle_torque_setpoint", "actuator_motors",  "esc_status"};

/* The headers, as blackbox_decode and ulog2csv write them (docs/csv-format.md). */
static const char BETAFLIGHT_HEADER[] =
    "loopIteration, time (us), axisP[0], axisP[1], axisP[2], axisI[0], axisI[1], axisI[2], axisD[0], axisD[1], "
    "axisF[0], axisF[1], axisF[2], rcCommand[0], rcCommand[1], rcCommand[2], rcCommand[3], setpoint[0], "
    "setpoint[1], setpoint[2], setpoint[3], gyroADC[0], gyroADC[1], gyroADC[2], gyroUnfilt[0], gyroUnfilt[1], "
    "gyroUnfilt[2], motor[0], motor[1], motor[2], motor[3], eRPM[0], eRPM[1], eRPM[2], eRPM[3]\n";
static const char GENERIC_HEADER[] =
    "time,gyro[0],gyro[1],gyro[2],gyro_raw[0],gyro_raw[1],gyro_raw[2],angle[0],angle[1],angle[2],"
    "quat[0],quat[1],quat[2],quat[3],ref_angle[0],ref_angle[1],ref_angle[2],ref_rate[0],ref_rate[1],ref_rate[2],"
    "command[0],command[1],command[2],throttle\n";
static const char *const PX4_HEADERS[8] = {
    "timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n",
    "timestamp,gyro_rad[0],gyro_rad[1],gyro_rad[2],accelerometer_m_s2[0],accelerometer_m_s2[1],"
    "accelerometer_m_s2[2]\n",
    "timestamp,q[0],q[1],q[2],q[3]\n",
    "timestamp,q_d[0],q_d[1],q_d[2],q_d[3],thrust_body[0],thrust_body[1],thrust_body[2]\n",
    "timestamp,roll,pitch,yaw,thrust_body[0],thrust_body[1],thrust_body[2]\n",
    "timestamp,xyz[0],xyz[1],xyz[2]\n",
    "timestamp,control[0],control[1],control[2],control[3]\n",
    "timestamp,esc[0].esc_rpm,esc[1].esc_rpm,esc[2].esc_rpm,esc[3].esc_rpm\n"};

/* What the controller was given and applied each tick. */
typedef struct {
    double t_s;
    ladrc_real_t rate[3], angle[3], ref[3], applied_Nm[3];
} given_t;

static sim_scenario_t sc;
static attitude_run_t run; /* large: its line buffers */
static given_t given[TICKS];
static char dir[64];
static int flown;

void setUp(void)
{
}
void tearDown(void)
{
}

static void file_path(char *out, size_t len, const char *suffix)
{
    snprintf(out, len, "%s/INDI%s", dir, suffix);
}

/* Flies the scenario once as the runner does, keeping what INDI got. */
static void fly(void)
{
    if (flown)
        return;
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_parse(&sc, SCENARIO, "runner_log.ini", &perr), perr.message);
    snprintf(dir, sizeof dir, "runner_log_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    static char csv_path[128];
    file_path(csv_path, sizeof csv_path, ".csv");
    static sim_metrics_t m;
    char err[256] = "";
    sim_run_spec_t spec = {
        .ctrl = SIM_CTRL_INDI, .csv_path = csv_path, .metrics = &m, .err = err, .err_len = sizeof err};
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
        TEST_ASSERT_EQUAL_INT(1, runner_run_tick(&sc, &run, at.t_s[j], ref, ref_rad, dist, w2));
        given[k].t_s = at.t_s[j];
        for (int i = 0; i < 3; ++i) {
            ladrc_real_t disturbance; /* every pointer given, or nothing is written */
            ladrc_axis_get_estimate(&run.att.axis[i], &given[k].angle[i], &given[k].rate[i], &disturbance);
            given[k].applied_Nm[i] = ladrc_axis_get_acting_Nm(&run.att.axis[i]);
            given[k].ref[i] = ref[i];
        }
        runner_disturbance_batch_fill(&batch, &run.plant, sc.control_dt_s, sc.plant_substeps);
        batch_reader_t reader = {.b = &batch, .next = 0};
        sim_plant_step(&run.plant, w2, sc.control_dt_s, sc.plant_substeps, runner_read_batch, &reader);
    }
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, runner_run_close(&sc, &run), err);
    flown = 1;
}

/* The lines of a file: its header into header, the rows into rows (each
 * LINE_MAX_BYTES, allocated); returns the number of rows. */
static int read_rows(const char *path, char *header, char (**rows)[LINE_MAX_BYTES])
{
    FILE *f = fopen(path, "r");
    TEST_ASSERT_NOT_NULL_MESSAGE(f, path);
    TEST_ASSERT_NOT_NULL(fgets(header, LINE_MAX_BYTES, f));
    *rows = malloc((size_t)(TICKS + 2) * LINE_MAX_BYTES);
    TEST_ASSERT_NOT_NULL(*rows);
    int n = 0;
    while (n < TICKS + 2 && fgets((*rows)[n], LINE_MAX_BYTES, f) != NULL)
        ++n;
    fclose(f);
    return n;
}

/* The fields of line separated by sep (", " or ","), cut in place; the
 * count. Fails when a separator is not exactly sep. */
static int split(char *line, const char *sep, char *field[FIELDS_MAX])
{
    int n = 0;
    line[strcspn(line, "\n")] = '\0';
    for (char *p = line;;) {
        TEST_ASSERT_TRUE(n < FIELDS_MAX);
        field[n++] = p;
        char *comma = strchr(p, ',');
        if (comma == NULL)
            return n;
        TEST_ASSERT_EQUAL_INT(0, strncmp(comma, sep, strlen(sep)));
        *comma = '\0';
        p = comma + strlen(sep);
        TEST_ASSERT_TRUE(*p != ' ');
    }
}

/* A cell that must be a whole number (an optional '-' and digits). */
static long long integer(const char *cell)
{
    const char *p = cell + (cell[0] == '-');
    TEST_ASSERT_TRUE_MESSAGE(*p != '\0' && strspn(p, "0123456789") == strlen(p), cell);
    return strtoll(cell, NULL, 10);
}

static void test_every_form_has_its_header_and_one_row_per_tick(void)
{
    fly();
    char path[256], header[LINE_MAX_BYTES];
    char(*rows)[LINE_MAX_BYTES];
    const char *suffix[10];
    const char *expected[10];
    char px4_suffix[8][64];
    suffix[0] = "_betaflight.csv";
    expected[0] = BETAFLIGHT_HEADER;
    suffix[1] = "_log.csv";
    expected[1] = GENERIC_HEADER;
    for (int k = 0; k < 8; ++k) {
        snprintf(px4_suffix[k], sizeof px4_suffix[k], "_px4_%s_0.csv", PX4_TOPICS[k]);
        suffix[2 + k] = px4_suffix[k];
        expected[2 + k] = PX4_HEADERS[k];
    }
    for (int f = 0; f < 10; ++f) {
        file_path(path, sizeof path, suffix[f]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(TICKS, read_rows(path, header, &rows), path);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(expected[f], header, path);
        free(rows);
    }
}

/* The real the controller got, from its text (9 digits for a float, 17 for a double: it reads back as itself). */
static void assert_float_cell(ladrc_real_t expected, const char *cell)
{
    char m[128];
    snprintf(m, sizeof m, "%s vs %.9g", cell, (double)expected);
    TEST_ASSERT_TRUE_MESSAGE((ladrc_real_t)strtod(cell, NULL) == expected, m);
}

static void test_the_generic_form_holds_what_the_controller_got_and_did(void)
{
    fly();
    char path[256], header[LINE_MAX_BYTES];
    char(*rows)[LINE_MAX_BYTES];
    file_path(path, sizeof path, "_log.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &rows));
    int filtered = 0, chirped = 0;
    for (int k = 0; k < TICKS; ++k) {
        char *cell[FIELDS_MAX];
        TEST_ASSERT_EQUAL_INT(24, split(rows[k], ",", cell));
        TEST_ASSERT_TRUE(strtod(cell[0], NULL) == given[k].t_s); /* %.17g: exact */
        for (int i = 0; i < 3; ++i) {
            assert_float_cell(given[k].rate[i], cell[1 + i]);
            assert_float_cell(given[k].angle[i], cell[7 + i]);
            assert_float_cell(given[k].ref[i], cell[14 + i]);
            const double command = (double)given[k].applied_Nm[i] / sim_setup_authority_Nm(&sc, i);
            TEST_ASSERT_TRUE_MESSAGE(strtod(cell[20 + i], NULL) == command, cell[20 + i]);
            filtered |= strtod(cell[4 + i], NULL) != (double)given[k].rate[i];
        }
        chirped |= fabs(strtod(cell[22], NULL)) > 0.05; /* the yaw chirp (0.1) shows */
        const double q_norm = hypot(hypot(strtod(cell[10], NULL), strtod(cell[11], NULL)),
                                    hypot(strtod(cell[12], NULL), strtod(cell[13], NULL)));
        TEST_ASSERT_TRUE(fabs(q_norm - 1.0) < 1e-12); /* a unit quaternion, to double rounding */
        const double throttle = strtod(cell[23], NULL);
        TEST_ASSERT_TRUE(throttle > 0.0 && throttle < 1.0);
    }
    TEST_ASSERT_TRUE(filtered); /* gyro_raw is the rate before the filter */
    TEST_ASSERT_TRUE(chirped);
    free(rows);
}

static void test_betaflight_values_are_integers_from_the_same_tick(void)
{
    fly();
    char path[256], header[LINE_MAX_BYTES];
    char(*bf)[LINE_MAX_BYTES], (*generic)[LINE_MAX_BYTES];
    file_path(path, sizeof path, "_betaflight.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &bf));
    file_path(path, sizeof path, "_log.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &generic));
    const double rad2deg = 180.0 / 3.14159265358979323846;
    for (int k = 0; k < TICKS; ++k) {
        char *b[FIELDS_MAX], *g[FIELDS_MAX];
        TEST_ASSERT_EQUAL_INT(35, split(bf[k], ", ", b));
        TEST_ASSERT_EQUAL_INT(24, split(generic[k], ",", g));
        long long v[35];
        for (int c = 0; c < 35; ++c)
            v[c] = integer(b[c]);
        TEST_ASSERT_EQUAL_INT(k, (int)v[0]);
        TEST_ASSERT_TRUE(v[1] == llround(strtod(g[0], NULL) * 1e6));
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(v[2 + i] == llround(1000.0 * strtod(g[20 + i], NULL)));   /* axisP */
            TEST_ASSERT_TRUE(v[21 + i] == llround(strtod(g[1 + i], NULL) * rad2deg));  /* gyroADC */
            TEST_ASSERT_TRUE(v[24 + i] == llround(strtod(g[4 + i], NULL) * rad2deg));  /* gyroUnfilt */
            TEST_ASSERT_TRUE(v[17 + i] == llround(strtod(g[17 + i], NULL) * rad2deg)); /* setpoint */
        }
        for (int c = 5; c < 16; ++c)
            TEST_ASSERT_TRUE(v[c] == 0); /* axisI, axisD, axisF, rcCommand[0..2] */
        TEST_ASSERT_TRUE(v[16] == llround(1000.0 * strtod(g[23], NULL)) && v[20] == v[16]); /* throttle */
        for (int q = 0; q < 4; ++q) {
            TEST_ASSERT_TRUE(v[27 + q] >= 48 && v[27 + q] <= 2047);
            TEST_ASSERT_TRUE(v[31 + q] > 0); /* eRPM / 100 of spinning rotors */
        }
    }
    free(bf);
    free(generic);
}

static void test_px4_topics_agree_with_the_generic_form(void)
{
    fly();
    char path[256], header[LINE_MAX_BYTES];
    char(*generic)[LINE_MAX_BYTES], (*torque)[LINE_MAX_BYTES], (*rates)[LINE_MAX_BYTES];
    file_path(path, sizeof path, "_log.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &generic));
    file_path(path, sizeof path, "_px4_vehicle_torque_setpoint_0.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &torque));
    file_path(path, sizeof path, "_px4_vehicle_angular_velocity_0.csv");
    TEST_ASSERT_EQUAL_INT(TICKS, read_rows(path, header, &rates));
    for (int k = 0; k < TICKS; ++k) {
        char *g[FIELDS_MAX], *t[FIELDS_MAX], *r[FIELDS_MAX];
        TEST_ASSERT_EQUAL_INT(24, split(generic[k], ",", g));
        TEST_ASSERT_EQUAL_INT(4, split(torque[k], ",", t));
        TEST_ASSERT_EQUAL_INT(5, split(rates[k], ",", r));
        const long long us = llround(strtod(g[0], NULL) * 1e6);
        TEST_ASSERT_TRUE(integer(t[0]) == us && integer(r[0]) == us && integer(r[1]) == us);
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_EQUAL_STRING(g[20 + i], t[1 + i]); /* the command, %.17g */
            TEST_ASSERT_EQUAL_STRING(g[1 + i], r[2 + i]);  /* the controller's rate, as the real it was */
        }
    }
    free(generic);
    free(torque);
    free(rates);
}

/* A run that diverges at 1.501 s (test_sim_runner.c's infinite disturbance):
 * its ticks 0 .. 1500 are logged, nothing after. */
static void test_nothing_is_logged_after_a_divergence(void)
{
    fly();
    static sim_scenario_t bad;
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0,
                                  sim_scenario_parse(&bad,
                                                     "[run]\nduration_s = 3\ncontrollers = PID\nlog = generic\n"
                                                     "[disturbance]\nroll = 1.5 .. 3 : 1e300 * 1e300\n",
                                                     "diverges.ini", &perr),
                                  perr.message);
    char csv_path[256], log_path[256], header[LINE_MAX_BYTES];
    snprintf(csv_path, sizeof csv_path, "%s/PID.csv", dir);
    snprintf(log_path, sizeof log_path, "%s/PID_log.csv", dir);
    sim_metrics_t m;
    char err[256] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(&bad, SIM_CTRL_PID, csv_path, NULL, &m, err, sizeof err), err);
    TEST_ASSERT_TRUE(m.diverged);
    char(*rows)[LINE_MAX_BYTES];
    TEST_ASSERT_EQUAL_INT((int)m.rotor_w2[0].n, read_rows(log_path, header, &rows));
    TEST_ASSERT_EQUAL_INT(1501, (int)m.rotor_w2[0].n);
    free(rows);
    remove(csv_path);
    remove(log_path);
}

static void test_a_log_that_cannot_be_written_is_named(void)
{
    fly();
    static sim_scenario_t one;
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(
        0, sim_scenario_parse(&one, "[run]\nduration_s = 0.1\ncontrollers = PID\nlog = px4\n", "one.ini", &perr),
        perr.message);
    char csv_path[256], blocked[256];
    snprintf(csv_path, sizeof csv_path, "%s/PID.csv", dir);
    snprintf(blocked, sizeof blocked, "%s/PID_px4_esc_status_0.csv", dir);
    TEST_ASSERT_EQUAL_INT(0, mkdir(blocked, 0700)); /* a folder where the file should go */
    sim_metrics_t m;
    char err[512] = "";
    TEST_ASSERT_EQUAL_INT(-1, sim_run_attitude(&one, SIM_CTRL_PID, csv_path, NULL, &m, err, sizeof err));
    char expected[300];
    snprintf(expected, sizeof expected, "%s: cannot write: ", blocked);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, strncmp(err, expected, strlen(expected)), err);
    rmdir(blocked);
    remove(csv_path);
    for (int k = 0; k < 8; ++k) { /* the topics opened before it */
        char path[256];
        snprintf(path, sizeof path, "%s/PID_px4_%s_0.csv", dir, PX4_TOPICS[k]);
        remove(path);
    }
}

/* The run's files and folder. */
static void clean_up(void)
{
    if (!flown)
        return;
    char path[256];
    file_path(path, sizeof path, ".csv");
    remove(path);
    file_path(path, sizeof path, "_betaflight.csv");
    remove(path);
    file_path(path, sizeof path, "_log.csv");
    remove(path);
    for (int k = 0; k < 8; ++k) {
        char suffix[64];
        snprintf(suffix, sizeof suffix, "_px4_%s_0.csv", PX4_TOPICS[k]);
        file_path(path, sizeof path, suffix);
        remove(path);
    }
    rmdir(dir);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_form_has_its_header_and_one_row_per_tick);
    RUN_TEST(test_the_generic_form_holds_what_the_controller_got_and_did);
    RUN_TEST(test_betaflight_values_are_integers_from_the_same_tick);
    RUN_TEST(test_px4_topics_agree_with_the_generic_form);
    RUN_TEST(test_nothing_is_logged_after_a_divergence);
    RUN_TEST(test_a_log_that_cannot_be_written_is_named);
    const int failures = UNITY_END();
    clean_up();
    return failures;
}
