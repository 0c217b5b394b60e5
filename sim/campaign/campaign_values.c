/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The names and values of a campaign's [grid] and [draw] keys
 * (campaign_parser.h): numbers, lists, range(), the distributions, and
 * whole numbers. Values are cut up in place.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "campaign_parser.h"
#include "scenario/expr.h"
#include "scenario/ini.h"

static int is_alpha(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static int is_alnum(char c)
{
    return is_alpha(c) || (c >= '0' && c <= '9');
}
/* characters of a varied name: a variable's, and a scenario key's
 * (SECTION.KEY, controller:NAME.KEY) */
static int is_name_char(char c)
{
    return is_alnum(c) || c == '.' || c == ':' || c == '-';
}
/* characters of a campaign's name */
int campaign_is_name_char(char c)
{
    return is_alnum(c) || c == '.' || c == '-';
}

/* A signed decimal number at s: its length (0 if none) and value. */
static size_t scan_signed(const char *s, double *v)
{
    const size_t sign = (*s == '-' || *s == '+') ? 1u : 0u;
    double x = 0.0;
    const size_t n = sim_expr_scan_number(s + sign, &x);
    if (n == 0) {
        return 0;
    }
    *v = *s == '-' ? -x : x;
    return sign + n;
}

/* A number filling the token [s, s + len). */
static int parse_number(parser_t *p, char *s, size_t len, double *v)
{
    const size_t n = len > 0 ? scan_signed(s, v) : 0u;
    if (n == 0 || n != len) {
        return ini_fail(&p->place, s, "expected a number, got '%.*s'", SHOWN(len), s);
    }
    if (!isfinite(*v)) {
        return ini_fail(&p->place, s, "number out of range");
    }
    return 0;
}

/* An unsigned whole number filling the rest of the value. */
int campaign_parse_whole(parser_t *p, char *s, uint64_t max, uint64_t *out, const char *what)
{
    uint64_t v = 0;
    char *d = s;
    for (; *d >= '0' && *d <= '9'; ++d) {
        const uint64_t digit = (uint64_t)(*d - '0');
        if (v > (max - digit) / 10u) {
            return ini_fail(&p->place, s, "%s out of range (at most %llu)", what, (unsigned long long)max);
        }
        v = v * 10u + digit;
    }
    if (d == s || *d != '\0') {
        return ini_fail(&p->place, s, "%s: expected a whole number, got '%.*s'", what, SHOWN(strlen(s)), s);
    }
    *out = v;
    return 0;
}

/* NAME(ARG, ARG, ...): the name's span, and the arguments' text, cut at
 * the commas (each NUL-terminated and trimmed). Returns the number of
 * arguments, or -1 after recording an error. */
static int parse_call(parser_t *p, char *s, char **name, size_t *name_len, char **args, int max_args)
{
    *name = s;
    while (is_alnum(*s)) {
        ++s;
    }
    *name_len = (size_t)(s - *name);
    char *open = ini_skip_space(s);
    if (*name_len == 0 || *open != '(') {
        return -2; /* not a call */
    }
    char *close = strrchr(open, ')');
    if (close == NULL) {
        return ini_fail(&p->place, open + strlen(open), "expected ')'");
    }
    if (*ini_skip_space(close + 1) != '\0') {
        return ini_fail(&p->place, ini_skip_space(close + 1), "trailing characters after ')'");
    }
    *close = '\0';
    int n = 0;
    char *arg = open + 1;
    for (;;) {
        char *comma = strchr(arg, ',');
        if (comma != NULL) {
            *comma = '\0';
        }
        arg = ini_skip_space(arg);
        ini_trim_end(arg);
        if (n == max_args) {
            return ini_fail(&p->place, arg, "too many arguments to %.*s()", SHOWN(*name_len), *name);
        }
        args[n++] = arg;
        if (comma == NULL) {
            break;
        }
        arg = comma + 1;
    }
    return n;
}

static int expect_args(parser_t *p, char *name, size_t len, int n, int wanted, const char *form)
{
    if (n != wanted) {
        return ini_fail(&p->place, name, "%.*s takes %d numbers: %s", SHOWN(len), name, wanted, form);
    }
    return 0;
}

/* A number filling an argument's text. */
static int parse_arg(parser_t *p, char *arg, double *v)
{
    return parse_number(p, arg, strlen(arg), v);
}

/* range(FROM, TO, COUNT), or a list: numbers separated by commas, spaces or both. */
static int parse_grid_values(parser_t *p, sim_campaign_key_t *key, char *value)
{
    char *name;
    size_t name_len;
    char *args[3];
    char *start = value;
    const int n = parse_call(p, value, &name, &name_len, args, 3);
    if (n == -1) {
        return -1;
    }
    if (n >= 0) {
        if (name_len != 5 || strncmp(name, "range", 5) != 0) {
            return ini_fail(&p->place, name,
                            "unknown function '%.*s' in [grid] (expected a list or range(FROM, TO, COUNT))",
                            SHOWN(name_len), name);
        }
        double from, to, count;
        if (expect_args(p, name, name_len, n, 3, "range(FROM, TO, COUNT)") != 0 || parse_arg(p, args[0], &from) != 0 ||
            parse_arg(p, args[1], &to) != 0 || parse_arg(p, args[2], &count) != 0) {
            return -1;
        }
        if (count != floor(count) || count < 2.0 || count > (double)SIM_CAMPAIGN_MAX_VALUES) {
            return ini_fail(&p->place, args[2], "range COUNT must be a whole number from 2 to %d, got '%s'",
                            SIM_CAMPAIGN_MAX_VALUES, args[2]);
        }
        if (!(from != to)) {
            return ini_fail(&p->place, args[1], "range FROM and TO must differ");
        }
        key->n_values = (long)count;
        key->values = malloc((size_t)key->n_values * sizeof *key->values);
        if (key->values == NULL) {
            return ini_fail(&p->place, name, "out of memory");
        }
        for (long i = 0; i < key->n_values; ++i) {
            /* ends exact: FROM at i = 0, TO at the last */
            key->values[i] = i == key->n_values - 1 ? to : from + (to - from) * (double)i / (count - 1.0);
        }
        return 0;
    }
    /* a list: count, then read */
    long count = 0;
    for (int pass = 0; pass < 2; ++pass) {
        char *s = start;
        count = 0;
        int after_comma = 1; /* at the start: a leading comma is an empty value */
        for (;;) {
            s = ini_skip_space(s);
            if (*s == '\0') {
                if (after_comma && count > 0) {
                    return ini_fail(&p->place, s, "empty value after ','");
                }
                break;
            }
            if (*s == ',') {
                if (after_comma) {
                    return ini_fail(&p->place, s, "empty value before ','");
                }
                after_comma = 1;
                ++s;
                continue;
            }
            char *end = s;
            while (*end != '\0' && *end != ',' && !ini_is_space(*end)) {
                ++end;
            }
            double v = 0.0;
            if (parse_number(p, s, (size_t)(end - s), &v) != 0) {
                return -1;
            }
            if (pass == 1) {
                key->values[count] = v;
            }
            if (++count > SIM_CAMPAIGN_MAX_VALUES) {
                return ini_fail(&p->place, s, "more than %d values", SIM_CAMPAIGN_MAX_VALUES);
            }
            after_comma = 0;
            s = end;
        }
        if (pass == 0) {
            key->values = malloc((size_t)count * sizeof *key->values);
            if (key->values == NULL) {
                return ini_fail(&p->place, start, "out of memory");
            }
        }
    }
    key->n_values = count;
    return 0;
}

/* uniform(A, B), normal(MEAN, STD), log_uniform(A, B). */
static int parse_draw(parser_t *p, sim_campaign_key_t *key, char *value)
{
    char *name;
    size_t len;
    char *args[3];
    const int n = parse_call(p, value, &name, &len, args, 3);
    if (n == -1) {
        return -1;
    }
    static const char *const EXPECTED = "expected uniform(A, B), normal(MEAN, STD) or log_uniform(A, B)";
    if (n == -2) {
        return ini_fail(&p->place, value, "expected a distribution, got '%.*s' (%s)", SHOWN(strlen(value)), value,
                        EXPECTED);
    }
    double a = 0.0, b = 0.0;
    if (len == 7 && strncmp(name, "uniform", 7) == 0) {
        if (expect_args(p, name, len, n, 2, "uniform(A, B)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(a < b)) {
            return ini_fail(&p->place, name, "uniform(A, B) needs A < B");
        }
        key->dist = SIM_DRAW_UNIFORM;
    } else if (len == 6 && strncmp(name, "normal", 6) == 0) {
        if (expect_args(p, name, len, n, 2, "normal(MEAN, STD)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(b > 0.0)) {
            return ini_fail(&p->place, args[1], "normal(MEAN, STD) needs STD > 0");
        }
        key->dist = SIM_DRAW_NORMAL;
    } else if (len == 11 && strncmp(name, "log_uniform", 11) == 0) {
        if (expect_args(p, name, len, n, 2, "log_uniform(A, B)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(a > 0.0 && a < b)) {
            return ini_fail(&p->place, name, "log_uniform(A, B) needs 0 < A < B");
        }
        key->dist = SIM_DRAW_LOG_UNIFORM;
    } else {
        return ini_fail(&p->place, name, "unknown distribution '%.*s' (%s)", SHOWN(len), name, EXPECTED);
    }
    key->a = a;
    key->b = b;
    return 0;
}

static const sim_campaign_key_t *find_varied(const parser_t *p, const char *name)
{
    for (int i = 0; i < p->n_grid; ++i) {
        if (strcmp(p->grid[i].name, name) == 0) {
            return &p->grid[i];
        }
    }
    for (int i = 0; i < p->n_draw; ++i) {
        if (strcmp(p->draw[i].name, name) == 0) {
            return &p->draw[i];
        }
    }
    return NULL;
}

/* NAME = ... of [grid] or [draw]. */
int campaign_parse_varied(parser_t *p, char *key, size_t key_len, char *value)
{
    const int draw = p->section == SEC_DRAW;
    int *n = draw ? &p->n_draw : &p->n_grid;
    if (p->n_grid + p->n_draw >= SIM_CAMPAIGN_MAX_VARIED) {
        return ini_fail(&p->place, key, "more than %d [grid] and [draw] keys", SIM_CAMPAIGN_MAX_VARIED);
    }
    for (size_t i = 0; i < key_len; ++i) {
        if (!is_name_char(key[i])) {
            return ini_fail(&p->place, key + i,
                            "unexpected '%c' in a name (a variable: letters, digits, '_'; a scenario key: "
                            "SECTION.KEY)",
                            key[i]);
        }
    }
    if (key_len >= SIM_CAMPAIGN_KEY_LEN) {
        return ini_fail(&p->place, key, "name longer than %d characters", SIM_CAMPAIGN_KEY_LEN - 1);
    }
    sim_campaign_key_t k;
    memset(&k, 0, sizeof k);
    memcpy(k.name, key, key_len);
    k.name[key_len] = '\0';
    k.is_variable = memchr(key, '.', key_len) == NULL;
    if (k.is_variable &&
        (!is_alpha(key[0]) || memchr(key, ':', key_len) != NULL || memchr(key, '-', key_len) != NULL)) {
        return ini_fail(&p->place, key, "a variable's name is a letter or '_' then letters, digits or '_', got '%s'",
                        k.name);
    }
    if (!k.is_variable && (key[0] == '.' || key[key_len - 1] == '.')) {
        return ini_fail(&p->place, key, "expected SECTION.KEY, got '%s'", k.name);
    }
    const sim_campaign_key_t *twice = find_varied(p, k.name);
    if (twice != NULL) {
        return ini_fail(&p->place, key, "'%s' already varied on line %d", k.name, twice->line);
    }
    k.is_draw = draw;
    k.line = p->place.line;
    k.column = ini_column(&p->place, key);
    k.draw_index = draw ? *n + 1 : 0;
    if ((draw ? parse_draw(p, &k, value) : parse_grid_values(p, &k, value)) != 0) {
        free(k.values);
        return -1;
    }
    (draw ? p->draw : p->grid)[(*n)++] = k;
    return 0;
}
