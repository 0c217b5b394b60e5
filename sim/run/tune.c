/* SPDX-License-Identifier: BSD-3-Clause */
#define _POSIX_C_SOURCE 200809L
/* tune = margins (see tune.h). */
#include "tune.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "run/runner.h"
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

static void keep(sim_tuning_t *t, int i, const ladrc_axis_config_t *tuned, const ladrc_margins_tuning_t *r, int idle)
{
    t->gains[i] = *tuned;
    t->pm_deg[i] = r->margins.pm_deg;
    t->gm_db[i] = r->margins.gm_db;
    t->gm_low_db[i] = r->margins.gm_low_db;
    t->crossover_rad_s[i] = r->margins.wc_rad_s;
    t->ms[i] = r->margins.ms;
    t->step_cost_rad2_s[i] = r->step_cost_rad2_s;
    t->idle[i] = idle;
}

static void copy_axis(sim_tuning_t *t, int to, int from)
{
    t->gains[to] = t->gains[from];
    t->pm_deg[to] = t->pm_deg[from];
    t->gm_db[to] = t->gm_db[from];
    t->gm_low_db[to] = t->gm_low_db[from];
    t->crossover_rad_s[to] = t->crossover_rad_s[from];
    t->ms[to] = t->ms[from];
    t->step_cost_rad2_s[to] = t->step_cost_rad2_s[from];
    t->idle[to] = t->idle[from];
    t->shared[to] = 1;
}

/* The targets of ladrc_margins_tune: stable, PM and both gain margins. */
static int meets(const ladrc_margins_result_t *m, const ladrc_margins_targets_t *tg)
{
    return m->stable && m->pm_deg >= tg->pm_min_deg && m->gm_db >= tg->gm_min_db && m->gm_low_db <= -tg->gm_min_db;
}

int sim_tune_controller(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                        sim_parse_error_t *err)
{
    sim_tuning_t *t = &sc->tuning[id];
    memset(t, 0, sizeof *t);
    if (!sim_tune_wanted(sc, id)) {
        return 0;
    }
    const double start = now_s();
    const sim_overrides_t *o = &sc->overrides[id];
    const ladrc_margins_targets_t targets = {
        .pm_min_deg = isnan(o->tune_pm_deg) ? SIM_TUNE_PM_DEG_DEFAULT : o->tune_pm_deg,
        .gm_min_db = isnan(o->tune_gm_db) ? SIM_TUNE_GM_DB_DEFAULT : o->tune_gm_db};
    t->pm_target_deg = targets.pm_min_deg;
    t->gm_target_db = targets.gm_min_db;
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(sc, id, &acfg); /* tuning[id] is clear: the defaults and the file's keys */
    sim_tune_filter_t filter;
    sim_tune_filter(sc, &filter);
    for (int i = 0; i < 3; ++i) {
        ladrc_margins_plant_t plant;
        sim_tune_plant(sc, i, &plant);
        ladrc_margins_request_t req;
        ladrc_margins_request_default(&req, &plant);
        sim_tune_objective(sc, id, &req);
        /* Roll and pitch of a symmetric airframe are the same loop: pitch
         * takes roll's gains when its own analysis with them meets the
         * targets (an adaptive variant's linearisation under the tone may
         * differ between the two), else it is tuned itself. */
        if (i == 1 && plant.inertia_kg_m2 == sc->inertia_kg_m2[0] * sc->inertia_scale[0]) {
            ladrc_attitude_config_t shared = acfg;
            sim_setup_tuned_gains(t, 0, &shared.axis[1]);
            const ladrc_margins_controller_t chk = sim_tune_controller_of(sc, &filter, &shared, 1);
            int idle = 0;
            ladrc_margins_result_t *m = &ws->scratch;
            if (ladrc_margins_analyse_reported(ws, &chk, &req, m, &idle) == LADRC_MARGINS_OK && meets(m, &targets)) {
                copy_axis(t, 1, 0);
                t->pm_deg[1] = m->pm_deg;
                t->gm_db[1] = m->gm_db;
                t->gm_low_db[1] = m->gm_low_db;
                t->crossover_rad_s[1] = m->wc_rad_s;
                t->ms[1] = m->ms;
                t->idle[1] = idle;
                continue;
            }
        }
        const ladrc_margins_controller_t ctl = sim_tune_controller_of(sc, &filter, &acfg, i);
        ladrc_axis_config_t tuned;
        ladrc_margins_tuning_t result;
        const ladrc_margins_status_t st = ladrc_margins_tune(ws, &ctl, &req, &targets, &tuned, &result);
        int idle = 0;
        if (st == LADRC_MARGINS_OK || st == LADRC_MARGINS_ERR_TARGETS_NOT_MET) {
            /* whether the reported margins are HP-MLADRC's idle ones */
            ladrc_attitude_config_t again = acfg;
            again.axis[i] = tuned;
            const ladrc_margins_controller_t chk = sim_tune_controller_of(sc, &filter, &again, i);
            (void)ladrc_margins_analyse_reported(ws, &chk, &req, &ws->scratch, &idle);
        }
        keep(t, i, &tuned, &result, idle);
        char msg[256];
        if (st == LADRC_MARGINS_ERR_TARGETS_NOT_MET) {
            const ladrc_margins_result_t *m = &result.margins;
            snprintf(msg, sizeof msg,
                     "tune = margins: %s on %s cannot meet PM >= %g deg, GM >= %g dB; best reached: %s, "
                     "PM %.1f deg, GM %.1f dB, lower GM %.1f dB",
                     sim_controller_name(id), AXIS_NAMES[i], targets.pm_min_deg, targets.gm_min_db,
                     m->stable ? "stable" : "UNSTABLE", m->pm_deg, m->gm_db, m->gm_low_db);
            tune_error(sc, id, err, msg);
            return -1;
        }
        if (st != LADRC_MARGINS_OK) {
            snprintf(msg, sizeof msg, "tune = margins: %s on %s: the analysis failed: %s", sim_controller_name(id),
                     AXIS_NAMES[i], ladrc_margins_status_str(st));
            tune_error(sc, id, err, msg);
            return -1;
        }
    }
    t->tuned = 1;
    t->wall_s = now_s() - start;
    /* The library takes the tuned gains (the parser checked the defaults). */
    sim_setup_attitude(sc, id, &acfg);
    ladrc_attitude_t att;
    const ladrc_status_t st = ladrc_attitude_init(&att, &acfg, NULL);
    if (st != LADRC_OK) {
        char msg[256];
        snprintf(msg, sizeof msg, "tune = margins: %s does not start with the tuned gains: %s", sim_controller_name(id),
                 ladrc_status_str(st));
        t->tuned = 0;
        tune_error(sc, id, err, msg);
        return -1;
    }
    /* Margins are those of a small-angle loop on the modelled airframe: the
     * scenario flown whole (its disturbances may start late) before the
     * gains are accepted. Deterministic: the run that follows flies the same.
     * The messages read "NAME on AXIS: ..." as the others (tools/suite.sh). */
    sim_metrics_t m;
    char run_err[160] = "";
    if (sim_run_attitude(sc, id, NULL, NULL, &m, run_err, sizeof run_err) != 0) {
        char msg[256];
        snprintf(msg, sizeof msg, "tune = margins: %s: the check flight with the tuned gains failed: %s",
                 sim_controller_name(id), run_err);
        t->tuned = 0;
        tune_error(sc, id, err, msg);
        return -1;
    }
    if (m.diverged) {
        char msg[256];
        if (m.diverged_axis >= 0 && m.diverged_axis < 3 && !isnan(m.diverged_error_deg)) {
            snprintf(msg, sizeof msg,
                     "tune = margins: %s on %s: the tuned gains diverge at %.3f s of the check flight "
                     "(|error| %.1f deg beyond %g deg)",
                     sim_controller_name(id), AXIS_NAMES[m.diverged_axis], m.diverged_at_s, m.diverged_error_deg,
                     sc->diverge_limit_deg);
        } else if (m.diverged_axis >= 0 && m.diverged_axis < 3) {
            snprintf(msg, sizeof msg,
                     "tune = margins: %s on %s: the tuned gains diverge at %.3f s of the check flight "
                     "(its state turned non-finite)",
                     sim_controller_name(id), AXIS_NAMES[m.diverged_axis], m.diverged_at_s);
        } else {
            snprintf(msg, sizeof msg,
                     "tune = margins: %s on the rotors: the tuned gains diverge at %.3f s of the check flight "
                     "(a rotor's state turned non-finite)",
                     sim_controller_name(id), m.diverged_at_s);
        }
        t->tuned = 0;
        tune_error(sc, id, err, msg);
        return -1;
    }
    t->wall_s = now_s() - start;
    return 0;
}
