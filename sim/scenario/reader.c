/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario reader (parser.h): a file's lines and the command line's
 * settings, [section] headers, and each KEY = VALUE filed by the key table
 * (schema.h): the key known in its section and for its controller, given
 * once (a setting replaces the file's value), its value to the lexer.
 */
#include "parser.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_key_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

static int parse_key_line(parser_t *p, char *s)
{
    char *key = s;
    while (is_key_char(*s)) {
        ++s;
    }
    const size_t key_len = (size_t)(s - key);
    if (key_len == 0) {
        return ini_fail(&p->place, key, "expected a key or a [section]");
    }
    char *eq = ini_skip_space(s);
    if (*eq != '=') {
        return ini_fail(&p->place, eq, "expected '=' after '%.*s'", SHOWN(key_len), key);
    }
    key[key_len] = '\0'; /* may overwrite '=': eq still points past the key */
    char *value = ini_skip_space(eq + 1);
    const int key_col = ini_column(&p->place, key);
    if (p->section < 0) {
        return ini_fail(&p->place, key, "key '%s' before any [section]", key);
    }
    if (*value == '\0') {
        return ini_fail(&p->place, value, "missing value for '%s'", key);
    }
    const int sec = p->section;
    const int table = SCHEMA_TABLE(sec);
    const int k = schema_find_key(table, key);
    if (k < 0) {
        char title[48];
        return ini_fail(&p->place, key, "unknown key '%s' in %s", key, schema_section_title(sec, title, sizeof title));
    }
    if (table == SEC_CONTROLLER && !schema_applies_to(&SCHEMA_KEYS[k], sec - SEC_CONTROLLER)) {
        return ini_fail(&p->place, key, "'%s' does not apply to %s", key,
                        sim_controller_name((sim_controller_id_t)(sec - SEC_CONTROLLER)));
    }
    loc_t *seen = &p->seen[sec][k];
    char *base = (table == SEC_CONTROLLER) ? (char *)&p->sc->overrides[sec - SEC_CONTROLLER] : (char *)p->sc;
    if (p->first_set_line > 0 && seen->line != 0 && seen->line < p->first_set_line) {
        /* a command-line setting replaces the file's value, every piece of a signal */
        memset(seen, 0, sizeof *seen);
        if (SCHEMA_KEYS[k].type == V_SIGNAL) {
            ((sim_signal_t *)(void *)(base + SCHEMA_KEYS[k].offset))->n_pieces = 0;
        }
    }
    if (p->first_set_line > 0 && SCHEMA_KEYS[k].twin != NULL) {
        loc_t *twin = &p->seen[sec][schema_find_key(table, SCHEMA_KEYS[k].twin)];
        if (twin->line != 0 && twin->line < p->first_set_line) {
            memset(twin, 0, sizeof *twin); /* the same field: replaced as well */
        }
    }
    if (seen->line != 0 && SCHEMA_KEYS[k].type != V_SIGNAL) {
        if (p->first_set_line > 0) {
            return ini_fail(&p->place, key, "duplicate key '%s' (set twice on the command line)", key);
        }
        return ini_fail(&p->place, key, "duplicate key '%s' (first given on line %d)", key, seen->line);
    }
    if (SCHEMA_KEYS[k].twin != NULL) {
        const loc_t *twin = &p->seen[sec][schema_find_key(table, SCHEMA_KEYS[k].twin)];
        if (twin->line != 0) {
            if (p->first_set_line > 0) {
                return ini_fail(&p->place, key, "'%s' and '%s' set the same value (both on the command line)", key,
                                SCHEMA_KEYS[k].twin);
            }
            return ini_fail(&p->place, key, "'%s' and '%s' (line %d) set the same value", key, SCHEMA_KEYS[k].twin,
                            twin->line);
        }
    }
    if (seen->line == 0) {
        seen->line = p->place.line;
        seen->key_col = key_col;
        seen->value_col = ini_column(&p->place, value);
    }
    return lex_value(p, k, base, value, key_col);
}

static int parse_section(parser_t *p, char *s)
{
    if (ini_section_header(&p->place, s) != 0) {
        return -1;
    }
    char *rest = s + 1;
    size_t len;
    char *name = lex_next_token(&rest, &len);
    if (len == 0) {
        return ini_fail(&p->place, name, "expected a section name");
    }
    int sec = schema_find_section(name, len);
    if (sec < 0) {
        return ini_fail(&p->place, name, "unknown section [%.*s]", SHOWN(len), name);
    }
    if (sec == SEC_CONTROLLER) {
        char *ctrl = lex_next_token(&rest, &len);
        if (len == 0) {
            return ini_fail(&p->place, ctrl, "expected a controller name after 'controller'");
        }
        const int id = schema_controller_id(ctrl, len);
        if (id < 0) {
            return lex_fail_unknown_controller(p, ctrl, len);
        }
        sec += id;
    }
    char *extra = lex_next_token(&rest, &len);
    if (len > 0) {
        return ini_fail(&p->place, extra, "unexpected '%.*s' in the section header", SHOWN(len), extra);
    }
    if (p->section_line[sec] != 0) {
        char title[48];
        return ini_fail(&p->place, s, "section %s already given on line %d",
                        schema_section_title(sec, title, sizeof title), p->section_line[sec]);
    }
    p->section_line[sec] = p->place.line;
    p->section = sec;
    return 0;
}

/* One command-line setting SECTION.KEY=VALUE as a line of SECTION. */
static int parse_setting(parser_t *p, char *s)
{
    p->place.line_start = s;
    char *eq = strchr(s, '=');
    char *dot = strchr(s, '.');
    if (eq == NULL || dot == NULL || dot > eq) {
        return ini_fail(&p->place, s, "expected SECTION.KEY=VALUE, got '%.*s'", SHOWN(strlen(s)), s);
    }
    char *name = ini_skip_space(s);
    size_t len = 0;
    while (name + len < dot && is_key_char(name[len])) {
        ++len;
    }
    int sec = schema_find_section(name, len);
    char *rest = name + len;
    if (sec < 0 || (sec != SEC_CONTROLLER && ini_skip_space(rest) != dot)) {
        return ini_fail(&p->place, name, "unknown section '%.*s'", SHOWN((size_t)(dot - name)), name);
    }
    if (sec == SEC_CONTROLLER) {
        if (*rest == ':') {
            ++rest;
        }
        char *ctrl = ini_skip_space(rest);
        char *end = ctrl;
        while (end < dot && !ini_is_space(*end)) {
            ++end;
        }
        if (end == ctrl) {
            return ini_fail(&p->place, ctrl,
                            "expected a controller name after 'controller' ('controller:NAME.KEY=VALUE')");
        }
        const int id = schema_controller_id(ctrl, (size_t)(end - ctrl));
        if (id < 0) {
            return lex_fail_unknown_controller(p, ctrl, (size_t)(end - ctrl));
        }
        if (ini_skip_space(end) != dot) {
            return ini_fail(&p->place, ini_skip_space(end), "expected '.' after the controller's name");
        }
        sec += id;
    }
    if (p->section_line[sec] == 0) {
        p->section_line[sec] = p->place.line;
    }
    p->section = sec;
    char *key = ini_skip_space(dot + 1);
    if (key == eq) {
        return ini_fail(&p->place, key, "expected a key after '.'");
    }
    return parse_key_line(p, key);
}

static int read_line(void *ctx, char *s)
{
    parser_t *p = (parser_t *)ctx;
    return (*s == '[') ? parse_section(p, s) : parse_key_line(p, s);
}

int reader_lines(parser_t *p, char *text)
{
    return ini_lines(text, &p->place, read_line, p);
}

int reader_settings(parser_t *p, const char *const *sets, int n_sets)
{
    p->first_set_line = p->place.line + 1;
    p->sc->first_set_line = p->first_set_line;
    for (int i = 0; i < n_sets; ++i) {
        p->place.line = p->first_set_line + i;
        const size_t n = strlen(sets[i]);
        char *copy = malloc(n + 1);
        if (copy == NULL) {
            return ini_fail_at(&p->place, p->place.line, 1, "out of memory");
        }
        memcpy(copy, sets[i], n + 1);
        const int rc = parse_setting(p, copy);
        free(copy);
        if (rc != 0) {
            return -1;
        }
    }
    return 0;
}
