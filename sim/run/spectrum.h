/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Power spectral density of a stream, by Welch's method: segments of
 * SIM_SPECTRUM_N samples, Hann window, half overlap, averaged periodograms,
 * one-sided. Fixed memory whatever the stream's length; the flight-log
 * tools use it for the gyro's noise floor and vibration lines and for the
 * command's noise per frequency band.
 */
#ifndef LADRC_SIM_SPECTRUM_H
#define LADRC_SIM_SPECTRUM_H

#define SIM_SPECTRUM_N 1024 /* samples per segment: 0.98 Hz bins at 1 kHz */
#define SIM_SPECTRUM_BINS (SIM_SPECTRUM_N / 2 + 1)
#define SIM_SPECTRUM_MAX_LINES 8

typedef struct {
    double fs_hz;
    double window[SIM_SPECTRUM_N];                                         /* Hann */
    double twiddle_re[SIM_SPECTRUM_N / 2], twiddle_im[SIM_SPECTRUM_N / 2]; /* e^(-2 pi i k / N) */
    double window_power;                                                   /* sum of window^2 */
    double buf[SIM_SPECTRUM_N];                                            /* the current segment, as a ring */
    int fill;                          /* samples in buf; a segment each SIM_SPECTRUM_N / 2 after the first */
    long long pushed;                  /* since the start or the last break */
    double sum_psd[SIM_SPECTRUM_BINS]; /* sum over segments of the periodogram (unit^2/Hz) */
    long segments;
} sim_spectrum_t;

/* A spectral line: a local peak of the PSD standing out of the floor. */
typedef struct {
    double hz;
    double rms;         /* the line's rms amplitude (unit): its peak's bins above the floor */
    double above_floor; /* its peak PSD over the floor (ratio) */
} sim_spectrum_line_t;

void sim_spectrum_init(sim_spectrum_t *s, double fs_hz);
void sim_spectrum_push(sim_spectrum_t *s, double x);

/* A break in the stream (a gap in a log): the samples of the segment under
 * way are dropped and the next segment starts with the next sample, so that
 * no periodogram spans the break; the segments averaged so far stay. Spectra
 * fed in lockstep stay so when broken at the same sample. */
void sim_spectrum_break(sim_spectrum_t *s);

/* x[i] into s[i] for i < n, the same as sim_spectrum_push on each; spectra
 * of the same rate fed in lockstep share their FFTs two by two (one complex
 * transform of two real segments), which halves their cost. */
void sim_spectrum_push_many(sim_spectrum_t *const *s, const double *x, int n);

/* Segments averaged so far (0: no estimate yet, fewer than SIM_SPECTRUM_N samples). */
long sim_spectrum_segments(const sim_spectrum_t *s);

/* The one-sided PSD at bin k (unit^2/Hz) and that bin's frequency (Hz). */
double sim_spectrum_psd(const sim_spectrum_t *s, int k);
double sim_spectrum_hz(const sim_spectrum_t *s, int k);

/* The rms (unit) of the stream's content between f_lo_hz and f_hi_hz
 * (bins whose centre lies in [f_lo, f_hi), the mean removed: bin 0 left out). */
double sim_spectrum_band_rms(const sim_spectrum_t *s, double f_lo_hz, double f_hi_hz);

/* The noise floor: the median PSD over [f_lo_hz, f_hi_hz] (unit^2/Hz), robust
 * to the lines that stand out of it. NaN without an estimate. */
double sim_spectrum_floor(const sim_spectrum_t *s, double f_lo_hz, double f_hi_hz);

/* The lines above f_lo_hz whose peak stands min_ratio times above the floor
 * `floor_psd`, strongest first; returns how many (at most max). */
int sim_spectrum_lines(const sim_spectrum_t *s, double f_lo_hz, double floor_psd, double min_ratio,
                       sim_spectrum_line_t *lines, int max);

#endif
