/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_replay's noise stage (docs/flight-logs.md, "Noise and the filter
 * stage"): before the airframe is written, the log's noise (log_noise.h)
 * sets the LADRC family's command-noise cap and the proposed gyro filter
 * stage (filter_proposal.h); after the replay, what the tuning predicted
 * against what the replay measured and what the log's controller did.
 */
#ifndef LADRC_SIM_REPLAY_NOISE_H
#define LADRC_SIM_REPLAY_NOISE_H

#include <stddef.h>
#include <stdio.h>

#include "log/airframe.h"
#include "log/log.h"
#include "log/replay.h"
#include "scenario/scenario.h"

/* Measures the log (one pass as opt reads it), sets a's log_cmd_noise (when
 * the log has a command) and its proposed filter stage, and prints both to
 * out. Returns 0, or -1 with the reader's located message in err. */
int sim_replay_noise_stage(const sim_log_options_t *opt, sim_airframe_t *a, FILE *out, char *err, size_t err_len);

/* Per controller and axis: the command noise above 20 Hz the tuning
 * predicted (normalised by the replay's authority), the replay's, and the
 * log's; the LADRC family's quietest against the log's on every axis. */
void sim_replay_noise_report(FILE *out, const sim_scenario_t *sc, const sim_replay_t *r);

#endif
