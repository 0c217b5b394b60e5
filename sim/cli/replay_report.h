/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What ladrc_replay writes and prints (docs/flight-logs.md): the
 * identification's table and CSV, the replay's time series, its summary per
 * controller and axis, and the spectra.
 */
#ifndef LADRC_SIM_REPLAY_REPORT_H
#define LADRC_SIM_REPLAY_REPORT_H

#include <stdio.h>

#include "log/airframe.h"
#include "log/replay.h"

/* The identification as a table on out, with its warnings. */
void sim_report_identification(FILE *out, const sim_airframe_t *a);

/* identification.csv: one row per axis. 0, or -1 when it cannot be written. */
int sim_write_identification_csv(const char *path, const sim_airframe_t *a);

/* The time series' header and one tick's row. */
void sim_replay_csv_header(FILE *f, const sim_replay_t *r);
void sim_replay_csv_row(FILE *f, const sim_replay_t *r, const sim_log_sample_t *s, const sim_replay_tick_t *t);

/* The summary table on out, and replay_summary.csv and spectrum.csv in dir
 * (0, or -1 with the file that failed in why); the untunable controllers
 * (not replayed) are rows of replay_summary.csv whose values read
 * untunable. */
void sim_report_replay(FILE *out, const sim_replay_t *r);
int sim_write_replay_files(const char *dir, const sim_replay_t *r, const sim_controller_id_t *untunable,
                           int n_untunable, char *why, size_t why_len);

#endif
