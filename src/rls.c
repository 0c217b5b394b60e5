/* SPDX-License-Identifier: BSD-3-Clause */
/* Bounded-gain RLS on the factors P = U D U^T (see rls.h). */
#include "ladrc/rls.h"
#include "rls1_internal.h"
#include "require.h"

#include "compiler.h"

/* Forgetting stops when tr(P) is within this fraction of k0. It is far above
 * the rounding of the trace (about n eps = 5e-7 in float), so without
 * excitation P lands on an exact fixed point, and far below anything the
 * law would show (the rate left there is lambda0 * 1e-4). */
#define RLS_FORGET_DEADBAND LADRC_R(1e-4)
/* A P that rounding pushed above k0 is scaled to this fraction of k0: inside
 * the dead band, and 5e-5 below k0, so the scaled trace cannot round above. */
#define RLS_CLAMP_FRACTION LADRC_R(0.99995)

/* U(i,j), i < j, stored by columns: column j holds rows 0..j-1. */
static unsigned u_index(unsigned i, unsigned j)
{
    return (j * (j - 1u)) / 2u + i;
}

/* tr(U D U^T) = sum_j D_j (1 + sum_{i<j} U_ij^2). Inline: the update, the
 * deepest function of a tick, calls it. */
static LADRC_FORCE_INLINE ladrc_real_t trace_of(const ladrc_real_t *u, const ladrc_real_t *d, unsigned n)
{
    ladrc_real_t tr = LADRC_R(0.0);
    for (unsigned j = 0u; j < n; ++j) {
        ladrc_real_t col = LADRC_R(1.0);
        for (unsigned i = 0u; i < j; ++i) {
            const ladrc_real_t uij = u[u_index(i, j)];
            col += uij * uij;
        }
        tr += d[j] * col;
    }
    return tr;
}

/* tr(p_initial I), summed as trace_of sums it (U = I). */
static ladrc_real_t initial_trace(ladrc_real_t p_initial, unsigned n)
{
    ladrc_real_t tr = LADRC_R(0.0);
    for (unsigned j = 0u; j < n; ++j) {
        tr += p_initial;
    }
    return tr;
}

/* P = p_initial I; unused entries zero so that states compare bitwise.
 * Inline: called from the update, the deepest function of a tick. */
static LADRC_FORCE_INLINE void restart_p(ladrc_rls_t *rls)
{
    for (unsigned k = 0u; k < LADRC_RLS_U_SIZE; ++k) {
        rls->u[k] = LADRC_R(0.0);
    }
    for (unsigned j = 0u; j < LADRC_RLS_MAX_PARAMS; ++j) {
        rls->d[j] = (j < rls->n_params) ? rls->p_initial : LADRC_R(0.0);
    }
    rls->trace = initial_trace(rls->p_initial, rls->n_params);
}

/* lambda0 h <= 1 keeps the trace map monotone, so the bound holds (rls.h). */
static int lambda0_is_valid(ladrc_real_t lambda0_per_s, ladrc_real_t dt_s)
{
    return ladrc_is_finite(lambda0_per_s) && lambda0_per_s >= LADRC_R(0.0) && lambda0_per_s * dt_s <= LADRC_R(1.0);
}

/* The checks of ladrc_rls_init after the NULLs and n_params, in its order. */
static ladrc_status_t check_config(const ladrc_rls_config_t *cfg)
{
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!lambda0_is_valid(cfg->lambda0_per_s, cfg->dt_s)) {
        return LADRC_ERR_RLS_LAMBDA0;
    }
    if (!ladrc_is_positive(cfg->p_bound)) {
        return LADRC_ERR_RLS_P_BOUND;
    }
    if (!ladrc_is_positive(cfg->p_initial)) {
        return LADRC_ERR_RLS_P_INITIAL;
    }
    /* The trace the start state will hold must itself meet the bound. */
    if (initial_trace(cfg->p_initial, cfg->n_params) > cfg->p_bound) {
        return LADRC_ERR_RLS_P_INITIAL;
    }
    return LADRC_OK;
}

ladrc_status_t ladrc_rls_init(ladrc_rls_t *rls, const ladrc_rls_config_t *cfg)
{
    if (rls == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (cfg->n_params < 1u || cfg->n_params > LADRC_RLS_MAX_PARAMS) {
        return LADRC_ERR_RLS_N_PARAMS;
    }
    const ladrc_status_t status = check_config(cfg);
    if (status != LADRC_OK) {
        return status;
    }
    rls->n_params = cfg->n_params;
    rls->dt_s = cfg->dt_s;
    rls->lambda0_per_s = cfg->lambda0_per_s;
    rls->p_bound = cfg->p_bound;
    rls->p_initial = cfg->p_initial;
    ladrc_rls_reset(rls, NULL);
    return LADRC_OK;
}

void ladrc_rls_reset(ladrc_rls_t *rls, const ladrc_real_t *theta0)
{
    LADRC_REQUIRE_VOID(rls != NULL);
    for (unsigned i = 0u; i < LADRC_RLS_MAX_PARAMS; ++i) {
        ladrc_real_t v = LADRC_R(0.0);
        if (theta0 != NULL && i < rls->n_params && ladrc_is_finite(theta0[i])) {
            v = theta0[i];
        }
        rls->theta[i] = v;
    }
    restart_p(rls);
    rls->lambda_per_s = LADRC_R(0.0);
    rls->faults = LADRC_FAULT_NONE;
}

ladrc_status_t ladrc_rls_restart(ladrc_rls_t *rls, uint8_t n_params, const ladrc_real_t *theta0)
{
    if (rls == NULL) {
        return LADRC_ERR_NULL;
    }
    if (n_params < 1u || n_params > LADRC_RLS_MAX_PARAMS) {
        return LADRC_ERR_RLS_N_PARAMS;
    }
    if (initial_trace(rls->p_initial, n_params) > rls->p_bound) {
        return LADRC_ERR_RLS_P_INITIAL;
    }
    rls->n_params = n_params;
    ladrc_rls_reset(rls, theta0);
    return LADRC_OK;
}

/* lambda = lambda0 (1 - tr(P) / k0), 0 within the dead band below k0 (rls.h). */
static LADRC_FORCE_INLINE ladrc_real_t forgetting_rate(ladrc_real_t trace, ladrc_real_t p_bound,
                                                       ladrc_real_t lambda0_per_s)
{
    const ladrc_real_t room = LADRC_R(1.0) - trace / p_bound;
    return (room > RLS_FORGET_DEADBAND) ? lambda0_per_s * room : LADRC_R(0.0);
}

/* The update for n parameters, inlined into ladrc_rls_update: where n is a
 * constant the compiler lays the loops out flat (one formula, written once). */
static LADRC_FORCE_INLINE ladrc_fault_t update_n(ladrc_rls_t *rls, const ladrc_real_t *phi, ladrc_real_t y,
                                                 const unsigned n)
{
    int finite = ladrc_is_finite(y);
    for (unsigned i = 0u; i < n; ++i) {
        if (!ladrc_is_finite(phi[i])) {
            finite = 0;
        }
    }
    if (!finite) {
        rls->faults = LADRC_FAULT_INPUT;
        return rls->faults;
    }

    const ladrc_real_t h = rls->dt_s;
    const ladrc_real_t lambda = forgetting_rate(rls->trace, rls->p_bound, rls->lambda0_per_s);
    rls->lambda_per_s = lambda;
    const ladrc_real_t mu = ladrc_exp(-lambda * h);
    const ladrc_real_t inv_mu = LADRC_R(1.0) / mu;
    ladrc_real_t *u = rls->u;
    ladrc_real_t *d = rls->d;
    const ladrc_real_t *theta = rls->theta;

    /* f = U^T phi, g = h D f (h: P is in continuous units), prior error e;
     * then Bierman's update, one column j at a time and in place (column j
     * reads only columns < j of the old factors, and U_ij before it writes
     * it), with beta_j = mu + h sum_{k<=j} D_k f_k^2:
     *   D_j <- D_j beta_j-1 / (beta_j mu),  U_ij <- U_ij - nu_i f_j / beta_j-1,
     * nu accumulating the unnormalised gain; the gain is nu / beta_n. The new
     * trace and the soundness of the new factors are gathered on the way. */
    ladrc_real_t nu[LADRC_RLS_MAX_PARAMS];
    ladrc_real_t e = y;
    ladrc_real_t beta = mu;
    ladrc_real_t inv_beta = inv_mu;
    ladrc_real_t tr = LADRC_R(0.0);
    int sound = 1;
    for (unsigned j = 0u; j < n; ++j) {
        ladrc_real_t *col = &u[u_index(0u, j)]; /* U(i,j) at col[i] */
        ladrc_real_t f = phi[j];
        for (unsigned i = 0u; i < j; ++i) {
            f += col[i] * phi[i];
        }
        const ladrc_real_t g = h * d[j] * f;
        e -= phi[j] * theta[j];
        const ladrc_real_t beta_prev = beta;
        const ladrc_real_t p = -f * inv_beta;
        beta = beta_prev + f * g;
        inv_beta = LADRC_R(1.0) / beta;
        d[j] *= beta_prev * inv_beta * inv_mu;
        ladrc_real_t column_norm = LADRC_R(1.0);
        for (unsigned i = 0u; i < j; ++i) {
            const ladrc_real_t old = col[i];
            col[i] = old + nu[i] * p;
            nu[i] += old * g;
            column_norm += col[i] * col[i];
            sound &= ladrc_is_finite(col[i]);
        }
        nu[j] = g;
        tr += d[j] * column_norm;
        sound &= ladrc_is_positive(d[j]);
    }

    /* nu becomes the new theta. */
    const ladrc_real_t step = e * inv_beta;
    int theta_ok = 1;
    for (unsigned i = 0u; i < n; ++i) {
        nu[i] = theta[i] + nu[i] * step;
        theta_ok &= ladrc_is_finite(nu[i]);
    }
    /* Bound: only rounding can take the trace above k0 (rls.h). */
    if (sound && tr > rls->p_bound) {
        const ladrc_real_t scale = rls->p_bound * RLS_CLAMP_FRACTION / tr;
        for (unsigned j = 0u; j < n; ++j) {
            d[j] *= scale;
            sound &= ladrc_is_positive(d[j]);
        }
        tr = trace_of(u, d, n);
    }
    if (!sound || !theta_ok) {
        /* Restart P so that the next sample meets a sound covariance; theta
         * takes its update only if that is finite. */
        restart_p(rls);
        rls->faults = LADRC_FAULT_STATE;
    } else {
        rls->trace = tr;
        rls->faults = LADRC_FAULT_NONE;
    }
    if (theta_ok) {
        for (unsigned i = 0u; i < n; ++i) {
            rls->theta[i] = nu[i];
        }
    }
    return rls->faults;
}

ladrc_fault_t ladrc_rls_update(ladrc_rls_t *rls, const ladrc_real_t *phi, ladrc_real_t y)
{
    LADRC_REQUIRE(rls != NULL && phi != NULL, LADRC_FAULT_STATE);
    /* The count the estimators use most laid out flat (HP, one tone: 3; LP
     * has its own one-parameter form, ladrc_rls1_t); the others through the
     * loops. */
    switch (rls->n_params) {
    case 3u:
        return update_n(rls, phi, y, 3u);
    default:
        return update_n(rls, phi, y, rls->n_params);
    }
}

ladrc_real_t ladrc_rls_predict(const ladrc_rls_t *rls, const ladrc_real_t *phi)
{
    LADRC_REQUIRE(rls != NULL && phi != NULL, LADRC_R(0.0));
    ladrc_real_t y = LADRC_R(0.0);
    for (unsigned i = 0u; i < rls->n_params; ++i) {
        y += phi[i] * rls->theta[i];
    }
    return y;
}

void ladrc_rls_shift(ladrc_rls_t *rls, unsigned k, ladrc_real_t delta)
{
    LADRC_REQUIRE_VOID(rls != NULL);
    if (k < rls->n_params) {
        const ladrc_real_t moved = rls->theta[k] + delta;
        if (ladrc_is_finite(moved)) {
            rls->theta[k] = moved;
        }
    }
}

const ladrc_real_t *ladrc_rls_get_theta(const ladrc_rls_t *rls)
{
    LADRC_REQUIRE(rls != NULL, NULL);
    return rls->theta;
}

ladrc_real_t ladrc_rls_get_p_norm(const ladrc_rls_t *rls)
{
    LADRC_REQUIRE(rls != NULL, LADRC_R(0.0));
    return rls->trace;
}

ladrc_real_t ladrc_rls_get_p_bound(const ladrc_rls_t *rls)
{
    LADRC_REQUIRE(rls != NULL, LADRC_R(0.0));
    return rls->p_bound;
}

ladrc_real_t ladrc_rls_get_p(const ladrc_rls_t *rls, uint8_t row, uint8_t col)
{
    LADRC_REQUIRE(rls != NULL, LADRC_R(0.0));
    const unsigned n = rls->n_params;
    if (row >= n || col >= n) {
        return LADRC_R(0.0);
    }
    /* Same order for (i,j) and (j,i): P_ij = sum_{k>=j} U_ik D_k U_jk, i <= j. */
    const unsigned i = (row < col) ? row : col;
    const unsigned j = (row < col) ? col : row;
    ladrc_real_t p = LADRC_R(0.0);
    for (unsigned k = j; k < n; ++k) {
        const ladrc_real_t uik = (k == i) ? LADRC_R(1.0) : rls->u[u_index(i, k)];
        const ladrc_real_t ujk = (k == j) ? LADRC_R(1.0) : rls->u[u_index(j, k)];
        p += uik * rls->d[k] * ujk;
    }
    return p;
}

ladrc_real_t ladrc_rls_get_lambda(const ladrc_rls_t *rls)
{
    LADRC_REQUIRE(rls != NULL, LADRC_R(0.0));
    return rls->lambda_per_s;
}

ladrc_fault_t ladrc_rls_get_faults(const ladrc_rls_t *rls)
{
    LADRC_REQUIRE(rls != NULL, LADRC_FAULT_STATE);
    return rls->faults;
}

ladrc_status_t ladrc_rls_set_lambda0(ladrc_rls_t *rls, ladrc_real_t lambda0_per_s)
{
    if (rls == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!lambda0_is_valid(lambda0_per_s, rls->dt_s)) {
        return LADRC_ERR_RLS_LAMBDA0;
    }
    rls->lambda0_per_s = lambda0_per_s;
    return LADRC_OK;
}

/* --- one parameter, regressor 1 (rls.h) --------------------------------------- */

ladrc_status_t ladrc_rls1_init(ladrc_rls1_t *rls, const ladrc_rls_config_t *cfg)
{
    if (rls == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (cfg->n_params != 1u) {
        return LADRC_ERR_RLS_N_PARAMS;
    }
    const ladrc_status_t status = check_config(cfg);
    if (status != LADRC_OK) {
        return status;
    }
    rls->dt_s = cfg->dt_s;
    rls->lambda0_per_s = cfg->lambda0_per_s;
    rls->p_bound = cfg->p_bound;
    rls->p_initial = cfg->p_initial;
    ladrc_rls1_reset(rls);
    return LADRC_OK;
}

/* P restarted as restart_p does at n = 1 (its trace: initial_trace(p_initial, 1) = p_initial). */
void rls1_restart_p(ladrc_rls1_t *rls)
{
    rls->p = rls->p_initial;
    rls->settled = 0u;
    rls->gain = LADRC_R(0.0);
    rls->inv_beta = LADRC_R(0.0);
}

void ladrc_rls1_reset(ladrc_rls1_t *rls)
{
    LADRC_REQUIRE_VOID(rls != NULL);
    rls->theta = LADRC_R(0.0);
    rls1_restart_p(rls);
    rls->faults = LADRC_FAULT_NONE;
}

/* update_n at n = 1, phi = 1, operation for operation: f = 1, so g = h D,
 * beta = mu + g, D <- D mu / (beta mu) and tr(P) = D; U is empty. Each
 * product with phi = 1 is exact, so leaving it out changes no bit
 * (tests/test_rls1.c compares the two on every path). */
ladrc_fault_t rls1_full_update(ladrc_rls1_t *rls, ladrc_real_t y)
{
    const ladrc_real_t h = rls->dt_s;
    const ladrc_real_t p_before = rls->p;
    const ladrc_real_t lambda = forgetting_rate(p_before, rls->p_bound, rls->lambda0_per_s);
    const ladrc_real_t mu = ladrc_exp(-lambda * h);
    const ladrc_real_t inv_mu = LADRC_R(1.0) / mu;
    const ladrc_real_t g = h * p_before;
    const ladrc_real_t e = y - rls->theta;
    const ladrc_real_t inv_beta = LADRC_R(1.0) / (mu + g);
    ladrc_real_t p = p_before * (mu * inv_beta * inv_mu);
    int sound = ladrc_is_positive(p);
    const ladrc_real_t theta = rls->theta + g * (e * inv_beta);
    const int theta_ok = ladrc_is_finite(theta);
    if (sound && p > rls->p_bound) {
        p *= rls->p_bound * RLS_CLAMP_FRACTION / p;
        sound &= ladrc_is_positive(p);
    }
    if (!sound || !theta_ok) {
        rls1_restart_p(rls);
        rls->faults = LADRC_FAULT_STATE;
    } else {
        /* P is a function of P alone here: the same P, the same update for good. */
        rls->settled = (p == p_before) ? 1u : 0u;
        rls->gain = g;
        rls->inv_beta = inv_beta;
        rls->p = p;
        rls->faults = LADRC_FAULT_NONE;
    }
    if (theta_ok) {
        rls->theta = theta;
    }
    return rls->faults;
}

ladrc_fault_t ladrc_rls1_update(ladrc_rls1_t *rls, ladrc_real_t y)
{
    LADRC_REQUIRE(rls != NULL, LADRC_FAULT_STATE);
    return rls1_update(rls, y);
}
