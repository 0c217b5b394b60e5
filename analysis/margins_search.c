/* SPDX-License-Identifier: BSD-3-Clause */
/* The margin searches: the largest stable motor lag and sensor delay, and
 * the simulated check of a loop's stability. */
#include "margins_internal.h"

#include <math.h>

/* Simulated check: an angle below this share of its peak has decayed to
 * the float controller's rounding. */
#define SIM_DECAYED 1e-6

ladrc_margins_status_t ladrc_margins_max_motor_tau(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                                   double tau_max_s, double *tau_s)
{
    if (tau_s == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    const ladrc_margins_status_t st = margins_make_loop(ws, plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (!(tau_max_s > 0.0 && isfinite(tau_max_s)))
        return LADRC_MARGINS_ERR_MOTOR_TAU;
    ladrc_margins_plant_t p = *plant;
    p.motor_tau_s = 0.0;
    if (!ladrc_margins_is_stable(ws, &p)) {
        *tau_s = 0.0;
        return LADRC_MARGINS_OK;
    }
    /* The first unstable lag by doubling from a tenth of a tick, then bisection. */
    double lo = 0.0, hi = 0.1 * plant->dt_s;
    for (;;) {
        p.motor_tau_s = hi;
        if (!ladrc_margins_is_stable(ws, &p))
            break;
        lo = hi;
        if (hi >= tau_max_s) {
            *tau_s = tau_max_s;
            return LADRC_MARGINS_OK;
        }
        hi = fmin(2.0 * hi, tau_max_s);
    }
    while (hi - lo > 1e-3 * hi) {
        p.motor_tau_s = 0.5 * (lo + hi);
        if (ladrc_margins_is_stable(ws, &p)) {
            lo = p.motor_tau_s;
        } else {
            hi = p.motor_tau_s;
        }
    }
    *tau_s = lo;
    return LADRC_MARGINS_OK;
}

/* Delays ladrc_margins_max_delay tries one by one (the range of earlier releases). */
#define MAX_DELAY_SCAN 64

ladrc_margins_status_t ladrc_margins_max_delay(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                               int *ticks)
{
    if (ticks == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    const ladrc_margins_status_t st = margins_make_loop(ws, plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    ladrc_margins_plant_t p = *plant;
    *ticks = -1;
    /* Every delay up to MAX_DELAY_SCAN (the first unstable one ends it, as
     * always); past it, up to LADRC_MARGINS_MAX_DELAY (hundreds of ticks:
     * 50 ms at 8 kHz), doubling then bisecting: about 2 log2 d verdicts,
     * taking the loop as stable below one delay and unstable above it. */
    int d = 0;
    for (; d <= MAX_DELAY_SCAN; ++d) {
        p.delay_ticks = d;
        if (!ladrc_margins_is_stable(ws, &p))
            return LADRC_MARGINS_OK;
        *ticks = d;
    }
    int lo = MAX_DELAY_SCAN, hi = LADRC_MARGINS_MAX_DELAY + 1; /* stable at lo; hi unstable or past the range */
    for (d = 2 * MAX_DELAY_SCAN; d < hi; d *= 2) {
        p.delay_ticks = d;
        if (!ladrc_margins_is_stable(ws, &p)) {
            hi = d;
            break;
        }
        lo = d;
    }
    while (hi - lo > 1) {
        p.delay_ticks = lo + (hi - lo) / 2;
        if (ladrc_margins_is_stable(ws, &p)) {
            lo = p.delay_ticks;
        } else {
            hi = p.delay_ticks;
        }
    }
    *ticks = lo;
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_simulate(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                              const ladrc_margins_plant_t *plant, long n_ticks, double *growth)
{
    if (ws == NULL || ctl == NULL || plant == NULL || growth == NULL)
        return LADRC_MARGINS_ERR_NULL;
    ladrc_margins_status_t st = margins_check_plant(plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    if ((ctl->attitude == NULL) == (ctl->axis == NULL) || n_ticks < 64)
        return LADRC_MARGINS_ERR_REQUEST;
    ctl_state_t *s = (ctl_state_t *)(void *)ws->copy;
    st = margins_ctl_init(ctl, &s[0]);
    if (st != LADRC_MARGINS_OK)
        return st;
    dplant_t dp;
    margins_discretise(plant, &dp);
    psim_t ps;
    psim_reset(&ps);
    /* A 10 ms pulse of 1 rad/s^2: a small step of the rate, all frequencies excited. */
    const long pulse = (long)(0.01 / plant->dt_s + 0.5) + 1;
    double third = 0.0, last = 0.0, peak = 0.0;
    for (long k = 0; k < n_ticks; ++k) {
        double y, r;
        psim_measure(&ps, &dp, &y, &r);
        const double u = margins_ctl_step(ctl, &s[0], 0.0, y, r);
        psim_step(&ps, &dp, u, k < pulse ? 1.0 : 0.0);
        const double a = fabs(ps.x[0]);
        if (!(a < DIVERGED_RAD)) {
            /* From a 1e-5 rad pulse response: diverged (beyond, the torque
             * limits would turn the growth into a bounded limit cycle). */
            last = INFINITY;
            break;
        }
        peak = fmax(peak, a);
        if (k >= n_ticks / 2 && k < n_ticks - n_ticks / 4)
            third = fmax(third, a);
        if (k >= n_ticks - n_ticks / 4)
            last = fmax(last, a);
    }
    /* Consecutive quarters: in the end the slowest mode dominates, growing
     * (> 1) or decaying (< 1); a response decayed to the float controller's
     * rounding (1e-7 of its peak) counts as decayed whatever its ratio. */
    const double floor_level = SIM_DECAYED * peak;
    *growth = (last <= floor_level) ? 0.0 : last / fmax(third, floor_level);
    return LADRC_MARGINS_OK;
}
