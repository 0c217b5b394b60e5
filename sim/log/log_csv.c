/* SPDX-License-Identifier: BSD-3-Clause */
/* The streaming CSV row reader (log_csv.h). */
#include "log_csv.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define BLOCK_BYTES 65536  /* read from the file at once */
#define FIRST_LINE_CAP 256 /* the line buffer's first size, doubled as needed */
#define FIRST_CELLS_CAP 64

int sim_log_csv_init(sim_log_csv_t *c, FILE *f)
{
    memset(c, 0, sizeof *c);
    c->f = f;
    c->block = malloc(BLOCK_BYTES);
    c->line = malloc(FIRST_LINE_CAP);
    c->cells = malloc(FIRST_CELLS_CAP * sizeof *c->cells);
    c->line_cap = FIRST_LINE_CAP;
    c->cells_cap = FIRST_CELLS_CAP;
    if (c->block == NULL || c->line == NULL || c->cells == NULL) {
        sim_log_csv_free(c);
        return -1;
    }
    return 0;
}

void sim_log_csv_free(sim_log_csv_t *c)
{
    free(c->block);
    free(c->line);
    free(c->cells);
    c->block = NULL;
    c->line = NULL;
    c->cells = NULL;
}

static int fail(sim_log_error_t *err, int line, int column, const char *message)
{
    err->line = line;
    err->column = column;
    snprintf(err->message, sizeof err->message, "%s", message);
    return -1;
}

static int append(sim_log_csv_t *c, const char *p, size_t n, sim_log_error_t *err)
{
    if (c->line_len + n > SIM_LOG_CSV_LINE_MAX + 1) { /* + 1: a CR before the LF */
        char message[96];
        snprintf(message, sizeof message, "line longer than %d bytes", SIM_LOG_CSV_LINE_MAX);
        return fail(err, c->line_no + 1, SIM_LOG_CSV_LINE_MAX + 1, message);
    }
    if (c->line_len + n > c->line_cap) {
        size_t cap = c->line_cap;
        while (cap < c->line_len + n) {
            cap *= 2;
        }
        char *grown = realloc(c->line, cap);
        if (grown == NULL) {
            return fail(err, c->line_no + 1, 1, "out of memory");
        }
        c->line = grown;
        c->line_cap = cap;
    }
    memcpy(c->line + c->line_len, p, n);
    c->line_len += n;
    return 0;
}

/* One raw line into c->line: 1, 0 when nothing is left, -1 on error. */
static int read_line(sim_log_csv_t *c, sim_log_error_t *err)
{
    int got = 0;
    c->line_len = 0;
    for (;;) {
        if (c->block_pos == c->block_len) {
            if (c->f_done) {
                break;
            }
            c->block_len = fread(c->block, 1, BLOCK_BYTES, c->f);
            c->block_pos = 0;
            if (c->block_len == 0) {
                c->f_done = 1;
                if (ferror(c->f)) {
                    return fail(err, c->line_no + 1, 1, "read error");
                }
                break;
            }
        }
        const char *p = c->block + c->block_pos;
        const size_t avail = c->block_len - c->block_pos;
        const char *nl = memchr(p, '\n', avail);
        const size_t take = nl != NULL ? (size_t)(nl - p) : avail;
        got = 1;
        if (append(c, p, take, err) != 0) {
            return -1;
        }
        c->block_pos += take;
        c->bytes += (long long)take;
        if (nl != NULL) {
            c->block_pos += 1;
            c->bytes += 1;
            c->ended_newline = 1;
            return 1;
        }
    }
    if (got) {
        c->ended_newline = 0; /* a last line without LF */
    }
    return got;
}

static int is_blank(char ch)
{
    return ch == ' ' || ch == '\t';
}

static int add_cell(sim_log_csv_t *c, const char *start, const char *end, sim_log_error_t *err)
{
    while (start < end && is_blank(*start)) {
        ++start;
    }
    while (end > start && is_blank(end[-1])) {
        --end;
    }
    if (c->n_cells == c->cells_cap) {
        sim_log_cell_t *grown = realloc(c->cells, 2 * (size_t)c->cells_cap * sizeof *grown);
        if (grown == NULL) {
            return fail(err, c->line_no, 1, "out of memory");
        }
        c->cells = grown;
        c->cells_cap *= 2;
    }
    sim_log_cell_t *cell = &c->cells[c->n_cells++];
    cell->text = start;
    cell->len = (size_t)(end - start);
    cell->column = (int)(start - (c->line + c->bom)) + 1;
    return 0;
}

int sim_log_csv_next(sim_log_csv_t *c, sim_log_error_t *err)
{
    for (;;) {
        const int rc = read_line(c, err);
        if (rc <= 0) {
            return rc;
        }
        ++c->line_no;
        c->raw_len = c->line_len;
        c->bom = 0;
        if (c->line_no == 1 && c->line_len >= 3 && memcmp(c->line, "\xEF\xBB\xBF", 3) == 0) {
            c->bom = 3;
        }
        if (c->line_len > (size_t)c->bom && c->line[c->line_len - 1] == '\r') {
            --c->line_len;
        }
        const char *start = c->line + c->bom;
        const char *end = c->line + c->line_len;
        const char *p = start;
        while (p < end && (is_blank(*p) || *p == '\r')) {
            ++p;
        }
        if (p == end) {
            continue; /* blank */
        }
        c->n_cells = 0;
        c->end_column = (int)(end - start) + 1;
        for (p = start;;) {
            const char *comma = memchr(p, ',', (size_t)(end - p));
            const char *cell_end = comma != NULL ? comma : end;
            if (add_cell(c, p, cell_end, err) != 0) {
                return -1;
            }
            if (comma == NULL) {
                break;
            }
            p = comma + 1;
        }
        return 1;
    }
}

void sim_log_csv_end(const sim_log_csv_t *c, int *line, int *column)
{
    if (c->line_no == 0) {
        *line = 1;
        *column = 1;
    } else if (c->ended_newline) {
        *line = c->line_no + 1;
        *column = 1;
    } else {
        *line = c->line_no;
        *column = (int)c->raw_len - c->bom + 1;
    }
}

#define NUMBER_CHARS_MAX 127 /* longer cells are no number this reader takes */

static int is_digit(char ch)
{
    return ch >= '0' && ch <= '9';
}

/* Exact powers of ten: 10^0 .. 10^22 are doubles without rounding. */
static const double POW10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
#define FAST_DIGITS_MAX 15 /* a mantissa of 15 digits is below 2^53: exact */

int sim_log_number(const char *text, size_t len, double *v)
{
    char buf[NUMBER_CHARS_MAX + 1];
    size_t i = 0, digits = 0;
    uint64_t mantissa = 0;
    int frac_digits = 0, negative = 0;
    if (len == 0 || len > NUMBER_CHARS_MAX) {
        return -1;
    }
    /* the syntax first: strtod alone would take nan, inf and hex */
    if (text[i] == '+' || text[i] == '-') {
        negative = text[i] == '-';
        ++i;
    }
    for (; i < len && is_digit(text[i]); ++i) {
        mantissa = digits < FAST_DIGITS_MAX ? mantissa * 10u + (uint64_t)(text[i] - '0') : mantissa;
        ++digits;
    }
    if (i < len && text[i] == '.') {
        for (++i; i < len && is_digit(text[i]); ++i) {
            mantissa = digits < FAST_DIGITS_MAX ? mantissa * 10u + (uint64_t)(text[i] - '0') : mantissa;
            ++digits;
            ++frac_digits;
        }
    }
    if (digits == 0) {
        return -1;
    }
    int exponent = 0, exp_sign = 1;
    if (i < len && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        if (i < len && (text[i] == '+' || text[i] == '-')) {
            exp_sign = text[i] == '-' ? -1 : 1;
            ++i;
        }
        const size_t exp_start = i;
        for (; i < len && is_digit(text[i]); ++i) {
            exponent = exponent < 10000 ? exponent * 10 + (text[i] - '0') : exponent;
        }
        if (i == exp_start) {
            return -1;
        }
    }
    if (i != len) {
        return -1;
    }
    /* Clinger's fast path: an exact mantissa times or over an exact power of
     * ten is one correctly rounded operation, the value strtod gives */
    const int power = exp_sign * exponent - frac_digits;
    if (digits <= FAST_DIGITS_MAX && power >= -22 && power <= 22) {
        const double m = (double)mantissa;
        *v = power >= 0 ? m * POW10[power] : m / POW10[-power];
        *v = negative ? -*v : *v;
        return 0;
    }
    memcpy(buf, text, len);
    buf[len] = '\0';
    *v = strtod(buf, NULL);
    return isfinite(*v) ? 0 : -1; /* overflow gives inf */
}

int sim_log_is_nan_text(const char *text, size_t len)
{
    if (len > 0 && (text[0] == '+' || text[0] == '-')) {
        ++text;
        --len;
    }
    return len == 3 && (text[0] | 0x20) == 'n' && (text[1] | 0x20) == 'a' && (text[2] | 0x20) == 'n';
}
