/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The field's views of flight logs (response.h) written as CSVs: each log
 * read once more at its own rate, under a source name ("LOG" for the log
 * flown, a controller's name for a simulated flight's log), into DIR:
 *   step_response.csv   source,axis,t_s,step,spread
 *   freq_response.csv   source,axis,hz,gain,phase_deg,coherence
 *   noise_throttle.csv  source,signal,axis,throttle_from,throttle_to,segments,hz,psd
 *                       (signal gyro_deg_s or gyro_raw_deg_s: psd in (deg/s)^2/Hz;
 *                       command: 1/Hz)
 *   response_summary.csv source,axis,windows,rejected,steady,rise_ms,delay_ms,
 *                       overshoot_pct,freq_segments
 * Every log is read before anything is written: a refused log leaves DIR as it was.
 */
#ifndef LADRC_SIM_LOG_VIEWS_H
#define LADRC_SIM_LOG_VIEWS_H

#include <stddef.h>
#include <stdio.h>

#include "log.h"

typedef struct {
    const char *source;    /* the name in the CSVs' source column */
    sim_log_options_t log; /* dt_s 0: the log's own row period */
} sim_views_input_t;

/* The CSVs the views write, k in 0 .. SIM_VIEWS_FILES - 1. */
#define SIM_VIEWS_FILES 4
const char *sim_log_views_file(int k);

/* Reads the n logs, writes the four CSVs in dir and, when report is not
 * NULL, a line per source and axis (windows, rise, delay, overshoot).
 * 0, or -1 with err set (the log's file:line:column, or the file not written). */
int sim_log_views_write(const sim_views_input_t *in, int n, const char *dir, FILE *report, char *err, size_t len);

/* The views of the log a replay reads (source "LOG"), as above. */
int sim_log_views_of_log(const sim_log_options_t *log, const char *dir, FILE *report, char *err, size_t len);

#endif
