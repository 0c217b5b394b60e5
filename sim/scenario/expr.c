/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Expression compiler (expr_code.h): recursive descent straight to postfix,
 * then the postfix program into the evaluated form.
 *
 *   sum     := product (('+' | '-') product)*
 *   product := unary (('*' | '/') unary)*
 *   unary   := ('-' | '+') unary | power
 *   power   := primary ('^' unary)?
 *   primary := number | name | function '(' sum (',' sum)? ')' | '(' sum ')'
 *
 * The exponent of ^ is a unary, so a power chain recurses to the right and
 * a minus in front of a power applies to the whole power.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "expr_code.h"

typedef struct {
    const char *name;
    unsigned char op;
    int arity;
} function_t;

static const function_t FUNCTIONS[] = {
    {.name = "sin", .op = OP_SIN, .arity = 1},     {.name = "cos", .op = OP_COS, .arity = 1},
    {.name = "tan", .op = OP_TAN, .arity = 1},     {.name = "asin", .op = OP_ASIN, .arity = 1},
    {.name = "acos", .op = OP_ACOS, .arity = 1},   {.name = "atan", .op = OP_ATAN, .arity = 1},
    {.name = "exp", .op = OP_EXP, .arity = 1},     {.name = "log", .op = OP_LOG, .arity = 1},
    {.name = "sqrt", .op = OP_SQRT, .arity = 1},   {.name = "abs", .op = OP_ABS, .arity = 1},
    {.name = "floor", .op = OP_FLOOR, .arity = 1}, {.name = "ceil", .op = OP_CEIL, .arity = 1},
    {.name = "step", .op = OP_STEP, .arity = 1},   {.name = "sign", .op = OP_SIGN, .arity = 1},
    {.name = "min", .op = OP_MIN, .arity = 2},     {.name = "max", .op = OP_MAX, .arity = 2},
};

/* Parentheses, unary signs and powers nest the parser's recursion. */
#define MAX_NESTING 64
/* Longest number token converted (digits, point, exponent). */
#define MAX_NUMBER_CHARS 63

typedef struct {
    const char *text;
    const char *p;
    sim_expr_t *out;
    sim_expr_error_t *err;
    int depth; /* values on the evaluation stack after the emitted ops */
    int nesting;
    int failed;
} parser_t;

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}
static int is_name_start(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
static int is_name_char(char c)
{
    return is_name_start(c) || is_digit(c);
}

size_t sim_expr_scan_number(const char *s, double *value)
{
    size_t n = 0;
    size_t digits = 0;
    while (is_digit(s[n])) {
        ++n;
        ++digits;
    }
    if (s[n] == '.') {
        ++n;
        while (is_digit(s[n])) {
            ++n;
            ++digits;
        }
    }
    if (digits == 0) {
        return 0;
    }
    if (s[n] == 'e' || s[n] == 'E') {
        size_t k = n + 1;
        if (s[k] == '+' || s[k] == '-') {
            ++k;
        }
        if (is_digit(s[k])) {
            while (is_digit(s[k])) {
                ++k;
            }
            n = k;
        }
    }
    char buf[MAX_NUMBER_CHARS + 1];
    if (n > MAX_NUMBER_CHARS) {
        /* Only absurdly padded numbers get here; strtod reads the rest. */
        *value = strtod(s, NULL);
        return n;
    }
    memcpy(buf, s, n);
    buf[n] = '\0';
    *value = strtod(buf, NULL);
    return n;
}

static int column_of(const parser_t *ps, const char *at)
{
    return (int)(at - ps->text) + 1;
}

static void fail(parser_t *ps, const char *at, const char *message)
{
    if (ps->failed) {
        return;
    }
    ps->failed = 1;
    ps->err->column = column_of(ps, at);
    snprintf(ps->err->message, sizeof ps->err->message, "%s", message);
}

static void fail_name(parser_t *ps, const char *at, const char *format, const char *name, size_t len)
{
    char message[sizeof ps->err->message];
    int shown = len > 40 ? 40 : (int)len;
    snprintf(message, sizeof message, format, shown, name);
    fail(ps, at, message);
}

static void skip_space(parser_t *ps)
{
    while (*ps->p == ' ' || *ps->p == '\t') {
        ++ps->p;
    }
}

/* Appends one instruction; `at` is the token it comes from, for errors. */
static void emit(parser_t *ps, unsigned char op, double value, const char *at)
{
    if (ps->failed) {
        return;
    }
    if (ps->out->n_ops >= SIM_EXPR_MAX_OPS) {
        fail(ps, at, "expression too long");
        return;
    }
    if (op == OP_CONST || op == OP_T) {
        ++ps->depth;
    } else if (op >= OP_ADD && op <= OP_POW) {
        --ps->depth;
    } else if (op == OP_MIN || op == OP_MAX) {
        --ps->depth;
    }
    if (ps->depth > SIM_EXPR_MAX_STACK) {
        fail(ps, at, "expression too deeply nested");
        return;
    }
    ps->out->op[ps->out->n_ops] = op;
    ps->out->value[ps->out->n_ops] = value;
    ++ps->out->n_ops;
}

static void parse_sum(parser_t *ps);
static void parse_unary(parser_t *ps);

static void expect(parser_t *ps, char c, const char *message)
{
    skip_space(ps);
    if (*ps->p != c) {
        fail(ps, ps->p, message);
        return;
    }
    ++ps->p;
}

static void parse_call(parser_t *ps, const function_t *fn, const char *at)
{
    ++ps->p; /* '(' */
    parse_sum(ps);
    for (int arg = 1; arg < fn->arity && !ps->failed; ++arg) {
        expect(ps, ',', "expected ','");
        if (!ps->failed) {
            parse_sum(ps);
        }
    }
    if (!ps->failed) {
        expect(ps, ')', "expected ')'");
    }
    emit(ps, fn->op, 0.0, at);
}

static void parse_name(parser_t *ps)
{
    const char *start = ps->p;
    while (is_name_char(*ps->p)) {
        ++ps->p;
    }
    size_t len = (size_t)(ps->p - start);
    skip_space(ps);
    if (*ps->p == '(') {
        for (size_t i = 0; i < sizeof FUNCTIONS / sizeof FUNCTIONS[0]; ++i) {
            if (strlen(FUNCTIONS[i].name) == len && strncmp(FUNCTIONS[i].name, start, len) == 0) {
                parse_call(ps, &FUNCTIONS[i], start);
                return;
            }
        }
        fail_name(ps, start, "unknown function '%.*s'", start, len);
        return;
    }
    if (len == 1 && start[0] == 't') {
        emit(ps, OP_T, 0.0, start);
    } else if (len == 2 && strncmp(start, "pi", 2) == 0) {
        emit(ps, OP_CONST, 3.14159265358979323846, start);
    } else if (len == 1 && start[0] == 'e') {
        emit(ps, OP_CONST, 2.71828182845904523536, start);
    } else {
        for (size_t i = 0; i < sizeof FUNCTIONS / sizeof FUNCTIONS[0]; ++i) {
            if (strlen(FUNCTIONS[i].name) == len && strncmp(FUNCTIONS[i].name, start, len) == 0) {
                fail_name(ps, ps->p, "expected '(' after '%.*s'", start, len);
                return;
            }
        }
        fail_name(ps, start, "unknown name '%.*s'", start, len);
    }
}

static void parse_primary(parser_t *ps)
{
    skip_space(ps);
    const char *at = ps->p;
    double value;
    size_t n = sim_expr_scan_number(at, &value);
    if (n > 0) {
        ps->p += n;
        if (!isfinite(value)) {
            fail(ps, at, "number out of range");
            return;
        }
        emit(ps, OP_CONST, value, at);
    } else if (is_name_start(*at)) {
        parse_name(ps);
    } else if (*at == '(') {
        ++ps->p;
        parse_sum(ps);
        if (!ps->failed) {
            expect(ps, ')', "expected ')'");
        }
    } else {
        fail(ps, at, "expected a number, name or '('");
    }
}

static void parse_power(parser_t *ps)
{
    parse_primary(ps);
    skip_space(ps);
    if (!ps->failed && *ps->p == '^') {
        const char *at = ps->p++;
        parse_unary(ps);
        emit(ps, OP_POW, 0.0, at);
    }
}

static void parse_unary(parser_t *ps)
{
    skip_space(ps);
    if (++ps->nesting > MAX_NESTING) {
        fail(ps, ps->p, "expression too deeply nested");
    } else if (*ps->p == '-' || *ps->p == '+') {
        const char *at = ps->p++;
        parse_unary(ps);
        if (*at == '-') {
            emit(ps, OP_NEG, 0.0, at);
        }
    } else {
        parse_power(ps);
    }
    --ps->nesting;
}

static void parse_product(parser_t *ps)
{
    parse_unary(ps);
    for (;;) {
        skip_space(ps);
        if (ps->failed || (*ps->p != '*' && *ps->p != '/')) {
            return;
        }
        const char *at = ps->p++;
        parse_unary(ps);
        emit(ps, *at == '*' ? OP_MUL : OP_DIV, 0.0, at);
    }
}

static void parse_sum(parser_t *ps)
{
    parse_product(ps);
    for (;;) {
        skip_space(ps);
        if (ps->failed || (*ps->p != '+' && *ps->p != '-')) {
            return;
        }
        const char *at = ps->p++;
        parse_product(ps);
        emit(ps, *at == '+' ? OP_ADD : OP_SUB, 0.0, at);
    }
}

static void build_code(sim_expr_t *expr);

int sim_expr_compile(sim_expr_t *expr, const char *text, sim_expr_error_t *err)
{
    sim_expr_error_t ignored;
    parser_t ps;
    if (err == NULL) {
        err = &ignored;
    }
    err->column = 0;
    err->message[0] = '\0';
    if (expr == NULL || text == NULL) {
        snprintf(err->message, sizeof err->message, "no expression");
        return -1;
    }
    expr->n_ops = 0;
    expr->n_code = 0;
    ps.text = text;
    ps.p = text;
    ps.out = expr;
    ps.err = err;
    ps.depth = 0;
    ps.nesting = 0;
    ps.failed = 0;
    parse_sum(&ps);
    skip_space(&ps);
    if (!ps.failed && *ps.p != '\0') {
        fail(&ps, ps.p, "trailing characters");
    }
    if (ps.failed) {
        expr->n_ops = 0;
        expr->n_code = 0;
        return -1;
    }
    build_code(expr);
    return 0;
}

/* ---- the evaluated form ------------------------------------------------
 *
 * The postfix program becomes a tree; subtrees without t are folded to
 * constants with apply_unary/apply_binary, the functions the postfix
 * evaluation uses. The tree is then emitted for an accumulator machine:
 * every instruction leaves its result in acc. A binary operation whose right
 * operand is a constant or t takes it directly (modes C and T); one whose
 * left operand is (RC, RT) takes the accumulator as its right operand;
 * otherwise the left value is pushed while the right one is worked out (S). */

typedef struct {
    unsigned char op; /* OP_CONST (folded or written), OP_T, or an operator */
    int left, right;  /* children, -1 when absent; a unary has left only */
    double value;     /* OP_CONST */
} node_t;

typedef struct {
    node_t node[SIM_EXPR_MAX_OPS];
    sim_expr_t *out;
} builder_t;

static int is_leaf(const node_t *n)
{
    return n->op == OP_CONST || n->op == OP_T;
}

static void put(builder_t *b, unsigned char code, double operand)
{
    b->out->code[b->out->n_code] = code;
    b->out->operand[b->out->n_code] = operand;
    ++b->out->n_code;
}

static void emit_node(builder_t *b, int k)
{
    const node_t *n = &b->node[k];
    if (n->op == OP_CONST) {
        put(b, X_LOADC, n->value);
    } else if (n->op == OP_T) {
        put(b, X_LOADT, 0.0);
    } else if (n->right < 0) {
        emit_node(b, n->left);
        put(b, (unsigned char)(X_UNARY + n->op - OP_NEG), 0.0);
    } else {
        const node_t *l = &b->node[n->left], *r = &b->node[n->right];
        const int base = X_BINARY + binary_index(n->op) * N_MODES;
        if (is_leaf(r)) {
            emit_node(b, n->left);
            put(b, (unsigned char)(base + (r->op == OP_T ? MODE_T : MODE_C)), r->value);
        } else if (is_leaf(l)) {
            emit_node(b, n->right);
            put(b, (unsigned char)(base + (l->op == OP_T ? MODE_RT : MODE_RC)), l->value);
        } else {
            emit_node(b, n->left);
            put(b, X_PUSH, 0.0);
            emit_node(b, n->right);
            put(b, (unsigned char)(base + MODE_S), 0.0);
        }
    }
}

static void build_code(sim_expr_t *expr)
{
    static const double none = 0.0;
    builder_t b;
    int stack[SIM_EXPR_MAX_STACK];
    int sp = 0;
    b.out = expr;
    for (int i = 0; i < expr->n_ops; ++i) {
        node_t *n = &b.node[i];
        n->op = expr->op[i];
        n->value = (n->op == OP_CONST) ? expr->value[i] : none;
        n->left = n->right = -1;
        if (n->op != OP_CONST && n->op != OP_T) {
            if (is_binary(n->op)) {
                n->right = stack[--sp];
            }
            n->left = stack[--sp];
            const node_t *l = &b.node[n->left];
            const node_t *r = n->right >= 0 ? &b.node[n->right] : NULL;
            if (l->op == OP_CONST && (r == NULL || r->op == OP_CONST)) {
                n->value = r == NULL ? apply_unary(n->op, l->value) : apply_binary(n->op, l->value, r->value);
                n->op = OP_CONST;
                n->left = n->right = -1;
            }
        }
        stack[sp++] = i;
    }
    expr->n_code = 0;
    emit_node(&b, stack[0]);
}
