/* SPDX-License-Identifier: BSD-3-Clause */
/* The tuner's time-domain objective: the squared angle error of the
 * controller as it flies, integrated through a reference step and then a
 * disturbance step on the sampled plant with its lag and delay
 * (docs/margins.md). It weighs tracking, which the disturbance response of
 * the frequency-domain search is blind to, and it is the suite's own measure
 * (RMS error squared, times the time flown). */
#include "margins_internal.h"

#include <math.h>

ladrc_margins_status_t ladrc_margins_step_cost(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                               const ladrc_margins_request_t *req, double *cost)
{
    if (ws == NULL || ctl == NULL || req == NULL || cost == NULL)
        return LADRC_MARGINS_ERR_NULL;
    ladrc_margins_status_t st = margins_check_request(req);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (!margins_ctl_names_axis(ctl))
        return LADRC_MARGINS_ERR_CONTROLLER;
    const double dt = req->plant.dt_s;
    if (fabs((double)margins_ctl_axis_config(ctl)->dt_s - dt) > 1e-6 * dt)
        return LADRC_MARGINS_ERR_DT_S;
    ctl_state_t *s = (ctl_state_t *)(void *)ws->copy;
    st = margins_ctl_init(ctl, &s[0]);
    if (st != LADRC_MARGINS_OK)
        return st;
    dplant_t dp;
    margins_discretise(&req->plant, &dp);
    psim_t ps;
    psim_reset(&ps);
    const long window = (long)(req->step_window_s / dt + 0.5);
    const double ref = req->track_step_rad;
    double ise = 0.0;
    for (long k = 0; k < 2 * window; ++k) {
        double y, r;
        psim_measure(&ps, &dp, &y, &r);
        const double u = margins_ctl_step(ctl, &s[0], ref, y, r);
        psim_step(&ps, &dp, u, k >= window ? req->dist_step_rad_s2 : 0.0);
        const double e = ref - ps.x[0];
        if (!(fabs(e) < DIVERGED_RAD)) {
            *cost = INFINITY;
            return LADRC_MARGINS_OK;
        }
        ise += e * e * dt;
    }
    *cost = ise;
    return LADRC_MARGINS_OK;
}
