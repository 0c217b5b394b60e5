/* SPDX-License-Identifier: BSD-3-Clause */
/* A flight log's outliers found and repaired as it streams (log_outlier.h). */
#include "log_outlier.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RAD2DEG (180.0 / 3.14159265358979323846)
#define MAD_TO_SIGMA 1.482602218505602 /* 1 / Phi^-1(3/4): the MAD's sigma on Gaussian data */
#define P90_TO_SIGMA 0.6079301331      /* 1 / Phi^-1(0.95): the 90th percentile of |x|'s sigma on Gaussian data */
#define P90_SHARE 0.9
#define LOCAL SIM_LOG_OUTLIER_LOCAL
/* held: LOCAL samples already out (the context before the block), the block, and after it the look-ahead a run's end
 * and its context need */
#define AHEAD (SIM_LOG_OUTLIER_RUN_MAX + LOCAL)
#define CAPACITY (LOCAL + SIM_LOG_OUTLIER_BLOCK + AHEAD)
#define SLOTS (3 * SIM_LOG_OUTLIER_CHANNELS) /* axis * SIM_LOG_OUTLIER_CHANNELS + channel */

/* A channel's state across blocks. */
typedef struct {
    int on;       /* the log has it */
    double last;  /* the last sample kept (NaN: none, or a gap since) */
    int carry;    /* samples after the block already judged (a run that reached past it) */
    double sigma; /* the robust scale of its increments over the current block (0: not judged) */
} channel_state_t;

struct sim_log_despike {
    sim_log_sample_t buf[CAPACITY];
    unsigned char replaced[CAPACITY][SLOTS];
    double original[CAPACITY][SLOTS];
    int fill, ready, out; /* samples held; those before `ready` are judged; the next to pop */
    int history;          /* samples at the front already popped, kept as context */
    channel_state_t ch[SLOTS];
    double increments[CAPACITY];
    sim_log_outliers_t count;
    int ended;            /* sim_log_next_repaired: the log's end reached */
    size_t offset[SLOTS]; /* channel_offset of each slot */
};

/* Where each slot's value lies in a sample (bytes). */
static size_t channel_offset(int slot)
{
    const size_t axis = (size_t)(slot / SIM_LOG_OUTLIER_CHANNELS) * sizeof(double);
    switch (slot % SIM_LOG_OUTLIER_CHANNELS) {
    case SIM_LOG_OUTLIER_GYRO:
        return offsetof(sim_log_sample_t, gyro_rad_s) + axis;
    case SIM_LOG_OUTLIER_GYRO_RAW:
        return offsetof(sim_log_sample_t, gyro_raw_rad_s) + axis;
    case SIM_LOG_OUTLIER_COMMAND:
        return offsetof(sim_log_sample_t, command) + axis;
    default:
        return offsetof(sim_log_sample_t, ref_rate_rad_s) + axis;
    }
}

/* The slot's value in the buffer's sample i. */
static double *value_at(sim_log_despike_t *d, int i, int slot)
{
    return (double *)((char *)&d->buf[i] + d->offset[slot]);
}

sim_log_despike_t *sim_log_despike_new(unsigned has)
{
    sim_log_despike_t *d = calloc(1, sizeof *d);
    if (d == NULL) {
        return NULL;
    }
    const unsigned flag[SIM_LOG_OUTLIER_CHANNELS] = {SIM_LOG_HAS_GYRO, SIM_LOG_HAS_GYRO_RAW, SIM_LOG_HAS_COMMAND,
                                                     SIM_LOG_HAS_REF_RATE};
    for (int k = 0; k < SLOTS; ++k) {
        d->ch[k].on = (has & flag[k % SIM_LOG_OUTLIER_CHANNELS]) != 0;
        d->ch[k].last = NAN;
        d->offset[k] = channel_offset(k);
    }
    return d;
}

void sim_log_despike_free(sim_log_despike_t *d)
{
    free(d);
}

static void swap(double *a, double *b)
{
    const double t = *a;
    *a = *b;
    *b = t;
}

/* The k-th smallest of x[0..n) (Hoare's selection; x reordered). */
static double select_kth(double *x, int n, int k)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        const double pivot = x[lo + (hi - lo) / 2];
        int i = lo, j = hi;
        while (i <= j) {
            while (x[i] < pivot) {
                ++i;
            }
            while (x[j] > pivot) {
                --j;
            }
            if (i <= j) {
                swap(&x[i++], &x[j--]);
            }
        }
        if (k <= j) {
            hi = j;
        } else if (k >= i) {
            lo = i;
        } else {
            break;
        }
    }
    return x[k];
}

/* The robust sigma of n absolute increments (reordered): the larger of
 * MAD_TO_SIGMA x their median and P90_TO_SIGMA x their 90th percentile.
 * Both are the standard deviation on Gaussian noise; the percentile still
 * sees a quantised signal that holds most ticks (its median increment 0)
 * and is the more cautious where real motion has heavy tails; it breaks
 * down only beyond 10 % of bad increments. 0: too few to judge, or the
 * signal holds 9 ticks in 10. */
static double robust_sigma(double *inc, int n, int n_min)
{
    if (n < n_min) {
        return 0.0;
    }
    /* the percentile first: the median then lies among the smaller ones it leaves in front */
    const int k90 = (int)(P90_SHARE * (n - 1));
    const double p90 = select_kth(inc, n, k90);
    const double median = select_kth(inc, k90 + 1, n / 2);
    return fmax(MAD_TO_SIGMA * median, P90_TO_SIGMA * p90);
}

/* The finite absolute increments x[j] - x[j - 1] of the channel for j in [from, to), those of [skip_lo, skip_hi) left
 * out, into d->increments; their count. */
static int gather_increments(sim_log_despike_t *d, int slot, int from, int to, int skip_lo, int skip_hi)
{
    int n = 0;
    for (int j = from > 1 ? from : 1; j < to && j < d->fill; ++j) {
        const double inc = fabs(*value_at(d, j, slot) - *value_at(d, j - 1, slot));
        if (isfinite(inc) && (j < skip_lo || j >= skip_hi)) {
            d->increments[n++] = inc;
        }
    }
    return n;
}

/* 1 when the m samples from i are an outlier run after the kept sample
 * `last`: every one beyond `limit` from `last` and from the sample after
 * the run, and those two within it. */
static int run_is_out(sim_log_despike_t *d, int slot, int i, int m, double last, double limit)
{
    const double after = *value_at(d, i + m, slot);
    if (!(fabs(after - last) <= limit)) {
        return 0;
    }
    for (int r = 0; r < m; ++r) {
        const double x = *value_at(d, i + r, slot);
        if (!(fabs(x - last) > limit && fabs(x - after) > limit)) { /* NaN: not out */
            return 0;
        }
    }
    return 1;
}

/* The length (1..SIM_LOG_OUTLIER_RUN_MAX) of the shortest outlier run starting at i, 0 when there is none. */
static int outlier_run(sim_log_despike_t *d, int slot, int i, double last, double limit)
{
    for (int m = 1; m <= SIM_LOG_OUTLIER_RUN_MAX && i + m < d->fill; ++m) {
        if (run_is_out(d, slot, i, m, last, limit)) {
            return m;
        }
    }
    return 0;
}

/* The run of m samples from i confirmed against the local scale: the
 * increments within LOCAL ticks either side, the run's own left out (the
 * motion there, a burst of vibration the block's scale averages away). */
static int outlier_confirmed(sim_log_despike_t *d, int slot, int i, int m, double last, double block_sigma)
{
    const int n = gather_increments(d, slot, i - LOCAL, i + m + 1 + LOCAL, i, i + m + 1);
    const double sigma = fmax(block_sigma, robust_sigma(d->increments, n, SIM_LOG_OUTLIER_MIN_INCREMENTS / 2));
    return run_is_out(d, slot, i, m, last, SIM_LOG_OUTLIER_K * sigma);
}

/* The run of m samples from i replaced by the line from `last` to the sample after it. */
static void repair(sim_log_despike_t *d, int slot, int i, int m, double last)
{
    const double after = *value_at(d, i + m, slot);
    for (int r = 0; r < m; ++r) {
        double *x = value_at(d, i + r, slot);
        d->replaced[i + r][slot] = 1;
        d->original[i + r][slot] = *x;
        *x = last + (after - last) * (r + 1) / (m + 1);
    }
}

/* Judges the channel's samples in [from, to) (a run may reach past it into the look-ahead). */
static void judge_channel(sim_log_despike_t *d, int slot, int from, int to)
{
    channel_state_t *c = &d->ch[slot];
    c->sigma =
        robust_sigma(d->increments, gather_increments(d, slot, 1, d->fill, 0, 0), SIM_LOG_OUTLIER_MIN_INCREMENTS);
    if (slot % SIM_LOG_OUTLIER_CHANNELS == SIM_LOG_OUTLIER_SETPOINT) {
        /* a stick's held steps: their moves on the gyro's scale (judged before it) are no outliers */
        const channel_state_t *gyro = &d->ch[slot - SIM_LOG_OUTLIER_SETPOINT];
        c->sigma = fmax(c->sigma, fmax(gyro[SIM_LOG_OUTLIER_GYRO].sigma, gyro[SIM_LOG_OUTLIER_GYRO_RAW].sigma));
    }
    const double sigma = c->sigma;
    const double limit = SIM_LOG_OUTLIER_K * sigma;
    int i = from + c->carry;
    while (i < to) {
        const double x = *value_at(d, i, slot);
        int m = 0;
        if (limit > 0.0 && isfinite(c->last) && isfinite(x) && !(fabs(x - c->last) <= limit)) {
            m = outlier_run(d, slot, i, c->last, limit);
            m = m > 0 && outlier_confirmed(d, slot, i, m, c->last, sigma) ? m : 0;
        }
        if (m > 0) {
            repair(d, slot, i, m, c->last);
            i += m;
        } else {
            c->last = x; /* NaN: a gap, nothing paired across it */
            ++i;
        }
    }
    c->carry = i - to;
}

/* The next n samples after the history judged and made ready. */
static void judge(sim_log_despike_t *d, int n)
{
    for (int k = 0; k < SLOTS; ++k) {
        if (d->ch[k].on) {
            judge_channel(d, k, d->history, d->history + n);
        }
    }
    d->ready = d->history + n;
    d->out = d->history;
}

/* The popped samples out of the buffer but the last LOCAL (the next block's context). */
static void compact(sim_log_despike_t *d)
{
    const int drop = d->out > LOCAL ? d->out - LOCAL : 0;
    if (drop > 0) {
        const int keep = d->fill - drop;
        memmove(d->buf, d->buf + drop, (size_t)keep * sizeof d->buf[0]);
        memmove(d->replaced, d->replaced + drop, (size_t)keep * sizeof d->replaced[0]);
        memmove(d->original, d->original + drop, (size_t)keep * sizeof d->original[0]);
        memset(d->replaced + keep, 0, (size_t)(CAPACITY - keep) * sizeof d->replaced[0]);
        d->fill = keep;
    }
    d->history = d->out - drop;
    d->ready = d->out = d->history;
}

int sim_log_despike_push(sim_log_despike_t *d, const sim_log_sample_t *s)
{
    if (d->out == d->ready) {
        compact(d);
    }
    if (d->fill == CAPACITY) {
        return -1; /* the ready samples were not all popped */
    }
    d->buf[d->fill++] = *s;
    if (d->fill == CAPACITY) {
        judge(d, d->fill - d->history - AHEAD);
    }
    return 0;
}

void sim_log_despike_finish(sim_log_despike_t *d)
{
    if (d->out != d->ready) {
        return; /* samples ready and not popped: they come first */
    }
    compact(d);
    if (d->fill > d->history) {
        judge(d, d->fill - d->history);
    }
}

/* A popped sample's replaced values into the count. */
static void count(sim_log_despike_t *d, int i)
{
    sim_log_outliers_t *o = &d->count;
    o->samples++;
    for (int axis = 0; axis < 3; ++axis) {
        int first = -1;
        for (int c = 0; c < SIM_LOG_OUTLIER_CHANNELS && first < 0; ++c) {
            first = d->replaced[i][axis * SIM_LOG_OUTLIER_CHANNELS + c] ? c : -1;
        }
        if (first < 0) {
            continue;
        }
        o->rejected[axis]++;
        if (o->n_located[axis] < SIM_LOG_OUTLIER_LOCATED) {
            o->located[axis][o->n_located[axis]++] =
                (sim_log_outlier_at_t){d->buf[i].t_s, d->original[i][axis * SIM_LOG_OUTLIER_CHANNELS + first], first};
        }
    }
}

int sim_log_despike_pop(sim_log_despike_t *d, sim_log_sample_t *out)
{
    if (d->out >= d->ready) {
        return 0;
    }
    count(d, d->out);
    *out = d->buf[d->out++];
    return 1;
}

int sim_log_next_repaired(sim_log_t *log, sim_log_despike_t *d, sim_log_sample_t *s, sim_log_error_t *err)
{
    while (!sim_log_despike_pop(d, s)) {
        if (d->ended) {
            return 0;
        }
        sim_log_sample_t in;
        const int rc = sim_log_next(log, &in, err);
        if (rc < 0) {
            return rc;
        }
        if (rc == 0) {
            d->ended = 1;
            sim_log_despike_finish(d);
        } else {
            sim_log_despike_push(d, &in); /* never refused: everything ready was popped above */
        }
    }
    return 1;
}

void sim_log_despike_outliers(const sim_log_despike_t *d, sim_log_outliers_t *out)
{
    *out = d->count;
}

const char *sim_log_outlier_channel_name(int channel)
{
    static const char *const NAME[SIM_LOG_OUTLIER_CHANNELS] = {"gyro", "raw gyro", "command", "setpoint"};
    return channel >= 0 && channel < SIM_LOG_OUTLIER_CHANNELS ? NAME[channel] : "?";
}

/* n with its thousands grouped by commas ("4,000"). */
static void grouped(long long n, char *buf, size_t len)
{
    char digits[32];
    const int nd = snprintf(digits, sizeof digits, "%lld", n < 0 ? -n : n);
    size_t k = 0;
    if (n < 0 && k + 1 < len) {
        buf[k++] = '-';
    }
    for (int i = 0; i < nd && k + 1 < len; ++i) {
        if (i > 0 && (nd - i) % 3 == 0 && k + 2 < len) {
            buf[k++] = ',';
        }
        buf[k++] = digits[i];
    }
    buf[k] = '\0';
}

int sim_log_outliers_describe(const sim_log_outliers_t *o, int axis, char *buf, size_t len)
{
    static const char *const AXIS[3] = {"roll", "pitch", "yaw"};
    if (o->rejected[axis] == 0) {
        if (len > 0) {
            buf[0] = '\0';
        }
        return 0;
    }
    char n[32], of[32];
    grouped(o->rejected[axis], n, sizeof n);
    grouped(o->samples, of, sizeof of);
    int w = snprintf(buf, len, "%s: %s sample%s of %s rejected as %s (", AXIS[axis], n,
                     o->rejected[axis] == 1 ? "" : "s", of, o->rejected[axis] == 1 ? "an outlier" : "outliers");
    for (int k = 0; k < o->n_located[axis]; ++k) {
        const sim_log_outlier_at_t *at = &o->located[axis][k];
        const int rate = at->channel != SIM_LOG_OUTLIER_COMMAND;
        const size_t used = (size_t)w < len ? (size_t)w : len;
        w += snprintf(buf + used, len - used, "%s%s %.6g%s at t = %.3f s", k > 0 ? ", " : "",
                      sim_log_outlier_channel_name(at->channel), rate ? at->value * RAD2DEG : at->value,
                      rate ? " deg/s" : "", at->t_s);
    }
    const size_t used = (size_t)w < len ? (size_t)w : len;
    w += snprintf(buf + used, len - used, "%s)", o->rejected[axis] > o->n_located[axis] ? ", ..." : "");
    return w;
}

int sim_log_outliers_many(const sim_log_outliers_t *o, int axis)
{
    return o->samples > 0 && (double)o->rejected[axis] > SIM_LOG_OUTLIER_WARN_SHARE * (double)o->samples;
}
