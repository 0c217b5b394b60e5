/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * PX4 ULog (.ulg) decoded as a stream into the CSVs ulog2csv writes: one
 * file per logged topic and instance, `<out_base>_<topic>_<multi_id>.csv`
 * ('/' in a topic's name written '_'), ulog2csv's column names
 * (`timestamp` first, `xyz[0]`, `esc[0].esc_rpm`, a char array as one text
 * column), the values as full-precision decimals (integers exactly, float
 * to 9 significant digits and double to 17, each of which reads back to the
 * logged value; NaN as `nan`). Text cells are the chars up to the first NUL,
 * a comma, a control or a non-ASCII byte written `?` (ulog2csv writes them
 * as they are, which can break its rows).
 *
 * Held while decoding: the formats, the subscriptions and a read buffer,
 * never the data (a 1 GB log decodes in a few MB). Written only: the topics
 * asked for, those of them with data (a topic subscribed but never logged
 * has no file, as with ulog2csv), rows whose timestamp increases (others
 * counted). Timestamps narrower than 64 bits are unwrapped (uint8_t is in
 * ms), written in us.
 *
 * What a log has that is not refused, but counted (sim_log_ulog_stats_t,
 * sim_log_ulog_stats_describe): a header's version above 1 (read as 1, as
 * the spec asks), a log cut inside a message (decoded up to it), dropouts, appended data (read as part of the data section; a message
 * cut by an appended section is dropped), messages of unknown types (skipped
 * by their size), data messages of a size their format does not fit or of no
 * subscription, a corrupt message header (type or size 0: decoding resumes
 * after the next sync message, or ends there when there is none).
 *
 * Refused, `file: offset N: message`: no ULog header, incompatible flags,
 * a message too short for its own fixed fields ('A', 'D', 'R', 'O', 'B'),
 * a format without `name:`, a topic asked for whose format is missing or
 * malformed, or an output file that cannot be written. Nothing is left
 * written on a refusal.
 */
#ifndef LADRC_SIM_LOG_ULOG_H
#define LADRC_SIM_LOG_ULOG_H

#include <stdio.h>

#include "log.h"

/* Bytes decoded so far, of the log's total (0 when unknown); the same type
 * as log_convert.h's sim_log_convert_progress_fn. */
typedef void (*sim_log_ulog_progress_fn)(void *ctx, long long bytes_done, long long bytes_total);

typedef enum {
    SIM_LOG_ULOG_END_WHOLE = 0, /* the log ends after a whole message */
    SIM_LOG_ULOG_END_CUT,       /* it ends inside a message, at end_offset */
    SIM_LOG_ULOG_END_CORRUPT    /* a corrupt header at end_offset, no sync message after it */
} sim_log_ulog_end_t;

typedef struct {
    int version;                    /* the header's */
    long long bytes;                /* of the log read */
    long long messages;             /* whole messages read */
    long long rows;                 /* written, over every file */
    int files;                      /* CSVs written */
    long long subscribed;           /* 'A' messages */
    long long dropouts;             /* 'O' messages */
    long long dropout_ms;           /* their durations summed */
    long long data_bad_size;        /* 'D' messages whose size their format does not fit: skipped */
    long long data_no_subscription; /* 'D' messages of a msg_id never (or no longer) subscribed */
    long long out_of_order;         /* rows whose timestamp did not increase: skipped */
    long long unknown;              /* messages of unknown types, skipped by their size */
    long long resyncs;              /* corrupt headers passed over to the next sync message */
    long long resync_bytes;         /* bytes passed over */
    int appended;                   /* appended data sections reached */
    long long appended_cut_bytes;   /* bytes of messages cut by an appended section: dropped */
    sim_log_ulog_end_t end;
    long long end_offset; /* END_CUT, END_CORRUPT: where decoding stopped */
} sim_log_ulog_stats_t;

/* Decodes in_path: 0, or -1 with err set (`in_path: offset N: message`) and
 * no file left. topics/n_topics: the only topics to write (NULL/0: all).
 * progress may be NULL. */
int sim_log_ulog_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                        sim_log_ulog_progress_fn progress, void *progress_ctx, sim_log_error_t *err);

/* The same, with what the log had that was not refused in *stats. */
int sim_log_ulog_to_csv_stats(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                              sim_log_ulog_progress_fn progress, void *progress_ctx, sim_log_ulog_stats_t *stats,
                              sim_log_error_t *err);

/* The same from an open stream (not closed; `name` in messages; its total
 * size total_bytes, 0 when unknown). stats and progress may be NULL. */
int sim_log_ulog_to_csv_stream(FILE *in, const char *name, long long total_bytes, const char *out_base,
                               const char *const *topics, int n_topics, sim_log_ulog_progress_fn progress,
                               void *progress_ctx, sim_log_ulog_stats_t *stats, sim_log_error_t *err);

/* One line of what the stats tell a user (a cut, dropouts, skips), or ""
 * when the log was whole and clean; returns the notes written. */
int sim_log_ulog_stats_describe(const sim_log_ulog_stats_t *st, char *buf, size_t len);

#endif
