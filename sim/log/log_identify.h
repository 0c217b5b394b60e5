/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A log's airframe: the identification's passes over a flight log (ident.h):
 * the first streams the log through the reader (log.h) and keeps each
 * tick's gyro, command and setpoint in a temporary file (ident_cache.h),
 * which the later passes read back; the gyro's noise floor and vibration
 * lines from its spectrum; and, when the log has the gyro both before and
 * after its filters, their delay and attenuation (gyro_filter.h). The
 * identification takes the gyro before the log's filters when the log has
 * it (the plant's own response), else the filtered one.
 */
#ifndef LADRC_SIM_LOG_IDENTIFY_H
#define LADRC_SIM_LOG_IDENTIFY_H

#include <stddef.h>

#include "airframe.h"
#include "log.h"

/* Progress while a pass reads: its number and name, the share of the bytes read. */
typedef void (*sim_log_progress_fn)(void *ctx, int pass, int passes, const char *what, double fraction);

typedef struct {
    sim_log_options_t log;
    double prefilter_hz; /* sim_ident_options_t's; 0: its default */
    double lag_max_s;
    int delay_max_ticks;          /* < 0: the default */
    const char *noise_series;     /* a path to write the gyro's noise to, for the scenario; NULL: none */
    double noise_series_s;        /* its length (s): the log's first this many seconds */
    sim_log_progress_fn progress; /* may be NULL */
    void *progress_ctx;
} sim_log_identify_options_t;

/* The noise series' high-pass corner (Hz) at sample rate fs: the floor band's low edge. */
double sim_log_noise_corner_hz(double fs_hz);

/* Identifies the log's airframe into *out (and the reader's stats of the
 * first pass into *stats when not NULL). Returns 0, or -1 with the message
 * in err (a log the reader refuses, a log without gyro or command, a noise
 * file that cannot be written). */
int sim_log_identify(const sim_log_identify_options_t *o, sim_airframe_t *out, sim_log_stats_t *stats, char *err,
                     size_t err_len);

#endif
