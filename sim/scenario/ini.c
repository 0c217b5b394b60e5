/* SPDX-License-Identifier: BSD-3-Clause */
/* The line structure of scenario and campaign files, and the places of
 * their errors (ini.h). */
#include "ini.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
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

int ini_column(const ini_place_t *place, const char *at)
{
    return (int)(at - place->line_start) + 1;
}

void ini_vset_error(sim_parse_error_t *err, int line, int col, const char *format, va_list ap)
{
    err->line = line;
    err->column = col;
    vsnprintf(err->message, sizeof err->message, format, ap);
}

int ini_fail_at(ini_place_t *place, int line, int col, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    ini_vset_error(place->err, line, col, format, ap);
    va_end(ap);
    return -1;
}

int ini_section_header(ini_place_t *place, char *s)
{
    char *close = strchr(s, ']');
    if (close == NULL) {
        return ini_fail(place, s + strlen(s), "expected ']'");
    }
    char *after = ini_skip_space(close + 1);
    if (*after != '\0') {
        return ini_fail(place, after, "trailing characters after ']'");
    }
    *close = '\0';
    return 0;
}

int ini_lines(char *text, ini_place_t *place, ini_line_fn fn, void *ctx)
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
        ++place->line;
        place->line_start = start;
        char *hash = strchr(start, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        ini_trim_end(start);
        char *s = ini_skip_space(start);
        if (*s != '\0' && fn(ctx, s) != 0) {
            return -1;
        }
    }
    return 0;
}

int ini_read_file_max(const char *path, size_t max_bytes, char **text, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    size_t cap = 4096;
    size_t n = 0;
    char *buf = malloc(cap);
    int rc = buf != NULL ? 0 : -2;
    while (rc == 0) {
        /* never more than one byte past the most: a huge file costs no more */
        const size_t room = cap - 1 - n;
        n += fread(buf + n, 1, max_bytes - n < room ? max_bytes - n + 1 : room, f);
        if (n > max_bytes) {
            rc = -4;
        } else if (n < cap - 1) {
            break; /* the end, or an error */
        } else {
            const size_t grow = cap * 2 - 1 > max_bytes + 1 ? max_bytes + 2 : cap * 2;
            char *grown = realloc(buf, grow);
            if (grown == NULL) {
                rc = -2;
            } else {
                buf = grown;
                cap = grow;
            }
        }
    }
    if (rc == 0 && ferror(f)) {
        rc = -3;
    }
    fclose(f);
    if (rc != 0) {
        free(buf);
        errno = rc == -2 ? ENOMEM : rc == -3 ? EIO : EFBIG;
        return rc;
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return 0;
}

int ini_read_file(const char *path, char **text, size_t *len)
{
    return ini_read_file_max(path, INI_FILE_MAX_BYTES, text, len);
}
