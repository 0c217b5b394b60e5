/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * One CSV of a log and the items it gives: its header's columns found, its
 * rows read as the time (us) and the items' values, the first rows held to
 * estimate the median row period, then the two rows around the current
 * tick (the bracket) and nothing more.
 */
#ifndef LADRC_SIM_LOG_FILE_H
#define LADRC_SIM_LOG_FILE_H

#include <stdio.h>

#include "log.h"
#include "log_csv.h"
#include "log_map.h"

#define SIM_LOG_PERIOD_ROWS 1000 /* rows the median row period is estimated from */
#define SIM_LOG_NEEDED_MAX ((SIM_LOG_N_SLOTS + 1) * SIM_LOG_TERMS_MAX)

typedef struct {
    char path[SIM_LOG_PATH_LEN];
    FILE *f;
    int own;        /* f opened here, closed with the file */
    long long size; /* bytes; 0 when unknown */
    sim_log_csv_t csv;
    int csv_ready;
    int n_header;
    int header_line, header_end;
    /* the items: time first, then those this file gives (item i + 1 is slot[i]'s) */
    int n_items;
    int slot[SIM_LOG_N_SLOTS];
    const sim_log_item_t *item[SIM_LOG_N_SLOTS + 1];            /* the caller's, kept while the file is open */
    int col[SIM_LOG_N_SLOTS + 1][SIM_LOG_TERMS_MAX];            /* each term's header cell, -1 absent */
    double term_factor[SIM_LOG_N_SLOTS + 1][SIM_LOG_TERMS_MAX]; /* the cell's unit to the term's (log_units.h) */
    int present[SIM_LOG_N_SLOTS];                               /* item i has a column */
    double time_to_us;
    /* the header cells read from each row, ascending */
    int n_needed;
    int needed[SIM_LOG_NEEDED_MAX];
    int needed_optional[SIM_LOG_NEEDED_MAX]; /* only optional terms read it */
    double *cell_v;                          /* by header cell */
    /* the first rows, held until used */
    double *buf_t, *buf_v;
    int buf_n, buf_pos;
    double median_us;
    /* the bracket: t0 <= tick <= t1 */
    double t0, t1;
    double *v0, *v1;
    double last_read_us, prev_used_us;
    long long rows, gaps;
    double longest_gap_us;
} sim_log_file_t;

#if defined(__GNUC__)
#define SIM_LOG_PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define SIM_LOG_PRINTF_LIKE(f, a)
#endif

/* The reader's one form of an error: *err set to path, line, column and
 * the message; returns -1. */
int SIM_LOG_PRINTF_LIKE(5, 6)
    sim_log_fail(sim_log_error_t *err, const char *path, int line, int column, const char *format, ...);

/* Reads the header and the first rows of stream (closed with the file when
 * own), for the time item (kept, as map) and the items of map whose topic is `topic`
 * (every item but the time when topic is NULL), and puts the bracket on its
 * first two rows. 0, or -1 with err set (the file closed). */
int sim_log_file_open(sim_log_file_t *f, FILE *stream, int own, const char *path, const sim_log_item_t *time,
                      const sim_log_map_t *map, const char *topic, sim_log_error_t *err);

/* Moves the bracket to tick: 1, 0 when the file ends before it, -1 with
 * err set (a bad row). */
int sim_log_file_reach(sim_log_file_t *f, double tick_us, sim_log_error_t *err);

void sim_log_file_close(sim_log_file_t *f);

/* 1 when a tick at tick_us lies inside a gap of the bracket that the
 * ticks skip (log.h: SIM_LOG_GAP_SKIP_FACTOR), not on either row. */
static inline int sim_log_file_in_skipped_gap(const sim_log_file_t *f, double tick_us)
{
    return f->t0 < tick_us && tick_us < f->t1 && f->t1 - f->t0 > SIM_LOG_GAP_SKIP_FACTOR * f->median_us;
}

#endif
