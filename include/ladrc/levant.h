/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file levant.h
 * @brief Levant's 3rd-order robust exact differentiator: the reference shaper
 *        of the modified LADRC. Estimates r, r', r'' and r''' of a raw
 *        reference (states z0..z3, the paper's c1..c4).
 *
 * Continuous form (docs/method.md section 3), with e = z0 - r and
 * [e]^a = |e|^a sign(e):
 *
 *     z0' = z1 - k3 [e]^(3/4)        z2' = z3 - k1 [e]^(1/4)
 *     z1' = z2 - k2 [e]^(1/2)        z3' =    - k0 sign(e)
 *
 * This non-recursive form is the paper's recursive one, exactly: from
 * c2 - v1 = L1 [e]^(3/4) and so on, k3 = L1, k2 = L2 L1^(2/3),
 * k1 = L3 L2^(1/2) L1^(1/3), k0 = L4. Gains are continuous-time:
 * - LIPSCHITZ (default): from a bound L >= |r''''| (rad/s^4), Levant's
 *   published coefficients for this order, k3 = 3 L^(1/4), k2 = 4.16 L^(1/2),
 *   k1 = 3.06 L^(3/4), k0 = 1.1 L (recursive lambda = 1.1, 1.5, 2, 3).
 *   A larger L converges faster and lets more noise through.
 * - EXPLICIT: the recursive gains L1..L4 as given (paper: 20, 20, 20, L4
 *   not given). They must be well proportioned for the differentiator to
 *   converge (the LIPSCHITZ ones are); nothing checks it.
 *
 * Discrete time, step h = dt_s, per-sample gains g_i = h k_i, one sample r_k
 * per step, p = exp(hA) z the exact Taylor prediction of the integrator chain
 * (p0 = z0 + h z1 + h^2/2 z2 + h^3/6 z3, p1 = z1 + h z2 + h^2/2 z3,
 * p2 = z2 + h z3, p3 = z3):
 *
 * - IMPLICIT (default, no chattering): the corrections use the error after
 *   the update, e = z0+ - r_k, the unique solution of
 *       e + g3 [e]^(3/4) + h g2 [e]^(1/2) + h^2 g1 [e]^(1/4) + h^3 g0 s = p0 - r_k
 *   with s = sign(e), or the s in [-1, 1] that fits when e = 0 (set-valued
 *   sign: e = 0 exactly when |p0 - r_k| <= h^3 g0); then
 *       z0+ = r_k + e
 *       z1+ = p1 - g2 [e]^(1/2) - h g1 [e]^(1/4) - 11/6 h^2 g0 s
 *       z2+ = p2 - g1 [e]^(1/4) - 2 h g0 s
 *       z3+ = p3 - g0 s
 *   The power terms enter as in implicit Euler; the sign term is spread with
 *   the dead-beat gain of the integrator chain, so once e = 0 the remaining
 *   error vanishes in three steps instead of chattering by g0 per step.
 *   Exact on cubics (r'''' = 0) up to rounding. Float samples are rounded
 *   to about 1e-8 rad, usually more than h^3 g0: what is left is that
 *   rounding noise through the differentiator, not a limit cycle. Cost: the
 *   quartic in |e|^(1/4) is solved by Newton's method from a start blended
 *   from its terms' bounds, at most 3 iterations (measured, Levant's
 *   coefficients and the paper's gains) of about 12 flops and a division.
 *   The new state estimates the instant t_k of r_k.
 * - HD: the homogeneous discrete differentiator (Livne and Levant 2014), with
 *   the prediction error e = z0 - r_k:
 *       z0+ = p0 - g3 [e]^(3/4)   z1+ = p1 - g2 [e]^(1/2)
 *       z2+ = p2 - g1 [e]^(1/4)   z3+ = p3 - g0 sign(e)
 *   About 35 flops and two square roots.
 * - EULER: the paper's explicit Euler step: HD with p = (z0 + h z1,
 *   z1 + h z2, z2 + h z3, z3). Lags r' by half a step.
 *   Both explicit forms kick r''' by g0 every step, and with large gains
 *   (the paper's, at 1 kHz) fall into a limit cycle: they chatter. Their new
 *   state estimates the instant t_k + h.
 *
 * Sign convention: e = estimate - reference; a positive e pulls every
 * estimate down. Units follow the input: for r in rad, r' is rad/s, r''
 * rad/s^2, r''' rad/s^3. Inside, z0 is kept as its offset from the last
 * sample, so the error is formed without cancelling two large values.
 */
#ifndef LADRC_LEVANT_H
#define LADRC_LEVANT_H

#include "ladrc/td.h"
#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How the differentiator is discretised. */
typedef enum {
    LADRC_LEVANT_IMPLICIT = 0, /**< implicit, set-valued sign: no chattering (default) */
    LADRC_LEVANT_HD = 1,       /**< explicit homogeneous discrete differentiator */
    LADRC_LEVANT_EULER = 2     /**< explicit Euler (paper) */
} ladrc_levant_method_t;

/** Where the differentiator's gains come from. */
typedef enum {
    LADRC_LEVANT_GAINS_LIPSCHITZ = 0, /**< from lipschitz_rad_s4 with Levant's coefficients (default) */
    LADRC_LEVANT_GAINS_EXPLICIT = 1   /**< recursive-form gains l1..l4 as given */
} ladrc_levant_gains_t;

/** Differentiator configuration (ladrc_levant_init validates it). */
typedef struct {
    ladrc_real_t dt_s;             /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_levant_method_t method;  /**< discretisation */
    ladrc_levant_gains_t gains;    /**< which gain fields are read */
    ladrc_real_t lipschitz_rad_s4; /**< LIPSCHITZ: L >= |r''''| (rad/s^4), finite, > 0 */
    ladrc_real_t l1;               /**< EXPLICIT: L1 (rad^(1/4)/s), finite, > 0 */
    ladrc_real_t l2;               /**< EXPLICIT: L2 (rad^(1/3)/s), finite, > 0 */
    ladrc_real_t l3;               /**< EXPLICIT: L3 (rad^(1/2)/s), finite, > 0 */
    ladrc_real_t l4;               /**< EXPLICIT: L4 (rad/s^4), finite, > 0 */
} ladrc_levant_config_t;

/** Differentiator state; owned by the caller. Read it through the getters
 *  (faults may be read directly); never write it. */
typedef struct {
    ladrc_real_t w;      /**< z0 minus r_last (rad) */
    ladrc_real_t r_last; /**< last finite reference sample (rad) */
    ladrc_real_t z1;     /**< estimate of r' (rad/s) */
    ladrc_real_t z2;     /**< estimate of r'' (rad/s^2) */
    ladrc_real_t z3;     /**< estimate of r''' (rad/s^3) */
    ladrc_real_t h_s;    /**< step h (s) */
    /** @{ */
    ladrc_real_t g3, g2, g1, g0; /**< per-sample gains h k3 .. h k0 */
    /** @} */
    uint8_t method;       /**< a ladrc_levant_method_t */
    ladrc_fault_t faults; /**< flags of the latest step */
} ladrc_levant_t;

/**
 * Validates cfg and derives the gains, then resets to rest at 0. Errors, in
 * this order: LADRC_ERR_NULL, LADRC_ERR_DT_S, LADRC_ERR_LEVANT_METHOD,
 * LADRC_ERR_LEVANT_GAINS, then the fields of the chosen gains
 * (LADRC_ERR_LEVANT_LIPSCHITZ, or LADRC_ERR_LEVANT_L1 .. _L4), then
 * LADRC_ERR_LEVANT_RANGE when dt_s and the gains give per-sample
 * coefficients (up to h^4 k0) that overflow or vanish in ladrc_real_t.
 * On an error (not LADRC_ERR_NULL) *lev is zeroed: its steps raise
 * LADRC_FAULT_STATE and output 0.
 * @param[out] lev  the differentiator to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                   set up
 * @retval LADRC_ERR_NULL             lev or cfg is NULL
 * @retval LADRC_ERR_DT_S             dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_LEVANT_METHOD    method not a ladrc_levant_method_t
 * @retval LADRC_ERR_LEVANT_LIPSCHITZ gains LIPSCHITZ: lipschitz_rad_s4 not finite or not > 0
 * @retval LADRC_ERR_LEVANT_L1        gains EXPLICIT: l1 not finite or not > 0
 * @retval LADRC_ERR_LEVANT_L2        gains EXPLICIT: l2 not finite or not > 0
 * @retval LADRC_ERR_LEVANT_L3        gains EXPLICIT: l3 not finite or not > 0
 * @retval LADRC_ERR_LEVANT_L4        gains EXPLICIT: l4 not finite or not > 0
 * @retval LADRC_ERR_LEVANT_GAINS     gains not a ladrc_levant_gains_t
 * @retval LADRC_ERR_LEVANT_RANGE     per-sample coefficients overflow or vanish
 */
ladrc_status_t ladrc_levant_init(ladrc_levant_t *lev, const ladrc_levant_config_t *cfg);

/** Restarts at rest on r_rad: r = r_rad, r' = r'' = r''' = 0, faults cleared.
 *  A non-finite r_rad restarts at rest on the current estimate of r and
 *  raises LADRC_FAULT_INPUT.
 *  @param lev    the differentiator; NULL: nothing happens
 *  @param r_rad  the reference to rest on (rad) */
void ladrc_levant_reset(ladrc_levant_t *lev, ladrc_real_t r_rad);

/**
 * One step with the newest reference sample r_rad; writes the new estimate
 * (r, r', r'') to out (out may be NULL). A non-finite r_rad leaves the state
 * unchanged, raises LADRC_FAULT_INPUT and writes the held estimate; the next
 * finite steps continue as if the bad samples had been skipped. An update
 * that would make the state non-finite is refused the same way with
 * LADRC_FAULT_STATE.
 * @param lev    the differentiator
 * @param r_rad  newest reference sample (rad)
 * @param out    out: the estimate (rad, rad/s, rad/s^2), or NULL
 * @return the fault flags of this step (also kept in lev->faults); lev
 *         NULL: LADRC_FAULT_STATE, nothing written
 */
ladrc_fault_t ladrc_levant_step(ladrc_levant_t *lev, ladrc_real_t r_rad, ladrc_ref_t *out);

/** The current estimate (r, r', r'').
 *  @param lev  the differentiator
 *  @param out  out: (r, r', r'') in rad, rad/s, rad/s^2; lev or out NULL:
 *              nothing written */
void ladrc_levant_get_ref(const ladrc_levant_t *lev, ladrc_ref_t *out);

/** The current estimate of r''' (rad/s^3).
 *  @param lev  the differentiator; NULL: 0
 *  @return r''' (rad/s^3) */
ladrc_real_t ladrc_levant_get_dddr(const ladrc_levant_t *lev);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_LEVANT_H */
