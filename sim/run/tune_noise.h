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
#include "scenario/scenario.h"

/* Fills req's noise from sc's [sensors] angle and rate noise (white, their
 * standard deviations per sample) with the corner at
 * LADRC_MARGINS_NOISE_CORNER_HZ (20 Hz); the other fields are kept.
 * [vibration] lines are not included (the noise is white only). */
void sim_tune_noise_request(const sim_scenario_t *sc, ladrc_margins_request_t *req);

#endif
