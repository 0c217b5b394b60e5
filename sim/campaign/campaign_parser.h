/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The campaign parser's state, internal to it (campaign.h is the interface):
 *   campaign.c         lines, [section] headers, [campaign] and [set] keys,
 *                      the checks once the file is read, the entry points;
 *   campaign_values.c  the names and values of [grid] and [draw] keys, and
 *                      whole numbers.
 * Errors are recorded at their place with ini.h's helpers (ini_fail), as the
 * scenario parser's are. The draws and the runs (campaign_draw.c,
 * campaign_runs.c) work on a parsed campaign.
 */
#ifndef LADRC_SIM_CAMPAIGN_PARSER_H
#define LADRC_SIM_CAMPAIGN_PARSER_H

#include <stddef.h>
#include <stdint.h>

#include "campaign.h"
#include "scenario/ini.h"

enum { SEC_CAMPAIGN, SEC_GRID, SEC_DRAW, SEC_SET, SEC_COUNT };

enum { K_NAME, K_BASE, K_SEED, K_SAMPLES, K_OUTPUT_DIR, K_COUNT };

typedef struct {
    sim_campaign_t *c;
    ini_place_t place; /* the current line, and where errors go */
    int section;
    int section_line[SEC_COUNT];
    int key_line[K_COUNT];
    int base_col;
    /* [grid] and [draw] keys as read, before they are put in order */
    sim_campaign_key_t grid[SIM_CAMPAIGN_MAX_VARIED], draw[SIM_CAMPAIGN_MAX_VARIED];
    int n_grid, n_draw;
} parser_t;

/* ---- campaign_values.c ------------------------------------------------------- */

/* A character of a campaign's name. */
int campaign_is_name_char(char c);

/* An unsigned whole number, at most max, filling the rest of the value
 * (what names it in messages). */
int campaign_parse_whole(parser_t *p, char *s, uint64_t max, uint64_t *out, const char *what);

/* NAME = ... of [grid] or [draw] (p->section), kept in p->grid or p->draw. */
int campaign_parse_varied(parser_t *p, char *key, size_t key_len, char *value);

#endif
