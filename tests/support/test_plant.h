/* SPDX-License-Identifier: BSD-3-Clause */
/* Small plants simulated inside the tests, in double precision so the
 * reference never limits what a test can resolve. */
#ifndef LADRC_TEST_PLANT_H
#define LADRC_TEST_PLANT_H

/* Disturbance acceleration d(t) in rad/s^2. */
typedef double (*test_disturbance_fn)(double t_s, const void *ctx);

/* y'' = d(t) + b * u, u held constant over each control step (zero-order hold). */
typedef struct {
    double y_rad;
    double rate_rad_s;
    double t_s;
    double b; /* rad/s^2 per unit of u */
    test_disturbance_fn disturbance;
    const void *ctx;
} test_double_integrator_t;

void test_plant_init(test_double_integrator_t *p, double b, test_disturbance_fn d, const void *ctx);

/* Advances by dt_s with `substeps` RK4 steps; exact for constant d with substeps = 1. */
void test_plant_step(test_double_integrator_t *p, double u, double dt_s, int substeps);

/* Sinusoidal disturbance bias + amp * sin(w t + phase). */
typedef struct {
    double bias;
    double amp;
    double w_rad_s;
    double phase_rad;
} test_sine_t;

double test_sine_disturbance(double t_s, const void *ctx);

/* One step h (s) of a unit torque through a first-order motor lag tau (s,
 * 0 = none), exactly for u held over the step: the acting torque m (in: at
 * the step's start; out: at its end) and the increments of the velocity,
 * dw = integral of m, and of the angle, dy = double integral, per unit of
 * 1/J. y'' = m / J + d then steps as y += w h + dy / J + d h^2 / 2,
 * w += dw / J + d h. */
void test_lag_step(double h_s, double tau_s, double u, double *m, double *dy, double *dw);

#endif
