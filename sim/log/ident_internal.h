/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Between ident.c (the passes and their fits) and ident_result.c (the
 * intervals and warnings): the identification's state. Not a public header.
 */
#ifndef LADRC_SIM_IDENT_INTERNAL_H
#define LADRC_SIM_IDENT_INTERNAL_H

#include "run/biquad.h"
#include "ident.h"

#define PI 3.14159265358979323846
#define RING (SIM_IDENT_MAX_DELAY + 1)
#define MAX_CHANNELS (SIM_IDENT_COARSE_TAUS > SIM_IDENT_FINE_TAUS ? SIM_IDENT_COARSE_TAUS : SIM_IDENT_FINE_TAUS)
#define PREFILTER_SECTIONS 3 /* two low-pass, one high-pass */
/* The split-window variance: pass 3 sums b0's influence (the residual
 * times row 1 of the inverse sums matrix times the regressors) over this
 * many consecutive blocks of the samples; their scatter is b0's variance
 * with every correlation inside a block counted, however long (a
 * cluster-robust sandwich over contiguous blocks). */
#define SPLIT_BLOCKS 8

/* The prefilter's sections' states (ident.c: the band-pass both sides go through). */
typedef struct {
    biquad_t s[PREFILTER_SECTIONS];
} prefilter_t;

/* The command through one candidate lag: phi(j) = u(j) + (x(j) - u(j)) g,
 * the mean of the lag's output over a hold of u(j) starting from x(j), then
 * x(j + 1) = alpha x(j) + (1 - alpha) u(j); filtered, into a ring by tick:
 * the newest at slot pos, which counts down, and each value written twice
 * (at pos and pos + RING) so that delays 0, 1, 2... are the consecutive
 * slots from pos (lag_channel_at): the grid's inner loop reads them in
 * order, without a modulo, and vectorises. */
typedef struct {
    double tau_s, alpha, gain;
    double x;
    prefilter_t filter;
    double ring[2 * RING];
    /* running sums of phi and phi^2 since the segment's start, by tick
     * (the same doubled ring, one slot more): a candidate's sums of phi and
     * phi^2 over a segment are two of these apart (segment_close) */
    double sum1, sum2;
    double ring1[2 * (RING + 1)], ring2[2 * (RING + 1)];
} lag_channel_t;

/* The channel's value d ticks before the newest (at ring slot pos), 0 <= d < RING. */
static inline double lag_channel_at(const lag_channel_t *ch, int pos, int d)
{
    return ch->ring[pos + d];
}

/* Sums of x x' and x y over the samples of one candidate (tau, d); x = (phi, w, 1). */
typedef struct {
    double pp, pw, p1, py;
} candidate_sums_t;

/* The same sums of every candidate of a pass, by channel and delay, one
 * array per sum (the grid's inner loop over the delays vectorises). */
typedef struct {
    double pp[MAX_CHANNELS][RING], pw[MAX_CHANNELS][RING], p1[MAX_CHANNELS][RING], py[MAX_CHANNELS][RING];
} candidate_grid_t;

static inline candidate_sums_t candidate_at(const candidate_grid_t *g, int c, int j)
{
    const candidate_sums_t s = {g->pp[c][j], g->pw[c][j], g->p1[c][j], g->py[c][j]};
    return s;
}

typedef struct {
    double ww, w1, n, wy, y1, yy;
} shared_sums_t;

typedef struct {
    /* streaming state */
    double w_prev, u_prev;
    long long since_restart;
    prefilter_t fy, fw;
    lag_channel_t ch[MAX_CHANNELS];
    int pos;  /* ring slot of the newest phi */
    int spos; /* slot of the newest running sums (rings of RING + 1) */
    shared_sums_t sh;
    candidate_grid_t cand;
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
    /* the last hac_lags + 1 influences, newest at h_pos, which counts down;
     * each written twice (at h_pos and h_pos + hac_lags + 1) so that lags
     * 0, 1, 2... are consecutive slots: the products' loop vectorises */
    double h_ring[2 * (SIM_IDENT_MAX_HAC_LAGS + 1)];
    int h_pos;
    double hac[SIM_IDENT_MAX_HAC_LAGS + 1];
    long long h_count, h_seg; /* residuals in all, and since the last gap */
    sim_spectrum_t command;   /* pass 1: the command's spectrum */
    double sse3;
    double block_h[SPLIT_BLOCKS]; /* pass 3: b0's influence summed per block */
    /* pass 3: the instrumental-variable fit: the setpoint through the chosen
     * lag (its ring by tick) and its filtered mid-point; sums of z x' and z y
     * with z = (setpoint's phi, setpoint, 1), over all and per block */
    lag_channel_t ref_ch;
    prefilter_t fr;
    double r_prev;
    int iv_on; /* every sample of pass 3 had a finite setpoint */
    double zx[3][3], zy[3];
    double block_zx[SPLIT_BLOCKS][3][3], block_zy[SPLIT_BLOCKS][3];
    long long n_fitted; /* the samples pass 2 fitted: pass 3 fits the same */
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
