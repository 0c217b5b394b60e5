/* SPDX-License-Identifier: BSD-3-Clause */
/* A damaged frame's spike among thousands of samples (log/log_outlier.h):
 * found, repaired and counted as the log streams, while noise, steps, ramps
 * and a stick's held steps pass untouched; and the identification of a
 * generated closed-loop log (log/log_identify.h) with one spike of each kind,
 * or 1 % of its cells corrupt, gives what the unmodified log gives, and so
 * does its noise pass (log/log_noise.h). */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include "unity.h"
#include "ident_loop.h"
#include "log/log_identify.h"
#include "log/log_noise.h"
#include "log/log_outlier.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define DEG (3.14159265358979323846 / 180.0)
#define DT_S 0.001
#define N_STREAM 20000 /* samples of the filter's own tests: 78 blocks */

/* The identification of the unmodified log against a damaged one: b0
 * inside the unmodified log's own 95 % interval (the damage moves it by less
 * than what the log cannot tell), R^2 above 0.9 (the unmodified fit's is
 * 0.99; one spike took it to 0.03 before), the gyro's noise floor within a
 * factor 2 (one spike took it 100 times up). */
#define R2_MIN 0.9
#define FLOOR_RATIO_MAX 2.0
/* A repaired sample is its neighbours' mean, to the rounding of doubles. */
#define REPAIR_TOL 1e-12

static char path[64];

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

static sim_log_sample_t *stream;     /* N_STREAM samples in */
static sim_log_sample_t *stream_out; /* and out */

/* Quiet samples: every channel NaN but those the test sets. */
static void stream_clear(void)
{
    for (int k = 0; k < N_STREAM; ++k) {
        sim_log_sample_t *s = &stream[k];
        memset(s, 0, sizeof *s);
        s->t_s = k * DT_S;
        for (int i = 0; i < 3; ++i) {
            s->gyro_rad_s[i] = s->gyro_raw_rad_s[i] = s->command[i] = s->ref_rate_rad_s[i] = 0.0;
        }
    }
}

/* Gaussian noise of sigma on a slow swing, on every channel. */
static void stream_noise(double sigma, uint64_t seed)
{
    sim_rng_t r;
    sim_rng_seed(&r, seed);
    for (int k = 0; k < N_STREAM; ++k) {
        sim_log_sample_t *s = &stream[k];
        const double swing = sin(2.0 * LOOP_PI * 0.5 * k * DT_S);
        for (int i = 0; i < 3; ++i) {
            s->gyro_rad_s[i] = swing + sigma * sim_rng_gauss(&r);
            s->gyro_raw_rad_s[i] = swing + sigma * sim_rng_gauss(&r);
            s->command[i] = 0.1 * swing + 0.1 * sigma * sim_rng_gauss(&r);
            s->ref_rate_rad_s[i] = swing + sigma * sim_rng_gauss(&r);
        }
    }
}

/* The stream through the filter (pushed one by one, popped as ready); its count. */
static void stream_filter(unsigned has, sim_log_outliers_t *o)
{
    sim_log_despike_t *d = sim_log_despike_new(has);
    TEST_ASSERT_NOT_NULL(d);
    int n_out = 0;
    for (int k = 0; k < N_STREAM; ++k) {
        TEST_ASSERT_EQUAL_INT(0, sim_log_despike_push(d, &stream[k]));
        while (n_out < N_STREAM && sim_log_despike_pop(d, &stream_out[n_out])) {
            n_out++;
        }
    }
    sim_log_despike_finish(d);
    while (n_out < N_STREAM && sim_log_despike_pop(d, &stream_out[n_out])) {
        n_out++;
    }
    sim_log_sample_t spare;
    TEST_ASSERT_EQUAL_INT(0, sim_log_despike_pop(d, &spare)); /* none more than pushed */
    sim_log_despike_outliers(d, o);
    sim_log_despike_free(d);
    TEST_ASSERT_EQUAL_INT(N_STREAM, n_out); /* every sample out */
    TEST_ASSERT_EQUAL_INT(N_STREAM, o->samples);
    for (int k = 0; k < N_STREAM; ++k) {
        TEST_ASSERT_TRUE(stream[k].t_s == stream_out[k].t_s); /* in order */
    }
}

/* The judged channels of the stream in and out equal, bit for bit, at every sample. */
static void assert_stream_unchanged(void)
{
    for (int k = 0; k < N_STREAM; ++k) {
        const sim_log_sample_t *a = &stream[k], *b = &stream_out[k];
        for (int i = 0; i < 3; ++i) {
            const double in[4] = {a->gyro_rad_s[i], a->gyro_raw_rad_s[i], a->command[i], a->ref_rate_rad_s[i]};
            const double out[4] = {b->gyro_rad_s[i], b->gyro_raw_rad_s[i], b->command[i], b->ref_rate_rad_s[i]};
            TEST_ASSERT_EQUAL_MEMORY(in, out, sizeof in);
        }
    }
}

#define HAS_ALL (SIM_LOG_HAS_GYRO | SIM_LOG_HAS_GYRO_RAW | SIM_LOG_HAS_COMMAND | SIM_LOG_HAS_REF_RATE)

static long long rejected_all(const sim_log_outliers_t *o)
{
    return o->rejected[0] + o->rejected[1] + o->rejected[2];
}

static void test_gaussian_noise_passes_untouched(void)
{
    /* 12 channels x 20,000 samples: at K = 30 the chance of one false
     * rejection is below 1e-180; at the K = 7 of the Gaussian argument it
     * would still be 2e-11 */
    stream_noise(0.01, 11);
    sim_log_outliers_t o;
    stream_filter(HAS_ALL, &o);
    TEST_ASSERT_EQUAL_INT(0, rejected_all(&o));
    assert_stream_unchanged();
}

static void test_one_spike_is_repaired_counted_and_located(void)
{
    stream_noise(0.01, 12);
    const int at = 7777;
    stream[at].gyro_raw_rad_s[1] = 2000.0 * DEG; /* pitch, the gyro before the filters */
    stream[at + 3000].command[2] = 32.767;       /* yaw, a PID sum at full scale over 1000 */
    sim_log_outliers_t o;
    stream_filter(HAS_ALL, &o);
    TEST_ASSERT_EQUAL_INT(0, o.rejected[0]);
    TEST_ASSERT_EQUAL_INT(1, o.rejected[1]);
    TEST_ASSERT_EQUAL_INT(1, o.rejected[2]);
    TEST_ASSERT_EQUAL_INT(1, o.n_located[1]);
    TEST_ASSERT_EQUAL_INT(SIM_LOG_OUTLIER_GYRO_RAW, o.located[1][0].channel);
    TEST_ASSERT_TRUE(at * DT_S == o.located[1][0].t_s);
    TEST_ASSERT_TRUE(2000.0 * DEG == o.located[1][0].value);
    TEST_ASSERT_EQUAL_INT(SIM_LOG_OUTLIER_COMMAND, o.located[2][0].channel);
    const double mean = 0.5 * (stream[at - 1].gyro_raw_rad_s[1] + stream[at + 1].gyro_raw_rad_s[1]);
    TEST_ASSERT_TRUE(fabs((mean) - (stream_out[at].gyro_raw_rad_s[1])) <= REPAIR_TOL);
    /* nothing else touched */
    stream[at].gyro_raw_rad_s[1] = stream_out[at].gyro_raw_rad_s[1];
    stream[at + 3000].command[2] = stream_out[at + 3000].command[2];
    assert_stream_unchanged();
    char line[512];
    sim_log_outliers_describe(&o, 1, line, sizeof line);
    TEST_ASSERT_EQUAL_STRING("pitch: 1 sample of 20,000 rejected as an outlier (raw gyro 2000 deg/s at t = 7.777 s)",
                             line);
    TEST_ASSERT_EQUAL_INT(0, sim_log_outliers_describe(&o, 0, line, sizeof line));
    TEST_ASSERT_FALSE(sim_log_outliers_many(&o, 1)); /* 1 in 20,000 */
}

static void test_a_run_of_three_is_repaired_along_the_line(void)
{
    stream_noise(0.01, 13);
    const int at = 5000;
    for (int r = 0; r < 3; ++r) {
        stream[at + r].gyro_rad_s[0] = -32767.0 * DEG;
    }
    sim_log_outliers_t o;
    stream_filter(HAS_ALL, &o);
    TEST_ASSERT_EQUAL_INT(3, o.rejected[0]);
    const double a = stream[at - 1].gyro_rad_s[0], b = stream[at + 3].gyro_rad_s[0];
    for (int r = 0; r < 3; ++r) {
        TEST_ASSERT_TRUE(fabs((a + (b - a) * (r + 1) / 4.0) - (stream_out[at + r].gyro_rad_s[0])) <= REPAIR_TOL);
    }
}

static void test_steps_ramps_and_held_sticks_are_motion(void)
{
    stream_noise(0.001, 14);
    sim_rng_t r;
    sim_rng_seed(&r, 41);
    for (int k = 0; k < N_STREAM; ++k) {
        /* roll: a step of 10 rad/s (7,000 sigma of the increments) every 0.5 s that stays */
        stream[k].gyro_rad_s[0] += (k / 500) % 2 ? 10.0 : 0.0;
        /* pitch: a snap of the stick, 1 rad/s a tick for 10 ticks, held 0.1 s, back down as fast */
        const int phase = k % 1000;
        stream[k].gyro_raw_rad_s[1] += phase < 10 ? phase : phase < 110 ? 10.0 : phase < 120 ? 120 - phase : 0.0;
        /* yaw: a setpoint held in quanta of 1 deg/s (with a reader's rounding of 1e-6),
         * blips of one quantum for 2 ticks: 10,000 sigma of its own increments */
        stream[k].ref_rate_rad_s[2] = (k % 300 < 2 ? 5.0 : 4.0) * DEG + 1e-6 * sim_rng_gauss(&r);
    }
    /* a reference's step logged as a rate setpoint: one tick of 15,000 deg/s
     * that carries the step (the simulator's logs hold one at each step) */
    stream[9001].ref_rate_rad_s[0] = 15000.0 * DEG;
    sim_log_outliers_t o;
    stream_filter(HAS_ALL, &o);
    TEST_ASSERT_EQUAL_INT(0, rejected_all(&o));
    assert_stream_unchanged();
}

static void test_gaps_pass_and_are_not_judged_across(void)
{
    stream_noise(0.01, 15);
    stream[3000].gyro_rad_s[0] = NAN;
    stream[3001].gyro_rad_s[0] = 50.0; /* the first after a gap: nothing before it to judge by */
    sim_log_outliers_t o;
    stream_filter(SIM_LOG_HAS_GYRO, &o);
    TEST_ASSERT_EQUAL_INT(0, rejected_all(&o));
    TEST_ASSERT_TRUE(isnan(stream_out[3000].gyro_rad_s[0]));
    TEST_ASSERT_TRUE(50.0 == stream_out[3001].gyro_rad_s[0]);
}

/* The generated flight: 4 s at 1 kHz, a chirp on each axis's command (b0
 * told), the rate setpoint the loop's, into a generic CSV. */
#define FLIGHT_TICKS 4000
static double flight[FLIGHT_TICKS][9]; /* gyro[3], command[3], ref_rate[3] */

static void fly(void)
{
    const loop_axis_t roll = {.b0 = 120.0,
                              .tau_s = 0.03,
                              .damping_per_s = 10.0,
                              .delay_ticks = 2,
                              .noise_rad_s = 0.002,
                              .chirp_amp = 0.1,
                              .f0_hz = 1.0,
                              .f1_hz = 40.0,
                              .chirp_s = 4.0,
                              .manoeuvre_rad = 0.2};
    loop_axis_t yaw = roll; /* a yaw: less effective, less damped */
    yaw.b0 = 50.0;
    yaw.damping_per_s = 5.0;
    const loop_axis_t ax[3] = {roll, roll, yaw};
    for (int i = 0; i < 3; ++i) {
        loop_t l;
        loop_init(&l, &ax[i], DT_S, 100 + (uint64_t)i);
        for (int k = 0; k < FLIGHT_TICKS; ++k) {
            loop_tick(&l, &flight[k][i], &flight[k][3 + i]);
            flight[k][6 + i] = l.setpoint_rad_s;
        }
    }
}

/* The flight, as damaged, into a generic CSV at `path`; its reading options. */
static void write_flight(double (*log)[9], sim_log_options_t *opt)
{
    snprintf(path, sizeof path, "/tmp/test_sim_log_outlier_XXXXXX");
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    FILE *f = fdopen(fd, "w");
    TEST_ASSERT_NOT_NULL(f);
    fprintf(f, "time,gyro[0],gyro[1],gyro[2],command[0],command[1],command[2],ref_rate[0],ref_rate[1],ref_rate[2]\n");
    for (int k = 0; k < FLIGHT_TICKS; ++k) {
        fprintf(f, "%.6f", k * DT_S);
        for (int c = 0; c < 9; ++c) {
            fprintf(f, ",%.17g", log[k][c]);
        }
        fputc('\n', f);
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    sim_log_options_default(opt);
    opt->format = SIM_LOG_GENERIC;
    snprintf(opt->path, sizeof opt->path, "%s", path);
}

/* The flight, as damaged, identified. */
static void identify(double (*log)[9], sim_airframe_t *a)
{
    sim_log_identify_options_t o;
    memset(&o, 0, sizeof o);
    write_flight(log, &o.log);
    o.delay_max_ticks = -1;
    char err[256];
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_identify(&o, a, NULL, err, sizeof err), err);
    remove(path);
    path[0] = '\0';
}

static sim_airframe_t clean, damaged;
static double damaged_flight[FLIGHT_TICKS][9];

static void assert_as_unmodified(int axis)
{
    const sim_ident_axis_t *c = &clean.axis[axis], *x = &damaged.axis[axis];
    if (getenv("OUTLIER_TEST_SHOW") != NULL) {
        printf("axis %d: b0 %.4g [%.4g, %.4g] R^2 %.4f floor %.3g, unmodified %.4g [%.4g, %.4g] R^2 %.4f floor %.3g\n",
               axis, x->b0, x->b0_lo, x->b0_hi, x->r2, damaged.noise_floor_rad_s_rthz[axis], c->b0, c->b0_lo, c->b0_hi,
               c->r2, clean.noise_floor_rad_s_rthz[axis]);
    }
    TEST_ASSERT_TRUE(c->b0_lo <= x->b0 && x->b0 <= c->b0_hi);
    TEST_ASSERT_TRUE(x->r2 > R2_MIN);
    const double ratio = damaged.noise_floor_rad_s_rthz[axis] / clean.noise_floor_rad_s_rthz[axis];
    TEST_ASSERT_TRUE(ratio < FLOOR_RATIO_MAX && ratio > 1.0 / FLOOR_RATIO_MAX);
}

static void test_one_spike_of_each_kind_leaves_the_identification_as_unmodified(void)
{
    fly();
    identify(flight, &clean);
    TEST_ASSERT_EQUAL_INT(0, rejected_all(&clean.outliers));
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(clean.axis[i].r2 > 0.95); /* the unmodified fit is good: the comparison means something */
    }
    /* roll's gyro at 2000 and at 32767 deg/s, roll's command at 32767 / 1000, at tick 2000 */
    const int cells[3] = {0, 0, 3};
    const double values[3] = {2000.0 * DEG, 32767.0 * DEG, 32.767};
    for (int kind = 0; kind < 3; ++kind) {
        memcpy(damaged_flight, flight, sizeof flight);
        damaged_flight[2000][cells[kind]] = values[kind];
        identify(damaged_flight, &damaged);
        assert_as_unmodified(0);
        TEST_ASSERT_EQUAL_INT(1, damaged.outliers.rejected[0]);
        TEST_ASSERT_TRUE(values[kind] == damaged.outliers.located[0][0].value);
    }
}

static void test_one_percent_of_cells_corrupt_is_repaired_and_warned(void)
{
    fly();
    identify(flight, &clean);
    memcpy(damaged_flight, flight, sizeof flight);
    sim_rng_t r;
    sim_rng_seed(&r, 77);
    const int n_bad = FLIGHT_TICKS / 100;
    for (int j = 0; j < n_bad; ++j) {
        /* distinct rows (one every 100, placed at random within), any of the 6 judged cells (the
         * gyro and the command: the setpoint is not judged, log_outlier.h), +-1000..32767 in the
         * log's units */
        const int row = j * 100 + 1 + (int)(98.0 * sim_rng_uniform(&r));
        const int cell = (int)(6.0 * sim_rng_uniform(&r)) % 6;
        const double v = (sim_rng_uniform(&r) < 0.5 ? -1.0 : 1.0) * (1000.0 + 31767.0 * sim_rng_uniform(&r));
        damaged_flight[row][cell] = cell >= 3 && cell < 6 ? v / 1000.0 : v * DEG;
    }
    identify(damaged_flight, &damaged);
    for (int i = 0; i < 3; ++i) {
        assert_as_unmodified(i);
    }
    TEST_ASSERT_EQUAL_INT(n_bad, rejected_all(&damaged.outliers));
    for (int i = 0; i < 3; ++i) {
        /* some 13 of 4,000 per axis: above the one in a thousand that warns */
        TEST_ASSERT_TRUE(sim_log_outliers_many(&damaged.outliers, i));
    }
}

/* The logged command's noise above 20 Hz of the flight and of the same
 * with roll's command at 32767 / 1000 for one tick: equal within 1 % (the
 * repaired tick is its neighbours' mean, within the command's noise of the
 * truth; the spike alone would add 0.5 rms over 4,000 ticks to some 0.05). */
#define COMMAND_NOISE_REL_TOL 0.01

static sim_log_noise_t noise_clean, noise_damaged;

static void test_the_noise_pass_is_not_carried_by_one_sample(void)
{
    fly();
    char err[256];
    sim_log_options_t opt;
    write_flight(flight, &opt);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_noise_measure(&opt, 30.0, &noise_clean, err, sizeof err), err);
    remove(path);
    memcpy(damaged_flight, flight, sizeof flight);
    damaged_flight[2000][3] = 32.767;
    write_flight(damaged_flight, &opt);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_log_noise_measure(&opt, 30.0, &noise_damaged, err, sizeof err), err);
    const double clean_rms = sim_log_noise_command_above(&noise_clean, 0, 20.0);
    TEST_ASSERT_TRUE(clean_rms > 0.0);
    TEST_ASSERT_TRUE(fabs(sim_log_noise_command_above(&noise_damaged, 0, 20.0) - clean_rms) <=
                     COMMAND_NOISE_REL_TOL * clean_rms);
    TEST_ASSERT_EQUAL_INT(1, noise_damaged.outliers.rejected[0]);
    TEST_ASSERT_EQUAL_INT(0, noise_clean.outliers.rejected[0] + noise_clean.outliers.rejected[1] +
                                 noise_clean.outliers.rejected[2]);
}

int main(void)
{
    stream = malloc(N_STREAM * sizeof *stream);
    stream_out = malloc(N_STREAM * sizeof *stream_out);
    if (stream == NULL || stream_out == NULL) {
        return 1;
    }
    stream_clear();
    UNITY_BEGIN();
    RUN_TEST(test_gaussian_noise_passes_untouched);
    RUN_TEST(test_one_spike_is_repaired_counted_and_located);
    RUN_TEST(test_a_run_of_three_is_repaired_along_the_line);
    RUN_TEST(test_steps_ramps_and_held_sticks_are_motion);
    RUN_TEST(test_gaps_pass_and_are_not_judged_across);
    RUN_TEST(test_one_spike_of_each_kind_leaves_the_identification_as_unmodified);
    RUN_TEST(test_one_percent_of_cells_corrupt_is_repaired_and_warned);
    RUN_TEST(test_the_noise_pass_is_not_carried_by_one_sample);
    free(stream);
    free(stream_out);
    return UNITY_END();
}
