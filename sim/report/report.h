/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The comparison tables on stdout (the paper's Tables 3-7) and the metrics
 * summary file.
 */
#ifndef LADRC_SIM_REPORT_H
#define LADRC_SIM_REPORT_H

#include <stddef.h>
#include <stdio.h>

#include "run/metrics.h"
#include "scenario/scenario.h"

/* Results of one scenario: one sim_metrics_t per controller in sc->controllers
 * (attitude), or the differentiator metrics. */
typedef struct {
    const sim_scenario_t *sc;
    const sim_metrics_t *attitude;  /* sc->n_controllers entries, or NULL */
    const sim_diff_metrics_t *diff; /* or NULL */
} sim_scenario_result_t;

/* What the tables print in place of a number. */
#define SIM_TEXT_DIVERGED "diverged"       /* every statistic of a run that diverged */
#define SIM_TEXT_UNTUNABLE "untunable"     /* every statistic of a controller not flown (tune.h) */
#define SIM_TEXT_NOT_SETTLED "not settled" /* a settling time when the error ends outside the band */

/* The tokens of metrics.csv's value column in place of a number (docs/simulator.md;
 * tools/sim_output.py reads them). */
#define SIM_TOKEN_DIVERGED "diverged"       /* every statistic of a run that diverged */
#define SIM_TOKEN_UNTUNABLE "untunable"     /* every statistic of a controller not flown (tune.h) */
#define SIM_TOKEN_NOT_SETTLED "not_settled" /* settling_s when the error ends outside the band */
#define SIM_TOKEN_NONE "-"                  /* diverged_at_s, diverged_error_deg of a healthy run */

void sim_report_tables(FILE *out, const sim_scenario_result_t *res);

/* One line per axis of each listed controller with tune = margins: the
 * gains chosen, which candidate they are (tune.h) and their margins
 * against the targets, then a line of why when the tuner's gains are not
 * flown or miss (part of the tables' header; nothing for untuned
 * controllers). */
void sim_report_tuning(FILE *out, const sim_scenario_t *sc);

/* "diverged at t = ... s on roll: |tracking error| ... deg exceeds diverge_limit_deg = ..."
 * or "...: the state turned non-finite (roll angle or rate)", for the tables and stderr. */
void sim_report_divergence_text(char *buf, size_t len, const sim_scenario_t *sc, const sim_metrics_t *m);

/* Largest |reference''| on axis i (rad/s^2) over (0, until_s]: second
 * differences of the scenario's reference over SIM_REFERENCE_ACCEL_STEP_S. */
#define SIM_REFERENCE_ACCEL_STEP_S 0.005
double sim_report_reference_accel(const sim_scenario_t *sc, int axis, double until_s);

/* "the reference outran the shaper on roll from ... s (|error| up to ... deg, ...): it asks up to
 * ... rad/s^2 where the rotors give ... about hover: reference beyond authority" (or "...: a
 * shaper's bound holds it back"), for axis i of a run whose reference_outran_at_s[i] is set. */
void sim_report_outran_text(char *buf, size_t len, const sim_scenario_t *sc, const sim_metrics_t *m, int axis);

/* Appends the metrics as CSV rows: scenario,controller,table,quantity,axis,value,
 * (a tuned controller adds table "tune": its gains wc_rad_s, wo_rad_s or
 * pid_kp, pid_ki, pid_kd, pid_d_filter_tau_s, and pm_deg, gm_db, gm_low_db,
 * crossover_rad_s, ms per axis; "inf" where a margin does not exist),
 * where value is a number (%.9g; "nan" for a diverged_error_deg of a non-finite
 * state) or one of the tokens above.
 * Writes the header when header is non-zero. Returns 0, or -1 on a write error. */
int sim_report_metrics_csv(FILE *out, const sim_scenario_result_t *res, int header);

#endif
