/* SPDX-License-Identifier: BSD-3-Clause */
/* Signals of a scenario evaluated at an instant (signals.h). */
#include "signals.h"

#include <stddef.h>

double sim_signal_eval_memo(const sim_signal_t *sig, double t_s, sim_expr_memo_t *memo)
{
    for (int i = 0; i < sig->n_pieces; ++i) {
        if (sig->from_s[i] < t_s && t_s <= sig->to_s[i]) {
            return sig->scale * sim_expr_eval_memo(&sig->expr[i], t_s, memo);
        }
    }
    return 0.0;
}

double sim_signal_eval(const sim_signal_t *sig, double t_s)
{
    return sim_signal_eval_memo(sig, t_s, NULL);
}
