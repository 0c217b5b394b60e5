/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The campaign-file parser (campaign_parser.h): lines, [section] headers,
 * [campaign] and [set] keys, the checks once the file is read, and the
 * entry points. The text is copied once and cut up in place as the
 * scenario parser does: each line NUL-terminated, its comment removed;
 * [set] lines keep pointers into the copy.
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign_parser.h"
#include "scenario/ini.h"

static const char *const SECTION_NAMES[SEC_COUNT] = {"campaign", "grid", "draw", "set"};
static const char *const CAMPAIGN_KEYS[K_COUNT] = {"name", "base", "seed", "samples", "output_dir"};

static int parse_campaign_key(parser_t *p, char *key, char *value)
{
    int k = 0;
    while (k < K_COUNT && strcmp(CAMPAIGN_KEYS[k], key) != 0) {
        ++k;
    }
    if (k == K_COUNT) {
        return ini_fail(&p->place, key,
                        "unknown key '%s' in [campaign] (expected name, base, seed, samples, output_dir)", key);
    }
    if (p->key_line[k] != 0) {
        return ini_fail(&p->place, key, "duplicate key '%s' (first given on line %d)", key, p->key_line[k]);
    }
    p->key_line[k] = p->place.line;
    sim_campaign_t *c = p->c;
    uint64_t v = 0;
    switch (k) {
    case K_NAME:
        for (char *s = value; *s != '\0'; ++s) {
            if (!campaign_is_name_char(*s)) {
                return ini_fail(&p->place, s,
                                "a campaign's name is made of letters, digits, '_', '.' and '-', got '%s'", value);
            }
        }
        if (strlen(value) >= sizeof c->name) {
            return ini_fail(&p->place, value, "name longer than %d characters", (int)sizeof c->name - 1);
        }
        strcpy(c->name, value);
        return 0;
    case K_BASE:
        if (strlen(value) >= sizeof c->base_path - 1) {
            return ini_fail(&p->place, value, "path too long");
        }
        p->base_col = ini_column(&p->place, value);
        strcpy(c->base_path, value); /* made relative to the campaign's directory once read */
        return 0;
    case K_SEED:
        if (campaign_parse_whole(p, value, UINT64_MAX, &v, "seed") != 0) {
            return -1;
        }
        c->seed = v;
        return 0;
    case K_SAMPLES:
        if (campaign_parse_whole(p, value, (uint64_t)SIM_CAMPAIGN_MAX_RUNS, &v, "samples") != 0) {
            return -1;
        }
        if (v < 1u) {
            return ini_fail(&p->place, value, "samples must be at least 1");
        }
        c->samples = (long)v;
        return 0;
    default:
        if (strlen(value) >= sizeof c->output_dir) {
            return ini_fail(&p->place, value, "path too long");
        }
        strcpy(c->output_dir, value);
        return 0;
    }
}

/* KEY = VALUE of [set]: KEY is SECTION.KEY as --set takes it. */
static int parse_set(parser_t *p, char *key, char *value)
{
    if (p->c->n_sets >= SIM_CAMPAIGN_MAX_SETS) {
        return ini_fail(&p->place, key, "more than %d [set] lines", SIM_CAMPAIGN_MAX_SETS);
    }
    if (strchr(key, '.') == NULL) {
        return ini_fail(&p->place, key, "expected SECTION.KEY = VALUE, got '%s' (a [set] line sets a scenario key)",
                        key);
    }
    sim_campaign_set_t *s = &p->c->sets[p->c->n_sets++];
    s->key = key;
    s->value = value;
    s->line = p->place.line;
    s->value_column = ini_column(&p->place, value);
    return 0;
}

static int parse_section(parser_t *p, char *s)
{
    if (ini_section_header(&p->place, s) != 0) {
        return -1;
    }
    char *name = ini_skip_space(s + 1);
    ini_trim_end(name);
    int sec = 0;
    while (sec < SEC_COUNT && strcmp(SECTION_NAMES[sec], name) != 0) {
        ++sec;
    }
    if (sec == SEC_COUNT) {
        return ini_fail(&p->place, name, "unknown section [%.*s] (expected [campaign], [grid], [draw] or [set])",
                        SHOWN(strlen(name)), name);
    }
    if (p->section_line[sec] != 0) {
        return ini_fail(&p->place, s, "section [%s] already given on line %d", name, p->section_line[sec]);
    }
    p->section_line[sec] = p->place.line;
    p->section = sec;
    return 0;
}

static int parse_key_line(parser_t *p, char *s)
{
    char *eq = strchr(s, '=');
    if (eq == NULL) {
        return ini_fail(&p->place, s + strlen(s), "expected KEY = VALUE");
    }
    *eq = '\0';
    ini_trim_end(s);
    char *value = ini_skip_space(eq + 1);
    if (*s == '\0') {
        return ini_fail(&p->place, s, "expected a key before '='");
    }
    if (p->section < 0) {
        return ini_fail(&p->place, s, "key '%s' before any [section]", s);
    }
    if (*value == '\0') {
        return ini_fail(&p->place, value, "missing value for '%s'", s);
    }
    switch (p->section) {
    case SEC_CAMPAIGN:
        return parse_campaign_key(p, s, value);
    case SEC_SET:
        return parse_set(p, s, value);
    default:
        return campaign_parse_varied(p, s, strlen(s), value);
    }
}

static int parse_line(void *ctx, char *s)
{
    parser_t *p = (parser_t *)ctx;
    return (*s == '[') ? parse_section(p, s) : parse_key_line(p, s);
}

static int parse_lines(parser_t *p, char *text)
{
    return ini_lines(text, &p->place, parse_line, p);
}

/* The key with every blank removed, for comparing [set] keys with varied ones. */
static void squeeze(const char *s, char *out, size_t n)
{
    size_t o = 0;
    for (; *s != '\0' && o + 1 < n; ++s) {
        if (!ini_is_space(*s)) {
            out[o++] = *s;
        }
    }
    out[o] = '\0';
}

/* {name} in the [set] values: each a variable; every variable used. */
static int check_variables(parser_t *p)
{
    sim_campaign_t *c = p->c;
    int used[SIM_CAMPAIGN_MAX_VARIED] = {0};
    for (int i = 0; i < c->n_sets; ++i) {
        const sim_campaign_set_t *s = &c->sets[i];
        for (const char *v = s->value; *v != '\0'; ++v) {
            const int col = s->value_column + (int)(v - s->value);
            if (*v == '}') {
                return ini_fail_at(&p->place, s->line, col, "'}' without '{'");
            }
            if (*v != '{') {
                continue;
            }
            const char *close = strchr(v, '}');
            if (close == NULL) {
                return ini_fail_at(&p->place, s->line, col, "'{' without '}'");
            }
            const size_t len = (size_t)(close - v - 1);
            int found = -1;
            for (int k = 0; k < c->n_keys; ++k) {
                if (c->keys[k].is_variable && strlen(c->keys[k].name) == len &&
                    strncmp(c->keys[k].name, v + 1, len) == 0) {
                    found = k;
                }
            }
            if (found < 0) {
                return ini_fail_at(&p->place, s->line, col, "unknown variable '{%.*s}' (define it in [grid] or [draw])",
                                   SHOWN(len), v + 1);
            }
            used[found] = 1;
            v = close;
        }
        char a[SIM_CAMPAIGN_KEY_LEN + 8];
        squeeze(s->key, a, sizeof a);
        if (strcmp(a, "run.seed") == 0) {
            c->sets_seed = 1;
        }
        for (int k = 0; k < c->n_keys; ++k) {
            if (!c->keys[k].is_variable && strcmp(a, c->keys[k].name) == 0) {
                return ini_fail_at(&p->place, s->line, s->value_column - (int)(s->value - s->key),
                                   "'%s' is varied in [%s] (line %d): set it there or here, not both", a,
                                   c->keys[k].is_draw ? "draw" : "grid", c->keys[k].line);
            }
        }
    }
    for (int k = 0; k < c->n_keys; ++k) {
        if (c->keys[k].is_variable && !used[k]) {
            return ini_fail_at(&p->place, c->keys[k].line, c->keys[k].column,
                               "variable '%s' is not used in [set] (write {%s} in a value there)", c->keys[k].name,
                               c->keys[k].name);
        }
        if (strcmp(c->keys[k].name, "run.seed") == 0) {
            c->sets_seed = 1;
        }
    }
    return 0;
}

/* The campaign's name from its file name: without directories and its last extension. */
static void name_from_path(char *name, size_t n, const char *path)
{
    const char *base = strrchr(path, '/');
    base = base != NULL ? base + 1 : path;
    size_t len = strlen(base);
    const char *dot = strrchr(base, '.');
    if (dot != NULL && dot != base) {
        len = (size_t)(dot - base);
    }
    snprintf(name, n, "%.*s", (int)len, base);
}

/* What follows the file's lines: required keys, the order of the keys, the
 * variables, the number of runs, the base scenario's bytes. */
static int finish(parser_t *p)
{
    sim_campaign_t *c = p->c;
    if (p->key_line[K_BASE] == 0) {
        return ini_fail_at(&p->place, p->section_line[SEC_CAMPAIGN], p->section_line[SEC_CAMPAIGN] > 0 ? 1 : 0,
                           "missing base = SCENARIO in [campaign] (the scenario every run starts from)");
    }
    if (c->name[0] == '\0') {
        name_from_path(c->name, sizeof c->name, c->path);
        for (const char *s = c->name; *s != '\0'; ++s) {
            if (!campaign_is_name_char(*s)) {
                return ini_fail_at(&p->place, 0, 0,
                                   "the file's name '%s' is no campaign name (letters, digits, '_', '.', '-'): "
                                   "give [campaign] name",
                                   c->name);
            }
        }
        if (c->name[0] == '\0') {
            return ini_fail_at(&p->place, 0, 0, "no campaign name: give [campaign] name");
        }
    }
    if (c->output_dir[0] == '\0') {
        snprintf(c->output_dir, sizeof c->output_dir, "out/%s", c->name);
    }
    for (int i = 0; i < p->n_grid; ++i) {
        c->keys[c->n_keys++] = p->grid[i];
    }
    for (int i = 0; i < p->n_draw; ++i) {
        c->keys[c->n_keys++] = p->draw[i];
    }
    c->n_grid = p->n_grid;
    p->n_grid = p->n_draw = 0; /* the values belong to c now */
    double runs = (double)c->samples;
    for (int k = 0; k < c->n_grid; ++k) {
        runs *= (double)c->keys[k].n_values;
    }
    if (runs > (double)SIM_CAMPAIGN_MAX_RUNS) {
        return ini_fail_at(&p->place, 0, 0, "%.0f runs: at most %ld in a campaign", runs, SIM_CAMPAIGN_MAX_RUNS);
    }
    c->n_runs = (long)runs;
    if (check_variables(p) != 0) {
        return -1;
    }
    /* the base, relative to the campaign file's directory */
    char base[SIM_PATH_LEN];
    const char *slash = strrchr(c->path, '/');
    if (c->base_path[0] == '/' || slash == NULL) {
        snprintf(base, sizeof base, "%s", c->base_path);
    } else if (snprintf(base, sizeof base, "%.*s/%s", (int)(slash - c->path), c->path, c->base_path) >=
               (int)sizeof base) {
        return ini_fail_at(&p->place, p->key_line[K_BASE], p->base_col, "base path too long");
    }
    memcpy(c->base_path, base, sizeof base);
    if (ini_read_file(c->base_path, &c->base_text, &c->base_len) != 0) {
        return ini_fail_at(&p->place, p->key_line[K_BASE], p->base_col, "cannot read the base scenario '%s': %s",
                           c->base_path, strerror(errno));
    }
    return 0;
}

void sim_campaign_free(sim_campaign_t *c)
{
    if (c == NULL) {
        return;
    }
    for (int k = 0; k < c->n_keys; ++k) {
        free(c->keys[k].values);
    }
    free(c->text);
    free(c->base_text);
    memset(c, 0, sizeof *c);
}

int sim_campaign_parse(sim_campaign_t *c, const char *text, const char *path, sim_campaign_error_t *err)
{
    memset(c, 0, sizeof *c);
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", path);
    if (strlen(path) >= sizeof c->path) {
        snprintf(err->message, sizeof err->message, "path too long");
        return -1;
    }
    strcpy(c->path, path);
    c->seed = 1;
    c->samples = 1;
    const size_t len = strlen(text);
    c->text = malloc(len + 1);
    parser_t *p = calloc(1, sizeof *p);
    if (c->text == NULL || p == NULL) {
        free(p);
        free(c->text);
        c->text = NULL;
        snprintf(err->message, sizeof err->message, "out of memory");
        return -1;
    }
    memcpy(c->text, text, len + 1);
    p->c = c;
    p->place.err = err;
    p->section = -1;
    int rc = parse_lines(p, c->text);
    if (rc == 0) {
        rc = finish(p);
    }
    for (int i = 0; i < p->n_grid; ++i) {
        free(p->grid[i].values);
    }
    for (int i = 0; i < p->n_draw; ++i) {
        free(p->draw[i].values);
    }
    free(p);
    if (rc != 0) {
        sim_campaign_free(c);
    }
    return rc;
}

int sim_campaign_load(sim_campaign_t *c, const char *path, sim_campaign_error_t *err)
{
    char *text = NULL;
    size_t len = 0;
    memset(c, 0, sizeof *c);
    if (ini_read_file(path, &text, &len) != 0) {
        memset(err, 0, sizeof *err);
        snprintf(err->path, sizeof err->path, "%s", path);
        snprintf(err->message, sizeof err->message, "cannot read: %s", strerror(errno));
        return -1;
    }
    if (strlen(text) != len) {
        memset(err, 0, sizeof *err);
        snprintf(err->path, sizeof err->path, "%s", path);
        snprintf(err->message, sizeof err->message, "unexpected NUL byte");
        free(text);
        return -1;
    }
    const int rc = sim_campaign_parse(c, text, path, err);
    free(text);
    return rc;
}
