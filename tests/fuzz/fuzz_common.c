/* SPDX-License-Identifier: BSD-3-Clause */
/* What every fuzz target shares (see fuzz.h). */
#include "fuzz.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

void fuzz_fail(const char *file, int line, const char *cond, const char *format, ...)
{
    va_list ap;
    fprintf(stderr, "%s:%d: check failed: %s: ", file, line, cond);
    va_start(ap, format);
    vfprintf(stderr, format, ap);
    va_end(ap);
    fputc('\n', stderr);
    abort();
}

void fuzz_measure_lines(const uint8_t *data, size_t size, int line, int *lines, size_t *line_len)
{
    int n = 1;
    size_t start = 0;
    *line_len = 0;
    for (size_t i = 0; i <= size; ++i) {
        if (i == size || data[i] == '\n') {
            if (n == line) {
                *line_len = i - start;
            }
            if (i < size) {
                ++n;
                start = i + 1;
            }
        }
    }
    *lines = n;
}
