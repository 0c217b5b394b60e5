/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_replay: a flight log in (Betaflight blackbox_decode CSV, PX4
 * ulog2csv topics, or a generic CSV), the airframe identified from it and
 * written as a scenario, the controllers tuned for it (or as a given
 * scenario configures them), then replayed open loop on the log's streams
 * (docs/flight-logs.md).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli_number.h"
#include "cli/fly.h"
#include "cli/replay_noise.h"
#include "cli/replay_report.h"
#include "cli/staged_dir.h"
#include "log/log_convert.h"
#include "log/log_identify.h"
#include "log/log_views.h"
#include "log/replay.h"
#include "report/report.h"
#include "run/tune.h"
#include "scenario/scenario.h"

#define NOISE_SERIES_S 60.0 /* the noise file: the log's first minute */
#define SLOW_LOG_HZ 100.0   /* below: slower than any multirotor's attitude loop */

typedef struct {
    sim_log_options_t log;
    int format_given;
    const char *scenario; /* NULL: the identified airframe */
    const char *out_dir;
    long every; /* time-series rows: every this many ticks; 0: none */
    int identify_only, quiet, strict;
    int n_controllers;
    sim_controller_id_t controllers[SIM_MAX_CONTROLLERS];
} options_t;

static void usage(FILE *out)
{
    fputs("usage: ladrc_replay LOG [--format betaflight|px4|ardupilot|generic] [--map FIELD=SOURCE]...\n"
          "                    [--dt S] [--from S] [--to S] [--scenario FILE] [--controllers LIST]\n"
          "                    [--out DIR] [--every N] [--identify-only] [--strict] [--quiet]\n"
          "  LOG               a blackbox_decode CSV, a PX4 ulog2csv topic file (or their common\n"
          "                    prefix), an ArduPilot DataFlash .bin, or a CSV whose columns --map\n"
          "                    names (docs/flight-logs.md)\n"
          "  --format F        the log's form (default: told from the files)\n"
          "  --map F=SOURCE    a column (or sum of columns, times a scale) for a field, over the form's\n"
          "  --dt S            control period to resample to (default: the log's row period)\n"
          "  --from S, --to S  the window of the log, in seconds from its start\n"
          "  --scenario FILE   the controllers as this scenario configures them (default: tuned by\n"
          "                    tune = margins on the airframe identified from the log)\n"
          "  --controllers L   a subset of the scenario's controllers\n"
          "  --out DIR         where the outputs go (default: replay/<log name>)\n"
          "  --every N         write every Nth tick to replay.csv (default 1; 0: no time series)\n"
          "  --identify-only   stop after the identification and the scenario\n"
          "  --strict          exit 1 when the identification warned or a replayed controller\n"
          "                    faulted, else 4 when a controller was not replayed (untunable)\n"
          "  --quiet           no progress on stderr\n"
          "Writes in DIR: identification.csv, airframe.ini, airframe_noise.csv, replay.csv,\n"
          "replay_summary.csv, spectrum.csv, and the log's step and frequency responses and noise\n"
          "against throttle (step_response.csv, freq_response.csv, noise_throttle.csv,\n"
          "response_summary.csv), all at once when the run ends (nothing on a refusal);\n"
          "tools/replay_plot.py DIR draws them. A controller that cannot be tuned for the airframe\n"
          "or does not start at the log's rate is not replayed: its reason is printed and in\n"
          "replay_summary.csv; the others are.\n"
          "Exit status 0 when the replay ran (warnings, untunable controllers and faults are\n"
          "reported, see --strict); 2 for bad usage, a refused log or scenario, an output that\n"
          "would replace the log, or an output that cannot be written.\n",
          out);
}

static int parse_args(int argc, char **argv, options_t *o)
{
    memset(o, 0, sizeof *o);
    sim_log_options_default(&o->log);
    o->every = 1;
    const char *path = NULL;
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a], *val = a + 1 < argc ? argv[a + 1] : NULL;
        double v;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            exit(0);
        } else if (strcmp(arg, "--identify-only") == 0) {
            o->identify_only = 1;
        } else if (strcmp(arg, "--quiet") == 0) {
            o->quiet = 1;
        } else if (strcmp(arg, "--strict") == 0) {
            o->strict = 1;
        } else if (val == NULL && arg[0] == '-') {
            fprintf(stderr, "ladrc_replay: %s needs a value\n", arg);
            return -1;
        } else if (strcmp(arg, "--format") == 0) {
            const int f = sim_log_format_parse(argv[++a]);
            if (f < 0) {
                fprintf(stderr, "ladrc_replay: --format: expected betaflight, px4, ardupilot or generic, got '%s'\n",
                        val);
                return -1;
            }
            o->log.format = (sim_log_format_t)f;
            o->format_given = 1;
        } else if (strcmp(arg, "--map") == 0) {
            if (o->log.n_map >= SIM_LOG_MAX_MAP) {
                fprintf(stderr, "ladrc_replay: --map: at most %d items\n", SIM_LOG_MAX_MAP);
                return -1;
            }
            o->log.map[o->log.n_map++] = argv[++a];
        } else if (strcmp(arg, "--dt") == 0 || strcmp(arg, "--from") == 0 || strcmp(arg, "--to") == 0) {
            if (sim_cli_number("ladrc_replay", arg, argv[++a], &v) != 0) {
                return -1;
            }
            *(arg[2] == 'd' ? &o->log.dt_s : arg[2] == 'f' ? &o->log.t_from_s : &o->log.t_to_s) = v;
        } else if (strcmp(arg, "--scenario") == 0) {
            o->scenario = argv[++a];
        } else if (strcmp(arg, "--controllers") == 0) {
            char msg[256];
            size_t at;
            if (sim_controller_list_parse(argv[++a], o->controllers, &o->n_controllers, &at, msg, sizeof msg) != 0) {
                fprintf(stderr, "ladrc_replay: --controllers: %s\n", msg);
                return -1;
            }
        } else if (strcmp(arg, "--out") == 0) {
            o->out_dir = argv[++a];
        } else if (strcmp(arg, "--every") == 0) {
            if (sim_cli_number("ladrc_replay", arg, argv[++a], &v) != 0 || v != floor(v) || v > 1e9) {
                fprintf(stderr, "ladrc_replay: --every: expected a whole number of ticks\n");
                return -1;
            }
            o->every = (long)v;
        } else if (arg[0] == '-' || path != NULL) {
            fprintf(stderr, "ladrc_replay: unknown or extra argument '%s'\n", arg);
            return -1;
        } else {
            path = arg;
        }
    }
    if (path == NULL) {
        usage(stderr);
        return -1;
    }
    if (snprintf(o->log.path, sizeof o->log.path, "%s", path) >= (int)sizeof o->log.path) {
        fprintf(stderr, "ladrc_replay: %s: path too long\n", path);
        return -1;
    }
    return 0;
}

/* The log's name without folders and extension: the default output folder's. */
static void log_stem(const char *path, char *buf, size_t len)
{
    const char *base = strrchr(path, '/');
    snprintf(buf, len, "%s", base != NULL ? base + 1 : path);
    char *dot = strrchr(buf, '.');
    if (dot != NULL && dot != buf) {
        *dot = '\0';
    }
}

typedef struct {
    int quiet, tty;
    double start_s, last_s;
} progress_t;

static void show_progress(void *ctx, int pass, int passes, const char *what, double fraction)
{
    progress_t *p = (progress_t *)ctx;
    const double now = sim_fly_now_s();
    if (p->quiet || now - p->last_s < (p->tty ? 0.25 : 2.0)) {
        return;
    }
    p->last_s = now;
    fprintf(stderr, "%sladrc_replay: %s, pass %d of %d: %3.0f%% (%.1f s)%s", p->tty ? "\r" : "", what, pass, passes,
            100.0 * fraction, now - p->start_s, p->tty ? "\033[K" : "\n");
}

static void end_progress(const progress_t *p)
{
    if (!p->quiet && p->tty) {
        fputs("\r\033[K", stderr);
    }
}

/* The decoded form of a binary log, removed at exit. */
static sim_log_prepared_t prepared;

static void remove_prepared(void)
{
    sim_log_prepared_remove(&prepared);
}

static void show_decoding(void *ctx, long long done, long long total)
{
    show_progress(ctx, 1, 1, "decoding", total > 0 ? (double)done / (double)total : 0.0);
}

/* The owned outputs of a run, in the output folder: written by it, or,
 * left by an earlier run and not written by this one, removed (the figures
 * tools/replay_plot.py drew from them among them). */
static const char *const OUTPUTS[] = {"step_response.csv",    "freq_response.csv",   "noise_throttle.csv",
                                      "response_summary.csv", "identification.csv",  "airframe.ini",
                                      "airframe_noise.csv",   "replay.csv",          "replay_summary.csv",
                                      "spectrum.csv",         "replay_commands.png", "replay_spectrum.png"};
#define N_OUTPUTS ((int)(sizeof OUTPUTS / sizeof OUTPUTS[0]))
#define VIEWS OUTPUTS /* the first four: the log's views (log_views.h) */
#define N_VIEWS 4

static sim_staged_dir_t stage; /* the outputs until the run succeeds; an exit or a signal before removes them */

static void remove_outputs(void)
{
    sim_staged_abort(&stage);
}

/* The staged outputs go by unlink and rmdir alone; the decoded log's folder
 * is listed to be removed (not async-signal-safe, but the process ends). */
static void remove_outputs_on_signal(int sig)
{
    sim_staged_abort(&stage);
    sim_log_prepared_remove(&prepared);
    signal(sig, SIG_DFL);
    raise(sig);
}

static void remove_outputs_on_exit(void)
{
    static const int SIGNALS[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
    atexit(remove_outputs);
    for (size_t k = 0; k < sizeof SIGNALS / sizeof SIGNALS[0]; ++k) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = remove_outputs_on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGNALS[k], &sa, NULL);
    }
}

/* A staged output's path; the names are few and short, so it always fits. */
static const char *out_path(const char *name, char *buf, size_t len)
{
    const char *p = sim_staged_path(&stage, name, buf, len);
    return p != NULL ? p : "";
}

/* A path as the user will find it: in the output folder, not the staging one. */
static const char *shown(const char *path)
{
    static char buf[SIM_STAGED_PATH_LEN + 128];
    const char *staged = sim_staged_shown(&stage, path, buf, sizeof buf);
    if (staged != buf) {
        snprintf(buf, sizeof buf, "%s", staged);
    }
    sim_log_prepared_explain(&prepared, buf, sizeof buf); /* a decoded log's file: the log's name */
    return buf;
}

static int write_scenario(const sim_airframe_t *a, const char *log_path, sim_airframe_refused_t *refused, char *ini,
                          size_t ini_len, char *why, size_t why_len)
{
    char stem[SIM_LOG_PATH_LEN];
    const char *base = strrchr(log_path, '/');
    snprintf(stem, sizeof stem, "%s", base != NULL ? base + 1 : log_path);
    out_path("airframe.ini", ini, ini_len);
    FILE *f = fopen(ini, "w");
    if (f == NULL) {
        snprintf(why, why_len, "%s: cannot write: %s", shown(ini), strerror(errno));
        return -1;
    }
    const int rc = sim_airframe_write(f, a, stem, "airframe_noise.csv", refused, why, why_len);
    if (fclose(f) != 0 && rc == 0) {
        snprintf(why, why_len, "%s: write failed", shown(ini));
        return -1;
    }
    if (rc != 0) {
        unlink(ini);
    }
    return rc;
}

/* A tuning that missed (a warning) or a controller untunable, at its key. */
static void tune_note(void *ctx, int scenario_index, int rc, const sim_parse_error_t *err)
{
    (void)ctx;
    (void)scenario_index;
    fprintf(stderr, "%s:%d:%d: %s%s\n", shown(err->path), err->line, err->column,
            rc == SIM_TUNE_UNTUNABLE ? "" : "warning: ", err->message);
}

static void print_parse_error(const sim_parse_error_t *perr)
{
    if (perr->line > 0) {
        fprintf(stderr, "%s:%d:%d: %s\n", shown(perr->path), perr->line, perr->column, perr->message);
    } else {
        fprintf(stderr, "%s: %s\n", shown(perr->path), perr->message);
    }
}

static int is_refused(const sim_airframe_refused_t *refused, sim_controller_id_t id, int *at)
{
    for (int k = 0; refused != NULL && k < refused->n; ++k) {
        if (refused->ids[k] == id) {
            *at = k;
            return 1;
        }
    }
    return 0;
}

static void skip(sim_replay_skipped_t *skipped, int *n_skipped, sim_controller_id_t id, const char *reason)
{
    skipped[*n_skipped].id = id;
    skipped[*n_skipped].untunable = 1;
    snprintf(skipped[*n_skipped].reason, sizeof skipped[0].reason, "%s", reason);
    ++*n_skipped;
}

/* Loads and tunes the scenario the controllers come from; the controllers
 * the identified airframe's scenario does not list (refused: they do not
 * start at the log's rate) and those left untunable are not replayed: they
 * go, with the reason, to skipped[*n_skipped]. */
static int load_scenario(const options_t *o, const char *path, const sim_airframe_refused_t *refused,
                         const char *no_replay, sim_scenario_t *sc, sim_replay_skipped_t *skipped, int *n_skipped)
{
    sim_parse_error_t perr;
    *n_skipped = 0;
    if (sim_scenario_load(sc, path, &perr) != 0) {
        print_parse_error(&perr);
        return -1;
    }
    if (o->n_controllers > 0) {
        sim_controller_id_t wanted[SIM_MAX_CONTROLLERS];
        int n = 0, at;
        for (int c = 0; c < o->n_controllers; ++c) {
            if (is_refused(refused, o->controllers[c], &at)) {
                skip(skipped, n_skipped, o->controllers[c], refused->reason[at]);
            } else {
                wanted[n++] = o->controllers[c];
            }
        }
        if (n == 0) {
            sc->n_controllers = 0;
        } else if (sim_scenario_set_controllers(sc, wanted, n, &perr) != 0) {
            print_parse_error(&perr);
            return -1;
        }
    } else {
        for (int k = 0; refused != NULL && k < refused->n; ++k) {
            skip(skipped, n_skipped, refused->ids[k], refused->reason[k]);
        }
    }
    if (sc->kind != SIM_KIND_ATTITUDE) {
        fprintf(stderr, "ladrc_replay: %s: not an attitude scenario\n", shown(path));
        return -1;
    }
    if (no_replay != NULL) { /* nothing to replay against: no tuning, every controller named */
        for (int c = 0; c < sc->n_controllers; ++c) {
            skip(skipped, n_skipped, sc->controllers[c], no_replay);
            skipped[*n_skipped - 1].untunable = 0;
        }
        sc->n_controllers = 0;
        return 0;
    }
    int failed = 0;
    const sim_fly_tune_options_t tune_opt = {.jobs = 2, .quiet = o->quiet, .strict = 0, .note = tune_note};
    if (sim_fly_tune(sc, 1, &tune_opt, &perr, &failed) < 0) {
        print_parse_error(&perr);
        return -1;
    }
    /* an untunable controller is not replayed: the others are */
    int n = 0;
    for (int c = 0; c < sc->n_controllers; ++c) {
        const sim_controller_id_t id = sc->controllers[c];
        if (sc->tuning[id].by == SIM_TUNED_UNTUNABLE) {
            skip(skipped, n_skipped, id, sc->tuning[id].reason);
        } else {
            sc->controllers[n++] = id;
        }
    }
    sc->n_controllers = n;
    return 0;
}

/* The replay pass; 0, or -1 after printing why. */
static int replay(const options_t *o, const sim_scenario_t *sc, sim_replay_t *r, progress_t *prog)
{
    char err[512];
    if (sim_replay_init(r, sc, sc->controllers, sc->n_controllers, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_replay: %s\n", shown(err));
        return -1;
    }
    sim_log_options_t lo = o->log;
    lo.dt_s = sc->control_dt_s; /* the controllers' period */
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&lo, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, sizeof err);
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    const unsigned has = sim_log_has(log);
    if (sc->n_controllers > 0 && !(has & (SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_REF_INTEGRATED))) {
        fprintf(stderr, "ladrc_replay: %s: the log has no setpoint (attitude or rate): nothing to replay against\n",
                prepared.original);
        sim_log_close(log);
        return -1;
    }
    FILE *csv = NULL;
    char path[SIM_STAGED_PATH_LEN + 64];
    if (o->every > 0) {
        csv = fopen(out_path("replay.csv", path, sizeof path), "w");
        if (csv == NULL) {
            fprintf(stderr, "ladrc_replay: %s: cannot write: %s\n", shown(path), strerror(errno));
            sim_log_close(log);
            return -1;
        }
        sim_replay_csv_header(csv, r);
    }
    static sim_replay_tick_t tick;
    sim_log_sample_t s;
    int rc;
    long long k = 0;
    while ((rc = sim_log_next(log, &s, &lerr)) == 1) {
        sim_replay_step(r, &s, has, &tick);
        if (csv != NULL && k % o->every == 0) {
            sim_replay_csv_row(csv, r, &s, &tick);
        }
        if (++k % 65536 == 0) {
            long long done, total;
            sim_log_progress(log, &done, &total);
            show_progress(prog, 1, 1, "replay", total > 0 ? (double)done / (double)total : 0.0);
        }
    }
    end_progress(prog);
    if (rc < 0) {
        sim_log_error_format(&lerr, err, sizeof err);
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
    }
    sim_log_close(log);
    if (csv != NULL && (ferror(csv) | fclose(csv)) != 0) {
        fprintf(stderr, "ladrc_replay: %s: write failed\n", shown(path));
        return -1;
    }
    return rc < 0 ? -1 : 0;
}

/* NULL when the log has a setpoint (attitude or rate) the controllers are
 * replayed against, else why not; "" when it cannot be opened (said). */
static const char *why_no_replay(const options_t *o)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&o->log, &lerr);
    if (log == NULL) {
        char err[1024];
        sim_log_error_format(&lerr, err, sizeof err);
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return "";
    }
    const unsigned has = sim_log_has(log);
    sim_log_close(log);
    return (has & (SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_REF_INTEGRATED))
               ? NULL
               : "the log has no setpoint to replay against (Betaflight: setpoint[0..2], which 3.x logs lack; "
                 "PX4: vehicle_rates_setpoint or vehicle_attitude_setpoint); --map ref_rate[i]=COLUMN or "
                 "ref_angle[i]=COLUMN gives one";
}

/* Refuses a run whose outputs would replace its own log or scenario: 0, or -1 after saying so. */
static int check_inputs(const options_t *o, const char *dir)
{
    char err[SIM_STAGED_PATH_LEN + 256];
    const char *inputs[2] = {o->log.path, o->scenario};
    for (int k = 0; k < 2; ++k) {
        if (sim_staged_check_input(dir, OUTPUTS, N_OUTPUTS, inputs[k], err, sizeof err) != 0) {
            fprintf(stderr, "ladrc_replay: %s: give another --out\n", err);
            return -1;
        }
    }
    return 0;
}

/* The exit status of a replay that ran: 0; with --strict 1 when the
 * identification warned or a controller faulted, else 4 when one was not
 * replayed. */
static int exit_status(const options_t *o, int warned, int faulted, int n_skipped)
{
    if (!o->strict) {
        return 0;
    }
    return warned || faulted ? 1 : n_skipped > 0 ? 4 : 0;
}

int main(int argc, char **argv)
{
    static options_t o;
    if (parse_args(argc, argv, &o) != 0) {
        return 2;
    }
    char dir[SIM_LOG_PATH_LEN + 16], stem[SIM_LOG_PATH_LEN], noise[SIM_STAGED_PATH_LEN + 64], err[1024];
    log_stem(o.log.path, stem, sizeof stem);
    snprintf(dir, sizeof dir, "%s%s", o.out_dir != NULL ? o.out_dir : "replay/", o.out_dir != NULL ? "" : stem);
    if (check_inputs(&o, dir) != 0) {
        return 2;
    }
    progress_t prog = {.quiet = o.quiet, .tty = isatty(2), .start_s = sim_fly_now_s(), .last_s = 0.0};
    sim_log_error_t lerr;
    if (sim_log_prepare(&o.log, o.format_given, &prepared, show_decoding, &prog, &lerr) != 0) {
        end_progress(&prog);
        sim_log_error_format(&lerr, err, sizeof err);
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    atexit(remove_prepared);
    end_progress(&prog);
    if (prepared.dir[0] != '\0' && !o.quiet) {
        fprintf(stderr, "ladrc_replay: %s: a %s log of %lld bytes, decoded in %.2f s\n", prepared.original,
                sim_log_source_name(prepared.source), prepared.bytes, prepared.decode_s);
    }
    remove_outputs_on_exit();
    if (sim_staged_open(&stage, dir, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_replay: %s\n", err);
        return 2;
    }
    sim_log_identify_options_t io = {.log = o.log,
                                     .delay_max_ticks = -1,
                                     .noise_series = out_path("airframe_noise.csv", noise, sizeof noise),
                                     .noise_series_s = NOISE_SERIES_S,
                                     .progress = show_progress,
                                     .progress_ctx = &prog};
    static sim_airframe_t airframe;
    sim_log_stats_t stats;
    if (!o.quiet) {
        fprintf(stderr, "ladrc_replay: %s (%s form)\n", prepared.original, sim_log_format_name(o.log.format));
    }
    if (sim_log_identify(&io, &airframe, &stats, err, sizeof err) != 0) {
        end_progress(&prog);
        fprintf(stderr, "%s\n", shown(err));
        return 2;
    }
    end_progress(&prog);
    printf("%s: %lld rows in %d file(s), %lld ticks at %.4g s, identified in %.2f s (4 passes)", prepared.original,
           stats.rows, stats.n_files, stats.ticks, airframe.dt_s, sim_fly_now_s() - prog.start_s);
    if (stats.gaps > 0) {
        printf(", %lld gap(s) interpolated over (longest %.3g s)", stats.gaps, stats.longest_gap_s);
    }
    printf("\n");
    if (1.0 / airframe.dt_s < SLOW_LOG_HZ) {
        printf("note: the log's rate, %.4g Hz, is below %.0f Hz: the controllers run at it, as in a loop that slow "
               "(those that refuse it are not replayed); --dt resamples the log to another\n",
               1.0 / airframe.dt_s, SLOW_LOG_HZ);
    }
    sim_report_identification(stdout, &airframe);
    int warned = 0;
    for (int i = 0; i < 3; ++i) {
        char note[256];
        warned |= airframe.axis[i].warnings != 0 || sim_log_outliers_many(&airframe.outliers, i);
        if (sim_airframe_b0_note(&airframe, i, note, sizeof note)) {
            printf("warning: %s\n", note);
        }
    }
    char path[SIM_STAGED_PATH_LEN + 64], ini[SIM_STAGED_PATH_LEN + 64];
    if (sim_write_identification_csv(out_path("identification.csv", path, sizeof path), &airframe) != 0) {
        fprintf(stderr, "ladrc_replay: %s: write failed\n", shown(path));
        return 2;
    }
    if (sim_replay_noise_stage(&o.log, &airframe, stdout, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", shown(err));
        return 2;
    }
    static sim_airframe_refused_t refused;
    const int have_airframe =
        write_scenario(&airframe, prepared.original, &refused, ini, sizeof ini, err, sizeof err) == 0;
    if (have_airframe) {
        printf("scenario of the airframe: %s (ladrc_sil flies it, ladrc_margins tunes it)\n", shown(ini));
    } else if (o.scenario == NULL) {
        fprintf(stderr, "ladrc_replay: %s: no airframe to tune the controllers for: %s\n", prepared.original, err);
        return 2;
    } else {
        printf("no scenario of the airframe: %s\n", err);
    }
    static sim_scenario_t sc;
    static sim_replay_skipped_t skipped[SIM_CTRL_COUNT];
    int n_skipped = 0;
    if (!o.identify_only) {
        const char *no_replay = why_no_replay(&o);
        if ((no_replay != NULL && no_replay[0] == '\0') ||
            load_scenario(&o, o.scenario != NULL ? o.scenario : ini, o.scenario != NULL ? NULL : &refused, no_replay,
                          &sc, skipped, &n_skipped) != 0) {
            return 2;
        }
        sim_report_tuning(stdout, &sc);
        sim_report_skipped(stdout, skipped, n_skipped);
        static sim_replay_t r;
        prog.start_s = sim_fly_now_s();
        if (replay(&o, &sc, &r, &prog) != 0) {
            return 2;
        }
        const double replay_s = sim_fly_now_s() - prog.start_s;
        printf("replayed %lld ticks (%.4g s of flight) with %d controllers in %.2f s: %.0fx real time\n", r.ticks,
               (double)r.ticks * sc.control_dt_s, r.n, replay_s, (double)r.ticks * sc.control_dt_s / replay_s);
        sim_report_replay(stdout, &r);
        sim_replay_noise_report(stdout, &sc, &r);
        char spectrum[SIM_STAGED_PATH_LEN + 64];
        for (int k = 0; k < N_VIEWS; ++k) { /* registered: an exit before the commit removes them */
            out_path(VIEWS[k], spectrum, sizeof spectrum);
        }
        if (sim_write_replay_files(out_path("replay_summary.csv", path, sizeof path),
                                   out_path("spectrum.csv", spectrum, sizeof spectrum), &r, skipped, n_skipped, err,
                                   sizeof err) != 0 ||
            sim_log_views_of_log(&o.log, stage.stage, stdout, err, sizeof err) != 0) {
            fprintf(stderr, "ladrc_replay: %s\n", shown(err));
            return 2;
        }
        for (int c = 0; c < r.n; ++c) {
            if (r.fault_ticks[c] > 0) {
                warned |= 2;
            }
        }
    }
    if (sim_staged_commit(&stage, OUTPUTS, N_OUTPUTS, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_replay: %s\n", err);
        return 2;
    }
    printf("outputs in %s (tools/replay_plot.py %s draws them)\n", dir, dir);
    return exit_status(&o, warned & 1, warned & 2, n_skipped);
}
