/* SPDX-License-Identifier: BSD-3-Clause */
/* The identification's result (ident.h): the profile intervals, b0's
 * sandwich variance and the warnings. */
#include <math.h>
#include <string.h>

#include "ident_internal.h"

#define CHI2_1_95 3.841458820694124 /* chi-square(1) at 95 % */
#define Z_95 1.959963984540054
/* The profiles' threshold is chi-square's times this: in closed loop the
 * gyro's noise reaches the command, which biases the fit by more than its
 * scatter, and lag and delay trade against each other at low frequency.
 * On the test loops a manoeuvre's wrong delay stood 2-600 sigma^2 above the
 * best, a chirp's 1e4 and more. */
#define PROFILE_SAFETY 25.0
/* ... and a bias bound that does not shrink with the log's length: a
 * candidate whose sum of squares lies within this share of the best's is
 * consistent with the log too. The closed loop's bias (the gyro's noise in
 * the command, the loop's answer to gusts) is a fixed share of the fit,
 * while chi-square's threshold shrinks as 1/n relative to it: on the 20
 * random airframes of tools/log_ident_check.py the true (lag, delay) of a
 * manoeuvre flight stood 0.01-51 % above the best (a median of 1.7 %); see
 * docs/flight-logs.md for the coverage this gives. */
#define PROFILE_BIAS_SHARE 0.10
/* Student's t at 97.5 % for SPLIT_BLOCKS - 1 = 7 degrees of freedom. */
#define T_975_7 2.364624251592785

/* Bartlett-weighted sum of the residuals' autocovariances: the sandwich variance of b0. */
static double sandwich_variance(const sim_ident_t *id, const axis_t *a)
{
    double v = a->hac[0];
    for (int m = 1; m <= id->hac_lags; ++m) {
        v += 2.0 * (1.0 - (double)m / (id->hac_lags + 1)) * a->hac[m];
    }
    return v;
}

/* The split-window variance of b0: the blocks' summed influences' scatter
 * (SPLIT_BLOCKS / (SPLIT_BLOCKS - 1) times their sum of squares about
 * their mean), honest where the sandwich's lags cannot reach: slow changes
 * of the flight, and a log whose excitation comes in one part. */
static double split_variance(const axis_t *a)
{
    double mean = 0.0, ss = 0.0;
    for (int b = 0; b < SPLIT_BLOCKS; ++b) {
        mean += a->block_h[b] / SPLIT_BLOCKS;
    }
    for (int b = 0; b < SPLIT_BLOCKS; ++b) {
        ss += (a->block_h[b] - mean) * (a->block_h[b] - mean);
    }
    return ss * SPLIT_BLOCKS / (SPLIT_BLOCKS - 1);
}

/* b0 by instrumental variables: the setpoint's phi z (the lag and delay
 * chosen) is the instrument of the command's phi p, the damping taken from
 * the least squares (a second instrument for it, the setpoint itself, is
 * nearly collinear with z):
 *
 *   b0 = sum (z - mean z)(y + a wm) / sum (z - mean z) p
 *
 * Its 95 % interval: t over the blocks' summed influences, as
 * split_variance. 0 when the log has no setpoint or z says nothing of p. */
static double centred(double s_zx, double z_mean, double s_x)
{
    return s_zx - z_mean * s_x;
}

static int iv_fit(const axis_t *a, double *b0, double *lo, double *hi)
{
    const double n = a->zx[2][2];
    if (!a->iv_on || !(n > 3.0)) {
        return 0;
    }
    const double z_mean = a->zx[0][2] / n, minus_a = a->theta[1];
    const double den = centred(a->zx[0][0], z_mean, a->zx[2][0]);
    const double num = centred(a->zy[0], z_mean, a->zy[2]) - minus_a * centred(a->zx[0][1], z_mean, a->zx[2][1]);
    if (!(fabs(den) > 0.0)) {
        return 0;
    }
    const double b = num / den;
    double h[SPLIT_BLOCKS], mean = 0.0, ss = 0.0;
    for (int k = 0; k < SPLIT_BLOCKS; ++k) {
        const double(*zx)[3] = a->block_zx[k];
        const double *zy = a->block_zy[k];
        h[k] = (centred(zy[0], z_mean, zy[2]) - minus_a * centred(zx[0][1], z_mean, zx[2][1]) -
                b * centred(zx[0][0], z_mean, zx[2][0])) /
               den;
        mean += h[k] / SPLIT_BLOCKS;
    }
    for (int k = 0; k < SPLIT_BLOCKS; ++k) {
        ss += (h[k] - mean) * (h[k] - mean);
    }
    const double half = T_975_7 * sqrt(ss * SPLIT_BLOCKS / (SPLIT_BLOCKS - 1));
    *b0 = b;
    *lo = b - half;
    *hi = b + half;
    return isfinite(half) && isfinite(b);
}

/* The profile intervals: every candidate (tau, d) of both grids whose sum of
 * squares lies within `limit` is consistent with the log; the lag's interval
 * is widened to the next grid point outside that set (the boundary lies
 * between), the delay's is the set's range, and b0's spans the set's b0s. */
typedef struct {
    double tau_lo, tau_hi, b0_lo, b0_hi;
    int d_lo, d_hi;
} profile_t;

static void profile_take(profile_t *p, double sse, double limit, double tau, int d, double b0)
{
    if (sse <= limit) {
        p->tau_lo = fmin(p->tau_lo, tau);
        p->tau_hi = fmax(p->tau_hi, tau);
        p->b0_lo = fmin(p->b0_lo, b0);
        p->b0_hi = fmax(p->b0_hi, b0);
        p->d_lo = d < p->d_lo ? d : p->d_lo;
        p->d_hi = d > p->d_hi ? d : p->d_hi;
    }
}

/* The grid's nearest lags outside the set's range, into *lo and *hi. */
static void widen_to_grid(const double *grid, int n, const profile_t *p, double *lo, double *hi)
{
    for (int g = 0; g < n; ++g) {
        *lo = grid[g] < p->tau_lo && grid[g] > *lo ? grid[g] : *lo;
        *hi = grid[g] > p->tau_hi && grid[g] < *hi ? grid[g] : *hi;
    }
}

static void profile_intervals(const sim_ident_t *id, const axis_t *a, double limit, profile_t *p)
{
    *p = (profile_t){a->tau_s, a->tau_s, a->theta[0], a->theta[0], a->delay, a->delay};
    for (int c = 0; c < SIM_IDENT_COARSE_TAUS; ++c) {
        for (int d = 0; d <= id->delay_max; ++d) {
            profile_take(p, a->sse_coarse[c][d], limit, a->tau_coarse[c], d, a->b0_coarse[c][d]);
        }
    }
    for (int c = 0; c < SIM_IDENT_FINE_TAUS; ++c) {
        for (int j = 0; j < a->fine_nd; ++j) {
            profile_take(p, a->sse_fine[c][j], limit, a->tau_fine[c], a->fine_d0 + j, a->b0_fine[c][j]);
        }
    }
    double lo = 0.0, hi = id->opt.lag_max_s;
    widen_to_grid(a->tau_coarse, SIM_IDENT_COARSE_TAUS, p, &lo, &hi);
    widen_to_grid(a->tau_fine, SIM_IDENT_FINE_TAUS, p, &lo, &hi);
    p->tau_lo = p->tau_lo > 0.0 ? lo : 0.0;
    p->tau_hi = hi;
}

void sim_ident_result(const sim_ident_t *id, int axis, sim_ident_axis_t *out)
{
    const axis_t *a = &id->axis[axis];
    memset(out, 0, sizeof *out);
    out->samples = (long long)a->sh.n;
    if (!a->valid || id->pass < 3) {
        out->b0 = out->b0_lo = out->b0_hi = out->lag_s = out->lag_lo_s = out->lag_hi_s = NAN;
        out->damping_per_s = out->r2 = out->command_rms = out->variance_ratio = NAN;
        out->b0_iv = out->b0_iv_lo = out->b0_iv_hi = NAN;
        out->delay_ticks = out->delay_lo_ticks = out->delay_hi_ticks = -1;
        out->warnings = SIM_IDENT_WARN_FEW | SIM_IDENT_WARN_LOW_FIT | SIM_IDENT_WARN_B0_NOT_TOLD;
        return;
    }
    const double dof = a->n - 3.0;
    const double sigma2 = a->sse / dof;
    const double var_ols = sigma2 * a->m_inv[0][0];
    const double var_hac = sandwich_variance(id, a);
    const double ratio = var_hac > var_ols ? var_hac / var_ols : 1.0;
    const double var_split = split_variance(a);
    const double half = fmax(Z_95 * sqrt(fmax(var_hac, var_ols)), T_975_7 * sqrt(var_split));
    const double limit = a->sse + fmax(CHI2_1_95 * sigma2 * fmax(ratio, PROFILE_SAFETY), PROFILE_BIAS_SHARE * a->sse);
    profile_t prof;
    profile_intervals(id, a, limit, &prof);
    out->b0 = a->theta[0];
    out->b0_lo = prof.b0_lo - half;
    out->b0_hi = prof.b0_hi + half;
    out->b0_iv = out->b0_iv_lo = out->b0_iv_hi = NAN;
    if (iv_fit(a, &out->b0_iv, &out->b0_iv_lo, &out->b0_iv_hi)) {
        /* either fit may be the biased one: the interval holds both */
        out->b0_lo = fmin(out->b0_lo, out->b0_iv_lo);
        out->b0_hi = fmax(out->b0_hi, out->b0_iv_hi);
    }
    out->damping_per_s = -a->theta[1];
    out->r2 = a->sst > 0.0 ? 1.0 - a->sse / a->sst : 0.0;
    out->command_rms = sqrt(fmax(a->phi_var, 0.0));
    out->variance_ratio = ratio;
    /* motors faster than the band fitted: nothing there tells lag from delay (share 0) */
    const double corner_hz = 1.0 / (2.0 * PI * fmax(a->tau_s, id->opt.dt_s));
    const double df_hz = 1.0 / (id->opt.dt_s * SIM_SPECTRUM_N);
    out->band_share = corner_hz >= id->opt.prefilter_hz
                          ? 0.0
                          : sim_spectrum_band_rms(&a->command, corner_hz, id->opt.prefilter_hz) /
                                sim_spectrum_band_rms(&a->command, df_hz, id->opt.prefilter_hz);
    out->lag_s = a->tau_s;
    out->lag_lo_s = prof.tau_lo;
    out->lag_hi_s = prof.tau_hi;
    out->delay_ticks = a->delay;
    out->delay_lo_ticks = prof.d_lo;
    out->delay_hi_ticks = prof.d_hi;

    unsigned w = 0;
    if (out->samples < SIM_IDENT_MIN_SAMPLES) {
        w |= SIM_IDENT_WARN_FEW;
    }
    if (!(out->b0 > 0.0)) {
        w |= SIM_IDENT_WARN_SIGN;
    }
    if (out->b0_hi - out->b0_lo > 2.0 * SIM_IDENT_B0_REL_MAX * fabs(out->b0)) {
        w |= SIM_IDENT_WARN_B0_WIDE;
    }
    if (out->lag_hi_s - out->lag_lo_s > fmax(SIM_IDENT_LAG_REL_MAX * out->lag_s, 0.004)) {
        w |= SIM_IDENT_WARN_LAG_WIDE;
    }
    if (out->delay_hi_ticks != out->delay_lo_ticks) {
        w |= SIM_IDENT_WARN_DELAY_WIDE;
    }
    if (!sim_ident_b0_told(out)) {
        w |= SIM_IDENT_WARN_B0_NOT_TOLD;
    }
    if (out->r2 < SIM_IDENT_R2_MIN) {
        w |= SIM_IDENT_WARN_LOW_FIT;
    }
    if (out->lag_s >= a->tau_coarse[SIM_IDENT_COARSE_TAUS - 1] ||
        (out->delay_ticks == id->delay_max && id->delay_max > 0)) {
        w |= SIM_IDENT_WARN_EDGE;
    }
    if (!(out->band_share >= SIM_IDENT_BAND_SHARE_MIN)) {
        w |= SIM_IDENT_WARN_NARROW;
    }
    out->warnings = w;
}

int sim_ident_b0_told(const sim_ident_axis_t *x)
{
    const int own_signal = isfinite(x->b0_iv) || x->band_share >= SIM_IDENT_BAND_SHARE_MIN;
    return x->samples >= SIM_IDENT_MIN_SAMPLES && own_signal && x->r2 >= SIM_IDENT_R2_MIN && x->b0 > 0.0 &&
           x->b0_lo > 0.0 && x->b0_hi <= SIM_IDENT_B0_TOLD_RATIO * x->b0_lo;
}

const char *sim_ident_warning_text(unsigned bit)
{
    switch (bit) {
    case SIM_IDENT_WARN_FEW:
        return "too few samples to fit: the log is short, or nothing moves on the axis (no excitation)";
    case SIM_IDENT_WARN_SIGN:
        return "b0 is not positive: the command and the gyro disagree in sign (check the axis's mapping)";
    case SIM_IDENT_WARN_B0_WIDE:
        return "b0's interval is wider than +-10 %: weak excitation (fly a chirp or sharper manoeuvres)";
    case SIM_IDENT_WARN_LAG_WIDE:
        return "the motor lag's interval is wide: weak excitation above the motors' corner";
    case SIM_IDENT_WARN_DELAY_WIDE:
        return "the delay is not told to the tick: weak excitation at high frequency";
    case SIM_IDENT_WARN_LOW_FIT:
        return "the model explains under half the filtered angular acceleration (R^2 < 0.5)";
    case SIM_IDENT_WARN_EDGE:
        return "the best fit lies at the edge of the lag or delay searched";
    case SIM_IDENT_WARN_NARROW:
        return "lag and delay are not told apart: the command has little content above the motors' corner, or "
               "that corner lies above the band fitted (fly a chirp; their sum is told)";
    case SIM_IDENT_WARN_B0_NOT_TOLD:
        return "b0 not told: no signal of the log's own (no moving setpoint, no command above the motors' corner: "
               "the loop's answer to the gyro's noise and to gusts looks like a plant), or its interval holds 0 or "
               "spans more than a factor of 2, or R^2 < 0.5; the airframe takes its interval's upper end, the side a "
               "tuning is gentle on";
    default:
        return "";
    }
}
