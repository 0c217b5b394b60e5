/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the flight-log reader (sim_log_open_stream) on
 * arbitrary bytes, read to the end in the Betaflight and generic forms, at
 * the rows' own period and at 1 ms, and in the generic form with a few
 * items of the caller's and a window. Besides what the sanitizers catch, it
 * checks that:
 * - a refused input has its error inside the text: 1 <= line <= the lines of
 *   the text, 1 <= column <= that line's length + 1, and a message (but a
 *   window that starts after the log's end, before any tick);
 * - an accepted one gives ticks whose time increases, whose fields present
 *   (sim_log_has) are finite, and as many as the statistics count.
 */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include "fuzz.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "log/log.h"

/* Ticks read per form at most: rows a millisecond apart then one a day
 * later give millions of ticks, alike after the first ones (each over a
 * bracket of the same two rows); more would slow the search a hundredfold. */
#define TICKS_MAX 1000

static void check_refused(const uint8_t *data, size_t size, const sim_log_error_t *err)
{
    int lines;
    size_t line_len;
    fuzz_measure_lines(data, size, err->line, &lines, &line_len);
    FUZZ_CHECK(err->line >= 1 && err->line <= lines, "line %d of %d: %s", err->line, lines, err->message);
    FUZZ_CHECK(err->column >= 1 && (size_t)err->column <= line_len + 1, "column %d of a %zu-byte line %d: %s",
               err->column, line_len, err->line, err->message);
    FUZZ_CHECK(err->message[0] != '\0', "no message at %d:%d", err->line, err->column);
    FUZZ_CHECK(strcmp(err->path, "fuzz.csv") == 0, "path '%s'", err->path);
}

static void check_finite(const double *v, int n, const char *what, long long tick)
{
    for (int i = 0; i < n; ++i) {
        FUZZ_CHECK(isfinite(v[i]), "tick %lld: %s[%d] = %g", tick, what, i, v[i]);
    }
}

static void check_sample(const sim_log_sample_t *s, unsigned has, long long tick)
{
    check_finite(&s->t_s, 1, "t_s", tick);
    if (has & SIM_LOG_HAS_GYRO) {
        check_finite(s->gyro_rad_s, 3, "gyro", tick);
    }
    if (has & SIM_LOG_HAS_GYRO_RAW) {
        check_finite(s->gyro_raw_rad_s, 3, "gyro_raw", tick);
    }
    if (has & (SIM_LOG_HAS_ANGLE | SIM_LOG_HAS_ANGLE_INTEGRATED)) {
        check_finite(s->angle_rad, 3, "angle", tick);
    }
    if (has & SIM_LOG_HAS_ANGLE) {
        check_finite(s->quat, 4, "quat", tick);
    }
    if (has & (SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_REF_INTEGRATED)) {
        check_finite(s->ref_angle_rad, 3, "ref_angle", tick);
    }
    if (has & SIM_LOG_HAS_REF_ANGLE) {
        check_finite(s->ref_quat, 4, "ref_quat", tick);
    }
    if (has & SIM_LOG_HAS_REF_RATE) {
        check_finite(s->ref_rate_rad_s, 3, "ref_rate", tick);
    }
    if (has & SIM_LOG_HAS_COMMAND) {
        check_finite(s->command, 3, "command", tick);
    }
    if (has & SIM_LOG_HAS_THROTTLE) {
        check_finite(&s->throttle, 1, "throttle", tick);
    }
    FUZZ_CHECK(s->n_motors >= 0 && s->n_motors <= SIM_LOG_MAX_MOTORS, "%d motors", s->n_motors);
    for (int q = 0; q < s->n_motors; ++q) { /* a motor without its column is NaN, never infinite */
        FUZZ_CHECK(!isinf(s->motor[q]) && !isinf(s->rotor_hz[q]), "tick %lld: motor %d", tick, q);
    }
    if (s->n_motors > 0) {
        const int q = s->n_motors - 1;
        FUZZ_CHECK(isfinite(s->motor[q]) || isfinite(s->rotor_hz[q]), "tick %lld: motor %d has nothing", tick, q);
    }
}

static void read_all(const uint8_t *data, size_t size, const sim_log_options_t *o)
{
    FILE *f = fmemopen((void *)(uintptr_t)data, size, "r");
    FUZZ_CHECK(f != NULL, "fmemopen of %zu bytes", size);
    const sim_log_options_t opt = *o;
    sim_log_error_t err;
    memset(&err, 0, sizeof err);
    sim_log_t *log = sim_log_open_stream(f, "fuzz.csv", &opt, &err);
    if (log == NULL) {
        check_refused(data, size, &err);
        fclose(f);
        return;
    }
    const unsigned has = sim_log_has(log);
    const double dt = sim_log_dt_s(log);
    FUZZ_CHECK(dt > 0.0 && isfinite(dt), "dt %g", dt);
    sim_log_sample_t s;
    double t_prev = -1.0;
    long long ticks = 0;
    int rc = 1;
    while (ticks < TICKS_MAX && (rc = sim_log_next(log, &s, &err)) == 1) {
        check_sample(&s, has, ticks);
        FUZZ_CHECK(s.t_s > t_prev, "tick %lld at %.17g s after %.17g s", ticks, s.t_s, t_prev);
        t_prev = s.t_s;
        ++ticks;
    }
    if (rc < 0 && err.line == 0 && opt.t_from_s > 0.0) { /* a window after the log's end: no place in it */
        FUZZ_CHECK(ticks == 0 && strstr(err.message, "window") != NULL, "after %lld ticks: %s", ticks, err.message);
    } else if (rc < 0) {
        check_refused(data, size, &err);
    }
    sim_log_stats_t st;
    sim_log_stats(log, &st);
    FUZZ_CHECK(st.ticks == ticks, "%lld ticks counted, %lld read", st.ticks, ticks);
    FUZZ_CHECK(st.has == has && st.n_files == 1 && st.rows >= 2, "stats: has %x, %d files, %lld rows", st.has,
               st.n_files, st.rows);
    long long done, total;
    sim_log_progress(log, &done, &total);
    FUZZ_CHECK(done >= 0 && (size_t)done <= size && total == 0, "progress %lld of %lld", done, total);
    sim_log_close(log);
    fclose(f);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) {
        return 0; /* fmemopen wants a buffer */
    }
    sim_log_options_t o;
    sim_log_options_default(&o);
    read_all(data, size, &o); /* Betaflight at the rows' period */
    o.format = SIM_LOG_GENERIC;
    read_all(data, size, &o);
    o.dt_s = 0.001;
    read_all(data, size, &o);
    /* the caller's items over the preset (sums, optional columns, scales), a window */
    o.map[0] = "command[1]=?a+?b*-1*ms";
    o.map[1] = "ref_rate[2]=?b*deg";
    o.map[2] = "quat[3]=?z+?quat[3]";
    o.n_map = 3;
    o.t_from_s = 0.002;
    o.t_to_s = 0.5;
    read_all(data, size, &o);
    return 0;
}
