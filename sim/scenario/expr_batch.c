/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Expressions at several instants at once (expr_code.h): each instruction
 * of the evaluated form over a whole batch, with a memo of function results
 * by batch of arguments.
 */
#include <math.h>
#include <string.h>

#include "expr_code.h"

void sim_expr_batch_memo_clear(sim_expr_batch_memo_t *memo)
{
    memo->n = 0;
    memo->next = 0;
}

/* apply_unary on x[0..n) in place, through the memo for the functions worth
 * remembering: a hit needs the same function on the same n arguments, bit
 * for bit. */
static void unary_batch(unsigned char op, double *x, int n, sim_expr_batch_memo_t *memo)
{
    const int remember = memo != NULL && op >= OP_SIN && op <= OP_LOG;
    if (remember) {
        for (int i = 0; i < memo->n; ++i) {
            if (memo->fn[i] == op && memo->len[i] == n && memcmp(memo->arg[i], x, (size_t)n * sizeof x[0]) == 0) {
                memcpy(x, memo->result[i], (size_t)n * sizeof x[0]);
                return;
            }
        }
    }
    int slot = 0;
    if (remember) {
        slot = memo_slot(&memo->n, &memo->next);
        memo->fn[slot] = op;
        memo->len[slot] = n;
        memcpy(memo->arg[slot], x, (size_t)n * sizeof x[0]);
    }
    if (op == OP_NEG) {
        for (int k = 0; k < n; ++k) {
            x[k] = -x[k];
        }
    } else if (op == OP_SIN) { /* the usual disturbance: no switch per value */
        for (int k = 0; k < n; ++k) {
            x[k] = sin(x[k]);
        }
    } else if (op == OP_COS) {
        for (int k = 0; k < n; ++k) {
            x[k] = cos(x[k]);
        }
    } else {
        for (int k = 0; k < n; ++k) {
            x[k] = apply_unary(op, x[k]);
        }
    }
    if (remember) {
        memcpy(memo->result[slot], x, (size_t)n * sizeof x[0]);
    }
}

#define BATCH_BINARY_CASES(op)                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_C: {                                                                           \
        const double operand = expr->operand[i];                                                                       \
        for (int k = 0; k < n; ++k)                                                                                    \
            acc[k] = BIN_##op(acc[k], operand);                                                                        \
    } break;                                                                                                           \
    case X_BINARY + (op)*N_MODES + MODE_T:                                                                             \
        for (int k = 0; k < n; ++k)                                                                                    \
            acc[k] = BIN_##op(acc[k], t_s[k]);                                                                         \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_S:                                                                             \
        --sp;                                                                                                          \
        for (int k = 0; k < n; ++k)                                                                                    \
            acc[k] = BIN_##op(stack[sp][k], acc[k]);                                                                   \
        break;                                                                                                         \
    case X_BINARY + (op)*N_MODES + MODE_RC: {                                                                          \
        const double operand = expr->operand[i];                                                                       \
        for (int k = 0; k < n; ++k)                                                                                    \
            acc[k] = BIN_##op(operand, acc[k]);                                                                        \
    } break;                                                                                                           \
    case X_BINARY + (op)*N_MODES + MODE_RT:                                                                            \
        for (int k = 0; k < n; ++k)                                                                                    \
            acc[k] = BIN_##op(t_s[k], acc[k]);                                                                         \
        break;

void sim_expr_eval_batch(const sim_expr_t *expr, const double *t_s, int n, double *out, sim_expr_batch_memo_t *memo)
{
    double stack[SIM_EXPR_MAX_STACK][SIM_EXPR_BATCH_MAX];
    double acc[SIM_EXPR_BATCH_MAX];
    int sp = 0;
    n = n < 0 ? 0 : (n > SIM_EXPR_BATCH_MAX ? SIM_EXPR_BATCH_MAX : n);
    for (int k = 0; k < n; ++k) {
        acc[k] = NAN; /* an empty program gives NaN */
    }
    for (int i = 0; i < expr->n_code; ++i) {
        const unsigned char c = expr->code[i];
        switch (c) {
        case X_LOADC:
            for (int k = 0; k < n; ++k)
                acc[k] = expr->operand[i];
            break;
        case X_LOADT:
            memcpy(acc, t_s, (size_t)n * sizeof acc[0]);
            break;
        case X_PUSH:
            memcpy(stack[sp++], acc, (size_t)n * sizeof acc[0]);
            break;
            BATCH_BINARY_CASES(0)
            BATCH_BINARY_CASES(1)
            BATCH_BINARY_CASES(2)
            BATCH_BINARY_CASES(3)
            BATCH_BINARY_CASES(4)
            BATCH_BINARY_CASES(5)
            BATCH_BINARY_CASES(6)
        default:
            unary_batch((unsigned char)(c - X_UNARY + OP_NEG), acc, n, memo);
            break;
        }
    }
    memcpy(out, acc, (size_t)n * sizeof acc[0]);
}
