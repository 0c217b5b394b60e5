/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * A small closed loop for the identification tests: per axis a plant
 *   w' = b0 x - a w + c,   x' = (u - x) / tau   (the motors' first-order lag),
 * integrated in substeps with the lag exact and the rate by the trapezoid,
 * a gyro delayed by whole ticks with Gaussian noise, and a P attitude / P
 * rate controller closing the loop; a logarithmic chirp may be added to the
 * command, and the reference may manoeuvre (a sine and a square wave).
 */
#ifndef LADRC_SIM_TEST_IDENT_LOOP_H
#define LADRC_SIM_TEST_IDENT_LOOP_H

#include <math.h>

#include "plant/rng.h"

#define LOOP_PI 3.14159265358979323846
#define LOOP_HISTORY 64 /* ticks of delay the loop can hold */
#define LOOP_SUBSTEPS 20

typedef struct {
    double b0, tau_s, damping_per_s, bias_rad_s2; /* the plant */
    int delay_ticks;
    double noise_rad_s;                      /* gyro noise std */
    double chirp_amp, f0_hz, f1_hz, chirp_s; /* chirp on the command from t = 0 (amp 0: none) */
    double manoeuvre_rad;                    /* reference amplitude (0: hover) */
} loop_axis_t;

typedef struct {
    loop_axis_t ax;
    double dt_s, kp_att, kp_rate;
    double w, x, angle;
    double setpoint_rad_s; /* the rate setpoint of the last tick (the angle loop's output) */
    double hist_w[LOOP_HISTORY], hist_angle[LOOP_HISTORY];
    long k;
    sim_rng_t rng;
} loop_t;

static void loop_init(loop_t *l, const loop_axis_t *ax, double dt_s, uint64_t seed)
{
    *l = (loop_t){.ax = *ax, .dt_s = dt_s};
    /* gains that keep the loop well damped whatever the lag and delay */
    l->kp_rate = 1.0 / (3.0 * ax->tau_s + 3.0 * (ax->delay_ticks + 1) * dt_s);
    l->kp_att = l->kp_rate / 5.0;
    sim_rng_seed(&l->rng, seed);
}

static double loop_chirp(const loop_axis_t *ax, double t)
{
    if (!(ax->chirp_amp > 0.0) || t >= ax->chirp_s) {
        return 0.0;
    }
    const double lr = log(ax->f1_hz / ax->f0_hz);
    return ax->chirp_amp * sin(2.0 * LOOP_PI * ax->f0_hz * ax->chirp_s / lr * (exp(t * lr / ax->chirp_s) - 1.0));
}

/* One tick: the gyro and command a log would hold. */
static void loop_tick(loop_t *l, double *gyro_rad_s, double *command)
{
    const loop_axis_t *ax = &l->ax;
    const double t = l->k * l->dt_s;
    const int now = (int)(l->k % LOOP_HISTORY),
              then = (int)((l->k - ax->delay_ticks + LOOP_HISTORY * 1000L) % LOOP_HISTORY);
    l->hist_w[now] = l->w;
    l->hist_angle[now] = l->angle;
    const double gyro = l->hist_w[then] + ax->noise_rad_s * sim_rng_gauss(&l->rng);
    const double ref = ax->manoeuvre_rad * (sin(2.0 * LOOP_PI * 0.7 * t) + 0.5 * (((long)(t / 1.3)) % 2 ? 1.0 : -1.0));
    l->setpoint_rad_s = l->kp_att * (ref - l->hist_angle[then]);
    const double u = l->kp_rate * (l->setpoint_rad_s - gyro) / ax->b0 + loop_chirp(ax, t);
    const double h = l->dt_s / LOOP_SUBSTEPS, alpha = exp(-h / ax->tau_s);
    for (int s = 0; s < LOOP_SUBSTEPS; ++s) {
        const double x_next = alpha * l->x + (1.0 - alpha) * u;
        const double accel = ax->b0 * 0.5 * (l->x + x_next) - ax->damping_per_s * l->w + ax->bias_rad_s2;
        const double w_next = l->w + h * accel;
        l->angle += h * 0.5 * (l->w + w_next);
        l->w = w_next;
        l->x = x_next;
    }
    l->k++;
    *gyro_rad_s = gyro;
    *command = u;
}

#endif
