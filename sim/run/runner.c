/* SPDX-License-Identifier: BSD-3-Clause */
#define _POSIX_C_SOURCE 200809L
/* The runs of one scenario (runner.h): the lockstep group's steps and the
 * attitude entry points (runner_parts.h lists the other parts). */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "runner_parts.h"

/* A group's plants step side by side (sim_plant_step_group). */
typedef char plant_group_fits_t[SIM_MAX_CONTROLLERS <= SIM_PLANT_GROUP_MAX ? 1 : -1];

long sim_run_ticks(const sim_scenario_t *sc)
{
    return (long)floor(sc->duration_s / sc->control_dt_s + 0.5);
}

double runner_wall_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void widen(const ladrc_real_t x[3], double out[3])
{
    for (int i = 0; i < 3; ++i) {
        out[i] = (double)x[i];
    }
}

/* A lockstep group of runs on one scenario (sim_run_attitude_group). */
typedef struct {
    const sim_scenario_t *sc;
    sim_run_spec_t *runs;
    attitude_run_t run[SIM_MAX_CONTROLLERS];
    int n;                     /* runs in the group */
    int n_flying;              /* of them, flying */
    instants_t at;             /* the control instants' references and disturbances */
    disturbance_batch_t batch; /* the disturbances of a plant step */
    wind_field_t wind;         /* the air they all meet */
    double wind_stage[STAGES_MAX][3];
    recorded_t rec;                               /* the recorded series they fly */
    sim_series_cursor_t dist_cur, dist_stage_cur; /* the disturbance's, at the instants and the stages */
    sim_series_cursor_t ref_cur;                  /* the reference series', at the instants */
} group_t;

/* The recorded reference series (rad) added to the references at t, rounded
 * to ladrc_real_t as the controllers get them. */
static void add_reference_series(const recorded_t *rec, sim_series_cursor_t *cur, double t, ladrc_real_t ref[3])
{
    if (!rec->has_ref) {
        return;
    }
    double add[3] = {0.0, 0.0, 0.0};
    runner_recorded_add(&rec->ref, cur, t, add);
    for (int i = 0; i < 3; ++i) {
        ref[i] = (ladrc_real_t)((double)ref[i] + add[i]);
    }
}

/* Every started run refused with err (it does not fly; its files closed). */
static void group_refuse(group_t *g, const char *err)
{
    for (int k = 0; k < g->n; ++k) {
        if (g->runs[k].rc == 0) {
            (void)runner_run_close(g->sc, &g->run[k]);
            snprintf(g->runs[k].err, g->runs[k].err_len, "%s", err);
            g->runs[k].rc = -1;
            g->run[k].flying = 0;
            --g->n_flying;
        }
    }
}

/* Opens every run (those beyond SIM_MAX_CONTROLLERS fail). */
static void group_open(group_t *g, const sim_scenario_t *sc, sim_run_spec_t *runs, int n_runs)
{
    g->sc = sc;
    g->runs = runs;
    g->n_flying = 0;
    for (int k = 0; k < n_runs && k < SIM_MAX_CONTROLLERS; ++k) {
        runs[k].rc = runner_run_open(sc, &g->run[k], &runs[k]);
        g->n_flying += runs[k].rc == 0;
    }
    for (int k = SIM_MAX_CONTROLLERS; k < n_runs; ++k) {
        snprintf(runs[k].err, runs[k].err_len, "%s: more than %d runs in one group", sc->path, SIM_MAX_CONTROLLERS);
        runs[k].rc = -1;
    }
    g->n = n_runs < SIM_MAX_CONTROLLERS ? n_runs : SIM_MAX_CONTROLLERS;
    char err[SIM_PATH_LEN + 320];
    if (runner_wind_open(&g->wind, sc) != 0) {
        snprintf(err, sizeof err, "%s: bad [wind] settings", sc->path);
        group_refuse(g, err);
    }
    sim_series_cursor_init(&g->dist_cur);
    sim_series_cursor_init(&g->dist_stage_cur);
    sim_series_cursor_init(&g->ref_cur);
    if (runner_recorded_open(&g->rec, sc, err, sizeof err) != 0) {
        group_refuse(g, err);
    }
    for (int k = 0; k < g->n; ++k) {
        g->run[k].rec = &g->rec;
        sim_series_cursor_init(&g->run[k].rate_cur);
        sim_series_cursor_init(&g->run[k].angle_cur);
    }
    runner_disturbance_batch_init(&g->batch, sc);
    g->at.first = g->at.n = 0;
}

/* Every flying run's controller at tick k of n_ticks, its rotors' command
 * into w2_cmd; returns the first run still flying (its plant leads the
 * step), NULL when none is. */
static const sim_plant_t *group_control(group_t *g, long k, long n_ticks, double w2_cmd[][4])
{
    if (k - g->at.first >= g->at.n) {
        runner_instants_fill(&g->at, g->sc, k, n_ticks);
    }
    const int j = (int)(k - g->at.first);
    const double t = g->at.t_s[j];
    /* the references rounded to ladrc_real_t where they are worked out, in
     * instants_fill: GCC 12 turns a float rounding and the widening back,
     * side by side in one loop and vectorized, into no rounding at all */
    ladrc_real_t ref[3];
    double ref_rad[3], dist[3];
    for (int i = 0; i < 3; ++i) {
        ref[i] = g->at.ref[i][j];
        dist[i] = g->at.dist[i][j];
    }
    if (g->rec.has_dist) {
        runner_recorded_add(&g->rec.dist, &g->dist_cur, t, dist);
    }
    add_reference_series(&g->rec, &g->ref_cur, t, ref);
    widen(ref, ref_rad);
    const sim_plant_t *lead = NULL; /* the plants' times are the same bits */
    for (int q = 0; q < g->n; ++q) {
        attitude_run_t *r = &g->run[q];
        if (r->flying && !runner_run_tick(g->sc, r, t, ref, ref_rad, dist, w2_cmd[q])) {
            r->flying = 0; /* diverged: it stops here */
            --g->n_flying;
        }
        if (r->flying && lead == NULL) {
            lead = &r->plant;
        }
    }
    return lead;
}

/* The flying runs' plants through one control period, side by side, the
 * step's disturbances read from one batch: they are all at the lead's time
 * (they have flown every step together), but should one not be, every
 * plant asks for its own. */
static void group_step_plants(group_t *g, const sim_plant_t *lead, const double w2_cmd[][4])
{
    const sim_scenario_t *sc = g->sc;
    const double dt = sc->control_dt_s;
    runner_disturbance_batch_fill(&g->batch, lead, dt, sc->plant_substeps);
    for (int k = 0; g->rec.has_dist && k < g->batch.n; ++k) {
        runner_recorded_add(&g->rec.dist, &g->dist_stage_cur, g->batch.t_s[k], g->batch.stage[k]);
    }
    sim_plant_t *plants[SIM_MAX_CONTROLLERS];
    double cmds[SIM_MAX_CONTROLLERS][4];
    int n_plants = 0;
    for (int q = 0; q < g->n; ++q) {
        if (g->run[q].flying) {
            plants[n_plants] = &g->run[q].plant;
            memcpy(cmds[n_plants++], w2_cmd[q], sizeof cmds[0]);
        }
    }
    int same_time = 1;
    for (int q = 1; q < n_plants; ++q) {
        same_time = same_time && memcmp(&plants[q]->t_s, &lead->t_s, sizeof lead->t_s) == 0;
    }
    if (g->batch.n > 0 && same_time) {
        if (g->wind.on) {
            runner_wind_at(&g->wind, g->batch.t_s, g->batch.n, g->wind_stage);
        }
        (void)sim_plant_step_group_air(plants, (const double(*)[4])cmds, n_plants, dt, sc->plant_substeps,
                                       (const double(*)[3])g->batch.stage,
                                       g->wind.on ? (const double(*)[3])g->wind_stage : NULL);
    } else { /* never with wind or a recorded disturbance: the parser keeps substeps within the table, and
              * the plants fly together */
        batch_reader_t reader = {.b = &g->batch, .next = 0};
        sim_plant_step_group(plants, (const double(*)[4])cmds, n_plants, dt, sc->plant_substeps, runner_read_batch,
                             &reader);
    }
}

/* The state the last step left, at t = duration (n_ticks periods), checked
 * for divergence like every tick's. */
static void group_check_end(group_t *g, long n_ticks)
{
    const sim_scenario_t *sc = g->sc;
    const double t = (double)n_ticks * sc->control_dt_s;
    sim_expr_memo_t memo;
    sim_expr_memo_clear(&memo);
    ladrc_real_t ref[3];
    double ref_rad[3];
    runner_references(sc, t, &memo, ref);
    add_reference_series(&g->rec, &g->ref_cur, t, ref);
    widen(ref, ref_rad);
    for (int q = 0; q < g->n; ++q) {
        if (g->run[q].flying) {
            (void)runner_diverged(sc, &g->run[q].plant, ref_rad, g->run[q].wrap_yaw, t,
                                  g->run[q].bf != NULL ? NULL : &g->run[q].att, g->runs[q].metrics);
        }
    }
}

/* Closes every run that started; each gets the group's wall time. */
static void group_close(group_t *g, double wall_s)
{
    for (int q = 0; q < g->n; ++q) {
        if (g->runs[q].rc == 0) {
            g->runs[q].metrics->wall_s = wall_s;
            g->runs[q].rc = runner_run_close(g->sc, &g->run[q]);
        }
    }
    runner_recorded_close(&g->rec);
}

void sim_run_attitude_group(const sim_scenario_t *sc, sim_run_spec_t *runs, int n_runs, const sim_progress_t *progress)
{
    group_t g;
    group_open(&g, sc, runs, n_runs);
    const double start = runner_wall_now_s();
    const long n = sim_run_ticks(sc);
    long k = 0;
    for (; k < n && g.n_flying > 0; ++k) {
        double w2_cmd[SIM_MAX_CONTROLLERS][4];
        const sim_plant_t *lead = group_control(&g, k, n, w2_cmd);
        if (lead == NULL) {
            break;
        }
        group_step_plants(&g, lead, (const double(*)[4])w2_cmd);
        if (progress != NULL && progress->ticks_done != NULL && (k & 1023) == 1023) {
            *progress->ticks_done += 1024L * g.n_flying;
        }
    }
    if (k == n) {
        group_check_end(&g, n);
    }
    group_close(&g, runner_wall_now_s() - start);
}

int sim_run_attitude(const sim_scenario_t *sc, sim_controller_id_t ctrl, const char *csv_path,
                     const sim_progress_t *progress, sim_metrics_t *m, char *err, size_t err_len)
{
    sim_run_spec_t spec = {.ctrl = ctrl, .csv_path = csv_path, .metrics = m, .err = err, .err_len = err_len, .rc = 0};
    sim_run_attitude_group(sc, &spec, 1, progress);
    return spec.rc;
}
