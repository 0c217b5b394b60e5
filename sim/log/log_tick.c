/* SPDX-License-Identifier: BSD-3-Clause */
/* The reader's ticks (log.h): each file's bracket moved to the tick, the
 * sample interpolated from the brackets, the attitude derived or
 * integrated; progress and statistics. */
#include "log.h"

#include "log_attitude.h"
#include "log_reader.h"

#include <math.h>
#include <stdio.h>

static double tick_us(const sim_log_t *log, long long k)
{
    if (log->whole) {
        return (double)(log->t_first_whole + k * log->dt_whole); /* exact: below 2^54 */
    }
    return log->t_first_us + (double)k * log->dt_us;
}

/* The slot's rows around the tick: 1 when the tick is on one of them (a,
 * b: its value), else 0 with the two rows' values and the fraction. */
static int bracket(const sim_log_t *log, int slot, double tick, double *a, double *b, double *frac)
{
    const sim_log_file_t *f = &log->files[log->slot_file[slot]];
    const int j = log->slot_index[slot];
    *frac = 0.0;
    if (tick == f->t1 || tick == f->t0) {
        *a = *b = tick == f->t1 ? f->v1[j] : f->v0[j];
        return 1;
    }
    *a = f->v0[j];
    *b = f->v1[j];
    *frac = (tick - f->t0) / (f->t1 - f->t0);
    return 0;
}

/* A plain field: linear between rows; a component without a column is 0
 * (motors: NaN). */
static void plain(const sim_log_t *log, sim_log_group_t g, double tick, double absent, double *out)
{
    const int first = sim_log_group_first(g);
    int n = sim_log_group_count(g);
    if (g == SIM_LOG_G_MOTOR || g == SIM_LOG_G_ROTOR_HZ) {
        n = log->n_motors;
    }
    for (int i = 0; i < n; ++i) {
        double a, b, frac;
        if (log->slot_file[first + i] < 0) {
            out[i] = absent;
        } else if (bracket(log, first + i, tick, &a, &b, &frac)) {
            out[i] = a; /* the row's bits */
        } else {
            out[i] = a + (b - a) * frac;
        }
    }
}

/* The log's attitude (angles, a quaternion or both), one from the other. */
static void attitude(const sim_log_t *log, sim_log_group_t g_angle, sim_log_group_t g_quat, double tick,
                     double angle[3], double q[4])
{
    double a[4], b[4], frac = 0.0, f;
    if (log->group_has[g_angle]) {
        const int first = sim_log_group_first(g_angle);
        for (int i = 0; i < 3; ++i) {
            angle[i] = 0.0;
            if (log->slot_file[first + i] >= 0) {
                angle[i] = bracket(log, first + i, tick, &a[0], &b[0], &f) ? a[0] : sim_log_angle_lerp(a[0], b[0], f);
            }
        }
    }
    if (log->group_has[g_quat]) { /* all four mapped (checked at open) */
        const int first = sim_log_group_first(g_quat);
        int exact = 1;
        for (int i = 0; i < 4; ++i) {
            exact &= bracket(log, first + i, tick, &a[i], &b[i], &f);
            frac = i == 0 ? f : frac;
        }
        for (int i = 0; exact && i < 4; ++i) {
            q[i] = a[i]; /* on a row: its bits, not normalised */
        }
        if (!exact) {
            sim_log_quat_lerp(a, b, frac, q);
        }
        if (!log->group_has[g_angle]) {
            sim_log_quat_to_angle(q, angle);
        }
    } else if (log->group_has[g_angle]) {
        sim_log_angle_to_quat(angle, q);
    }
}

/* Trapezoid over the ticks, from 0 at the first tick given; not wrapped. */
static void integrate(double sum[3], double prev[3], const double rate[3], double dt_s, int first)
{
    for (int i = 0; i < 3; ++i) {
        sum[i] = first ? 0.0 : sum[i] + 0.5 * (prev[i] + rate[i]) * dt_s;
        prev[i] = rate[i];
    }
}

static void set_nan(double *v, int n)
{
    for (int i = 0; i < n; ++i) {
        v[i] = NAN;
    }
}

static void fill(sim_log_t *log, double tick, sim_log_sample_t *s)
{
    const int first = log->ticks == 0;
    const double dt_s = log->dt_us * 1e-6;
    set_nan(s->gyro_rad_s, 3);
    set_nan(s->gyro_raw_rad_s, 3);
    set_nan(s->angle_rad, 3);
    set_nan(s->quat, 4);
    set_nan(s->ref_angle_rad, 3);
    set_nan(s->ref_quat, 4);
    set_nan(s->ref_rate_rad_s, 3);
    set_nan(s->command, 3);
    set_nan(&s->throttle, 1);
    set_nan(s->motor, SIM_LOG_MAX_MOTORS);
    set_nan(s->rotor_hz, SIM_LOG_MAX_MOTORS);
    s->n_motors = log->n_motors;
    s->t_s = (tick - log->t_first_us) * 1e-6;
    if (log->has & SIM_LOG_HAS_GYRO) {
        plain(log, SIM_LOG_G_GYRO, tick, 0.0, s->gyro_rad_s);
    }
    if (log->has & SIM_LOG_HAS_GYRO_RAW) {
        plain(log, SIM_LOG_G_GYRO_RAW, tick, 0.0, s->gyro_raw_rad_s);
    }
    if (log->has & SIM_LOG_HAS_REF_RATE) {
        plain(log, SIM_LOG_G_REF_RATE, tick, 0.0, s->ref_rate_rad_s);
    }
    if (log->has & SIM_LOG_HAS_COMMAND) {
        plain(log, SIM_LOG_G_COMMAND, tick, 0.0, s->command);
    }
    if (log->has & SIM_LOG_HAS_THROTTLE) {
        plain(log, SIM_LOG_G_THROTTLE, tick, 0.0, &s->throttle);
    }
    plain(log, SIM_LOG_G_MOTOR, tick, NAN, s->motor);
    plain(log, SIM_LOG_G_ROTOR_HZ, tick, NAN, s->rotor_hz);
    if (log->has & SIM_LOG_HAS_ANGLE) {
        attitude(log, SIM_LOG_G_ANGLE, SIM_LOG_G_QUAT, tick, s->angle_rad, s->quat);
    } else if (log->has & SIM_LOG_HAS_ANGLE_INTEGRATED) {
        integrate(log->angle, log->prev_gyro, s->gyro_rad_s, dt_s, first);
        for (int i = 0; i < 3; ++i) {
            s->angle_rad[i] = log->angle[i];
        }
    }
    if (log->has & SIM_LOG_HAS_REF_ANGLE) {
        attitude(log, SIM_LOG_G_REF_ANGLE, SIM_LOG_G_REF_QUAT, tick, s->ref_angle_rad, s->ref_quat);
    } else if (log->has & SIM_LOG_HAS_REF_INTEGRATED) {
        integrate(log->ref_angle, log->prev_ref_rate, s->ref_rate_rad_s, dt_s, first);
        for (int i = 0; i < 3; ++i) {
            s->ref_angle_rad[i] = log->ref_angle[i];
        }
    }
}

/* The log ended before the first tick given: only a window can do that. */
static int ended(sim_log_t *log, const sim_log_file_t *f, sim_log_error_t *err)
{
    log->done = 1;
    if (log->ticks > 0) {
        return 0;
    }
    log->failed = 1;
    snprintf(log->err.path, sizeof log->err.path, "%s", f->path);
    log->err.line = 0;
    log->err.column = 0;
    snprintf(log->err.message, sizeof log->err.message, "the window starts at %g s, after the log's end (%.9g s)",
             log->t_from_s, (f->t0 - log->t_first_us) * 1e-6);
    *err = log->err;
    return -1;
}

/* The first tick at or after t_us (a row's time past the current tick). */
static long long first_tick_at(const sim_log_t *log, double t_us)
{
    long long k = (long long)ceil((t_us - log->t_first_us) / log->dt_us); /* t_us < 2^54, dt >= 1 us */
    while (k > log->k && tick_us(log, k - 1) >= t_us) {
        --k; /* the division's rounding, either way */
    }
    while (tick_us(log, k) < t_us) {
        ++k;
    }
    return k;
}

/* Every file's bracket moved to the tick: 1, 0 at the end, -1 on error. */
static int reach_all(sim_log_t *log, double tick, sim_log_error_t *err)
{
    for (int i = 0; i < log->n_files; ++i) {
        sim_log_file_t *f = &log->files[i];
        const int rc = sim_log_file_reach(f, tick, &log->err);
        if (rc == 0) {
            return ended(log, f, err);
        }
        if (rc < 0) {
            snprintf(log->err.path, sizeof log->err.path, "%s", f->path);
            log->failed = 1;
            *err = log->err;
            return -1;
        }
    }
    return 1;
}

/* 1 when the tick lies inside a gap the ticks skip in every file, with the
 * span no file has a row in (from its latest row before to its earliest
 * after); 0 when a file's rows go on around it (a topic that pauses while
 * the others go on is interpolated: the ticks stay bounded by that file's
 * rows). */
static int in_skipped_gap(const sim_log_t *log, double tick, double *from_us, double *to_us)
{
    *from_us = -INFINITY;
    *to_us = INFINITY;
    for (int i = 0; i < log->n_files; ++i) {
        const sim_log_file_t *f = &log->files[i];
        if (!sim_log_file_in_skipped_gap(f, tick)) {
            return 0;
        }
        *from_us = fmax(*from_us, f->t0);
        *to_us = fmin(*to_us, f->t1);
    }
    return 1;
}

int sim_log_next(sim_log_t *log, sim_log_sample_t *s, sim_log_error_t *err)
{
    if (log->failed) {
        *err = log->err;
        return -1;
    }
    double tick;
    for (;;) {
        if (log->done || log->k > log->k_end) {
            log->done = 1;
            return 0;
        }
        tick = tick_us(log, log->k);
        const int rc = reach_all(log, tick, err);
        if (rc <= 0) {
            return rc;
        }
        double from_us, to_us;
        if (!in_skipped_gap(log, tick, &from_us, &to_us)) {
            break;
        }
        /* skipped, not interpolated: on to the first row after the gap */
        log->skipped_gaps++;
        log->skipped_file_gaps += log->n_files;
        log->skipped_us += to_us - from_us;
        log->k = first_tick_at(log, to_us);
        log->after_gap = log->ticks > 0; /* a window that starts in a gap has nothing before it */
    }
    fill(log, tick, s);
    s->after_gap = log->after_gap;
    log->after_gap = 0;
    ++log->k;
    ++log->ticks;
    return 1;
}

double sim_log_dt_s(const sim_log_t *log)
{
    return log->dt_us * 1e-6;
}

unsigned sim_log_has(const sim_log_t *log)
{
    return log->has;
}

void sim_log_progress(const sim_log_t *log, long long *done, long long *total)
{
    *done = 0;
    *total = 0;
    for (int i = 0; i < log->n_files; ++i) {
        *done += log->files[i].csv.bytes;
        *total += log->files[i].size;
    }
}

void sim_log_stats(const sim_log_t *log, sim_log_stats_t *st)
{
    st->rows = 0;
    st->gaps = 0;
    st->longest_gap_s = 0.0;
    for (int i = 0; i < log->n_files; ++i) {
        const sim_log_file_t *f = &log->files[i];
        st->rows += f->rows;
        st->gaps += f->gaps;
        st->longest_gap_s = fmax(st->longest_gap_s, f->longest_gap_us * 1e-6);
    }
    st->ticks = log->ticks;
    st->skipped_gaps = log->skipped_gaps;
    st->skipped_s = log->skipped_us * 1e-6;
    st->skipped_file_gaps = log->skipped_file_gaps;
    st->row_period_s = log->files[0].median_us * 1e-6;
    st->has = log->has;
    st->n_files = log->n_files;
}

int sim_log_gap_warning(const sim_log_stats_t *st, char *buf, size_t len)
{
    buf[0] = '\0';
    if (st->skipped_gaps <= 0) {
        return 0;
    }
    snprintf(buf, len,
             "%lld gap(s) in the log's time longer than %.0f row periods skipped, not interpolated (%.6g s in "
             "all): what spans one restarts after it",
             st->skipped_gaps, SIM_LOG_GAP_SKIP_FACTOR, st->skipped_s);
    return 1;
}
