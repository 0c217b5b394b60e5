/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The stability-margin analysis's parts, internal to it (ladrc/margins.h is
 * the interface, docs/margins.md the method):
 *   margins_status.c   the status texts;
 *   margins_plant.c    the sampled plant: checks, exact discretisation,
 *                      frequency response;
 *   margins_measure.c  the controller in closed loop on that plant and its
 *                      measured response (impulse, tail fit, FFT);
 *   margins_loop.c     the Nyquist contour and the margins of a loop;
 *   margins_search.c   the largest stable motor lag and sensor delay, and the
 *                      simulated check;
 *   margins_steps.c    the tuner's time-domain objective (reference and
 *                      disturbance steps on the sampled plant);
 *   margins_noise.c    the command noise a loop predicts;
 *   margins_tune.c     the margins-based tuner.
 * Double precision; no heap, no stdio.
 */
#ifndef LADRC_MARGINS_INTERNAL_H
#define LADRC_MARGINS_INTERNAL_H

#include "ladrc/margins.h"

#include <complex.h>
#include <string.h>

typedef double complex cplx;

#define PI 3.14159265358979323846
#define N_FFT LADRC_MARGINS_MAX_TAPS
#define N_HALF (LADRC_MARGINS_MAX_TAPS / 2)

/* Divergence of a converged run: beyond a radian the small-angle loop is
 * meaningless. */
#define DIVERGED_RAD 1.0
/* The objective's window: within a minute of simulated flight (s). */
#define STEP_WINDOW_MAX_S 60.0

/* ---- margins_plant.c ------------------------------------------------------ */

#define NX_MAX 3 /* angle, rate, lagged torque */

typedef struct {
    int n;                                          /* 2 without lag, 3 with */
    int delay;                                      /* ticks */
    double j_kg_m2;                                 /* true inertia */
    double a[NX_MAX][NX_MAX], b[NX_MAX], e[NX_MAX]; /* x+ = A x + B u + E d */
} dplant_t;

ladrc_margins_status_t margins_check_plant(const ladrc_margins_plant_t *p);
/* Exact ZOH discretisation of [A B E] (u and d held over the tick). */
void margins_discretise(const ladrc_margins_plant_t *p, dplant_t *dp);
/* (zI - A)^-1 [B E]: g[0..n-1] the state response to u, g[NX_MAX..] to d. */
void margins_plant_solve(const dplant_t *dp, cplx z, cplx gu[NX_MAX], cplx gd[NX_MAX]);

static inline cplx cpow_int(cplx z, int k)
{
    cplx r = 1.0;
    for (int i = 0; i < k; ++i)
        r *= z;
    return r;
}

/* ---- margins_measure.c ---------------------------------------------------- */

/* One copy of the workspace (ladrc_margins_workspace_t.copy): the controller
 * and the gyro filter before it. */
typedef struct {
    union {
        ladrc_axis_t axis;
        ladrc_attitude_t attitude;
    } ctl;
    ladrc_gyro_filter_t filter;
} ctl_state_t;

/* 1 when ctl names one axis: an attitude controller and an axis index in
 * range, or an axis alone (not both, not neither); 0 for NULL. */
int margins_ctl_names_axis(const ladrc_margins_controller_t *ctl);
/* The config of the axis ctl names (margins_ctl_names_axis). */
const ladrc_axis_config_t *margins_ctl_axis_config(const ladrc_margins_controller_t *ctl);
ladrc_margins_status_t margins_ctl_init(const ladrc_margins_controller_t *ctl, ctl_state_t *s);
/* One tick of the real code at reference ref_rad: torque command (N m). */
double margins_ctl_step(const ladrc_margins_controller_t *ctl, ctl_state_t *s, double ref_rad, double angle_rad,
                        double rate_rad_s);
ladrc_margins_status_t margins_check_request(const ladrc_margins_request_t *req);

/* The discrete plant in the time domain with its measurement delay line. */
typedef struct {
    double x[NX_MAX];
    double hist[LADRC_MARGINS_MAX_DELAY + 1][2];
    int head;
} psim_t;

static inline void psim_reset(psim_t *ps)
{
    memset(ps, 0, sizeof *ps);
}

/* Measurement of this tick: the state delay ticks ago. */
static inline void psim_measure(psim_t *ps, const dplant_t *dp, double *angle, double *rate)
{
    const int len = LADRC_MARGINS_MAX_DELAY + 1;
    ps->hist[ps->head][0] = ps->x[0];
    ps->hist[ps->head][1] = ps->x[1];
    const int idx = (ps->head - dp->delay + len) % len;
    *angle = ps->hist[idx][0];
    *rate = ps->hist[idx][1];
    ps->head = (ps->head + 1) % len;
}

static inline void psim_step(psim_t *ps, const dplant_t *dp, double u, double d)
{
    double nx[NX_MAX] = {0.0}; /* the states beyond n stay 0 */
    for (int r = 0; r < dp->n; ++r) {
        double s = dp->b[r] * u + dp->e[r] * d;
        for (int c = 0; c < dp->n; ++c)
            s += dp->a[r][c] * ps->x[c];
        nx[r] = s;
    }
    memcpy(ps->x, nx, sizeof nx);
}

static inline int is_adaptive(const ladrc_axis_config_t *a)
{
    return a->variant == LADRC_VARIANT_LP_MLADRC || a->variant == LADRC_VARIANT_HP_MLADRC;
}

/* The tail's transform: sum_k (c0 + c1 k) z^-k = c0 / (1 - z^-1) + c1 z^-1 / (1 - z^-1)^2. */
static inline cplx tail_at(const ladrc_margins_workspace_t *ws, int p, cplx zi)
{
    const cplx one_minus = 1.0 - zi;
    return ws->tail[p] / one_minus + ws->ramp[p] * zi / (one_minus * one_minus);
}

/* C(z) of response p: sum (h_k - c0 - c1 k) z^-k (Horner in z^-1) + the tail's. */
static inline cplx ctl_at(const ladrc_margins_workspace_t *ws, int p, cplx z)
{
    const cplx zi = 1.0 / z;
    cplx acc = 0.0;
    for (int k = ws->n_taps - 1; k >= 0; --k)
        acc = acc * zi + (ws->h[p][k] - ws->tail[p] - ws->ramp[p] * (double)k);
    return acc + tail_at(ws, p, zi);
}

/* ---- margins_loop.c ------------------------------------------------------- */

/* Anything that gives L at a complex z, with a fast path on the FFT grid. */
typedef struct {
    /* measured controller on a plant */
    const ladrc_margins_workspace_t *ws;
    dplant_t dp;
    /* or a user function */
    ladrc_margins_loop_fn fn;
    void *ctx;
} loop_t;

/* The loop of a measured controller on a plant (discretised into lp). */
ladrc_margins_status_t margins_make_loop(const ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                         loop_t *lp);
/* The margins of a loop into res (stability, GM, PM, DM, Ms; no output grid). */
void margins_compute(const loop_t *lp, double dt, ladrc_margins_result_t *res);

/* ---- margins_noise.c ------------------------------------------------------ */

/* 1 when the request has angle or rate noise. */
int margins_noise_wanted(const ladrc_margins_request_t *req);
/* 0 when the request's noise fields are valid, else -1. */
int margins_check_noise(const ladrc_margins_request_t *req);
/* The predicted command noise (N m RMS above req->noise_corner_hz) of a
 * measured controller's loop; 0 when the request has no noise. */
double margins_cmd_noise(const loop_t *lp, const ladrc_margins_request_t *req);

/* Radix-2 FFT in place (n a power of 2), forward: X_m = sum x_k e^{-j 2 pi m k / n}. */
void margins_fft(double *re, double *im, int n);

#endif
