/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Runs a fuzz target's LLVMFuzzerTestOneInput once per file, without
 * libFuzzer: how ctest replays the committed corpora (tests/fuzz/corpus) in
 * every build, sanitizers and coverage included. Arguments are files or
 * directories (their files, not recursively, in name order).
 * Usage: REPLAY PATH...
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz.h"

static int run_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        fprintf(stderr, "replay: cannot open %s\n", path);
        return -1;
    }
    size_t cap = 4096, len = 0;
    unsigned char *data = malloc(cap);
    while (data != NULL) {
        len += fread(data + len, 1, cap - len, f);
        if (len < cap) {
            break;
        }
        unsigned char *grown = realloc(data, cap * 2);
        if (grown == NULL) {
            free(data);
        }
        data = grown;
        cap *= 2;
    }
    const int failed = ferror(f);
    fclose(f);
    if (data == NULL || failed) {
        fprintf(stderr, "replay: cannot read %s\n", path);
        free(data);
        return -1;
    }
    LLVMFuzzerTestOneInput(data, len);
    free(data);
    return 0;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The regular files of a directory, in name order; -1 on error, else the count run. */
static int run_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL) {
        fprintf(stderr, "replay: cannot open %s\n", dir);
        return -1;
    }
    char **names = NULL;
    size_t n = 0;
    for (struct dirent *e = readdir(d); e != NULL; e = readdir(d)) {
        if (e->d_name[0] == '.') {
            continue;
        }
        char **grown = realloc(names, (n + 1) * sizeof *names);
        char *path = malloc(strlen(dir) + strlen(e->d_name) + 2);
        if (grown == NULL || path == NULL) {
            free(path);
            names = grown != NULL ? grown : names;
            break;
        }
        names = grown;
        sprintf(path, "%s/%s", dir, e->d_name);
        names[n++] = path;
    }
    closedir(d);
    if (n > 0) {
        qsort(names, n, sizeof *names, by_name);
    }
    int count = 0;
    for (size_t i = 0; i < n; ++i) {
        struct stat st;
        if (stat(names[i], &st) == 0 && S_ISREG(st.st_mode)) {
            count = (count < 0 || run_file(names[i]) != 0) ? -1 : count + 1;
        }
        free(names[i]);
    }
    free(names);
    return count;
}

int main(int argc, char **argv)
{
    int total = 0;
    for (int i = 1; i < argc; ++i) {
        struct stat st;
        const int n =
            (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode)) ? run_dir(argv[i]) : (run_file(argv[i]) == 0 ? 1 : -1);
        if (n < 0) {
            return 1;
        }
        total += n;
    }
    printf("replay: %d inputs, no failed check\n", total);
    return total > 0 ? 0 : 1;
}
