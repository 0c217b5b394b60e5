/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The line structure that scenario and campaign files share: lines of
 * `[section]` or `key = value`, `#` comments, blank lines, an optional UTF-8
 * byte order mark. What a line means is each parser's own.
 */
#ifndef LADRC_SIM_INI_H
#define LADRC_SIM_INI_H

int ini_is_space(char c);
char *ini_skip_space(char *s);
void ini_trim_end(char *s);

/* One line with its comment and surrounding blanks removed: line_start is
 * where the line begins (for columns), s its first non-blank character.
 * Returns 0 to go on, nonzero to stop. */
typedef int (*ini_line_fn)(void *ctx, const char *line_start, char *s);

/* Cuts text into lines in place and calls fn for each that is not empty;
 * *line counts every line read (1-based numbers for messages). Returns 0, or
 * -1 when fn stopped the reading. */
int ini_lines(char *text, int *line, ini_line_fn fn, void *ctx);

#endif
