/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A streaming CSV row reader over a FILE*: one line at a time in a buffer
 * that grows up to SIM_LOG_CSV_LINE_MAX bytes, split into cells at commas
 * (no quoting: blackbox_decode and ulog2csv write none), each cell trimmed
 * of spaces and tabs (blackbox_decode writes ", "). LF or CRLF line ends, a
 * UTF-8 byte order mark at the start (not counted in columns), blank lines
 * skipped. Columns are 1-based bytes.
 */
#ifndef LADRC_SIM_LOG_CSV_H
#define LADRC_SIM_LOG_CSV_H

#include <stdio.h>

#include "log.h"

#define SIM_LOG_CSV_LINE_MAX 65536 /* bytes of one line, its end excluded */

typedef struct {
    const char *text; /* not NUL-terminated: len bytes */
    size_t len;
    int column; /* of the trimmed text's first byte (where it would be, when empty) */
} sim_log_cell_t;

typedef struct {
    FILE *f;
    char *block; /* bytes read from f, not yet consumed */
    size_t block_len, block_pos;
    int f_done; /* f gave its last byte */
    char *line; /* the current line, its end and a final CR excluded */
    size_t line_len, line_cap;
    int line_no;       /* of the current line (1-based) */
    int bom;           /* bytes of byte order mark before line 1's text */
    int ended_newline; /* the last line read ended with LF */
    size_t raw_len;    /* the last line's bytes, CR included */
    sim_log_cell_t *cells;
    int n_cells, cells_cap;
    int end_column;  /* just past the row's last byte */
    long long bytes; /* consumed from f */
} sim_log_csv_t;

/* Starts reading f (not closed by the reader). -1 when out of memory. */
int sim_log_csv_init(sim_log_csv_t *c, FILE *f);

/* The next non-blank line as cells: 1, 0 at the end, -1 with err's line,
 * column and message set (a line too long, a read error). */
int sim_log_csv_next(sim_log_csv_t *c, sim_log_error_t *err);

/* Where the text ends (after the last byte), for errors found there. */
void sim_log_csv_end(const sim_log_csv_t *c, int *line, int *column);

void sim_log_csv_free(sim_log_csv_t *c);

/* A decimal number (`2`, `-3`, `2.`, `.5`, `1e-3`; no nan, inf or hex),
 * finite: 0 with *v set, -1 otherwise. */
int sim_log_number(const char *text, size_t len, double *v);

/* The text is `nan` (any case, signed): what ulog2csv writes for a field
 * not in use. */
int sim_log_is_nan_text(const char *text, size_t len);

#endif
