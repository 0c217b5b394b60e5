/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The setpoint as a flight stack smooths it before its rate loop.
 *
 * A log's setpoint (Betaflight's `setpoint`, before its RC smoothing) holds
 * the radio link's frames: steps at the link's rate, whose edges carry
 * energy up to the loop's Nyquist frequency. Each firmware low-passes them
 * before its controllers see them; a replay that hands the controllers the
 * steps as they are charges them with noise the flight never had.
 *
 * The rule (Betaflight's automatic RC smoothing): the link's frame rate is
 * learned from the setpoint itself, the mean interval between each axis's
 * distinct steps over the first SETPOINT_SMOOTH_TRAINING_STEPS intervals (intervals
 * within 0.5-1.5x their median, so that held sticks do not count); the
 * cutoff is SETPOINT_SMOOTH_CUTOFF_FACTOR times that rate, at least
 * SETPOINT_SMOOTH_MIN_CUTOFF_HZ; the filter a second-order Butterworth
 * low-pass. A setpoint that steps every tick or more often than every 1.5
 * ticks on average is as smooth as the log can tell (the simulator's logs):
 * it passes unchanged; so does one whose steps come slower than a link
 * (more than SETPOINT_SMOOTH_MAX_FRAME_S apart: a scripted step sequence).
 * Until the rate is learned the setpoint passes unchanged with the filter
 * held settled on it, so it starts without a transient.
 *
 * The filter runs on the angles the controllers are given (for a rate
 * setpoint, its integral: the same filter on a linear signal), yaw on its
 * unwrapped increments so a wrap at +-pi is not smoothed into a sweep.
 */
#ifndef LADRC_SIM_SETPOINT_SMOOTH_H
#define LADRC_SIM_SETPOINT_SMOOTH_H

#include <stddef.h>

#include "run/biquad.h"

#define SETPOINT_SMOOTH_TRAINING_STEPS 256
/* Betaflight's cutoff factor 1.5 / (1 + rc_smoothing_auto_factor / 10) at its default factor, 30 */
#define SETPOINT_SMOOTH_CUTOFF_FACTOR 0.375
#define SETPOINT_SMOOTH_MIN_CUTOFF_HZ 15.0 /* Betaflight's floor */
#define SETPOINT_SMOOTH_MAX_FRAME_S 0.0655 /* the slowest frame Betaflight takes for a link's */

typedef enum {
    SETPOINT_SMOOTH_TRAINING = 0, /* learning the step rate: passed as is */
    SETPOINT_SMOOTH_ON,           /* low-passed at cutoff_hz */
    SETPOINT_SMOOTH_ALREADY,      /* steps every tick or nearly: passed as is */
    SETPOINT_SMOOTH_NO_LINK       /* steps too rare for a link: passed as is */
} setpoint_smooth_state_t;

typedef struct {
    double dt_s;
    setpoint_smooth_state_t state;
    double prev_source[3];             /* the signal the steps are counted on */
    long long tick, last_step_tick[3]; /* per axis */
    int run_ticks[3];                  /* ticks in a row the axis has changed */
    int n_intervals;
    int intervals[SETPOINT_SMOOTH_TRAINING_STEPS];
    double frame_ticks; /* the learned interval between the link's frames (ticks) */
    double link_hz, cutoff_hz;
    biquad_coef_t coef;
    biquad_t lp[3];
    double unwrapped[3], prev_angle[3]; /* the angles, yaw unwrapped */
} setpoint_smooth_t;

void setpoint_smooth_init(setpoint_smooth_t *s, double dt_s);

/* One tick: source[3] the signal whose steps reveal the link (the logged
 * rate setpoint, else the angle setpoint); angle_rad[3] the reference angles
 * the controllers get, smoothed in place. */
void setpoint_smooth_step(setpoint_smooth_t *s, const double source[3], double angle_rad[3]);

/* One line saying what was applied (for the replay's outputs). */
void setpoint_smooth_describe(const setpoint_smooth_t *s, char *buf, size_t len);

#endif
