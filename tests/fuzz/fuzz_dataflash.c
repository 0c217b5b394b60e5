/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the ArduPilot DataFlash decoder
 * (sim_log_dataflash_to_csv_stream) on arbitrary bytes, every message type
 * written. Besides what the sanitizers catch, it checks that:
 * - a refused input has its error at an offset ("offset N: ...", N within
 *   the input) and leaves no file behind;
 * - an accepted one wrote as many CSVs as it counts, each with a header and
 *   rows of as many cells, and a TimeUS column (GYR, ACC: SampleUS; where
 *   there is one) whose values increase strictly; the bytes skipped and the
 *   cut lie within the input.
 */
#define _POSIX_C_SOURCE 200809L /* fmemopen, mkdtemp, opendir */
#include "fuzz.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "log/log_dataflash.h"

static char dir[64];

static void remove_dir(void)
{
    rmdir(dir);
}

static int cells_of(const char *line)
{
    int n = 1;
    for (const char *p = line; *p != '\0' && *p != '\n'; ++p) {
        n += *p == ',';
    }
    return n;
}

/* The header's cells and the index of the column that times the rows
 * (-1: none): SampleUS for GYR and ACC, TimeUS for the others. */
static int header_of(const char *line, const char *time_name, int *time_col)
{
    *time_col = -1;
    int col = 0;
    const size_t k = strlen(time_name);
    for (const char *p = line;; ++col) {
        const size_t n = strcspn(p, ",\n");
        if (n == k && strncmp(p, time_name, k) == 0) {
            *time_col = col;
        }
        if (p[n] != ',') {
            return col + 1;
        }
        p += n + 1;
    }
}

static long long cell_value(const char *line, int col)
{
    const char *p = line;
    for (int i = 0; i < col; ++i) {
        p = strchr(p, ',') + 1;
    }
    return strtoll(p, NULL, 10);
}

static void check_csv(const char *path, const char *file)
{
    static char line[1 << 16];
    FILE *f = fopen(path, "r");
    FUZZ_CHECK(f != NULL, "cannot read %s", path);
    FUZZ_CHECK(fgets(line, sizeof line, f) != NULL, "%s: no header", path);
    int time_col;
    const int sampled = strncmp(file, "log_GYR_", 8) == 0 || strncmp(file, "log_ACC_", 8) == 0;
    const int cells = header_of(line, sampled ? "SampleUS" : "TimeUS", &time_col);
    long long prev = 0, rows = 0;
    while (fgets(line, sizeof line, f) != NULL) {
        FUZZ_CHECK(strchr(line, '\n') != NULL, "%s: row %lld unended or too long", path, rows + 1);
        FUZZ_CHECK(cells_of(line) == cells, "%s: row %lld has %d cells, the header %d", path, rows + 1, cells_of(line),
                   cells);
        if (time_col >= 0) {
            const long long t = cell_value(line, time_col);
            FUZZ_CHECK(rows == 0 || t > prev, "%s: row %lld at TimeUS %lld after %lld", path, rows + 1, t, prev);
            prev = t;
        }
        ++rows;
    }
    fclose(f);
}

/* Checks (check) and removes the files of dir: their count. */
static int sweep(int check)
{
    DIR *d = opendir(dir);
    FUZZ_CHECK(d != NULL, "opendir %s", dir);
    char path[sizeof dir + 260]; /* dir, '/', a name of up to 255 bytes */
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (e->d_name[0] == '.') {
            continue;
        }
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (check) {
            check_csv(path, e->d_name);
        }
        remove(path);
        ++n;
    }
    closedir(d);
    return n;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (dir[0] == '\0') {
        snprintf(dir, sizeof dir, "/tmp/fuzz_dataflash_XXXXXX");
        FUZZ_CHECK(mkdtemp(dir) != NULL, "mkdtemp");
        atexit(remove_dir);
    }
    if (size == 0) {
        return 0; /* fmemopen of 0 bytes fails on some C libraries */
    }
    FILE *f = fmemopen((void *)(uintptr_t)data, size, "r");
    FUZZ_CHECK(f != NULL, "fmemopen of %zu bytes", size);
    char base[128];
    snprintf(base, sizeof base, "%s/log", dir);
    static sim_log_dataflash_stats_t st;
    sim_log_error_t err;
    memset(&err, 0, sizeof err);
    const int rc = sim_log_dataflash_to_csv_stream(f, "fuzz.bin", base, NULL, 0, NULL, NULL, &st, &err);
    fclose(f);
    if (rc != 0) {
        long long offset = -1;
        FUZZ_CHECK(sscanf(err.message, "offset %lld:", &offset) == 1 && offset >= 0 && offset <= (long long)size,
                   "refused without an offset in the input: %s: %s", err.path, err.message);
        FUZZ_CHECK(sweep(0) == 0, "files left after a refusal: %s", err.message);
        return 0;
    }
    FUZZ_CHECK(st.bytes == (long long)size, "%lld bytes read of %zu", st.bytes, size);
    FUZZ_CHECK(st.skipped_bytes >= 0 && st.skipped_bytes <= (long long)size, "%lld skipped", st.skipped_bytes);
    FUZZ_CHECK(st.first_skip_offset < (long long)size, "first skip at %lld", st.first_skip_offset);
    FUZZ_CHECK(!st.truncated || (st.truncated_offset >= 0 && st.truncated_offset < (long long)size), "cut at %lld",
               st.truncated_offset);
    const int files = sweep(1);
    FUZZ_CHECK(files == st.files, "%d files written, %d counted", files, st.files);
    return 0;
}
