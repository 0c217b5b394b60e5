/* SPDX-License-Identifier: BSD-3-Clause */
/* The line structure of scenario and campaign files (ini.h). */
#include "ini.h"

#include <string.h>

int ini_is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

char *ini_skip_space(char *s)
{
    while (ini_is_space(*s)) {
        ++s;
    }
    return s;
}

void ini_trim_end(char *s)
{
    size_t n = strlen(s);
    while (n > 0 && ini_is_space(s[n - 1])) {
        s[--n] = '\0';
    }
}

int ini_lines(char *text, int *line, ini_line_fn fn, void *ctx)
{
    if (strncmp(text, "\xEF\xBB\xBF", 3) == 0) {
        text += 3; /* UTF-8 byte order mark */
    }
    char *next = text;
    while (next != NULL) {
        char *start = next;
        char *nl = strchr(start, '\n');
        next = NULL;
        if (nl != NULL) {
            *nl = '\0';
            next = nl + 1;
        }
        ++*line;
        char *hash = strchr(start, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        ini_trim_end(start);
        char *s = ini_skip_space(start);
        if (*s != '\0' && fn(ctx, start, s) != 0) {
            return -1;
        }
    }
    return 0;
}
