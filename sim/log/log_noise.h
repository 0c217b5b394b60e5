/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A flight log's noise, measured in one streamed pass: per axis the Welch
 * spectra (spectrum.h) of the logged command, the gyro the controller used
 * and the gyro before the log's filters, and the delay of the log's own
 * filter chain from the gyro before it to the gyro after it (the lag that
 * maximises their cross-correlation). The logged controller's command noise
 * above LADRC_MARGINS_NOISE_CORNER_HZ is what the replay summary's
 * noise_above_20hz column measures for a controller (docs/flight-logs.md,
 * "Noise and the filter stage").
 */
#ifndef LADRC_SIM_LOG_NOISE_H
#define LADRC_SIM_LOG_NOISE_H

#include <stddef.h>

#include "log.h"
#include "spectrum.h"

/* Lags (ticks) the cross-correlation tries for the log's chain's delay: up
 * to 31 ms at 1 kHz, beyond any flight stack's gyro filters (2-10 ms). */
#define SIM_LOG_NOISE_LAGS 32

/* The delay from a stream x to a stream y (y a filtered x): the lag that
 * maximises their cross-covariance, parabola-interpolated. */
typedef struct {
    double xcorr[SIM_LOG_NOISE_LAGS]; /* sum over ticks of y[k] x[k - j] */
    double ring[SIM_LOG_NOISE_LAGS];  /* x's latest */
    double x_sum, y_sum;
    long long n;
} sim_lag_t;

void sim_lag_push(sim_lag_t *l, double x, double y);
/* The delay (ticks); NaN with fewer than 4 SIM_LOG_NOISE_LAGS samples. */
double sim_lag_ticks(const sim_lag_t *l);

typedef struct {
    double dt_s;
    unsigned has; /* SIM_LOG_HAS_* */
    long long ticks;
    sim_spectrum_t command[3], gyro[3], gyro_raw[3]; /* gyro_raw: when has & SIM_LOG_HAS_GYRO_RAW */
    sim_lag_t chain[3];                              /* from the gyro before the filters to the gyro after them */
    int rotors;          /* the most rotors a tick reports a speed for */
    double rotor_hz_sum; /* mean rotor speed over the ticks and rotors that report one (Hz) */
    long long rotor_samples;
} sim_log_noise_t;

/* Reads the whole log (as opt reads it) into *n. Returns 0, or -1 with the
 * reader's located message in err (nothing measured). */
int sim_log_noise_measure(const sim_log_options_t *opt, sim_log_noise_t *n, char *err, size_t err_len);

/* The logged command's rms above f_lo_hz on axis i (normalised command):
 * the replay summary's definition (sim_spectrum_band_rms up to Nyquist). */
double sim_log_noise_command_above(const sim_log_noise_t *n, int axis, double f_lo_hz);

/* The log's filter chain on axis i (needs the gyro before the filters):
 * its delay (s) at the cross-correlation's peak, parabola-interpolated;
 * NaN without the gyro before the filters. */
double sim_log_noise_chain_delay_s(const sim_log_noise_t *n, int axis);

/* The mean rotor speed the log reports (Hz); 0 when it has none. */
double sim_log_noise_rotor_hz(const sim_log_noise_t *n);

#endif
