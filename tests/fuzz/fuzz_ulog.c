/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the ULog decoder (sim_log_ulog_to_csv_stream) on
 * arbitrary bytes through fmemopen, every topic and then two topics asked
 * for, into a temporary folder emptied after each input. Besides what the
 * sanitizers catch, it checks that:
 * - a refused input's error is `fuzz.ulg: offset N: ...` with N inside the
 *   input, and leaves no file;
 * - an accepted one wrote as many files and rows as its statistics count,
 *   each file a header and rows of as many cells, the first cell a whole
 *   number of microseconds that increases row by row; a cut or corrupt end
 *   lies inside the input.
 */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkdtemp */
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "log/log_ulog.h"

static char dir[64];

static void remove_dir(void)
{
    (void)rmdir(dir); /* emptied after each input */
}

static void make_dir(void)
{
    if (dir[0] == '\0') {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/fuzz_ulog.XXXXXX", tmp != NULL && strlen(tmp) < 40 ? tmp : "/tmp");
        FUZZ_CHECK(mkdtemp(dir) != NULL, "mkdtemp %s", dir);
        atexit(remove_dir);
    }
}

/* One CSV: its rows, after checking its cells and its time. */
static long long check_csv(const char *path)
{
    FILE *f = fopen(path, "rb");
    FUZZ_CHECK(f != NULL, "cannot read %s", path);
    long long rows = -1, cells = 0, header_cells = 0;
    unsigned long long t = 0, t_prev = 0;
    int in_first = 1, digits = 0, ch;
    while ((ch = fgetc(f)) != EOF) {
        if (ch == ',' || ch == '\n') {
            if (in_first && rows >= 0) {
                FUZZ_CHECK(digits > 0, "%s: row %lld: the timestamp is not a number", path, rows + 1);
                FUZZ_CHECK(rows == 0 || t > t_prev, "%s: row %lld: timestamp %llu after %llu", path, rows + 1, t,
                           t_prev);
                t_prev = t;
            }
            in_first = 0;
            ++cells;
        } else if (in_first && rows >= 0) {
            FUZZ_CHECK(ch >= '0' && ch <= '9' && digits < 20, "%s: row %lld: timestamp byte %d", path, rows + 1, ch);
            t = t * 10u + (unsigned)(ch - '0');
            ++digits;
        }
        if (ch == '\n') {
            if (rows < 0) {
                header_cells = cells;
            } else {
                FUZZ_CHECK(cells == header_cells, "%s: row %lld has %lld cells, the header %lld", path, rows + 1, cells,
                           header_cells);
            }
            ++rows;
            cells = 0;
            in_first = 1;
            digits = 0;
            t = 0;
        }
    }
    fclose(f);
    FUZZ_CHECK(rows >= 1 && cells == 0, "%s: %lld rows, %lld cells after the last line end", path, rows, cells);
    return rows;
}

/* Checks (when accepted) and removes every file of the folder: their count
 * and rows. */
static void sweep(int accepted, int *files, long long *rows)
{
    DIR *d = opendir(dir);
    FUZZ_CHECK(d != NULL, "opendir %s", dir);
    const struct dirent *e;
    char path[4096];
    *files = 0;
    *rows = 0;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) {
            continue;
        }
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (accepted) {
            *rows += check_csv(path);
        }
        ++*files;
        remove(path);
    }
    closedir(d);
}

static void decode(const uint8_t *data, size_t size, const char *const *topics, int n_topics)
{
    FILE *f = fmemopen((void *)(uintptr_t)data, size, "rb");
    FUZZ_CHECK(f != NULL, "fmemopen of %zu bytes", size);
    char base[128];
    snprintf(base, sizeof base, "%s/fuzz", dir);
    sim_log_ulog_stats_t st;
    sim_log_error_t err;
    memset(&err, 0, sizeof err);
    const int rc =
        sim_log_ulog_to_csv_stream(f, "fuzz.ulg", (long long)size, base, topics, n_topics, NULL, NULL, &st, &err);
    fclose(f);
    int files;
    long long rows;
    sweep(rc == 0, &files, &rows);
    if (rc != 0) {
        long long offset = -1;
        const int is_input = strcmp(err.path, "fuzz.ulg") == 0;
        FUZZ_CHECK(rc == -1 && err.line == 0 && err.message[0] != '\0', "rc %d, %s:%d: %s", rc, err.path, err.line,
                   err.message);
        FUZZ_CHECK(!is_input ||
                       (sscanf(err.message, "offset %lld: ", &offset) == 1 && offset >= 0 && (size_t)offset < size),
                   "error '%s' outside the %zu bytes", err.message, size);
        FUZZ_CHECK(is_input || strncmp(err.path, dir, strlen(dir)) == 0, "error path '%s': %s", err.path, err.message);
        FUZZ_CHECK(files == 0, "%d files left after a refusal: %s", files, err.message);
        return;
    }
    FUZZ_CHECK(files == st.files && rows == st.rows, "%d files, %lld rows written; counted %d, %lld", files, rows,
               st.files, st.rows);
    FUZZ_CHECK(st.bytes == (long long)size, "%lld bytes read of %zu", st.bytes, size);
    FUZZ_CHECK(st.end == SIM_LOG_ULOG_END_WHOLE || (st.end_offset >= 16 && (size_t)st.end_offset < size),
               "end %d at offset %lld of %zu", (int)st.end, st.end_offset, size);
    char notes[1024];
    const int n = sim_log_ulog_stats_describe(&st, notes, sizeof notes);
    FUZZ_CHECK(n >= 0 && (n == 0) == (notes[0] == '\0'), "%d notes: '%s'", n, notes);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0) {
        return 0; /* fmemopen wants a buffer */
    }
    make_dir();
    decode(data, size, NULL, 0);
    static const char *const topics[] = {"vehicle_angular_velocity", "a"};
    decode(data, size, topics, 2);
    return 0;
}
