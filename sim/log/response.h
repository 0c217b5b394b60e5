/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the field's tuning tools show of a flight log, from its rate
 * setpoint, gyro, command and throttle, streamed in fixed memory:
 *
 * - the step response setpoint -> gyro, as PIDtoolbox and PID-Analyzer
 *   estimate it: 2 s Hann windows every 0.5 s, those whose setpoint reaches
 *   20 deg/s, each deconvolved (Wiener: H = Y X* / (|X|^2 + lambda(f)),
 *   lambda the window's mean input power below 25 Hz times a noise-to-signal
 *   ratio of 1e-4 that rises as (f / 25 Hz)^8 above), the step the cumulative
 *   sum of the impulse response over 0.5 s; a window whose step does not stay
 *   within 0.5-3 over 0.2-0.5 s is dropped (PIDtoolbox's check); mean and
 *   spread (standard deviation) over the windows kept;
 * - the closed-loop frequency response setpoint -> gyro (Welch's H1 =
 *   Sxy / Sxx, Hann segments of about 1 s, half overlap, the same 20 deg/s
 *   gate) with its coherence |Sxy|^2 / (Sxx Syy);
 * - the noise against throttle: Welch spectra of the gyro (used and before
 *   the filters) and of the command over 0.25 s Hann segments, binned by the
 *   segment's mean throttle into tenths (PID-Analyzer's noise view).
 */
#ifndef LADRC_SIM_RESPONSE_H
#define LADRC_SIM_RESPONSE_H

#include "log.h"

#define SIM_RESPONSE_WINDOW_S 2.0         /* deconvolution window (PIDtoolbox: 2 s) */
#define SIM_RESPONSE_HOP_S 0.5            /* a window every 0.5 s: 75 % overlap */
#define SIM_RESPONSE_LENGTH_S 0.5         /* the step response's length (both tools: 0.5 s) */
#define SIM_RESPONSE_MIN_INPUT_DEG_S 20.0 /* a window's setpoint must reach this (both tools) */
#define SIM_RESPONSE_CUTOFF_HZ 25.0       /* PID-Analyzer's cut: the input holds little above it */
#define SIM_RESPONSE_NSR 0.0001           /* noise-to-signal ratio below the cut (-40 dB) */
#define SIM_RESPONSE_NSR_ORDER 8          /* its rise above the cut: 80 dB a decade */
#define SIM_RESPONSE_STEADY_FROM_S 0.2    /* the steady part of the step: 0.2-0.5 s */
#define SIM_RESPONSE_STEADY_MIN 0.5       /* PIDtoolbox's quality check on it */
#define SIM_RESPONSE_STEADY_MAX 3.0
#define SIM_RESPONSE_FREQ_SEGMENT_S 1.0   /* H1 segments: the power of two of ticks nearest above */
#define SIM_RESPONSE_NOISE_SEGMENT_S 0.25 /* noise segments (PID-Analyzer: 0.3 s) */
#define SIM_RESPONSE_THROTTLE_BINS 10     /* tenths of throttle */

/* The noise view's signals. */
typedef enum {
    SIM_NOISE_GYRO = 0,
    SIM_NOISE_GYRO_RAW = 1,
    SIM_NOISE_COMMAND = 2,
    SIM_NOISE_SIGNALS = 3
} sim_noise_signal_t;

typedef struct sim_response sim_response_t; /* heap; host only */

/* The step response of one axis and its figures (NaN without windows). */
typedef struct {
    int windows;          /* windows kept */
    int rejected;         /* windows past the 20 deg/s gate that failed the quality check */
    int n;                /* samples of mean and spread, from t = 0 every dt */
    const double *mean;   /* the step (gyro per setpoint: 1 tracks) */
    const double *spread; /* its standard deviation over the windows */
    double steady;        /* mean over 0.2-0.5 s */
    double rise_s;        /* 10 % to 90 % of steady */
    double delay_s;       /* to 50 % of steady */
    double overshoot;     /* peak over steady, less 1 (0.1: 10 %); 0 when none */
} sim_step_response_t;

/* A reader of ticks at dt_s; NULL when dt_s is not positive or memory runs out. */
sim_response_t *sim_response_new(double dt_s);
void sim_response_free(sim_response_t *r);

/* One tick; `has` the log's SIM_LOG_HAS_* (a field absent is not used). */
void sim_response_push(sim_response_t *r, const sim_log_sample_t *s, unsigned has);

double sim_response_dt_s(const sim_response_t *r);

/* The SIM_LOG_HAS_* of the ticks pushed (0 before the first). */
unsigned sim_response_has(const sim_response_t *r);

/* The step response of axis 0..2, its mean and spread computed into r's
 * arrays from the sums (valid until the next call, push or free). */
void sim_response_step(sim_response_t *r, int axis, sim_step_response_t *out);

/* The frequency response: bins 0..n-1 (up to Nyquist), segments used, and
 * per bin its frequency, gain (gyro per setpoint), phase and coherence. */
int sim_response_freq_bins(const sim_response_t *r);
long sim_response_freq_segments(const sim_response_t *r, int axis);
void sim_response_freq(const sim_response_t *r, int axis, int k, double *hz, double *gain, double *phase_rad,
                       double *coherence);

/* The noise view: bins 0..n-1, segments per throttle bin, and the PSD of a
 * signal (gyro: (rad/s)^2/Hz; command: 1/Hz) at bin k, throttle bin b (NaN
 * without segments there or without the signal in the log). */
int sim_response_noise_bins(const sim_response_t *r);
double sim_response_noise_hz(const sim_response_t *r, int k);
long sim_response_noise_segments(const sim_response_t *r, int throttle_bin);
double sim_response_noise_psd(const sim_response_t *r, sim_noise_signal_t sig, int axis, int throttle_bin, int k);

/* The figures of a step (steady, rise, delay, overshoot) from its samples at dt_s. */
void sim_step_figures(const double *step, int n, double dt_s, sim_step_response_t *out);

#endif
