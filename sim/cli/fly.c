/* SPDX-License-Identifier: BSD-3-Clause */
/* Flying a batch of scenarios on worker threads (see fly.h). */
#define _POSIX_C_SOURCE 200809L
#include "fly.h"

#include <errno.h>
#include <signal.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "bridge/bf_link.h"
#include "run/progress.h"
#include "staged_dir.h"
#include "report/report.h"
#include "run/runner.h"
#include "run/tune.h"

#define MAX_JOBS (SIM_FLY_MAX_SCENARIOS * SIM_MAX_CONTROLLERS)
#define MAX_THREADS 256

typedef struct {
    const sim_scenario_t *sc;
    int scenario_index;                 /* into the batch */
    int controller_index;               /* into sc->controllers; -1 for a differentiator run */
    int group_size;                     /* runs flown in lockstep from this job on; 0: in an earlier job's group */
    char csv_path[SIM_STAGED_PATH_LEN]; /* in the scenario's staging folder */
    sim_metrics_t *attitude;            /* where the result goes */
    sim_diff_metrics_t *diff;
    volatile long ticks_done; /* progress hint, written by the worker only */
    char error[SIM_PATH_LEN + 160];
    int failed;
} job_t;

typedef struct {
    job_t *jobs;
    const int *order; /* groups (their first jobs) in the order they are handed out */
    int n_groups;
    int n_jobs;
    int next; /* next group to take, under lock */
    int done;
    int runs_left[SIM_FLY_MAX_SCENARIOS]; /* of each scenario, under lock */
    int scenarios_done;
    pthread_mutex_t lock;
    pthread_cond_t finished; /* signalled as each job ends */
} pool_t;

double sim_fly_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

double sim_fly_total_ticks(const sim_scenario_t *scenarios, int n_sc)
{
    double total = 0.0;
    for (int s = 0; s < n_sc; ++s) {
        const int n = scenarios[s].kind == SIM_KIND_DIFFERENTIATOR ? 1 : scenarios[s].n_controllers;
        total += (double)n * (double)sim_run_ticks(&scenarios[s]);
    }
    return total;
}

/* tune = margins of one controller of one scenario, run before the flights. */
typedef struct {
    sim_scenario_t *sc;
    int scenario_index;
    sim_controller_id_t id;
    sim_parse_error_t err;
    int rc; /* of sim_tune_controller; -1: not run (out of memory) */
} tune_task_t;

typedef struct {
    tune_task_t *tasks;
    int n, next;
    pthread_mutex_t lock;
} tune_pool_t;

static void *tune_worker(void *arg)
{
    tune_pool_t *pool = (tune_pool_t *)arg;
    ladrc_margins_workspace_t *ws = malloc(sizeof *ws);
    for (;;) {
        pthread_mutex_lock(&pool->lock);
        const int i = pool->next < pool->n ? pool->next++ : -1;
        pthread_mutex_unlock(&pool->lock);
        if (i < 0) {
            break;
        }
        tune_task_t *t = &pool->tasks[i];
        if (ws == NULL) {
            snprintf(t->err.message, sizeof t->err.message, "tune = margins: out of memory");
            t->rc = -1;
            continue;
        }
        t->rc = sim_tune_controller(t->sc, t->id, ws, &t->err);
    }
    free(ws);
    return NULL;
}

int sim_fly_tune(sim_scenario_t *scenarios, int n_sc, const sim_fly_tune_options_t *opt, sim_parse_error_t *err,
                 int *failed)
{
    static tune_task_t tasks[MAX_JOBS];
    int n = 0;
    for (int s = 0; s < n_sc && s < SIM_FLY_MAX_SCENARIOS; ++s) {
        for (int c = 0; c < scenarios[s].n_controllers && scenarios[s].kind == SIM_KIND_ATTITUDE; ++c) {
            if (sim_tune_wanted(&scenarios[s], scenarios[s].controllers[c])) {
                memset(&tasks[n], 0, sizeof tasks[n]);
                tasks[n].sc = &scenarios[s];
                tasks[n].scenario_index = s;
                tasks[n].id = scenarios[s].controllers[c];
                ++n;
            }
        }
    }
    if (n == 0) {
        return 0;
    }
    const double start = sim_fly_now_s();
    /* A controller capped by another's command noise (tune_noise_ref) is
     * tuned after it: the tasks without such a cap first, then the rest. */
    static tune_task_t ordered[MAX_JOBS];
    int n_first = 0;
    for (int pass = 0, k = 0; pass < 2; ++pass) {
        for (int i = 0; i < n; ++i) {
            if ((tasks[i].sc->overrides[tasks[i].id].tune_noise_ref >= 0) == pass) {
                ordered[k++] = tasks[i];
            }
        }
        n_first = pass == 0 ? k : n_first;
    }
    memcpy(tasks, ordered, (size_t)n * sizeof tasks[0]);
    int started = 0;
    for (int pass = 0; pass < 2 && (pass == 0 || n_first < n); ++pass) {
        tune_pool_t pool = {.tasks = tasks + (pass ? n_first : 0),
                            .n = pass ? n - n_first : n_first,
                            .next = 0,
                            .lock = PTHREAD_MUTEX_INITIALIZER};
        pthread_t threads[MAX_THREADS];
        int running = 0;
        for (int t = 0; t < opt->jobs && t < pool.n && t < MAX_THREADS; ++t) {
            if (pthread_create(&threads[t], NULL, tune_worker, &pool) != 0) {
                break;
            }
            ++running;
        }
        if (running == 0) {
            tune_worker(&pool);
        }
        for (int t = 0; t < running; ++t) {
            pthread_join(threads[t], NULL);
        }
        started = running > started ? running : started;
    }
    int untunable = 0;
    double wall_s = 0.0, tuner_s = 0.0;
    for (int i = 0; i < n; ++i) {
        const tune_task_t *t = &tasks[i];
        wall_s += t->sc->tuning[t->id].wall_s;
        tuner_s += t->sc->tuning[t->id].tuner_s;
        if (t->rc < 0 || (opt->strict && t->rc != SIM_TUNE_OK)) {
            *err = t->err;
            *failed = t->scenario_index;
            return -1;
        }
        untunable += t->rc == SIM_TUNE_UNTUNABLE;
        if (t->rc != SIM_TUNE_OK && opt->note != NULL) {
            opt->note(opt->note_ctx, t->scenario_index, t->rc, &t->err);
        }
    }
    if (!opt->quiet) {
        fprintf(stderr,
                "ladrc_sil: tuned %d controllers (tune = margins) in %.2f s with %d jobs%s; of one core %.2f s, "
                "the tuners and their check flights %.2f s, the other candidates %.2f s (%.2fx)\n",
                n, sim_fly_now_s() - start, started > 0 ? started : 1, untunable > 0 ? "; some untunable" : "", wall_s,
                tuner_s, wall_s - tuner_s, tuner_s > 0.0 ? wall_s / tuner_s : 0.0);
    }
    return untunable;
}

int sim_fly_make_dirs(const char *path)
{
    char buf[SIM_PATH_LEN + 64];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p != '\0'; ++p) {
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
                return -1;
            }
            *p = '/';
        }
    }
    return (mkdir(buf, 0777) != 0 && errno != EEXIST) ? -1 : 0;
}

static void *worker(void *arg)
{
    pool_t *pool = (pool_t *)arg;
    for (;;) {
        pthread_mutex_lock(&pool->lock);
        const int i = pool->next < pool->n_groups ? pool->next++ : -1;
        pthread_mutex_unlock(&pool->lock);
        if (i < 0) {
            return NULL;
        }
        job_t *job = &pool->jobs[pool->order[i]];
        const sim_progress_t progress = {.ticks_done = &job->ticks_done};
        if (job->controller_index < 0) {
            const char *csv = job->csv_path[0] != '\0' ? job->csv_path : NULL;
            job->failed =
                sim_run_differentiator(job->sc, csv, &progress, job->diff, job->error, sizeof job->error) != 0;
        } else {
            sim_run_spec_t runs[SIM_MAX_CONTROLLERS];
            for (int g = 0; g < job->group_size; ++g) {
                job_t *j = job + g;
                const sim_run_spec_t spec = {.ctrl = j->sc->controllers[j->controller_index],
                                             .csv_path = j->csv_path[0] != '\0' ? j->csv_path : NULL,
                                             .metrics = j->attitude,
                                             .err = j->error,
                                             .err_len = sizeof j->error,
                                             .rc = 0};
                runs[g] = spec;
            }
            sim_run_attitude_group(job->sc, runs, job->group_size, &progress);
            for (int g = 0; g < job->group_size; ++g) {
                job[g].failed = runs[g].rc != 0;
            }
        }
        pthread_mutex_lock(&pool->lock);
        pool->done += job->group_size;
        if ((pool->runs_left[job->scenario_index] -= job->group_size) == 0) {
            ++pool->scenarios_done;
        }
        pthread_cond_signal(&pool->finished);
        pthread_mutex_unlock(&pool->lock);
    }
}

/* out/x, out//x/ and ./out/x name the same directory: compared in this form. */
static void normal_dir(const char *dir, char *out, size_t n)
{
    size_t o = 0;
    for (const char *s = dir; *s != '\0' && o + 1 < n;) {
        if ((s == dir || s[-1] == '/') && s[0] == '.' && (s[1] == '/' || s[1] == '\0')) {
            s += s[1] == '/' ? 2 : 1; /* a "./" component */
            continue;
        }
        if (*s == '/' && o > 0 && out[o - 1] == '/') {
            ++s;
            continue;
        }
        out[o++] = *s++;
    }
    while (o > 1 && out[o - 1] == '/') {
        --o;
    }
    out[o] = '\0';
}

#define MAX_OUTPUT_NAMES SIM_STAGED_MAX_FILES

static sim_staged_dir_t stages[SIM_FLY_MAX_SCENARIOS]; /* each scenario's outputs until they are whole */
static volatile sig_atomic_t n_stages;

/* The names of the files a scenario's runs write in its output folder (sc
 * NULL: those any scenario's may, for removing an earlier run's), into names;
 * returns their count. */
static int output_names(const sim_scenario_t *sc, char names[][SIM_STAGED_NAME_LEN])
{
    int n = 0;
    snprintf(names[n++], SIM_STAGED_NAME_LEN, "metrics.csv");
    snprintf(names[n++], SIM_STAGED_NAME_LEN, "signals.csv");
    if (sc == NULL || sc->kind == SIM_KIND_DIFFERENTIATOR) {
        snprintf(names[n++], SIM_STAGED_NAME_LEN, "differentiator.csv");
    }
    const int n_ctl = sc == NULL ? SIM_CTRL_COUNT : sc->kind == SIM_KIND_ATTITUDE ? sc->n_controllers : 0;
    for (int c = 0; c < n_ctl && n < MAX_OUTPUT_NAMES; ++c) {
        const char *name = sim_controller_name(sc == NULL ? (sim_controller_id_t)c : sc->controllers[c]);
        snprintf(names[n++], SIM_STAGED_NAME_LEN, "%s.csv", name);
        for (int k = 0; k < SIM_RUN_LOG_FILES && n < MAX_OUTPUT_NAMES; ++k) {
            const int form = sim_run_log_name(name, k, names[n], SIM_STAGED_NAME_LEN);
            n += form != 0 && (sc == NULL || (sc->log_forms & form) != 0);
        }
    }
    return n;
}

/* Every name a scenario's runs may write: an earlier run's, not written
 * again, is removed when a run's outputs are put in place. */
static char owned[MAX_OUTPUT_NAMES][SIM_STAGED_NAME_LEN];
static const char *owned_of[MAX_OUTPUT_NAMES];
static int n_owned;

/* Stops an interrupted batch without leaving its half-written outputs. */
static void abort_stages(int sig)
{
    for (int s = 0; s < n_stages; ++s) {
        sim_staged_abort(&stages[s]);
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

int sim_fly_check_inputs(const sim_scenario_t *sc, const char *other)
{
    char names[MAX_OUTPUT_NAMES][SIM_STAGED_NAME_LEN];
    const char *name_of[MAX_OUTPUT_NAMES];
    const int n = output_names(sc, names);
    for (int i = 0; i < n; ++i) {
        name_of[i] = names[i];
    }
    const char *const inputs[] = {
        sc->path, sc->dist_series, sc->ref_series, sc->rate_noise_series, sc->angle_noise_series, other};
    char why[2 * SIM_PATH_LEN];
    if (sim_staged_check_inputs(sc->output_dir, name_of, n, inputs, (int)(sizeof inputs / sizeof inputs[0]), why,
                                sizeof why) != 0) {
        fprintf(stderr, "ladrc_sil: %s: %s: give the run another output_dir (or --out)\n", sc->path, why);
        return -1;
    }
    return 0;
}

int sim_fly_set_betaflight(sim_scenario_t *sc, const char *dir)
{
    int flies = 0;
    for (int c = 0; sc->kind == SIM_KIND_ATTITUDE && c < sc->n_controllers; ++c) {
        flies |= sc->controllers[c] == SIM_CTRL_BETAFLIGHT;
    }
    if (!flies) {
        return 0;
    }
    if (dir == NULL || dir[0] == '\0') {
        fprintf(stderr,
                "%s: BETAFLIGHT needs a Betaflight SITL: --betaflight DIR or LADRC_BETAFLIGHT_SITL=DIR "
                "(tools/betaflight_sitl.sh CHECKOUT DIR builds one; docs/betaflight.md)\n",
                sc->path);
        return -1;
    }
    if (strlen(dir) >= sizeof sc->betaflight_sitl) {
        fprintf(stderr, "%s: --betaflight: path too long\n", sc->path);
        return -1;
    }
    char program[SIM_PATH_LEN + 32], config[SIM_PATH_LEN + 32];
    snprintf(program, sizeof program, "%s/%s", dir, BF_SITL_PROGRAM);
    snprintf(config, sizeof config, "%s/%s", dir, BF_SITL_CONFIG);
    const char *missing = access(program, X_OK) != 0 ? program : access(config, R_OK) != 0 ? config : NULL;
    if (missing != NULL) {
        fprintf(stderr, "%s: BETAFLIGHT: %s: %s (tools/betaflight_sitl.sh CHECKOUT %s builds it; docs/betaflight.md)\n",
                sc->path, missing, strerror(errno), dir);
        return -1;
    }
    snprintf(sc->betaflight_sitl, sizeof sc->betaflight_sitl, "%s", dir);
    return 0;
}

int sim_fly_check_collisions(const sim_scenario_t *scenarios, int n)
{
    static char norm[SIM_FLY_MAX_SCENARIOS][SIM_PATH_LEN];
    for (int i = 0; i < n && i < SIM_FLY_MAX_SCENARIOS; ++i) {
        if (sim_fly_check_inputs(&scenarios[i], NULL) != 0) {
            return -1;
        }
        normal_dir(scenarios[i].output_dir, norm[i], sizeof norm[i]);
        for (int j = 0; j < i; ++j) {
            if (strcmp(norm[i], norm[j]) == 0) {
                fprintf(stderr,
                        "ladrc_sil: %s and %s would both write '%s' (give one its own [run] output_dir, "
                        "or run them apart)\n",
                        scenarios[j].path, scenarios[i].path, scenarios[i].output_dir);
                return -1;
            }
        }
    }
    return 0;
}

/* One row per piece of each signal the scenario gives: its kind, axis and
 * window (from_s, to_s] ("-inf", "inf" when unbounded), so that a reader of
 * the outputs knows where the references and disturbances change. */
static int write_signals_csv(FILE *f, const sim_scenario_t *sc)
{
    static const char *const AXIS[3] = {"roll", "pitch", "yaw"};
    fputs("signal,axis,piece,from_s,to_s\n", f);
    const struct {
        const char *what;
        const sim_signal_t *sig;
        const char *axis;
    } rows[] = {{.what = "reference", .sig = &sc->reference[0], .axis = AXIS[0]},
                {.what = "reference", .sig = &sc->reference[1], .axis = AXIS[1]},
                {.what = "reference", .sig = &sc->reference[2], .axis = AXIS[2]},
                {.what = "disturbance", .sig = &sc->disturbance[0], .axis = AXIS[0]},
                {.what = "disturbance", .sig = &sc->disturbance[1], .axis = AXIS[1]},
                {.what = "disturbance", .sig = &sc->disturbance[2], .axis = AXIS[2]},
                {.what = "signal", .sig = &sc->diff_signal, .axis = "-"}};
    const int first = sc->kind == SIM_KIND_DIFFERENTIATOR ? 6 : 0;
    const int last = sc->kind == SIM_KIND_DIFFERENTIATOR ? 7 : 6;
    for (int r = first; r < last; ++r) {
        for (int k = 0; k < rows[r].sig->n_pieces; ++k) {
            fprintf(f, "%s,%s,%d,%.17g,%.17g\n", rows[r].what, rows[r].axis, k + 1, rows[r].sig->from_s[k],
                    rows[r].sig->to_s[k]);
        }
    }
    return ferror(f) ? -1 : 0;
}

/* Rough cost of a job in ns of one core per control tick, for the order
 * only: the longest groups go first, so that the last one to start is a
 * short one and the workers finish together. Measured on a Release build
 * (2 shared cores) with ten copies of a shipped scenario flown one after
 * the other (--jobs 1, the fly time ladrc_sil prints, best of 7):
 *   paper.ini alone, 10 substeps, no CSV, ns per tick: PID 1233,
 *     CASCADED 1267, INDI 1233, LADRC 1300, LP-MLADRC 1367, HP-MLADRC 1433;
 *   PID with 1 substep 500, with 4 substeps 667: the plant ~80 ns a substep;
 *   real_paper_lag20.ini (PID, tune = none): motor lag 1467 against 1300
 *     without, x1.2 on the plant's ~800;
 *   every CSV: +1733 ns a run alone, +1861 ns a run in a group of six;
 *   table3_differentiator.ini: ~150 ns, its CSV (five columns) ~250 ns.
 * The rest of a run alone (controller, sensor, signals, metrics) is the
 * controller's figure below: its time less the plant's ~800. */
static double job_compute_ns(const job_t *job)
{
    /* BETAFLIGHT: a UDP round trip with its SITL */
    static const double CONTROLLER_NS[SIM_CTRL_COUNT] = {630.0, 570.0, 500.0, 430.0, 470.0, 430.0, 0.0, 20000.0};
    /* HP LP LADRC PID CASCADED INDI */
    const double ticks = (double)sim_run_ticks(job->sc);
    if (job->controller_index < 0) {
        return ticks * 150.0;
    }
    const sim_controller_id_t id = job->sc->controllers[job->controller_index];
    return ticks * (80.0 * job->sc->plant_substeps * (job->sc->motor_tau_s > 0.0 ? 1.2 : 1.0) + CONTROLLER_NS[id]);
}

/* Writing the job's time series, ns: the same alone or in a group. */
static double job_csv_ns(const job_t *job)
{
    if (job->csv_path[0] == '\0') {
        return 0.0;
    }
    return (double)sim_run_ticks(job->sc) * (job->controller_index < 0 ? 250.0 : 1750.0);
}

/* Rough cost of a group: every run's time series, the first run's
 * computing, and 0.35 of each other run's, the share a run adds to a
 * lockstep group (shared references and disturbances, the plants in
 * interleaved lanes). Measured as above, PID, CASCADED, INDI, LADRC,
 * LP-MLADRC, HP-MLADRC added one by one: the group of 1 to 6 runs took
 * 1233, 1533, 2000, 2100, 2833, 3500 ns per tick, each added run 0.24,
 * 0.38, 0.08 (a fourth plant fills the lanes of three), 0.54 and 0.47 of
 * its time alone (mean 0.34); six runs took 0.45 of their times alone. */
static double group_cost(const job_t *jobs, int first)
{
    double c = 0.0;
    for (int g = 0; g < jobs[first].group_size; ++g) {
        c += job_csv_ns(&jobs[first + g]) + job_compute_ns(&jobs[first + g]) * (g == 0 ? 1.0 : 0.35);
    }
    return c;
}

/* The groups' first jobs by decreasing cost; equal costs keep their order.
 * Returns the number of groups. */
static int order_longest_first(const job_t *jobs, int n, int *order)
{
    int n_groups = 0;
    for (int i = 0; i < n; ++i) {
        if (jobs[i].group_size == 0) {
            continue;
        }
        const double c = group_cost(jobs, i);
        int k = n_groups++;
        while (k > 0 && group_cost(jobs, order[k - 1]) < c) {
            order[k] = order[k - 1];
            --k;
        }
        order[k] = i;
    }
    return n_groups;
}

/* Waits for every job. Without a callback, prints progress on stderr for
 * batches longer than a second: the share of control periods done, the runs
 * done, the time so far and the time left at the pace so far. Woken by each
 * finished job, so the wall time is not rounded up to a polling period. */
static void wait_with_progress(pool_t *pool, double total_ticks, const sim_fly_options_t *opt)
{
    const double start = sim_fly_now_s();
    double last_print = start;
    const int tty = isatty(fileno(stderr));
    pthread_mutex_lock(&pool->lock);
    while (pool->done < pool->n_jobs) {
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += 100000000L;
        if (until.tv_nsec >= 1000000000L) {
            until.tv_sec += 1;
            until.tv_nsec -= 1000000000L;
        }
        pthread_cond_timedwait(&pool->finished, &pool->lock, &until);
        const int done = pool->done;
        double ticks = 0.0;
        for (int i = 0; i < pool->n_jobs; ++i) {
            ticks += (double)pool->jobs[i].ticks_done;
        }
        if (opt->progress != NULL) {
            opt->progress(opt->progress_ctx, ticks, pool->scenarios_done);
            continue;
        }
        const double t = sim_fly_now_s();
        if (done < pool->n_jobs && !opt->quiet && t - start > 1.0 && t - last_print >= (tty ? 0.5 : 2.0)) {
            char text[128];
            sim_progress_text(text, sizeof text, ticks / total_ticks, done, pool->n_jobs, t - start);
            fprintf(stderr, "%sladrc_sil: %s%s", tty ? "\r" : "", text, tty ? "\033[K" : "\n");
            last_print = t;
        }
    }
    pthread_mutex_unlock(&pool->lock);
    if (opt->progress == NULL && !opt->quiet && tty && sim_fly_now_s() - start > 1.0) {
        fputc('\n', stderr);
    }
}

/* The batch's results live here until the next batch. */
static sim_metrics_t attitude[SIM_FLY_MAX_SCENARIOS][SIM_MAX_CONTROLLERS];
static sim_diff_metrics_t diff[SIM_FLY_MAX_SCENARIOS];
static job_t jobs[MAX_JOBS];
static int order[MAX_JOBS];

/* Writes what a scenario's runs give: the tables (when wanted),
 * metrics.csv and signals.csv; counts its diverged runs. */
static void write_outputs(const sim_scenario_t *sc, int s, const sim_fly_options_t *opt, sim_fly_result_t *res)
{
    const int writes_failed = res->writes_failed;
    const sim_scenario_result_t out = {.sc = sc,
                                       .attitude = sc->kind == SIM_KIND_DIFFERENTIATOR ? NULL : attitude[s],
                                       .diff = sc->kind == SIM_KIND_DIFFERENTIATOR ? &diff[s] : NULL};
    if (opt->print_tables) {
        sim_report_tables(stdout, &out);
    }
    char path[SIM_STAGED_PATH_LEN];
    FILE *f = sim_staged_path(&stages[s], "metrics.csv", path, sizeof path) != NULL ? fopen(path, "w") : NULL;
    if (f == NULL || (sim_report_metrics_csv(f, &out, 1) | fclose(f)) != 0) {
        fprintf(stderr, "ladrc_sil: %s/metrics.csv: cannot write\n", sc->output_dir);
        ++res->writes_failed;
    }
    f = sim_staged_path(&stages[s], "signals.csv", path, sizeof path) != NULL ? fopen(path, "w") : NULL;
    if (f == NULL || (write_signals_csv(f, sc) | fclose(f)) != 0) {
        fprintf(stderr, "ladrc_sil: %s/signals.csv: cannot write\n", sc->output_dir);
        ++res->writes_failed;
    }
    char err[SIM_STAGED_PATH_LEN + 160];
    if (res->writes_failed > writes_failed) {
        sim_staged_abort(&stages[s]);
        fprintf(stderr, "ladrc_sil: %s: nothing written\n", sc->output_dir);
    } else if (sim_staged_commit(&stages[s], owned_of, n_owned, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_sil: %s\n", err);
        ++res->writes_failed;
    }
    int diverged = 0;
    for (int c = 0; sc->kind == SIM_KIND_ATTITUDE && c < sc->n_controllers; ++c) {
        if (attitude[s][c].diverged) {
            ++diverged;
            if (opt->report_divergence) {
                char why[160];
                sim_report_divergence_text(why, sizeof why, sc, &attitude[s][c]);
                fprintf(stderr, "ladrc_sil: %s (%s): controller %s %s\n", sc->name, sc->path,
                        sim_controller_name(sc->controllers[c]), why);
            }
        }
    }
    res->runs_diverged += diverged;
    res->scenarios_diverged += diverged > 0;
    int flown = sc->kind == SIM_KIND_DIFFERENTIATOR ? 1 : 0;
    for (int c = 0; sc->kind == SIM_KIND_ATTITUDE && c < sc->n_controllers; ++c) {
        flown += !attitude[s][c].untunable;
    }
    res->simulated_s += sc->duration_s * flown;
}

static void abort_all(void)
{
    for (int s = 0; s < n_stages; ++s) {
        sim_staged_abort(&stages[s]);
    }
    n_stages = 0;
}

/* A staging folder per scenario, every name its runs write registered (an
 * interruption removes them); a scenario whose folder cannot be made is
 * marked in failed[] (said) and not flown. */
static void open_stages(const sim_scenario_t *scenarios, int n_sc, int *failed)
{
    if (n_owned == 0) {
        n_owned = output_names(NULL, owned);
        for (int i = 0; i < n_owned; ++i) {
            owned_of[i] = owned[i];
        }
    }
    signal(SIGINT, abort_stages);
    signal(SIGTERM, abort_stages);
    signal(SIGHUP, abort_stages);
    for (int s = 0; s < n_sc; ++s) {
        char err[SIM_STAGED_PATH_LEN + 160], names[MAX_OUTPUT_NAMES][SIM_STAGED_NAME_LEN], path[SIM_STAGED_PATH_LEN];
        if (sim_staged_open(&stages[s], scenarios[s].output_dir, err, sizeof err) != 0) {
            fprintf(stderr, "ladrc_sil: %s: cannot write its outputs: %s\n", scenarios[s].path, err);
            failed[s] = 1;
        }
        n_stages = s + 1;
        const int n = failed[s] ? 0 : output_names(&scenarios[s], names);
        for (int i = 0; i < n && !failed[s]; ++i) {
            if (sim_staged_path(&stages[s], names[i], path, sizeof path) == NULL) {
                fprintf(stderr, "ladrc_sil: %s/%s: path too long\n", scenarios[s].output_dir, names[i]);
                sim_staged_abort(&stages[s]);
                failed[s] = 1;
            }
        }
    }
}

int sim_fly_batch(const sim_scenario_t *scenarios, int n_sc, const sim_fly_options_t *opt, sim_fly_result_t *res)
{
    memset(res, 0, sizeof *res);
    if (n_sc < 1 || n_sc > SIM_FLY_MAX_SCENARIOS) {
        fprintf(stderr, "ladrc_sil: a batch holds 1 to %d scenarios, not %d\n", SIM_FLY_MAX_SCENARIOS, n_sc);
        ++res->runs_failed;
        return -1;
    }
    /* One job per controller of each attitude scenario, one per differentiator. */
    int n_jobs = 0;
    double total_ticks = 0.0;
    /* A scenario's runs fly in lockstep groups (they share the disturbances):
     * as few groups as keep every worker busy, at least one per scenario. */
    int n_scenarios_flown = 0;
    for (int s = 0; s < n_sc; ++s) {
        n_scenarios_flown += scenarios[s].kind == SIM_KIND_ATTITUDE;
    }
    pool_t pool;
    memset(&pool, 0, sizeof pool);
    int scenario_failed[SIM_FLY_MAX_SCENARIOS] = {0};
    open_stages(scenarios, n_sc, scenario_failed);
    for (int s = 0; s < n_sc; ++s) {
        const sim_scenario_t *sc = &scenarios[s];
        if (scenario_failed[s]) {
            ++res->writes_failed;
            ++pool.scenarios_done;
            continue;
        }
        const int n_ctl = sc->kind == SIM_KIND_DIFFERENTIATOR ? 1 : sc->n_controllers;
        int n = 0; /* runs flown: an untunable controller is not */
        for (int c = 0; c < n_ctl; ++c) {
            if (sc->kind == SIM_KIND_ATTITUDE && sc->tuning[sc->controllers[c]].by == SIM_TUNED_UNTUNABLE) {
                memset(&attitude[s][c], 0, sizeof attitude[s][c]);
                attitude[s][c].untunable = 1;
                ++res->runs_untunable;
                continue;
            }
            ++n;
            job_t *job = &jobs[n_jobs++];
            memset(job, 0, sizeof *job);
            job->sc = sc;
            job->scenario_index = s;
            job->controller_index = sc->kind == SIM_KIND_DIFFERENTIATOR ? -1 : c;
            job->attitude = &attitude[s][c];
            job->diff = &diff[s];
            if (opt->want_csv) {
                char name[SIM_STAGED_NAME_LEN];
                snprintf(name, sizeof name, "%s.csv",
                         job->controller_index < 0 ? "differentiator" : sim_controller_name(sc->controllers[c]));
                (void)sim_staged_path(&stages[s], name, job->csv_path, sizeof job->csv_path); /* registered */
            }
            total_ticks += (double)sim_run_ticks(sc);
        }
        pool.runs_left[s] = n;
        pool.scenarios_done += n == 0;
        if (sc->kind == SIM_KIND_DIFFERENTIATOR) {
            jobs[n_jobs - 1].group_size = 1;
        } else if (n > 0) {
            const int groups_wanted = (opt->jobs + n_scenarios_flown - 1) / n_scenarios_flown;
            const int n_groups_sc = groups_wanted < n ? groups_wanted : n;
            const int size = (n + n_groups_sc - 1) / n_groups_sc;
            for (int c = 0; c < n; c += size) {
                jobs[n_jobs - n + c].group_size = n - c < size ? n - c : size;
            }
        }
    }

    const int n_groups = order_longest_first(jobs, n_jobs, order);
    pool.jobs = jobs;
    pool.order = order;
    pool.n_groups = n_groups;
    pool.n_jobs = n_jobs;
    pthread_mutex_init(&pool.lock, NULL);
    pthread_cond_init(&pool.finished, NULL);
    const int wanted = opt->jobs < MAX_THREADS ? opt->jobs : MAX_THREADS;
    const int n_threads = wanted < n_groups ? wanted : n_groups;
    pthread_t threads[MAX_THREADS];
    const double start = sim_fly_now_s();
    int started = 0;
    for (int t = 0; t < n_threads; ++t) {
        if (pthread_create(&threads[t], NULL, worker, &pool) != 0) {
            break;
        }
        ++started;
    }
    if (started < n_threads) {
        fprintf(stderr, "ladrc_sil: cannot start a worker thread\n");
        pthread_mutex_lock(&pool.lock);
        pool.next = pool.n_groups; /* nothing more is handed out */
        pthread_mutex_unlock(&pool.lock);
        for (int t = 0; t < started; ++t) {
            pthread_join(threads[t], NULL);
        }
        abort_all();
        ++res->runs_failed;
        return -1;
    }
    wait_with_progress(&pool, total_ticks, opt);
    for (int t = 0; t < started; ++t) {
        pthread_join(threads[t], NULL);
    }
    pthread_mutex_destroy(&pool.lock);
    pthread_cond_destroy(&pool.finished);
    res->wall_s = sim_fly_now_s() - start;
    res->threads = started;
    res->runs = n_jobs;

    for (int j = 0; j < n_jobs; ++j) {
        if (jobs[j].failed) {
            fprintf(stderr, "ladrc_sil: %s\n", jobs[j].error);
            scenario_failed[jobs[j].scenario_index] = 1;
            ++res->runs_failed;
        }
    }
    for (int s = 0; s < n_sc; ++s) {
        if (!scenario_failed[s]) { /* no tables from a run that did not happen */
            write_outputs(&scenarios[s], s, opt, res);
        } else {
            sim_staged_abort(&stages[s]);
            fprintf(stderr, "ladrc_sil: %s: nothing written\n", scenarios[s].output_dir);
        }
    }
    n_stages = 0;
    return res->runs_failed > 0 || res->writes_failed > 0 ? -1 : 0;
}
