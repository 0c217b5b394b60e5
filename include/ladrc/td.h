/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file td.h
 * @brief Han's tracking differentiator (TD, "fhan"): the traditional LADRC
 *        reference shaper. Gives a smooth r, r' and r'' from a raw reference.
 *
 * Discrete time, fixed step h = dt_s, acceleration bound R = accel_rad_s2,
 * filter factor h0 = h0_s (h0 >= h; larger h0 filters more):
 *
 *     a_k     = fhan(x1_k - r_k, x2_k, R, h0)      |a_k| <= R always
 *     x1_k+1  = x1_k + h x2_k
 *     x2_k+1  = x2_k + h a_k
 *
 * The step outputs (r, r', r'') = (x1_k+1, x2_k+1, a_k). Units follow the
 * input: for an angle in rad, r' is rad/s and r'' rad/s^2. Gains are
 * continuous-time (R in rad/s^2, h0 in s).
 */
#ifndef LADRC_TD_H
#define LADRC_TD_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A shaped reference and its first two time derivatives. */
typedef struct {
    ladrc_real_t r;   /**< reference (rad) */
    ladrc_real_t dr;  /**< first derivative (rad/s) */
    ladrc_real_t ddr; /**< second derivative (rad/s^2) */
} ladrc_ref_t;

/** Tracking-differentiator configuration (ladrc_td_init validates it). */
typedef struct {
    ladrc_real_t dt_s;         /**< fixed step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t accel_rad_s2; /**< acceleration bound R of the shaped reference (rad/s^2), > 0 */
    ladrc_real_t h0_s;         /**< fhan filter factor (s), >= dt_s */
} ladrc_td_config_t;

/** TD state; owned by the caller. Read x1, x2, a and faults directly; never write them. */
typedef struct {
    ladrc_real_t dt_s;         /**< fixed step (s), of the config */
    ladrc_real_t accel_rad_s2; /**< acceleration bound R (rad/s^2), of the config */
    ladrc_real_t h0_s;         /**< filter factor (s), of the config */
    ladrc_real_t d;            /**< accel h0: fhan's speed step (rad/s), derived at init */
    ladrc_real_t d0;           /**< h0 d: fhan's linear-zone half-width (rad) */
    ladrc_real_t x1;           /**< shaped reference (rad) */
    ladrc_real_t x2;           /**< its rate (rad/s) */
    ladrc_real_t a;            /**< last acceleration (rad/s^2) */
    ladrc_fault_t faults;      /**< flags of the latest step */
} ladrc_td_t;

/**
 * Han's time-optimal synthesis function for a double integrator sampled at
 * h0_s with acceleration bound accel: the acceleration that brings (x1, x2)
 * to the origin fastest (x1 = position error, x2 = its rate; the result has
 * the opposite sign to the error it removes). |result| <= accel for any
 * input, huge or infinite ones included. Returns 0 when the result is
 * undefined: NaN x1 or x2, or accel or h0_s not finite and > 0.
 * @param x1     position error (rad)
 * @param x2     its rate (rad/s)
 * @param accel  acceleration bound (rad/s^2), finite, > 0
 * @param h0_s   sample time of the synthesis (s), finite, > 0
 * @return the acceleration (rad/s^2), within +-accel; 0 when undefined
 */
ladrc_real_t ladrc_fhan(ladrc_real_t x1, ladrc_real_t x2, ladrc_real_t accel, ladrc_real_t h0_s);

/**
 * Validates cfg in the order below and resets to 0. On a config error
 * (not LADRC_ERR_NULL) *td is zeroed: a step on it outputs 0, never moves.
 * @param[out] td   the differentiator to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                  set up
 * @retval LADRC_ERR_NULL            td or cfg is NULL
 * @retval LADRC_ERR_DT_S            dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_TD_ACCEL_RAD_S2 accel_rad_s2 not finite or not > 0
 * @retval LADRC_ERR_TD_H0_S         h0_s not finite or < dt_s
 */
ladrc_status_t ladrc_td_init(ladrc_td_t *td, const ladrc_td_config_t *cfg);

/** Restarts at rest on r_rad (x1 = r_rad, x2 = 0, faults cleared). A non-finite
 *  r_rad restarts at rest on the current x1 and raises LADRC_FAULT_INPUT.
 *  @param td     the differentiator; NULL: nothing happens
 *  @param r_rad  the reference to rest on (rad) */
void ladrc_td_reset(ladrc_td_t *td, ladrc_real_t r_rad);

/**
 * One step towards raw reference r_rad; writes (r, r', r'') to out (out may
 * be NULL). A non-finite r_rad leaves the state unchanged, raises
 * LADRC_FAULT_INPUT and writes the held state (x1, x2, 0); the next finite
 * steps continue as if the bad samples had been skipped. An update that
 * would overflow the state does the same with LADRC_FAULT_STATE.
 * @param td     the differentiator
 * @param r_rad  raw reference (rad)
 * @param out    out: the shaped reference (rad, rad/s, rad/s^2), or NULL
 * @return the fault flags of this step (also kept in td->faults); td NULL:
 *         LADRC_FAULT_STATE, nothing written
 */
ladrc_fault_t ladrc_td_step(ladrc_td_t *td, ladrc_real_t r_rad, ladrc_ref_t *out);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_TD_H */
