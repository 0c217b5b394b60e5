/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Signals of a scenario: references and disturbances as expressions of t
 * over time windows (docs/scenario-format.md, "Signals"), evaluated at each
 * tick of a run, one instant or a batch of them. The scenario parser
 * (scenario.h) fills them; the runner evaluates them. (Named signals.h: a
 * signal.h on the include path would hide the C library's <signal.h>.)
 */
#ifndef LADRC_SIM_SIGNALS_H
#define LADRC_SIM_SIGNALS_H

#include "expr.h"

#define SIM_MAX_PIECES 8

/* A signal defined piecewise over windows (from_s, to_s]; 0 outside them.
 * A piece with from_s = -inf, to_s = +inf covers all t. */
typedef struct {
    double from_s[SIM_MAX_PIECES];
    double to_s[SIM_MAX_PIECES];
    sim_expr_t expr[SIM_MAX_PIECES];
    double scale; /* applied to the expression's value: deg -> rad for references */
    int n_pieces;
} sim_signal_t;

/* Value of the first piece whose window holds t, times scale; 0 if none. */
double sim_signal_eval(const sim_signal_t *sig, double t_s);

/* The same, sharing function results with other signals at the same t
 * through memo (NULL: none); bit for bit the value of sim_signal_eval. */
double sim_signal_eval_memo(const sim_signal_t *sig, double t_s, sim_expr_memo_t *memo);

/* The least and greatest of t_s[0..n), n >= 1, for sim_signal_eval_batch;
 * both NaN when one is NaN (the batch then goes instant by instant). */
void sim_signal_batch_range(const double *t_s, int n, double *lo, double *hi);

/* sim_signal_eval(sig, t_s[k]) for k < n <= SIM_EXPR_BATCH_MAX into out, bit
 * for bit, every t_s[k] within [lo, hi] (sim_signal_batch_range): a piece's
 * instants are evaluated together (sim_expr_eval_batch), sharing function
 * results with other signals at the same instants through memo (NULL:
 * none); 0 where no piece holds the instant. */
void sim_signal_eval_batch(const sim_signal_t *sig, const double *t_s, int n, double lo, double hi, double *out,
                           sim_expr_batch_memo_t *memo);

#endif
