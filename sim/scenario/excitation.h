/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The [excitation] section's chirp (docs/scenario-format.md): a logarithmic
 * (exponential) frequency sweep from f0 to f1 over T seconds,
 *
 *     phase(t') = 2 pi f0 T / ln(f1 / f0) (exp(t' ln(f1 / f0) / T) - 1),
 *     value(t') = amplitude sin(phase(t'))   for 0 <= t' < T, else 0,
 *
 * t' the time since the chirp's start; its frequency phase'(t') / (2 pi) is
 * f0 exp(t' ln(f1 / f0) / T), f0 at the start and f1 at the end. The value
 * is a normalised command: the runner adds value times the axis's
 * sim_setup_authority_Nm (setup.h) to the controller's torque before the
 * mixer, as the system-identification injections of PX4 and Betaflight do.
 */
#ifndef LADRC_SIM_EXCITATION_H
#define LADRC_SIM_EXCITATION_H

#include "scenario.h"

/* The chirp's value at t_since_start_s (above); 0 outside [0, duration_s). */
double sim_chirp_value(double amplitude, double f0_hz, double f1_hz, double duration_s, double t_since_start_s);

/* Its instantaneous frequency (Hz) at t_since_start_s, within [0, duration_s]. */
double sim_chirp_frequency_hz(double f0_hz, double f1_hz, double duration_s, double t_since_start_s);

/* The axes sc's excitation sweeps, in order (1, or 3 for axis = all), and
 * the time the last chirp ends (s). */
int sim_excitation_axes(const sim_scenario_t *sc);
double sim_excitation_end_s(const sim_scenario_t *sc);

/* The normalised command sc's excitation adds at t_s on roll, pitch and yaw
 * (0 on every axis without [excitation], and outside the chirps): axis =
 * all sweeps roll from start_s, pitch from start_s + duration_s, yaw from
 * start_s + 2 duration_s. */
void sim_excitation_at(const sim_scenario_t *sc, double t_s, double command[3]);

#endif
