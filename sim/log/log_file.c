/* SPDX-License-Identifier: BSD-3-Clause */
/* One CSV of a log: header, rows, the first rows held, the bracket (log_file.h). */
#include "log_file.h"

#include "log_units.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* 2^53 us (285 years): every whole microsecond up to it is a double, so
 * tick times computed in integers compare exactly with the rows'. */
#define TIME_MAX_US 9007199254740992.0
/* Far beyond any quantity a log holds (rad/s, Hz, a motor's units); below
 * it, sums, interpolations and integrals over 2^53 us stay finite. */
#define VALUE_MAX 1e15
/* A time within this of a whole microsecond is that microsecond: what a
 * decimal time in seconds times 1e6 rounds to (a few ulps). */
#define SNAP_ULPS 8.0
#define SHOWN 40 /* characters of a cell quoted in a message */

int sim_log_fail(sim_log_error_t *err, const char *path, int line, int column, const char *format, ...)
{
    va_list ap;
    snprintf(err->path, sizeof err->path, "%s", path);
    err->line = line;
    err->column = column;
    va_start(ap, format);
    vsnprintf(err->message, sizeof err->message, format, ap);
    va_end(ap);
    return -1;
}

static int shown(size_t len)
{
    return len > SHOWN ? SHOWN : (int)len;
}

static double snap_whole(double x, double rel)
{
    const double r = floor(x + 0.5);
    return fabs(x - r) <= rel * fabs(x) + DBL_MIN ? r : x;
}

/* How a term's column was found in the header. */
typedef enum { FOUND_NAME, FOUND_CONVERTED, FOUND_UNITLESS } found_t;

static int same_text(const char *a, size_t a_len, const char *b, size_t b_len)
{
    return a_len == b_len && memcmp(a, b, a_len) == 0;
}

/* The header cell of a term's column and the factor its values take: the
 * name itself; else, when the term names a unit (`gyroADC[0] (deg/s)`), the
 * same base in another unit of that quantity (converted: blackbox_decode's
 * unit flags) or with no unit (taken to be in the term's unit). -1: none. */
static int find_column(const sim_log_csv_t *c, const char *name, double *factor, found_t *how)
{
    const size_t n = strlen(name);
    size_t base_len, unit_len, cell_base_len, cell_unit_len;
    const char *unit, *cell_unit;
    *factor = 1.0;
    *how = FOUND_NAME;
    for (int i = 0; i < c->n_cells; ++i) {
        if (same_text(c->cells[i].text, c->cells[i].len, name, n)) {
            return i;
        }
    }
    sim_log_unit_split(name, n, &base_len, &unit, &unit_len);
    if (unit_len == 0) {
        return -1;
    }
    for (int i = 0; i < c->n_cells; ++i) {
        sim_log_unit_split(c->cells[i].text, c->cells[i].len, &cell_base_len, &cell_unit, &cell_unit_len);
        if (!same_text(c->cells[i].text, cell_base_len, name, base_len)) {
            continue;
        }
        if (cell_unit_len == 0) {
            *how = FOUND_UNITLESS;
            return i;
        }
        if (sim_log_unit_factor(cell_unit, cell_unit_len, unit, unit_len, factor) == 0) {
            *how = FOUND_CONVERTED;
            return i;
        }
    }
    return -1;
}

/* A header cell of the column's base in a unit that cannot be converted
 * to the term's, or in one when the term names none: -1 when none. */
static int find_other_unit(const sim_log_csv_t *c, const char *name)
{
    size_t base_len, unit_len, cell_base_len, cell_unit_len;
    const char *unit, *cell_unit;
    sim_log_unit_split(name, strlen(name), &base_len, &unit, &unit_len);
    for (int i = 0; i < c->n_cells; ++i) {
        sim_log_unit_split(c->cells[i].text, c->cells[i].len, &cell_base_len, &cell_unit, &cell_unit_len);
        if (cell_unit_len > 0 && same_text(c->cells[i].text, cell_base_len, name, base_len)) {
            return i;
        }
    }
    return -1;
}

/* A required term's column missing, at the header line's end: what the
 * header has of its base in another unit, and how a log would give it. */
static int missing_column(const sim_log_file_t *f, const sim_log_item_t *it, int k, sim_log_error_t *err)
{
    char field[32], other[SIM_LOG_NAME_LEN + 64] = "";
    const char *hint = sim_log_column_hint(it->term[k].column);
    const int cell = find_other_unit(&f->csv, it->term[k].column);
    sim_log_slot_name(it->slot, field, sizeof field);
    if (cell >= 0) {
        size_t base_len, unit_len;
        const char *unit;
        sim_log_unit_split(it->term[k].column, strlen(it->term[k].column), &base_len, &unit, &unit_len);
        snprintf(other, sizeof other, "; the log has '%.*s'%s", shown(f->csv.cells[cell].len), f->csv.cells[cell].text,
                 unit_len > 0 ? ", in a unit not convertible to the one named" : ": name the column with its unit");
    }
    return sim_log_fail(err, f->path, f->header_line, f->header_end, "no column '%s' (needed for %s)%s%s%s",
                        it->term[k].column, field, other, hint != NULL ? ": " : "", hint != NULL ? hint : "");
}

/* The header's cell of every term; a required one missing is an error at
 * the header line's end. */
static int resolve(sim_log_file_t *f, sim_log_error_t *err)
{
    const sim_log_csv_t *c = &f->csv;
    for (int i = 0; i <= f->n_items; ++i) {
        const sim_log_item_t *it = f->item[i];
        int found = 0;
        for (int k = 0; k < it->n_terms; ++k) {
            found_t how;
            f->col[i][k] = find_column(c, it->term[k].column, &f->term_factor[i][k], &how);
            found |= f->col[i][k] >= 0;
            if (f->col[i][k] < 0 && !it->term[k].optional) {
                return missing_column(f, it, k, err);
            }
            if (i == 0 && how == FOUND_UNITLESS) { /* blackbox_decode names its time's unit but under --raw */
                return sim_log_fail(err, f->path, f->header_line, c->cells[f->col[i][k]].column,
                                    "column '%s' has no unit: blackbox_decode --raw writes it so, with the fields' "
                                    "deltas, not their values (decode without --raw)",
                                    it->term[k].column);
            }
        }
        if (i == 0 && !found) { /* a time made of optional columns only */
            return missing_column(f, it, 0, err);
        }
    }
    return 0;
}

/* The cells read from each row, ascending, and whether only optional terms
 * read each. */
static void list_needed(sim_log_file_t *f)
{
    f->n_needed = 0;
    for (int i = 0; i <= f->n_items; ++i) {
        for (int k = 0; k < f->item[i]->n_terms; ++k) {
            const int col = f->col[i][k];
            const int optional = f->item[i]->term[k].optional;
            int j = 0;
            while (j < f->n_needed && f->needed[j] < col) {
                ++j;
            }
            if (col < 0) {
                continue;
            }
            if (j < f->n_needed && f->needed[j] == col) {
                f->needed_optional[j] &= optional;
                continue;
            }
            memmove(&f->needed[j + 1], &f->needed[j], (size_t)(f->n_needed - j) * sizeof f->needed[0]);
            memmove(&f->needed_optional[j + 1], &f->needed_optional[j],
                    (size_t)(f->n_needed - j) * sizeof f->needed_optional[0]);
            f->needed[j] = col;
            f->needed_optional[j] = optional;
            ++f->n_needed;
        }
    }
}

/* A column of optional terms only that reads nan in the first row is taken
 * as absent: ulog2csv writes nan for the unused entries of an array. */
static void drop_column(sim_log_file_t *f, int col)
{
    for (int i = 0; i <= f->n_items; ++i) {
        for (int k = 0; k < f->item[i]->n_terms; ++k) {
            if (f->col[i][k] == col) {
                f->col[i][k] = -1;
            }
        }
    }
}

static const char *column_name(const sim_log_file_t *f, int col)
{
    for (int i = 0; i <= f->n_items; ++i) {
        for (int k = 0; k < f->item[i]->n_terms; ++k) {
            if (f->col[i][k] == col) {
                return f->item[i]->term[k].column;
            }
        }
    }
    return "?";
}

/* Item i's sum of its columns, the first of them (-1: none) and the one
 * whose term is largest in magnitude: where a sum beyond range is told,
 * the column that holds the bad value (not the sum's first). */
static double item_sum(const sim_log_file_t *f, int i, int *first_col, int *largest_col)
{
    double sum = 0.0, largest = -1.0;
    *first_col = -1;
    *largest_col = -1;
    for (int k = 0; k < f->item[i]->n_terms; ++k) {
        const int col = f->col[i][k];
        if (col >= 0) {
            const double term = f->cell_v[col] * f->term_factor[i][k];
            sum += term;
            if (*first_col < 0) {
                *first_col = col;
            }
            if (!(fabs(term) <= largest)) { /* a NaN or inf term is the largest */
                largest = fabs(term);
                *largest_col = col;
            }
        }
    }
    return sum;
}

static int parse_cells(sim_log_file_t *f, sim_log_error_t *err)
{
    const sim_log_csv_t *c = &f->csv;
    for (int j = 0; j < f->n_needed; ++j) {
        const int col = f->needed[j];
        if (col < 0) {
            continue;
        }
        const sim_log_cell_t *cell = &c->cells[col];
        if (f->rows == 0 && f->needed_optional[j] && sim_log_is_nan_text(cell->text, cell->len)) {
            drop_column(f, col);
            f->needed[j] = -1;
            continue;
        }
        if (sim_log_number(cell->text, cell->len, &f->cell_v[col]) != 0) {
            if (cell->len == 0) {
                return sim_log_fail(err, f->path, c->line_no, cell->column,
                                    "not a finite number in column '%s': empty cell", column_name(f, col));
            }
            return sim_log_fail(err, f->path, c->line_no, cell->column, "not a finite number in column '%s': '%.*s'",
                                column_name(f, col), shown(cell->len), cell->text);
        }
    }
    return 0;
}

static int column_of(const sim_log_file_t *f, int col)
{
    return col >= 0 ? f->csv.cells[col].column : 1;
}

/* 1 when this file gives all four components of group g's quaternion and
 * they are all 0 in the row v: no attitude at all (a length other than 1 is
 * normalised: its direction is the attitude). */
static int quat_of_no_length(const sim_log_file_t *f, const double *v, sim_log_group_t g)
{
    const int first = sim_log_group_first(g);
    int given = 0;
    double n2 = 0.0;
    for (int i = 0; i < f->n_items; ++i) {
        if (f->present[i] && f->slot[i] >= first && f->slot[i] < first + 4) {
            ++given;
            n2 += v[i] * v[i];
        }
    }
    return given == 4 && n2 == 0.0;
}

/* For an item that sums columns: which of them holds the value told at
 * (its name and the cell as read), else "". */
static const char *summed_from(const sim_log_file_t *f, int i, int col, char *buf, size_t len)
{
    buf[0] = '\0';
    if (f->item[i]->n_terms > 1 && col >= 0) {
        const sim_log_cell_t *cell = &f->csv.cells[col];
        snprintf(buf, len, ": the sum's column '%s' holds '%.*s'", column_name(f, col), shown(cell->len), cell->text);
    }
    return buf;
}

/* One row from the file: 1, 0 at its end, -1 on error. */
static int read_row(sim_log_file_t *f, double *t_us, double *v, sim_log_error_t *err)
{
    const sim_log_csv_t *c = &f->csv;
    char held[SIM_LOG_NAME_LEN + SHOWN + 48];
    int rc = sim_log_csv_next(&f->csv, err);
    if (rc <= 0) {
        return rc;
    }
    if (c->n_cells < f->n_header) {
        return sim_log_fail(err, f->path, c->line_no, c->end_column, "row has %d cells, the header %d", c->n_cells,
                            f->n_header);
    }
    if (c->n_cells > f->n_header) {
        return sim_log_fail(err, f->path, c->line_no, c->cells[f->n_header].column, "row has %d cells, the header %d",
                            c->n_cells, f->n_header);
    }
    if (parse_cells(f, err) != 0) {
        return -1;
    }
    int col, largest;
    double t = snap_whole(item_sum(f, 0, &col, &largest) * f->time_to_us, SNAP_ULPS * DBL_EPSILON);
    if (!(fabs(t) <= TIME_MAX_US)) {
        return sim_log_fail(err, f->path, c->line_no, column_of(f, largest),
                            "time %.9g s is beyond the reader's range (2^53 us)%s", t * 1e-6,
                            summed_from(f, 0, largest, held, sizeof held));
    }
    if (f->time_to_us != 1.0 && !(fabs(t) <= 0.5 * TIME_MAX_US)) {
        /* a time in s or ms is a product: from 2^52 us on it no longer
         * resolves a microsecond, and distinct rows would read as one */
        return sim_log_fail(err, f->path, c->line_no, column_of(f, largest),
                            "time %.9g s is beyond what a time in s or ms resolves to the microsecond (2^52 us)%s: "
                            "give the time in us, or from a nearer origin",
                            t * 1e-6, summed_from(f, 0, largest, held, sizeof held));
    }
    if (f->rows > 0 && t <= f->last_read_us) {
        if (t == f->last_read_us) {
            return sim_log_fail(err, f->path, c->line_no, column_of(f, col), "time repeats (%.9g s)", t * 1e-6);
        }
        return sim_log_fail(err, f->path, c->line_no, column_of(f, col), "time goes back from %.9g s to %.9g s",
                            f->last_read_us * 1e-6, t * 1e-6);
    }
    for (int i = 1; i <= f->n_items; ++i) {
        f->present[i - 1] = 0;
        v[i - 1] = 0.0;
        const double sum = item_sum(f, i, &col, &largest);
        if (col < 0) {
            continue;
        }
        f->present[i - 1] = 1;
        v[i - 1] = sum * f->item[i]->scale;
        if (!(fabs(v[i - 1]) <= VALUE_MAX)) {
            char field[32];
            sim_log_slot_name(f->slot[i - 1], field, sizeof field);
            return sim_log_fail(err, f->path, c->line_no, column_of(f, largest),
                                "%s is %g, beyond the reader's range (1e15)%s", field, v[i - 1],
                                summed_from(f, i, largest, held, sizeof held));
        }
    }
    if (quat_of_no_length(f, v, SIM_LOG_G_QUAT) || quat_of_no_length(f, v, SIM_LOG_G_REF_QUAT)) {
        return sim_log_fail(err, f->path, c->line_no, 1, "a quaternion of no length (all four components 0)");
    }
    *t_us = t;
    f->last_read_us = t;
    ++f->rows;
    return 1;
}

/* The next row in order: the held ones first. Counts the gaps. */
static int next_row(sim_log_file_t *f, double *t_us, double *v, sim_log_error_t *err)
{
    if (f->buf_pos < f->buf_n) {
        *t_us = f->buf_t[f->buf_pos];
        memcpy(v, &f->buf_v[(size_t)f->buf_pos * (size_t)f->n_items], (size_t)f->n_items * sizeof *v);
        ++f->buf_pos;
    } else {
        const int rc = read_row(f, t_us, v, err);
        if (rc <= 0) {
            return rc;
        }
    }
    if (f->buf_pos > 1) { /* not the first row */
        const double period = *t_us - f->prev_used_us;
        if (period > SIM_LOG_GAP_FACTOR * f->median_us) {
            ++f->gaps;
            if (period > f->longest_gap_us) {
                f->longest_gap_us = period;
            }
        }
    }
    f->prev_used_us = *t_us;
    return 1;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Room for twice as many held rows (a short file holds a few). */
static int grow_held(sim_log_file_t *f, size_t *cap)
{
    const size_t rows = *cap == 0 ? 16 : (2 * *cap < SIM_LOG_PERIOD_ROWS ? 2 * *cap : SIM_LOG_PERIOD_ROWS);
    double *t = realloc(f->buf_t, rows * sizeof *t);
    if (t == NULL) {
        return -1;
    }
    f->buf_t = t;
    double *v = realloc(f->buf_v, rows * ((size_t)f->n_items + 1) * sizeof *v);
    if (v == NULL) {
        return -1;
    }
    f->buf_v = v;
    *cap = rows;
    return 0;
}

/* Holds the first rows and takes the median of their periods (the lower
 * middle one: a whole number of microseconds when the rows' times are). */
static int hold_first_rows(sim_log_file_t *f, sim_log_error_t *err)
{
    const size_t stride = (size_t)f->n_items;
    size_t cap = 0;
    while (f->buf_n < SIM_LOG_PERIOD_ROWS) {
        if ((size_t)f->buf_n == cap && grow_held(f, &cap) != 0) {
            return sim_log_fail(err, f->path, 0, 0, "out of memory");
        }
        const int rc = read_row(f, &f->buf_t[f->buf_n], &f->buf_v[(size_t)f->buf_n * stride], err);
        if (rc < 0) {
            return -1;
        }
        if (rc == 0) {
            break;
        }
        ++f->buf_n;
    }
    if (f->buf_n < 2) {
        int line, column;
        sim_log_csv_end(&f->csv, &line, &column);
        return sim_log_fail(err, f->path, line, column, "fewer than 2 rows (%d)", f->buf_n);
    }
    double *period = malloc((size_t)(f->buf_n - 1) * sizeof *period);
    if (period == NULL) {
        return sim_log_fail(err, f->path, 0, 0, "out of memory");
    }
    for (int i = 1; i < f->buf_n; ++i) {
        period[i - 1] = f->buf_t[i] - f->buf_t[i - 1];
    }
    qsort(period, (size_t)(f->buf_n - 1), sizeof *period, cmp_double);
    f->median_us = period[(f->buf_n - 2) / 2];
    free(period);
    return 0;
}

static long long file_size(FILE *stream)
{
    long long size = 0;
    const long at = ftell(stream);
    if (at >= 0 && fseek(stream, 0, SEEK_END) == 0) {
        const long end = ftell(stream);
        size = end > at ? end - at : 0;
        if (fseek(stream, at, SEEK_SET) != 0) {
            size = 0;
        }
    }
    return size;
}

static int open_rest(sim_log_file_t *f, sim_log_error_t *err)
{
    int rc = sim_log_csv_init(&f->csv, f->f);
    if (rc != 0) {
        return sim_log_fail(err, f->path, 0, 0, "out of memory");
    }
    f->csv_ready = 1;
    rc = sim_log_csv_next(&f->csv, err);
    if (rc < 0) {
        return -1;
    }
    if (rc == 0) {
        int line, column;
        sim_log_csv_end(&f->csv, &line, &column);
        return sim_log_fail(err, f->path, line, column, "no header line");
    }
    f->n_header = f->csv.n_cells;
    f->header_line = f->csv.line_no;
    f->header_end = f->csv.end_column;
    if (resolve(f, err) != 0) {
        return -1;
    }
    list_needed(f);
    f->cell_v = calloc((size_t)f->n_header, sizeof *f->cell_v);
    f->v0 = malloc(((size_t)f->n_items + 1) * sizeof *f->v0);
    f->v1 = malloc(((size_t)f->n_items + 1) * sizeof *f->v1);
    if (f->cell_v == NULL || f->v0 == NULL || f->v1 == NULL) {
        return sim_log_fail(err, f->path, 0, 0, "out of memory");
    }
    if (hold_first_rows(f, err) != 0) {
        return -1;
    }
    (void)next_row(f, &f->t0, f->v0, err); /* held: cannot fail */
    (void)next_row(f, &f->t1, f->v1, err);
    return 0;
}

int sim_log_file_open(sim_log_file_t *f, FILE *stream, int own, const char *path, const sim_log_item_t *time,
                      const sim_log_map_t *map, const char *topic, sim_log_error_t *err)
{
    memset(f, 0, sizeof *f);
    snprintf(f->path, sizeof f->path, "%s", path);
    f->f = stream;
    f->own = own;
    f->size = own ? file_size(stream) : 0;
    f->item[0] = time;
    for (int slot = 1; slot < SIM_LOG_N_SLOTS; ++slot) {
        if (map->mapped[slot] && (topic == NULL || strcmp(map->item[slot].topic, topic) == 0)) {
            f->slot[f->n_items] = slot;
            f->item[++f->n_items] = &map->item[slot];
        }
    }
    f->time_to_us = snap_whole(time->scale * 1e6, 1e-9);
    if (open_rest(f, err) != 0) {
        sim_log_file_close(f);
        return -1;
    }
    return 0;
}

int sim_log_file_reach(sim_log_file_t *f, double tick_us, sim_log_error_t *err)
{
    while (f->t1 < tick_us) {
        double *swap = f->v0;
        f->v0 = f->v1;
        f->v1 = swap;
        f->t0 = f->t1;
        const int rc = next_row(f, &f->t1, f->v1, err);
        if (rc <= 0) {
            f->t1 = f->t0; /* the last row, for what is read after the end */
            memcpy(f->v1, f->v0, (size_t)f->n_items * sizeof *f->v1);
            return rc;
        }
    }
    return 1;
}

void sim_log_file_close(sim_log_file_t *f)
{
    if (f->csv_ready) {
        sim_log_csv_free(&f->csv);
        f->csv_ready = 0;
    }
    if (f->own && f->f != NULL) {
        fclose(f->f);
    }
    f->f = NULL;
    free(f->cell_v);
    free(f->buf_t);
    free(f->buf_v);
    free(f->v0);
    free(f->v1);
    f->cell_v = f->buf_t = f->buf_v = f->v0 = f->v1 = NULL;
}
