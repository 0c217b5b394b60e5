/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario parser's state, internal to it (scenario.h is the interface).
 * One parse goes through four rooms:
 *   lexer.c    a value's text into numbers, words, windows and signal pieces;
 *   reader.c   lines, [section] headers and the command line's settings,
 *              each KEY = VALUE filed by the key table (schema.h);
 *   checks.c   once everything is read: the checks across keys, then what
 *              the library accepts, each error at the key responsible;
 *   scenario.c the entry points: defaults, the text, the order of the above.
 * Errors are recorded at their place with ini.h's helpers (ini_fail), as the
 * campaign parser's are.
 */
#ifndef LADRC_SIM_PARSER_H
#define LADRC_SIM_PARSER_H

#include <stdarg.h>
#include <stddef.h>

#include "ini.h"
#include "scenario.h"
#include "schema.h"

/* Where a key was given. */
typedef struct {
    int line; /* 0: not given */
    int key_col;
    int value_col;
} loc_t;

typedef struct {
    sim_scenario_t *sc;
    ini_place_t place; /* the current line, and where errors go */
    int section;       /* SEC_* slot, -1 before the first header */
    int section_line[SEC_COUNT];
    loc_t seen[SEC_COUNT][SCHEMA_MAX_KEYS];
    int piece_line[SCHEMA_MAX_KEYS][SIM_MAX_PIECES];
    int checked;        /* a consistency error is in place.err */
    int first_set_line; /* > 0: reading the command line's settings from this line */
} parser_t;

/* ---- lexer.c ---------------------------------------------------------------- */

/* Next whitespace-separated token at or after *s: its start and length
 * (0 at the end of the value); *s moves past it. */
char *lex_next_token(char **s, size_t *len);

/* The error of an unknown controller name tok[0..len-1]; returns -1. */
int lex_fail_unknown_controller(parser_t *p, const char *tok, size_t len);

/* The value of key (an index in SCHEMA_KEYS) into its field under base
 * (the scenario, or a controller's overrides); 0, or -1 with the error. */
int lex_value(parser_t *p, int key, char *base, char *value, int key_col);

/* ---- reader.c ------------------------------------------------------------------ */

/* The file's lines (text is cut up in place). */
int reader_lines(parser_t *p, char *text);

/* The command line's settings, after the file's lines. */
int reader_settings(parser_t *p, const char *const *sets, int n_sets);

/* ---- checks.c ------------------------------------------------------------------ */

/* Where key `name` of section slot sec was given. */
const loc_t *checks_seen(const parser_t *p, int sec, const char *name);

/* Every check across keys, then the library's; the earliest error is in
 * p->err and p->checked is set. */
void checks_run(parser_t *p);

/* Fills what depends on other keys once the scenario is accepted: metric
 * windows, controllers, output directory, where `tune` was given. */
void checks_finish(parser_t *p);

#endif
