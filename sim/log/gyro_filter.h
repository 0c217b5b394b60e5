/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The log's own gyro filters, measured from a log that holds the gyro both
 * before and after them (Betaflight's gyroUnfilt and gyroADC): per axis,
 *
 * - the delay: the slope of the phase of the cross-spectrum from the raw
 *   to the filtered gyro's first differences (differences keep the
 *   flight's slow motion from swamping it) over the low band up to
 *   SIM_GYRO_FILTER_BAND_SHARE of the sample rate, where the loop's
 *   crossover lies: the filter's delay as a control loop below its corner
 *   sees it. The cross-spectrum comes from the cross-correlation over
 *   +-SIM_GYRO_FILTER_TAPS ticks under a Hann lag window. Its phase is
 *   untouched by noise in either gyro that the other lacks (the log's
 *   rounding to 1 deg/s), which biases a fitted impulse response;
 * - the attenuation in the vibration band: the filtered gyro's power over
 *   the raw one's at the raw gyro's vibration lines (dB; a ratio of
 *   spectra, so a notch that follows the rotors counts as it acted).
 *
 * Streaming, fixed memory (heap: three spectra per axis side).
 */
#ifndef LADRC_SIM_GYRO_FILTER_H
#define LADRC_SIM_GYRO_FILTER_H

#include "run/spectrum.h"

#define SIM_GYRO_FILTER_TAPS 64         /* lags each way: 64 ms at 1 kHz, a 16 Hz resolution */
#define SIM_GYRO_FILTER_BAND_SHARE 0.05 /* the band the delay is read in: 50 Hz at 1 kHz */

typedef struct {
    double delay_s;      /* the filter's delay at low frequency; NaN when not measured */
    double gain_low;     /* the gain at the lowest frequency read: ~1 for a low-pass chain */
    double vib_atten_db; /* power after over before the filters at the vibration lines (dB, < 0 attenuates);
                              NaN without lines */
    int n_lines;         /* the raw gyro's lines it was taken at */
} sim_gyro_filter_axis_t;

typedef struct sim_gyro_filter sim_gyro_filter_t;

/* A new measurement at sample period dt_s (heap); NULL when out of memory. */
sim_gyro_filter_t *sim_gyro_filter_new(double dt_s);
void sim_gyro_filter_free(sim_gyro_filter_t *g);

/* One tick: the gyro before and after the filters (rad/s). A non-finite
 * value restarts the differences and the spectra's segments (a gap). */
void sim_gyro_filter_add(sim_gyro_filter_t *g, const double raw_rad_s[3], const double filtered_rad_s[3]);

/* The result of axis 0 roll, 1 pitch, 2 yaw: lines are those of the raw
 * gyro standing min_ratio above its floor over [floor_lo_hz, floor_hi_hz]. */
void sim_gyro_filter_result(const sim_gyro_filter_t *g, int axis, double floor_lo_hz, double floor_hi_hz,
                            double min_ratio, sim_gyro_filter_axis_t *out);

#endif
