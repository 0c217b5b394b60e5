/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_sil's campaign mode (campaign_main.h): every run of the shard is
 * expanded and parsed first (one bad run: exit 2, nothing written), then
 * OUT/plan.csv is checked and written, and the runs fly in batches of
 * SIM_FLY_MAX_SCENARIOS through the scenario mode's job pool.
 */
#define _POSIX_C_SOURCE 200809L
#include "campaign_main.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign/campaign.h"
#include "fly.h"
#include "staged_dir.h"
#include "run/progress.h"
#include "scenario/scenario.h"

enum { EXIT_RUN_FAILED = 1, EXIT_BAD_INPUT = 2 };

static void usage(FILE *out)
{
    fputs(
        "usage: ladrc_sil --campaign FILE [--list | --print-out] [--shard K/N] [--jobs N] [--out DIR] [--csv] "
        "[--quiet]\n"
        "  --campaign FILE   a campaign file (format: docs/campaign-format.md): a base scenario's\n"
        "                    runs with keys varied on a grid and drawn at random\n"
        "  --list            print the plan (CSV: run, then each varied value) and write nothing\n"
        "  --print-out       print the output directory OUT and write nothing\n"
        "  --shard K/N       only the runs r with (r - 1) %% N = K - 1\n"
        "  --jobs N          worker threads (default: the number of cores)\n"
        "  --out DIR         write under DIR/<campaign name> (default: the campaign's output_dir)\n"
        "  --csv             also the time series of every run (default: none)\n"
        "  --quiet           no progress on stderr\n"
        "Writes OUT/plan.csv and OUT/runs/<run>/metrics.csv, signals.csv. --set, --seed and\n"
        "--controllers are refused with --campaign: put them in the campaign's [set].\n"
        "Exit status: 0 every run of the shard flew and wrote its files (diverged runs and\n"
        "untunable controllers are results, counted on stderr); 1 a run failed or a file could not be written; 2 bad\n"
        "input (then nothing is run or written).\n",
        out);
}

/* "name=value, ..." of a run, for messages. */
static void values_text(char *buf, size_t n, const sim_campaign_t *c, const sim_campaign_run_t *run)
{
    size_t o = 0;
    buf[0] = '\0';
    for (int k = 0; k < c->n_keys && o < n; ++k) {
        const int w = snprintf(buf + o, n - o, "%s%s=%s", k > 0 ? ", " : "", c->keys[k].name, run->text[k]);
        o += w > 0 ? (size_t)w : 0u;
    }
    if (c->n_keys == 0) {
        snprintf(buf, n, "no varied values");
    }
}

/* A run the simulator refuses: the campaign file (and the line of the
 * setting at fault), the run and its values, then the scenario's error. */
static void print_run_error(const sim_campaign_t *c, const sim_campaign_run_t *run, const sim_parse_error_t *e)
{
    char values[1024];
    values_text(values, sizeof values, c, run);
    const int k = e->first_set_line > 0 && e->line >= e->first_set_line ? e->line - e->first_set_line : -1;
    if (k >= 0 && k < run->n_settings) {
        char where[32] = "";
        if (run->setting_line[k] > 0) {
            snprintf(where, sizeof where, ":%d", run->setting_line[k]);
        }
        fprintf(stderr, "%s%s: run %ld (%s): '%s':%d: %s (with %s)\n", c->path, where, run->run, values,
                run->settings[k], e->column, e->message, e->path);
    } else if (e->line > 0) {
        fprintf(stderr, "%s: run %ld (%s): %s:%d:%d: %s\n", c->path, run->run, values, e->path, e->line, e->column,
                e->message);
    } else {
        fprintf(stderr, "%s: run %ld (%s): %s: %s\n", c->path, run->run, values,
                e->path[0] != '\0' ? e->path : c->base_path, e->message);
    }
}

/* The plan of every run, in memory (what OUT/plan.csv holds). */
static char *plan_text(const sim_campaign_t *c, size_t *len)
{
    char *text = NULL;
    FILE *f = open_memstream(&text, len);
    if (f == NULL) {
        return NULL;
    }
    const int bad = sim_campaign_write_plan(f, c, 1, 1);
    if (fclose(f) != 0 || bad) {
        free(text);
        return NULL;
    }
    return text;
}

/* 1: path holds exactly text; 0: it does not exist; -1: it holds something
 * else; -3: it cannot be read (errno set). */
static int same_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return errno == ENOENT ? 0 : -3;
    }
    int same = 1;
    size_t at = 0;
    char buf[8192];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) {
        if (at + n > len || memcmp(buf, text + at, n) != 0) {
            same = 0;
            break;
        }
        at += n;
    }
    same = same && !ferror(f) && at == len;
    fclose(f);
    return same ? 1 : -1;
}

/* OUT/plan.csv through a temporary file and a rename. */
static int write_plan_atomically(const char *out_dir, const char *text, size_t len)
{
    char tmp[SIM_PATH_LEN + 64], path[SIM_PATH_LEN + 32];
    snprintf(path, sizeof path, "%s/plan.csv", out_dir);
    snprintf(tmp, sizeof tmp, "%s/.plan.csv.%ld.tmp", out_dir, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    if (f == NULL) {
        return -1;
    }
    const int bad = fwrite(text, 1, len, f) != len;
    if (fclose(f) != 0 || bad || rename(tmp, path) != 0) {
        remove(tmp);
        return -1;
    }
    return 0;
}

/* The progress of the whole shard over its batches. */
typedef struct {
    const char *name;
    double start, last_print;
    double total_ticks, ticks_before;
    long runs_before, runs_total;
    int tty, quiet, printed;
} progress_t;

static void on_progress(void *ctx, double ticks, int scenarios_done)
{
    progress_t *p = (progress_t *)ctx;
    const double t = sim_fly_now_s();
    if (p->quiet || t - p->start < 1.0 || t - p->last_print < (p->tty ? 0.5 : 2.0)) {
        return;
    }
    const double fraction = p->total_ticks > 0.0 ? (p->ticks_before + ticks) / p->total_ticks : 0.0;
    char so_far[32], left[48] = "";
    sim_progress_duration(so_far, sizeof so_far, t - p->start);
    const double eta = sim_progress_eta_s(fraction, t - p->start);
    if (eta >= 0.0) {
        char text[32];
        sim_progress_duration(text, sizeof text, eta);
        snprintf(left, sizeof left, ", about %s left", text);
    }
    fprintf(stderr, "%sladrc_sil: campaign %s: %ld of %ld runs done (%.0f%%), %s%s%s", p->tty ? "\r" : "", p->name,
            p->runs_before + scenarios_done, p->runs_total, 100.0 * fraction, so_far, left, p->tty ? "\033[K" : "\n");
    p->last_print = t;
    p->printed = 1;
}

int sim_campaign_main(int argc, char **argv)
{
    const char *path = NULL, *out_root = NULL;
    long jobs = sysconf(_SC_NPROCESSORS_ONLN);
    long shard_k = 1, shard_n = 1;
    int list = 0, print_out = 0, want_csv = 0, quiet = 0;
    char msg[256];
    for (int a = 1; a < argc; ++a) {
        if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
            usage(stdout);
            return 0;
        }
    }
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a];
        if (strcmp(arg, "--campaign") == 0 && a + 1 < argc) {
            if (path != NULL) {
                fprintf(stderr, "ladrc_sil: --campaign given twice (one campaign per call)\n");
                return EXIT_BAD_INPUT;
            }
            path = argv[++a];
        } else if (strcmp(arg, "--list") == 0) {
            list = 1;
        } else if (strcmp(arg, "--print-out") == 0) {
            print_out = 1;
        } else if (strcmp(arg, "--shard") == 0 && a + 1 < argc) {
            if (sim_campaign_parse_shard(argv[++a], &shard_k, &shard_n, msg, sizeof msg) != 0) {
                fprintf(stderr, "ladrc_sil: --shard %s\n", msg);
                return EXIT_BAD_INPUT;
            }
        } else if (strcmp(arg, "--jobs") == 0 && a + 1 < argc) {
            char *end = NULL;
            jobs = strtol(argv[++a], &end, 10);
            if (*end != '\0' || jobs < 1 || jobs > 256) {
                fprintf(stderr, "ladrc_sil: --jobs: expected a whole number from 1 to 256, got '%s'\n", argv[a]);
                return EXIT_BAD_INPUT;
            }
        } else if (strcmp(arg, "--out") == 0 && a + 1 < argc) {
            out_root = argv[++a];
        } else if (strcmp(arg, "--csv") == 0) {
            want_csv = 1;
        } else if (strcmp(arg, "--no-csv") == 0) {
            want_csv = 0;
        } else if (strcmp(arg, "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(arg, "--set") == 0 || strcmp(arg, "--seed") == 0 || strcmp(arg, "--controllers") == 0) {
            fprintf(stderr,
                    "ladrc_sil: %s cannot be combined with --campaign: put the setting in the campaign's [set] "
                    "section (run.seed, run.controllers, ...)\n",
                    arg);
            return EXIT_BAD_INPUT;
        } else if (arg[0] == '-') {
            fprintf(stderr, "ladrc_sil: unknown or incomplete option '%s'\n", arg);
            usage(stderr);
            return EXIT_BAD_INPUT;
        } else {
            fprintf(stderr,
                    "ladrc_sil: '%s': a scenario file cannot be combined with --campaign (the campaign "
                    "names its base)\n",
                    arg);
            return EXIT_BAD_INPUT;
        }
    }
    if (path == NULL) {
        usage(stderr);
        return EXIT_BAD_INPUT;
    }

    static sim_campaign_t c;
    sim_campaign_error_t cerr;
    if (sim_campaign_load(&c, path, &cerr) != 0) {
        if (cerr.line > 0) {
            fprintf(stderr, "%s:%d:%d: %s\n", cerr.path, cerr.line, cerr.column, cerr.message);
        } else {
            fprintf(stderr, "%s: %s\n", cerr.path, cerr.message);
        }
        return EXIT_BAD_INPUT;
    }
    char out_dir[SIM_PATH_LEN];
    if (snprintf(out_dir, sizeof out_dir, "%s%s%s", out_root != NULL ? out_root : "", out_root != NULL ? "/" : "",
                 out_root != NULL ? c.name : c.output_dir) >= (int)sizeof out_dir - 32) {
        fprintf(stderr, "ladrc_sil: %s: output directory path too long\n", path);
        sim_campaign_free(&c);
        return EXIT_BAD_INPUT;
    }
    if (print_out) {
        const int bad = puts(out_dir) < 0 || fflush(stdout) != 0;
        sim_campaign_free(&c);
        return bad ? EXIT_RUN_FAILED : 0;
    }

    /* Every run of the shard, expanded and parsed before anything is written. */
    static sim_campaign_run_t run;
    static sim_scenario_t scratch;
    sim_parse_error_t perr;
    double total_ticks = 0.0;
    long runs_total = 0;
    for (long r = shard_k; r <= c.n_runs; r += shard_n) {
        if (sim_campaign_expand(&c, r, &run, msg, sizeof msg) != 0) {
            fprintf(stderr, "%s: %s\n", path, msg);
            sim_campaign_free(&c);
            return EXIT_BAD_INPUT;
        }
        if (sim_campaign_load_run(&c, &run, out_dir, &scratch, &perr) != 0) {
            print_run_error(&c, &run, &perr);
            sim_campaign_free(&c);
            return EXIT_BAD_INPUT;
        }
        if (sim_fly_check_inputs(&scratch, path) != 0) { /* the base, its series or the campaign */
            sim_campaign_free(&c);
            return EXIT_BAD_INPUT;
        }
        total_ticks += sim_fly_total_ticks(&scratch, 1);
        ++runs_total;
    }
    if (list) {
        const int bad = sim_campaign_write_plan(stdout, &c, shard_k, shard_n) != 0 || fflush(stdout) != 0;
        sim_campaign_free(&c);
        return bad ? EXIT_RUN_FAILED : 0;
    }

    /* OUT/plan.csv: the same plan, or another campaign's runs. */
    size_t plan_len = 0;
    char *plan = plan_text(&c, &plan_len);
    char plan_path[SIM_PATH_LEN + 32];
    snprintf(plan_path, sizeof plan_path, "%s/plan.csv", out_dir);
    const char *plan_name = "plan.csv", *const inputs[] = {path, c.base_path};
    char why[2 * SIM_PATH_LEN + 128];
    if (sim_staged_check_inputs(out_dir, &plan_name, 1, inputs, 2, why, sizeof why) != 0) {
        fprintf(stderr, "ladrc_sil: %s: choose another --out\n", why);
        free(plan);
        sim_campaign_free(&c);
        return EXIT_BAD_INPUT;
    }
    const int same = plan != NULL ? same_file(plan_path, plan, plan_len) : -2;
    if (same == -2) {
        fprintf(stderr, "ladrc_sil: %s: cannot make the plan (out of memory)\n", path);
        sim_campaign_free(&c);
        return EXIT_RUN_FAILED;
    }
    if (same == -3) {
        fprintf(stderr, "ladrc_sil: %s: cannot read: %s\n", plan_path, strerror(errno));
        free(plan);
        sim_campaign_free(&c);
        return EXIT_RUN_FAILED;
    }
    if (same < 0) {
        fprintf(stderr,
                "ladrc_sil: %s holds another campaign's runs (its plan.csv is not the plan of %s): choose another "
                "--out or remove it\n",
                out_dir, path);
        free(plan);
        sim_campaign_free(&c);
        return EXIT_BAD_INPUT;
    }
    char runs_dir[SIM_PATH_LEN + 8];
    snprintf(runs_dir, sizeof runs_dir, "%s/runs", out_dir);
    if (sim_fly_make_dirs(runs_dir) != 0 || write_plan_atomically(out_dir, plan, plan_len) != 0) {
        fprintf(stderr, "ladrc_sil: %s: cannot write: %s\n", plan_path, strerror(errno));
        free(plan);
        sim_campaign_free(&c);
        return EXIT_RUN_FAILED;
    }
    free(plan);

    /* The runs, in batches. */
    static sim_scenario_t batch[SIM_FLY_MAX_SCENARIOS];
    static long batch_run[SIM_FLY_MAX_SCENARIOS];
    progress_t progress = {.name = c.name,
                           .start = sim_fly_now_s(),
                           .last_print = 0.0,
                           .total_ticks = total_ticks,
                           .ticks_before = 0.0,
                           .runs_before = 0,
                           .runs_total = runs_total,
                           .tty = isatty(fileno(stderr)),
                           .quiet = quiet,
                           .printed = 0};
    const sim_fly_options_t opt = {.jobs = (int)jobs,
                                   .want_csv = want_csv,
                                   .quiet = quiet,
                                   .print_tables = 0,
                                   .report_divergence = 0,
                                   .progress = on_progress,
                                   .progress_ctx = &progress};
    int status = 0;
    long flights = 0, failed_flights = 0, diverged_flights = 0, diverged_runs = 0, untunable_flights = 0;
    double simulated = 0.0;
    int threads = 0;
    long r = shard_k;
    while (r <= c.n_runs && status == 0) {
        int n = 0;
        for (; r <= c.n_runs && n < SIM_FLY_MAX_SCENARIOS; r += shard_n) {
            if (sim_campaign_expand(&c, r, &run, msg, sizeof msg) != 0 ||
                sim_campaign_load_run(&c, &run, out_dir, &batch[n], &perr) != 0) {
                print_run_error(&c, &run, &perr); /* not reached: every run was parsed above */
                status = EXIT_RUN_FAILED;
                break;
            }
            batch_run[n++] = r;
        }
        if (status != 0) {
            break;
        }
        int failed = 0;
        const sim_fly_tune_options_t tune_opt = {.jobs = (int)jobs, .quiet = 1};
        const int untunable = sim_fly_tune(batch, n, &tune_opt, &perr, &failed);
        if (untunable < 0) {
            sim_campaign_expand(&c, batch_run[failed], &run, msg, sizeof msg);
            print_run_error(&c, &run, &perr);
            status = EXIT_RUN_FAILED;
            break;
        }
        sim_fly_result_t res;
        if (sim_fly_batch(batch, n, &opt, &res) != 0) {
            status = EXIT_RUN_FAILED;
        }
        flights += res.runs;
        failed_flights += res.runs_failed;
        diverged_flights += res.runs_diverged;
        untunable_flights += untunable;
        diverged_runs += res.scenarios_diverged;
        simulated += res.simulated_s;
        threads = res.threads > threads ? res.threads : threads;
        progress.ticks_before += sim_fly_total_ticks(batch, n);
        progress.runs_before += n;
    }
    if (progress.printed && progress.tty) {
        fputc('\n', stderr);
    }
    const double wall = sim_fly_now_s() - progress.start;
    if (!quiet) {
        fprintf(stderr,
                "ladrc_sil: campaign %s, shard %ld/%ld: %ld of %ld runs flown (%ld flights), %.1f s simulated in "
                "%.2f s with %d jobs (%.0fx real time)\n",
                c.name, shard_k, shard_n, progress.runs_before, runs_total, flights, simulated, wall, threads,
                wall > 0.0 ? simulated / wall : 0.0);
    }
    if (diverged_flights > 0 || !quiet) {
        fprintf(stderr, "ladrc_sil: campaign %s: %ld runs with a diverged controller (%ld of %ld flights diverged)\n",
                c.name, diverged_runs, diverged_flights, flights);
    }
    if (untunable_flights > 0) {
        fprintf(stderr,
                "ladrc_sil: campaign %s: %ld controllers untunable (not flown; their statistics read untunable)\n",
                c.name, untunable_flights);
    }
    if (failed_flights > 0) {
        fprintf(stderr, "ladrc_sil: campaign %s: %ld flights failed to run\n", c.name, failed_flights);
    }
    sim_campaign_free(&c);
    return status;
}
