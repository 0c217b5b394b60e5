/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_sil: runs scenario files against the ladrc library on a simulated
 * quadrotor and prints the paper's comparison tables. Independent runs are
 * spread over worker threads, a scenario's runs in lockstep groups that share
 * the disturbances (runner.h); results depend on neither.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "progress.h"
#include "report.h"
#include "runner.h"
#include "scenario.h"
#include "tune.h"

#define MAX_SCENARIOS 32

/* Exit statuses (usage(), README "The simulator"). */
enum { EXIT_RUN_FAILED = 1, EXIT_BAD_INPUT = 2, EXIT_DIVERGED = 3 };

typedef struct {
    const sim_scenario_t *sc;
    int controller_index;          /* into sc->controllers; -1 for a differentiator run */
    int group_size;                /* runs flown in lockstep from this job on; 0: in an earlier job's group */
    char csv_path[SIM_PATH_LEN + 64];
    sim_metrics_t *attitude;       /* where the result goes */
    sim_diff_metrics_t *diff;
    volatile long ticks_done;      /* progress hint, written by the worker only */
    char error[SIM_PATH_LEN + 160];
    int failed;
} job_t;

typedef struct {
    job_t *jobs;
    const int *order;              /* groups (their first jobs) in the order they are handed out */
    int n_groups;
    int n_jobs;
    int next;                      /* next group to take, under lock */
    int done;
    pthread_mutex_t lock;
    pthread_cond_t finished;       /* signalled as each job ends */
} pool_t;

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The command line's settings: --set items and --seed, in their order. */
#define MAX_SETTINGS 64
typedef struct {
    const char *text[MAX_SETTINGS];
    const char *shown[MAX_SETTINGS]; /* the argument as given */
    int shift[MAX_SETTINGS];         /* columns of text before the argument ("run.seed=") */
    char label[MAX_SETTINGS][24];    /* "--set 2", "--seed" */
    char seed_text[40];            /* "run.seed=N" of --seed */
    int n;
} settings_t;

/* Prints an error of a scenario or of a setting, as file:line:column or
 * "--set K (TEXT):column". */
static void print_error(const sim_parse_error_t *e, const settings_t *set, const char *fallback_path)
{
    const int k = e->first_set_line > 0 && e->line >= e->first_set_line ? e->line - e->first_set_line : -1;
    if (k >= 0 && k < set->n) {
        const int col = e->column - set->shift[k];
        fprintf(stderr, "ladrc_sil: %s '%s':%d: %s (with %s)\n", set->label[k], set->shown[k], col > 0 ? col : 1,
                e->message, e->path);
    } else if (e->line > 0) {
        fprintf(stderr, "%s:%d:%d: %s\n", e->path, e->line, e->column, e->message);
    } else {
        fprintf(stderr, "%s: %s\n", e->path[0] != '\0' ? e->path : fallback_path, e->message);
    }
}

/* tune = margins of one controller of one scenario, run before the flights. */
typedef struct {
    sim_scenario_t *sc;
    sim_controller_id_t id;
    sim_parse_error_t err;
    int failed;
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
            t->failed = 1;
            continue;
        }
        t->failed = sim_tune_controller(t->sc, t->id, ws, &t->err) != 0;
    }
    free(ws);
    return NULL;
}

/* Tunes every listed controller with tune = margins, n_threads at a time.
 * Returns 0, or -1 after printing the first failure (in task order). */
static int tune_all(sim_scenario_t *scenarios, int n_sc, int n_threads, int quiet, const settings_t *set)
{
    static tune_task_t tasks[MAX_SCENARIOS * SIM_MAX_CONTROLLERS];
    int n = 0;
    for (int s = 0; s < n_sc; ++s) {
        for (int c = 0; c < scenarios[s].n_controllers && scenarios[s].kind == SIM_KIND_ATTITUDE; ++c) {
            if (sim_tune_wanted(&scenarios[s], scenarios[s].controllers[c])) {
                memset(&tasks[n], 0, sizeof tasks[n]);
                tasks[n].sc = &scenarios[s];
                tasks[n].id = scenarios[s].controllers[c];
                ++n;
            }
        }
    }
    if (n == 0) {
        return 0;
    }
    const double start = now_s();
    tune_pool_t pool = {tasks, n, 0, PTHREAD_MUTEX_INITIALIZER};
    pthread_t threads[256];
    int started = 0;
    for (int t = 0; t < n_threads && t < n; ++t) {
        if (pthread_create(&threads[t], NULL, tune_worker, &pool) != 0) {
            break;
        }
        ++started;
    }
    if (started == 0) {
        tune_worker(&pool);
    }
    for (int t = 0; t < started; ++t) {
        pthread_join(threads[t], NULL);
    }
    for (int i = 0; i < n; ++i) {
        if (tasks[i].failed) {
            print_error(&tasks[i].err, set, tasks[i].sc->path);
            return -1;
        }
    }
    if (!quiet) {
        fprintf(stderr, "ladrc_sil: tuned %d controllers (tune = margins) in %.2f s with %d jobs\n", n,
                now_s() - start, started > 0 ? started : 1);
    }
    return 0;
}

static void usage(FILE *out)
{
    fputs("usage: ladrc_sil SCENARIO... [--jobs N] [--controllers LIST] [--set SECTION.KEY=VALUE]... [--seed N]\n"
          "                 [--out DIR] [--no-csv] [--quiet]\n"
          "  SCENARIO          a scenario file (format: docs/scenario-format.md)\n"
          "  --jobs N          worker threads (default: the number of cores)\n"
          "  --controllers L   subset of HP-MLADRC LP-MLADRC LADRC PID CASCADED INDI, names separated\n"
          "                    by commas, spaces or both (default: each scenario's own list)\n"
          "  --set S.K=V       KEY = VALUE in [SECTION] of every scenario, replacing the file's value\n"
          "                    (a controller's section: controller:NAME.KEY=V); repeatable\n"
          "  --seed N          [run] seed = N in every scenario\n"
          "  --out DIR         write every scenario's output under DIR/<scenario name>\n"
          "                    (default: each scenario's output_dir)\n"
          "  --no-csv          no time series, only metrics.csv and the tables\n"
          "  --quiet           no progress on stderr\n"
          "Prints the comparison tables on stdout; writes <out>/<controller>.csv time series and\n"
          "<out>/metrics.csv. A run diverges when |tracking error| on an axis exceeds the scenario's\n"
          "diverge_limit_deg (default 90) or its state turns non-finite: it stops there, its statistics\n"
          "print as \"diverged\", and stderr names it.\n"
          "Exit status: 0 every run flew; 1 a run failed or an output could not be written;\n"
          "2 bad usage or a bad scenario, a tune = margins target not met included (then nothing is\n"
          "run or written); 3 every run and output\n"
          "completed but a run diverged (1 wins over 3).\n",
          out);
}


/* mkdir -p */
static int make_dirs(const char *path)
{
    char buf[SIM_PATH_LEN + 64];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
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
        const sim_progress_t progress = {&job->ticks_done};
        if (job->controller_index < 0) {
            const char *csv = job->csv_path[0] != '\0' ? job->csv_path : NULL;
            job->failed = sim_run_differentiator(job->sc, csv, &progress, job->diff, job->error, sizeof job->error) != 0;
        } else {
            sim_run_spec_t runs[SIM_MAX_CONTROLLERS];
            for (int g = 0; g < job->group_size; ++g) {
                job_t *j = job + g;
                const sim_run_spec_t spec = {j->sc->controllers[j->controller_index],
                                             j->csv_path[0] != '\0' ? j->csv_path : NULL,
                                             j->attitude, j->error, sizeof j->error, 0};
                runs[g] = spec;
            }
            sim_run_attitude_group(job->sc, runs, job->group_size, &progress);
            for (int g = 0; g < job->group_size; ++g) {
                job[g].failed = runs[g].rc != 0;
            }
        }
        pthread_mutex_lock(&pool->lock);
        pool->done += job->group_size;
        pthread_cond_signal(&pool->finished);
        pthread_mutex_unlock(&pool->lock);
    }
}

static int parse_controllers(const char *list, sim_controller_id_t *ids, int *n)
{
    char msg[160];
    size_t at = 0;
    if (sim_controller_list_parse(list, ids, n, &at, msg, sizeof msg) != 0) {
        fprintf(stderr, "ladrc_sil: --controllers '%s': %s\n", list, msg);
        return -1;
    }
    return 0;
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

/* Two scenarios writing the same directory would overwrite each other's
 * files: refused before anything is written. Returns 0, or -1 after
 * printing the first pair. */
static int check_collisions(const sim_scenario_t *scenarios, int n)
{
    static char norm[MAX_SCENARIOS][SIM_PATH_LEN];
    for (int i = 0; i < n; ++i) {
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
    } rows[] = {{"reference", &sc->reference[0], AXIS[0]},   {"reference", &sc->reference[1], AXIS[1]},
                {"reference", &sc->reference[2], AXIS[2]},   {"disturbance", &sc->disturbance[0], AXIS[0]},
                {"disturbance", &sc->disturbance[1], AXIS[1]}, {"disturbance", &sc->disturbance[2], AXIS[2]},
                {"signal", &sc->diff_signal, "-"}};
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

/* Rough cost of a job in ns of one core (measured on the paper scenario),
 * for the order only: the longest runs go first, so that the last one to
 * start is a short one and the workers finish together. */
static double job_cost(const job_t *job)
{
    static const double CONTROLLER_NS[SIM_CTRL_COUNT] = {1000.0, 450.0, 400.0, 200.0, 200.0, 250.0};
    /* HP LP LADRC PID CASCADED INDI */
    const double csv_ns = job->csv_path[0] != '\0' ? 1200.0 : 0.0;
    const double ticks = (double)sim_run_ticks(job->sc);
    if (job->controller_index < 0) {
        return ticks * (300.0 + csv_ns);
    }
    const sim_controller_id_t id = job->sc->controllers[job->controller_index];
    return ticks * (100.0 * job->sc->plant_substeps * (job->sc->motor_tau_s > 0.0 ? 2.0 : 1.0) +
                    CONTROLLER_NS[id] + csv_ns);
}

/* Rough cost of a group: its runs' costs less the disturbances they share
 * (one run's worth, about 60 % of a run, paid once). */
static double group_cost(const job_t *jobs, int first)
{
    double c = 0.0;
    for (int g = 0; g < jobs[first].group_size; ++g) {
        c += job_cost(&jobs[first + g]) * (g == 0 ? 1.0 : 0.4);
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

/* Waits for every job, printing progress on stderr for runs longer than a
 * second: the share of control periods done, the runs done, the time so
 * far and the time left at the pace so far. Woken by each finished job, so
 * the wall time is not rounded up to a polling period. */
static void wait_with_progress(pool_t *pool, double total_ticks, int quiet)
{
    const double start = now_s();
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
        const double t = now_s();
        if (done < pool->n_jobs && !quiet && t - start > 1.0 && t - last_print >= (tty ? 0.5 : 2.0)) {
            double ticks = 0.0;
            for (int i = 0; i < pool->n_jobs; ++i) {
                ticks += (double)pool->jobs[i].ticks_done;
            }
            char text[128];
            sim_progress_text(text, sizeof text, ticks / total_ticks, done, pool->n_jobs, t - start);
            fprintf(stderr, "%sladrc_sil: %s%s", tty ? "\r" : "", text, tty ? "\033[K" : "\n");
            last_print = t;
        }
    }
    pthread_mutex_unlock(&pool->lock);
    if (!quiet && tty && now_s() - start > 1.0) {
        fputc('\n', stderr);
    }
}

int main(int argc, char **argv)
{
    static sim_scenario_t scenarios[MAX_SCENARIOS];
    int n_sc = 0;
    long jobs_wanted = sysconf(_SC_NPROCESSORS_ONLN);
    const char *out_root = NULL;
    int want_csv = 1, quiet = 0, n_override = 0;
    sim_controller_id_t override_ids[SIM_MAX_CONTROLLERS];
    const char *paths[MAX_SCENARIOS];
    int n_paths = 0;
    static settings_t set;

    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(arg, "--jobs") == 0 && a + 1 < argc) {
            char *end = NULL;
            jobs_wanted = strtol(argv[++a], &end, 10);
            if (*end != '\0' || jobs_wanted < 1 || jobs_wanted > 256) {
                fprintf(stderr, "ladrc_sil: --jobs: expected a whole number from 1 to 256, got '%s'\n", argv[a]);
                return EXIT_BAD_INPUT;
            }
        } else if (strcmp(arg, "--controllers") == 0 && a + 1 < argc) {
            if (parse_controllers(argv[++a], override_ids, &n_override) != 0) {
                return EXIT_BAD_INPUT;
            }
        } else if ((strcmp(arg, "--set") == 0 || strcmp(arg, "--seed") == 0) && a + 1 < argc) {
            if (set.n >= MAX_SETTINGS) {
                fprintf(stderr, "ladrc_sil: at most %d --set and --seed per call\n", MAX_SETTINGS);
                return EXIT_BAD_INPUT;
            }
            if (strcmp(arg, "--set") == 0) {
                int count = 1;
                for (int i = 0; i < set.n; ++i) {
                    count += strncmp(set.label[i], "--set", 5) == 0;
                }
                snprintf(set.label[set.n], sizeof set.label[0], "--set %d", count);
                set.text[set.n] = set.shown[set.n] = argv[++a];
                set.shift[set.n++] = 0;
            } else if (set.seed_text[0] != '\0') {
                fprintf(stderr, "ladrc_sil: --seed given twice\n");
                return EXIT_BAD_INPUT;
            } else {
                if (snprintf(set.seed_text, sizeof set.seed_text, "run.seed=%s", argv[++a]) >=
                    (int)sizeof set.seed_text) {
                    fprintf(stderr, "ladrc_sil: --seed '%s': seed out of range\n", argv[a]);
                    return EXIT_BAD_INPUT;
                }
                snprintf(set.label[set.n], sizeof set.label[0], "--seed");
                set.text[set.n] = set.seed_text;
                set.shown[set.n] = argv[a];
                set.shift[set.n++] = (int)strlen("run.seed=");
            }
        } else if (strcmp(arg, "--out") == 0 && a + 1 < argc) {
            out_root = argv[++a];
        } else if (strcmp(arg, "--no-csv") == 0) {
            want_csv = 0;
        } else if (strcmp(arg, "--quiet") == 0) {
            quiet = 1;
        } else if (arg[0] == '-') {
            fprintf(stderr, "ladrc_sil: unknown or incomplete option '%s'\n", arg);
            usage(stderr);
            return EXIT_BAD_INPUT;
        } else if (n_paths < MAX_SCENARIOS) {
            paths[n_paths++] = arg;
        } else {
            fprintf(stderr, "ladrc_sil: at most %d scenarios per call\n", MAX_SCENARIOS);
            return EXIT_BAD_INPUT;
        }
    }
    if (n_paths == 0) {
        usage(stderr);
        return EXIT_BAD_INPUT;
    }
    /* Every scenario is read before anything runs: one bad file, nothing written. */
    for (int i = 0; i < n_paths; ++i) {
        sim_parse_error_t perr;
        sim_scenario_t *sc = &scenarios[n_sc++];
        if (sim_scenario_load_with(sc, paths[i], set.text, set.n, &perr) != 0 ||
            (n_override > 0 && sim_scenario_set_controllers(sc, override_ids, n_override, &perr) != 0)) {
            print_error(&perr, &set, paths[i]);
            return EXIT_BAD_INPUT;
        }
        if (out_root != NULL) {
            char dir[sizeof sc->output_dir];
            if (snprintf(dir, sizeof dir, "%s/%s", out_root, sc->name) >= (int)sizeof dir) {
                fprintf(stderr, "ladrc_sil: --out: path too long\n");
                return EXIT_BAD_INPUT;
            }
            memcpy(sc->output_dir, dir, sizeof dir);
        }
    }

    if (check_collisions(scenarios, n_sc) != 0) {
        return EXIT_BAD_INPUT;
    }

    /* tune = margins, before anything is written: a target that cannot be
     * met is an error of the file. */
    if (tune_all(scenarios, n_sc, (int)jobs_wanted, quiet, &set) != 0) {
        return EXIT_BAD_INPUT;
    }

    /* One job per controller of each attitude scenario, one per differentiator. */
    static sim_metrics_t attitude[MAX_SCENARIOS][SIM_MAX_CONTROLLERS];
    static sim_diff_metrics_t diff[MAX_SCENARIOS];
    static job_t jobs[MAX_SCENARIOS * SIM_MAX_CONTROLLERS];
    int n_jobs = 0;
    double total_ticks = 0.0;
    /* A scenario's runs fly in lockstep groups (they share the disturbances):
     * as few groups as keep every worker busy, at least one per scenario. */
    int n_scenarios_flown = 0;
    for (int s = 0; s < n_sc; ++s) {
        n_scenarios_flown += scenarios[s].kind == SIM_KIND_ATTITUDE;
    }
    for (int s = 0; s < n_sc; ++s) {
        const sim_scenario_t *sc = &scenarios[s];
        if (make_dirs(sc->output_dir) != 0) {
            fprintf(stderr, "ladrc_sil: %s: cannot create output directory '%s': %s\n", sc->path, sc->output_dir,
                    strerror(errno));
            return EXIT_RUN_FAILED;
        }
        const int n = sc->kind == SIM_KIND_DIFFERENTIATOR ? 1 : sc->n_controllers;
        for (int c = 0; c < n; ++c) {
            job_t *job = &jobs[n_jobs++];
            memset(job, 0, sizeof *job);
            job->sc = sc;
            job->controller_index = sc->kind == SIM_KIND_DIFFERENTIATOR ? -1 : c;
            job->attitude = &attitude[s][c];
            job->diff = &diff[s];
            if (want_csv) {
                snprintf(job->csv_path, sizeof job->csv_path, "%s/%s.csv", sc->output_dir,
                         job->controller_index < 0 ? "differentiator"
                                                   : sim_controller_name(sc->controllers[c]));
            }
            total_ticks += (double)sim_run_ticks(sc);
        }
        if (sc->kind == SIM_KIND_DIFFERENTIATOR) {
            jobs[n_jobs - 1].group_size = 1;
        } else if (n > 0) {
            const int groups_wanted = (int)((jobs_wanted + n_scenarios_flown - 1) / n_scenarios_flown);
            const int n_groups_sc = groups_wanted < n ? groups_wanted : n;
            const int size = (n + n_groups_sc - 1) / n_groups_sc;
            for (int c = 0; c < n; c += size) {
                jobs[n_jobs - n + c].group_size = n - c < size ? n - c : size;
            }
        }
    }

    static int order[MAX_SCENARIOS * SIM_MAX_CONTROLLERS];
    const int n_groups = order_longest_first(jobs, n_jobs, order);
    pool_t pool = {jobs, order, n_groups, n_jobs, 0, 0, PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER};
    const int n_threads = (int)(jobs_wanted < n_groups ? jobs_wanted : n_groups);
    pthread_t threads[256];
    const double start = now_s();
    for (int t = 0; t < n_threads; ++t) {
        if (pthread_create(&threads[t], NULL, worker, &pool) != 0) {
            fprintf(stderr, "ladrc_sil: cannot start a worker thread\n");
            return EXIT_RUN_FAILED;
        }
    }
    wait_with_progress(&pool, total_ticks, quiet);
    for (int t = 0; t < n_threads; ++t) {
        pthread_join(threads[t], NULL);
    }
    const double wall = now_s() - start;

    int status = 0;
    int scenario_failed[MAX_SCENARIOS] = {0};
    for (int j = 0; j < n_jobs; ++j) {
        if (jobs[j].failed) {
            fprintf(stderr, "ladrc_sil: %s\n", jobs[j].error);
            scenario_failed[jobs[j].sc - scenarios] = 1;
            status = EXIT_RUN_FAILED;
        }
    }
    double simulated = 0.0;
    int any_diverged = 0;
    for (int s = 0; s < n_sc; ++s) {
        const sim_scenario_t *sc = &scenarios[s];
        if (scenario_failed[s]) {
            continue; /* no tables from a run that did not happen */
        }
        const sim_scenario_result_t res = {sc, sc->kind == SIM_KIND_DIFFERENTIATOR ? NULL : attitude[s],
                                           sc->kind == SIM_KIND_DIFFERENTIATOR ? &diff[s] : NULL};
        sim_report_tables(stdout, &res);
        char path[SIM_PATH_LEN + 32];
        snprintf(path, sizeof path, "%s/metrics.csv", sc->output_dir);
        FILE *f = fopen(path, "w");
        if (f == NULL || sim_report_metrics_csv(f, &res, 1) != 0 || fclose(f) != 0) {
            fprintf(stderr, "ladrc_sil: %s: cannot write\n", path);
            status = EXIT_RUN_FAILED;
        }
        snprintf(path, sizeof path, "%s/signals.csv", sc->output_dir);
        f = fopen(path, "w");
        if (f == NULL || write_signals_csv(f, sc) != 0 || fclose(f) != 0) {
            fprintf(stderr, "ladrc_sil: %s: cannot write\n", path);
            status = EXIT_RUN_FAILED;
        }
        for (int c = 0; sc->kind == SIM_KIND_ATTITUDE && c < sc->n_controllers; ++c) {
            if (attitude[s][c].diverged) {
                char why[160];
                sim_report_divergence_text(why, sizeof why, sc, &attitude[s][c]);
                fprintf(stderr, "ladrc_sil: %s (%s): controller %s %s\n", sc->name, sc->path,
                        sim_controller_name(sc->controllers[c]), why);
                any_diverged = 1;
            }
        }
        simulated += sc->duration_s * (sc->kind == SIM_KIND_DIFFERENTIATOR ? 1 : sc->n_controllers);
    }
    if (status == 0 && any_diverged) {
        status = EXIT_DIVERGED;
    }
    if (!quiet) {
        fprintf(stderr, "ladrc_sil: %d runs, %.1f s simulated in %.2f s with %d jobs (%.0fx real time)\n", n_jobs,
                simulated, wall, n_threads, simulated / wall);
    }
    return status;
}
