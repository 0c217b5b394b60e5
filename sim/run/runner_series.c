/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The recorded series of a group's runs (runner_parts.h): the files the
 * parser checked, read once per group and shared read-only by its runs.
 */
#include <stdio.h>
#include <string.h>

#include "runner_parts.h"

static int open_one(sim_series_t *s, int *has, const char *path, sim_dim_t dim, int interp, int end, char *err,
                    size_t err_len)
{
    *has = path[0] != '\0';
    if (!*has) {
        return 0;
    }
    const sim_series_spec_t spec = {
        .dim = dim, .key = NULL, .interp = (sim_series_interp_t)interp, .end = (sim_series_end_t)end};
    sim_series_error_t e;
    if (sim_series_load(s, path, &spec, &e) != 0) {
        snprintf(err, err_len, "%s:%d:%d: %s", e.path, e.line, e.column, e.message);
        *has = 0;
        return -1;
    }
    return 0;
}

int runner_recorded_open(recorded_t *r, const sim_scenario_t *sc, char *err, size_t err_len)
{
    memset(r, 0, sizeof *r);
    if (open_one(&r->dist, &r->has_dist, sc->dist_series, SIM_DIM_ANG_ACCEL, sc->dist_series_interp,
                 sc->dist_series_end, err, err_len) != 0 ||
        open_one(&r->ref, &r->has_ref, sc->ref_series, SIM_DIM_ANGLE, sc->ref_series_interp, sc->ref_series_end, err,
                 err_len) != 0 ||
        open_one(&r->rate, &r->has_rate, sc->rate_noise_series, SIM_DIM_ANG_RATE, sc->noise_series_interp,
                 sc->noise_series_end, err, err_len) != 0 ||
        open_one(&r->angle, &r->has_angle, sc->angle_noise_series, SIM_DIM_ANGLE, sc->noise_series_interp,
                 sc->noise_series_end, err, err_len) != 0) {
        runner_recorded_close(r);
        return -1;
    }
    return 0;
}

void runner_recorded_close(recorded_t *r)
{
    sim_series_free(&r->dist);
    sim_series_free(&r->ref);
    sim_series_free(&r->rate);
    sim_series_free(&r->angle);
    r->has_dist = r->has_ref = r->has_rate = r->has_angle = 0;
}

void runner_recorded_add(const sim_series_t *s, sim_series_cursor_t *cursor, double t_s, double v[3])
{
    double x[SIM_SERIES_MAX_COLS];
    sim_series_eval(s, cursor, t_s, x);
    for (int i = 0; i < 3 && i < SIM_SERIES_MAX_COLS; ++i) {
        v[i] += x[i];
    }
}
