/* SPDX-License-Identifier: BSD-3-Clause */
/* Dryden turbulence (turbulence.h). */
#include "turbulence.h"

#include <math.h>
#include <stddef.h>

#define FT_PER_M (1.0 / 0.3048)
#define M_S_PER_KT (1852.0 / 3600.0)
#define PI_D 3.14159265358979323846
#define SQRT3 1.73205080756887729353

/* W20, the wind at 20 ft, of the three levels (kt). */
static const double W20_KT[] = {0.0, 15.0, 30.0, 45.0};

/* The second-order shaping filter's output weights on its two states: for
 * y1 = n / (1 + tau s), y2 = y1 / (1 + tau s), (1 + sqrt3 tau s) y2 =
 * sqrt3 y1 + (1 - sqrt3) y2. Its stationary covariance is p (1, 1/2; 1/2, 1/2)
 * and the output's variance 2 p, so p = sigma^2 / 2. */
#define C0 SQRT3
#define C1 (1.0 - SQRT3)

static double gust_of(int axis, const double x[2])
{
    return axis == 0 ? x[0] : C0 * x[0] + C1 * x[1];
}

/* Lower Cholesky factor of the symmetric 2x2 q (q[1][0] unused); a
 * rounding below zero on the diagonal counts as zero. */
static void cholesky2(double q[2][2], double l[2][2])
{
    l[0][0] = q[0][0] > 0.0 ? sqrt(q[0][0]) : 0.0;
    l[0][1] = 0.0;
    l[1][0] = l[0][0] > 0.0 ? q[0][1] / l[0][0] : 0.0;
    const double d = q[1][1] - l[1][0] * l[1][0];
    l[1][1] = d > 0.0 ? sqrt(d) : 0.0;
}

/* x = L n for fresh standard normals n. */
static void draw(sim_rng_t *rng, double l[2][2], double x[2])
{
    const double n0 = sim_rng_gauss(rng);
    const double n1 = sim_rng_gauss(rng);
    x[0] = l[0][0] * n0;
    x[1] = l[1][0] * n0 + l[1][1] * n1;
}

/* One component's transition and noise per sample, and its first state
 * drawn from the stationary covariance. */
static void setup_axis(sim_turb_t *t, int axis)
{
    const double a = t->speed_m_s / t->scale_m[axis]; /* 1 / tau */
    const double e = exp(-a * t->dt_s);
    const double s2 = t->sigma_m_s[axis] * t->sigma_m_s[axis];
    double p[2][2], q[2][2], l[2][2];
    double(*phi)[2] = t->phi[axis];
    if (axis == 0) { /* Ornstein-Uhlenbeck: one state of variance sigma^2 */
        phi[0][0] = e;
        phi[0][1] = phi[1][0] = phi[1][1] = 0.0;
        p[0][0] = s2;
        p[0][1] = p[1][0] = p[1][1] = 0.0;
    } else { /* A = -a I + N with N nilpotent: e^{A dt} = e^{-a dt} (I + N dt) */
        phi[0][0] = e;
        phi[0][1] = 0.0;
        phi[1][0] = a * t->dt_s * e;
        phi[1][1] = e;
        p[0][0] = 0.5 * s2;
        p[0][1] = p[1][0] = 0.25 * s2;
        p[1][1] = 0.25 * s2;
    }
    /* Q = P - Phi P Phi^T: what keeps the sampled process stationary */
    for (int i = 0; i < 2; ++i) {
        for (int j = 0; j < 2; ++j) {
            double fpf = 0.0;
            for (int m = 0; m < 2; ++m) {
                for (int n = 0; n < 2; ++n) {
                    fpf += phi[i][m] * p[m][n] * phi[j][n];
                }
            }
            q[i][j] = p[i][j] - fpf;
        }
    }
    cholesky2(q, t->chol[axis]);
    cholesky2(p, l);
    draw(&t->rng, l, t->x[axis]);
}

/* Moves every component one sample on. */
static void advance(sim_turb_t *t)
{
    for (int axis = 0; axis < 3; ++axis) {
        double(*phi)[2] = t->phi[axis];
        double *x = t->x[axis];
        double n[2];
        draw(&t->rng, t->chol[axis], n);
        const double x0 = phi[0][0] * x[0] + phi[0][1] * x[1] + n[0];
        const double x1 = phi[1][0] * x[0] + phi[1][1] * x[1] + n[1];
        x[0] = x0;
        x[1] = x1;
    }
}

static void take_sample(const sim_turb_t *t, double g[3])
{
    for (int axis = 0; axis < 3; ++axis) {
        g[axis] = gust_of(axis, t->x[axis]);
    }
}

int sim_turb_init(sim_turb_t *t, const sim_turb_config_t *cfg, uint64_t seed)
{
    if (t == NULL || cfg == NULL || cfg->level <= SIM_TURB_OFF || cfg->level > SIM_TURB_SIGMA ||
        !(cfg->altitude_m > 0.0 && cfg->altitude_m <= SIM_TURB_ALTITUDE_MAX_M) ||
        !(cfg->mean_wind_m_s >= 0.0 && isfinite(cfg->mean_wind_m_s)) ||
        !(cfg->sample_dt_s > 0.0 && isfinite(cfg->sample_dt_s)) ||
        (cfg->level == SIM_TURB_SIGMA && !(cfg->sigma_m_s > 0.0 && isfinite(cfg->sigma_m_s)))) {
        return -1;
    }
    const double alt_m = cfg->altitude_m < SIM_TURB_ALTITUDE_MIN_M ? SIM_TURB_ALTITUDE_MIN_M : cfg->altitude_m;
    const double h_ft = alt_m * FT_PER_M;
    const double base = 0.177 + 0.000823 * h_ft;
    const double sigma_w = cfg->level == SIM_TURB_SIGMA ? cfg->sigma_m_s : 0.1 * W20_KT[cfg->level] * M_S_PER_KT;
    const double sigma_uv = sigma_w / pow(base, 0.4);
    const double l_uv = alt_m / pow(base, 1.2);
    sim_rng_seed(&t->rng, seed);
    t->dt_s = cfg->sample_dt_s;
    t->sigma_m_s[0] = t->sigma_m_s[1] = sigma_uv;
    t->sigma_m_s[2] = sigma_w;
    t->scale_m[0] = t->scale_m[1] = l_uv;
    t->scale_m[2] = alt_m;
    t->speed_m_s = cfg->mean_wind_m_s > sigma_uv ? cfg->mean_wind_m_s : sigma_uv;
    for (int axis = 0; axis < 3; ++axis) {
        setup_axis(t, axis);
    }
    t->k = 0;
    take_sample(t, t->sample[0]);
    advance(t);
    take_sample(t, t->sample[1]);
    return 0;
}

void sim_turb_gust_at(sim_turb_t *t, double t_s, double gust_m_s[3])
{
    /* whole samples from 0; past the next one, move on (times do not decrease) */
    while (t_s > (double)(t->k + 1u) * t->dt_s) {
        for (int axis = 0; axis < 3; ++axis) {
            t->sample[0][axis] = t->sample[1][axis];
        }
        advance(t);
        take_sample(t, t->sample[1]);
        ++t->k;
    }
    double f = (t_s - (double)t->k * t->dt_s) / t->dt_s;
    f = f < 0.0 ? 0.0 : f;
    for (int axis = 0; axis < 3; ++axis) {
        gust_m_s[axis] = t->sample[0][axis] + f * (t->sample[1][axis] - t->sample[0][axis]);
    }
}

double sim_turb_psd(const sim_turb_t *t, int axis, double omega_rad_s)
{
    const double l = t->scale_m[axis], v = t->speed_m_s, s2 = t->sigma_m_s[axis] * t->sigma_m_s[axis];
    const double r2 = (l * omega_rad_s / v) * (l * omega_rad_s / v);
    if (axis == 0) {
        return s2 * (2.0 * l / (PI_D * v)) / (1.0 + r2);
    }
    return s2 * (l / (PI_D * v)) * (1.0 + 3.0 * r2) / ((1.0 + r2) * (1.0 + r2));
}
