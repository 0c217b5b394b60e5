/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_sil: runs scenario files against the ladrc library on a simulated
 * quadrotor and prints the paper's comparison tables. Independent runs are
 * spread over worker threads, a scenario's runs in lockstep groups that share
 * the disturbances (runner.h); results depend on neither.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "campaign_main.h"
#include "fly.h"
#include "run/tune.h"
#include "scenario/scenario.h"

#define MAX_SCENARIOS SIM_FLY_MAX_SCENARIOS

/* Exit statuses (usage(), docs/simulator.md). */
enum { EXIT_RUN_FAILED = 1, EXIT_BAD_INPUT = 2, EXIT_DIVERGED = 3, EXIT_UNTUNABLE = 4 };

/* The command line's settings: --set items and --seed, in their order. */
#define MAX_SETTINGS 64
typedef struct {
    const char *text[MAX_SETTINGS];
    const char *shown[MAX_SETTINGS]; /* the argument as given */
    int shift[MAX_SETTINGS];         /* columns of text before the argument ("run.seed=") */
    char label[MAX_SETTINGS][24];    /* "--set 2", "--seed" */
    char seed_text[40];              /* "run.seed=N" of --seed */
    int n;
} settings_t;

/* Prints an error of a scenario or of a setting, as file:line:column or
 * "--set K (TEXT):column". */
/* e on stderr, its message after prefix ("" or "warning: "). */
static void print_error_as(const sim_parse_error_t *e, const settings_t *set, const char *fallback_path,
                           const char *prefix)
{
    const int k = e->first_set_line > 0 && e->line >= e->first_set_line ? e->line - e->first_set_line : -1;
    if (k >= 0 && k < set->n) {
        const int col = e->column - set->shift[k];
        fprintf(stderr, "ladrc_sil: %s '%s':%d: %s%s (with %s)\n", set->label[k], set->shown[k], col > 0 ? col : 1,
                prefix, e->message, e->path);
    } else if (e->line > 0) {
        fprintf(stderr, "%s:%d:%d: %s%s\n", e->path, e->line, e->column, prefix, e->message);
    } else {
        fprintf(stderr, "%s: %s%s\n", e->path[0] != '\0' ? e->path : fallback_path, prefix, e->message);
    }
}

static void print_error(const sim_parse_error_t *e, const settings_t *set, const char *fallback_path)
{
    print_error_as(e, set, fallback_path, "");
}

/* A tuning that missed (a warning) or a controller untunable, at its key. */
typedef struct {
    const settings_t *set;
    const sim_scenario_t *scenarios;
} tune_note_ctx_t;

static void tune_note(void *ctx, int scenario_index, int rc, const sim_parse_error_t *err)
{
    const tune_note_ctx_t *n = (const tune_note_ctx_t *)ctx;
    print_error_as(err, n->set, n->scenarios[scenario_index].path, rc == SIM_TUNE_UNTUNABLE ? "" : "warning: ");
}

static void usage(FILE *out)
{
    fputs("usage: ladrc_sil SCENARIO... [--jobs N] [--controllers LIST] [--set SECTION.KEY=VALUE]... [--seed N]\n"
          "                 [--out DIR] [--no-csv] [--strict] [--quiet] [--betaflight DIR]\n"
          "       ladrc_sil --campaign FILE [--list] [--shard K/N] [--jobs N] [--out DIR] [--csv] [--quiet]\n"
          "                 (its options: ladrc_sil --campaign --help; docs/campaign-format.md)\n"
          "  SCENARIO          a scenario file (format: docs/scenario-format.md)\n"
          "  --jobs N          worker threads (default: the number of cores)\n"
          "  --controllers L   subset of HP-MLADRC LP-MLADRC LADRC PID CASCADED INDI RATE-ADRC BETAFLIGHT, names\n"
          "                    separated by commas, spaces or both (default: each scenario's own list)\n"
          "  --set S.K=V       KEY = VALUE in [SECTION] of every scenario, replacing the file's value\n"
          "                    (a controller's section: controller:NAME.KEY=V); repeatable\n"
          "  --seed N          [run] seed = N in every scenario\n"
          "  --out DIR         write every scenario's output under DIR/<scenario name>\n"
          "                    (default: each scenario's output_dir)\n"
          "  --no-csv          no time series, only metrics.csv and the tables\n"
          "  --strict          a tune = margins that misses its targets, or whose gains do not fly the\n"
          "                    check flight, refuses the scenario (exit 2) instead of flying the best\n"
          "                    candidate (docs/margins.md)\n"
          "  --quiet           no progress on stderr\n"
          "  --betaflight DIR  the Betaflight SITL that BETAFLIGHT flies (tools/betaflight_sitl.sh builds\n"
          "                    DIR; default: $LADRC_BETAFLIGHT_SITL; docs/betaflight.md)\n"
          "Prints the comparison tables on stdout; writes <out>/<controller>.csv time series and\n"
          "<out>/metrics.csv. A run diverges when |tracking error| on an axis exceeds the scenario's\n"
          "diverge_limit_deg (default 90) or its state turns non-finite: it stops there, its statistics\n"
          "print as \"diverged\", and stderr names it.\n"
          "A controller that tune = margins leaves untunable (no candidate gains fly the check flight)\n"
          "is not flown: stderr names it with the reason at its tune key, its statistics print as\n"
          "\"untunable\"; every other controller flies.\n"
          "Exit status: 0 every run flew; 1 a run failed or an output could not be written;\n"
          "2 bad usage or a bad scenario, with --strict a tuning that missed included (then nothing is\n"
          "run or written); 3 every run and output completed but a run diverged; 4 every run and\n"
          "output completed, none diverged, but a controller was untunable (1 wins over 3, 3 over 4).\n",
          out);
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

int main(int argc, char **argv)
{
    static sim_scenario_t scenarios[MAX_SCENARIOS];
    int n_sc = 0;
    long jobs_wanted = sysconf(_SC_NPROCESSORS_ONLN);
    const char *out_root = NULL;
    const char *betaflight = getenv("LADRC_BETAFLIGHT_SITL");
    int want_csv = 1, quiet = 0, strict = 0, n_override = 0;
    sim_controller_id_t override_ids[SIM_MAX_CONTROLLERS];
    const char *paths[MAX_SCENARIOS];
    int n_paths = 0;
    static settings_t set;

    for (int a = 1; a < argc; ++a) {
        if (strcmp(argv[a], "--campaign") == 0) {
            return sim_campaign_main(argc, argv);
        }
    }
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
        } else if (strcmp(arg, "--betaflight") == 0 && a + 1 < argc) {
            betaflight = argv[++a];
        } else if (strcmp(arg, "--no-csv") == 0) {
            want_csv = 0;
        } else if (strcmp(arg, "--csv") == 0) {
            want_csv = 1;
        } else if (strcmp(arg, "--list") == 0 || strcmp(arg, "--shard") == 0) {
            fprintf(stderr, "ladrc_sil: %s needs --campaign FILE\n", arg);
            return EXIT_BAD_INPUT;
        } else if (strcmp(arg, "--quiet") == 0) {
            quiet = 1;
        } else if (strcmp(arg, "--strict") == 0) {
            strict = 1;
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
        if (sim_fly_set_betaflight(sc, betaflight) != 0) {
            return EXIT_BAD_INPUT;
        }
    }

    if (sim_fly_check_collisions(scenarios, n_sc) != 0) {
        return EXIT_BAD_INPUT;
    }

    /* tune = margins, before anything is written: a controller left
     * untunable is named at its key and not flown; with --strict a tuning
     * that misses is an error of the file. */
    sim_parse_error_t tune_err;
    int tune_failed = 0;
    tune_note_ctx_t note = {.set = &set, .scenarios = scenarios};
    const sim_fly_tune_options_t tune_opt = {
        .jobs = (int)jobs_wanted, .quiet = quiet, .strict = strict, .note = tune_note, .note_ctx = &note};
    const int untunable = sim_fly_tune(scenarios, n_sc, &tune_opt, &tune_err, &tune_failed);
    if (untunable < 0) {
        print_error(&tune_err, &set, scenarios[tune_failed].path);
        return EXIT_BAD_INPUT;
    }

    const sim_fly_options_t opt = {.jobs = (int)jobs_wanted,
                                   .want_csv = want_csv,
                                   .quiet = quiet,
                                   .print_tables = 1,
                                   .report_divergence = 1,
                                   .progress = NULL,
                                   .progress_ctx = NULL};
    sim_fly_result_t res;
    int status = sim_fly_batch(scenarios, n_sc, &opt, &res) != 0 ? EXIT_RUN_FAILED : 0;
    if (status == 0 && res.runs_diverged > 0) {
        status = EXIT_DIVERGED;
    }
    if (status == 0 && untunable > 0) {
        status = EXIT_UNTUNABLE;
    }
    if (!quiet && res.runs > 0) {
        fprintf(stderr, "ladrc_sil: %d runs, %.1f s simulated in %.2f s with %d jobs (%.0fx real time)\n", res.runs,
                res.simulated_s, res.wall_s, res.threads, res.simulated_s / res.wall_s);
    }
    return status;
}
