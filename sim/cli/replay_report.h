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

/* A controller not replayed: untunable for the airframe, or refused by the
 * library at the log's rate, and why. */
typedef struct {
    sim_controller_id_t id;
    int untunable; /* 1: untunable or refused at the log's rate; 0: the log cannot be replayed (no setpoint) */
    char reason[600];
} sim_replay_skipped_t;

/* The summary table on out; the controllers not replayed, each with its reason. */
void sim_report_replay(FILE *out, const sim_replay_t *r);
void sim_report_skipped(FILE *out, const sim_replay_skipped_t *skipped, int n_skipped);

/* replay_summary.csv and spectrum.csv at the paths given (0, or -1 with the
 * file that failed in why). The summary's last column, status, reads
 * replayed, or for a controller not replayed "untunable: " or "not
 * replayed: " and the reason (its value columns then read untunable or
 * not_replayed). */
int sim_write_replay_files(const char *summary_path, const char *spectrum_path, const sim_replay_t *r,
                           const sim_replay_skipped_t *skipped, int n_skipped, char *why, size_t why_len);

#endif
