/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The line structure that scenario and campaign files share: lines of
 * `[section]` or `key = value`, `#` comments, blank lines, an optional UTF-8
 * byte order mark; and the place of an error in them (line and column).
 * What a line means is each parser's own.
 */
#ifndef LADRC_SIM_INI_H
#define LADRC_SIM_INI_H

#include <stdarg.h>
#include <stddef.h>

#include "scenario.h"

#if defined(__GNUC__)
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

/* Tokens are shown in messages up to this many characters. */
#define SHOWN(len) ((len) > 40 ? 40 : (int)(len))

int ini_is_space(char c);
char *ini_skip_space(char *s);
void ini_trim_end(char *s);

/* Where a parser is in its text, and where its errors go. */
typedef struct {
    sim_parse_error_t *err;
    int line;               /* the current line, 1-based */
    const char *line_start; /* where it begins, for columns */
} ini_place_t;

/* 1-based column of `at` in the current line. */
int ini_column(const ini_place_t *place, const char *at);

/* err's line, column and message. */
void ini_vset_error(sim_parse_error_t *err, int line, int col, const char *format, va_list ap);

/* Records an error at (line, col) in place->err; returns -1. */
int PRINTF_LIKE(4, 5) ini_fail_at(ini_place_t *place, int line, int col, const char *format, ...);

/* The same at `at` in the current line. */
#define ini_fail(place, at, ...) ini_fail_at((place), (place)->line, ini_column((place), (at)), __VA_ARGS__)

/* A section header line s = "[...]": checks its closing ']' and that nothing
 * follows it, and ends the string there (the name starts at s + 1).
 * Returns 0, or -1 with the error recorded at the fault. */
int ini_section_header(ini_place_t *place, char *s);

/* One line with its comment and surrounding blanks removed, s its first
 * non-blank character. Returns 0 to go on, nonzero to stop. */
typedef int (*ini_line_fn)(void *ctx, char *s);

/* Cuts text into lines in place and calls fn for each that is not empty;
 * place->line counts every line read (1-based numbers for messages) and
 * place->line_start is where the line begins. Returns 0, or -1 when fn
 * stopped the reading. */
int ini_lines(char *text, ini_place_t *place, ini_line_fn fn, void *ctx);

/* The most bytes ini_read_file takes: a scenario or campaign is a short
 * text; /dev/zero given as one is refused, not read until memory runs out. */
#define INI_FILE_MAX_BYTES ((size_t)16 * 1024 * 1024)

/* The bytes of the file at path, NUL-terminated, in *text (to free) and
 * their number in *len. Returns 0; -1 when it cannot be opened (errno from
 * fopen), -2 out of memory (errno ENOMEM), -3 a read error (errno EIO), -4
 * more than INI_FILE_MAX_BYTES (errno EFBIG). */
int ini_read_file(const char *path, char **text, size_t *len);

/* The same for a file of at most max_bytes (< SIZE_MAX / 2): -4 (errno
 * EFBIG) for a larger one, having read one byte past the most. */
int ini_read_file_max(const char *path, size_t max_bytes, char **text, size_t *len);

#endif
