/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the Betaflight blackbox decoder (sim_log_bbl_decode) on
 * arbitrary bytes, for the first log of the file and for the longest.
 * Besides what the sanitizers catch, it checks that:
 * - a refused input has a message `offset N: ...` with N inside the input,
 *   and the input's name;
 * - an accepted one wrote a CSV whose header starts `loopIteration, time
 *   (us)`, whose rows have as many cells as the header, each an integer
 *   (or a decimal number in a converted gyro column), and whose time
 *   increases; as many rows as the statistics count, and statistics that
 *   hold together (the log inside the file, a valid frame count per row), and
 *   their one-line description fits the buffer it is given.
 */
#define _POSIX_C_SOURCE 200809L /* fmemopen, open_memstream */
#include "fuzz.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "log/log_bbl.h"

static void check_refused(size_t size, const sim_log_error_t *err)
{
    long long offset = -1;
    FUZZ_CHECK(strcmp(err->path, "fuzz.bbl") == 0, "path '%s'", err->path);
    if (strncmp(err->message, "offset ", 7) == 0) {
        offset = strtoll(err->message + 7, NULL, 10);
        FUZZ_CHECK(offset >= 0 && (size_t)offset <= size, "offset %lld of %zu bytes: %s", offset, size, err->message);
    } else { /* only the stream's own failures have no offset */
        FUZZ_CHECK(strstr(err->message, "cannot") != NULL || strstr(err->message, "out of memory") != NULL,
                   "no offset: %s", err->message);
    }
}

/* A cell: an optional sign, digits, and a fraction where decimals are allowed. */
static int is_number(const char *p, size_t n, int decimals)
{
    size_t i = 0, digits = 0;
    if (i < n && p[i] == '-') {
        ++i;
    }
    for (; i < n && p[i] >= '0' && p[i] <= '9'; ++i) {
        ++digits;
    }
    if (decimals && i < n && p[i] == '.') {
        for (++i; i < n && p[i] >= '0' && p[i] <= '9'; ++i) {
        }
    }
    return digits > 0 && i == n;
}

static void check_csv(const char *text, size_t len, const sim_log_bbl_stats_t *st)
{
    const char *end = text + len;
    const char *eol = memchr(text, '\n', len);
    FUZZ_CHECK(eol != NULL, "no header line");
    FUZZ_CHECK(len >= 24 && strncmp(text, "loopIteration, time (us)", 24) == 0, "header '%.40s'", text);
    int cells = 1;
    for (const char *p = text; p < eol; ++p) {
        cells += *p == ',';
    }
    long long rows = 0;
    long long t_prev = 0;
    for (const char *line = eol + 1; line < end; ++rows) {
        const char *stop = memchr(line, '\n', (size_t)(end - line));
        FUZZ_CHECK(stop != NULL, "row %lld without its end", rows + 1);
        int cell = 0;
        for (const char *c = line; c <= stop; ++cell) {
            const char *comma = memchr(c, ',', (size_t)(stop - c));
            const char *cend = comma != NULL ? comma : stop;
            FUZZ_CHECK(cell < cells, "row %lld has more than %d cells", rows + 1, cells);
            FUZZ_CHECK(is_number(c, (size_t)(cend - c), 1), "row %lld cell %d: '%.*s'", rows + 1, cell + 1,
                       (int)(cend - c), c);
            if (cell == 1) {
                const long long t = strtoll(c, NULL, 10);
                FUZZ_CHECK(rows == 0 || t > t_prev, "row %lld: time %lld after %lld", rows + 1, t, t_prev);
                t_prev = t;
            }
            c = cend + (comma != NULL ? 2 : 1); /* ", " between cells */
        }
        FUZZ_CHECK(cell == cells, "row %lld has %d cells, the header %d", rows + 1, cell, cells);
        line = stop + 1;
    }
    FUZZ_CHECK(rows == st->rows && rows >= 1, "%lld rows written, %lld counted", rows, st->rows);
    FUZZ_CHECK(st->rows <= st->frames[0] + st->frames[1], "%lld rows from %lld main frames", st->rows,
               st->frames[0] + st->frames[1]);
}

static void decode(const uint8_t *data, size_t size, int index)
{
    FILE *in = fmemopen((void *)(uintptr_t)data, size, "rb");
    FUZZ_CHECK(in != NULL, "fmemopen of %zu bytes", size);
    char *text = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&text, &len);
    FUZZ_CHECK(out != NULL, "open_memstream");
    sim_log_bbl_stats_t st;
    sim_log_error_t err;
    memset(&err, 0, sizeof err);
    const int rc = sim_log_bbl_decode(in, "fuzz.bbl", out, index, NULL, NULL, &st, &err);
    fclose(in);
    fclose(out);
    if (rc != 0) {
        FUZZ_CHECK(rc == -1, "rc %d", rc);
        check_refused(size, &err);
    } else {
        FUZZ_CHECK(st.n_logs >= 1 && st.index >= 1 && st.index <= st.n_logs, "log %d of %d", st.index, st.n_logs);
        FUZZ_CHECK(st.log_offset >= 0 && st.log_bytes > 0 && (size_t)(st.log_offset + st.log_bytes) <= size,
                   "log at %lld, %lld bytes, of %zu", st.log_offset, st.log_bytes, size);
        FUZZ_CHECK(!st.truncated ||
                       (st.truncated_at >= st.log_offset && st.truncated_at < st.log_offset + st.log_bytes),
                   "cut at %lld", st.truncated_at);
        check_csv(text, len, &st);
        char said[160]; /* shorter than some descriptions: cut, and terminated */
        const int n = sim_log_bbl_stats_describe(&st, said, sizeof said);
        FUZZ_CHECK(n >= 0 && (size_t)n < sizeof said && strlen(said) == (size_t)n, "description of %d bytes", n);
    }
    free(text);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) {
        return 0; /* fmemopen wants a buffer */
    }
    decode(data, size, 1);
    decode(data, size, 0);
    return 0;
}
