/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Between ident.c (the passes and their fits) and ident_result.c (the
 * intervals and warnings): the identification's state. Not a public header.
 */
#ifndef LADRC_SIM_IDENT_INTERNAL_H
#define LADRC_SIM_IDENT_INTERNAL_H

#include "biquad.h"
#include "ident.h"

#define PI 3.14159265358979323846
#define RING (SIM_IDENT_MAX_DELAY + 1)
#define MAX_CHANNELS (SIM_IDENT_COARSE_TAUS > SIM_IDENT_FINE_TAUS ? SIM_IDENT_COARSE_TAUS : SIM_IDENT_FINE_TAUS)
#define PREFILTER_SECTIONS 3 /* two low-pass, one high-pass */

/* The prefilter's sections' states (ident.c: the band-pass both sides go through). */
typedef struct {
    biquad_t s[PREFILTER_SECTIONS];
} prefilter_t;

/* The command through one candidate lag: phi(j) = u(j) + (x(j) - u(j)) g,
 * the mean of the lag's output over a hold of u(j) starting from x(j), then
 * x(j + 1) = alpha x(j) + (1 - alpha) u(j); filtered, into a ring by tick. */
typedef struct {
    double tau_s, alpha, gain;
    double x;
    prefilter_t filter;
    double ring[2 * RING]; /* each value twice, at k and k + RING: any window of delays reads in one run */
} lag_channel_t;

/* Sums of x x' and x y over the samples of one candidate (tau, d); x = (phi, w, 1). */
typedef struct {
    double pp, pw, p1, py;
} candidate_sums_t;

typedef struct {
    double ww, w1, n, wy, y1, yy;
} shared_sums_t;

typedef struct {
    /* streaming state */
    double w_prev, u_prev;
    long long since_restart;
    prefilter_t fy, fw;
    lag_channel_t ch[MAX_CHANNELS];
    int pos; /* ring slot of the newest phi */
    shared_sums_t sh;
    candidate_sums_t cand[MAX_CHANNELS][RING];
    /* profiles: the best sum of squares per candidate of each pass */
    double sse_coarse[SIM_IDENT_COARSE_TAUS][RING], b0_coarse[SIM_IDENT_COARSE_TAUS][RING];
    double sse_fine[SIM_IDENT_FINE_TAUS][SIM_IDENT_FINE_DELAYS], b0_fine[SIM_IDENT_FINE_TAUS][SIM_IDENT_FINE_DELAYS];
    double tau_coarse[SIM_IDENT_COARSE_TAUS], tau_fine[SIM_IDENT_FINE_TAUS];
    int fine_d0, fine_nd;
    /* the choice */
    double tau_s, tau_grid_s; /* the lag chosen, and the fine grid's best */
    int delay;
    double theta[3]; /* b0, -a, c */
    double m_inv[3][3];
    double sse, sst, n;
    double phi_mean, phi_var;
    /* pass 3: the residuals' sandwich */
    double v[3]; /* row 1 of m_inv */
    double h_ring[SIM_IDENT_MAX_HAC_LAGS + 1];
    double hac[SIM_IDENT_MAX_HAC_LAGS + 1];
    long long h_count, h_seg; /* residuals in all, and since the last gap */
    sim_spectrum_t command;   /* pass 1: the command's spectrum */
    double sse3;
    int valid;
} axis_t;

struct sim_ident {
    sim_ident_options_t opt;
    biquad_coef_t lpf[PREFILTER_SECTIONS];
    int delay_max, skip, hac_lags;
    int pass;
    axis_t axis[3];
};

#endif
