/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Expressions at one instant (expr_code.h): the postfix program as written
 * (the reference), and the evaluated form with its memo of function results.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "expr_code.h"

double sim_expr_eval_postfix(const sim_expr_t *expr, double t_s)
{
    double stack[SIM_EXPR_MAX_STACK];
    int sp = 0;
    if (expr->n_ops <= 0) {
        return NAN;
    }
    for (int i = 0; i < expr->n_ops; ++i) {
        const unsigned char op = expr->op[i];
        if (op == OP_CONST || op == OP_T) {
            stack[sp++] = (op == OP_T) ? t_s : expr->value[i];
        } else if (is_binary(op)) {
            --sp;
            stack[sp - 1] = apply_binary(op, stack[sp - 1], stack[sp]);
        } else {
            stack[sp - 1] = apply_unary(op, stack[sp - 1]);
        }
    }
    return stack[0];
}

int sim_expr_is_constant(const sim_expr_t *expr, double *value)
{
    if (expr->n_ops <= 0) {
        return 0;
    }
    for (int i = 0; i < expr->n_ops; ++i) {
        if (expr->op[i] == OP_T) {
            return 0;
        }
    }
    if (value != NULL) {
        *value = sim_expr_eval_postfix(expr, 0.0);
    }
    return 1;
}

void sim_expr_memo_clear(sim_expr_memo_t *memo)
{
    memo->n = 0;
    memo->next = 0;
}

static int same_bits(double a, double b)
{
    uint64_t x, y;
    memcpy(&x, &a, sizeof x);
    memcpy(&y, &b, sizeof y);
    return x == y;
}

/* apply_unary through the memo for the functions worth remembering */
static double unary_memo(unsigned char op, double x, sim_expr_memo_t *memo)
{
    if (memo == NULL || op < OP_SIN || op > OP_LOG) {
        return apply_unary(op, x);
    }
    for (int i = 0; i < memo->n; ++i) {
        if (memo->fn[i] == op && same_bits(memo->arg[i], x)) {
            return memo->result[i];
        }
    }
    const double y = apply_unary(op, x);
    const int slot = memo_slot(&memo->n, &memo->next);
    memo->fn[slot] = op;
    memo->arg[slot] = x;
    memo->result[slot] = y;
    return y;
}

#define BINARY_CASES(op)                                                                                               \
    case X_BINARY + (op)*N_MODES + MODE_C:                                                                             \
        acc = BIN_##op(acc, expr->operand[i]);                                                                         \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_T:                                                                             \
        acc = BIN_##op(acc, t_s);                                                                                      \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_S:                                                                             \
        --sp;                                                                                                          \
        acc = BIN_##op(stack[sp], acc);                                                                                \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_RC:                                                                            \
        acc = BIN_##op(expr->operand[i], acc);                                                                         \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_RT:                                                                            \
        acc = BIN_##op(t_s, acc);                                                                                      \
        break;

double sim_expr_eval_memo(const sim_expr_t *expr, double t_s, sim_expr_memo_t *memo)
{
    double stack[SIM_EXPR_MAX_STACK];
    int sp = 0;
    double acc = NAN; /* an empty program gives NaN */
    for (int i = 0; i < expr->n_code; ++i) {
        const unsigned char c = expr->code[i];
        switch (c) {
        case X_LOADC:
            acc = expr->operand[i];
            break;
        case X_LOADT:
            acc = t_s;
            break;
        case X_PUSH:
            stack[sp++] = acc;
            break;
            BINARY_CASES(0)
            BINARY_CASES(1)
            BINARY_CASES(2)
            BINARY_CASES(3)
            BINARY_CASES(4)
            BINARY_CASES(5)
            BINARY_CASES(6)
        default:
            acc = unary_memo((unsigned char)(c - X_UNARY + OP_NEG), acc, memo);
            break;
        }
    }
    return acc;
}

double sim_expr_eval(const sim_expr_t *expr, double t_s)
{
    return sim_expr_eval_memo(expr, t_s, NULL);
}
