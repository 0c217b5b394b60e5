/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Campaign files (see campaign.h). The text is copied once and cut up in
 * place as the scenario parser does: each line NUL-terminated, its comment
 * removed; [set] lines keep pointers into the copy.
 */
#include "campaign.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "expr.h"
#include "ini.h"
#include "numfmt.h"
#include "rng.h"

#if defined(__GNUC__)
#define PRINTF_LIKE(f, a) __attribute__((format(printf, f, a)))
#else
#define PRINTF_LIKE(f, a)
#endif

#define TWO_PI 6.28318530717958647692

/* ---- counter-based draws ---------------------------------------------------- */

/* The first SplitMix64 output from counter x: a bijective 64-bit mix. */
static uint64_t mix64(uint64_t x)
{
    return sim_rng_splitmix64(&x);
}

uint64_t sim_campaign_stream(uint64_t seed, long r, int k, int i)
{
    uint64_t state = mix64(mix64(mix64(seed) ^ (uint64_t)r) ^ (uint64_t)k);
    uint64_t out = 0;
    for (int j = 0; j < i; ++j) {
        out = sim_rng_splitmix64(&state);
    }
    return out;
}

double sim_campaign_uniform(uint64_t seed, long r, int k, int i)
{
    /* the top 53 bits, centred in their interval: 2^53 values evenly spaced
     * in (0, 1), symmetric about 1/2, never 0 (log) nor 1 */
    return ((double)(sim_campaign_stream(seed, r, k, i) >> 11) + 0.5) * 0x1.0p-53;
}

static double clamp(double v, double lo, double hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

double sim_campaign_draw(const sim_campaign_t *c, const sim_campaign_key_t *key, long r)
{
    const double u = sim_campaign_uniform(c->seed, r, key->draw_index, 1);
    switch (key->dist) {
    case SIM_DRAW_NORMAL: {
        /* Box-Muller: u and a second uniform of the same stream */
        const double u2 = sim_campaign_uniform(c->seed, r, key->draw_index, 2);
        return key->a + key->b * sqrt(-2.0 * log(u)) * cos(TWO_PI * u2);
    }
    case SIM_DRAW_LOG_UNIFORM: {
        const double la = log(key->a);
        return clamp(exp(la + (log(key->b) - la) * u), key->a, key->b);
    }
    default:
        return clamp(key->a + (key->b - key->a) * u, key->a, key->b);
    }
}

int sim_campaign_format_value(char *buf, double x)
{
    /* the shortest of the texts %.Pg, P = 1..17, that read back (the
     * smallest P among equals): 100 is "100" rather than %.1g's "1e+02" */
    char tmp[SIM_NUMFMT_MAX];
    int best = -1;
    for (int p = 1; p <= 17; ++p) {
        /* sim_fmt_g is printf's %.Pg up to 15 digits; 16 and 17 from printf */
        const int len = p <= 15 ? sim_fmt_g(tmp, x, p) : snprintf(tmp, sizeof tmp, "%.*g", p, x);
        if ((best < 0 || len < best) && len < SIM_CAMPAIGN_VALUE_LEN && strtod(tmp, NULL) == x) {
            memcpy(buf, tmp, (size_t)len + 1u);
            best = len;
        }
    }
    /* %.17g of a finite double always reads back, in at most 24 chars */
    return best;
}

void sim_campaign_run_name(char *buf, size_t n, long r)
{
    snprintf(buf, n, "%05ld", r);
}

/* ---- the parser ------------------------------------------------------------- */

enum { SEC_CAMPAIGN, SEC_GRID, SEC_DRAW, SEC_SET, SEC_COUNT };
static const char *const SECTION_NAMES[SEC_COUNT] = {"campaign", "grid", "draw", "set"};

enum { K_NAME, K_BASE, K_SEED, K_SAMPLES, K_OUTPUT_DIR, K_COUNT };
static const char *const CAMPAIGN_KEYS[K_COUNT] = {"name", "base", "seed", "samples", "output_dir"};

typedef struct {
    sim_campaign_t *c;
    sim_campaign_error_t *err;
    int line;
    const char *line_start;
    int section;
    int section_line[SEC_COUNT];
    int key_line[K_COUNT];
    int base_col;
    /* [grid] and [draw] keys as read, before they are put in order */
    sim_campaign_key_t grid[SIM_CAMPAIGN_MAX_VARIED], draw[SIM_CAMPAIGN_MAX_VARIED];
    int n_grid, n_draw;
} parser_t;

static int column(const parser_t *p, const char *at)
{
    return (int)(at - p->line_start) + 1;
}

static int PRINTF_LIKE(3, 4) fail(parser_t *p, const char *at, const char *format, ...)
{
    p->err->line = p->line;
    p->err->column = at != NULL ? column(p, at) : 1;
    va_list ap;
    va_start(ap, format);
    vsnprintf(p->err->message, sizeof p->err->message, format, ap);
    va_end(ap);
    return -1;
}

static int PRINTF_LIKE(4, 5) fail_at(parser_t *p, int line, int col, const char *format, ...)
{
    p->err->line = line;
    p->err->column = col;
    va_list ap;
    va_start(ap, format);
    vsnprintf(p->err->message, sizeof p->err->message, format, ap);
    va_end(ap);
    return -1;
}

#define SHOWN(len) ((len) > 40 ? 40 : (int)(len))

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
static int is_campaign_name_char(char c)
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
        return fail(p, s, "expected a number, got '%.*s'", SHOWN(len), s);
    }
    if (!isfinite(*v)) {
        return fail(p, s, "number out of range");
    }
    return 0;
}

/* An unsigned whole number filling the rest of the value. */
static int parse_whole(parser_t *p, char *s, uint64_t max, uint64_t *out, const char *what)
{
    uint64_t v = 0;
    char *d = s;
    for (; *d >= '0' && *d <= '9'; ++d) {
        const uint64_t digit = (uint64_t)(*d - '0');
        if (v > (max - digit) / 10u) {
            return fail(p, s, "%s out of range (at most %llu)", what, (unsigned long long)max);
        }
        v = v * 10u + digit;
    }
    if (d == s || *d != '\0') {
        return fail(p, s, "%s: expected a whole number, got '%.*s'", what, SHOWN(strlen(s)), s);
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
        return fail(p, open + strlen(open), "expected ')'");
    }
    if (*ini_skip_space(close + 1) != '\0') {
        return fail(p, ini_skip_space(close + 1), "trailing characters after ')'");
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
            return fail(p, arg, "too many arguments to %.*s()", SHOWN(*name_len), *name);
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
        return fail(p, name, "%.*s takes %d numbers: %s", SHOWN(len), name, wanted, form);
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
            return fail(p, name, "unknown function '%.*s' in [grid] (expected a list or range(FROM, TO, COUNT))",
                        SHOWN(name_len), name);
        }
        double from, to, count;
        if (expect_args(p, name, name_len, n, 3, "range(FROM, TO, COUNT)") != 0 || parse_arg(p, args[0], &from) != 0 ||
            parse_arg(p, args[1], &to) != 0 || parse_arg(p, args[2], &count) != 0) {
            return -1;
        }
        if (count != floor(count) || count < 2.0 || count > (double)SIM_CAMPAIGN_MAX_VALUES) {
            return fail(p, args[2], "range COUNT must be a whole number from 2 to %d, got '%s'",
                        SIM_CAMPAIGN_MAX_VALUES, args[2]);
        }
        if (!(from != to)) {
            return fail(p, args[1], "range FROM and TO must differ");
        }
        key->n_values = (long)count;
        key->values = malloc((size_t)key->n_values * sizeof *key->values);
        if (key->values == NULL) {
            return fail(p, name, "out of memory");
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
                    return fail(p, s, "empty value after ','");
                }
                break;
            }
            if (*s == ',') {
                if (after_comma) {
                    return fail(p, s, "empty value before ','");
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
                return fail(p, s, "more than %d values", SIM_CAMPAIGN_MAX_VALUES);
            }
            after_comma = 0;
            s = end;
        }
        if (pass == 0) {
            key->values = malloc((size_t)count * sizeof *key->values);
            if (key->values == NULL) {
                return fail(p, start, "out of memory");
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
        return fail(p, value, "expected a distribution, got '%.*s' (%s)", SHOWN(strlen(value)), value, EXPECTED);
    }
    double a = 0.0, b = 0.0;
    if (len == 7 && strncmp(name, "uniform", 7) == 0) {
        if (expect_args(p, name, len, n, 2, "uniform(A, B)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(a < b)) {
            return fail(p, name, "uniform(A, B) needs A < B");
        }
        key->dist = SIM_DRAW_UNIFORM;
    } else if (len == 6 && strncmp(name, "normal", 6) == 0) {
        if (expect_args(p, name, len, n, 2, "normal(MEAN, STD)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(b > 0.0)) {
            return fail(p, args[1], "normal(MEAN, STD) needs STD > 0");
        }
        key->dist = SIM_DRAW_NORMAL;
    } else if (len == 11 && strncmp(name, "log_uniform", 11) == 0) {
        if (expect_args(p, name, len, n, 2, "log_uniform(A, B)") != 0 || parse_arg(p, args[0], &a) != 0 ||
            parse_arg(p, args[1], &b) != 0) {
            return -1;
        }
        if (!(a > 0.0 && a < b)) {
            return fail(p, name, "log_uniform(A, B) needs 0 < A < B");
        }
        key->dist = SIM_DRAW_LOG_UNIFORM;
    } else {
        return fail(p, name, "unknown distribution '%.*s' (%s)", SHOWN(len), name, EXPECTED);
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
static int parse_varied(parser_t *p, char *key, size_t key_len, char *value)
{
    const int draw = p->section == SEC_DRAW;
    int *n = draw ? &p->n_draw : &p->n_grid;
    if (p->n_grid + p->n_draw >= SIM_CAMPAIGN_MAX_VARIED) {
        return fail(p, key, "more than %d [grid] and [draw] keys", SIM_CAMPAIGN_MAX_VARIED);
    }
    for (size_t i = 0; i < key_len; ++i) {
        if (!is_name_char(key[i])) {
            return fail(p, key + i,
                        "unexpected '%c' in a name (a variable: letters, digits, '_'; a scenario key: "
                        "SECTION.KEY)",
                        key[i]);
        }
    }
    if (key_len >= SIM_CAMPAIGN_KEY_LEN) {
        return fail(p, key, "name longer than %d characters", SIM_CAMPAIGN_KEY_LEN - 1);
    }
    sim_campaign_key_t k;
    memset(&k, 0, sizeof k);
    memcpy(k.name, key, key_len);
    k.name[key_len] = '\0';
    k.is_variable = memchr(key, '.', key_len) == NULL;
    if (k.is_variable &&
        (!is_alpha(key[0]) || memchr(key, ':', key_len) != NULL || memchr(key, '-', key_len) != NULL)) {
        return fail(p, key, "a variable's name is a letter or '_' then letters, digits or '_', got '%s'", k.name);
    }
    if (!k.is_variable && (key[0] == '.' || key[key_len - 1] == '.')) {
        return fail(p, key, "expected SECTION.KEY, got '%s'", k.name);
    }
    const sim_campaign_key_t *twice = find_varied(p, k.name);
    if (twice != NULL) {
        return fail(p, key, "'%s' already varied on line %d", k.name, twice->line);
    }
    k.is_draw = draw;
    k.line = p->line;
    k.column = column(p, key);
    k.draw_index = draw ? *n + 1 : 0;
    if ((draw ? parse_draw(p, &k, value) : parse_grid_values(p, &k, value)) != 0) {
        free(k.values);
        return -1;
    }
    (draw ? p->draw : p->grid)[(*n)++] = k;
    return 0;
}

static int parse_campaign_key(parser_t *p, char *key, char *value)
{
    int k = 0;
    while (k < K_COUNT && strcmp(CAMPAIGN_KEYS[k], key) != 0) {
        ++k;
    }
    if (k == K_COUNT) {
        return fail(p, key, "unknown key '%s' in [campaign] (expected name, base, seed, samples, output_dir)", key);
    }
    if (p->key_line[k] != 0) {
        return fail(p, key, "duplicate key '%s' (first given on line %d)", key, p->key_line[k]);
    }
    p->key_line[k] = p->line;
    sim_campaign_t *c = p->c;
    uint64_t v = 0;
    switch (k) {
    case K_NAME:
        for (char *s = value; *s != '\0'; ++s) {
            if (!is_campaign_name_char(*s)) {
                return fail(p, s, "a campaign's name is made of letters, digits, '_', '.' and '-', got '%s'", value);
            }
        }
        if (strlen(value) >= sizeof c->name) {
            return fail(p, value, "name longer than %d characters", (int)sizeof c->name - 1);
        }
        strcpy(c->name, value);
        return 0;
    case K_BASE:
        if (strlen(value) >= sizeof c->base_path - 1) {
            return fail(p, value, "path too long");
        }
        p->base_col = column(p, value);
        strcpy(c->base_path, value); /* made relative to the campaign's directory once read */
        return 0;
    case K_SEED:
        if (parse_whole(p, value, UINT64_MAX, &v, "seed") != 0) {
            return -1;
        }
        c->seed = v;
        return 0;
    case K_SAMPLES:
        if (parse_whole(p, value, (uint64_t)SIM_CAMPAIGN_MAX_RUNS, &v, "samples") != 0) {
            return -1;
        }
        if (v < 1u) {
            return fail(p, value, "samples must be at least 1");
        }
        c->samples = (long)v;
        return 0;
    default:
        if (strlen(value) >= sizeof c->output_dir) {
            return fail(p, value, "path too long");
        }
        strcpy(c->output_dir, value);
        return 0;
    }
}

/* KEY = VALUE of [set]: KEY is SECTION.KEY as --set takes it. */
static int parse_set(parser_t *p, char *key, char *value)
{
    if (p->c->n_sets >= SIM_CAMPAIGN_MAX_SETS) {
        return fail(p, key, "more than %d [set] lines", SIM_CAMPAIGN_MAX_SETS);
    }
    if (strchr(key, '.') == NULL) {
        return fail(p, key, "expected SECTION.KEY = VALUE, got '%s' (a [set] line sets a scenario key)", key);
    }
    sim_campaign_set_t *s = &p->c->sets[p->c->n_sets++];
    s->key = key;
    s->value = value;
    s->line = p->line;
    s->value_column = column(p, value);
    return 0;
}

static int parse_section(parser_t *p, char *s)
{
    char *close = strchr(s, ']');
    if (close == NULL) {
        return fail(p, s + strlen(s), "expected ']'");
    }
    char *after = ini_skip_space(close + 1);
    if (*after != '\0') {
        return fail(p, after, "trailing characters after ']'");
    }
    *close = '\0';
    char *name = ini_skip_space(s + 1);
    ini_trim_end(name);
    int sec = 0;
    while (sec < SEC_COUNT && strcmp(SECTION_NAMES[sec], name) != 0) {
        ++sec;
    }
    if (sec == SEC_COUNT) {
        return fail(p, name, "unknown section [%.*s] (expected [campaign], [grid], [draw] or [set])",
                    SHOWN(strlen(name)), name);
    }
    if (p->section_line[sec] != 0) {
        return fail(p, s, "section [%s] already given on line %d", name, p->section_line[sec]);
    }
    p->section_line[sec] = p->line;
    p->section = sec;
    return 0;
}

static int parse_key_line(parser_t *p, char *s)
{
    char *eq = strchr(s, '=');
    if (eq == NULL) {
        return fail(p, s + strlen(s), "expected KEY = VALUE");
    }
    *eq = '\0';
    ini_trim_end(s);
    char *value = ini_skip_space(eq + 1);
    if (*s == '\0') {
        return fail(p, s, "expected a key before '='");
    }
    if (p->section < 0) {
        return fail(p, s, "key '%s' before any [section]", s);
    }
    if (*value == '\0') {
        return fail(p, value, "missing value for '%s'", s);
    }
    switch (p->section) {
    case SEC_CAMPAIGN:
        return parse_campaign_key(p, s, value);
    case SEC_SET:
        return parse_set(p, s, value);
    default:
        return parse_varied(p, s, strlen(s), value);
    }
}

static int parse_line(void *ctx, const char *line_start, char *s)
{
    parser_t *p = (parser_t *)ctx;
    p->line_start = line_start;
    return (*s == '[') ? parse_section(p, s) : parse_key_line(p, s);
}

static int parse_lines(parser_t *p, char *text)
{
    return ini_lines(text, &p->line, parse_line, p);
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
                return fail_at(p, s->line, col, "'}' without '{'");
            }
            if (*v != '{') {
                continue;
            }
            const char *close = strchr(v, '}');
            if (close == NULL) {
                return fail_at(p, s->line, col, "'{' without '}'");
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
                return fail_at(p, s->line, col, "unknown variable '{%.*s}' (define it in [grid] or [draw])", SHOWN(len),
                               v + 1);
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
                return fail_at(p, s->line, s->value_column - (int)(s->value - s->key),
                               "'%s' is varied in [%s] (line %d): set it there or here, not both", a,
                               c->keys[k].is_draw ? "draw" : "grid", c->keys[k].line);
            }
        }
    }
    for (int k = 0; k < c->n_keys; ++k) {
        if (c->keys[k].is_variable && !used[k]) {
            return fail_at(p, c->keys[k].line, c->keys[k].column,
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

static int read_file(const char *path, char **text, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return -1;
    }
    size_t cap = 4096;
    size_t n = 0;
    char *buf = malloc(cap);
    while (buf != NULL) {
        n += fread(buf + n, 1, cap - 1 - n, f);
        if (n < cap - 1) {
            break;
        }
        char *grown = realloc(buf, cap * 2);
        if (grown == NULL) {
            free(buf);
            buf = NULL;
        } else {
            buf = grown;
            cap *= 2;
        }
    }
    const int bad = ferror(f);
    fclose(f);
    if (buf == NULL || bad) {
        free(buf);
        errno = buf == NULL ? ENOMEM : EIO;
        return -1;
    }
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return 0;
}

/* What follows the file's lines: required keys, the order of the keys, the
 * variables, the number of runs, the base scenario's bytes. */
static int finish(parser_t *p)
{
    sim_campaign_t *c = p->c;
    if (p->key_line[K_BASE] == 0) {
        return fail_at(p, p->section_line[SEC_CAMPAIGN], p->section_line[SEC_CAMPAIGN] > 0 ? 1 : 0,
                       "missing base = SCENARIO in [campaign] (the scenario every run starts from)");
    }
    if (c->name[0] == '\0') {
        name_from_path(c->name, sizeof c->name, c->path);
        for (const char *s = c->name; *s != '\0'; ++s) {
            if (!is_campaign_name_char(*s)) {
                return fail_at(p, 0, 0,
                               "the file's name '%s' is no campaign name (letters, digits, '_', '.', '-'): "
                               "give [campaign] name",
                               c->name);
            }
        }
        if (c->name[0] == '\0') {
            return fail_at(p, 0, 0, "no campaign name: give [campaign] name");
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
        return fail_at(p, 0, 0, "%.0f runs: at most %ld in a campaign", runs, SIM_CAMPAIGN_MAX_RUNS);
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
        return fail_at(p, p->key_line[K_BASE], p->base_col, "base path too long");
    }
    memcpy(c->base_path, base, sizeof base);
    if (read_file(c->base_path, &c->base_text, &c->base_len) != 0) {
        return fail_at(p, p->key_line[K_BASE], p->base_col, "cannot read the base scenario '%s': %s", c->base_path,
                       strerror(errno));
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
    p->err = err;
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
    if (read_file(path, &text, &len) != 0) {
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

/* ---- runs ------------------------------------------------------------------- */

typedef struct {
    char *buf;
    size_t n, cap;
    int overflow;
} text_t;

static void put(text_t *t, const char *s, size_t len)
{
    if (t->n + len + 1 > t->cap) {
        t->overflow = 1;
        return;
    }
    memcpy(t->buf + t->n, s, len);
    t->n += len;
    t->buf[t->n] = '\0';
}

static void puts_(text_t *t, const char *s)
{
    put(t, s, strlen(s));
}

int sim_campaign_expand(const sim_campaign_t *c, long r, sim_campaign_run_t *out, char *msg, size_t msg_len)
{
    out->run = r;
    out->n_settings = 0;
    if (r < 1 || r > c->n_runs) {
        snprintf(msg, msg_len, "run %ld: the campaign's runs are 1 to %ld", r, c->n_runs);
        return -1;
    }
    long point = (r - 1) / c->samples;
    for (int k = c->n_grid - 1; k >= 0; --k) {
        const sim_campaign_key_t *key = &c->keys[k];
        out->values[k] = key->values[point % key->n_values];
        point /= key->n_values;
    }
    for (int k = c->n_grid; k < c->n_keys; ++k) {
        out->values[k] = sim_campaign_draw(c, &c->keys[k], r);
    }
    for (int k = 0; k < c->n_keys; ++k) {
        sim_campaign_format_value(out->text[k], out->values[k]);
    }
    out->run_seed = sim_campaign_stream(c->seed, r, 0, 1);
    text_t t = {out->buf, 0, sizeof out->buf, 0};
    /* each setting is NUL-terminated in buf; pointers taken once it is full */
    size_t starts[SIM_CAMPAIGN_MAX_SETS + SIM_CAMPAIGN_MAX_VARIED + 1];
    if (!c->sets_seed) {
        char seed[40];
        snprintf(seed, sizeof seed, "run.seed=%llu", (unsigned long long)out->run_seed);
        starts[out->n_settings] = t.n;
        out->setting_line[out->n_settings++] = 0;
        puts_(&t, seed);
        put(&t, "", 0);
        t.n += 1;
    }
    for (int i = 0; i < c->n_sets; ++i) {
        const sim_campaign_set_t *s = &c->sets[i];
        starts[out->n_settings] = t.n;
        out->setting_line[out->n_settings++] = s->line;
        puts_(&t, s->key);
        puts_(&t, "=");
        for (const char *v = s->value; *v != '\0'; ++v) {
            const char *close = *v == '{' ? strchr(v, '}') : NULL;
            if (close == NULL) {
                put(&t, v, 1);
                continue;
            }
            const size_t len = (size_t)(close - v - 1);
            for (int k = 0; k < c->n_keys; ++k) {
                if (c->keys[k].is_variable && strlen(c->keys[k].name) == len &&
                    strncmp(c->keys[k].name, v + 1, len) == 0) {
                    puts_(&t, out->text[k]);
                }
            }
            v = close;
        }
        put(&t, "", 0);
        t.n += 1;
    }
    for (int k = 0; k < c->n_keys; ++k) {
        if (!c->keys[k].is_variable) {
            starts[out->n_settings] = t.n;
            out->setting_line[out->n_settings++] = c->keys[k].line;
            puts_(&t, c->keys[k].name);
            puts_(&t, "=");
            puts_(&t, out->text[k]);
            put(&t, "", 0);
            t.n += 1;
        }
    }
    if (t.overflow || t.n > t.cap) {
        snprintf(msg, msg_len, "run %ld: its settings are longer than %d characters", r, SIM_CAMPAIGN_RUN_TEXT);
        out->n_settings = 0;
        return -1;
    }
    for (int i = 0; i < out->n_settings; ++i) {
        out->settings[i] = out->buf + starts[i];
    }
    return 0;
}

int sim_campaign_load_run(const sim_campaign_t *c, const sim_campaign_run_t *run, const char *out_dir,
                          sim_scenario_t *sc, sim_parse_error_t *err)
{
    if (sim_scenario_parse_buffer_with(sc, c->base_text, c->base_len, c->base_path, run->settings, run->n_settings,
                                       err) != 0) {
        return -1;
    }
    sim_campaign_run_name(sc->name, sizeof sc->name, run->run);
    if (snprintf(sc->output_dir, sizeof sc->output_dir, "%s/runs/%s", out_dir, sc->name) >=
        (int)sizeof sc->output_dir) {
        memset(err, 0, sizeof *err);
        snprintf(err->path, sizeof err->path, "%s", out_dir);
        snprintf(err->message, sizeof err->message, "output directory path too long");
        return -1;
    }
    return 0;
}

int sim_campaign_write_plan(FILE *f, const sim_campaign_t *c, long shard_k, long shard_n)
{
    fputs("run", f);
    for (int k = 0; k < c->n_keys; ++k) {
        fprintf(f, ",%s", c->keys[k].name);
    }
    fputc('\n', f);
    static sim_campaign_run_t run; /* large: kept off the stack */
    char msg[128];
    for (long r = shard_k; r <= c->n_runs; r += shard_n) {
        if (sim_campaign_expand(c, r, &run, msg, sizeof msg) != 0) {
            return -1;
        }
        fprintf(f, "%ld", r);
        for (int k = 0; k < c->n_keys; ++k) {
            fprintf(f, ",%s", run.text[k]);
        }
        fputc('\n', f);
    }
    return ferror(f) ? -1 : 0;
}

int sim_campaign_parse_shard(const char *text, long *k, long *n, char *msg, size_t msg_len)
{
    const char *slash = strchr(text, '/');
    long v[2] = {0, 0};
    const char *parts[2] = {text, slash != NULL ? slash + 1 : NULL};
    const char *ends[2] = {slash, slash != NULL ? slash + 1 + strlen(slash + 1) : NULL};
    for (int i = 0; i < 2; ++i) {
        if (parts[i] == NULL || parts[i] == ends[i]) {
            snprintf(msg, msg_len, "expected K/N (shard K of N, 1 <= K <= N), got '%s'", text);
            return -1;
        }
        for (const char *s = parts[i]; s < ends[i]; ++s) {
            if (*s < '0' || *s > '9') {
                snprintf(msg, msg_len, "expected K/N with whole numbers K and N, got '%s'", text);
                return -1;
            }
            if (v[i] > SIM_CAMPAIGN_MAX_RUNS) {
                snprintf(msg, msg_len, "'%s': at most %ld shards", text, SIM_CAMPAIGN_MAX_RUNS);
                return -1;
            }
            v[i] = v[i] * 10 + (*s - '0');
        }
    }
    if (v[1] < 1 || v[1] > SIM_CAMPAIGN_MAX_RUNS) {
        snprintf(msg, msg_len, "'%s': N must be from 1 to %ld", text, SIM_CAMPAIGN_MAX_RUNS);
        return -1;
    }
    if (v[0] < 1 || v[0] > v[1]) {
        snprintf(msg, msg_len, "'%s': K must be from 1 to N = %ld", text, v[1]);
        return -1;
    }
    *k = v[0];
    *n = v[1];
    return 0;
}
