/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Signals of a scenario: references and disturbances as expressions of t
 * over time windows (docs/scenario-format.md, "Signals"), evaluated at each
 * tick of a run. The scenario parser (scenario.h) fills them; the runner
 * evaluates them. (Named signals.h: a signal.h on the include path would
 * hide the C library's <signal.h>.)
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

#endif
