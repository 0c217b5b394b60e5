/* SPDX-License-Identifier: BSD-3-Clause */
/* The setpoint smoothed as a flight stack does (setpoint_smooth.h). */
#include "setpoint_smooth.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

static double wrap_pi(double x)
{
    return x - 2.0 * PI * floor((x + PI) / (2.0 * PI));
}

void setpoint_smooth_init(setpoint_smooth_t *s, double dt_s)
{
    memset(s, 0, sizeof *s);
    s->dt_s = dt_s;
    for (int i = 0; i < 3; ++i) {
        s->last_step_tick[i] = -1;
    }
    s->frame_ticks = NAN;
    s->link_hz = NAN;
    s->cutoff_hz = NAN;
}

static int cmp_int(const void *a, const void *b)
{
    const int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* The link's frame interval from the training steps: the mean of the
 * intervals near their median (a held stick's long gaps left out). */
static void learn(setpoint_smooth_t *s)
{
    int sorted[SETPOINT_SMOOTH_TRAINING_STEPS];
    memcpy(sorted, s->intervals, sizeof sorted);
    qsort(sorted, SETPOINT_SMOOTH_TRAINING_STEPS, sizeof sorted[0], cmp_int);
    const double median =
        0.5 * (sorted[SETPOINT_SMOOTH_TRAINING_STEPS / 2 - 1] + sorted[SETPOINT_SMOOTH_TRAINING_STEPS / 2]);
    double sum = 0.0;
    int n = 0;
    for (int i = 0; i < SETPOINT_SMOOTH_TRAINING_STEPS; ++i) {
        if (sorted[i] >= 0.5 * median && sorted[i] <= 1.5 * median) {
            sum += sorted[i];
            n++;
        }
    }
    s->frame_ticks = sum / n; /* n >= 1: the median's own samples lie in the band */
    s->link_hz = 1.0 / (s->frame_ticks * s->dt_s);
    if (s->frame_ticks < 1.5) {
        s->state = SETPOINT_SMOOTH_ALREADY;
        return;
    }
    if (s->frame_ticks * s->dt_s > SETPOINT_SMOOTH_MAX_FRAME_S) {
        s->state = SETPOINT_SMOOTH_NO_LINK;
        return;
    }
    s->cutoff_hz = fmax(SETPOINT_SMOOTH_MIN_CUTOFF_HZ, SETPOINT_SMOOTH_CUTOFF_FACTOR * s->link_hz);
    /* a corner at or past 0.45 of the loop rate would not be a low-pass the bilinear map can hold */
    if (s->cutoff_hz >= 0.45 / s->dt_s) {
        s->state = SETPOINT_SMOOTH_ALREADY;
        return;
    }
    s->coef = biquad_lowpass(s->cutoff_hz, s->dt_s, BIQUAD_Q_BUTTERWORTH);
    for (int i = 0; i < 3; ++i) {
        biquad_settle(&s->coef, &s->lp[i], s->unwrapped[i]);
    }
    s->state = SETPOINT_SMOOTH_ON;
}

/* Steps counted per axis (the axes' frames interleave when pooled); two
 * changed ticks in a row are one step (a row's step lands on two ticks
 * when the log's rows sit between them); a longer run steps every tick. */
static void count_steps(setpoint_smooth_t *s, const double source[3])
{
    for (int i = 0; i < 3 && s->state == SETPOINT_SMOOTH_TRAINING; ++i) {
        /* NaN never steps: a missing axis leaves the others to tell */
        const int changed =
            s->tick > 0 && source[i] != s->prev_source[i] && !isnan(source[i]) && !isnan(s->prev_source[i]);
        s->prev_source[i] = source[i];
        s->run_ticks[i] = changed ? s->run_ticks[i] + 1 : 0;
        /* a run's second tick is its step's other half; from its third on, it changes every tick */
        if (!changed || s->run_ticks[i] == 2) {
            continue;
        }
        if (s->last_step_tick[i] >= 0) {
            const long long gap = s->tick - s->last_step_tick[i];
            s->intervals[s->n_intervals++] = gap > 1000000 ? 1000000 : (int)gap;
            if (s->n_intervals == SETPOINT_SMOOTH_TRAINING_STEPS) {
                learn(s);
            }
        }
        s->last_step_tick[i] = s->tick;
    }
}

void setpoint_smooth_step(setpoint_smooth_t *s, const double source[3], double angle_rad[3])
{
    for (int i = 0; i < 3; ++i) {
        const double step = s->tick > 0 ? wrap_pi(angle_rad[i] - s->prev_angle[i]) : angle_rad[i];
        s->unwrapped[i] = s->tick > 0 ? s->unwrapped[i] + step : angle_rad[i];
        s->prev_angle[i] = angle_rad[i];
    }
    if (s->state == SETPOINT_SMOOTH_TRAINING) {
        count_steps(s, source);
    }
    if (s->state == SETPOINT_SMOOTH_ON) {
        for (int i = 0; i < 3; ++i) {
            /* the smoothed value on the branch the log's own angle is on */
            angle_rad[i] += biquad_step(&s->coef, &s->lp[i], s->unwrapped[i]) - s->unwrapped[i];
        }
    }
    s->tick++;
}

void setpoint_smooth_describe(const setpoint_smooth_t *s, char *buf, size_t len)
{
    switch (s->state) {
    case SETPOINT_SMOOTH_ON:
        snprintf(buf, len,
                 "setpoint smoothed: steps every %.2f ticks (a %.1f Hz link), second-order low-pass at %.1f Hz "
                 "(%.3g x the link rate, at least %.0f Hz)",
                 s->frame_ticks, s->link_hz, s->cutoff_hz, SETPOINT_SMOOTH_CUTOFF_FACTOR,
                 SETPOINT_SMOOTH_MIN_CUTOFF_HZ);
        break;
    case SETPOINT_SMOOTH_ALREADY:
        snprintf(buf, len, "setpoint not smoothed: it steps every %.2f ticks (%.1f Hz), as smooth as the log's rate",
                 s->frame_ticks, s->link_hz);
        break;
    case SETPOINT_SMOOTH_NO_LINK:
        snprintf(buf, len, "setpoint not smoothed: its steps come every %.1f ms, slower than any radio link's frames",
                 1e3 * s->frame_ticks * s->dt_s);
        break;
    default:
        snprintf(buf, len,
                 "setpoint not smoothed: %d intervals between its steps seen, %d needed to learn the link's rate",
                 s->n_intervals, SETPOINT_SMOOTH_TRAINING_STEPS);
        break;
    }
}
