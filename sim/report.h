/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The comparison tables on stdout (the paper's Tables 3-7) and the metrics
 * summary file.
 */
#ifndef LADRC_SIM_REPORT_H
#define LADRC_SIM_REPORT_H

#include <stdio.h>

#include "metrics.h"
#include "scenario.h"

/* Results of one scenario: one sim_metrics_t per controller in sc->controllers
 * (attitude), or the differentiator metrics. */
typedef struct {
    const sim_scenario_t *sc;
    const sim_metrics_t *attitude;      /* sc->n_controllers entries, or NULL */
    const sim_diff_metrics_t *diff;     /* or NULL */
} sim_scenario_result_t;

void sim_report_tables(FILE *out, const sim_scenario_result_t *res);

/* Appends the metrics as CSV rows: scenario,controller,table,quantity,axis,value.
 * Writes the header when header is non-zero. Returns 0, or -1 on a write error. */
int sim_report_metrics_csv(FILE *out, const sim_scenario_result_t *res, int header);

#endif
