/*
 * Arithmetic expressions of time t for scenario files: numbers, t, pi, e,
 * + - * / ^ (right-associative power), unary minus, parentheses, and the
 * functions sin cos tan asin acos atan exp log sqrt abs floor ceil min max
 * step(x) (1 for x >= 0, else 0) sign(x). Compiled once to a small postfix
 * program, evaluated per tick without allocating.
 *
 * Precedence, loosest first: + -, then * /, then unary - and +, then ^; so
 * -2^2 = -4, 2^-1 = 0.5 and 2^3^2 = 2^9. min and max take two arguments
 * separated by a comma, the other functions one. Names and functions are
 * case-sensitive; spaces and tabs between tokens are ignored. NaN arguments
 * give NaN from every function (step and sign included).
 */
#ifndef LADRC_SIM_EXPR_H
#define LADRC_SIM_EXPR_H

#include <stddef.h>

#define SIM_EXPR_MAX_OPS 96
/* Values the evaluation stack holds; compile rejects deeper expressions. */
#define SIM_EXPR_MAX_STACK 32

typedef struct {
    unsigned char op[SIM_EXPR_MAX_OPS];  /* opcode per instruction */
    double value[SIM_EXPR_MAX_OPS];      /* operand of push-constant instructions */
    int n_ops;
} sim_expr_t;

/* Where and why a compile failed: 1-based column within the text, and a
 * message naming what was expected ("expected ')'", "unknown name 'sn'"). */
typedef struct {
    int column;
    char message[96];
} sim_expr_error_t;

/* Compiles text; returns 0 on success, -1 with *err filled otherwise. */
int sim_expr_compile(sim_expr_t *expr, const char *text, sim_expr_error_t *err);

/* Value at time t_s (non-finite results are returned as they are). expr must
 * come from a successful sim_expr_compile; an empty program gives NaN. */
double sim_expr_eval(const sim_expr_t *expr, double t_s);

/* A constant expression (no t): 1 and *value set; else 0. */
int sim_expr_is_constant(const sim_expr_t *expr, double *value);

/* Scans an unsigned decimal number at s: digits with an optional fraction
 * ("2", "2.", ".5", "2.50") and an optional exponent ("1e-3", "4E+2"); an
 * exponent letter without digits after it is not part of the number. Returns
 * the characters consumed and sets *value (inf when it overflows), or returns
 * 0 when s does not start with a number. Signs are not part of numbers. */
size_t sim_expr_scan_number(const char *s, double *value);

#endif
