/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Betaflight's native blackbox log (`.bbl`, `.bfl`, `.txt` from the flight
 * controller's flash or card) decoded, streaming, into the CSV that
 * blackbox_decode writes, which the Betaflight form of the reader (log.h)
 * takes unchanged.
 *
 * A file holds one log per arming, each starting with its own header
 * (`H Product:Blackbox flight data recorder ...`, then `H name:value`
 * lines: the frames' field names, signedness, predictors and encodings,
 * the sampling intervals and the constants the predictors add). The data
 * are frames, each a marker byte and its fields: I (every field, predicted
 * from constants only), P (predicted from the last one or two main frames),
 * S (slow: flight mode and state flags), G and H (GPS, decoded and not
 * written) and E (events: a sync beep, an in-flight adjustment, logging
 * resumed, a disarm, a flight mode change, the log's end).
 *
 * Corruption is handled as blackbox_decode does: a frame that does not end
 * on another frame's marker (or the log's end), or that is longer than 256
 * bytes, is corrupt: it is counted, decoding resumes looking for a marker
 * from its second byte, and P frames are dropped until the next I frame
 * (they predict from frames lost). A main frame whose iteration or time
 * goes back or jumps (more than 5000 iterations or 10 s) is dropped the
 * same way. A log cut anywhere decodes up to its last whole frame, and
 * the statistics say where it was cut.
 *
 * The CSV, `OUT_BASE.csv`, is blackbox_decode's for that log with the unit
 * flags `--unit-vbat raw --unit-amperage raw --unit-flags raw`: the I
 * frame's fields in their order as `loopIteration, time (us), ...` (the
 * time in microseconds, 64-bit past the logger's 32-bit wrap; the gyro as
 * logged, deg/s in Betaflight; converted to `gyroADC[i] (deg/s)` when the
 * header's gyro_scale says the log holds another unit), then the last S
 * frame's fields, one row per main frame; blackbox_decode's computed
 * `energyCumulative (mAh)` is not written, nor the GPS. A row whose time
 * does not increase (equal times, a logging resume going back) is left out
 * and counted, so that the time of the rows always increases.
 */
#ifndef LADRC_SIM_LOG_BBL_H
#define LADRC_SIM_LOG_BBL_H

#include <stdio.h>

#include "log.h"
#include "log_convert.h"

typedef struct {
    int n_logs;              /* logs in the file */
    int index;               /* the one decoded, 1-based */
    long long log_offset;    /* its first byte in the file */
    long long log_bytes;     /* its length */
    long long frames[6];     /* valid frames by type: I, P, S, G, H, E */
    long long rows;          /* main frames written */
    long long corrupt;       /* frames that did not decode (skipped, decoding resumed after) */
    long long dropped;       /* main frames dropped: after a corrupt frame, or iteration/time out of line */
    long long time_repeats;  /* main frames left out: their time did not increase */
    long long skipped_bytes; /* bytes that were no frame's marker, looked past */
    int ended;               /* the log's end event was read */
    int truncated;           /* the log ends within a frame */
    long long truncated_at;  /* that frame's offset in the file */
} sim_log_bbl_stats_t;

/* Decodes log `index` (1-based; 0: the longest) of the blackbox file
 * in_path into OUT_BASE.csv. topics: unused (NULL, 0). 0, or -1 with err
 * set as `in_path: offset N: message` and nothing written. */
int sim_log_bbl_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics, int index,
                       sim_log_convert_progress_fn progress, void *progress_ctx, sim_log_error_t *err);

/* The same with the statistics of the log decoded (stats may be NULL). */
int sim_log_bbl_to_csv_stats(const char *in_path, const char *out_base, int index, sim_log_convert_progress_fn progress,
                             void *progress_ctx, sim_log_bbl_stats_t *stats, sim_log_error_t *err);

/* What the decoding met that the CSV does not show, as one line into buf
 * (the log chosen of several, corrupt frames, frames dropped, a cut): its
 * length, 0 when there is nothing to say. */
int sim_log_bbl_stats_describe(const sim_log_bbl_stats_t *st, char *buf, size_t len);

/* The same from a stream (seekable; `name` in messages) into the stream out
 * (the caller's: what was written before a refusal is the caller's to drop);
 * stats may be NULL. */
int sim_log_bbl_decode(FILE *in, const char *name, FILE *out, int index, sim_log_convert_progress_fn progress,
                       void *progress_ctx, sim_log_bbl_stats_t *stats, sim_log_error_t *err);

#endif
