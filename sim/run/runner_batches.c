/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * References and disturbances worked out in batches (runner_parts.h): the
 * control instants of SIM_EXPR_BATCH_MAX ticks, and the stage times of a
 * plant step, each signal's program interpreted once for all of them.
 */
#include <math.h>

#include "runner_parts.h"

/* The disturbances of the three axes at t_s; the axes often share sin(w t). */
static void disturbances_at(const sim_scenario_t *sc, double t_s, double d_out[3])
{
    sim_expr_memo_t memo;
    sim_expr_memo_clear(&memo);
    for (int i = 0; i < 3; ++i) {
        d_out[i] = sim_signal_eval_memo(&sc->disturbance[i], t_s, &memo);
    }
}

void runner_disturbance_batch_init(disturbance_batch_t *b, const sim_scenario_t *sc)
{
    b->sc = sc;
    b->n = b->last = 0;
    b->last_t_s = NAN; /* never equal: empty */
}

/* The step's distinct stage times into distinct[] (the first carried over
 * from the step before when it is that step's last), each stage time's row
 * in b->slot; returns the rows, *carried the rows already valued. */
static int distinct_times(disturbance_batch_t *b, double distinct[STAGES_MAX], int *carried)
{
    int rows = 0;
    *carried = 0;
    if (b->n > 0 && b->t_s[0] == b->last_t_s) { /* carried over from the step before */
        for (int i = 0; i < 3; ++i) {
            b->value[0][i] = b->value[b->last][i];
        }
        distinct[0] = b->t_s[0];
        rows = *carried = 1;
    }
    for (int k = 0; k < b->n; ++k) {
        if (rows == 0 || b->t_s[k] != distinct[rows - 1]) {
            distinct[rows++] = b->t_s[k];
        }
        b->slot[k] = rows - 1;
    }
    return rows;
}

/* The rows [from, rows) valued, SIM_EXPR_BATCH_MAX instants at a time, the
 * three axes sharing their function results. */
static void value_rows(disturbance_batch_t *b, const double distinct[STAGES_MAX], int from, int rows)
{
    for (int r = from; r < rows; r += SIM_EXPR_BATCH_MAX) {
        const int m = rows - r < SIM_EXPR_BATCH_MAX ? rows - r : SIM_EXPR_BATCH_MAX;
        double lo, hi;
        sim_signal_batch_range(&distinct[r], m, &lo, &hi);
        sim_expr_batch_memo_t memo;
        sim_expr_batch_memo_clear(&memo);
        for (int i = 0; i < 3; ++i) {
            double d[SIM_EXPR_BATCH_MAX];
            sim_signal_eval_batch(&b->sc->disturbance[i], &distinct[r], m, lo, hi, d, &memo);
            for (int j = 0; j < m; ++j) {
                b->value[r + j][i] = d[j];
            }
        }
    }
}

void runner_disturbance_batch_fill(disturbance_batch_t *b, const sim_plant_t *p, double dt_s, int substeps)
{
    /* more than the parser lets through: no table, every call evaluates */
    b->n = substeps <= SIM_PLANT_SUBSTEPS_MAX ? sim_plant_stage_times(p, dt_s, substeps, b->t_s) : 0;
    double distinct[STAGES_MAX];
    int carried;
    const int rows = distinct_times(b, distinct, &carried);
    value_rows(b, distinct, carried, rows);
    for (int k = 0; k < b->n; ++k) {
        for (int i = 0; i < 3; ++i) {
            b->stage[k][i] = b->value[b->slot[k]][i];
        }
    }
    if (rows > 0) {
        b->last_t_s = distinct[rows - 1];
    }
    b->last = rows - 1;
}

void runner_instants_fill(instants_t *b, const sim_scenario_t *sc, long first, long n_ticks)
{
    b->first = first;
    b->n = n_ticks - first < SIM_EXPR_BATCH_MAX ? (int)(n_ticks - first) : SIM_EXPR_BATCH_MAX;
    for (int j = 0; j < b->n; ++j) {
        b->t_s[j] = (double)(first + j) * sc->control_dt_s;
    }
    double lo, hi;
    sim_signal_batch_range(b->t_s, b->n, &lo, &hi);
    sim_expr_batch_memo_t memo;
    sim_expr_batch_memo_clear(&memo);
    for (int i = 0; i < 3; ++i) {
        double ref[SIM_EXPR_BATCH_MAX];
        sim_signal_eval_batch(&sc->reference[i], b->t_s, b->n, lo, hi, ref, &memo);
        for (int j = 0; j < b->n; ++j) {
            b->ref[i][j] = (ladrc_real_t)ref[j];
        }
    }
    for (int i = 0; i < 3; ++i) {
        sim_signal_eval_batch(&sc->disturbance[i], b->t_s, b->n, lo, hi, b->dist[i], &memo);
    }
}

void runner_read_batch(double t_s, void *ctx, double d_out[3])
{
    batch_reader_t *r = (batch_reader_t *)ctx;
    const disturbance_batch_t *b = r->b;
    if (r->next < b->n && b->t_s[r->next] == t_s) {
        const double *v = b->value[b->slot[r->next++]];
        for (int i = 0; i < 3; ++i) {
            d_out[i] = v[i];
        }
    } else { /* not the listed time: evaluated as asked */
        disturbances_at(b->sc, t_s, d_out);
    }
}

/* The references at t, rad, as the controllers get them (ladrc_real_t). */
void runner_references(const sim_scenario_t *sc, double t_s, sim_expr_memo_t *memo, ladrc_real_t ref[3])
{
    for (int i = 0; i < 3; ++i) {
        ref[i] = (ladrc_real_t)sim_signal_eval_memo(&sc->reference[i], t_s, memo);
    }
}
