/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Flying a batch of loaded scenarios on worker threads, the part of
 * ladrc_sil shared by its scenario mode (main.c) and its campaign mode
 * (campaign_main.c): tune = margins first, then one job per controller of
 * each attitude scenario (one per differentiator scenario), a scenario's
 * runs in lockstep groups that share the disturbances (runner.h), the
 * longest groups first; then each scenario's metrics.csv and signals.csv.
 * Results depend neither on the number of threads nor on the batch.
 */
#ifndef LADRC_SIM_FLY_H
#define LADRC_SIM_FLY_H

#include "scenario/scenario.h"

/* Scenarios in one batch: the static arrays of a batch hold this many. */
#define SIM_FLY_MAX_SCENARIOS 32

/* Called about every 0.1 s while a batch flies, from the thread that called
 * sim_fly_batch: control periods done so far in the batch (a hint), and the
 * scenarios of the batch whose every run has ended. */
typedef void (*sim_fly_progress_fn)(void *ctx, double ticks_done, int scenarios_done);

typedef struct {
    int jobs;                     /* worker threads wanted, >= 1 */
    int want_csv;                 /* time series <out>/<CONTROLLER>.csv */
    int quiet;                    /* no progress line (the callback is still called) */
    int print_tables;             /* the comparison tables on stdout */
    int report_divergence;        /* one stderr line per diverged run */
    sim_fly_progress_fn progress; /* NULL: the scenario mode's progress line on stderr */
    void *progress_ctx;
} sim_fly_options_t;

typedef struct {
    int runs;               /* jobs flown: controllers of attitude scenarios, differentiators */
    int runs_failed;        /* runs that could not run (their message printed on stderr) */
    int writes_failed;      /* metrics.csv or signals.csv not written (printed on stderr) */
    int runs_diverged;      /* attitude runs that diverged */
    int runs_untunable;     /* controllers not flown: untunable (sim_fly_tune) */
    int scenarios_diverged; /* scenarios with at least one */
    double simulated_s;     /* simulated time of the runs that flew */
    double wall_s;          /* wall time of the flights */
    int threads;            /* worker threads started */
} sim_fly_result_t;

/* Monotonic clock, seconds. */
double sim_fly_now_s(void);

/* Ticks of every run of the scenarios (control periods x controllers), for
 * the progress of several batches. */
double sim_fly_total_ticks(const sim_scenario_t *scenarios, int n_sc);

/* How sim_fly_tune runs and tells. */
typedef struct {
    int jobs;   /* worker threads, >= 1 */
    int quiet;  /* no line of the time it took */
    int strict; /* 1: a tuning that misses (SIM_TUNE_MISSED) or a controller untunable refuses the batch */
    /* Called, when not strict, for each controller whose tuning missed or
     * that is untunable (rc: SIM_TUNE_MISSED or SIM_TUNE_UNTUNABLE of
     * tune.h), in task order, after every tuning ended; NULL: nothing. */
    void (*note)(void *ctx, int scenario_index, int rc, const sim_parse_error_t *err);
    void *note_ctx;
} sim_fly_tune_options_t;

/* Tunes every listed controller with tune = margins, opt->jobs at a time.
 * Returns the number of controllers found untunable (they are not flown:
 * sim_fly_batch marks them); or, when strict, -1 with the first that
 * missed or is untunable (in task order) in *err and its scenario's index
 * in *failed (nothing printed). A line of the time it took on stderr
 * unless quiet. */
int sim_fly_tune(sim_scenario_t *scenarios, int n_sc, const sim_fly_tune_options_t *opt, sim_parse_error_t *err,
                 int *failed);

/* The Betaflight SITL folder of a scenario that flies BETAFLIGHT (dir:
 * --betaflight or $LADRC_BETAFLIGHT_SITL; NULL or "": none given); 0, or -1
 * after printing why on stderr (none given, or too long). */
int sim_fly_set_betaflight(sim_scenario_t *sc, const char *dir);

/* Refuses two scenarios writing the same output_dir: returns 0, or -1 after
 * printing the first pair on stderr. */
int sim_fly_check_collisions(const sim_scenario_t *scenarios, int n_sc);

/* mkdir -p: 0, or -1 with errno set. */
int sim_fly_make_dirs(const char *path);

/* -1 (said on stderr) when the scenario's file, one of its recorded series
 * or other (NULL: none) is one of the files its run writes in its
 * output_dir: the run would replace its own input; else 0. */
int sim_fly_check_inputs(const sim_scenario_t *sc, const char *other);

/* Flies scenarios[0..n_sc-1] (at most SIM_FLY_MAX_SCENARIOS, tuned already;
 * a controller untunable is not flown: its statistics read untunable)
 * and writes each one's output_dir: the directory, the time series when
 * wanted, metrics.csv and signals.csv. Fills *res; returns 0 when every run
 * flew and every file was written, else -1 (each failure printed on stderr;
 * the outputs of the scenarios whose runs all flew are still written). */
int sim_fly_batch(const sim_scenario_t *scenarios, int n_sc, const sim_fly_options_t *opt, sim_fly_result_t *res);

#endif
