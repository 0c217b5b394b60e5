/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Outliers of a flight log, found and repaired as the log streams by: a
 * damaged blackbox frame gives a cell of full scale (a gyro at 2000 or
 * 32767 deg/s, a PID sum at 32767) that one sample among thousands turns
 * an identification's b0 and its gyro's noise floor into nonsense.
 *
 * Each channel (per axis: the gyro, the gyro before the log's filters, the
 * command, the rate setpoint) is judged on its own, on a robust scale s of
 * its increments over a block of SIM_LOG_OUTLIER_BLOCK samples: the larger
 * of 1.4826 x their median absolute value and 0.608 x their 90th
 * percentile (each the standard deviation on Gaussian noise; the second
 * still sees a quantised signal that holds most ticks, and breaks down only
 * beyond 10 % of bad increments). A run of 1 to SIM_LOG_OUTLIER_RUN_MAX
 * samples is an outlier when every one of them stands more than
 * SIM_LOG_OUTLIER_K s from both the sample kept before the run and the
 * sample after it, and those two agree within K s: a spike that leaves and
 * comes back. A step (the signal stays) or a fast ramp (the two ends
 * disagree) is motion, never an outlier. The run is confirmed on the scale
 * of the increments SIM_LOG_OUTLIER_LOCAL ticks either side of it (a burst
 * of vibration is no spike), and the setpoint's scale is at least its
 * gyro's (a stick's held steps, most increments 0, are moves on the gyro's
 * scale). The run is replaced by the straight line between its two
 * neighbours, and counted: a gap instead would cost the identification
 * its filters' settling, some 150 ticks, per outlier (at 1 % corrupt no
 * segment would remain), while one tick interpolated is below the band it
 * fits (under 40 Hz at 1 kHz). Not judged: the first sample of the log and
 * after a gap (no sample before it), a channel whose block holds still 9
 * ticks in 10 or has under SIM_LOG_OUTLIER_MIN_INCREMENTS finite
 * increments.
 *
 * The samples come out in order, all of them, at most
 * SIM_LOG_OUTLIER_BLOCK + SIM_LOG_OUTLIER_RUN_MAX + 2 SIM_LOG_OUTLIER_LOCAL
 * pushes late (the block's scale and the look-ahead a run's end and its
 * context need). Memory is fixed: a log of any length streams.
 */
#ifndef LADRC_SIM_LOG_OUTLIER_H
#define LADRC_SIM_LOG_OUTLIER_H

#include <stddef.h>

#include "log.h"

/* K: on white Gaussian noise a sample stands 7 sigma of the increments
 * from both its neighbours on the same side with probability 1e-16 (the
 * two increments correlate at 0.5), at 30 below 1e-190: no false rejection
 * of noise at either. Flight data's tails are not Gaussian: on the
 * committed real logs the farthest a real sample stood out was 10.2 sigma
 * (a knock on a bench, a pulse 4 ticks wide at 83 Hz), which K = 30 leaves
 * with a margin of 3. The spikes of a damaged frame (a gyro at 2000 or
 * 32767 deg/s, a PID sum at 32767) stood 2,700-54,000 sigma out. */
#define SIM_LOG_OUTLIER_K 30.0
#define SIM_LOG_OUTLIER_BLOCK 256         /* samples per scale estimate: 0.26 s at 1 kHz */
#define SIM_LOG_OUTLIER_RUN_MAX 3         /* the longest run of bad samples repaired */
#define SIM_LOG_OUTLIER_MIN_INCREMENTS 16 /* fewer finite increments in a block: not judged */
/* A run the block's scale finds is confirmed against the increments this
 * many ticks either side of it (a burst of vibration the block's scale
 * averages away is not a spike). */
#define SIM_LOG_OUTLIER_LOCAL 16
#define SIM_LOG_OUTLIER_LOCATED 3 /* outliers located per axis in the report */
/* A share of outliers above this (one in a thousand) is a warning: the log may be damaged. */
#define SIM_LOG_OUTLIER_WARN_SHARE 0.001

typedef enum {
    SIM_LOG_OUTLIER_GYRO = 0,
    SIM_LOG_OUTLIER_GYRO_RAW,
    SIM_LOG_OUTLIER_COMMAND,
    SIM_LOG_OUTLIER_SETPOINT,
    SIM_LOG_OUTLIER_CHANNELS
} sim_log_outlier_channel_t;

typedef struct {
    double t_s;   /* the sample's time */
    double value; /* as logged: rad/s for the rates, normalised for the command */
    int channel;  /* sim_log_outlier_channel_t */
} sim_log_outlier_at_t;

typedef struct {
    long long samples;     /* ticks judged */
    long long rejected[3]; /* ticks of each axis with a sample replaced */
    int n_located[3];
    sim_log_outlier_at_t located[3][SIM_LOG_OUTLIER_LOCATED]; /* the first ones, in time order */
} sim_log_outliers_t;

typedef struct sim_log_despike sim_log_despike_t;

/* A new filter for a log with the fields `has` (SIM_LOG_HAS_*); NULL when out of memory. */
sim_log_despike_t *sim_log_despike_new(unsigned has);
void sim_log_despike_free(sim_log_despike_t *d);

/* One sample in; then take what is ready with sim_log_despike_pop until it
 * returns 0. 0, or -1 (the sample not taken) when the samples ready were
 * not all taken first. */
int sim_log_despike_push(sim_log_despike_t *d, const sim_log_sample_t *s);
/* The end of the log: every sample pushed becomes ready. */
void sim_log_despike_finish(sim_log_despike_t *d);
/* The next sample out, repaired: 1, or 0 when none is ready. */
int sim_log_despike_pop(sim_log_despike_t *d, sim_log_sample_t *out);

/* sim_log_next through the filter: the log's next sample, repaired (1), 0
 * at its end, -1 with the reader's error; d new for each reading of the log. */
int sim_log_next_repaired(sim_log_t *log, sim_log_despike_t *d, sim_log_sample_t *s, sim_log_error_t *err);

/* The count and places of what was replaced, over the samples popped. */
void sim_log_despike_outliers(const sim_log_despike_t *d, sim_log_outliers_t *out);

/* The channel's name ("gyro", "raw gyro", "command", "setpoint"). */
const char *sim_log_outlier_channel_name(int channel);

/* The report of one axis: "roll: 1 sample of 4,000 rejected as an outlier
 * (raw gyro 2000 deg/s at t = 2.000 s)"; "" when none was. Returns the
 * length snprintf would have written. */
int sim_log_outliers_describe(const sim_log_outliers_t *o, int axis, char *buf, size_t len);

/* 1 when the axis's share of outliers is above SIM_LOG_OUTLIER_WARN_SHARE. */
int sim_log_outliers_many(const sim_log_outliers_t *o, int axis);

#endif
