/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * ladrc_margins: stability margins of the controllers a scenario flies, per
 * axis, on the scenario's airframe (inertia, drag, motor lag, sensor delay):
 * the controllers are configured by sim_setup_attitude, the path ladrc_sil
 * takes, and analysed by ladrc_analysis (docs/margins.md).
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "ladrc/margins.h"
#include "scenario/scenario.h"
#include "report/report.h"
#include "scenario/setup.h"
#include "run/tune.h"
#include "run/tune_noise.h"
#include "run/runner.h"
#include "cli/replay_report.h"
#include "cli/staged_dir.h"
#include "log/log_convert.h"
#include "log/log_identify.h"

/* Largest motor lag searched (s): ten times any real motor's. */
#define TAU_SEARCH_MAX_S 0.5

static ladrc_margins_workspace_t ws;
static ladrc_margins_result_t res;
static ladrc_margins_tuning_t tuning;

static const char *const AXIS_NAMES[3] = {"roll", "pitch", "yaw"};

static void usage(FILE *out)
{
    fputs("usage: ladrc_margins SCENARIO [--controllers LIST] [--axis roll|pitch|yaw|all]\n"
          "                     [--inertia-factor F] [--csv DIR] [--tune] [--fly]\n"
          "       ladrc_margins --from-log LOG [--format betaflight|px4|ardupilot|generic]\n"
          "                     [--map F=SOURCE]... [--dt S] [--from S] [--to S]\n"
          "                     [--save-scenario FILE] [--strict] [the options above]\n"
          "  SCENARIO           an attitude scenario file (docs/scenario-format.md)\n"
          "  --from-log LOG     the airframe identified from a flight log (docs/flight-logs.md),\n"
          "                     its controllers tuned by tune = margins; --format, --map, --dt,\n"
          "                     --from, --to as ladrc_replay's; --save-scenario writes that\n"
          "                     airframe's scenario (not over the log itself); a controller that\n"
          "                     does not start at the log's rate or is untunable is named with\n"
          "                     its reason, the others analysed\n"
          "  --controllers L    comma-separated subset of HP-MLADRC,LP-MLADRC,LADRC,PID,CASCADED,INDI\n"
          "  --axis A           axis to analyse (default: all)\n"
          "  --inertia-factor F true inertia = F times the scenario's (default 1)\n"
          "  --csv DIR          write DIR/<controller>_<axis>.csv frequency responses\n"
          "  --tune             also tune for PM >= 45 deg, GM >= 6 dB and print the result\n"
          "  --fly              also fly the scenario (as ladrc_sil, no time series) and print the\n"
          "                     flown command noise above 20 Hz beside the predicted one\n"
          "Prints per controller and axis: gain margin, phase margin, delay margin,\n"
          "crossover, peak sensitivity, the verdict, the largest stable motor lag\n"
          "and sensor delay, and the predicted RMS of the torque command above 20 Hz\n"
          "from the scenario's [sensors] angle and rate noise (N m). A tune = margins\n"
          "that misses its targets is a warning (the best candidate's gains are\n"
          "analysed); a controller with no candidate that flies the check flight is\n"
          "untunable. Exit status 0, 1 if an analysis failed or a loop is unstable,\n"
          "2 for bad usage, a bad scenario or a refused log, 4 when, else clean, a\n"
          "controller was untunable; with --from-log an untunable controller leaves\n"
          "the status 0 unless --strict.\n",
          out);
}

static int parse_controllers(const char *list, sim_controller_id_t *ids, int *n)
{
    char buf[256];
    if (snprintf(buf, sizeof buf, "%s", list) >= (int)sizeof buf)
        return -1;
    *n = 0;
    for (char *tok = strtok(buf, ","); tok != NULL; tok = strtok(NULL, ",")) {
        int found = -1;
        for (int c = 0; c < SIM_CTRL_LIBRARY_COUNT; ++c) { /* a SITL's loop is not ours to analyse */
            if (strcmp(tok, sim_controller_name((sim_controller_id_t)c)) == 0)
                found = c;
        }
        if (found < 0 || *n >= SIM_MAX_CONTROLLERS) {
            fprintf(stderr, "ladrc_margins: --controllers: unknown controller '%s'\n", tok);
            return -1;
        }
        ids[(*n)++] = (sim_controller_id_t)found;
    }
    return *n > 0 ? 0 : -1;
}

/* --csv's files, one per controller and axis: NAME_AXIS.csv. */
#define CSV_NAMES (SIM_CTRL_COUNT * 3)
static char csv_names[CSV_NAMES][SIM_STAGED_NAME_LEN];
static const char *csv_name_of[CSV_NAMES];

static void name_csv_files(void)
{
    for (int k = 0; k < CSV_NAMES; ++k) {
        snprintf(csv_names[k], sizeof csv_names[k], "%s_%s.csv", sim_controller_name((sim_controller_id_t)(k / 3)),
                 AXIS_NAMES[k % 3]);
        csv_name_of[k] = csv_names[k];
    }
}

static int write_csv(sim_staged_dir_t *dir, const char *ctrl, int axis, const ladrc_margins_result_t *r)
{
    char name[SIM_STAGED_NAME_LEN], path[SIM_STAGED_PATH_LEN];
    snprintf(name, sizeof name, "%s_%s.csv", ctrl, AXIS_NAMES[axis]);
    FILE *f = sim_staged_path(dir, name, path, sizeof path) != NULL ? fopen(path, "w") : NULL;
    if (f == NULL) {
        fprintf(stderr, "ladrc_margins: %s/%s: cannot write: %s\n", dir->final, name, strerror(errno));
        return -1;
    }
    fprintf(f, "# gm_db=%.6g gm_rad_s=%.6g pm_deg=%.6g wc_rad_s=%.6g dm_s=%.6g ms=%.6g stable=%d\n", r->gm_db,
            r->gm_rad_s, r->pm_deg, r->wc_rad_s, r->dm_s, r->ms, r->stable);
    fprintf(f, "w_rad_s,L_re,L_im,L_mag_db,L_phase_deg,S_mag_db,dist_err_rad_per_rad_s2\n");
    for (int i = 0; i < r->n_out; ++i) {
        const double mag = hypot(r->l_re[i], r->l_im[i]);
        fprintf(f, "%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%.6g\n", r->w_rad_s[i], r->l_re[i], r->l_im[i], 20.0 * log10(mag),
                atan2(r->l_im[i], r->l_re[i]) * 180.0 / 3.14159265358979323846,
                20.0 * log10(hypot(r->s_re[i], r->s_im[i])), hypot(r->de_re[i], r->de_im[i]));
    }
    if ((ferror(f) | fclose(f)) != 0) {
        fprintf(stderr, "ladrc_margins: %s/%s: write failed\n", dir->final, name);
        return -1;
    }
    return 0;
}

static void fmt_margin(char *buf, size_t len, double v, const char *unit)
{
    if (isinf(v)) {
        snprintf(buf, len, "inf");
    } else {
        snprintf(buf, len, "%.1f%s", v, unit);
    }
}

/* The scenario of the airframe identified from a log (log_identify.h,
 * airframe.h): written to save_path when given, read from memory. */
/* The decoded form of a binary log, removed at exit. */
static sim_log_prepared_t prepared;

static void remove_prepared(void)
{
    sim_log_prepared_remove(&prepared);
}

static int load_from_log(const char *log_path, sim_log_options_t *opt, int format_given, const char *save_path,
                         sim_scenario_t *sc, sim_airframe_refused_t *refused)
{
    char err[SIM_STAGED_PATH_LEN + 256];
    if (snprintf(opt->path, sizeof opt->path, "%s", log_path) >= (int)sizeof opt->path) {
        fprintf(stderr, "ladrc_margins: %s: path too long\n", log_path);
        return -1;
    }
    static sim_staged_file_t saved; /* the scenario saved over the log would lose it */
    if (save_path != NULL && sim_staged_file_open(&saved, save_path, &log_path, 1, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_margins: --save-scenario: %s: give another path\n", err);
        return -1;
    }
    sim_log_error_t lerr;
    if (sim_log_prepare(opt, format_given, &prepared, NULL, NULL, &lerr) != 0) {
        sim_log_error_format(&lerr, err, sizeof err);
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        sim_staged_file_abort(&saved);
        return -1;
    }
    atexit(remove_prepared);
    const sim_log_identify_options_t io = {.log = *opt, .delay_max_ticks = -1};
    static sim_airframe_t airframe;
    sim_log_stats_t stats;
    if (sim_log_identify(&io, &airframe, &stats, err, sizeof err) != 0) {
        sim_log_prepared_explain(&prepared, err, sizeof err);
        fprintf(stderr, "%s\n", err);
        sim_staged_file_abort(&saved);
        return -1;
    }
    if (sim_log_gap_warning(&stats, err, sizeof err)) {
        printf("warning: %s: %s\n", log_path, err);
    }
    sim_report_identification(stdout, &airframe);
    for (int i = 0; i < 3; ++i) {
        char note[256];
        if (sim_airframe_b0_note(&airframe, i, note, sizeof note)) {
            printf("warning: %s\n", note);
        }
    }
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    const char *base = strrchr(log_path, '/');
    const int rc = mem == NULL ? -1
                               : sim_airframe_write(mem, &airframe, base != NULL ? base + 1 : log_path, NULL, refused,
                                                    err, sizeof err);
    if (mem == NULL || fclose(mem) != 0 || rc != 0) {
        fprintf(stderr, "ladrc_margins: %s: no airframe: %s\n", log_path, rc != 0 ? err : "out of memory");
        free(text);
        sim_staged_file_abort(&saved);
        return -1;
    }
    if (save_path != NULL && (fputs(text, saved.f) < 0 || sim_staged_file_commit(&saved, err, sizeof err) != 0)) {
        sim_staged_file_abort(&saved);
        fprintf(stderr, "ladrc_margins: --save-scenario: %s\n", err);
        free(text);
        return -1;
    }
    sim_parse_error_t perr;
    char name[SIM_PATH_LEN];
    snprintf(name, sizeof name, "%s.airframe.ini", log_path);
    const int parsed = sim_scenario_parse(sc, text, name, &perr);
    free(text);
    if (parsed != 0) {
        fprintf(stderr, "%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        return -1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    static sim_scenario_t sc;
    const char *path = NULL, *csv_dir = NULL, *from_log = NULL, *save_path = NULL;
    sim_log_options_t log_opt;
    int format_given = 0;
    sim_log_options_default(&log_opt);
    int axis_from = 0, axis_to = 2, tune = 0, fly = 0, n_override = 0, strict = 0;
    double inertia_factor = 1.0;
    sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
    for (int a = 1; a < argc; ++a) {
        const char *arg = argv[a];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(arg, "--controllers") == 0 && a + 1 < argc) {
            if (parse_controllers(argv[++a], ids, &n_override) != 0)
                return 2;
        } else if (strcmp(arg, "--axis") == 0 && a + 1 < argc) {
            const char *v = argv[++a];
            int found = -2;
            for (int i = 0; i < 3; ++i) {
                if (strcmp(v, AXIS_NAMES[i]) == 0)
                    found = i;
            }
            if (strcmp(v, "all") == 0)
                found = -1;
            if (found == -2) {
                fprintf(stderr, "ladrc_margins: --axis: expected roll, pitch, yaw or all, got '%s'\n", v);
                return 2;
            }
            axis_from = found < 0 ? 0 : found;
            axis_to = found < 0 ? 2 : found;
        } else if (strcmp(arg, "--inertia-factor") == 0 && a + 1 < argc) {
            char *end = NULL;
            inertia_factor = strtod(argv[++a], &end);
            if (*end != '\0' || !(inertia_factor > 0.0) || !isfinite(inertia_factor)) {
                fprintf(stderr, "ladrc_margins: --inertia-factor: expected a number > 0, got '%s'\n", argv[a]);
                return 2;
            }
        } else if (strcmp(arg, "--csv") == 0 && a + 1 < argc) {
            csv_dir = argv[++a];
        } else if (strcmp(arg, "--tune") == 0) {
            tune = 1;
        } else if (strcmp(arg, "--fly") == 0) {
            fly = 1;
        } else if (strcmp(arg, "--from-log") == 0 && a + 1 < argc) {
            from_log = argv[++a];
        } else if (strcmp(arg, "--format") == 0 && a + 1 < argc) {
            const int f = sim_log_format_parse(argv[++a]);
            if (f < 0) {
                fprintf(stderr, "ladrc_margins: --format: expected betaflight, px4, ardupilot or generic, got '%s'\n",
                        argv[a]);
                return 2;
            }
            log_opt.format = (sim_log_format_t)f;
            format_given = 1;
        } else if (strcmp(arg, "--map") == 0 && a + 1 < argc && log_opt.n_map < SIM_LOG_MAX_MAP) {
            log_opt.map[log_opt.n_map++] = argv[++a];
        } else if (strcmp(arg, "--save-scenario") == 0 && a + 1 < argc) {
            save_path = argv[++a];
        } else if (strcmp(arg, "--strict") == 0) {
            strict = 1;
        } else if ((strcmp(arg, "--dt") == 0 || strcmp(arg, "--from") == 0 || strcmp(arg, "--to") == 0) &&
                   a + 1 < argc) {
            char *end = NULL;
            const double v = strtod(argv[++a], &end);
            if (end == argv[a] || *end != '\0' || !isfinite(v) || v < 0.0) {
                fprintf(stderr, "ladrc_margins: %s: expected a number >= 0, got '%s'\n", arg, argv[a]);
                return 2;
            }
            *(arg[2] == 'd' ? &log_opt.dt_s : arg[2] == 'f' ? &log_opt.t_from_s : &log_opt.t_to_s) = v;
        } else if (arg[0] == '-' || path != NULL) {
            fprintf(stderr, "ladrc_margins: unknown, incomplete or extra argument '%s'\n", arg);
            usage(stderr);
            return 2;
        } else {
            path = arg;
        }
    }
    if ((path == NULL) == (from_log == NULL)) {
        usage(stderr);
        return 2;
    }
    name_csv_files();
    const char *const inputs[] = {path, from_log};
    char err[SIM_STAGED_PATH_LEN + 256];
    if (csv_dir != NULL && sim_staged_check_inputs(csv_dir, csv_name_of, CSV_NAMES, inputs, 2, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_margins: --csv: %s: give another folder\n", err);
        return 2;
    }
    sim_parse_error_t perr;
    static sim_airframe_refused_t refused;
    if (from_log != NULL && load_from_log(from_log, &log_opt, format_given, save_path, &sc, &refused) != 0) {
        return 2;
    }
    /* from a log: the controllers that do not start at its rate are named, not analysed */
    int n_kept = 0, not_started = 0;
    for (int k = 0; k < refused.n; ++k) {
        int asked = n_override == 0;
        for (int c = 0; c < n_override; ++c) {
            asked |= ids[c] == refused.ids[k];
        }
        if (asked) {
            printf("%-10s untunable: %s\n", sim_controller_name(refused.ids[k]), refused.reason[k]);
            ++not_started;
        }
    }
    for (int c = 0; c < n_override; ++c) {
        int out = 0;
        for (int k = 0; k < refused.n; ++k) {
            out |= ids[c] == refused.ids[k];
        }
        if (!out) {
            ids[n_kept++] = ids[c];
        }
    }
    if (n_override > 0 && n_kept == 0) {
        sc.n_controllers = 0;
    }
    n_override = n_kept;
    if ((from_log == NULL && sim_scenario_load(&sc, path, &perr) != 0) ||
        (n_override > 0 && sim_scenario_set_controllers(&sc, ids, n_override, &perr) != 0)) {
        if (perr.line > 0) {
            fprintf(stderr, "%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        } else {
            fprintf(stderr, "%s: %s\n", perr.path, perr.message);
        }
        return 2;
    }
    path = from_log != NULL ? from_log : path;
    if (sc.kind != SIM_KIND_ATTITUDE) {
        fprintf(stderr, "ladrc_margins: %s: not an attitude scenario\n", path);
        return 2;
    }
    /* tune = margins: the controllers are analysed with the gains it chooses. */
    int untunable = 0;
    for (int k = 0; k < 2 * sc.n_controllers; ++k) { /* those capped by another's noise after it */
        const int c = k % sc.n_controllers;
        if ((sc.overrides[sc.controllers[c]].tune_noise_ref >= 0) != (k >= sc.n_controllers)) {
            continue;
        }
        const int rc = sim_tune_controller(&sc, sc.controllers[c], &ws, &perr);
        if (rc != SIM_TUNE_OK) {
            fprintf(stderr, "%s:%d:%d: %s%s\n", perr.path, perr.line, perr.column,
                    rc == SIM_TUNE_UNTUNABLE ? "" : "warning: ", perr.message);
        }
        untunable += rc == SIM_TUNE_UNTUNABLE;
    }
    /* --fly: every controller flown once, its measured command noise (metrics.h) */
    static sim_metrics_t flown[SIM_MAX_CONTROLLERS];
    static char fly_err[SIM_MAX_CONTROLLERS][256];
    if (fly) {
        sim_run_spec_t runs[SIM_MAX_CONTROLLERS];
        for (int c = 0; c < sc.n_controllers; ++c) {
            const sim_run_spec_t spec = {.ctrl = sc.controllers[c],
                                         .csv_path = NULL,
                                         .metrics = &flown[c],
                                         .err = fly_err[c],
                                         .err_len = sizeof fly_err[c],
                                         .rc = 0};
            runs[c] = spec;
        }
        sim_run_attitude_group(&sc, runs, sc.n_controllers, NULL);
        for (int c = 0; c < sc.n_controllers; ++c) {
            if (runs[c].rc != 0) {
                fprintf(stderr, "ladrc_margins: --fly: %s: %s\n", sim_controller_name(sc.controllers[c]), fly_err[c]);
                return 1;
            }
        }
    }
    static sim_staged_dir_t csv_stage; /* --csv's files, put in place together at the end */
    if (csv_dir != NULL && sim_staged_open(&csv_stage, csv_dir, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_margins: --csv: %s\n", err);
        return 2;
    }
    int csv_failed = 0;
    printf("%s: dt %.4g s, motor lag %.4g s, sensor delay %d ticks, rate %s, true inertia x %.3g\n", sc.name,
           sc.control_dt_s, sc.motor_tau_s, sc.delay_ticks, sc.use_rate ? "used" : "not used", inertia_factor);
    sim_report_tuning(stdout, &sc);
    printf("%-10s %-5s %9s %10s %8s %10s %14s %7s %6s %12s %10s %12s%s\n", "controller", "axis", "GM", "GM at", "PM",
           "crossover", "delay margin", "Ms", "stable", "max lag", "max delay", "noise N m",
           fly ? "     flown N m" : "");
    int status = 0;
    for (int c = 0; c < sc.n_controllers; ++c) {
        const sim_controller_id_t id = sc.controllers[c];
        if (sc.tuning[id].by == SIM_TUNED_UNTUNABLE) {
            printf("%-10s untunable: no candidate gains fly the check flight\n", sim_controller_name(id));
            continue;
        }
        ladrc_attitude_config_t acfg;
        sim_setup_attitude(&sc, id, &acfg);
        sim_tune_filter_t filter;
        sim_tune_filter(&sc, &filter);
        for (int i = axis_from; i <= axis_to; ++i) {
            const double j_model = sc.inertia_kg_m2[i] * sc.inertia_scale[i];
            const ladrc_margins_plant_t plant = {.dt_s = sc.control_dt_s,
                                                 .inertia_kg_m2 = j_model,
                                                 .inertia_factor = sc.inertia_kg_m2[i] * inertia_factor / j_model,
                                                 .drag_Nm_s = sc.rot_drag_Nm_s,
                                                 .motor_tau_s = sc.motor_tau_s,
                                                 .delay_ticks = sc.delay_ticks};
            ladrc_margins_request_t req;
            ladrc_margins_request_default(&req, &plant);
            sim_tune_objective(&sc, id, &req);
            char series_why[512];
            if (sim_tune_noise_series(&sc, i, &req, series_why, sizeof series_why) != 0) {
                fprintf(stderr, "%s\n", series_why);
            }
            const ladrc_margins_controller_t ctl = sim_tune_controller_of(&sc, &filter, &acfg, i);
            int idle = 0;
            ladrc_margins_status_t st = ladrc_margins_analyse_reported(&ws, &ctl, &req, &res, &idle);
            /* HP-MLADRC's converged tone model may have no settled linear
             * response: then the margins of its idle state (no tone, weight 0). */
            const char *note = idle ? "  (estimator idle: no settled linearisation under the tone)" : "";
            if (st != LADRC_MARGINS_OK) {
                printf("%-10s %-5s analysis failed: %s\n", sim_controller_name(id), AXIS_NAMES[i],
                       ladrc_margins_status_str(st));
                status = 1;
                continue;
            }
            double tau_max = 0.0;
            int delay_max = -1;
            (void)ladrc_margins_max_motor_tau(&ws, &plant, TAU_SEARCH_MAX_S, &tau_max);
            (void)ladrc_margins_max_delay(&ws, &plant, &delay_max);
            char gm[32], gm_at[32], pm[32], wc[32], dm[48], lag[32];
            fmt_margin(gm, sizeof gm, res.gm_db, " dB");
            fmt_margin(gm_at, sizeof gm_at, res.gm_rad_s, "");
            fmt_margin(pm, sizeof pm, res.pm_deg, "");
            fmt_margin(wc, sizeof wc, res.wc_rad_s, "");
            if (isinf(res.dm_s)) {
                snprintf(dm, sizeof dm, "inf");
            } else {
                snprintf(dm, sizeof dm, "%.1f ms/%.1ft", res.dm_s * 1e3, res.dm_ticks);
            }
            if (tau_max >= TAU_SEARCH_MAX_S) {
                snprintf(lag, sizeof lag, ">= %.0f ms", TAU_SEARCH_MAX_S * 1e3);
            } else {
                snprintf(lag, sizeof lag, "%.1f ms", tau_max * 1e3);
            }
            char flown_text[32] = "";
            if (fly) {
                if (flown[c].diverged)
                    snprintf(flown_text, sizeof flown_text, " %13s", "diverged");
                else
                    snprintf(flown_text, sizeof flown_text, " %13.4g", flown[c].cmd_noise_Nm[i]);
            }
            printf("%-10s %-5s %9s %10s %8s %10s %14s %7.2f %6s %12s %7d t %12.4g%s%s\n", sim_controller_name(id),
                   AXIS_NAMES[i], gm, gm_at, pm, wc, dm, res.ms, res.stable ? "yes" : "NO", lag, delay_max,
                   res.cmd_noise_Nm, flown_text, note);
            if (!res.stable)
                status = 1;
            if (csv_dir != NULL && write_csv(&csv_stage, sim_controller_name(id), i, &res) != 0)
                csv_failed = 1;
            if (tune) {
                const ladrc_margins_targets_t targets = {.pm_min_deg = 45.0, .gm_min_db = 6.0};
                ladrc_axis_config_t tuned;
                st = ladrc_margins_tune(&ws, &ctl, &req, &targets, &tuned, &tuning);
                const ladrc_margins_result_t *m = &tuning.margins;
                char gains[256];
                (void)sim_setup_format_gains(&tuned, gains, sizeof gains);
                printf("  tuned: %s", gains);
                printf(" -> GM %.1f dB PM %.1f deg crossover %.1f rad/s Ms %.2f peak |d->e| %.3g rad per rad/s^2"
                       " step cost %.3g rad^2 s noise %.4g N m%s\n",
                       m->gm_db, m->pm_deg, m->wc_rad_s, m->ms, tuning.peak_dist_rad, tuning.step_cost_rad2_s,
                       tuning.cmd_noise_Nm, st == LADRC_MARGINS_OK ? "" : "  TARGETS NOT MET");
                if (st != LADRC_MARGINS_OK)
                    status = 1;
            }
        }
    }
    if (csv_dir != NULL && csv_failed) {
        sim_staged_abort(&csv_stage);
        fprintf(stderr, "ladrc_margins: --csv: nothing written in %s\n", csv_dir);
        status = 1;
    } else if (csv_dir != NULL && sim_staged_commit(&csv_stage, csv_name_of, CSV_NAMES, err, sizeof err) != 0) {
        fprintf(stderr, "ladrc_margins: --csv: %s\n", err);
        status = 1;
    }
    untunable += not_started;
    return status == 0 && untunable > 0 && (from_log == NULL || strict) ? 4 : status;
}
