/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A flight log's noise, measured in one streamed pass: per axis the Welch
 * spectra (spectrum.h) of the logged command, the gyro the controller used
 * and the gyro before the log's filters, and the phase of the log's own
 * filter chain (gyro after it against gyro before it) at a loop's
 * crossover. The logged controller's command noise above LADRC_MARGINS_NOISE_CORNER_HZ is what the replay summary's
 * noise_above_20hz column measures for a controller (docs/flight-logs.md,
 * "Noise and the filter stage").
 */
#ifndef LADRC_SIM_LOG_NOISE_H
#define LADRC_SIM_LOG_NOISE_H

#include <stddef.h>

#include "log.h"
#include "log_outlier.h"
#include "run/spectrum.h"

/* Samples per block of the phase probe: 1.02 s at 1 kHz, a resolution of
 * 1 Hz about the probed frequency, finer than any crossover's 3-6 Hz. */
#define SIM_PHASE_PROBE_N 1024

/* The phase of a stream y against a stream x (y a filtered x) at one
 * frequency: per block of SIM_PHASE_PROBE_N samples the Hann-windowed
 * Fourier coefficient of each there, their cross-power summed over blocks
 * (H = sum Y X* / sum |X|^2, the cross-spectral estimate). */
typedef struct {
    double w_rad_per_tick;
    double xr, xi, yr, yi; /* the current block's coefficients */
    int fill;
    double sxy_re, sxy_im, sxx;
    long blocks;
} sim_phase_probe_t;

/* The delay (s) a phase cost (deg, a lag positive) is at w_rad_s. */
static inline double sim_phase_delay_s(double phase_deg, double w_rad_s)
{
    return phase_deg * (3.14159265358979323846 / 180.0) / w_rad_s;
}

void sim_phase_probe_init(sim_phase_probe_t *p, double w_rad_s, double dt_s);
void sim_phase_probe_push(sim_phase_probe_t *p, double x, double y);
/* y's phase against x's at the frequency (rad, a lag negative, in (-pi, pi]); NaN before a whole block. */
double sim_phase_probe_rad(const sim_phase_probe_t *p);

typedef struct {
    double dt_s;
    unsigned has; /* SIM_LOG_HAS_* */
    long long ticks;
    sim_spectrum_t command[3], gyro[3], gyro_raw[3]; /* gyro_raw: when has & SIM_LOG_HAS_GYRO_RAW */
    double probe_rad_s;                              /* the frequency the chain's phase is probed at */
    sim_phase_probe_t chain[3];                      /* from the gyro before the filters to the gyro after them */
    int rotors;                                      /* the most rotors a tick reports a speed for */
    double rotor_hz_sum; /* mean rotor speed over the ticks and rotors that report one (Hz) */
    long long rotor_samples;
    sim_log_outliers_t outliers; /* the samples replaced as outliers before the spectra (log_outlier.h) */
} sim_log_noise_t;

/* Reads the whole log (as opt reads it), its outliers repaired (log_outlier.h), into *n, the chain's phase probed at probe_rad_s. Returns 0, or -1 with the
 * reader's located message in err (nothing measured). */
int sim_log_noise_measure(const sim_log_options_t *opt, double probe_rad_s, sim_log_noise_t *n, char *err,
                          size_t err_len);

/* The logged command's rms above f_lo_hz on axis i (normalised command):
 * the replay summary's definition (sim_spectrum_band_rms up to Nyquist). */
double sim_log_noise_command_above(const sim_log_noise_t *n, int axis, double f_lo_hz);

/* The log's filter chain on axis i at the probed frequency: its phase
 * cost (deg, a lag positive) and the delay that phase is (s); NaN without
 * the gyro before the filters or a whole probe block. */
double sim_log_noise_chain_phase_deg(const sim_log_noise_t *n, int axis);
double sim_log_noise_chain_delay_s(const sim_log_noise_t *n, int axis);

/* The mean rotor speed the log reports (Hz); 0 when it has none. */
double sim_log_noise_rotor_hz(const sim_log_noise_t *n);

#endif
