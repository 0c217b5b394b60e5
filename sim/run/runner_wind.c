/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The wind of a group's runs (runner_parts.h): the steady wind plus the
 * Dryden gusts (plant/turbulence.h), at a plant step's stage times, in
 * north-east-down axes. Every run of a scenario meets the same air: the
 * field is seeded from the scenario's seed, apart from the sensor noise's.
 */
#include <math.h>

#include "runner_parts.h"

/* The gusts' own stream: another seed than the sensor's. */
#define WIND_SEED_SALT 0x57494e44ULL /* "WIND" */

int runner_wind_open(wind_field_t *w, const sim_scenario_t *sc)
{
    w->on = sc->turbulence != SIM_TURB_OFF || sc->mean_wind_m_s > 0.0;
    if (!w->on) {
        return 0;
    }
    /* the air moves towards the heading opposite to where it comes from */
    const double to_rad = sc->mean_wind_from_rad + 3.14159265358979323846;
    w->along[0] = cos(to_rad);
    w->along[1] = sin(to_rad);
    w->mean_m_s = sc->mean_wind_m_s;
    w->gusts = sc->turbulence != SIM_TURB_OFF;
    if (!w->gusts) {
        return 0;
    }
    const sim_turb_config_t cfg = {.level = (sim_turb_level_t)sc->turbulence,
                                   .sigma_m_s = sc->turb_sigma_m_s,
                                   .altitude_m = sc->altitude_m,
                                   .mean_wind_m_s = sc->mean_wind_m_s,
                                   .sample_dt_s = sc->control_dt_s};
    return sim_turb_init(&w->turb, &cfg, sc->seed ^ WIND_SEED_SALT);
}

void runner_wind_at(wind_field_t *w, const double *t_s, int n, double (*wind_m_s)[3])
{
    for (int k = 0; k < n; ++k) {
        double gust[3] = {0.0, 0.0, 0.0}; /* along, across, down */
        if (w->gusts) {
            sim_turb_gust_at(&w->turb, t_s[k], gust);
        }
        const double along = w->mean_m_s + gust[0];
        wind_m_s[k][0] = along * w->along[0] - gust[1] * w->along[1];
        wind_m_s[k][1] = along * w->along[1] + gust[1] * w->along[0];
        wind_m_s[k][2] = gust[2];
    }
}
