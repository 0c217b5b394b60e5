/* SPDX-License-Identifier: BSD-3-Clause */
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
 *
 * Evaluation runs a second form of the program, made by the compiler from
 * the postfix one: constant subexpressions folded (with the same double
 * operations, so to the same bits), and an accumulator machine whose binary
 * operations take a constant or t directly as an operand. Its results are
 * those of the postfix program bit for bit (sim_expr_eval_postfix, tested
 * and fuzzed), NaN results aside: those are NaN in both, but their sign and
 * payload may differ, as C leaves them to the compiler, which may swap the
 * operands of + and * (docs/fuzzing.md).
 */
#ifndef LADRC_SIM_EXPR_H
#define LADRC_SIM_EXPR_H

#include <stddef.h>

#define SIM_EXPR_MAX_OPS 96
/* Values the evaluation stack holds; compile rejects deeper expressions. */
#define SIM_EXPR_MAX_STACK 32

typedef struct {
    unsigned char op[SIM_EXPR_MAX_OPS]; /* opcode per instruction */
    double value[SIM_EXPR_MAX_OPS];     /* operand of push-constant instructions */
    int n_ops;
    /* the evaluated form: accumulator code; one instruction per postfix one
     * at most, plus a push per binary operation (at most half of them) */
    unsigned char code[SIM_EXPR_MAX_OPS + SIM_EXPR_MAX_OPS / 2];
    double operand[SIM_EXPR_MAX_OPS + SIM_EXPR_MAX_OPS / 2];
    int n_code;
} sim_expr_t;

/* Results of the costly functions (sin, cos, exp, ...) by argument, shared by
 * the evaluations of several expressions at one instant: the disturbances of
 * three axes often call sin with the same argument. Bits in, bits out: a hit
 * returns exactly what the call would. */
#define SIM_EXPR_MEMO_SIZE 4
typedef struct {
    double arg[SIM_EXPR_MEMO_SIZE];
    double result[SIM_EXPR_MEMO_SIZE];
    unsigned char fn[SIM_EXPR_MEMO_SIZE];
    int n;    /* entries filled */
    int next; /* entry replaced next once full */
} sim_expr_memo_t;

/* Empties a memo. */
void sim_expr_memo_clear(sim_expr_memo_t *memo);

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

/* The same with the function results kept in / taken from memo (NULL: none). */
double sim_expr_eval_memo(const sim_expr_t *expr, double t_s, sim_expr_memo_t *memo);

/* Several instants at once: out[k] = sim_expr_eval_memo(expr, t_s[k], .)
 * bit for bit (NaN results aside, as above), for k < n <= SIM_EXPR_BATCH_MAX
 * (more are not evaluated); each instruction runs over all n values, so a
 * program is interpreted once per batch rather than once per instant. */
#define SIM_EXPR_BATCH_MAX 32

/* Results of the costly functions on a whole batch of arguments, shared by
 * several expressions evaluated on the same instants (the disturbances of
 * three axes): a hit needs the same function on the same arguments, bit
 * for bit, and returns exactly what the calls would. */
typedef struct {
    double arg[SIM_EXPR_MEMO_SIZE][SIM_EXPR_BATCH_MAX];
    double result[SIM_EXPR_MEMO_SIZE][SIM_EXPR_BATCH_MAX];
    unsigned char fn[SIM_EXPR_MEMO_SIZE];
    int len[SIM_EXPR_MEMO_SIZE];
    int n;    /* entries filled */
    int next; /* entry replaced next once full */
} sim_expr_batch_memo_t;

/* Empties a batch memo. */
void sim_expr_batch_memo_clear(sim_expr_batch_memo_t *memo);

/* memo may be NULL: none. */
void sim_expr_eval_batch(const sim_expr_t *expr, const double *t_s, int n, double *out, sim_expr_batch_memo_t *memo);

/* The same value from the postfix program as written, without folding or
 * memo: the reference the evaluated form is tested against. */
double sim_expr_eval_postfix(const sim_expr_t *expr, double t_s);

/* A constant expression (no t): 1 and *value set; else 0. */
int sim_expr_is_constant(const sim_expr_t *expr, double *value);

/* Scans an unsigned decimal number at s: digits with an optional fraction
 * ("2", "2.", ".5", "2.50") and an optional exponent ("1e-3", "4E+2"); an
 * exponent letter without digits after it is not part of the number. Returns
 * the characters consumed and sets *value (inf when it overflows), or returns
 * 0 when s does not start with a number. Signs are not part of numbers. */
size_t sim_expr_scan_number(const char *s, double *value);

#endif
