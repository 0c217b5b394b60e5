/* SPDX-License-Identifier: BSD-3-Clause */
/* Signals of a scenario evaluated at an instant or at a batch of instants (signals.h). */
#include "signals.h"

#include <math.h>
#include <stddef.h>

/* The piece of sig whose window (from, to] holds t first, -1 when none does. */
static int signal_piece(const sim_signal_t *sig, double t_s)
{
    for (int i = 0; i < sig->n_pieces; ++i) {
        if (sig->from_s[i] < t_s && t_s <= sig->to_s[i]) {
            return i;
        }
    }
    return -1;
}

double sim_signal_eval_memo(const sim_signal_t *sig, double t_s, sim_expr_memo_t *memo)
{
    const int i = signal_piece(sig, t_s);
    return i < 0 ? 0.0 : sig->scale * sim_expr_eval_memo(&sig->expr[i], t_s, memo);
}

double sim_signal_eval(const sim_signal_t *sig, double t_s)
{
    return sim_signal_eval_memo(sig, t_s, NULL);
}

void sim_signal_batch_range(const double *t_s, int n, double *lo, double *hi)
{
    double a = t_s[0], b = t_s[0];
    int nan_seen = 0;
    for (int j = 0; j < n; ++j) {
        a = t_s[j] < a ? t_s[j] : a;
        b = t_s[j] > b ? t_s[j] : b;
        nan_seen |= isnan(t_s[j]);
    }
    *lo = nan_seen ? NAN : a;
    *hi = nan_seen ? NAN : b;
}

/* The piece holding every instant of [lo, hi] when that is one piece's
 * alone (no earlier piece's window reaches into the range); -2 when the
 * instants may take different pieces, -1 when none holds any of them. */
static int signal_piece_of_range(const sim_signal_t *sig, double lo, double hi)
{
    if (!(lo <= hi)) {
        return -2; /* NaN: instant by instant */
    }
    for (int i = 0; i < sig->n_pieces; ++i) {
        const double from = sig->from_s[i], to = sig->to_s[i];
        if (from < lo && hi <= to) {
            return i; /* holds them all, and no earlier one holds any */
        }
        if (from < hi && lo <= to) {
            return -2; /* holds some of them */
        }
    }
    return -1;
}

void sim_signal_eval_batch(const sim_signal_t *sig, const double *t_s, int n, double lo, double hi, double *out,
                           sim_expr_batch_memo_t *memo)
{
    const int whole = signal_piece_of_range(sig, lo, hi);
    if (whole >= -1) { /* the usual case: one piece, or none, for all */
        if (whole < 0) {
            for (int k = 0; k < n; ++k) {
                out[k] = 0.0;
            }
            return;
        }
        sim_expr_eval_batch(&sig->expr[whole], t_s, n, out, memo);
        for (int k = 0; k < n; ++k) {
            out[k] = sig->scale * out[k];
        }
        return;
    }
    int piece[SIM_EXPR_BATCH_MAX];
    for (int k = 0; k < n; ++k) {
        piece[k] = signal_piece(sig, t_s[k]);
        out[k] = 0.0;
    }
    for (int i = 0; i < sig->n_pieces; ++i) {
        double value[SIM_EXPR_BATCH_MAX], tt[SIM_EXPR_BATCH_MAX];
        int at[SIM_EXPR_BATCH_MAX], m = 0;
        for (int k = 0; k < n; ++k) {
            if (piece[k] == i) {
                tt[m] = t_s[k];
                at[m++] = k;
            }
        }
        if (m > 0) {
            sim_expr_eval_batch(&sig->expr[i], tt, m, value, memo);
            for (int j = 0; j < m; ++j) {
                out[at[j]] = sig->scale * value[j];
            }
        }
    }
}
