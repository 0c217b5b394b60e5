/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Recorded series: a disturbance or a sensor's noise as it was measured,
 * read from a CSV file and flown as a function of time.
 *
 * The file
 *
 *     # gust measured on 2024-05-02, 1 kHz      <- comments: optional
 *     t [s], roll [rad/s^2], pitch [rad/s^2], yaw [rad/s^2]
 *     0.000, 0.0, 0.0, 0.0
 *     0.001, 0.8, -0.1, 0.0
 *     ...
 *
 * - Lines whose first non-blank character is '#' are comments, and blank
 *   lines are skipped, anywhere in the file. A '#' after a value is not a
 *   comment (it is an error).
 * - The first other line is the header: the time column, then 1 to 3 value
 *   columns (roll, pitch, yaw: the axes are the columns' order, the names
 *   are labels and are not checked), separated by commas. Each column is a
 *   name (a letter or '_', then letters, digits, '_', '-' or '.'; at most
 *   31 characters) and its unit in brackets: `roll [deg/s^2]`. A unit is
 *   required on every column, the time's too; `t_s` without brackets is a
 *   name without a unit, an error. Units (case-sensitive; blanks may
 *   surround the unit inside its brackets, `[ deg ]`, but not split it):
 *
 *       time                    s, ms            (the first column's)
 *       angle                   rad, deg
 *       angular rate            rad/s, deg/s
 *       angular acceleration    rad/s^2, deg/s^2
 *       velocity                m/s
 *       acceleration            m/s^2
 *
 *   Every value column must have the unit of what the scenario key expects
 *   (an angular acceleration for a disturbance); columns may mix rad and deg.
 *   Values are converted to SI as they are read: deg times pi/180, ms times
 *   0.001.
 * - Every further line is a row: one number per column, separated by commas,
 *   spaces around them allowed. Numbers are decimal as in scenario files
 *   (`2`, `-3`, `2.`, `.5`, `1e-3`, `+4E+2`); no `inf`, `nan` or hex, and
 *   every value finite. The times increase strictly; the span from the first
 *   to the last time must be finite. At least 2 rows.
 * - Line ends LF or CRLF; an optional UTF-8 byte order mark at the start.
 * - At most SIM_SERIES_MAX_ROWS rows and a file of SIM_SERIES_MAX_BYTES.
 *
 * Between rows the series is interpolated linearly, or held (zero-order
 * hold: the last row at or before t). Before the first row's time it has
 * the first row's values. Past the last row's time, by the end mode:
 * - repeat: the file loops with period P = last t - first t. The last row's
 *   time is where the next loop begins: at t = last t (and every first t +
 *   k P after it) the value is the first row's. Approaching that seam,
 *   linear interpolation runs towards the last row's values, so the series
 *   is continuous when the last row repeats the first and steps there
 *   otherwise; with hold the last row's values are never used.
 * - hold: the last row's values from its time on.
 * - refuse: a run longer than the file is an error of the scenario
 *   (sim_series_covers); evaluated past the end anyway, it holds.
 *
 * Errors are `path:line:column: message`, the line and column (1-based,
 * bytes; a tab is one column; the byte order mark is not counted) those of
 * the offending cell's first character, of the '[' of a wrong unit, of the
 * end of a row that lacks a value, or of the end of the file when the header
 * or rows are missing. A file that cannot be read has line and column 0.
 *
 * Evaluation: a loaded series is read-only and may be shared by any number
 * of threads. The search for the row at t starts from a cursor the caller
 * owns (one per thread, per series): O(1) while t grows in small steps (the
 * plant's RK4 stages), a binary search otherwise; without a cursor, always a
 * binary search. The value never depends on the cursor, and the same file
 * gives the same bits on every load.
 */
#ifndef LADRC_SIM_SERIES_H
#define LADRC_SIM_SERIES_H

#include <stddef.h>

#define SIM_SERIES_MAX_COLS 3                  /* value columns after the time */
#define SIM_SERIES_MAX_ROWS 10000000L          /* 1e7 rows: 2.8 h at 1 kHz */
#define SIM_SERIES_MAX_BYTES ((size_t)1 << 30) /* 1 GiB of file */
#define SIM_SERIES_NAME_LEN 32                 /* a column's name, with its NUL */
#define SIM_SERIES_PATH_LEN 512                /* paths kept for messages */

/* What a column holds. Every value column of a series has the dimension its
 * scenario key wants; the time column is SIM_DIM_TIME. */
typedef enum {
    SIM_DIM_TIME = 0,  /* s, ms */
    SIM_DIM_ANGLE,     /* rad, deg */
    SIM_DIM_ANG_RATE,  /* rad/s, deg/s */
    SIM_DIM_ANG_ACCEL, /* rad/s^2, deg/s^2 */
    SIM_DIM_VELOCITY,  /* m/s */
    SIM_DIM_LIN_ACCEL, /* m/s^2 */
    SIM_DIM_COUNT
} sim_dim_t;

/* Between rows. */
typedef enum {
    SIM_SERIES_LINEAR = 0, /* linear between the rows around t */
    SIM_SERIES_HOLD = 1    /* the last row at or before t */
} sim_series_interp_t;

/* Past the last row. */
typedef enum {
    SIM_SERIES_REPEAT = 0,   /* loop, period last t - first t */
    SIM_SERIES_HOLD_END = 1, /* the last row */
    SIM_SERIES_REFUSE = 2    /* a run past the end is an error (sim_series_covers) */
} sim_series_end_t;

/* What the scenario key asks of its file. */
typedef struct {
    sim_dim_t dim;   /* of every value column; not SIM_DIM_TIME */
    const char *key; /* the key's name, for messages ("disturbance_series"); NULL: none */
    sim_series_interp_t interp;
    sim_series_end_t end;
} sim_series_spec_t;

/* Where a load failed, as path:line:column: message (1-based line and
 * column; both 0 when the file could not be read at all). */
typedef struct {
    char path[SIM_SERIES_PATH_LEN];
    int line;
    int column;
    char message[256];
} sim_series_error_t;

/* A loaded series. All values SI; read-only once loaded. */
typedef struct {
    double *t_s;   /* n_rows times, strictly increasing */
    double *value; /* n_rows x n_cols values, row after row */
    size_t n_rows; /* >= 2 */
    int n_cols;    /* value columns, 1..SIM_SERIES_MAX_COLS */
    sim_dim_t dim;
    sim_series_interp_t interp;
    sim_series_end_t end;
    double period_s;                                         /* t_s[n_rows - 1] - t_s[0], > 0 and finite */
    char name[SIM_SERIES_MAX_COLS + 1][SIM_SERIES_NAME_LEN]; /* the header's names, the time's first */
} sim_series_t;

/* Where the last evaluation found its row: the caller's, one per thread and
 * series, zeroed (or sim_series_cursor_init) before the first use. Any
 * value is safe: a cursor from another series only costs a search. */
typedef struct {
    size_t row;
} sim_series_cursor_t;

/* Reads the file at path for a key that wants spec. Returns 0 with *s
 * filled (to sim_series_free), or -1 with *err set (NULL: not reported) and
 * *s empty, nothing left allocated. */
int sim_series_load(sim_series_t *s, const char *path, const sim_series_spec_t *spec, sim_series_error_t *err);

/* The same from len bytes in memory that need not end with a NUL (a NUL
 * among them is an error at its place); path is only used in messages. */
int sim_series_parse(sim_series_t *s, const char *data, size_t len, const char *path, const sim_series_spec_t *spec,
                     sim_series_error_t *err);

/* Releases a series' arrays and empties it; an empty (zeroed) or already
 * freed series is fine. */
void sim_series_free(sim_series_t *s);

void sim_series_cursor_init(sim_series_cursor_t *cursor);

/* The values at t_s into out[0..SIM_SERIES_MAX_COLS-1], columns beyond
 * n_cols 0; NaN values for a NaN t_s. cursor may be NULL (a binary search).
 * s must come from a successful load. */
void sim_series_eval(const sim_series_t *s, sim_series_cursor_t *cursor, double t_s, double out[SIM_SERIES_MAX_COLS]);

/* 1 when a run to t_end_s may fly s: always, but with end = refuse only
 * when t_end_s is at most the last row's time. Otherwise 0, and why (if not
 * NULL) says it: "'gust.csv' ends at t = 4 s, before the run's end at 10 s". */
int sim_series_covers(const sim_series_t *s, double t_end_s, const char *path, char *why, size_t why_len);

/* A unit's dimension and its factor to SI (value_si = value * *to_si) from
 * its text, text[0..len-1]. Returns 0, or -1 for a unit not in the table. */
int sim_series_unit(const char *text, size_t len, sim_dim_t *dim, double *to_si);

/* "an angular acceleration (rad/s^2 or deg/s^2)": what a dimension is, with
 * its units, for messages; "?" for anything else. */
const char *sim_dim_describe(sim_dim_t dim);

#endif
