/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The programs of compiled expressions, internal to expr*.c (expr.h is the
 * interface): the postfix opcodes and what each computes, the codes of the
 * evaluated form, and the memo slots the evaluators share.
 *   expr.c        the compiler: text to postfix, postfix to the evaluated form;
 *   expr_eval.c   one instant: the postfix program and the evaluated form;
 *   expr_batch.c  several instants at once (the disturbance batches).
 */
#ifndef LADRC_SIM_EXPR_CODE_H
#define LADRC_SIM_EXPR_CODE_H

#include <math.h>

#include "expr.h"

/* The postfix opcodes. */
enum {
    OP_CONST,
    OP_T,
    OP_NEG,
    OP_ADD,
    OP_SUB,
    OP_MUL,
    OP_DIV,
    OP_POW,
    OP_SIN,
    OP_COS,
    OP_TAN,
    OP_ASIN,
    OP_ACOS,
    OP_ATAN,
    OP_EXP,
    OP_LOG,
    OP_SQRT,
    OP_ABS,
    OP_FLOOR,
    OP_CEIL,
    OP_STEP,
    OP_SIGN,
    OP_MIN,
    OP_MAX
};

static inline double nan_or(double x, double value)
{
    return isnan(x) ? x : value;
}

/* a op b for the binary operators, a the left operand; NaN wins in min/max */
static inline double apply_binary(unsigned char op, double a, double b)
{
    switch (op) {
    case OP_ADD:
        return a + b;
    case OP_SUB:
        return a - b;
    case OP_MUL:
        return a * b;
    case OP_DIV:
        return a / b;
    case OP_POW:
        return pow(a, b);
    case OP_MIN:
        return isnan(b) ? b : ((!isnan(a) && b < a) ? b : a);
    default:
        return isnan(b) ? b : ((!isnan(a) && b > a) ? b : a); /* OP_MAX */
    }
}

static inline double apply_unary(unsigned char op, double x)
{
    switch (op) {
    case OP_NEG:
        return -x;
    case OP_SIN:
        return sin(x);
    case OP_COS:
        return cos(x);
    case OP_TAN:
        return tan(x);
    case OP_ASIN:
        return asin(x);
    case OP_ACOS:
        return acos(x);
    case OP_ATAN:
        return atan(x);
    case OP_EXP:
        return exp(x);
    case OP_LOG:
        return log(x);
    case OP_SQRT:
        return sqrt(x);
    case OP_ABS:
        return fabs(x);
    case OP_FLOOR:
        return floor(x);
    case OP_CEIL:
        return ceil(x);
    case OP_STEP:
        return nan_or(x, x >= 0.0 ? 1.0 : 0.0);
    default:
        return nan_or(x, x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0)); /* OP_SIGN */
    }
}

static inline int is_binary(unsigned char op)
{
    return (op >= OP_ADD && op <= OP_POW) || op == OP_MIN || op == OP_MAX;
}

/* The evaluated form (built in expr.c). */
enum { MODE_C, MODE_T, MODE_S, MODE_RC, MODE_RT, N_MODES };
enum { X_LOADC, X_LOADT, X_PUSH, X_UNARY };
/* unary op u: X_UNARY + u - OP_NEG (OP_NEG .. OP_SIGN but the binary ones);
 * binary: X_BINARY + index * N_MODES + mode */
#define X_BINARY (X_UNARY + OP_SIGN - OP_NEG + 1)

static inline int binary_index(unsigned char op)
{
    return op == OP_MIN ? 5 : (op == OP_MAX ? 6 : op - OP_ADD);
}

#define BIN_0(a, b) ((a) + (b))
#define BIN_1(a, b) ((a) - (b))
#define BIN_2(a, b) ((a) * (b))
#define BIN_3(a, b) ((a) / (b))
#define BIN_4(a, b) pow((a), (b))
#define BIN_5(a, b) apply_binary(OP_MIN, (a), (b))
#define BIN_6(a, b) apply_binary(OP_MAX, (a), (b))

/* The memo's next slot: a free one while there is one, else the oldest. */
static inline int memo_slot(int *n, int *next)
{
    if (*n < SIM_EXPR_MEMO_SIZE) {
        return (*n)++;
    }
    const int slot = *next;
    *next = (slot + 1) % SIM_EXPR_MEMO_SIZE;
    return slot;
}

#endif
