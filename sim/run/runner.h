/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * One simulation run: a scenario flown by one controller (attitude kind), or
 * the two reference shapers on a noisy signal (differentiator kind). The
 * library is driven exactly as firmware would: same float build, one
 * ladrc_attitude_step, mixer step and set_applied per control tick.
 */
#ifndef LADRC_SIM_RUNNER_H
#define LADRC_SIM_RUNNER_H

#include <stddef.h>

#include "metrics.h"
#include "scenario/scenario.h"

/* Progress: the run adds its completed control ticks here (may be NULL);
 * the caller reads it from another thread, so it is only a hint. */
typedef struct {
    volatile long *ticks_done;
} sim_progress_t;

/* A tracking error beyond diverge_limit_deg is the reference outrunning the
 * controller's shaper, not a divergence, while the controller is within
 * this share of the limit of its own shaped reference. */
#define SIM_SHAPED_TRACKING_SHARE 0.5

/* Runs one controller on an attitude scenario. csv_path NULL: no time series.
 * Returns 0, or -1 with a message in err (nothing was run).
 * Divergence: at each control instant t, before the controller acts, the
 * plant's state is checked; if an angle, rate or rotor w^2 is not finite, or
 * |reference - angle| on an axis exceeds the scenario's diverge_limit_deg,
 * the run stops there with out->diverged set (still returning 0): its time
 * series ends at the instant before, and no statistic of it is reported.
 * The state the last step leaves at t = duration is checked the same way. */
int sim_run_attitude(const sim_scenario_t *sc, sim_controller_id_t ctrl, const char *csv_path,
                     const sim_progress_t *progress, sim_metrics_t *out, char *err, size_t err_len);

/* One run of a group: what to fly and where its results go. */
typedef struct {
    sim_controller_id_t ctrl;
    const char *csv_path; /* NULL: no time series */
    sim_metrics_t *metrics;
    char *err; /* the message when rc is -1 */
    size_t err_len;
    int rc; /* set by the group: as sim_run_attitude returns */
} sim_run_spec_t;

/* Several controllers on one attitude scenario, stepped in lockstep: each
 * tick's references and disturbances (every plant stage time) are worked out
 * once for all of them, as their plants ask for the same times. Each run's
 * results are those of sim_run_attitude bit for bit, its rc what that would
 * return; a run that diverges stops alone, one that cannot start does not
 * fly. progress counts the ticks of every run; each run's wall_s is the
 * group's. At most SIM_MAX_CONTROLLERS runs: those beyond fail (rc -1). */
void sim_run_attitude_group(const sim_scenario_t *sc, sim_run_spec_t *runs, int n_runs, const sim_progress_t *progress);

/* Runs Levant and the TD on the differentiator scenario's noisy signal. */
int sim_run_differentiator(const sim_scenario_t *sc, const char *csv_path, const sim_progress_t *progress,
                           sim_diff_metrics_t *out, char *err, size_t err_len);

/* The flight logs ([run] log) of a run whose time series is STEM.csv: file k
 * of SIM_RUN_LOG_FILES is named into out; returns the SIM_RUN_LOG_* form it
 * belongs to, or 0 when k is out of range or the name does not fit. */
#define SIM_RUN_LOG_FILES 10
int sim_run_log_name(const char *stem, int k, char *out, size_t len);

/* Control ticks a run of sc takes (for progress). */
long sim_run_ticks(const sim_scenario_t *sc);

#endif
