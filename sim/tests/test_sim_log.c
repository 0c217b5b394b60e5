/* SPDX-License-Identifier: BSD-3-Clause */
/* The flight-log reader (log/log.h) on single CSVs: the Betaflight and
 * generic forms, exact read-back at the control rate, the integrated
 * attitude, gaps, the window, progress, bounded memory on a 20 MB log, and
 * every error at its line and column. The PX4 form: test_sim_log_px4.c. */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkstemp */
#include "unity.h"
#include "log/log.h"
#include "log/log_csv.h"
#include "plant/rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0) /* as the reader's `*deg` */
/* Values of order 1-100 through a few roundings (a sum, a scale, a
 * subtraction of times): some ulps. */
#define ROUND_TOL 1e-12
/* The memory a read may add to the process's peak: the reader holds a
 * 64 KiB block, a line, 1000 rows and the cells (under 1 MiB); the rest is
 * room for the C library's buffers and heap arenas. A reader that kept the
 * 20 MB log's rows (as doubles, more than its text) would add over 20 MiB. */
#define MEMORY_GROWTH_MAX_KIB (8 * 1024)
#define BIG_LOG_BYTES (20L * 1000 * 1000)

static char path[64]; /* a test's temporary file, removed after it */

/* Doubles and long longs (this Unity compares floats only). */
#define ASSERT_NEAR(tol, want, got) assert_near((tol), (want), (got), __LINE__)
#define ASSERT_EQ_LL(want, got) assert_near(0.0, (double)(want), (double)(got), __LINE__)

static void assert_near(double tol, double want, double got, int line)
{
    static char msg[200];
    snprintf(msg, sizeof msg, "want %.17g, got %.17g (tolerance %.3g)", want, got, tol);
    UNITY_TEST_ASSERT(fabs(got - want) <= tol, line, msg);
}

void setUp(void)
{
    path[0] = '\0';
}
void tearDown(void)
{
    if (path[0] != '\0') {
        remove(path);
    }
}

static sim_log_options_t options(sim_log_format_t format, double dt_s)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = format;
    o.dt_s = dt_s;
    return o;
}

/* Opens text as a stream; the stream in *f, closed by the caller. */
static sim_log_t *open_text(const char *text, const sim_log_options_t *o, FILE **f, sim_log_error_t *err)
{
    *f = fmemopen((void *)(uintptr_t)text, strlen(text), "r");
    TEST_ASSERT_NOT_NULL(*f);
    return sim_log_open_stream(*f, "test.csv", o, err);
}

/* Every tick of text into s (at most max): their count, or -1 with *err. */
static int read_text(const char *text, const sim_log_options_t *o, sim_log_sample_t *s, int max, sim_log_stats_t *st,
                     sim_log_error_t *err)
{
    FILE *f;
    sim_log_t *log = open_text(text, o, &f, err);
    int n = 0, rc = 1;
    if (log == NULL) {
        fclose(f);
        return -1;
    }
    sim_log_sample_t scratch;
    while (rc == 1) {
        rc = sim_log_next(log, n < max ? &s[n] : &scratch, err);
        n += rc == 1;
    }
    if (st != NULL) {
        sim_log_stats(log, st);
    }
    sim_log_close(log);
    fclose(f);
    return rc < 0 ? -1 : n;
}

static void expect_error_map(const char *text, sim_log_format_t format, const char *const *map, int n_map, int line,
                             int column, const char *needle)
{
    sim_log_options_t o = options(format, 0.001);
    sim_log_error_t err;
    sim_log_sample_t s[4];
    char shown[512];
    for (int i = 0; i < n_map; ++i) {
        o.map[i] = map[i];
    }
    o.n_map = n_map;
    memset(&err, 0, sizeof err);
    TEST_ASSERT_EQUAL_INT_MESSAGE(-1, read_text(text, &o, s, 4, NULL, &err), text);
    sim_log_error_format(&err, shown, sizeof shown);
    TEST_ASSERT_EQUAL_STRING_MESSAGE("test.csv", err.path, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(line, err.line, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(column, err.column, shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle), shown);
}

static void expect_error(const char *text, int line, int column, const char *needle)
{
    expect_error_map(text, SIM_LOG_GENERIC, NULL, 0, line, column, needle);
}

static int same_bits(const double *a, const double *b, size_t n)
{
    return memcmp(a, b, n * sizeof *a) == 0;
}

/* A new file of our own in the test's folder; the stream to write it. */
static FILE *create_temp(void)
{
    snprintf(path, sizeof path, "log_test_XXXXXX");
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    FILE *f = fdopen(fd, "wb");
    TEST_ASSERT_NOT_NULL(f);
    return f;
}

/* ---- Betaflight ---------------------------------------------------- */

#define BF_ROWS 1001 /* 2 s at 500 Hz */
#define BF_ROW_US 2000
#define BF_W (2.0 * PI * 1.5)
static const double BF_ANGLE_DEG[3] = {20.0, -10.0, 30.0}; /* amplitudes of the attitude */
static const double BF_REF_DEG[3] = {15.0, 5.0, -25.0};

static double bf_p(int j, int axis)
{
    return 100.0 + (j % 7) - 30.0 * axis;
}

/* One row as blackbox_decode writes it: ", " between cells, a text column. */
static void bf_row(FILE *f, int j)
{
    const double tau = j * BF_ROW_US * 1e-6;
    fprintf(f, "%d, %d", 4 * j, 1000000 + BF_ROW_US * j);
    for (int i = 0; i < 3; ++i) {
        fprintf(f, ", %.17g", bf_p(j, i));
    }
    fprintf(f, ", 5, 6, 7, -3, -4"); /* axisI[0..2], axisD[0..1]: no axisD[2] */
    fprintf(f, ", 2, 2, 2");         /* axisF */
    for (int i = 0; i < 3; ++i) {
        fprintf(f, ", %.17g", BF_REF_DEG[i] * BF_W * cos(BF_W * tau));
    }
    fprintf(f, ", 500");
    for (int i = 0; i < 3; ++i) {
        fprintf(f, ", %.17g", BF_ANGLE_DEG[i] * BF_W * cos(BF_W * tau));
    }
    fprintf(f, ", %d, %d, %d, %d, ARM|ANGLE_MODE\n", 1000 + j, 1100 + j, 1200 + j, 1300 + j);
}

static const char BF_HEADER[] = "loopIteration, time (us), axisP[0], axisP[1], axisP[2], axisI[0], axisI[1], "
                                "axisI[2], axisD[0], axisD[1], axisF[0], axisF[1], axisF[2], setpoint[0], "
                                "setpoint[1], setpoint[2], setpoint[3], gyroADC[0], gyroADC[1], gyroADC[2], "
                                "motor[0], motor[1], motor[2], motor[3], flightModeFlags\n";

static void test_betaflight_form_read_and_attitude_integrated(void)
{
    FILE *f = create_temp();
    fputs(BF_HEADER, f);
    for (int j = 0; j < BF_ROWS; ++j) {
        bf_row(f, j);
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));

    sim_log_options_t o = options(SIM_LOG_BETAFLIGHT, 0.001); /* 1 kHz from 500 Hz rows */
    snprintf(o.path, sizeof o.path, "%s", path);
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    const unsigned want = SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE_INTEGRATED | SIM_LOG_HAS_REF_RATE |
                          SIM_LOG_HAS_REF_INTEGRATED | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_THROTTLE | SIM_LOG_HAS_MOTOR;
    TEST_ASSERT_EQUAL_UINT(want, sim_log_has(log));
    ASSERT_NEAR(1e-15, 0.001, sim_log_dt_s(log));

    /* The trapezoid over 1 kHz ticks of the gyro interpolated linearly
     * between 500 Hz rows is the trapezoid over the rows (exact on each
     * piece): error <= T h^2 / 12 max|g''|, g = A w cos(w t). */
    const double T = (BF_ROWS - 1) * BF_ROW_US * 1e-6, h = BF_ROW_US * 1e-6;
    sim_log_sample_t s;
    int k = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        const int j = k / 2;
        const double tau = k * 1e-3;
        ASSERT_NEAR(1e-15, tau, s.t_s);
        TEST_ASSERT_EQUAL_INT(4, s.n_motors);
        TEST_ASSERT_TRUE(isnan(s.quat[0]) && isnan(s.ref_quat[0]) && isnan(s.gyro_raw_rad_s[0]));
        TEST_ASSERT_TRUE(isnan(s.motor[4]) && isnan(s.rotor_hz[0]));
        ASSERT_NEAR(0.0, 0.5, s.throttle);
        for (int i = 0; i < 3; ++i) {
            const double a = BF_ANGLE_DEG[i] * DEG, r = BF_REF_DEG[i] * DEG;
            const double tol = T * h * h / 12.0 * fabs(a) * pow(BF_W, 3) + ROUND_TOL;
            const double ref_tol = T * h * h / 12.0 * fabs(r) * pow(BF_W, 3) + ROUND_TOL;
            ASSERT_NEAR(tol, a * sin(BF_W * tau), s.angle_rad[i]);
            ASSERT_NEAR(ref_tol, r * sin(BF_W * tau), s.ref_angle_rad[i]);
        }
        if (k % 2 == 0) {                                /* on a row: its values, bit for bit */
            const double tau_row = j * BF_ROW_US * 1e-6; /* as the row was written */
            for (int i = 0; i < 3; ++i) {
                const double g = BF_ANGLE_DEG[i] * BF_W * cos(BF_W * tau_row) * DEG;
                TEST_ASSERT_TRUE(same_bits(&g, &s.gyro_rad_s[i], 1));
                const double d = i < 2 ? -3.0 - i : 0.0; /* yaw: no axisD[2], optional */
                const double c = (i < 2 ? bf_p(j, i) + (5.0 + i) + d : bf_p(j, i) + 7.0) + 2.0;
                const double want_c = c * 0.001;
                TEST_ASSERT_TRUE(same_bits(&want_c, &s.command[i], 1));
            }
            ASSERT_NEAR(0.0, 1000.0 + j, s.motor[0]);
            ASSERT_NEAR(0.0, 1300.0 + j, s.motor[3]);
        } else { /* half way: the mean of the rows */
            ASSERT_NEAR(ROUND_TOL, 1000.5 + j, s.motor[0]);
        }
        ++k;
    }
    TEST_ASSERT_EQUAL_INT(2 * (BF_ROWS - 1) + 1, k);
    sim_log_stats_t st;
    sim_log_stats(log, &st);
    ASSERT_EQ_LL(BF_ROWS, st.rows);
    ASSERT_EQ_LL(k, st.ticks);
    ASSERT_EQ_LL(0, st.gaps);
    ASSERT_NEAR(1e-15, 0.002, st.row_period_s);
    TEST_ASSERT_EQUAL_INT(1, st.n_files);
    long long done, total;
    sim_log_progress(log, &done, &total);
    TEST_ASSERT_TRUE(total > 0 && done == total); /* read to its end */
    sim_log_close(log);
}

static void test_betaflight_optional_columns_and_overrides(void)
{
    /* eRPM and gyroUnfilt found: rotor_hz and gyro_raw; the caller's item
     * replaces the preset's command[1] */
    static const char text[] = "time (us), axisP[0], axisP[1], axisP[2], gyroADC[0], gyroADC[1], gyroADC[2], "
                               "gyroUnfilt[0], gyroUnfilt[1], gyroUnfilt[2], eRPM[0], eRPM[1], other\n"
                               "100, 1, 2, 3, 10, 20, 30, 11, 21, 31, 420, 840, x\n"
                               "200, 1, 2, 3, 10, 20, 30, 11, 21, 31, 420, 840, y\n";
    sim_log_options_t o = options(SIM_LOG_BETAFLIGHT, 0.0001);
    o.map[0] = "command[1]=axisP[1]+axisP[2]*-1";
    o.n_map = 1;
    sim_log_sample_t s[4];
    sim_log_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(2, read_text(text, &o, s, 4, &st, &err), err.message);
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_GYRO_RAW | SIM_LOG_HAS_ANGLE_INTEGRATED |
                               SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_ROTOR_HZ,
                           st.has);
    TEST_ASSERT_EQUAL_INT(2, s[0].n_motors);
    TEST_ASSERT_TRUE(isnan(s[0].motor[0]));
    ASSERT_NEAR(1e-6, 100.0, s[0].rotor_hz[0]); /* 420 x 100 / 60 / 7 */
    ASSERT_NEAR(1e-6, 200.0, s[0].rotor_hz[1]);
    ASSERT_NEAR(ROUND_TOL, 31.0 * DEG, s[1].gyro_raw_rad_s[2]);
    ASSERT_NEAR(0.0, -5.0, s[0].command[1]);
    ASSERT_NEAR(0.0, 0.001, s[0].command[0]);
    TEST_ASSERT_TRUE(isnan(s[0].throttle));
}

/* ---- generic ------------------------------------------------------- */

/* Values with every bit of a double, as a log written by a simulator. */
static double value_of(int k, int col)
{
    return sin(0.37 * k + 1.3 * col) * (1.0 + col) / 3.0;
}

static const char GENERIC_HEADER[] =
    "time,gyro[0],gyro[1],gyro[2],quat[0],quat[1],quat[2],quat[3],command[0],command[1],command[2],throttle\n";
#define GENERIC_COLS 11

static char *generic_text(int rows, double dt_s, size_t *len)
{
    const size_t cap = (size_t)rows * 300 + 200;
    char *text = malloc(cap);
    size_t n = (size_t)snprintf(text, cap, "%s", GENERIC_HEADER);
    for (int k = 0; k < rows; ++k) {
        n += (size_t)snprintf(text + n, cap - n, "%.17g", k * dt_s);
        for (int c = 0; c < GENERIC_COLS; ++c) {
            n += (size_t)snprintf(text + n, cap - n, ",%.17g", value_of(k, c));
        }
        n += (size_t)snprintf(text + n, cap - n, "\n");
    }
    *len = n;
    return text;
}

static void test_generic_form_reads_back_bit_for_bit_at_the_control_rate(void)
{
    enum { ROWS = 500 };
    size_t len;
    char *text = generic_text(ROWS, 0.001, &len);
    static sim_log_sample_t s[ROWS + 1];
    const double dts[] = {0.001, 0.0}; /* given, and the median row period */
    for (int d = 0; d < 2; ++d) {
        sim_log_options_t o = options(SIM_LOG_GENERIC, dts[d]);
        sim_log_stats_t st;
        sim_log_error_t err;
        TEST_ASSERT_EQUAL_INT_MESSAGE(ROWS, read_text(text, &o, s, ROWS + 1, &st, &err), err.message);
        ASSERT_NEAR(1e-15, 0.001, st.row_period_s);
        TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_THROTTLE,
                               st.has);
        for (int k = 0; k < ROWS; ++k) {
            double v[GENERIC_COLS];
            for (int c = 0; c < GENERIC_COLS; ++c) {
                v[c] = value_of(k, c);
            }
            TEST_ASSERT_TRUE(same_bits(v, s[k].gyro_rad_s, 3));
            TEST_ASSERT_TRUE(same_bits(v + 3, s[k].quat, 4)); /* not normalised on a row */
            TEST_ASSERT_TRUE(same_bits(v + 7, s[k].command, 3));
            TEST_ASSERT_TRUE(same_bits(v + 10, &s[k].throttle, 1));
            TEST_ASSERT_TRUE(isfinite(s[k].angle_rad[0]) && isfinite(s[k].angle_rad[2]));
            TEST_ASSERT_EQUAL_INT(0, s[k].n_motors);
        }
    }
    free(text);
}

/* ZYX angles to a quaternion, written out as the reader's doc states it. */
static void quat_of(double r, double p, double y, double q[4])
{
    q[0] = cos(r / 2) * cos(p / 2) * cos(y / 2) + sin(r / 2) * sin(p / 2) * sin(y / 2);
    q[1] = sin(r / 2) * cos(p / 2) * cos(y / 2) - cos(r / 2) * sin(p / 2) * sin(y / 2);
    q[2] = cos(r / 2) * sin(p / 2) * cos(y / 2) + sin(r / 2) * cos(p / 2) * sin(y / 2);
    q[3] = cos(r / 2) * cos(p / 2) * sin(y / 2) - sin(r / 2) * sin(p / 2) * cos(y / 2);
}

static void test_angle_from_quat_and_quat_from_angle(void)
{
    const double a[2][3] = {{0.3, -0.2, 2.9}, {-1.1, 0.7, -3.0}};
    double q[2][4];
    char text[1024];
    quat_of(a[0][0], a[0][1], a[0][2], q[0]);
    quat_of(a[1][0], a[1][1], a[1][2], q[1]);
    /* the attitude as a quaternion, the reference as angles */
    int n =
        snprintf(text, sizeof text, "time,quat[0],quat[1],quat[2],quat[3],ref_angle[0],ref_angle[1],ref_angle[2]\n");
    for (int k = 0; k < 2; ++k) {
        n += snprintf(text + n, sizeof text - (size_t)n, "%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", k, q[k][0],
                      q[k][1], q[k][2], q[k][3], a[k][0], a[k][1], a[k][2]);
    }
    sim_log_options_t o = options(SIM_LOG_GENERIC, 1.0);
    sim_log_sample_t s[2];
    sim_log_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(2, read_text(text, &o, s, 2, &st, &err), err.message);
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_REF_ANGLE, st.has);
    for (int k = 0; k < 2; ++k) {
        for (int i = 0; i < 3; ++i) {
            ASSERT_NEAR(ROUND_TOL, a[k][i], s[k].angle_rad[i]);
        }
        for (int i = 0; i < 4; ++i) {
            ASSERT_NEAR(ROUND_TOL, q[k][i], s[k].ref_quat[i]);
        }
    }
    TEST_ASSERT_TRUE(isnan(s[0].gyro_rad_s[0]));
}

static void test_between_rows_linear_quaternions_normalised_wrapped_yaw_the_short_way(void)
{
    /* rows 1 s apart, ticks at 0.25 s; yaw from 170 to -170 deg (wrapped):
     * through 180, not through 0 */
    double q0[4], q1[4];
    quat_of(0.0, 0.0, 0.0, q0);
    quat_of(0.4, 0.0, 0.0, q1);
    char text[512];
    snprintf(text, sizeof text,
             "time,gyro[0],angle[2],ref_quat[0],ref_quat[1],ref_quat[2],ref_quat[3]\n"
             "0,1,%.17g,%.17g,%.17g,%.17g,%.17g\n1,3,%.17g,%.17g,%.17g,%.17g,%.17g\n",
             170.0 * DEG, q0[0], q0[1], q0[2], q0[3], -170.0 * DEG, q1[0], q1[1], q1[2], q1[3]);
    sim_log_options_t o = options(SIM_LOG_GENERIC, 0.25);
    sim_log_sample_t s[5];
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(5, read_text(text, &o, s, 5, NULL, &err), err.message);
    ASSERT_NEAR(0.0, 1.5, s[1].gyro_rad_s[0]);
    ASSERT_NEAR(0.0, 0.0, s[1].gyro_rad_s[1]); /* a component without a column */
    ASSERT_NEAR(ROUND_TOL, 175.0 * DEG, s[1].angle_rad[2]);
    ASSERT_NEAR(ROUND_TOL, 180.0 * DEG, s[2].angle_rad[2]);
    /* normalised, on the plane of the rotation: the normalised linear path
     * of a D = 0.4 rad turn departs from the uniform rotation by less than
     * 0.3 (D/4)^3 (its largest, 0.26 (D/4)^3, near a quarter of the way) */
    const double r = atan2(s[1].ref_quat[1], s[1].ref_quat[0]) * 2.0;
    ASSERT_NEAR(ROUND_TOL, 1.0, hypot(hypot(s[1].ref_quat[0], s[1].ref_quat[1]), s[1].ref_quat[2]));
    ASSERT_NEAR(0.3 * pow(0.4 / 4.0, 3), 0.1, r);
    ASSERT_NEAR(ROUND_TOL, 0.2, s[2].ref_angle_rad[0]);
}

static void test_gaps_counted_and_interpolated_over(void)
{
    /* rows 10 ms apart, then one 60 ms gap (> 5 x the median) and one 40 ms
     * period (not a gap) */
    static const char text[] = "time,gyro[0]\n0,0\n0.01,1\n0.02,2\n0.03,3\n0.09,9\n0.13,13\n0.14,14\n";
    sim_log_options_t o = options(SIM_LOG_GENERIC, 0.01);
    sim_log_sample_t s[16];
    sim_log_stats_t st;
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(15, read_text(text, &o, s, 16, &st, &err), err.message);
    ASSERT_EQ_LL(1, st.gaps);
    ASSERT_NEAR(1e-12, 0.06, st.longest_gap_s);
    ASSERT_NEAR(1e-15, 0.01, st.row_period_s);
    ASSERT_EQ_LL(7, st.rows);
    for (int k = 0; k < 15; ++k) {
        ASSERT_NEAR(ROUND_TOL, (double)k, s[k].gyro_rad_s[0]);
    }
}

static void test_window_from_and_to(void)
{
    size_t len;
    char *text = generic_text(400, 0.001, &len);
    sim_log_options_t o = options(SIM_LOG_GENERIC, 0.001);
    o.t_from_s = 0.1;
    o.t_to_s = 0.2;
    static sim_log_sample_t s[200];
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(101, read_text(text, &o, s, 200, NULL, &err), err.message);
    ASSERT_NEAR(1e-12, 0.1, s[0].t_s);
    ASSERT_NEAR(1e-12, 0.2, s[100].t_s);
    const double v = value_of(100, 0);
    TEST_ASSERT_TRUE(same_bits(&v, s[0].gyro_rad_s, 1));

    /* a window after the log's end is an error; one past it ends with it */
    o.t_from_s = 1.0;
    o.t_to_s = 0.0;
    TEST_ASSERT_EQUAL_INT(-1, read_text(text, &o, s, 200, NULL, &err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "after the log's end"), err.message);
    o.t_from_s = 0.39;
    o.t_to_s = 5.0;
    TEST_ASSERT_EQUAL_INT(10, read_text(text, &o, s, 200, NULL, &err));

    /* integrated angles start at 0 on the window's first tick */
    static const char rates[] = "time,gyro[2]\n0,1\n1,1\n2,1\n3,1\n";
    o.t_from_s = 1.0;
    o.t_to_s = 0.0;
    o.dt_s = 0.5;
    TEST_ASSERT_EQUAL_INT(5, read_text(rates, &o, s, 200, NULL, &err));
    ASSERT_NEAR(0.0, 0.0, s[0].angle_rad[2]);
    ASSERT_NEAR(0.0, 2.0, s[4].angle_rad[2]);
    free(text);
}

static void test_a_nan_column_of_optional_items_is_absent(void)
{
    /* ulog2csv writes nan for the unused entries of an array: an optional
     * column that reads nan in the first row is taken as absent */
    static const char text[] = "time,motor[0],motor[1],motor[2]\n0,5,6,nan\n1,5,6,nan\n2,5,6,7\n";
    sim_log_options_t o = options(SIM_LOG_GENERIC, 1.0);
    sim_log_sample_t s[3];
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(3, read_text(text, &o, s, 3, NULL, &err), err.message);
    TEST_ASSERT_EQUAL_INT(2, s[0].n_motors);
    ASSERT_NEAR(0.0, 6.0, s[2].motor[1]);
    /* a nan in a later row of a column in use is an error */
    expect_error("time,motor[0]\n0,5\n1,nan\n", 3, 3, "not a finite number in column 'motor[0]': 'nan'");
}

/* ---- errors -------------------------------------------------------- */

static void test_missing_columns_at_the_header_line_end(void)
{
    static const char bf[] = "loopIteration, time (us), axisP[0], axisP[1], gyroADC[0], gyroADC[1], gyroADC[2]\n"
                             "0, 0, 1, 1, 1, 1, 1\n1, 1000, 1, 1, 1, 1, 1\n";
    expect_error_map(bf, SIM_LOG_BETAFLIGHT, NULL, 0, 1, 81, "no column 'axisP[2]' (needed for command[2])");
    static const char *const map[] = {"command[0]=cmd*0.5"};
    expect_error_map("time,gyro[0]\n0,1\n1,1\n", SIM_LOG_GENERIC, map, 1, 1, 13,
                     "no column 'cmd' (needed for command[0])");
    /* the byte order mark and the CR are not counted; blank lines skipped */
    expect_error_map("\xEF\xBB\xBF  \r\n\n  time,gyro[0]\r\n0,1\r\n1,1\r\n", SIM_LOG_GENERIC, map, 1, 3, 15,
                     "no column 'cmd'");
    expect_error_map("\xEF\xBB\xBFtime,gyro[0]\r\n0,1\r\n1,1\r\n", SIM_LOG_GENERIC, map, 1, 1, 13, "no column 'cmd'");
    expect_error("gyro[0],t\n0,1\n1,1\n", 1, 10, "no column 'time' (needed for time)");
    expect_error("time,quat[0],quat[1]\n0,1,0\n1,1,0\n", 1, 21, "no column for quat[2]");
}

static void test_time_not_increasing(void)
{
    expect_error("time,gyro[0]\n0.000,1\n0.002,1\n0.001,1\n", 4, 1, "time goes back from 0.002 s to 0.001 s");
    expect_error("time,gyro[0]\n0.000,1\n0.002,1\n  0.002,1\n", 4, 3, "time repeats (0.002 s)");
    /* seconds past 2^52 us no longer resolve a microsecond: said, not read as a repeat */
    expect_error("time,gyro[0]\n4503599627370497e-6,1\n4503599627370498e-6,1\n", 2, 1,
                 "beyond what a time in s or ms resolves to the microsecond (2^52 us)");
    /* in the first rows, held to estimate the row period, as later */
    expect_error("gyro[0], time\n1, 0\n1, 5\n1, 4\n", 4, 4, "time goes back");
}

static void test_a_row_period_below_a_microsecond_is_refused_as_the_logs(void)
{
    /* rows 1e-300 s apart (a time column in another unit): refused for the log's own times, not
     * for a period the user did not give, and never converted to a tick count */
    sim_log_options_t o = options(SIM_LOG_GENERIC, 0.0);
    sim_log_error_t err;
    sim_log_sample_t s[4];
    memset(&err, 0, sizeof err);
    TEST_ASSERT_EQUAL_INT(-1, read_text("time,gyro[0]\n0,1\n1e-300,1\n2e-300,1\n3e-300,1\n", &o, s, 4, NULL, &err));
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "rows 1e-300 s apart (the median): below 1e-6 s"), err.message);
    TEST_ASSERT_EQUAL_INT(1, err.line); /* at the header, which names the time column's unit */
    TEST_ASSERT_EQUAL_INT(1, err.column);
}

/* Angles from arithmetic on a handful of reals: ulps. */
#define QUAT_ANGLE_TOL 1e-12

static void test_a_quaternion_that_is_not_unit_gives_its_directions_angles_on_rows_and_between(void)
{
    /* (2, 1, 0, 0) is (0.894, 0.447, 0, 0) scaled: roll atan2(4, 3) on every tick, rows (every
     * 2nd tick) and between alike (53.13 deg; 104 deg from the raw numbers before) */
    const char *text = "time,gyro[0],quat[0],quat[1],quat[2],quat[3]\n"
                       "0,0,2,1,0,0\n0.002,0,2,1,0,0\n0.004,0,2,1,0,0\n0.006,0,2,1,0,0\n";
    sim_log_options_t o = options(SIM_LOG_GENERIC, 0.001);
    sim_log_error_t err;
    sim_log_sample_t s[8];
    const int n = read_text(text, &o, s, 8, NULL, &err);
    TEST_ASSERT_TRUE(n >= 5);
    for (int k = 0; k < n && k < 8; ++k) {
        TEST_ASSERT_TRUE(fabs(s[k].angle_rad[0] - atan2(4.0, 3.0)) <= QUAT_ANGLE_TOL);
        TEST_ASSERT_TRUE(fabs(s[k].angle_rad[1]) <= QUAT_ANGLE_TOL);
    }
}

static void test_a_quaternion_of_no_length_is_refused_at_its_row(void)
{
    /* no attitude at all (it read as level before) */
    expect_error("time,gyro[0],quat[0],quat[1],quat[2],quat[3]\n0,0,1,0,0,0\n0.001,0,0,0,0,0\n", 3, 1,
                 "a quaternion of no length (all four components 0)");
}

static void test_rows_of_the_wrong_length(void)
{
    expect_error("time,gyro[0],command[0]\n0,1,2\n0.001,1\n", 3, 8, "row has 2 cells, the header 3");
    expect_error("time,gyro[0],command[0]\n0,1,2\n0.001,1,2,3\n", 3, 11, "row has 4 cells, the header 3");
    expect_error("time,gyro[0],command[0]\n0,1,2\n0.001,1,2,\n", 3, 11, "row has 4 cells, the header 3");
}

static void test_values_that_are_not_finite_numbers(void)
{
    static const char head[] = "time,gyro[0],command[0],note\n0,1,2,x\n";
    const struct {
        const char *row;
        int column;
        const char *message;
    } cases[] = {
        {"0.001, nan, 2, y\n", 8, "not a finite number in column 'gyro[0]': 'nan'"},
        {"0.001,inf,2,y\n", 7, "'inf'"},
        {"0.001,1,-Infinity,y\n", 9, "not a finite number in column 'command[0]': '-Infinity'"},
        {"0.001,1,abc,y\n", 9, "'abc'"},
        {"0.001,0x10,2,y\n", 7, "'0x10'"},
        {"0.001,1e999,2,y\n", 7, "'1e999'"},
        {"0.001,1.5.2,2,y\n", 7, "'1.5.2'"},
        {"0.001,,2,y\n", 7, "not a finite number in column 'gyro[0]': empty cell"},
        {"0.001,\t ,2,y\n", 9, "empty cell"},
        {"0.001,1,2 3,y\n", 9, "'2 3'"},
        {"x,1,2,y\n", 1, "column 'time': 'x'"},
    };
    char text[256];
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        snprintf(text, sizeof text, "%s%s", head, cases[i].row);
        expect_error(text, 3, cases[i].column, cases[i].message);
    }
    /* every written form of a number is taken, and text in a column not mapped */
    static const char forms[] = "time,gyro[0],note\n0,2,x\n1,-3,y\n2.,.5,z\n3e0,+4E+2,-\n4,1e-3,\n";
    sim_log_options_t o = options(SIM_LOG_GENERIC, 1.0);
    sim_log_sample_t s[5];
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(5, read_text(forms, &o, s, 5, NULL, &err), err.message);
    ASSERT_NEAR(0.0, 400.0, s[3].gyro_rad_s[0]);
    /* beyond the reader's range */
    expect_error("time,gyro[0]\n0,1\n1,2e15\n", 3, 3, "beyond the reader's range");
}

static void test_a_line_longer_than_the_buffer(void)
{
    /* a header of 70,000 bytes: refused at the buffer's end, nothing held beyond it */
    enum { LONG_LINE = 70000 };
    char *text = malloc(LONG_LINE + 32);
    TEST_ASSERT_NOT_NULL(text);
    memcpy(text, "time,", 5);
    memset(text + 5, 'x', LONG_LINE - 5);
    strcpy(text + LONG_LINE, "\n0,1\n1,1\n");
    expect_error(text, 1, 65537, "line longer than 65536 bytes");
    /* one just within it is read */
    text[65536] = '\0';
    strcat(text, "\n0,1\n1,1\n");
    sim_log_options_t o = options(SIM_LOG_GENERIC, 1.0);
    sim_log_sample_t s[2];
    sim_log_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(2, read_text(text, &o, s, 2, NULL, &err), err.message);
    free(text);
}

static void test_a_stream_has_no_known_size(void)
{
    static const char text[] = "time,gyro[0]\n0,1\n1,1\n2,1\n";
    sim_log_options_t o = options(SIM_LOG_GENERIC, 1.0);
    sim_log_error_t err;
    FILE *f;
    sim_log_t *log = open_text(text, &o, &f, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    long long done, total;
    sim_log_progress(log, &done, &total);
    ASSERT_EQ_LL(sizeof text - 1, done); /* the three rows held at the open */
    ASSERT_EQ_LL(0, total);
    sim_log_close(log);
    fclose(f);
}

static void test_fewer_than_two_rows(void)
{
    expect_error("time,gyro[0]\n0,1\n", 3, 1, "fewer than 2 rows (1)");
    expect_error("time,gyro[0]\n0,1", 2, 4, "fewer than 2 rows (1)");
    expect_error("time,gyro[0]\n\n  ", 3, 3, "fewer than 2 rows (0)");
    expect_error("\n", 2, 1, "no header line");
}

static void test_bad_map_items(void)
{
    const struct {
        const char *item;
        const char *message;
    } cases[] = {
        {"gyr[0]=x", "map item 'gyr[0]=x': unknown field 'gyr[0]'"},
        {"gyro[0]=g*furlongs", "map item 'gyro[0]=g*furlongs': bad scale"},
        {"gyro[0]=g*nan", "bad scale"},
        {"gyro[0]=g*", "bad scale"},
        {"gyro[3]=g", "no such component"},
        {"throttle[0]=g", "no such component"},
        {"gyro=g", "needs its component"},
        {"gyro[0]", "no '='"},
        {"gyro[0]=a+", "empty column name"},
        {"gyro[0]=?", "empty column name"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        expect_error_map("time,gyro[0]\n0,1\n1,1\n", SIM_LOG_GENERIC, &cases[i].item, 1, 0, 0, cases[i].message);
    }
}

static void test_options_formats_and_messages(void)
{
    TEST_ASSERT_EQUAL_INT(SIM_LOG_BETAFLIGHT, sim_log_format_parse("betaflight"));
    TEST_ASSERT_EQUAL_INT(SIM_LOG_PX4, sim_log_format_parse("px4"));
    TEST_ASSERT_EQUAL_INT(SIM_LOG_GENERIC, sim_log_format_parse("generic"));
    TEST_ASSERT_EQUAL_INT(-1, sim_log_format_parse("ulog"));
    TEST_ASSERT_EQUAL_STRING("px4", sim_log_format_name(SIM_LOG_PX4));
    sim_log_error_t err = {"a.csv", 3, 7, "bad"};
    char buf[300];
    sim_log_error_format(&err, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("a.csv:3:7: bad", buf);
    err.line = 0;
    sim_log_error_format(&err, buf, sizeof buf);
    TEST_ASSERT_EQUAL_STRING("a.csv: bad", buf);

    sim_log_options_t o = options(SIM_LOG_GENERIC, 1e-7);
    snprintf(o.path, sizeof o.path, "no_such_log.csv");
    TEST_ASSERT_NULL(sim_log_open(&o, &err));
    TEST_ASSERT_NOT_NULL(strstr(err.message, "dt_s"));
    o.dt_s = 0.0;
    TEST_ASSERT_NULL(sim_log_open(&o, &err));
    TEST_ASSERT_EQUAL_STRING("no_such_log.csv", err.path);
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "cannot open: "), err.message);
    o.t_from_s = 2.0;
    o.t_to_s = 1.0;
    TEST_ASSERT_NULL(sim_log_open(&o, &err));
    TEST_ASSERT_NOT_NULL(strstr(err.message, "empty window"));
}

/* ---- bounded memory ------------------------------------------------ */

static long max_rss_kib(void)
{
    struct rusage ru;
    TEST_ASSERT_EQUAL_INT(0, getrusage(RUSAGE_SELF, &ru));
    return ru.ru_maxrss; /* KiB on Linux */
}

static void test_a_20_mb_log_is_read_in_bounded_memory(void)
{
    FILE *f = create_temp();
    fputs(BF_HEADER, f);
    long rows = 0;
    while (ftell(f) < BIG_LOG_BYTES) {
        bf_row(f, (int)rows++);
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));

    const long before = max_rss_kib();
    sim_log_options_t o = options(SIM_LOG_BETAFLIGHT, 0.0); /* the rows' own period */
    snprintf(o.path, sizeof o.path, "%s", path);
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    long long ticks = 0, done, total;
    while (sim_log_next(log, &s, &err) == 1) {
        ++ticks;
    }
    sim_log_progress(log, &done, &total);
    sim_log_close(log);
    const long growth = max_rss_kib() - before;
    printf("log memory: %ld rows, %lld bytes read, peak resident memory grew by %ld KiB\n", rows, done, growth);
    ASSERT_EQ_LL(rows, ticks);
    TEST_ASSERT_TRUE(done == total && total >= BIG_LOG_BYTES);
    TEST_ASSERT_TRUE_MESSAGE(growth < MEMORY_GROWTH_MAX_KIB, "the reader's memory grows with the log");
}

/* The number parser's fast path (an exact mantissa and power of ten) gives
 * strtod's value bit for bit: integers, 9- and 17-digit decimals, exponents
 * on both sides of the fast path's reach, signs. */
static void test_numbers_read_as_strtod_reads_them(void)
{
    static const char *const formats[] = {"%.0f", "%.3f", "%.9g", "%.17g", "%.6e", "%.15g", "%.16g"};
    sim_rng_t r;
    sim_rng_seed(&r, 29);
    for (int k = 0; k < 20000; ++k) {
        const double x = (sim_rng_uniform(&r) - 0.5) * pow(10.0, (double)(k % 40) - 20.0);
        char text[64];
        snprintf(text, sizeof text, formats[k % 7], x);
        double got = 0.0;
        TEST_ASSERT_EQUAL_INT(0, sim_log_number(text, strlen(text), &got));
        const double want = strtod(text, NULL);
        TEST_ASSERT_TRUE_MESSAGE(memcmp(&got, &want, sizeof got) == 0, text);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_20_mb_log_is_read_in_bounded_memory); /* first: the peak before it is the process's start */
    RUN_TEST(test_numbers_read_as_strtod_reads_them);
    RUN_TEST(test_betaflight_form_read_and_attitude_integrated);
    RUN_TEST(test_betaflight_optional_columns_and_overrides);
    RUN_TEST(test_generic_form_reads_back_bit_for_bit_at_the_control_rate);
    RUN_TEST(test_angle_from_quat_and_quat_from_angle);
    RUN_TEST(test_between_rows_linear_quaternions_normalised_wrapped_yaw_the_short_way);
    RUN_TEST(test_gaps_counted_and_interpolated_over);
    RUN_TEST(test_window_from_and_to);
    RUN_TEST(test_a_nan_column_of_optional_items_is_absent);
    RUN_TEST(test_missing_columns_at_the_header_line_end);
    RUN_TEST(test_time_not_increasing);
    RUN_TEST(test_a_row_period_below_a_microsecond_is_refused_as_the_logs);
    RUN_TEST(test_a_quaternion_that_is_not_unit_gives_its_directions_angles_on_rows_and_between);
    RUN_TEST(test_a_quaternion_of_no_length_is_refused_at_its_row);
    RUN_TEST(test_rows_of_the_wrong_length);
    RUN_TEST(test_values_that_are_not_finite_numbers);
    RUN_TEST(test_fewer_than_two_rows);
    RUN_TEST(test_a_line_longer_than_the_buffer);
    RUN_TEST(test_a_stream_has_no_known_size);
    RUN_TEST(test_bad_map_items);
    RUN_TEST(test_options_formats_and_messages);
    return UNITY_END();
}
