/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file leso.h
 * @brief Third-order linear extended state observer (LESO) for one axis
 *        y'' = f + b0 u: estimates z1 ~ y, z2 ~ y', z3 ~ f (total disturbance).
 *
 * Continuous model (docs/method.md eq. 9-10), bandwidth wo, all poles at -wo:
 *
 *     z1' = z2 + 3 wo (y - z1)
 *     z2' = z3 + 3 wo^2 (y - z1) + a          a = b0 u + known acceleration
 *     z3' =      wo^3 (y - z1) + g             g = known rate of change of f
 *
 * Two discretisations at fixed step h, both called once per tick with the
 * newest measurement y_k and the input a applied over the previous step:
 *
 * - ZOH (default), the 'current observer' of the zero-order-hold model
 *   (Miklosovic/Herbst): predict p = Ad z + Bd a + Gd g with
 *   Ad = [1 h h^2/2; 0 1 h; 0 0 1], Bd = [h^2/2 h 0]', Gd = [h^3/6 h^2/2 h]',
 *   then correct z = p + l (y_k - p1) with, for beta = exp(-wo h),
 *   l = [1 - beta^3, 3/(2h) (1-beta)^2 (1+beta), (1-beta)^3 / h^2].
 *   The error obeys e_k = (I - l C) Ad e_k-1, whose three poles sit at beta.
 * - EULER, the paper's explicit Euler step of the equations above with the
 *   newest y: error poles at 1 - wo h, stable only for wo h < 2 (init rejects
 *   the rest with LADRC_ERR_LESO_EULER_UNSTABLE).
 */
#ifndef LADRC_LESO_H
#define LADRC_LESO_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How the LESO is discretised. */
typedef enum {
    LADRC_LESO_ZOH = 0,  /**< zero-order-hold current observer, poles at exp(-wo h) */
    LADRC_LESO_EULER = 1 /**< explicit Euler (paper), poles at 1 - wo h */
} ladrc_leso_method_t;

/** LESO configuration (ladrc_leso_init validates it); can live in flash. */
typedef struct {
    ladrc_real_t dt_s;          /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t wo_rad_s;      /**< observer bandwidth (rad/s), > 0 */
    ladrc_real_t b0;            /**< input gain: rad/s^2 of y'' per unit of u, finite, non-zero */
    ladrc_leso_method_t method; /**< discretisation */
} ladrc_leso_config_t;

/** Observer state; owned by the caller. Gains are per-sample, derived at init. */
typedef struct {
    ladrc_real_t z1; /**< estimate of y (rad) */
    ladrc_real_t z2; /**< estimate of y' (rad/s) */
    ladrc_real_t z3; /**< estimate of the total disturbance f (rad/s^2) */
    /** @{ */
    ladrc_real_t l1, l2, l3; /**< correction gains per sample */
    /** @} */
    /** @{ */
    ladrc_real_t h_s, h2_2, h3_6; /**< h (s), h^2/2 (s^2), h^3/6 (s^3) */
    /** @} */
    ladrc_real_t b0;            /**< input gain of the config */
    ladrc_leso_method_t method; /**< discretisation of the config */
    ladrc_fault_t faults;       /**< flags of the latest step */
} ladrc_leso_t;

/**
 * Validates cfg in the order below, derives the per-sample gains and resets
 * the estimate to 0.
 * @param[out] obs  the observer to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                      set up
 * @retval LADRC_ERR_NULL                obs or cfg is NULL
 * @retval LADRC_ERR_DT_S                dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_WO_RAD_S            wo_rad_s not finite or not > 0
 * @retval LADRC_ERR_B0                  b0 not finite or 0
 * @retval LADRC_ERR_LESO_EULER_UNSTABLE method EULER with wo_rad_s * dt_s >= 2
 * @retval LADRC_ERR_LESO_METHOD         method not a ladrc_leso_method_t
 */
ladrc_status_t ladrc_leso_init(ladrc_leso_t *obs, const ladrc_leso_config_t *cfg);

/**
 * Restarts at rest on y0: z = (y0, 0, 0), faults cleared.
 * @param obs  the observer; NULL: nothing happens
 * @param y0   the measurement to start on (rad); non-finite: 0
 */
void ladrc_leso_reset(ladrc_leso_t *obs, ladrc_real_t y0);

/**
 * One tick: predict over the step, correct with y.
 * Any non-finite argument, or a non-finite result, leaves the estimate
 * unchanged and raises LADRC_FAULT_INPUT / LADRC_FAULT_STATE.
 * @param obs          the observer; NULL: LADRC_FAULT_STATE, nothing changes
 * @param y            newest measurement (rad)
 * @param u            input applied over the previous step (units of 1/b0 rad/s^2)
 * @param accel_known  known acceleration added to b0 u (rad/s^2), 0 if none
 * @param f_rate_known known rate of change of f (rad/s^3), 0 if none
 * @return the step's fault flags (also kept in obs->faults)
 */
ladrc_fault_t ladrc_leso_step(ladrc_leso_t *obs, ladrc_real_t y, ladrc_real_t u, ladrc_real_t accel_known,
                              ladrc_real_t f_rate_known);

/**
 * Hands the part accel_rad_s2 of the disturbance estimate z3 over to a known
 * input that starts with the next step (z3 -= accel_rad_s2), so that
 * z3 + known input stays what it was.
 * @param obs           the observer; NULL: nothing happens
 * @param accel_rad_s2  the part handed over (rad/s^2); a non-finite result
 *                      leaves z3 unchanged
 */
void ladrc_leso_hand_over(ladrc_leso_t *obs, ladrc_real_t accel_rad_s2);

/** A second estimate run with an observer's gains (e.g. the observer's view
 *  of a still plant): 12 bytes instead of a whole ladrc_leso_t. */
typedef struct {
    /** @{ */
    ladrc_real_t z1, z2, z3; /**< as in ladrc_leso_t (rad, rad/s, rad/s^2) */
    /** @} */
} ladrc_leso_twin_t;

/** ladrc_leso_hand_over for a twin.
 *  @param twin          the twin; NULL: nothing happens
 *  @param accel_rad_s2  the part of z3 handed over (rad/s^2); a non-finite
 *                       result leaves z3 unchanged */
void ladrc_leso_twin_hand_over(ladrc_leso_twin_t *twin, ladrc_real_t accel_rad_s2);

/** Starts a twin at rest on y0: z = (y0, 0, 0).
 *  @param twin  the twin; NULL: nothing happens
 *  @param y0    the measurement to start on (rad); non-finite: 0 */
void ladrc_leso_twin_reset(ladrc_leso_twin_t *twin, ladrc_real_t y0);

/**
 * One tick of twin with obs's gains, the same equations and guards as
 * ladrc_leso_step; obs is not changed.
 * @param obs          the observer whose gains are used
 * @param twin         the estimate advanced
 * @param y            newest measurement (rad)
 * @param u            input applied over the previous step (units of 1/b0 rad/s^2)
 * @param accel_known  known acceleration added to b0 u (rad/s^2), 0 if none
 * @param f_rate_known known rate of change of f (rad/s^3), 0 if none
 * @return the step's fault flags (a twin keeps none); obs or twin NULL:
 *         LADRC_FAULT_STATE
 */
ladrc_fault_t ladrc_leso_step_twin(const ladrc_leso_t *obs, ladrc_leso_twin_t *twin, ladrc_real_t y, ladrc_real_t u,
                                   ladrc_real_t accel_known, ladrc_real_t f_rate_known);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_LESO_H */
