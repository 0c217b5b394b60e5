/* SPDX-License-Identifier: BSD-3-Clause */
/* The flight-log reader (log/log.h) on a PX4 log as ulog2csv writes it:
 * five topic files at different rates read in lockstep and resampled to
 * 1 kHz against the analytic signals they were written from, the base found
 * from one topic file's path, optional topics absent, and the errors of
 * missing files and columns and of files that do not overlap. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "unity.h"
#include "log/log.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define ROUND_TOL 1e-12 /* values of order 1 through a few roundings */

#define ASSERT_NEAR(tol, want, got) assert_near((tol), (want), (got), __LINE__)

static void assert_near(double tol, double want, double got, int line)
{
    static char msg[200];
    snprintf(msg, sizeof msg, "want %.17g, got %.17g (tolerance %.3g)", want, got, tol);
    UNITY_TEST_ASSERT(fabs(got - want) <= tol, line, msg);
}

/* The signals, of the time t (s) since the log's clock started. */
#define GYRO_AMP 2.0
#define GYRO_W (2.0 * PI * 3.0)
#define ROLL_AMP 0.4 /* rad: vehicle_attitude turns about x only */
#define ROLL_W (2.0 * PI * 2.0)
#define TORQUE_AMP 0.3
#define TORQUE_W (2.0 * PI * 3.0)
#define PITCH_AMP 0.2 /* rad: the setpoint turns about y only */
#define PITCH_W (2.0 * PI * 0.5)
#define THRUST_W (2.0 * PI)
#define MOTOR_W (2.0 * PI * 1.5)

/* The topics: rate, first time, how many rows (to 3 s at most). */
#define GYRO_US 1000 /* 1 kHz */
#define ATT_US 4000  /* 250 Hz */
#define TORQUE_US 2000
#define SP_US 10000 /* 100 Hz */
#define MOTOR_US 10000
#define T_END_US 3000000

static char dir[64];
static char base[128];
static char files[8][256];
static int n_files;

void setUp(void)
{
    snprintf(dir, sizeof dir, "log_px4_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(base, sizeof base, "%s/flight", dir);
    n_files = 0;
}

void tearDown(void)
{
    for (int i = 0; i < n_files; ++i) {
        remove(files[i]);
    }
    rmdir(dir);
}

static FILE *create_topic(const char *topic)
{
    TEST_ASSERT_TRUE(n_files < 8);
    snprintf(files[n_files], sizeof files[0], "%s_%s_0.csv", base, topic);
    FILE *f = fopen(files[n_files++], "w");
    TEST_ASSERT_NOT_NULL(f);
    return f;
}

static void write_gyro(void)
{
    FILE *f = create_topic("vehicle_angular_velocity");
    fprintf(f, "timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]\n");
    for (long t = 1000000; t <= T_END_US; t += GYRO_US) {
        const double s = t * 1e-6;
        fprintf(f, "%ld,%ld,%.17g,%.17g,%.17g\n", t, t - 150, GYRO_AMP * sin(GYRO_W * s), -GYRO_AMP * cos(GYRO_W * s),
                0.5 * GYRO_AMP * sin(2.0 * GYRO_W * s));
    }
    fclose(f);
}

static void write_attitude(void)
{
    FILE *f = create_topic("vehicle_attitude");
    fprintf(f, "timestamp,q[0],q[1],q[2],q[3],delta_q_reset[0],delta_q_reset[1],delta_q_reset[2],"
               "delta_q_reset[3],quat_reset_counter\n");
    for (long t = 1002000; t <= T_END_US; t += ATT_US) {
        const double r = ROLL_AMP * sin(ROLL_W * t * 1e-6);
        fprintf(f, "%ld,%.17g,%.17g,0,0,1,0,0,0,0\n", t, cos(r / 2), sin(r / 2));
    }
    fclose(f);
}

static double torque(int i, double s)
{
    return TORQUE_AMP * sin(TORQUE_W * s + i);
}

static void write_torque(long first_us, long last_us, int with_yaw)
{
    FILE *f = create_topic("vehicle_torque_setpoint");
    fprintf(f, "timestamp,timestamp_sample,xyz[0],xyz[1]%s\n", with_yaw ? ",xyz[2]" : "");
    for (long t = first_us; t <= last_us; t += TORQUE_US) {
        const double s = t * 1e-6;
        fprintf(f, "%ld,%ld,%.17g,%.17g", t, t, torque(0, s), torque(1, s));
        if (with_yaw) {
            fprintf(f, ",%.17g", torque(2, s));
        }
        fprintf(f, "\n");
    }
    fclose(f);
}

static void write_setpoint(void)
{
    FILE *f = create_topic("vehicle_attitude_setpoint");
    fprintf(f, "timestamp,roll_body,pitch_body,yaw_body,q_d[0],q_d[1],q_d[2],q_d[3],thrust_body[0],"
               "thrust_body[1],thrust_body[2],reset_integral\n");
    for (long t = 1005000; t <= T_END_US; t += SP_US) {
        const double s = t * 1e-6, p = PITCH_AMP * sin(PITCH_W * s);
        fprintf(f, "%ld,0,%.17g,0,%.17g,0,%.17g,0,0,0,%.17g,False\n", t, p, cos(p / 2), sin(p / 2),
                -(0.5 + 0.1 * sin(THRUST_W * s)));
    }
    fclose(f);
}

static double motor(int q, double s)
{
    return 0.4 + 0.1 * q + 0.05 * sin(MOTOR_W * s);
}

/* Four motors in use: ulog2csv writes nan for the other eight. */
static void write_motors(void)
{
    FILE *f = create_topic("actuator_motors");
    fprintf(f, "timestamp,timestamp_sample,reversible_flags");
    for (int q = 0; q < 12; ++q) {
        fprintf(f, ",control[%d]", q);
    }
    fprintf(f, "\n");
    for (long t = 1003000; t <= 2993000; t += MOTOR_US) {
        fprintf(f, "%ld,%ld,0", t, t);
        for (int q = 0; q < 12; ++q) {
            fprintf(f, q < 4 ? ",%.17g" : ",nan", motor(q, t * 1e-6));
        }
        fprintf(f, "\n");
    }
    fclose(f);
}

static void write_log(void)
{
    write_gyro();
    write_attitude();
    write_torque(1001000, T_END_US, 1);
    write_setpoint();
    write_motors();
}

static sim_log_options_t px4_options(const char *path, double dt_s)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_PX4;
    o.dt_s = dt_s;
    snprintf(o.path, sizeof o.path, "%s", path);
    return o;
}

/* The first tick: the latest first time (the setpoint's); the last: the
 * earliest last time (the motors'). */
#define FIRST_TICK_US 1005000
#define LAST_TICK_US 2993000
#define TICKS ((LAST_TICK_US - FIRST_TICK_US) / 1000 + 1)

/* Linear interpolation between rows h apart of A sin(w t): within
 * h^2/8 A w^2. */
static double lerp_tol(double h_s, double amp, double w)
{
    return h_s * h_s / 8.0 * amp * w * w + ROUND_TOL;
}

/* A quaternion turning about one axis, interpolated component-wise and
 * normalised: the turn interpolated linearly (lerp_tol), plus the
 * normalised chord's departure from the uniform turn, below 0.3 (D/4)^3 for
 * a turn D between the rows (D <= A w h). */
static double quat_tol(double h_s, double amp, double w)
{
    return lerp_tol(h_s, amp, w) + 0.3 * pow(amp * w * h_s / 4.0, 3);
}

static void test_five_topics_resampled_to_1_khz(void)
{
    write_log();
    sim_log_options_t o = px4_options(base, 0.0); /* the gyro's period, the first file read */
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    ASSERT_NEAR(1e-15, 0.001, sim_log_dt_s(log));
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_COMMAND |
                               SIM_LOG_HAS_THROTTLE | SIM_LOG_HAS_MOTOR,
                           sim_log_has(log));
    sim_log_sample_t s;
    int k = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        const long t_us = FIRST_TICK_US + 1000L * k;
        const double t = t_us * 1e-6;
        ASSERT_NEAR(1e-12, k * 1e-3, s.t_s);
        /* the gyro's rows are on the ticks: their bits */
        const double g[3] = {GYRO_AMP * sin(GYRO_W * t), -GYRO_AMP * cos(GYRO_W * t),
                             0.5 * GYRO_AMP * sin(2.0 * GYRO_W * t)};
        TEST_ASSERT_EQUAL_MEMORY(g, s.gyro_rad_s, sizeof g);
        for (int i = 0; i < 3; ++i) {
            ASSERT_NEAR(lerp_tol(TORQUE_US * 1e-6, TORQUE_AMP, TORQUE_W), torque(i, t), s.command[i]);
        }
        ASSERT_NEAR(quat_tol(ATT_US * 1e-6, ROLL_AMP, ROLL_W), ROLL_AMP * sin(ROLL_W * t), s.angle_rad[0]);
        ASSERT_NEAR(ROUND_TOL, 0.0, s.angle_rad[1]);
        ASSERT_NEAR(ROUND_TOL, 0.0, s.angle_rad[2]);
        ASSERT_NEAR(ROUND_TOL, 1.0, hypot(s.quat[0], s.quat[1])); /* normalised */
        ASSERT_NEAR(quat_tol(SP_US * 1e-6, PITCH_AMP, PITCH_W), PITCH_AMP * sin(PITCH_W * t), s.ref_angle_rad[1]);
        ASSERT_NEAR(ROUND_TOL, 0.0, s.ref_angle_rad[0]);
        ASSERT_NEAR(lerp_tol(SP_US * 1e-6, 0.1, THRUST_W), 0.5 + 0.1 * sin(THRUST_W * t), s.throttle);
        TEST_ASSERT_EQUAL_INT(4, s.n_motors);
        for (int q = 0; q < 4; ++q) {
            ASSERT_NEAR(lerp_tol(MOTOR_US * 1e-6, 0.05, MOTOR_W), motor(q, t), s.motor[q]);
            TEST_ASSERT_TRUE(isnan(s.rotor_hz[q]));
        }
        TEST_ASSERT_TRUE(isnan(s.gyro_raw_rad_s[0]) && isnan(s.ref_rate_rad_s[0]) && isnan(s.motor[4]));
        ++k;
    }
    TEST_ASSERT_EQUAL_INT(TICKS, k);
    sim_log_stats_t st;
    sim_log_stats(log, &st);
    TEST_ASSERT_EQUAL_INT(5, st.n_files);
    TEST_ASSERT_TRUE(st.ticks == TICKS && st.gaps == 0);
    ASSERT_NEAR(1e-15, 0.001, st.row_period_s);
    TEST_ASSERT_TRUE(st.rows > 2000 && st.rows <= 2001 + 500 + 1000 + 200 + 200);
    long long done, total;
    sim_log_progress(log, &done, &total);
    TEST_ASSERT_TRUE(done > 0 && done <= total);
    sim_log_close(log);
}

/* The samples of two reads, bit for bit. */
static void assert_same_reads(const sim_log_options_t *a, const sim_log_options_t *b)
{
    sim_log_error_t err;
    sim_log_t *la = sim_log_open(a, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(la, err.message);
    sim_log_t *lb = sim_log_open(b, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(lb, err.message);
    sim_log_sample_t sa, sb;
    int ra, rb, n = 0;
    do {
        memset(&sa, 0, sizeof sa);
        memset(&sb, 0, sizeof sb);
        ra = sim_log_next(la, &sa, &err);
        rb = sim_log_next(lb, &sb, &err);
        TEST_ASSERT_EQUAL_INT(ra, rb);
        TEST_ASSERT_EQUAL_MEMORY(&sa, &sb, sizeof sa);
        n += ra == 1;
    } while (ra == 1);
    TEST_ASSERT_EQUAL_INT(TICKS, n);
    sim_log_close(la);
    sim_log_close(lb);
}

static void test_the_base_from_a_topic_file_or_a_ulg(void)
{
    write_log();
    char path[300];
    const sim_log_options_t from_base = px4_options(base, 0.001);
    snprintf(path, sizeof path, "%s_vehicle_attitude_setpoint_0.csv", base);
    sim_log_options_t from_file = px4_options(path, 0.001);
    assert_same_reads(&from_base, &from_file);
    snprintf(path, sizeof path, "%s.ulg", base);
    from_file = px4_options(path, 0.001);
    assert_same_reads(&from_base, &from_file);
}

static void test_caller_items_over_the_preset(void)
{
    write_log();
    sim_log_options_t o = px4_options(base, 0.001);
    o.map[0] = "command[2]=vehicle_torque_setpoint.xyz[0]*-1";
    o.map[1] = "motor[5]=?actuator_motors.control[1]+?actuator_motors.control[2]";
    o.n_map = 2;
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    TEST_ASSERT_EQUAL_INT(1, sim_log_next(log, &s, &err));
    TEST_ASSERT_EQUAL_INT(6, s.n_motors);
    TEST_ASSERT_TRUE(isnan(s.motor[4]));
    ASSERT_NEAR(ROUND_TOL, s.motor[1] + s.motor[2], s.motor[5]);
    ASSERT_NEAR(0.0, -s.command[0], s.command[2]);
    sim_log_close(log);
}

static void expect_open_error(const sim_log_options_t *o, const char *topic, int line, int column, const char *needle)
{
    sim_log_error_t err;
    char want_path[300], shown[600];
    TEST_ASSERT_NULL(sim_log_open(o, &err));
    sim_log_error_format(&err, shown, sizeof shown);
    snprintf(want_path, sizeof want_path, "%s_%s_0.csv", base, topic);
    TEST_ASSERT_EQUAL_STRING_MESSAGE(want_path, err.path, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(line, err.line, shown);
    TEST_ASSERT_EQUAL_INT_MESSAGE(column, err.column, shown);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, needle), shown);
}

static void test_a_required_topic_file_missing(void)
{
    write_gyro();
    write_torque(1001000, T_END_US, 1);
    const sim_log_options_t o = px4_options(base, 0.001);
    expect_open_error(&o, "vehicle_attitude", 0, 0,
                      "cannot open: No such file or directory (topic vehicle_attitude, needed for quat[0])");
    /* an optional item made required by the caller */
    write_attitude();
    sim_log_options_t rates = o;
    rates.map[0] = "ref_rate[1]=vehicle_rates_setpoint.pitch";
    rates.n_map = 1;
    expect_open_error(&rates, "vehicle_rates_setpoint", 0, 0, "needed for ref_rate[1]");
    /* without the optional topics, the required ones are read */
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_stats_t st;
    sim_log_stats(log, &st);
    TEST_ASSERT_EQUAL_INT(3, st.n_files);
    TEST_ASSERT_EQUAL_UINT(SIM_LOG_HAS_GYRO | SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_COMMAND, st.has);
    sim_log_close(log);
}

static void test_a_required_column_missing(void)
{
    write_gyro();
    write_attitude();
    write_torque(1001000, T_END_US, 0);
    const sim_log_options_t o = px4_options(base, 0.001);
    expect_open_error(&o, "vehicle_torque_setpoint", 1, 41, "no column 'xyz[2]' (needed for command[2])");
}

static void test_files_that_do_not_overlap(void)
{
    write_gyro();
    write_attitude();
    write_torque(100000, 900000, 1); /* ends before the gyro starts */
    const sim_log_options_t o = px4_options(base, 0.001);
    expect_open_error(&o, "vehicle_torque_setpoint", 0, 0, "no overlap in time");
}

static void test_bad_px4_items(void)
{
    write_log();
    sim_log_options_t o = px4_options(base, 0.001);
    sim_log_error_t err;
    const char *const bad[] = {"time=vehicle_attitude.timestamp", "gyro[0]=xyz[0]",
                               "gyro[0]=vehicle_attitude.q[0]+vehicle_angular_velocity.xyz[0]"};
    for (int i = 0; i < 3; ++i) {
        o.map[0] = bad[i];
        o.n_map = 1;
        TEST_ASSERT_NULL(sim_log_open(&o, &err));
        TEST_ASSERT_EQUAL_INT(0, err.line);
        TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, bad[i]), err.message);
    }
    /* a stream is not a PX4 log */
    FILE *f = fopen(files[0], "r");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_NULL(sim_log_open_stream(f, "x.csv", &o, &err));
    fclose(f);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_five_topics_resampled_to_1_khz);
    RUN_TEST(test_the_base_from_a_topic_file_or_a_ulg);
    RUN_TEST(test_caller_items_over_the_preset);
    RUN_TEST(test_a_required_topic_file_missing);
    RUN_TEST(test_a_required_column_missing);
    RUN_TEST(test_files_that_do_not_overlap);
    RUN_TEST(test_bad_px4_items);
    return UNITY_END();
}
