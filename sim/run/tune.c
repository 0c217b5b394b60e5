/* SPDX-License-Identifier: BSD-3-Clause */
#define _POSIX_C_SOURCE 200809L
/* tune = margins (see tune.h). */
#include "tune.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "run/runner.h"
#include "run/tune_noise.h"
#include "scenario/setup.h"

static const char *const AXIS_NAMES[3] = {"roll", "pitch", "yaw"};

int sim_tune_wanted(const sim_scenario_t *sc, sim_controller_id_t id)
{
    return sc->kind == SIM_KIND_ATTITUDE && sc->overrides[id].tune == SIM_TUNE_MARGINS;
}

void sim_tune_objective(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_request_t *req)
{
    const sim_overrides_t *o = &sc->overrides[id];
    if (!isnan(o->tune_step_rad))
        req->track_step_rad = o->tune_step_rad;
    if (!isnan(o->tune_dist_rad_s2))
        req->dist_step_rad_s2 = o->tune_dist_rad_s2;
    sim_tune_noise_request(sc, req);
}

/* The targets of axis i: the file's margins and its command-noise cap (an
 * absolute one for this axis or every axis, or the reference controller's noise on that axis, tuned
 * before, times the ratio). */
static ladrc_margins_targets_t axis_targets_of(const sim_scenario_t *sc, sim_controller_id_t id,
                                               const ladrc_margins_targets_t *targets, int i)
{
    const sim_overrides_t *o = &sc->overrides[id];
    ladrc_margins_targets_t tg = *targets;
    if (!isnan(o->tune_noise_axis_max_Nm[i])) {
        tg.cmd_noise_max_Nm = o->tune_noise_axis_max_Nm[i];
    } else if (!isnan(o->tune_noise_max_Nm)) {
        tg.cmd_noise_max_Nm = o->tune_noise_max_Nm;
    } else if (o->tune_noise_ref >= 0) {
        const sim_tuning_t *ref = &sc->tuning[o->tune_noise_ref];
        tg.cmd_noise_max_Nm = ref->tuned ? ref->cmd_noise_Nm[i] * o->tune_noise_ratio : 0.0;
    }
    return tg;
}

void sim_tune_plant(const sim_scenario_t *sc, int axis, ladrc_margins_plant_t *plant)
{
    plant->dt_s = sc->control_dt_s;
    plant->inertia_kg_m2 = sc->inertia_kg_m2[axis] * sc->inertia_scale[axis];
    plant->inertia_factor = 1.0;
    plant->drag_Nm_s = sc->rot_drag_Nm_s * sc->rot_drag_scale;
    plant->motor_tau_s = sc->motor_tau_s;
    plant->delay_ticks = sc->delay_ticks;
}

void sim_tune_filter(const sim_scenario_t *sc, sim_tune_filter_t *f)
{
    f->on = sim_setup_filters_gyro(sc);
    sim_setup_gyro_filter(sc, &f->cfg);
    for (int q = 0; q < 4; ++q) {
        f->rotor_hz[q] = (ladrc_real_t)sim_setup_hover_rotor_hz(sc);
    }
}

ladrc_margins_controller_t sim_tune_controller_of(const sim_scenario_t *sc, const sim_tune_filter_t *f,
                                                  const ladrc_attitude_config_t *acfg, int axis)
{
    const ladrc_margins_controller_t ctl = {.attitude = acfg,
                                            .axis_index = axis,
                                            .axis = NULL,
                                            .use_rate = sc->use_rate,
                                            .filter = f->on ? &f->cfg : NULL,
                                            .filter_rotor_hz = f->rotor_hz,
                                            .filter_angle = sc->filter_angle};
    return ctl;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The error of the file at controller id's `tune` key. */
static void tune_error(const sim_scenario_t *sc, sim_controller_id_t id, sim_parse_error_t *err, const char *message)
{
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", sc->path);
    err->line = sc->tune_line[id];
    err->column = sc->tune_column[id];
    err->first_set_line = sc->first_set_line;
    snprintf(err->message, sizeof err->message, "%s", message);
}

/* The request and the targets of axis i: its plant, the file's objective
 * and noise (its recorded gyro noise included), and its noise cap. */
static void axis_request(const sim_scenario_t *sc, sim_controller_id_t id, const ladrc_margins_targets_t *targets,
                         int i, ladrc_margins_request_t *req, ladrc_margins_targets_t *axis_targets)
{
    ladrc_margins_plant_t plant;
    sim_tune_plant(sc, i, &plant);
    ladrc_margins_request_default(req, &plant);
    sim_tune_objective(sc, id, req);
    char why[512];
    if (sim_tune_noise_series(sc, i, req, why, sizeof why) != 0) {
        /* the parser read the file: it changed since; the prediction is then the white noise's only */
        fprintf(stderr, "%s\n", why);
    }
    *axis_targets = axis_targets_of(sc, id, targets, i);
}

static void keep(sim_tuning_t *t, int i, const ladrc_axis_config_t *tuned, const ladrc_margins_result_t *m,
                 double step_cost, double cap_Nm, int idle)
{
    t->gains[i] = *tuned;
    t->pm_deg[i] = m->pm_deg;
    t->gm_db[i] = m->gm_db;
    t->gm_low_db[i] = m->gm_low_db;
    t->crossover_rad_s[i] = m->wc_rad_s;
    t->ms[i] = m->ms;
    t->step_cost_rad2_s[i] = step_cost;
    t->cmd_noise_Nm[i] = m->cmd_noise_Nm;
    t->cmd_noise_cap_Nm[i] = cap_Nm;
    t->idle[i] = idle;
}

/* No margins to report for axis i (its analysis failed). */
static void keep_unanalysed(sim_tuning_t *t, int i, const ladrc_axis_config_t *gains)
{
    ladrc_margins_result_t none;
    memset(&none, 0, sizeof none);
    none.pm_deg = none.gm_db = none.gm_low_db = none.wc_rad_s = none.ms = none.cmd_noise_Nm = NAN;
    keep(t, i, gains, &none, NAN, 0.0, 0);
}

/* Appends printf-style text to buf (of size len), "; " between parts. */
static void add_reason(char *buf, size_t len, const char *fmt, ...)
{
    const size_t used = strlen(buf);
    if (used + 3 >= len) {
        return;
    }
    char *at = buf + used;
    size_t left = len - used;
    if (used > 0) {
        snprintf(at, left, "; ");
        at += 2;
        left -= 2;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(at, left, fmt, ap);
    va_end(ap);
}

/* The margins tuner on each axis into t (its gains, margins and idle
 * flags); where it misses the targets or fails, why into why. Returns 1
 * when every axis met the targets. */
static int tune_axes(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                     const ladrc_margins_targets_t *targets, const sim_tune_filter_t *filter, char *why, size_t why_len)
{
    sim_tuning_t *t = &sc->tuning[id];
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(sc, id, &acfg); /* tuning[id] is clear: the defaults and the file's keys */
    int met_all = 1;
    for (int i = 0; i < 3; ++i) {
        ladrc_margins_request_t req;
        ladrc_margins_targets_t axis_targets;
        axis_request(sc, id, targets, i, &req, &axis_targets);
        /* Roll and pitch of a symmetric airframe are the same loop: pitch
         * takes roll's gains when its own analysis with them meets the
         * targets (an adaptive variant's linearisation under the tone may
         * differ between the two), else it is tuned itself. */
        if (i == 1 && req.plant.inertia_kg_m2 == sc->inertia_kg_m2[0] * sc->inertia_scale[0] && !isnan(t->pm_deg[0])) {
            ladrc_attitude_config_t shared = acfg;
            sim_setup_tuned_gains(t, 0, &shared.axis[1]);
            const ladrc_margins_controller_t chk = sim_tune_controller_of(sc, filter, &shared, 1);
            int idle = 0;
            ladrc_margins_result_t *m = &ws->scratch;
            if (ladrc_margins_analyse_reported(ws, &chk, &req, m, &idle) == LADRC_MARGINS_OK &&
                ladrc_margins_meets(m, &axis_targets)) {
                keep(t, 1, &t->gains[0], m, t->step_cost_rad2_s[0], axis_targets.cmd_noise_max_Nm, idle);
                t->shared[1] = 1;
                continue;
            }
        }
        const ladrc_margins_controller_t ctl = sim_tune_controller_of(sc, filter, &acfg, i);
        ladrc_axis_config_t tuned;
        ladrc_margins_tuning_t result;
        const ladrc_margins_status_t st = ladrc_margins_tune(ws, &ctl, &req, &axis_targets, &tuned, &result);
        if (st != LADRC_MARGINS_OK && st != LADRC_MARGINS_ERR_TARGETS_NOT_MET) {
            add_reason(why, why_len, "%s on %s: the analysis failed: %s", sim_controller_name(id), AXIS_NAMES[i],
                       ladrc_margins_status_str(st));
            keep_unanalysed(t, i, &acfg.axis[i]); /* the file's gains stand in for the tuner's */
            met_all = 0;
            continue;
        }
        /* whether the reported margins are HP-MLADRC's idle ones */
        int idle = 0;
        ladrc_attitude_config_t again = acfg;
        again.axis[i] = tuned;
        const ladrc_margins_controller_t chk = sim_tune_controller_of(sc, filter, &again, i);
        (void)ladrc_margins_analyse_reported(ws, &chk, &req, &ws->scratch, &idle);
        keep(t, i, &tuned, &result.margins, result.step_cost_rad2_s, axis_targets.cmd_noise_max_Nm, idle);
        if (st == LADRC_MARGINS_ERR_TARGETS_NOT_MET) {
            const ladrc_margins_result_t *m = &result.margins;
            char cap[96] = "";
            if (axis_targets.cmd_noise_max_Nm > 0.0) {
                snprintf(cap, sizeof cap, ", command noise <= %.3g N m", axis_targets.cmd_noise_max_Nm);
            }
            add_reason(why, why_len,
                       "%s on %s cannot meet PM >= %g deg, GM >= %g dB%s; best reached: %s, PM %.1f deg, GM %.1f dB, "
                       "lower GM %.1f dB, command noise %.3g N m",
                       sim_controller_name(id), AXIS_NAMES[i], targets->pm_min_deg, targets->gm_min_db, cap,
                       m->stable ? "stable" : "UNSTABLE", m->pm_deg, m->gm_db, m->gm_low_db, m->cmd_noise_Nm);
            met_all = 0;
        }
    }
    return met_all;
}

/* Margins of the gains of t on each axis (a candidate other than the
 * tuner's: the library's defaults or the file's gains) into t; returns 1
 * when every axis meets the targets. */
static int analyse_candidate(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                             const ladrc_margins_targets_t *targets, const sim_tune_filter_t *filter)
{
    sim_tuning_t *t = &sc->tuning[id];
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(sc, id, &acfg);
    int met_all = 1;
    for (int i = 0; i < 3; ++i) {
        ladrc_margins_request_t req;
        ladrc_margins_targets_t axis_targets;
        axis_request(sc, id, targets, i, &req, &axis_targets);
        const ladrc_margins_controller_t ctl = sim_tune_controller_of(sc, filter, &acfg, i);
        int idle = 0;
        double step_cost = NAN;
        t->shared[i] = 0;
        if (ladrc_margins_analyse_reported(ws, &ctl, &req, &ws->scratch, &idle) != LADRC_MARGINS_OK) {
            keep_unanalysed(t, i, &acfg.axis[i]);
            met_all = 0;
            continue;
        }
        const ladrc_margins_result_t m = ws->scratch;
        if (req.track_step_rad > 0.0 || req.dist_step_rad_s2 > 0.0) {
            if (ladrc_margins_step_cost(ws, &ctl, &req, &step_cost) != LADRC_MARGINS_OK) {
                step_cost = NAN;
            }
        }
        keep(t, i, &acfg.axis[i], &m, step_cost, axis_targets.cmd_noise_max_Nm, idle);
        met_all &= ladrc_margins_meets(&m, &axis_targets);
    }
    return met_all;
}

/* The check flight: the whole scenario flown with the gains of
 * sc->tuning[id] (deterministic: the run that follows flies the same).
 * Returns the sum over the axes of the RMS error (deg), INFINITY where the
 * controller does not start, the flight fails or diverges; what it saw into
 * seen. The text reads "on AXIS: ..." as the others (tools/suite.sh). */
static double check_flight(const sim_scenario_t *sc, sim_controller_id_t id, char *seen, size_t len)
{
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(sc, id, &acfg);
    ladrc_attitude_t att;
    const ladrc_status_t st = ladrc_attitude_init(&att, &acfg, NULL);
    if (st != LADRC_OK) {
        snprintf(seen, len, "do not start: %s", ladrc_status_str(st));
        return INFINITY;
    }
    sim_metrics_t m;
    char run_err[160] = "";
    if (sim_run_attitude(sc, id, NULL, NULL, &m, run_err, sizeof run_err) != 0) {
        snprintf(seen, len, "the check flight failed: %s", run_err);
        return INFINITY;
    }
    if (m.diverged) {
        const int ax = m.diverged_axis;
        if (ax >= 0 && ax < 3 && !isnan(m.diverged_error_deg) && !isnan(m.reference_outran_at_s[ax])) {
            snprintf(seen, len,
                     "on %s: diverge at %.3f s of the check flight (|error| %.1f deg beyond %g deg), after the "
                     "reference outran the controller's shaper from %.3f s (td_accel_rad_s2, "
                     "levant_lipschitz_rad_s4)",
                     AXIS_NAMES[ax], m.diverged_at_s, m.diverged_error_deg, sc->diverge_limit_deg,
                     m.reference_outran_at_s[ax]);
        } else if (ax >= 0 && ax < 3 && !isnan(m.diverged_error_deg)) {
            snprintf(seen, len, "on %s: diverge at %.3f s of the check flight (|error| %.1f deg beyond %g deg)",
                     AXIS_NAMES[m.diverged_axis], m.diverged_at_s, m.diverged_error_deg, sc->diverge_limit_deg);
        } else if (m.diverged_axis >= 0 && m.diverged_axis < 3) {
            snprintf(seen, len, "on %s: diverge at %.3f s of the check flight (its state turned non-finite)",
                     AXIS_NAMES[m.diverged_axis], m.diverged_at_s);
        } else {
            snprintf(seen, len,
                     "on the rotors: diverge at %.3f s of the check flight (a rotor's state turned "
                     "non-finite)",
                     m.diverged_at_s);
        }
        return INFINITY;
    }
    double sum = 0.0;
    int outran = -1;
    for (int i = 0; i < 3; ++i) {
        sum += sim_stat_rms(&m.error_deg[i]);
        outran = (outran < 0 && !isnan(m.reference_outran_at_s[i])) ? i : outran;
    }
    snprintf(seen, len, "fly at %.4g deg RMS (summed over the axes)%s%s%s", sum,
             outran >= 0 ? ", the reference outrunning the shaper on " : "", outran >= 0 ? AXIS_NAMES[outran] : "",
             outran >= 0 ? " (see the run's report)" : "");
    return sum;
}

/* 1 when the gain fields of a and b differ on some axis. */
static int gains_differ(const ladrc_axis_config_t a[3], const ladrc_axis_config_t b[3])
{
    for (int i = 0; i < 3; ++i) {
        int n;
        const sim_gain_field_t *f = sim_setup_gain_fields(a[i].variant, &n);
        for (int k = 0; k < n; ++k) {
            if (sim_setup_gain(&a[i], &f[k]) != sim_setup_gain(&b[i], &f[k])) {
                return 1;
            }
        }
    }
    return 0;
}

int sim_tune_controller(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                        sim_parse_error_t *err)
{
    sim_tuning_t *t = &sc->tuning[id];
    memset(t, 0, sizeof *t);
    memset(err, 0, sizeof *err);
    if (!sim_tune_wanted(sc, id)) {
        return SIM_TUNE_OK;
    }
    const double start = now_s();
    const sim_overrides_t *o = &sc->overrides[id];
    const ladrc_margins_targets_t targets = {
        .pm_min_deg = isnan(o->tune_pm_deg) ? SIM_TUNE_PM_DEG_DEFAULT : o->tune_pm_deg,
        .gm_min_db = isnan(o->tune_gm_db) ? SIM_TUNE_GM_DB_DEFAULT : o->tune_gm_db};
    sim_tune_filter_t filter;
    sim_tune_filter(sc, &filter);
    char why[sizeof t->reason] = "";
    const int met = tune_axes(sc, id, ws, &targets, &filter, why, sizeof why);
    double tuner_s = now_s() - start; /* with its check flight below: what a tuning cost before candidates */

    /* The candidates: the tuner's gains (its closest miss when it misses
     * the targets), the library's defaults and the file's own gains, each
     * analysed and flown whole. */
    static const char *const NAMES[SIM_N_CANDIDATES] = {"the tuned gains", "the library's default gains",
                                                        "the file's gains"};
    sim_tuning_t cand[SIM_N_CANDIDATES];
    int cand_met[SIM_N_CANDIDATES] = {met, 0, 0};
    cand[SIM_CANDIDATE_MARGINS] = *t;
    cand[SIM_CANDIDATE_MARGINS].tuned = 1;
    ladrc_attitude_config_t cfg;
    sim_setup_library_defaults(sc, id, &cfg);
    memcpy(t->gains, cfg.axis, sizeof t->gains);
    t->tuned = 1;
    cand_met[SIM_CANDIDATE_DEFAULTS] = analyse_candidate(sc, id, ws, &targets, &filter);
    cand[SIM_CANDIDATE_DEFAULTS] = *t;
    t->tuned = 0;
    sim_setup_attitude(sc, id, &cfg); /* the file's gains */
    const int file_has_gains = gains_differ(cfg.axis, cand[SIM_CANDIDATE_DEFAULTS].gains);
    if (file_has_gains) {
        memcpy(t->gains, cfg.axis, sizeof t->gains);
        t->tuned = 1;
        cand_met[SIM_CANDIDATE_SCENARIO] = analyse_candidate(sc, id, ws, &targets, &filter);
        cand[SIM_CANDIDATE_SCENARIO] = *t;
    }
    double cost[SIM_N_CANDIDATES];
    char seen[SIM_N_CANDIDATES][280];
    int win = -1;
    for (int c = 0; c < SIM_N_CANDIDATES; ++c) {
        cost[c] = NAN;
        seen[c][0] = '\0';
        if (c == SIM_CANDIDATE_SCENARIO && !file_has_gains) {
            continue;
        }
        *t = cand[c];
        const double flight_start = now_s();
        cost[c] = check_flight(sc, id, seen[c], sizeof seen[c]);
        tuner_s += c == SIM_CANDIDATE_MARGINS ? now_s() - flight_start : 0.0;
        /* One that meets the targets beats one that does not; between
         * equals the check flight decides; ties go to the earlier one. */
        if (cost[c] < INFINITY &&
            (win < 0 || cand_met[c] > cand_met[win] || (cand_met[c] == cand_met[win] && cost[c] < cost[win]))) {
            win = c;
        }
    }
    int rc = met ? SIM_TUNE_OK : SIM_TUNE_MISSED;
    if (cost[SIM_CANDIDATE_MARGINS] == INFINITY) {
        add_reason(why, sizeof why, "%s: %s %s", sim_controller_name(id), NAMES[SIM_CANDIDATE_MARGINS],
                   seen[SIM_CANDIDATE_MARGINS]);
        rc = SIM_TUNE_MISSED;
    }
    if (win < 0) {
        for (int c = SIM_CANDIDATE_DEFAULTS; c < SIM_N_CANDIDATES; ++c) {
            if (!isnan(cost[c])) {
                add_reason(why, sizeof why, "%s %s", NAMES[c], seen[c]);
            }
        }
        win = SIM_CANDIDATE_MARGINS; /* what is reported: the tuner's */
        rc = SIM_TUNE_UNTUNABLE;
    } else if (win != SIM_CANDIDATE_MARGINS) {
        if (cost[SIM_CANDIDATE_MARGINS] < INFINITY) {
            add_reason(why, sizeof why,
                       "%s fly the check flight better than the tuned gains (%.4g against %.4g deg "
                       "RMS summed over the axes)%s",
                       NAMES[win], cost[win], cost[SIM_CANDIDATE_MARGINS],
                       cand_met[win] ? "" : ", neither meeting the targets");
        } else {
            add_reason(why, sizeof why, "%s fly instead (%.4g deg RMS summed over the axes)%s", NAMES[win], cost[win],
                       cand_met[win] ? "" : ", not meeting the targets");
        }
    }
    *t = cand[win];
    memcpy(t->check_cost_deg, cost, sizeof cost);
    memcpy(t->candidate_met, cand_met, sizeof cand_met);
    t->targets_met = cand_met[win];
    t->pm_target_deg = targets.pm_min_deg;
    t->gm_target_db = targets.gm_min_db;
    t->tuned = rc != SIM_TUNE_UNTUNABLE;
    t->by = rc == SIM_TUNE_UNTUNABLE        ? SIM_TUNED_UNTUNABLE
            : win == SIM_CANDIDATE_MARGINS  ? SIM_TUNED_MARGINS
            : win == SIM_CANDIDATE_DEFAULTS ? SIM_TUNED_DEFAULTS
                                            : SIM_TUNED_SCENARIO;
    snprintf(t->reason, sizeof t->reason, "%s", why);
    if (rc != SIM_TUNE_OK) {
        char msg[sizeof err->message];
        snprintf(msg, sizeof msg, "tune = margins: %s%s", rc == SIM_TUNE_UNTUNABLE ? "untunable: " : "", why);
        tune_error(sc, id, err, msg);
    }
    t->wall_s = now_s() - start;
    t->tuner_s = tuner_s;
    return rc;
}

const char *sim_tuned_by_name(sim_tuned_by_t by)
{
    switch (by) {
    case SIM_TUNED_MARGINS:
        return "tuned";
    case SIM_TUNED_DEFAULTS:
        return "defaults";
    case SIM_TUNED_SCENARIO:
        return "scenario";
    case SIM_TUNED_UNTUNABLE:
        return "untunable";
    default:
        return "none";
    }
}
