/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A log's attitude setpoints as a recorded series a scenario flies
 * (`[reference] series`, docs/scenario-format.md): the log's reference
 * angles (its attitude setpoint, or the integral of its rate setpoint from
 * the first tick, yaw not wrapped) every tick, from the log's start; after
 * a gap the reader skipped (log.h) the times go on a tick apart.
 */
#ifndef LADRC_SIM_LOG_REFERENCE_H
#define LADRC_SIM_LOG_REFERENCE_H

#include <stddef.h>

#include "log.h"

/* Writes `t [s], roll [rad], pitch [rad], yaw [rad]` rows for the first
 * max_s seconds of the log (0: all of it) to path, through path.tmp renamed
 * at the end (a refused log leaves nothing). The seconds written go to
 * *written_s. 0, or -1 with err set: the log's file:line:column, a log
 * without a setpoint (naming the fields that would give one), or the file. */
int sim_log_reference_write(const sim_log_options_t *log, double max_s, const char *path, double *written_s, char *err,
                            size_t len);

#endif
