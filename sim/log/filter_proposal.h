/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The gyro filter stage a flight log asks for (docs/flight-logs.md, "Noise
 * and the filter stage"): from the spectrum of the gyro before the log's
 * filters, notches at the vibration lines (centre at the peak, width from
 * the peak's own width), RPM notches on the harmonics of the rotors' speed
 * when the log reports it, and a second-order low-pass whose corner is the
 * lowest that keeps the whole stage's phase cost at the loop's crossover
 * within SIM_FILTER_PHASE_BUDGET_DEG. Fixed notches are taken strongest
 * line first while the stage stays within that budget; the RPM bank is
 * taken whole (its cost is reported). The stage is the library's
 * (gyro_filter.h); its response is evaluated from the sections the library
 * derives, so what is proposed is what flies.
 */
#ifndef LADRC_SIM_FILTER_PROPOSAL_H
#define LADRC_SIM_FILTER_PROPOSAL_H

#include <stdio.h>

#include "ladrc/gyro_filter.h"
#include "run/spectrum.h"

/* The phase (deg) the stage may cost at the crossover: 6 deg of a 45 deg
 * phase margin target (13 %), about one tick of delay at 30 rad/s and 1 kHz
 * times three: the tuning then loses little bandwidth to the filter. */
#define SIM_FILTER_PHASE_BUDGET_DEG 6.0
/* A vibration line: a peak this many times the floor's PSD (10 dB), as the identification's. */
#define SIM_FILTER_LINE_RATIO 10.0
/* Lines are searched from this frequency (Hz) up: above the command-noise corner (20 Hz),
 * where a pilot's manoeuvres and an identification chirp (to 40 Hz) still stand out. */
#define SIM_FILTER_LINE_MIN_HZ 30.0
/* A line's width: where its PSD above the floor falls to this share of its peak's (-10 dB). */
#define SIM_FILTER_WIDTH_SHARE 0.1
/* The notches' Q is kept in this range: a peak wider than Q 2 (half its
 * centre) is a hump of the flight's own motion or propwash, the low-pass's
 * to take, and a notch that wide eats the phase at the crossover; narrower
 * than 20 a drifting line walks out of it. */
#define SIM_FILTER_Q_MIN 2.0
#define SIM_FILTER_Q_MAX 20.0
/* A line is the RPM bank's when within this share of a harmonic of the rotors' mean speed. */
#define SIM_FILTER_RPM_MATCH 0.06

typedef struct {
    double hz, width_hz, power; /* centre, width at SIM_FILTER_WIDTH_SHARE, summed power over the axes ((rad/s)^2) */
    int harmonic; /* > 0: the RPM bank's harmonic that covers it; 0: a fixed notch, -1: left out (no room, too
                     wide, or over the phase budget) */
} sim_filter_line_t;

#define SIM_FILTER_MAX_LINES (3 * SIM_SPECTRUM_MAX_LINES)

typedef struct {
    ladrc_gyro_filter_config_t cfg;
    double rotor_hz;               /* the rotors' speed the RPM notches are evaluated at (Hz); 0: no RPM bank */
    double crossover_rad_s;        /* the crossover the low-pass is sized for */
    double band_lo_hz, band_hi_hz; /* the vibration band: the lines' span, or the floor band without lines */
    int n_lines;
    sim_filter_line_t lines[SIM_FILTER_MAX_LINES];
} sim_filter_proposal_t;

/* The stage's complex response at hz: gain and phase (rad, summed over the
 * sections, so not wrapped), RPM notches held at rotor_hz. Returns 0, or -1
 * when cfg is refused by ladrc_gyro_filter_init. */
int sim_filter_response(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, double hz, double *gain,
                        double *phase_rad);

/* The stage's phase at w_rad_s as a cost (deg, a lag positive); +INFINITY
 * when cfg is refused. */
double sim_filter_phase_cost_deg(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, double w_rad_s);

/* The attenuation (dB) of the stage over [lo_hz, hi_hz) of the spectrum
 * `in`: its power there over the power of |H|^2 times it. */
double sim_filter_band_attenuation_db(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, const sim_spectrum_t *in,
                                      double lo_hz, double hi_hz);

/* The measured attenuation (dB) from the spectrum `in` to `out` over [lo_hz, hi_hz). */
double sim_filter_measured_attenuation_db(const sim_spectrum_t *in, const sim_spectrum_t *out, double lo_hz,
                                          double hi_hz);

/* The crossover (rad/s) a loop with this motor lag and delay reaches at a
 * 45 deg phase margin, about: 1 / (lag + (delay + 1/2) dt) (the hold's half
 * tick included). The tuned crossovers of the simulator's chirp flight
 * (21-34 rad/s) bracket its 28 rad/s. NAN when the lag or the delay is not
 * known (not finite, negative: not identified). */
double sim_filter_crossover_estimate(double lag_s, int delay_ticks, double dt_s);

/* The crossover a stage is judged at when none is known (rad/s). */
#define SIM_FILTER_CROSSOVER_DEFAULT_RAD_S 30.0

/* Proposes the stage from the three axes' pre-filter gyro spectra at dt_s,
 * the rotors' mean speed (Hz; 0 when the log has none: every line a fixed
 * notch) and their number (each rotor its RPM notches), and the crossover to keep the phase cost at. Lines beyond
 * LADRC_GYRO_FILTER_MAX_NOTCHES fixed notches are left out, the weakest
 * first. Returns 0, or -1 (why says) when the spectra hold no estimate. */
int sim_filter_propose(const sim_spectrum_t raw[3], double dt_s, double rotor_hz, int rotors, double crossover_rad_s,
                       sim_filter_proposal_t *p, char *why, size_t why_len);

/* The stage as a scenario's [filter] section (docs/scenario-format.md); RPM
 * notches are written with their keys. */
void sim_filter_write_ini(FILE *f, const ladrc_gyro_filter_config_t *cfg);

#endif
