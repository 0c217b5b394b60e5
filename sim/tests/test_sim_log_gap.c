/* SPDX-License-Identifier: BSD-3-Clause */
/* Gaps in a log's time (log/log.h, SIM_LOG_GAP_SKIP_FACTOR): a long one is
 * skipped, not interpolated, so the ticks stay bounded by the rows whatever
 * the gap's length (3 h, 1e9 s); the tick after it is marked, and the
 * identification, the replay and their spectra restart there; short gaps
 * are interpolated as before; the warning's text. */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkstemp */
#include "unity.h"
#include "log/log.h"
#include "log/log_identify.h"
#include "log/log_noise.h"
#include "log/log_outlier.h"
#include "log/log_reference.h"
#include "log/response.h"
#include "log/replay.h"
#include "scenario/scenario.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
#define ROW_S 0.001      /* the logs' row period, and the control period */
#define HALF_ROWS 3000   /* rows on each side of the gap: 3 s, past the identification's 2000 samples */
#define GAP_3H_S 10800.0 /* the jump added to the times after the gap */
#define GAP_1E9_S 1e9
/* How far a loop reads before it gives up: a reader that interpolated the
 * 3 h gap would give 10.8 million ticks, the 1e9 s one 1e12. */
#define TICKS_CAP (4 * 2 * HALF_ROWS)
/* The times are written with 6 decimals (a microsecond): a sum of a time
 * near 1e9 s and a row's offset is off by less than half of one. */
#define TIME_TOL_S 1e-6
/* The command's roll over the time, written with 9 digits and divided back:
 * a few parts in 1e9. */
#define ROUND_TOL_LINEAR 1e-8
/* Each axis's plant, rate per unit of command (rad/s^2), as a chirp flight
 * would show it: enough for the fit to tell b0 on both sides of a gap. */
static const double B0[3] = {200.0, 150.0, 80.0};

static char path[64];       /* a test's temporary file, removed after it */
static char noise_path[80]; /* the identification's noise file, the same */

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
    noise_path[0] = '\0';
}
void tearDown(void)
{
    if (path[0] != '\0') {
        remove(path);
    }
    if (noise_path[0] != '\0') {
        remove(noise_path);
    }
}

/* A generic log of 2 * HALF_ROWS rows at ROW_S whose times after row
 * HALF_ROWS - 1 are shifted by gap_s (0: none): a chirp command on each axis
 * (written times pre_gap_command_scale before the gap) and the rate it makes
 * on a plant of gain B0 (integrated per row), the
 * rate setpoint the rate itself (a flight that tracked its setpoint: no
 * error for a controller to answer). Returned on the heap. */
static char *gap_log_text(double gap_s, double pre_gap_command_scale)
{
    const size_t cap = (size_t)(2 * HALF_ROWS) * 200 + 256;
    char *text = malloc(cap);
    TEST_ASSERT_NOT_NULL(text);
    size_t n = (size_t)snprintf(text, cap,
                                "time,gyro[0],gyro[1],gyro[2],command[0],command[1],command[2],"
                                "ref_rate[0],ref_rate[1],ref_rate[2]\n");
    double w[3] = {0.0, 0.0, 0.0}, u_prev[3] = {0.0, 0.0, 0.0};
    const double span_s = 2 * HALF_ROWS * ROW_S;
    for (int k = 0; k < 2 * HALF_ROWS; ++k) {
        const double t = k * ROW_S;
        /* 1 to 40 Hz over the log: phase 2 pi (f0 t + (f1 - f0) t^2 / (2 span)) */
        const double phase = 2.0 * PI * (1.0 * t + 39.0 * t * t / (2.0 * span_s));
        double u[3];
        for (int i = 0; i < 3; ++i) {
            u[i] = 0.1 * sin(phase + i);
            w[i] += ROW_S * B0[i] * u_prev[i];
            u_prev[i] = u[i];
        }
        const double scale = k < HALF_ROWS ? pre_gap_command_scale : 1.0;
        n += (size_t)snprintf(text + n, cap - n, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                              t + (k >= HALF_ROWS ? gap_s : 0.0), w[0], w[1], w[2], scale * u[0], scale * u[1],
                              scale * u[2], w[0], w[1], w[2]);
    }
    return text;
}

static sim_log_options_t generic(double dt_s)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_GENERIC;
    o.dt_s = dt_s;
    return o;
}

/* Reads text to its end (at most TICKS_CAP ticks): the ticks, the index of
 * each one marked after_gap into marked[] (at most 4), their count. */
static long long read_ticks(const char *text, const sim_log_options_t *o, sim_log_stats_t *st, long long marked[4],
                            int *n_marked, double *marked_t_s)
{
    FILE *f = fmemopen((void *)(uintptr_t)text, strlen(text), "r");
    TEST_ASSERT_NOT_NULL(f);
    sim_log_error_t err;
    sim_log_t *log = sim_log_open_stream(f, "gap.csv", o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    long long ticks = 0;
    int rc;
    *n_marked = 0;
    while (ticks < TICKS_CAP && (rc = sim_log_next(log, &s, &err)) == 1) {
        if (s.after_gap && *n_marked < 4) {
            marked[*n_marked] = ticks;
            marked_t_s[(*n_marked)++] = s.t_s;
        }
        ++ticks;
    }
    TEST_ASSERT_TRUE_MESSAGE(ticks < TICKS_CAP, "the ticks are not bounded by the rows");
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, err.message);
    sim_log_stats(log, st);
    sim_log_close(log);
    fclose(f);
    return ticks;
}

/* A long gap skipped: one tick per row, the first after the gap marked at
 * the row that ends it, the gap counted with its length. */
static void expect_skipped(double gap_s)
{
    char *text = gap_log_text(gap_s, 1.0);
    const sim_log_options_t o = generic(0.0);
    sim_log_stats_t st;
    long long marked[4];
    double marked_t_s[4];
    int n_marked;
    const long long ticks = read_ticks(text, &o, &st, marked, &n_marked, marked_t_s);
    ASSERT_EQ_LL(2 * HALF_ROWS, ticks);
    ASSERT_EQ_LL(2 * HALF_ROWS, st.ticks);
    ASSERT_EQ_LL(1, st.skipped_gaps);
    ASSERT_EQ_LL(1, st.gaps);
    ASSERT_EQ_LL(1, st.skipped_file_gaps);
    /* from the last row before the gap to the first after it */
    ASSERT_NEAR(TIME_TOL_S, gap_s + ROW_S, st.skipped_s);
    TEST_ASSERT_EQUAL_INT(1, n_marked);
    ASSERT_EQ_LL(HALF_ROWS, marked[0]);
    ASSERT_NEAR(TIME_TOL_S, HALF_ROWS * ROW_S + gap_s, marked_t_s[0]);
    free(text);
}

static void test_a_3h_gap_is_skipped_ticks_bounded_by_rows(void)
{
    expect_skipped(GAP_3H_S);
}

static void test_a_1e9_s_gap_is_skipped_ticks_bounded_by_rows(void)
{
    expect_skipped(GAP_1E9_S);
}

static void test_a_finer_control_period_keeps_the_bound(void)
{
    /* at a quarter of the row period: 4 ticks per row, never the gap's 4.3e7 */
    char *text = gap_log_text(GAP_3H_S, 1.0);
    const sim_log_options_t o = generic(ROW_S / 4.0);
    sim_log_stats_t st;
    long long marked[4];
    double marked_t_s[4];
    int n_marked;
    const long long ticks = read_ticks(text, &o, &st, marked, &n_marked, marked_t_s);
    /* each side: its rows' span at 4 ticks per row period, plus the first tick */
    ASSERT_EQ_LL(2 * (4 * (HALF_ROWS - 1) + 1), ticks);
    TEST_ASSERT_TRUE(ticks <= (long long)(2 * HALF_ROWS * (SIM_LOG_GAP_SKIP_FACTOR * 4.0 + 1.0)));
    ASSERT_EQ_LL(1, st.skipped_gaps);
    TEST_ASSERT_EQUAL_INT(1, n_marked);
    ASSERT_EQ_LL(4 * (HALF_ROWS - 1) + 1, marked[0]);
    free(text);
}

/* Rows ROW_S apart, then one period of `periods` row periods, then rows again. */
static char *one_gap_text(double periods)
{
    static char text[4096];
    size_t n = (size_t)snprintf(text, sizeof text, "time,gyro[0]\n");
    for (int k = 0; k < 20; ++k) {
        const double t = k < 10 ? k * ROW_S : (9 + periods + (k - 10)) * ROW_S;
        n += (size_t)snprintf(text + n, sizeof text - n, "%.6f,%.6f\n", t, t);
    }
    return text;
}

static void test_gaps_up_to_the_bound_are_interpolated_as_before(void)
{
    /* a gap of exactly SIM_LOG_GAP_SKIP_FACTOR periods: interpolated, every
     * tick in it on the line between its rows (gyro = time here) */
    const char *text = one_gap_text(SIM_LOG_GAP_SKIP_FACTOR);
    const sim_log_options_t o = generic(ROW_S);
    FILE *f = fmemopen((void *)(uintptr_t)text, strlen(text), "r");
    sim_log_error_t err;
    sim_log_t *log = sim_log_open_stream(f, "short.csv", &o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    long long k = 0;
    while (sim_log_next(log, &s, &err) == 1) {
        TEST_ASSERT_EQUAL_INT(0, s.after_gap);
        ASSERT_NEAR(1e-12, k * ROW_S, s.t_s);       /* the grid, unbroken */
        ASSERT_NEAR(1e-12, s.t_s, s.gyro_rad_s[0]); /* linear across the gap */
        ++k;
    }
    sim_log_stats_t st;
    sim_log_stats(log, &st);
    ASSERT_EQ_LL(9 + (long long)SIM_LOG_GAP_SKIP_FACTOR + 10, k);
    ASSERT_EQ_LL(1, st.gaps);
    ASSERT_EQ_LL(0, st.skipped_gaps);
    ASSERT_NEAR(0.0, 0.0, st.skipped_s);
    char warning[256];
    TEST_ASSERT_EQUAL_INT(0, sim_log_gap_warning(&st, warning, sizeof warning));
    TEST_ASSERT_EQUAL_STRING("", warning);
    sim_log_close(log);
    fclose(f);
}

static void test_a_gap_just_past_the_bound_is_skipped(void)
{
    const char *text = one_gap_text(SIM_LOG_GAP_SKIP_FACTOR + 1.0);
    const sim_log_options_t o = generic(ROW_S);
    sim_log_stats_t st;
    long long marked[4];
    double marked_t_s[4];
    int n_marked;
    ASSERT_EQ_LL(20, read_ticks(text, &o, &st, marked, &n_marked, marked_t_s));
    ASSERT_EQ_LL(1, st.skipped_gaps);
    TEST_ASSERT_EQUAL_INT(1, n_marked);
    ASSERT_EQ_LL(10, marked[0]);
}

static void test_a_window_that_starts_in_a_gap_is_not_marked(void)
{
    /* the first tick given has nothing before it to restart */
    const char *text = one_gap_text(1000.0);
    sim_log_options_t o = generic(ROW_S);
    o.t_from_s = 0.5; /* inside the gap (0.009 to 1.009 s) */
    sim_log_stats_t st;
    long long marked[4];
    double marked_t_s[4];
    int n_marked;
    ASSERT_EQ_LL(10, read_ticks(text, &o, &st, marked, &n_marked, marked_t_s));
    TEST_ASSERT_EQUAL_INT(0, n_marked);
    ASSERT_EQ_LL(1, st.skipped_gaps);
}

static void test_the_warning_says_count_bound_and_length(void)
{
    sim_log_stats_t st;
    memset(&st, 0, sizeof st);
    st.gaps = 3;
    st.skipped_gaps = 2;
    st.skipped_s = 10800.5;
    char warning[256];
    TEST_ASSERT_EQUAL_INT(1, sim_log_gap_warning(&st, warning, sizeof warning));
    TEST_ASSERT_EQUAL_STRING("2 gap(s) in the log's time longer than 100 row periods skipped, not interpolated "
                             "(10800.5 s in all): what spans one restarts after it",
                             warning);
}

/* The text into the test's temporary file. */
static void write_file(const char *text)
{
    snprintf(path, sizeof path, "/tmp/test_sim_log_gap_XXXXXX");
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    FILE *f = fdopen(fd, "w");
    TEST_ASSERT_NOT_NULL(f);
    TEST_ASSERT_EQUAL_INT(1, fwrite(text, strlen(text), 1, f) == 1);
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

/* The identification of text, its noise series (the first NOISE_S) into noise_path. */
#define NOISE_S 60.0
static void identify_text(const char *text, sim_airframe_t *a, sim_log_stats_t *st)
{
    write_file(text);
    snprintf(noise_path, sizeof noise_path, "%s.noise", path);
    sim_log_identify_options_t io;
    memset(&io, 0, sizeof io);
    io.log = generic(0.0);
    snprintf(io.log.path, sizeof io.log.path, "%s", path);
    io.delay_max_ticks = -1;
    io.noise_series = noise_path;
    io.noise_series_s = NOISE_S;
    char err[512];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_identify(&io, a, st, err, sizeof err), err);
    remove(path);
    path[0] = '\0';
}

/* A series file's rows (the noise file, the setpoints), each time a row
 * period after the one before (a series a scenario can read: no gap in
 * it); removes the file. */
static long long series_rows_a_tick_apart(void)
{
    FILE *f = fopen(noise_path, "r");
    TEST_ASSERT_NOT_NULL(f);
    char line[256];
    long long rows = 0;
    double prev = NAN, t;
    while (fgets(line, sizeof line, f) != NULL) {
        if (line[0] == '#' || line[0] == 't') {
            continue; /* the comment and the header */
        }
        TEST_ASSERT_EQUAL_INT(1, sscanf(line, "%lf", &t));
        if (rows > 0) {
            /* written with 9 digits: times below 10 s to 1e-8 s */
            ASSERT_NEAR(1e-8, ROW_S, t - prev);
        }
        prev = t;
        ++rows;
    }
    fclose(f);
    remove(noise_path);
    return rows;
}

static void test_identification_restarts_at_a_gap(void)
{
    static sim_airframe_t whole, gapped;
    sim_log_stats_t st_whole, st_gapped;
    char *text = gap_log_text(0.0, 1.0);
    identify_text(text, &whole, &st_whole);
    remove(noise_path);
    free(text);
    text = gap_log_text(GAP_3H_S, 1.0);
    identify_text(text, &gapped, &st_gapped);
    free(text);
    ASSERT_EQ_LL(2 * HALF_ROWS, series_rows_a_tick_apart());
    ASSERT_EQ_LL(2 * HALF_ROWS, st_gapped.ticks);
    ASSERT_EQ_LL(1, st_gapped.skipped_gaps);
    for (int i = 0; i < 3; ++i) {
        /* the filters restart after the gap and settle again before a
         * sample is fitted: the fit's settling (ident.c: 6 time constants of
         * the prefilter's corner) is lost once more, and nothing else */
        const long long settling = (long long)ceil(6.0 / (gapped.prefilter_hz * ROW_S));
        ASSERT_EQ_LL(whole.axis[i].samples - settling, gapped.axis[i].samples);
        /* the same plant on both sides: the same gain (the fit's sampling
         * error over 6 s of a noiseless chirp, far under its 10 % interval) */
        ASSERT_NEAR(0.02 * B0[i], whole.axis[i].b0, gapped.axis[i].b0);
    }
}

/* Welch's segments of n samples every n / 2 over one side of the gap. */
static long segments_per_side(int n)
{
    return (HALF_ROWS - n) / (n / 2) + 1;
}

#define REPLAY_CONTROLLERS "LADRC LP-MLADRC CASCADED PID INDI"

/* The replay of a log with a 1e9 s gap (commands before it times
 * pre_gap_command_scale): the replayed commands after the gap into
 * after[tick][controller][axis]; the replay left in *r. */
static void replay_gap_log(double pre_gap_command_scale, sim_replay_t *r, double (*after)[SIM_MAX_CONTROLLERS][3])
{
    static sim_scenario_t sc;
    static sim_replay_tick_t out;
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0,
                                  sim_scenario_parse(&sc,
                                                     "[run]\nduration_s = 1\ncontrol_dt_s = 0.001\n"
                                                     "controllers = " REPLAY_CONTROLLERS "\n",
                                                     "gap.ini", &perr),
                                  perr.message);
    char err[512];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_replay_init(r, &sc, sc.controllers, sc.n_controllers, err, sizeof err), err);
    char *text = gap_log_text(GAP_1E9_S, pre_gap_command_scale);
    FILE *f = fmemopen(text, strlen(text), "r");
    const sim_log_options_t o = generic(ROW_S);
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open_stream(f, "gap.csv", &o, &lerr);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, lerr.message);
    const unsigned has = sim_log_has(log);
    sim_log_sample_t s;
    long long ticks = 0;
    while (ticks < TICKS_CAP && sim_log_next(log, &s, &lerr) == 1) {
        sim_replay_step(r, &s, has, &out);
        if (ticks >= HALF_ROWS) {
            memcpy(after[ticks - HALF_ROWS], out.command, sizeof after[0]);
        }
        ++ticks;
    }
    sim_log_close(log);
    fclose(f);
    free(text);
    ASSERT_EQ_LL(2 * HALF_ROWS, ticks);
}

static void test_replay_restarts_at_a_gap(void)
{
    static sim_replay_t r, r_other;
    static double after[HALF_ROWS][SIM_MAX_CONTROLLERS][3], after_other[HALF_ROWS][SIM_MAX_CONTROLLERS][3];
    replay_gap_log(1.0, &r, after);
    ASSERT_EQ_LL(2 * HALF_ROWS, r.ticks);
    ASSERT_EQ_LL(1, r.gap_restarts);
    /* what came before the gap is forgotten: the same log after it, with
     * other commands before it, replays to the same commands, bit for bit */
    replay_gap_log(0.5, &r_other, after_other);
    for (int k = 0; k < HALF_ROWS; ++k) {
        for (int c = 0; c < r.n; ++c) {
            for (int i = 0; i < 3; ++i) {
                ASSERT_NEAR(0.0, after[k][c][i], after_other[k][c][i]);
            }
        }
    }
    /* no spectrum segment spans the gap: each side's own half-overlapping
     * segments of SIM_SPECTRUM_N ticks, not those of the whole */
    const long per_side = segments_per_side(SIM_SPECTRUM_N);
    TEST_ASSERT_EQUAL_INT(2 * per_side, sim_spectrum_segments(&r.gyro[0]));
    TEST_ASSERT_EQUAL_INT(2 * per_side, sim_spectrum_segments(&r.log_axis[0].spectrum));
    TEST_ASSERT_EQUAL_INT(2 * per_side, sim_spectrum_segments(&r.axis[0][0].spectrum));
}

static void test_views_noise_and_series_restart_at_a_gap(void)
{
    char *text = gap_log_text(GAP_1E9_S, 1.0);
    write_file(text);
    free(text);
    sim_log_options_t o = generic(ROW_S);
    snprintf(o.path, sizeof o.path, "%s", path);
    char err[512];
    /* the noise pass (ladrc_filter, the replay's noise stage): spectra per side */
    static sim_log_noise_t noise;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_noise_measure(&o, 2.0 * PI * 10.0, &noise, err, sizeof err), err);
    TEST_ASSERT_EQUAL_INT(2 * segments_per_side(SIM_SPECTRUM_N), sim_spectrum_segments(&noise.command[0]));
    TEST_ASSERT_EQUAL_INT(2 * segments_per_side(SIM_SPECTRUM_N), sim_spectrum_segments(&noise.gyro[2]));
    /* the field's views: the frequency response's segments (1024 ticks at
     * 1 kHz, the setpoint past the 20 deg/s gate throughout) per side */
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&o, &lerr);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, lerr.message);
    sim_response_t *r = sim_response_new(ROW_S);
    TEST_ASSERT_NOT_NULL(r);
    sim_log_sample_t s;
    long long ticks = 0;
    while (ticks < TICKS_CAP && sim_log_next(log, &s, &lerr) == 1) {
        sim_response_push(r, &s, sim_log_has(log));
        ++ticks;
    }
    sim_log_close(log);
    ASSERT_EQ_LL(2 * HALF_ROWS, ticks);
    TEST_ASSERT_EQUAL_INT(2 * segments_per_side(1024), sim_response_freq_segments(r, 0));
    sim_response_free(r);
    /* the setpoints as a series: a row per tick, a tick apart across the gap */
    snprintf(noise_path, sizeof noise_path, "%s.series", path);
    double written_s;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_reference_write(&o, 0.0, noise_path, &written_s, err, sizeof err), err);
    ASSERT_EQ_LL(2 * HALF_ROWS, series_rows_a_tick_apart());
    ASSERT_NEAR(TIME_TOL_S, (2 * HALF_ROWS - 1) * ROW_S, written_s);
}

/* A PX4 log as ulog2csv writes it, three topics (the required ones) from
 * 1 s to 3 s: the gyro at 1 kHz, the attitude at 250 Hz, the torque
 * setpoint at 500 Hz (its roll the time in s: linear, so interpolation
 * gives it exactly). Rows from jump_from_us on are shifted by jump_us; the
 * torque's rows in [pause_from_us, pause_to_us) are left out. */
#define PX4_FIRST_US 1000000L
#define PX4_LAST_US 3000000L
static char px4_dir[64];
static char px4_files[3][160];

static void write_topic(int i, const char *topic, const char *header, long period_us, long jump_from_us, double jump_us,
                        long pause_from_us, long pause_to_us)
{
    snprintf(px4_files[i], sizeof px4_files[i], "%s/log_%s_0.csv", px4_dir, topic);
    FILE *f = fopen(px4_files[i], "w");
    TEST_ASSERT_NOT_NULL(f);
    fprintf(f, "%s\n", header);
    for (long t = PX4_FIRST_US; t <= PX4_LAST_US; t += period_us) {
        if (t >= pause_from_us && t < pause_to_us) {
            continue;
        }
        const double stamp = (double)t + (t >= jump_from_us ? jump_us : 0.0);
        if (i == 1) {
            fprintf(f, "%.0f,1,0,0,0\n", stamp);
        } else {
            fprintf(f, "%.0f,%.0f,%.9g,0.1,0.2\n", stamp, stamp, t * 1e-6);
        }
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
}

static void write_px4(double jump_us, long pause_from_us, long pause_to_us)
{
    snprintf(px4_dir, sizeof px4_dir, "/tmp/test_sim_log_gap_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(px4_dir));
    const long jump_from_us = 2000000L;
    write_topic(0, "vehicle_angular_velocity", "timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]", 1000, jump_from_us,
                jump_us, 0, 0);
    write_topic(1, "vehicle_attitude", "timestamp,q[0],q[1],q[2],q[3]", 4000, jump_from_us, jump_us, 0, 0);
    write_topic(2, "vehicle_torque_setpoint", "timestamp,timestamp_sample,xyz[0],xyz[1],xyz[2]", 2000, jump_from_us,
                jump_us, pause_from_us, pause_to_us);
}

static void remove_px4(void)
{
    for (int i = 0; i < 3; ++i) {
        remove(px4_files[i]);
    }
    rmdir(px4_dir);
}

/* The PX4 log read at 1 kHz: its ticks, stats, the marked ticks; the
 * command's roll against the time (its offset from linear, largest). */
static long long read_px4(sim_log_stats_t *st, int *n_marked, long long *marked, double *off_linear)
{
    sim_log_options_t o;
    sim_log_options_default(&o);
    o.format = SIM_LOG_PX4;
    o.dt_s = 0.001;
    snprintf(o.path, sizeof o.path, "%s/log", px4_dir);
    sim_log_error_t err;
    sim_log_t *log = sim_log_open(&o, &err);
    TEST_ASSERT_NOT_NULL_MESSAGE(log, err.message);
    sim_log_sample_t s;
    long long ticks = 0;
    double first_ratio = NAN;
    *n_marked = 0;
    *off_linear = 0.0;
    while (ticks < TICKS_CAP && sim_log_next(log, &s, &err) == 1) {
        if (s.after_gap && *n_marked < 4) {
            marked[(*n_marked)++] = ticks;
        }
        if (!*n_marked) { /* before any gap: the time from the log's start, 1 s */
            const double ratio = s.command[0] / (s.t_s + 1.0);
            first_ratio = ticks == 0 ? ratio : first_ratio;
            *off_linear = fmax(*off_linear, fabs(ratio - first_ratio));
        }
        ++ticks;
    }
    TEST_ASSERT_TRUE_MESSAGE(ticks < TICKS_CAP, "the ticks are not bounded by the rows");
    sim_log_stats(log, st);
    sim_log_close(log);
    return ticks;
}

static void test_px4_a_jump_in_every_topic_is_skipped(void)
{
    write_px4(1e15, 0, 0); /* 1e9 s: a clock glitch in every topic */
    sim_log_stats_t st;
    int n_marked;
    long long marked[4];
    double off_linear;
    const long long ticks = read_px4(&st, &n_marked, marked, &off_linear);
    remove_px4();
    /* 1 s to 1.999 s, then the rows after the jump, 2 s to 3 s */
    ASSERT_EQ_LL(1000 + 1001, ticks);
    ASSERT_EQ_LL(1, st.skipped_gaps);
    ASSERT_EQ_LL(3, st.gaps); /* one in each topic's file, all three skipped */
    ASSERT_EQ_LL(3, st.skipped_file_gaps);
    /* from the latest row before it (the gyro's, 1.999 s) to the earliest after */
    ASSERT_NEAR(TIME_TOL_S, 1e9 + 0.001, st.skipped_s);
    TEST_ASSERT_EQUAL_INT(1, n_marked);
    ASSERT_EQ_LL(1000, marked[0]);
}

static void test_px4_a_topic_that_pauses_is_interpolated(void)
{
    /* the torque setpoint silent for 0.5 s (250 of its periods) while the
     * gyro and the attitude go on: interpolated over as before, nothing skipped */
    write_px4(0.0, 1500000L, 2000000L);
    sim_log_stats_t st;
    int n_marked;
    long long marked[4];
    double off_linear;
    const long long ticks = read_px4(&st, &n_marked, marked, &off_linear);
    remove_px4();
    ASSERT_EQ_LL(2001, ticks);
    ASSERT_EQ_LL(1, st.gaps);
    ASSERT_EQ_LL(0, st.skipped_gaps);
    ASSERT_EQ_LL(0, st.skipped_file_gaps);
    TEST_ASSERT_EQUAL_INT(0, n_marked);
    ASSERT_NEAR(ROUND_TOL_LINEAR, 0.0, off_linear); /* linear across the pause */
}

/* The gyro's roll through the outlier filter: a smooth signal with a
 * level of `spike` on sample SPIKE_AT (the last before the gap when
 * with_gap): the samples replaced. */
#define DESPIKE_SAMPLES 2000
#define SPIKE_AT 999
static long long despiked(double spike, int with_gap)
{
    sim_log_despike_t *d = sim_log_despike_new(SIM_LOG_HAS_GYRO);
    TEST_ASSERT_NOT_NULL(d);
    sim_log_sample_t in, out;
    memset(&in, 0, sizeof in);
    for (int k = 0; k < DESPIKE_SAMPLES; ++k) {
        in.t_s = k * ROW_S;
        /* motion and a deterministic ripple: increments of every size */
        in.gyro_rad_s[0] = sin(0.01 * k) + 0.01 * sin(2.3 * k * k);
        in.gyro_rad_s[0] += k == SPIKE_AT ? spike : 0.0;
        in.after_gap = with_gap && k == SPIKE_AT + 1;
        TEST_ASSERT_EQUAL_INT(0, sim_log_despike_push(d, &in));
        while (sim_log_despike_pop(d, &out)) {
        }
    }
    sim_log_despike_finish(d);
    while (sim_log_despike_pop(d, &out)) {
    }
    sim_log_outliers_t o;
    sim_log_despike_outliers(d, &o);
    sim_log_despike_free(d);
    return o.rejected[0];
}

static void test_no_outlier_is_judged_across_a_gap(void)
{
    /* the filter's own: 100 rad/s on one sample is a spike */
    ASSERT_EQ_LL(1, despiked(100.0, 0));
    /* the same sample the last before a skipped gap: what comes after the
     * gap does not tell it a spike (nor the first after it: not judged) */
    ASSERT_EQ_LL(0, despiked(100.0, 1));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_3h_gap_is_skipped_ticks_bounded_by_rows);
    RUN_TEST(test_a_1e9_s_gap_is_skipped_ticks_bounded_by_rows);
    RUN_TEST(test_a_finer_control_period_keeps_the_bound);
    RUN_TEST(test_gaps_up_to_the_bound_are_interpolated_as_before);
    RUN_TEST(test_a_gap_just_past_the_bound_is_skipped);
    RUN_TEST(test_a_window_that_starts_in_a_gap_is_not_marked);
    RUN_TEST(test_px4_a_jump_in_every_topic_is_skipped);
    RUN_TEST(test_px4_a_topic_that_pauses_is_interpolated);
    RUN_TEST(test_the_warning_says_count_bound_and_length);
    RUN_TEST(test_identification_restarts_at_a_gap);
    RUN_TEST(test_replay_restarts_at_a_gap);
    RUN_TEST(test_views_noise_and_series_restart_at_a_gap);
    RUN_TEST(test_no_outlier_is_judged_across_a_gap);
    return UNITY_END();
}
