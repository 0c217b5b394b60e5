/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Recorded series (series.h): the CSV file's header and rows, their units
 * converted to SI, and the evaluation at t with a caller's cursor.
 */
#include "series.h"

#include "ini.h"

#include "expr.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
#define SERIES_PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define SERIES_PRINTF_LIKE(f, a)
#endif

#define DEG_TO_RAD (3.14159265358979323846 / 180.0)

/* Text shown of a cell in messages. */
#define SHOWN_CHARS 40
/* Characters of a number; longer cells are no number this reader takes. */
#define MAX_NUMBER_CHARS 127
/* Cells the cursor steps forward before it searches. */
#define CURSOR_STEPS 4

typedef struct {
    const char *name;
    sim_dim_t dim;
    double to_si;
} unit_t;

static const unit_t UNITS[] = {
    {"s", SIM_DIM_TIME, 1.0},
    {"ms", SIM_DIM_TIME, 1e-3},
    {"rad", SIM_DIM_ANGLE, 1.0},
    {"deg", SIM_DIM_ANGLE, DEG_TO_RAD},
    {"rad/s", SIM_DIM_ANG_RATE, 1.0},
    {"deg/s", SIM_DIM_ANG_RATE, DEG_TO_RAD},
    {"rad/s^2", SIM_DIM_ANG_ACCEL, 1.0},
    {"deg/s^2", SIM_DIM_ANG_ACCEL, DEG_TO_RAD},
    {"m/s", SIM_DIM_VELOCITY, 1.0},
    {"m/s^2", SIM_DIM_LIN_ACCEL, 1.0},
};

/* Each dimension as a noun with its article, and its units (those of
 * UNITS), for messages. */
static const char *const DIM_NOUN[SIM_DIM_COUNT] = {
    "a time", "an angle", "an angular rate", "an angular acceleration", "a velocity", "an acceleration",
};
static const char *const DIM_DESCRIBED[SIM_DIM_COUNT] = {
    "a time (s or ms)",
    "an angle (rad or deg)",
    "an angular rate (rad/s or deg/s)",
    "an angular acceleration (rad/s^2 or deg/s^2)",
    "a velocity (m/s)",
    "an acceleration (m/s^2)",
};
/* The unit an example in a message shows, per dimension. */
static const char *const DIM_EXAMPLE_UNIT[SIM_DIM_COUNT] = {"s", "rad", "rad/s", "rad/s^2", "m/s", "m/s^2"};

/* Where the parser is, and where its error goes. */
typedef struct {
    const sim_series_spec_t *spec;
    sim_series_error_t *err;
    int line;               /* the current line, 1-based */
    const char *line_start; /* where it begins, for columns */
    double to_si[SIM_SERIES_MAX_COLS + 1];
    int n_cells;     /* the header's columns: time and values */
    int prev_line;   /* line of the last row read */
    size_t capacity; /* rows the arrays hold */
} reader_t;

static int SERIES_PRINTF_LIKE(3, 4) fail_at(reader_t *r, const char *at, const char *format, ...)
{
    va_list ap;
    r->err->line = r->line;
    r->err->column = (int)(at - r->line_start) + 1;
    va_start(ap, format);
    vsnprintf(r->err->message, sizeof r->err->message, format, ap);
    va_end(ap);
    return -1;
}

static int SERIES_PRINTF_LIKE(4, 5)
    fail_line_col(sim_series_error_t *err, int line, int column, const char *format, ...)
{
    va_list ap;
    err->line = line;
    err->column = column;
    va_start(ap, format);
    vsnprintf(err->message, sizeof err->message, format, ap);
    va_end(ap);
    return -1;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

static const char *skip_space(const char *p, const char *end)
{
    while (p < end && is_space(*p)) {
        ++p;
    }
    return p;
}

static const char *trim_end(const char *start, const char *end)
{
    while (end > start && is_space(end[-1])) {
        --end;
    }
    return end;
}

static const char *find_comma(const char *p, const char *end)
{
    if (p >= end) {
        return end;
    }
    const char *comma = memchr(p, ',', (size_t)(end - p));
    return comma != NULL ? comma : end;
}

static int is_letter(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

static int is_name_char(char c)
{
    return is_letter(c) || (c >= '0' && c <= '9') || c == '-' || c == '.';
}

static int shown(size_t len)
{
    return len > SHOWN_CHARS ? SHOWN_CHARS : (int)len;
}

int sim_series_unit(const char *text, size_t len, sim_dim_t *dim, double *to_si)
{
    for (size_t i = 0; i < sizeof UNITS / sizeof UNITS[0]; ++i) {
        if (strlen(UNITS[i].name) == len && memcmp(UNITS[i].name, text, len) == 0) {
            *dim = UNITS[i].dim;
            *to_si = UNITS[i].to_si;
            return 0;
        }
    }
    return -1;
}

const char *sim_dim_describe(sim_dim_t dim)
{
    return ((int)dim >= 0 && dim < SIM_DIM_COUNT) ? DIM_DESCRIBED[dim] : "?";
}

/* "key disturbance_series wants" or "the first column is the time" ...: who
 * wants the dimension of cell i, for messages. */
static void wanted_by(const reader_t *r, int cell, char *buf, size_t len)
{
    if (cell == 0) {
        snprintf(buf, len, "the first column is the time, in s or ms");
    } else if (r->spec->key != NULL) {
        snprintf(buf, len, "key %s wants %s", r->spec->key, sim_dim_describe(r->spec->dim));
    } else {
        snprintf(buf, len, "the series wants %s", sim_dim_describe(r->spec->dim));
    }
}

/* One header cell [c, end): NAME [UNIT]. */
static int header_cell(reader_t *r, sim_series_t *s, int cell, const char *c, const char *end)
{
    char who[160];
    const sim_dim_t want = cell == 0 ? SIM_DIM_TIME : r->spec->dim;
    const char *p = c;
    if (p == end || !is_letter(*p)) {
        if (cell == 0) {
            return fail_at(r, c, "expected a header line such as 't [s], roll [%s]' before the rows",
                           DIM_EXAMPLE_UNIT[r->spec->dim]);
        }
        return fail_at(r, c, "expected a column name and its unit, as in 'roll [%s]'", DIM_EXAMPLE_UNIT[want]);
    }
    while (p < end && is_name_char(*p)) {
        ++p;
    }
    const size_t name_len = (size_t)(p - c);
    if (name_len >= SIM_SERIES_NAME_LEN) {
        return fail_at(r, c, "column name '%.*s...' is longer than %d characters", shown(name_len), c,
                       SIM_SERIES_NAME_LEN - 1);
    }
    memcpy(s->name[cell], c, name_len);
    s->name[cell][name_len] = '\0';
    const char *open = skip_space(p, end);
    if (open == end || *open != '[') {
        return fail_at(r, c, "column '%.*s' has no unit: write it in brackets after the name, as in '%s [%s]'",
                       (int)name_len, c, cell == 0 ? "t" : s->name[cell], DIM_EXAMPLE_UNIT[want]);
    }
    const char *close = memchr(open, ']', (size_t)(end - open));
    if (close == NULL) {
        return fail_at(r, open, "expected ']' after the unit");
    }
    const char *u = skip_space(open + 1, close);
    const char *u_end = trim_end(u, close);
    sim_dim_t dim;
    double to_si;
    wanted_by(r, cell, who, sizeof who);
    if (sim_series_unit(u, (size_t)(u_end - u), &dim, &to_si) != 0) {
        return fail_at(r, open, "unknown unit [%.*s]; %s", shown((size_t)(u_end - u)), u, who);
    }
    if (dim != want) {
        return fail_at(r, open, "unit [%.*s] is %s; %s", (int)(u_end - u), u, DIM_NOUN[dim], who);
    }
    const char *after = skip_space(close + 1, end);
    if (after != end) {
        return fail_at(r, after, "unexpected '%.*s' after the unit", shown((size_t)(end - after)), after);
    }
    r->to_si[cell] = to_si;
    return 0;
}

/* The header line [a, b), a and b its first and last non-blank characters. */
static int read_header(reader_t *r, sim_series_t *s, const char *a, const char *b)
{
    const char *p = a;
    int cell = 0;
    for (;;) {
        const char *c = skip_space(p, b);
        const char *e = find_comma(c, b);
        if (cell > SIM_SERIES_MAX_COLS) {
            return fail_at(r, c, "too many columns: the time and at most %d value columns", SIM_SERIES_MAX_COLS);
        }
        if (header_cell(r, s, cell, c, trim_end(c, e)) != 0) {
            return -1;
        }
        ++cell;
        if (e == b) {
            break;
        }
        p = e + 1;
    }
    if (cell < 2) {
        return fail_at(r, b, "expected a value column after the time, as in 't [s], roll [%s]'",
                       DIM_EXAMPLE_UNIT[r->spec->dim]);
    }
    r->n_cells = cell;
    s->n_cols = cell - 1;
    return 0;
}

/* 1 when p[0..len-1] is word, whatever the case of its letters. */
static int is_word(const char *p, size_t len, const char *word)
{
    const size_t n = strlen(word);
    if (len != n) {
        return 0;
    }
    for (size_t i = 0; i < n; ++i) {
        char c = p[i];
        if (c >= 'A' && c <= 'Z') {
            c = (char)(c - 'A' + 'a');
        }
        if (c != word[i]) {
            return 0;
        }
    }
    return 1;
}

/* The number in the cell [c, e) (no blanks around it) into *value. */
static int read_number(reader_t *r, const char *c, const char *e, double *value)
{
    const size_t len = (size_t)(e - c);
    if (len == 0) {
        return fail_at(r, c, "expected a number");
    }
    const size_t sign = (*c == '-' || *c == '+') ? 1u : 0u;
    if (is_word(c + sign, len - sign, "nan") || is_word(c + sign, len - sign, "inf") ||
        is_word(c + sign, len - sign, "infinity")) {
        return fail_at(r, c, "'%.*s' is not finite: every value must be a finite number", shown(len), c);
    }
    char buf[MAX_NUMBER_CHARS + 1];
    size_t n = 0;
    double v = 0.0;
    if (len <= MAX_NUMBER_CHARS) {
        memcpy(buf, c, len);
        buf[len] = '\0';
        n = sim_expr_scan_number(buf + sign, &v);
    }
    if (n == 0 || sign + n != len) {
        return fail_at(r, c, "expected a number, got '%.*s'", shown(len), c);
    }
    if (!isfinite(v)) {
        return fail_at(r, c, "number out of range: '%.*s' (every value must be finite)", shown(len), c);
    }
    *value = (*c == '-') ? -v : v;
    return 0;
}

/* One row [a, b) into row s->n_rows. */
static int read_row(reader_t *r, sim_series_t *s, const char *a, const char *b)
{
    if (s->n_rows >= r->capacity) {
        return fail_at(r, a, "more than %ld rows: the most a series holds", SIM_SERIES_MAX_ROWS);
    }
    double *row = s->value + s->n_rows * (size_t)s->n_cols;
    const char *p = a;
    for (int cell = 0; cell < r->n_cells; ++cell) {
        if (cell > 0) {
            if (p == b) {
                return fail_at(r, b, "expected %d values (a time and %d), found %d: a value is missing", r->n_cells,
                               s->n_cols, cell);
            }
            ++p; /* the comma */
        }
        const char *c = skip_space(p, b);
        const char *e = find_comma(c, b);
        double v = 0.0;
        if (read_number(r, c, trim_end(c, e), &v) != 0) {
            return -1;
        }
        v *= r->to_si[cell];
        if (cell == 0) {
            if (s->n_rows > 0 && !(v > s->t_s[s->n_rows - 1])) {
                return fail_at(r, c,
                               "t = %.9g s does not follow the previous row's t = %.9g s (line %d): the "
                               "times must increase strictly",
                               v, s->t_s[s->n_rows - 1], r->prev_line);
            }
            if (s->n_rows > 0 && !isfinite(v - s->t_s[0])) {
                return fail_at(r, c, "t = %.9g s is too far from the first row's t = %.9g s: the span must be finite",
                               v, s->t_s[0]);
            }
            s->t_s[s->n_rows] = v;
        } else {
            row[cell - 1] = v;
        }
        p = e;
    }
    if (p != b) {
        const char *c = skip_space(p + 1, b);
        return fail_at(r, c, "unexpected value: the header has %d columns (a time and %d values)", r->n_cells,
                       s->n_cols);
    }
    r->prev_line = r->line;
    ++s->n_rows;
    return 0;
}

/* Arrays for the rows of [p, end) once the header is read: one row per line
 * that is left, at most SIM_SERIES_MAX_ROWS (a row beyond them is an error
 * of its line). */
static int allocate(reader_t *r, sim_series_t *s, const char *p, const char *end)
{
    size_t lines = 1;
    while (p < end && (p = memchr(p, '\n', (size_t)(end - p))) != NULL) {
        ++lines;
        ++p;
    }
    if (lines > (size_t)SIM_SERIES_MAX_ROWS) {
        lines = (size_t)SIM_SERIES_MAX_ROWS;
    }
    r->capacity = lines;
    s->t_s = malloc(lines * sizeof *s->t_s);
    s->value = malloc(lines * (size_t)s->n_cols * sizeof *s->value);
    if (s->t_s == NULL || s->value == NULL) {
        return fail_line_col(r->err, r->line, 1, "out of memory for %lu rows", (unsigned long)lines);
    }
    return 0;
}

/* Gives back what the arrays hold beyond the rows read. */
static void shrink(sim_series_t *s)
{
    double *t = realloc(s->t_s, s->n_rows * sizeof *s->t_s);
    if (t != NULL) {
        s->t_s = t;
    }
    double *v = realloc(s->value, s->n_rows * (size_t)s->n_cols * sizeof *s->value);
    if (v != NULL) {
        s->value = v;
    }
}

static int read_lines(reader_t *r, sim_series_t *s, const char *data, size_t len)
{
    const char *p = data;
    const char *end = data + len;
    if (len >= 3 && memcmp(p, "\xEF\xBB\xBF", 3) == 0) {
        p += 3; /* UTF-8 byte order mark */
    }
    int header = 0;
    const char *last_start = p;
    int ended_with_newline = 0;
    r->line = 0;
    while (p < end) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        const char *line_end = nl != NULL ? nl : end;
        ++r->line;
        r->line_start = p;
        last_start = p;
        ended_with_newline = nl != NULL;
        const char *nul = memchr(p, '\0', (size_t)(line_end - p));
        if (nul != NULL) {
            return fail_at(r, nul, "unexpected NUL byte");
        }
        const char *a = skip_space(p, line_end);
        const char *b = trim_end(a, line_end);
        if (a < b && *a != '#') {
            if (!header) {
                if (read_header(r, s, a, b) != 0 || allocate(r, s, line_end, end) != 0) {
                    return -1;
                }
                header = 1;
            } else if (read_row(r, s, a, b) != 0) {
                return -1;
            }
        }
        p = nl != NULL ? nl + 1 : end;
    }
    /* the end of the file, where a missing line would begin */
    if (r->line == 0 || ended_with_newline) {
        ++r->line;
        r->line_start = end;
    } else {
        r->line_start = last_start;
    }
    if (!header) {
        return fail_at(r, end, "%s: expected a header line such as 't [s], roll [%s]'",
                       len == 0 ? "empty file" : "no header", DIM_EXAMPLE_UNIT[r->spec->dim]);
    }
    if (s->n_rows < 2) {
        return fail_at(r, end, "%lu row%s: a series needs at least 2", (unsigned long)s->n_rows,
                       s->n_rows == 1 ? "" : "s");
    }
    return 0;
}

void sim_series_free(sim_series_t *s)
{
    if (s == NULL) {
        return;
    }
    free(s->t_s);
    free(s->value);
    memset(s, 0, sizeof *s);
}

int sim_series_parse(sim_series_t *s, const char *data, size_t len, const char *path, const sim_series_spec_t *spec,
                     sim_series_error_t *err)
{
    sim_series_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", path != NULL ? path : "");
    if (s == NULL) {
        return fail_line_col(err, 0, 0, "no series");
    }
    memset(s, 0, sizeof *s);
    if (spec == NULL || (int)spec->dim <= (int)SIM_DIM_TIME || spec->dim >= SIM_DIM_COUNT ||
        (spec->interp != SIM_SERIES_LINEAR && spec->interp != SIM_SERIES_HOLD) ||
        (spec->end != SIM_SERIES_REPEAT && spec->end != SIM_SERIES_HOLD_END && spec->end != SIM_SERIES_REFUSE)) {
        return fail_line_col(err, 0, 0, "invalid series request");
    }
    if (data == NULL && len > 0) {
        return fail_line_col(err, 0, 0, "no text");
    }
    if (len > SIM_SERIES_MAX_BYTES) {
        return fail_line_col(err, 0, 0, "larger than %lu bytes: the most a series file holds",
                             (unsigned long)SIM_SERIES_MAX_BYTES);
    }
    reader_t r;
    memset(&r, 0, sizeof r);
    r.spec = spec;
    r.err = err;
    if (read_lines(&r, s, data != NULL ? data : "", len) != 0) {
        sim_series_free(s);
        return -1;
    }
    shrink(s);
    s->dim = spec->dim;
    s->interp = spec->interp;
    s->end = spec->end;
    s->period_s = s->t_s[s->n_rows - 1] - s->t_s[0];
    return 0;
}

int sim_series_load(sim_series_t *s, const char *path, const sim_series_spec_t *spec, sim_series_error_t *err)
{
    sim_series_error_t ignored;
    if (err == NULL) {
        err = &ignored;
    }
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", path != NULL ? path : "");
    if (s != NULL) {
        memset(s, 0, sizeof *s);
    }
    if (path == NULL) {
        return fail_line_col(err, 0, 0, "cannot open: no path");
    }
    char *text = NULL;
    size_t len = 0;
    const int rc = ini_read_file_max(path, SIM_SERIES_MAX_BYTES, &text, &len);
    if (rc == -1) {
        return fail_line_col(err, 0, 0, "cannot open: %s", strerror(errno));
    }
    if (rc == -2) {
        return fail_line_col(err, 0, 0, "out of memory");
    }
    if (rc == -3) {
        return fail_line_col(err, 0, 0, "read error");
    }
    if (rc == -4) {
        return fail_line_col(err, 0, 0, "larger than %lu bytes: the most a series file holds",
                             (unsigned long)SIM_SERIES_MAX_BYTES);
    }
    const int parsed = sim_series_parse(s, text, len, path, spec, err);
    free(text);
    return parsed;
}

void sim_series_cursor_init(sim_series_cursor_t *cursor)
{
    cursor->row = 0;
}

/* The row i, 0 <= i <= n - 2, with t_s[i] <= t < t_s[i + 1], for
 * t_s[0] <= t < t_s[n - 1]: from the cursor's row forward a few steps,
 * else a binary search. */
static size_t find_row(const sim_series_t *s, sim_series_cursor_t *cursor, double t)
{
    const double *ts = s->t_s;
    size_t lo = 0;
    size_t hi = s->n_rows - 1; /* ts[lo] <= t < ts[hi] */
    if (cursor != NULL) {
        size_t i = cursor->row;
        if (i < s->n_rows - 1 && ts[i] <= t) {
            for (int k = 0; k < CURSOR_STEPS && i < s->n_rows - 1; ++k, ++i) {
                if (t < ts[i + 1]) {
                    cursor->row = i;
                    return i;
                }
            }
            lo = i < s->n_rows - 1 ? i : s->n_rows - 2;
        } else if (i < s->n_rows - 1) {
            hi = i;
        }
    }
    while (hi - lo > 1) {
        const size_t mid = lo + (hi - lo) / 2;
        if (ts[mid] <= t) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    if (cursor != NULL) {
        cursor->row = lo;
    }
    return lo;
}

static void copy_row(const sim_series_t *s, size_t i, double out[SIM_SERIES_MAX_COLS])
{
    const double *v = s->value + i * (size_t)s->n_cols;
    for (int k = 0; k < s->n_cols; ++k) {
        out[k] = v[k];
    }
}

void sim_series_eval(const sim_series_t *s, sim_series_cursor_t *cursor, double t_s, double out[SIM_SERIES_MAX_COLS])
{
    for (int k = 0; k < SIM_SERIES_MAX_COLS; ++k) {
        out[k] = 0.0;
    }
    const size_t last = s->n_rows - 1;
    if (isnan(t_s)) {
        for (int k = 0; k < s->n_cols; ++k) {
            out[k] = t_s;
        }
        return;
    }
    double t = t_s;
    if (t >= s->t_s[last] && s->end == SIM_SERIES_REPEAT) {
        t = s->t_s[0] + fmod(t - s->t_s[0], s->period_s);
    }
    if (!(t > s->t_s[0])) {
        copy_row(s, 0, out); /* before the first row, and at it */
        return;
    }
    if (!(t < s->t_s[last])) {
        /* hold and refuse past the end; repeat rounded to the seam from
         * below, where linear tends to the last row and hold keeps the one
         * before it */
        const int before_seam = s->end == SIM_SERIES_REPEAT && s->interp == SIM_SERIES_HOLD;
        copy_row(s, before_seam ? last - 1 : last, out);
        return;
    }
    const size_t i = find_row(s, cursor, t);
    if (s->interp == SIM_SERIES_HOLD) {
        copy_row(s, i, out);
        return;
    }
    const double t0 = s->t_s[i];
    const double f = (t - t0) / (s->t_s[i + 1] - t0); /* in [0, 1] */
    const double *v0 = s->value + i * (size_t)s->n_cols;
    const double *v1 = v0 + s->n_cols;
    for (int k = 0; k < s->n_cols; ++k) {
        const double d = v1[k] - v0[k];
        if (f == 0.0) {
            out[k] = v0[k];
        } else if (isfinite(d)) {
            out[k] = v0[k] + d * f;
        } else {
            /* values of opposite signs near the largest double: this sum of
             * opposite terms cannot overflow */
            out[k] = v0[k] * (1.0 - f) + v1[k] * f;
        }
    }
}

int sim_series_covers(const sim_series_t *s, double t_end_s, const char *path, char *why, size_t why_len)
{
    const double t_last = s->t_s[s->n_rows - 1];
    if (s->end != SIM_SERIES_REFUSE || t_end_s <= t_last) {
        return 1;
    }
    if (why != NULL && why_len > 0) {
        snprintf(why, why_len, "'%s' ends at t = %.9g s, before the run's end at %.9g s", path != NULL ? path : "",
                 t_last, t_end_s);
    }
    return 0;
}
