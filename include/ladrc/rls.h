/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file rls.h
 * @brief Small fixed-size recursive least squares (RLS) estimator with
 *        bounded-gain forgetting, for the adaptive disturbance estimators.
 *
 * Model y_k = phi_k^T theta + noise, n = n_params <= LADRC_RLS_MAX_PARAMS.
 * Continuous law (docs/method.md section 5, Slotine and Li 8.7), e = phi^T theta - y:
 *
 *     theta' = -P phi e
 *     P'     = lambda P - P phi phi^T P,      lambda = lambda0 (1 - ||P|| / k0)
 *
 * Discrete step h = dt_s, once per sample, ||P|| = trace(P):
 *
 *     lambda_k = lambda0 (1 - tr(P_k-1) / k0)     (0 once tr(P) >= (1 - 1e-4) k0)
 *     mu_k     = exp(-lambda_k h)                 per-sample forgetting factor
 *     g_k      = h P phi / (mu_k + h phi^T P phi)
 *     theta_k  = theta_k-1 + g_k (y_k - phi_k^T theta_k-1)
 *     P_k      = (P_k-1 - g_k phi_k^T P_k-1) / mu_k
 *
 * Units and gains: P keeps the continuous law's units (1/(s phi^2)) and k0,
 * lambda0 (1/s) and p_initial are continuous-time; h P is the usual
 * per-sample RLS covariance. As h -> 0 the step tends to the law above.
 *
 * Why these choices:
 * - mu = exp(-lambda h) is the exact decay of the information matrix
 *   P^-1 over one step of the continuous law; it lies in (0, 1] for any
 *   lambda h (1 - lambda h reaches 0 at lambda h = 1).
 * - The trace bounds the spectral norm of a positive definite P
 *   (||P||_2 <= tr P) and every entry (|P_ij| <= sqrt(P_ii P_jj)), and
 *   costs n additions. Hence P = p_initial I needs n p_initial <= k0.
 * - An update subtracts a positive semidefinite term before dividing by mu,
 *   so tr(P_k) <= tr(P_k-1) exp(lambda_k h). With lambda0 h <= 1 (checked
 *   at init) the map tr -> tr exp(lambda h) is increasing with fixed point
 *   k0, so in exact arithmetic the step never leaves tr(P) <= k0, with or
 *   without excitation. A P above k0 after rounding is scaled back to
 *   (1 - 5e-5) k0. Forgetting stops 1e-4 below k0, so without excitation
 *   P reaches a fixed point (same state, bit for bit) instead of a cycle.
 * - P is held as P = U D U^T (U unit upper triangular, D diagonal; Bierman's
 *   factorised update): symmetric by construction, positive definite while
 *   D > 0, and accurate when one sample of huge excitation makes P nearly
 *   singular, where the plain update loses definiteness in float. 6 reals
 *   for n = 3, as many as the upper triangle of P. Cost per update: one
 *   exp, n + 2 divisions and about 2 n^2 + 10 n multiply-adds; tr(P) is
 *   kept with the factors, so the forgetting rate costs one division.
 *
 * Guards: a non-finite phi or y leaves the state untouched
 * (LADRC_FAULT_INPUT). A step whose factors come out not finite or with a
 * D not > 0, or whose theta would not be finite, restarts P at p_initial I
 * and keeps theta's update only if that is finite (LADRC_FAULT_STATE): the
 * update runs in place on the factors (no copy of them on the stack), and a
 * P that made theta overflow is not one to keep.
 */
#ifndef LADRC_RLS_H
#define LADRC_RLS_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most tones the HP estimator models per axis (estimator.h); a build-time
 *  constant because it sets the state size. At least 1. */
#ifndef LADRC_HP_MAX_TONES
#define LADRC_HP_MAX_TONES 2
#endif
/** Largest number of parameters; sets the state size: the most any estimator
 *  here uses (HP: a bias and a cosine and sine per tone). */
#define LADRC_RLS_MAX_PARAMS (1 + 2 * LADRC_HP_MAX_TONES)
/** Entries of the strict upper triangle of U. */
#define LADRC_RLS_U_SIZE (LADRC_RLS_MAX_PARAMS * (LADRC_RLS_MAX_PARAMS - 1) / 2)

/** RLS configuration (ladrc_rls_init validates it). */
typedef struct {
    uint8_t n_params;           /**< 1..LADRC_RLS_MAX_PARAMS */
    ladrc_real_t dt_s;          /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t lambda0_per_s; /**< maximum forgetting rate (1/s), >= 0 (0 = no forgetting), lambda0 h <= 1 */
    ladrc_real_t p_bound;       /**< k0: bound on tr(P) (1/(s phi^2)), > 0 */
    ladrc_real_t p_initial;     /**< P after init/reset = p_initial I; > 0 and n_params p_initial <= p_bound */
} ladrc_rls_config_t;

/**
 * Estimator state; owned by the caller. Read it through the getters;
 * u and d are public only so that tests and diagnostics can see the factors.
 */
typedef struct {
    ladrc_real_t theta[LADRC_RLS_MAX_PARAMS]; /**< parameter estimate */
    ladrc_real_t u[LADRC_RLS_U_SIZE];         /**< U(i,j), i < j, at u[j (j - 1) / 2 + i] */
    ladrc_real_t d[LADRC_RLS_MAX_PARAMS];     /**< D(j), > 0 */
    ladrc_real_t trace;                       /**< tr(U D U^T), kept with the factors */
    ladrc_real_t lambda_per_s;                /**< forgetting rate of the last update */
    ladrc_real_t dt_s;                        /**< of the config (s) */
    ladrc_real_t lambda0_per_s;               /**< maximum forgetting rate (1/s) */
    ladrc_real_t p_bound;                     /**< of the config */
    ladrc_real_t p_initial;                   /**< of the config */
    uint8_t n_params;                         /**< parameters in use */
    ladrc_fault_t faults;                     /**< flags of the latest update */
} ladrc_rls_t;

/**
 * The one-parameter RLS with the regressor 1 (y_k = theta + noise: a
 * tracker of y, the LP estimator's), the same law and step as ladrc_rls_t
 * at n_params 1 and phi = 1, bit for bit, in 36 B instead of 108 (on
 * float). With phi = 1, P's evolution does not depend on the data; in
 * float and in double it mostly lands on a fixed point within a few
 * hundred samples (some settings end in a cycle of 2 or 3 values instead:
 * 24 of 112 measured in float, 20 in double; the paper's LP setting settles
 * in float and cycles in double). Once an update leaves P exactly as it
 * found it, every later update would compute the same forgetting, gain and
 * P again: they reuse the gain (no exp, no division) until a reset or a
 * fault.
 */
typedef struct {
    ladrc_real_t theta;         /**< the estimate */
    ladrc_real_t p;             /**< P = tr(P) (1/s) */
    ladrc_real_t gain;          /**< settled: g = h P of the update (per sample) */
    ladrc_real_t inv_beta;      /**< settled: 1 / (mu + g) of the update */
    ladrc_real_t dt_s;          /**< of the config (s) */
    ladrc_real_t lambda0_per_s; /**< of the config (1/s) */
    ladrc_real_t p_bound;       /**< of the config */
    ladrc_real_t p_initial;     /**< of the config */
    uint8_t settled;            /**< 1: the latest full update left P as it was */
    ladrc_fault_t faults;       /**< flags of the latest update */
} ladrc_rls1_t;

/**
 * Validates cfg as ladrc_rls_init does (n_params must be 1) and starts at
 * theta = 0, P = p_initial.
 * @param[out] rls  the estimator to set up
 * @param[in]  cfg  its configuration
 * @return as ladrc_rls_init
 */
ladrc_status_t ladrc_rls1_init(ladrc_rls1_t *rls, const ladrc_rls_config_t *cfg);

/** Restarts at theta = 0 and P = p_initial; clears the faults.
 *  @param rls  the estimator; NULL: nothing happens */
void ladrc_rls1_reset(ladrc_rls1_t *rls);

/**
 * One sample of y = theta: ladrc_rls_update with phi = 1, bit for bit.
 * @param rls  the estimator
 * @param y    measurement
 * @return flags of this update as ladrc_rls_update's; rls NULL:
 *         LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_rls1_update(ladrc_rls1_t *rls, ladrc_real_t y);

/**
 * Validates cfg (first bad field, in the order below) and starts at
 * theta = 0, P = p_initial I.
 * @param[out] rls  the estimator to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK               set up
 * @retval LADRC_ERR_NULL         rls or cfg is NULL
 * @retval LADRC_ERR_RLS_N_PARAMS n_params outside 1..LADRC_RLS_MAX_PARAMS
 * @retval LADRC_ERR_DT_S         dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_RLS_LAMBDA0  lambda0_per_s not finite, < 0, or times dt_s > 1
 * @retval LADRC_ERR_RLS_P_BOUND  p_bound not finite or not > 0
 * @retval LADRC_ERR_RLS_P_INITIAL p_initial not finite, not > 0, or n_params p_initial > p_bound
 */
ladrc_status_t ladrc_rls_init(ladrc_rls_t *rls, const ladrc_rls_config_t *cfg);

/**
 * Restarts at theta = theta0 (n_params entries; NULL or non-finite entries
 * give 0) and P = p_initial I; clears the faults and the last lambda.
 * ladrc_rls_reset(rls, ladrc_rls_get_theta(rls)) restarts P only.
 * @param rls     the estimator; NULL: nothing happens
 * @param theta0  the start estimate (n_params entries), or NULL for 0
 */
void ladrc_rls_reset(ladrc_rls_t *rls, const ladrc_real_t *theta0);

/**
 * Restarts with n_params parameters (the others settings kept) at theta0, as
 * ladrc_rls_reset does (theta0 may be this estimator's own theta). Rejected,
 * state unchanged, as init would reject the count.
 * @param rls       the estimator
 * @param n_params  the new count, 1..LADRC_RLS_MAX_PARAMS
 * @param theta0    the start estimate (n_params entries), or NULL for 0
 * @retval LADRC_OK                restarted
 * @retval LADRC_ERR_NULL          rls is NULL
 * @retval LADRC_ERR_RLS_N_PARAMS  n_params outside 1..LADRC_RLS_MAX_PARAMS
 * @retval LADRC_ERR_RLS_P_INITIAL n_params p_initial > p_bound
 */
ladrc_status_t ladrc_rls_restart(ladrc_rls_t *rls, uint8_t n_params, const ladrc_real_t *theta0);

/**
 * One sample of y = phi^T theta (see the file comment for the equations).
 * @param rls estimator
 * @param phi regressor, n_params entries (unit of y per unit of theta)
 * @param y   measurement
 * @return flags of this update: LADRC_FAULT_NONE, LADRC_FAULT_INPUT (a
 *         non-finite phi or y: state untouched) or LADRC_FAULT_STATE (refused,
 *         or P restarted); rls or phi NULL: LADRC_FAULT_STATE, nothing changes
 */
ladrc_fault_t ladrc_rls_update(ladrc_rls_t *rls, const ladrc_real_t *phi, ladrc_real_t y);

/** Prediction phi^T theta.
 *  @param rls  the estimator
 *  @param phi  regressor, n_params entries
 *  @return phi^T theta (unit of y); non-finite for a non-finite phi; rls or
 *          phi NULL: 0 */
ladrc_real_t ladrc_rls_predict(const ladrc_rls_t *rls, const ladrc_real_t *phi);

/** Moves parameter k of the estimate by delta, P unchanged: for a part of
 *  the estimate that another estimator takes over (a non-finite result
 *  leaves it as it was).
 *  @param rls    the estimator; NULL: nothing happens
 *  @param k      the parameter, < n_params (others: nothing happens)
 *  @param delta  the move (unit of theta[k]) */
void ladrc_rls_shift(ladrc_rls_t *rls, unsigned k, ladrc_real_t delta);

/** The estimate.
 *  @param rls  the estimator
 *  @return theta, n_params entries, valid while rls is; rls NULL: NULL */
const ladrc_real_t *ladrc_rls_get_theta(const ladrc_rls_t *rls);

/** tr(P), the norm the forgetting and the bound use.
 *  @param rls  the estimator; NULL: 0
 *  @return tr(P) (1/(s phi^2)) */
ladrc_real_t ladrc_rls_get_p_norm(const ladrc_rls_t *rls);

/** k0, the configured bound on tr(P) (1/(s phi^2)): ladrc_rls_get_p_norm
 *  never exceeds it after init, reset, restart or any update (file comment).
 *  @param rls  the estimator; NULL: 0
 *  @return k0 (1/(s phi^2)) */
ladrc_real_t ladrc_rls_get_p_bound(const ladrc_rls_t *rls);

/** Entry (row, col) of P = U D U^T, both < n_params (0 otherwise); P(i,j) and
 *  P(j,i) are the same number.
 *  @param rls  the estimator; NULL: 0
 *  @param row  row index
 *  @param col  column index
 *  @return P(row, col) (1/(s phi^2)) */
ladrc_real_t ladrc_rls_get_p(const ladrc_rls_t *rls, uint8_t row, uint8_t col);

/** Forgetting rate lambda (1/s) of the last update that got past the input
 *  check; 0 after init or reset.
 *  @param rls  the estimator; NULL: 0
 *  @return lambda (1/s) */
ladrc_real_t ladrc_rls_get_lambda(const ladrc_rls_t *rls);

/** Changes the maximum forgetting rate from the next update on (e.g. a memory
 *  that follows a signal's period). Rejected, state unchanged, as init would
 *  reject it.
 *  @param rls            the estimator
 *  @param lambda0_per_s  the new maximum forgetting rate (1/s)
 *  @retval LADRC_OK              changed
 *  @retval LADRC_ERR_NULL        rls is NULL
 *  @retval LADRC_ERR_RLS_LAMBDA0 lambda0_per_s not finite, < 0, or times dt_s > 1 */
ladrc_status_t ladrc_rls_set_lambda0(ladrc_rls_t *rls, ladrc_real_t lambda0_per_s);

/** Flags of the latest update.
 *  @param rls  the estimator
 *  @return the flags; rls NULL: LADRC_FAULT_STATE */
ladrc_fault_t ladrc_rls_get_faults(const ladrc_rls_t *rls);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_RLS_H */
