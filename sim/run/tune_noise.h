/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario's measurement noise as the margins analysis takes it
 * (ladrc_margins_request_t angle_noise_std_rad, rate_noise_std_rad_s): the
 * predicted command noise of a controller (margins.h cmd_noise_Nm) and the
 * tuning's noise cap (tune_noise_max_Nm, tune_noise_ref) use it.
 */
#ifndef LADRC_SIM_TUNE_NOISE_H
#define LADRC_SIM_TUNE_NOISE_H

#include "ladrc/margins.h"
#include <stddef.h>

#include "scenario/scenario.h"

/* Fills req's noise from sc's [sensors] angle and rate noise (white, their
 * standard deviations per sample) with the corner at
 * LADRC_MARGINS_NOISE_CORNER_HZ (20 Hz); the other fields are kept.
 * [vibration] lines are not included (the noise is white only). */
void sim_tune_noise_request(const sim_scenario_t *sc, ladrc_margins_request_t *req);

/* Adds to req axis's recorded rate noise (the scenario's [sensors]
 * rate_noise_series, as it flies: sampled at the control period over one
 * period of the series, at most SIM_TUNE_NOISE_SERIES_S) as a coloured
 * noise: its Welch spectrum (spectrum.h) in req's rate_noise_psd. Without a
 * series nothing changes. Returns 0, or -1 with the series' located error
 * in why (req unchanged). */
#define SIM_TUNE_NOISE_SERIES_S 120.0
int sim_tune_noise_series(const sim_scenario_t *sc, int axis, ladrc_margins_request_t *req, char *why, size_t why_len);

#endif
