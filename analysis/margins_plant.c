/* SPDX-License-Identifier: BSD-3-Clause */
/* The sampled airframe of the margin analysis: its checks, exact ZOH
 * discretisation (matrix exponential) and frequency response. */
#include "margins_internal.h"

#include <math.h>
#include <string.h>

ladrc_margins_status_t margins_check_plant(const ladrc_margins_plant_t *p)
{
    if (p == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!(isfinite(p->dt_s) && p->dt_s > 0.0))
        return LADRC_MARGINS_ERR_DT_S;
    if (!(isfinite(p->inertia_kg_m2) && p->inertia_kg_m2 > 0.0 && isfinite(p->inertia_factor) &&
          p->inertia_factor > 0.0))
        return LADRC_MARGINS_ERR_INERTIA;
    if (!(isfinite(p->drag_Nm_s) && p->drag_Nm_s >= 0.0))
        return LADRC_MARGINS_ERR_DRAG;
    if (!(isfinite(p->motor_tau_s) && p->motor_tau_s >= 0.0))
        return LADRC_MARGINS_ERR_MOTOR_TAU;
    if (p->delay_ticks < 0 || p->delay_ticks > LADRC_MARGINS_MAX_DELAY)
        return LADRC_MARGINS_ERR_DELAY;
    return LADRC_MARGINS_OK;
}

#define NM (NX_MAX + 2)

static void mat_mul(int n, double x[NM][NM], double y[NM][NM], double out[NM][NM])
{
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            double s = 0.0;
            for (int k = 0; k < n; ++k)
                s += x[i][k] * y[k][j];
            out[i][j] = s;
        }
    }
}

/* exp(m) by scaling and squaring of a Taylor series (n <= NM; the norm is
 * scaled below 0.5, where 20 terms leave 1e-26). */
static void mat_exp(int n, double m[NM][NM], double out[NM][NM])
{
    double norm = 0.0;
    for (int j = 0; j < n; ++j) {
        double col = 0.0;
        for (int i = 0; i < n; ++i)
            col += fabs(m[i][j]);
        if (col > norm)
            norm = col;
    }
    int squarings = 0;
    double scale = 1.0;
    while (norm * scale > 0.5 && squarings < 60) {
        scale *= 0.5;
        ++squarings;
    }
    double x[NM][NM], term[NM][NM], tmp[NM][NM];
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            x[i][j] = m[i][j] * scale;
            out[i][j] = (i == j) ? 1.0 : 0.0;
            term[i][j] = (i == j) ? 1.0 : 0.0;
        }
    }
    for (int k = 1; k <= 20; ++k) {
        mat_mul(n, term, x, tmp);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
                term[i][j] = tmp[i][j] / k;
                out[i][j] += term[i][j];
            }
        }
    }
    for (int s = 0; s < squarings; ++s) {
        mat_mul(n, out, out, tmp);
        memcpy(out, tmp, sizeof tmp);
    }
}

/* Exact ZOH discretisation of [A B E] (u and d held over the tick). */
void margins_discretise(const ladrc_margins_plant_t *p, dplant_t *dp)
{
    const double j = p->inertia_kg_m2 * p->inertia_factor;
    const int lag = p->motor_tau_s > 0.0;
    const int n = lag ? 3 : 2;
    double m[NM][NM];
    memset(m, 0, sizeof m);
    /* states: 0 angle, 1 rate, 2 lagged torque; inputs n: u, n + 1: d */
    m[0][1] = 1.0;
    m[1][1] = -p->drag_Nm_s / j;
    m[1][n + 1] = 1.0;
    if (lag) {
        m[1][2] = 1.0 / j;
        m[2][2] = -1.0 / p->motor_tau_s;
        m[2][n] = 1.0 / p->motor_tau_s;
    } else {
        m[1][n] = 1.0 / j;
    }
    for (int r = 0; r < n + 2; ++r) {
        for (int c = 0; c < n + 2; ++c)
            m[r][c] *= p->dt_s;
    }
    double ex[NM][NM];
    mat_exp(n + 2, m, ex);
    memset(dp, 0, sizeof *dp);
    dp->n = n;
    dp->delay = p->delay_ticks;
    dp->j_kg_m2 = j;
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c)
            dp->a[r][c] = ex[r][c];
        dp->b[r] = ex[r][n];
        dp->e[r] = ex[r][n + 1];
    }
}

/* (zI - A)^-1 [B E]: g[0..n-1] the state response to u, g[NX_MAX..] to d
 * (Gaussian elimination with partial pivoting). */
void margins_plant_solve(const dplant_t *dp, cplx z, cplx gu[NX_MAX], cplx gd[NX_MAX])
{
    const int n = dp->n;
    cplx m[NX_MAX][NX_MAX + 2];
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c)
            m[r][c] = ((r == c) ? z : 0.0) - dp->a[r][c];
        m[r][n] = dp->b[r];
        m[r][n + 1] = dp->e[r];
    }
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r) {
            if (cabs(m[r][c]) > cabs(m[piv][c]))
                piv = r;
        }
        if (piv != c) {
            for (int k = 0; k < n + 2; ++k) {
                const cplx t = m[c][k];
                m[c][k] = m[piv][k];
                m[piv][k] = t;
            }
        }
        for (int r = c + 1; r < n; ++r) {
            const cplx f = m[r][c] / m[c][c];
            for (int k = c; k < n + 2; ++k)
                m[r][k] -= f * m[c][k];
        }
    }
    for (int r = n - 1; r >= 0; --r) {
        cplx su = m[r][n], sd = m[r][n + 1];
        for (int k = r + 1; k < n; ++k) {
            su -= m[r][k] * gu[k];
            sd -= m[r][k] * gd[k];
        }
        gu[r] = su / m[r][r];
        gd[r] = sd / m[r][r];
    }
}

ladrc_margins_status_t ladrc_margins_plant_freq(const ladrc_margins_plant_t *plant, double w_rad_s, double out[4])
{
    const ladrc_margins_status_t st = margins_check_plant(plant);
    if (st != LADRC_MARGINS_OK || out == NULL)
        return st != LADRC_MARGINS_OK ? st : LADRC_MARGINS_ERR_NULL;
    dplant_t dp;
    margins_discretise(plant, &dp);
    const cplx z = cexp(I * w_rad_s * plant->dt_s);
    cplx gu[NX_MAX], gd[NX_MAX];
    margins_plant_solve(&dp, z, gu, gd);
    const cplx late = 1.0 / cpow_int(z, dp.delay);
    out[0] = creal(gu[0] * late);
    out[1] = cimag(gu[0] * late);
    out[2] = creal(gu[1] * late);
    out[3] = cimag(gu[1] * late);
    return LADRC_MARGINS_OK;
}
