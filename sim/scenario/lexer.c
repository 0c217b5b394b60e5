/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario lexer (parser.h): a value's text into tokens, numbers,
 * integers, words of a list, windows and signal pieces, each checked by the
 * key's schema entry. Values are cut up in place.
 */
#include "parser.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- tokens and values ------------------------------------------------------- */

char *lex_next_token(char **s, size_t *len)
{
    char *start = ini_skip_space(*s);
    char *end = start;
    while (*end != '\0' && !ini_is_space(*end)) {
        ++end;
    }
    *len = (size_t)(end - start);
    *s = end;
    return start;
}

/* A signed decimal number filling exactly [tok, tok + len). */
static int parse_number(parser_t *p, const char *tok, size_t len, double *value)
{
    size_t i = (len > 0 && (tok[0] == '-' || tok[0] == '+')) ? 1u : 0u;
    double x = 0.0;
    size_t n = (i < len) ? sim_expr_scan_number(tok + i, &x) : 0u;
    if (n == 0 || i + n != len) {
        return ini_fail(&p->place, tok, "expected a number, got '%.*s'", SHOWN(len), tok);
    }
    if (!isfinite(x)) {
        return ini_fail(&p->place, tok, "number out of range");
    }
    *value = (tok[0] == '-') ? -x : x;
    return 0;
}

/* The key's per-key check (schema.h) of v, an error at tok. */
static int check_range(parser_t *p, const key_def_t *def, const char *tok, double v)
{
    char msg[sizeof p->place.err->message];
    return schema_check_range(def, v, msg, sizeof msg) == 0 ? 0 : ini_fail(&p->place, tok, "%s", msg);
}

/* Exactly `count` numbers in value, each in range, stored with the unit factor. */
static int parse_reals(parser_t *p, const key_def_t *def, char *value, double *out, int count)
{
    char *s = value;
    size_t len;
    for (int i = 0; i < count; ++i) {
        char *tok = lex_next_token(&s, &len);
        double v = 0.0;
        if (len == 0) { /* only with count > 1: an empty value is refused before */
            return ini_fail(&p->place, tok, "expected %d numbers", count);
        }
        if (parse_number(p, tok, len, &v) != 0 || check_range(p, def, tok, v) != 0) {
            return -1;
        }
        const double scale = def->scale != 0.0 ? def->scale : 1.0;
        out[i] = (def->variance ? sqrt(v) : v) * scale;
    }
    char *extra = lex_next_token(&s, &len);
    if (len > 0) {
        return count == 1 ? ini_fail(&p->place, extra, "expected a single number")
                          : ini_fail(&p->place, extra, "expected %d numbers", count);
    }
    return 0;
}

/* 1 to SCHEMA_LIST_MAX numbers, each checked and scaled as parse_reals does; their count into *n. */
static int parse_list(parser_t *p, const key_def_t *def, char *value, double *out, int *n)
{
    char *s = value;
    size_t len;
    int count = 0;
    for (char *tok = lex_next_token(&s, &len); len > 0; tok = lex_next_token(&s, &len)) {
        double v = 0.0;
        if (count == SCHEMA_LIST_MAX) {
            return ini_fail(&p->place, tok, "expected at most %d numbers", SCHEMA_LIST_MAX);
        }
        if (parse_number(p, tok, len, &v) != 0 || check_range(p, def, tok, v) != 0) {
            return -1;
        }
        out[count++] = v * (def->scale != 0.0 ? def->scale : 1.0);
    }
    *n = count;
    return 0;
}

/* The one token of a value, or an error naming what was expected. */
static char *single_token(parser_t *p, char *value, size_t *len, const char *expected)
{
    char *s = value;
    char *tok = lex_next_token(&s, len);
    size_t extra_len;
    char *extra = lex_next_token(&s, &extra_len);
    if (extra_len > 0) {
        ini_fail(&p->place, extra, "expected %s, got '%.*s'", expected, SHOWN(extra_len), extra);
        return NULL;
    }
    return tok;
}

static int parse_int(parser_t *p, const key_def_t *def, char *value, int *out)
{
    size_t len;
    char *tok = single_token(p, value, &len, "a single integer");
    if (tok == NULL) {
        return -1;
    }
    size_t i = (tok[0] == '-' || tok[0] == '+') ? 1u : 0u;
    if (i == len) {
        return ini_fail(&p->place, tok, "expected an integer, got '%.*s'", SHOWN(len), tok);
    }
    for (size_t k = i; k < len; ++k) {
        if (tok[k] < '0' || tok[k] > '9') {
            return ini_fail(&p->place, tok, "expected an integer, got '%.*s'", SHOWN(len), tok);
        }
    }
    errno = 0;
    long v = strtol(tok, NULL, 10);
    if (errno != 0 || v > 1000000000L || v < -1000000000L) {
        return ini_fail(&p->place, tok, "number out of range");
    }
    if (check_range(p, def, tok, (double)v) != 0) {
        return -1;
    }
    *out = (int)v;
    return 0;
}

static int parse_seed(parser_t *p, char *value, uint64_t *out)
{
    size_t len;
    char *tok = single_token(p, value, &len, "a single integer");
    if (tok == NULL) {
        return -1;
    }
    uint64_t v = 0;
    for (size_t k = 0; k < len; ++k) {
        if (tok[k] < '0' || tok[k] > '9') {
            return ini_fail(&p->place, tok, "expected an unsigned integer, got '%.*s'", SHOWN(len), tok);
        }
        const uint64_t digit = (uint64_t)(tok[k] - '0');
        if (v > (UINT64_MAX - digit) / 10u) {
            return ini_fail(&p->place, tok, "seed out of range (at most 18446744073709551615)");
        }
        v = v * 10u + digit;
    }
    *out = v;
    return 0;
}

/* "a, b or c" of the choices' names into expected. */
static void choice_names(const choice_t *choices, char *expected, size_t len)
{
    size_t used = 0;
    expected[0] = '\0';
    for (int i = 0; choices[i].name != NULL && used < len; ++i) {
        const char *sep = (i == 0) ? "" : (choices[i + 1].name == NULL ? " or " : ", ");
        used += (size_t)snprintf(expected + used, len - used, "%s%s", sep, choices[i].name);
    }
}

static int parse_choice(parser_t *p, const choice_t *choices, char *value, int *out)
{
    char expected[96];
    choice_names(choices, expected, sizeof expected);
    size_t len;
    char *tok = single_token(p, value, &len, expected);
    if (tok == NULL) {
        return -1;
    }
    for (int i = 0; choices[i].name != NULL; ++i) {
        if (strlen(choices[i].name) == len && strncmp(choices[i].name, tok, len) == 0) {
            *out = choices[i].value;
            return 0;
        }
    }
    return ini_fail(&p->place, tok, "expected %s, got '%.*s'", expected, SHOWN(len), tok);
}

/* Controller id of a name, or -1. */

int lex_fail_unknown_controller(parser_t *p, const char *tok, size_t len)
{
    return ini_fail(&p->place, tok,
                    "unknown controller '%.*s' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)",
                    SHOWN(len), tok);
}

static int is_list_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

int sim_controller_list_parse(const char *text, sim_controller_id_t ids[SIM_MAX_CONTROLLERS], int *n, size_t *err_at,
                              char *msg, size_t msg_len)
{
    const char *s = text;
    int after_comma = 0;
    *n = 0;
    for (;;) {
        while (is_list_space(*s)) {
            ++s;
        }
        if (*s == '\0' || *s == ',') {
            if (*n > 0 && !after_comma && *s == '\0') {
                return 0;
            }
            *err_at = (size_t)(s - text);
            snprintf(msg, msg_len, "expected a controller name%s", *s == ',' ? " before ','" : "");
            return -1;
        }
        const char *tok = s;
        while (*s != '\0' && *s != ',' && !is_list_space(*s)) {
            ++s;
        }
        const size_t len = (size_t)(s - tok);
        const int id = schema_controller_id(tok, len);
        *err_at = (size_t)(tok - text);
        if (id < 0) {
            snprintf(msg, msg_len,
                     "unknown controller '%.*s' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)",
                     SHOWN(len), tok);
            return -1;
        }
        for (int i = 0; i < *n; ++i) {
            if ((int)ids[i] == id) {
                snprintf(msg, msg_len, "controller '%s' listed twice", sim_controller_name((sim_controller_id_t)id));
                return -1;
            }
        }
        /* distinct names fit: SIM_MAX_CONTROLLERS >= SIM_CTRL_COUNT */
        ids[(*n)++] = (sim_controller_id_t)id;
        while (is_list_space(*s)) {
            ++s;
        }
        after_comma = *s == ',';
        if (after_comma) {
            ++s;
        }
    }
}

static int parse_controllers(parser_t *p, char *value)
{
    sim_scenario_t *sc = p->sc;
    char msg[160];
    size_t at = 0;
    sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
    int n = 0;
    if (sim_controller_list_parse(value, ids, &n, &at, msg, sizeof msg) != 0) {
        return ini_fail(&p->place, value + at, "%s", msg);
    }
    memcpy(sc->controllers, ids, sizeof ids);
    sc->n_controllers = n;
    return 0;
}

/* Words of def's choices separated by commas, whitespace or both, as a
 * list of controllers is, each at most once; their values or'ed into *out. */
static int parse_flags(parser_t *p, const key_def_t *def, char *value, int *out)
{
    char expected[96];
    choice_names(def->choices, expected, sizeof expected);
    int flags = 0, after_comma = 0;
    char *s = value;
    for (;;) {
        while (is_list_space(*s)) {
            ++s;
        }
        if (*s == '\0' || *s == ',') {
            if (flags != 0 && !after_comma && *s == '\0') {
                *out = flags;
                return 0;
            }
            return ini_fail(&p->place, s, "expected %s%s", expected, *s == ',' ? " before ','" : "");
        }
        char *tok = s;
        while (*s != '\0' && *s != ',' && !is_list_space(*s)) {
            ++s;
        }
        const size_t len = (size_t)(s - tok);
        int i = 0;
        while (def->choices[i].name != NULL &&
               !(strlen(def->choices[i].name) == len && strncmp(def->choices[i].name, tok, len) == 0)) {
            ++i;
        }
        if (def->choices[i].name == NULL) {
            return ini_fail(&p->place, tok, "expected %s, got '%.*s'", expected, SHOWN(len), tok);
        }
        if ((flags & def->choices[i].value) != 0) {
            return ini_fail(&p->place, tok, "'%s' listed twice in %s", def->choices[i].name, def->name);
        }
        flags |= def->choices[i].value;
        while (is_list_space(*s)) {
            ++s;
        }
        after_comma = *s == ',';
        if (after_comma) {
            ++s;
        }
    }
}

static int parse_window(parser_t *p, const key_def_t *def, char *value, double *from, double *to)
{
    char *s = value;
    size_t len[3];
    char *tok[3];
    double v[2] = {0.0, 0.0};
    for (int i = 0; i < 3; ++i) {
        tok[i] = lex_next_token(&s, &len[i]);
    }
    if (len[1] == 0 || len[2] > 0) {
        return ini_fail(&p->place, len[1] == 0 ? tok[1] : tok[2], "expected two numbers FROM TO");
    }
    for (int i = 0; i < 2; ++i) {
        if (parse_number(p, tok[i], len[i], &v[i]) != 0) {
            return -1;
        }
    }
    if (v[0] < 0.0) {
        return ini_fail(&p->place, tok[0], "%s must start at or after 0", def->name);
    }
    if (v[0] >= v[1]) {
        return ini_fail(&p->place, tok[0], "%s: window start must be before its end", def->name);
    }
    *from = v[0];
    *to = v[1];
    return 0;
}

/* One end of a piece's window: empty is unbounded. */
static int parse_bound(parser_t *p, char *text, double unbounded, double *out)
{
    char *tok = ini_skip_space(text);
    ini_trim_end(tok);
    if (*tok == '\0') {
        *out = unbounded;
        return 0;
    }
    return parse_number(p, tok, strlen(tok), out);
}

static int parse_signal(parser_t *p, int key, sim_signal_t *sig, char *value, int key_col)
{
    double from = -INFINITY;
    double to = INFINITY;
    char *text = value;
    char *colon = strchr(value, ':');
    if (colon != NULL) {
        *colon = '\0';
        char *dots = strstr(value, "..");
        if (dots == NULL) {
            return ini_fail(&p->place, value, "expected 'FROM .. TO' before ':'");
        }
        *dots = '\0';
        if (parse_bound(p, value, -INFINITY, &from) != 0 || parse_bound(p, dots + 2, INFINITY, &to) != 0) {
            return -1;
        }
        if (!(from < to)) {
            return ini_fail(&p->place, value, "window start must be before its end");
        }
        text = ini_skip_space(colon + 1);
        if (*text == '\0') {
            return ini_fail(&p->place, text, "expected an expression after ':'");
        }
    } else {
        char *dots = strstr(value, "..");
        if (dots != NULL) {
            return ini_fail(&p->place, dots, "expected ':' between the window and the expression");
        }
    }
    if (sig->n_pieces >= SIM_MAX_PIECES) {
        return ini_fail_at(&p->place, p->place.line, key_col, "more than %d pieces for '%s'", SIM_MAX_PIECES,
                           SCHEMA_KEYS[key].name);
    }
    for (int i = 0; i < sig->n_pieces; ++i) {
        if (from < sig->to_s[i] && sig->from_s[i] < to) {
            if (p->first_set_line > 0) {
                return ini_fail(&p->place, value,
                                "window (%g, %g] overlaps another setting of '%s' on the command line", from, to,
                                SCHEMA_KEYS[key].name);
            }
            return ini_fail(&p->place, value, "window (%g, %g] overlaps the one given on line %d", from, to,
                            p->piece_line[key][i]);
        }
    }
    sim_expr_error_t e;
    const int n = sig->n_pieces;
    if (sim_expr_compile(&sig->expr[n], text, &e) != 0) {
        return ini_fail_at(&p->place, p->place.line, ini_column(&p->place, text) + e.column - 1, "%s", e.message);
    }
    sig->from_s[n] = from;
    sig->to_s[n] = to;
    p->piece_line[key][n] = p->place.line;
    sig->n_pieces = n + 1;
    return 0;
}

int lex_value(parser_t *p, int key, char *base, char *value, int key_col)
{
    const key_def_t *def = &SCHEMA_KEYS[key];
    void *field = base + def->offset;
    switch (def->type) {
    case V_REAL:
        return parse_reals(p, def, value, (double *)field, 1);
    case V_VEC3:
        return parse_reals(p, def, value, (double *)field, 3);
    case V_VEC2:
        return parse_reals(p, def, value, (double *)field, 2);
    case V_INT:
        return parse_int(p, def, value, (int *)field);
    case V_SEED:
        return parse_seed(p, value, (uint64_t *)field);
    case V_CHOICE:
        return parse_choice(p, def->choices, value, (int *)field);
    case V_KIND: {
        int kind;
        if (parse_choice(p, def->choices, value, &kind) != 0) {
            return -1;
        }
        p->sc->kind = (sim_kind_t)kind;
        return 0;
    }
    case V_TEXT:
        if (strlen(value) >= SIM_PATH_LEN) {
            return ini_fail(&p->place, value, "%s longer than %d characters", def->name, SIM_PATH_LEN - 1);
        }
        memcpy(field, value, strlen(value) + 1);
        return 0;
    case V_CONTROLLERS:
        return parse_controllers(p, value);
    case V_WINDOW:
        return parse_window(p, def, value, (double *)field, (double *)(void *)(base + def->offset2));
    case V_LIST:
        return parse_list(p, def, value, (double *)field, (int *)(void *)(base + def->offset2));
    case V_FLAGS:
        return parse_flags(p, def, value, (int *)field);
    default:
        return parse_signal(p, key, (sim_signal_t *)field, value, key_col);
    }
}
