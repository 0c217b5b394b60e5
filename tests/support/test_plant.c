/* SPDX-License-Identifier: BSD-3-Clause */
#include "test_plant.h"

#include <math.h>
#include <stddef.h>

void test_plant_init(test_double_integrator_t *p, double b, test_disturbance_fn d, const void *ctx)
{
    p->y_rad = 0.0;
    p->rate_rad_s = 0.0;
    p->t_s = 0.0;
    p->b = b;
    p->disturbance = d;
    p->ctx = ctx;
}

static double accel(const test_double_integrator_t *p, double t_s, double u)
{
    const double d = (p->disturbance != NULL) ? p->disturbance(t_s, p->ctx) : 0.0;
    return d + p->b * u;
}

void test_plant_step(test_double_integrator_t *p, double u, double dt_s, int substeps)
{
    const double h = dt_s / substeps;
    for (int i = 0; i < substeps; ++i) {
        const double t = p->t_s;
        const double y = p->y_rad;
        const double v = p->rate_rad_s;
        const double k1y = v;
        const double k1v = accel(p, t, u);
        const double k2y = v + 0.5 * h * k1v;
        const double k2v = accel(p, t + 0.5 * h, u);
        const double k3y = v + 0.5 * h * k2v;
        const double k3v = k2v;
        const double k4y = v + h * k3v;
        const double k4v = accel(p, t + h, u);
        p->y_rad = y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y);
        p->rate_rad_s = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        p->t_s = t + h;
    }
}

double test_sine_disturbance(double t_s, const void *ctx)
{
    const test_sine_t *s = (const test_sine_t *)ctx;
    return s->bias + s->amp * sin(s->w_rad_s * t_s + s->phase_rad);
}

void test_lag_step(double h_s, double tau_s, double u, double *m, double *dy, double *dw)
{
    *dy = 0.5 * h_s * h_s * u;
    *dw = h_s * u;
    if (tau_s > 0.0) {
        const double e = exp(-h_s / tau_s), c = *m - u;
        *dy += c * tau_s * (h_s - tau_s * (1.0 - e));
        *dw += c * tau_s * (1.0 - e);
        *m = u + c * e;
    } else {
        *m = u;
    }
}
