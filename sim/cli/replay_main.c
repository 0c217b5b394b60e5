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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/fly.h"
#include "cli/replay_noise.h"
#include "cli/replay_report.h"
#include "log/log_convert.h"
#include "log/log_identify.h"
#include "log/log_views.h"
#include "log/replay.h"
#include "report/report.h"
#include "run/tune.h"
#include "scenario/scenario.h"

#define NOISE_SERIES_S 60.0 /* the noise file: the log's first minute */

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
          "  --strict          refuse the scenario when a tuning misses its targets or a controller\n"
          "                    is untunable (default: the untunable are not replayed, the rest are)\n"
          "  --quiet           no progress on stderr\n"
          "Writes in DIR: identification.csv, airframe.ini, airframe_noise.csv, replay.csv,\n"
          "replay_summary.csv, spectrum.csv, and the log's step and frequency responses and noise\n"
          "against throttle (step_response.csv, freq_response.csv, noise_throttle.csv,\n"
          "response_summary.csv); tools/replay_plot.py DIR draws them.\n"
          "Exit status 0; 1 when a replayed controller faulted or the identification warned;\n"
          "2 for bad usage, a refused log or scenario; 4 when, else clean, a controller was\n"
          "untunable (not replayed; replay_summary.csv lists it as untunable).\n",
          out);
}

static int parse_number(const char *flag, const char *text, double *v)
{
    char *end = NULL;
    errno = 0;
    *v = strtod(text, &end);
    if (end == text || *end != '\0' || errno != 0 || !isfinite(*v) || *v < 0.0) {
        fprintf(stderr, "ladrc_replay: %s: expected a number >= 0, got '%s'\n", flag, text);
        return -1;
    }
    return 0;
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
            if (parse_number(arg, argv[++a], &v) != 0) {
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
            if (parse_number(arg, argv[++a], &v) != 0 || v != floor(v) || v > 1e9) {
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

static int write_scenario(const char *dir, const sim_airframe_t *a, const char *log_path, char *ini, size_t ini_len)
{
    char stem[SIM_LOG_PATH_LEN], why[256];
    const char *base = strrchr(log_path, '/');
    snprintf(stem, sizeof stem, "%s", base != NULL ? base + 1 : log_path);
    snprintf(ini, ini_len, "%s/airframe.ini", dir);
    FILE *f = fopen(ini, "w");
    if (f == NULL) {
        fprintf(stderr, "ladrc_replay: %s: cannot write: %s\n", ini, strerror(errno));
        return -1;
    }
    const int rc = sim_airframe_write(f, a, stem, "airframe_noise.csv", why, sizeof why);
    if ((fclose(f) != 0 || rc != 0)) {
        fprintf(stderr, "ladrc_replay: %s: %s\n", ini, rc != 0 ? why : "write failed");
        return -1;
    }
    return 0;
}

/* A tuning that missed (a warning) or a controller untunable, at its key. */
static void tune_note(void *ctx, int scenario_index, int rc, const sim_parse_error_t *err)
{
    (void)ctx;
    (void)scenario_index;
    fprintf(stderr, "%s:%d:%d: %s%s\n", err->path, err->line, err->column,
            rc == SIM_TUNE_UNTUNABLE ? "" : "warning: ", err->message);
}

/* Loads and tunes the scenario the controllers come from; the controllers
 * left untunable are taken off its list into untunable[*n_untunable]. */
static int load_scenario(const options_t *o, const char *path, sim_scenario_t *sc, sim_controller_id_t *untunable,
                         int *n_untunable)
{
    sim_parse_error_t perr;
    if (sim_scenario_load(sc, path, &perr) != 0 ||
        (o->n_controllers > 0 && sim_scenario_set_controllers(sc, o->controllers, o->n_controllers, &perr) != 0)) {
        if (perr.line > 0) {
            fprintf(stderr, "%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        } else {
            fprintf(stderr, "%s: %s\n", perr.path, perr.message);
        }
        return -1;
    }
    if (sc->kind != SIM_KIND_ATTITUDE) {
        fprintf(stderr, "ladrc_replay: %s: not an attitude scenario\n", path);
        return -1;
    }
    int failed = 0;
    const sim_fly_tune_options_t tune_opt = {.jobs = 2, .quiet = o->quiet, .strict = o->strict, .note = tune_note};
    if (sim_fly_tune(sc, 1, &tune_opt, &perr, &failed) < 0) {
        fprintf(stderr, "%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        return -1;
    }
    /* an untunable controller is not replayed: the others are */
    *n_untunable = 0;
    int n = 0;
    for (int c = 0; c < sc->n_controllers; ++c) {
        const sim_controller_id_t id = sc->controllers[c];
        if (sc->tuning[id].by == SIM_TUNED_UNTUNABLE) {
            untunable[(*n_untunable)++] = id;
        } else {
            sc->controllers[n++] = id;
        }
    }
    sc->n_controllers = n;
    return 0;
}

/* The replay pass; 0, or -1 after printing why. */
static int replay(const options_t *o, const sim_scenario_t *sc, const char *dir, sim_replay_t *r, progress_t *prog)
{
    char err[512];
    if (sim_replay_init(r, sc, sc->controllers, sc->n_controllers, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_replay: %s\n", err);
        return -1;
    }
    sim_log_options_t lo = o->log;
    lo.dt_s = sc->control_dt_s; /* the controllers' period */
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&lo, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return -1;
    }
    const unsigned has = sim_log_has(log);
    if (!(has & (SIM_LOG_HAS_REF_ANGLE | SIM_LOG_HAS_REF_INTEGRATED))) {
        fprintf(stderr, "ladrc_replay: %s: the log has no setpoint (attitude or rate): nothing to replay against\n",
                prepared.original);
        sim_log_close(log);
        return -1;
    }
    FILE *csv = NULL;
    char path[1024];
    if (o->every > 0) {
        snprintf(path, sizeof path, "%s/replay.csv", dir);
        csv = fopen(path, "w");
        if (csv == NULL) {
            fprintf(stderr, "ladrc_replay: %s: cannot write: %s\n", path, strerror(errno));
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
        fprintf(stderr, "%s\n", err);
    }
    sim_log_close(log);
    if (csv != NULL && (ferror(csv) | fclose(csv)) != 0) {
        fprintf(stderr, "ladrc_replay: %s: write failed\n", path);
        return -1;
    }
    return rc < 0 ? -1 : 0;
}

int main(int argc, char **argv)
{
    static options_t o;
    if (parse_args(argc, argv, &o) != 0) {
        return 2;
    }
    char dir[SIM_LOG_PATH_LEN + 16], stem[SIM_LOG_PATH_LEN], noise[SIM_LOG_PATH_LEN + 64], err[1024];
    log_stem(o.log.path, stem, sizeof stem);
    progress_t prog = {.quiet = o.quiet, .tty = isatty(2), .start_s = sim_fly_now_s(), .last_s = 0.0};
    sim_log_error_t lerr;
    if (sim_log_prepare(&o.log, o.format_given, &prepared, show_decoding, &prog, &lerr) != 0) {
        end_progress(&prog);
        sim_log_error_format(&lerr, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    atexit(remove_prepared);
    end_progress(&prog);
    if (prepared.dir[0] != '\0' && !o.quiet) {
        fprintf(stderr, "ladrc_replay: %s: a %s log of %lld bytes, decoded in %.2f s\n", prepared.original,
                sim_log_source_name(prepared.source), prepared.bytes, prepared.decode_s);
    }
    snprintf(dir, sizeof dir, "%s%s", o.out_dir != NULL ? o.out_dir : "replay/", o.out_dir != NULL ? "" : stem);
    if (sim_fly_make_dirs(dir) != 0) {
        fprintf(stderr, "ladrc_replay: cannot create '%s': %s\n", dir, strerror(errno));
        return 2;
    }
    snprintf(noise, sizeof noise, "%s/airframe_noise.csv", dir);
    sim_log_identify_options_t io = {.log = o.log,
                                     .delay_max_ticks = -1,
                                     .noise_series = noise,
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
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    end_progress(&prog);
    printf("%s: %lld rows in %d file(s), %lld ticks at %.4g s, identified in %.2f s (4 passes)", prepared.original,
           stats.rows, stats.n_files, stats.ticks, airframe.dt_s, sim_fly_now_s() - prog.start_s);
    if (stats.gaps > 0) {
        printf(", %lld gap(s) interpolated over (longest %.3g s)", stats.gaps, stats.longest_gap_s);
    }
    printf("\n");
    sim_report_identification(stdout, &airframe);
    int status = 0;
    for (int i = 0; i < 3; ++i) {
        status |= airframe.axis[i].warnings != 0;
    }
    char path[SIM_LOG_PATH_LEN + 64], ini[SIM_LOG_PATH_LEN + 64];
    snprintf(path, sizeof path, "%s/identification.csv", dir);
    if (sim_write_identification_csv(path, &airframe) != 0) {
        fprintf(stderr, "ladrc_replay: %s: write failed\n", path);
        return 2;
    }
    if (sim_replay_noise_stage(&o.log, &airframe, stdout, err, sizeof err) != 0) {
        fprintf(stderr, "%s\n", err);
        return 2;
    }
    const int have_airframe = write_scenario(dir, &airframe, prepared.original, ini, sizeof ini) == 0;
    if (have_airframe) {
        printf("scenario of the airframe: %s (ladrc_sil flies it, ladrc_margins tunes it)\n", ini);
    }
    if (o.identify_only) {
        return have_airframe ? status : 2;
    }
    if (o.scenario == NULL && !have_airframe) {
        fprintf(stderr, "ladrc_replay: no airframe to tune the controllers for: give one with --scenario\n");
        return 2;
    }
    static sim_scenario_t sc;
    sim_controller_id_t untunable[SIM_MAX_CONTROLLERS];
    int n_untunable = 0;
    if (load_scenario(&o, o.scenario != NULL ? o.scenario : ini, &sc, untunable, &n_untunable) != 0) {
        return 2;
    }
    sim_report_tuning(stdout, &sc);
    static sim_replay_t r;
    prog.start_s = sim_fly_now_s();
    if (replay(&o, &sc, dir, &r, &prog) != 0) {
        return 2;
    }
    const double replay_s = sim_fly_now_s() - prog.start_s;
    printf("replayed %lld ticks (%.4g s of flight) with %d controllers in %.2f s: %.0fx real time\n", r.ticks,
           (double)r.ticks * sc.control_dt_s, r.n, replay_s, (double)r.ticks * sc.control_dt_s / replay_s);
    sim_report_replay(stdout, &r);
    sim_replay_noise_report(stdout, &sc, &r);
    if (sim_write_replay_files(dir, &r, untunable, n_untunable, err, sizeof err) != 0 ||
        sim_log_views_of_log(&o.log, dir, stdout, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_replay: %s\n", err);
        return 2;
    }
    for (int c = 0; c < r.n; ++c) {
        status |= r.fault_ticks[c] > 0;
    }
    printf("outputs in %s (tools/replay_plot.py %s draws them)\n", dir, dir);
    return status == 0 && n_untunable > 0 ? 4 : status;
}
