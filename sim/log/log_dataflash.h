/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ArduPilot DataFlash logs (.bin) decoded, streaming, into one CSV per
 * message type and instance, BASE_<NAME>_<instance>.csv, the form the
 * reader takes as SIM_LOG_ARDUPILOT (log.h).
 *
 * The format (ArduPilot's AP_Logger/LogStructure.h): each message is 0xA3
 * 0x95, a type byte, then the fields its FMT message (type 128) defines:
 * the message's length (header included), a 4-character name, a format
 * string of one character per field and the fields' names, comma
 * separated. Field kinds (bytes): b B M 1, h H 2, i I f 4, d q Q 8, n 4,
 * N 16, Z 64 (text, NUL padded), c C 2 and e E 4 (integers, hundredths),
 * L 4 (degrees x1e7), g 2 (half float), a 64 (32 int16: 32 cells,
 * NAME[0]..NAME[31]). FMTU messages give each field a unit id ('#': the
 * instance field) and a multiplier id, MULT messages the multipliers.
 *
 * Values written: integers as decimals, c C e E and L with the decimal
 * point where their scale puts it (exact), other fields times the FMTU
 * multiplier of the column when one is logged (so in the unit FMTU names:
 * deg, deg/s, rad/s, us for PWM; the preset turns them into SI), TimeUS as
 * logged (us). A type's conversion is fixed by its first row: an FMTU
 * logged after it is not applied. Floats print with 9 significant
 * digits, doubles with 17 (both read back to the value logged). Text has
 * commas, quotes and bytes outside printable ASCII replaced by '_'.
 *
 * Instances: a type whose FMTU marks a field '#' (without FMTU: a field
 * named I or Instance) goes to one file per value of that field (0..255);
 * the others to _0. Rows whose TimeUS (GYR and ACC: SampleUS) is not after
 * the previous row's in their file are dropped and counted: the reader
 * takes time strictly increasing (a log whose clock restarts, a repeat).
 *
 * Damage is handled as ArduPilot's tools do: a byte that does not start a
 * known message is skipped until the next 0xA3 0x95 of a defined type, and
 * the bytes skipped are counted; a log cut inside a message is decoded up
 * to the cut. An FMT whose fields overrun its length, whose name is not
 * letters and digits, that names a column twice, whose TimeUS (GYR, ACC:
 * SampleUS) is not a plain integer, or that redefines a type after its
 * rows, is not used (counted). A type of no fields frames its messages and
 * writes nothing.
 * Refused, nothing written: a file that cannot be read,
 * no FMT message in it, more than SIM_LOG_DATAFLASH_MAX_FILES outputs, a
 * write error.
 */
#ifndef LADRC_SIM_LOG_DATAFLASH_H
#define LADRC_SIM_LOG_DATAFLASH_H

#include <stdio.h>

#include "log.h"
#include "log_convert.h"

#define SIM_LOG_DATAFLASH_MAX_FILES 512 /* CSVs open at once: the descriptors a process is given */

typedef struct {
    long long bytes;             /* read */
    long long messages;          /* decoded, FMT included */
    long long rows;              /* written */
    long long skipped_bytes;     /* not part of a known message */
    long long skip_runs;         /* runs of them */
    long long first_skip_offset; /* -1: none */
    long long rows_backwards;    /* dropped: TimeUS not after the previous row's */
    long long rows_bad_instance; /* dropped: an instance outside 0..255 */
    int bad_fmts;                /* FMT messages not used */
    int truncated;               /* the log ends inside a message */
    long long truncated_offset;  /* where that message starts */
    int files;                   /* CSVs written */
    long long type_count[256];   /* messages of each type */
    char type_name[256][5];      /* each type's name ("" when undefined) */
} sim_log_dataflash_stats_t;

/* The contract's decoder (log_convert.h): the log at in_path into
 * out_base's CSVs, only the message types named in topics (NULL or 0: all).
 * 0, or -1 with err set ("offset N: ..."), nothing left written. A skip or
 * a cut is told on stderr, one line each. */
int sim_log_dataflash_to_csv(const char *in_path, const char *out_base, const char *const *topics, int n_topics,
                             sim_log_convert_progress_fn progress, void *progress_ctx, sim_log_error_t *err);

/* The same from an open stream (not closed; `name` in messages), telling
 * nothing on stderr; st (may be NULL) gets the counts. */
int sim_log_dataflash_to_csv_stream(FILE *in, const char *name, const char *out_base, const char *const *topics,
                                    int n_topics, sim_log_convert_progress_fn progress, void *progress_ctx,
                                    sim_log_dataflash_stats_t *st, sim_log_error_t *err);

#endif
