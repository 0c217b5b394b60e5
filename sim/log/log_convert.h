/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Logs as they come: the form of a log told from its first bytes, and the
 * binary forms (PX4 ULog, Betaflight blackbox, ArduPilot DataFlash) decoded,
 * streaming, into the CSV forms the reader takes (log.h), in a temporary
 * folder that sim_log_prepared_remove deletes. Each decoder writes the CSVs
 * its form's own tools write (ulog2csv, blackbox_decode, per message type),
 * so one reader, one mapping and one set of tests serve both.
 */
#ifndef LADRC_SIM_LOG_CONVERT_H
#define LADRC_SIM_LOG_CONVERT_H

#include <stddef.h>

#include "log.h"

typedef enum {
    SIM_LOG_SOURCE_CSV = 0,   /* text: a CSV, or the common prefix of ulog2csv's files */
    SIM_LOG_SOURCE_ULOG,      /* "ULog" 0x01 0x12 0x35 */
    SIM_LOG_SOURCE_BBL,       /* "H Product:Blackbox flight data recorder" */
    SIM_LOG_SOURCE_DATAFLASH, /* 0xA3 0x95, then a FMT message (type 128) */
    SIM_LOG_SOURCE_MISSING    /* no file of that name (and no topic files under it) */
} sim_log_source_t;

/* Bytes of the log decoded so far, of its total (0 when unknown). */
typedef void (*sim_log_convert_progress_fn)(void *ctx, long long bytes_done, long long bytes_total);

/* The form of the file at path, told from its first bytes. */
sim_log_source_t sim_log_source_of(const char *path);
const char *sim_log_source_name(sim_log_source_t s);

/* The CSV form of a text log given without a form: PX4 when ulog2csv's topic
 * files are there, Betaflight when the header has gyroADC, else generic. */
sim_log_format_t sim_log_csv_format_of(const char *path);

typedef struct {
    sim_log_source_t source;
    char original[SIM_LOG_PATH_LEN]; /* the path the user gave */
    char dir[SIM_LOG_PATH_LEN];      /* the temporary folder; "" when none was made */
    long long bytes;                 /* of the original */
    double decode_s;                 /* wall time decoding it */
} sim_log_prepared_t;

/* Makes the options read the log at o->path: a binary log is decoded into a
 * temporary folder and o->path and o->format point at its CSVs (the form
 * given is then replaced by the decoded one); a text log's form is told from
 * its files unless format_given. 0, or -1 with err set and nothing left
 * behind. p records what to remove. */
int sim_log_prepare(sim_log_options_t *o, int format_given, sim_log_prepared_t *p, sim_log_convert_progress_fn progress,
                    void *progress_ctx, sim_log_error_t *err);

/* A message naming a file of the temporary folder names the log the user
 * gave instead ("LOG.bin, decoded as LOG_IMU_0.csv:1:37: ..."): the folder
 * is gone when the message is read. msg is rewritten in place (cut at len). */
void sim_log_prepared_explain(const sim_log_prepared_t *p, char *msg, size_t len);

/* Removes the temporary folder (and every file in it); safe to call twice. */
void sim_log_prepared_remove(sim_log_prepared_t *p);

#endif
