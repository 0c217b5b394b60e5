/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file reso.h
 * @brief Second-order extended state observer on a measured rate (RESO):
 *        for w' = f + b0 u it estimates z1 ~ w (rad/s) and z2 ~ f (rad/s^2),
 *        the observer of the rate-loop ADRC (axis.h, LADRC_VARIANT_RATE_ADRC).
 *
 * Continuous model (docs/method.md, "Rate-loop ADRC"), both poles at -wo:
 *
 *     z1' = z2 + 2 wo (w - z1) + a          a = b0 u + known acceleration
 *     z2' =      wo^2 (w - z1) + g          g = known rate of change of f
 *
 * Discretised as the LESO's ZOH 'current observer' (leso.h), once per tick
 * with the newest measurement w_k and the input a applied over the previous
 * step: predict p = Ad z + Bd a + Gd g with Ad = [1 h; 0 1], Bd = [h 0]',
 * Gd = [h^2/2 h]', then correct z = p + l (w_k - p1) with, for
 * beta = exp(-wo h),
 *
 *     l = [1 - beta^2, (1 - beta)^2 / h].
 *
 * The error obeys e_k = (I - l C) Ad e_k-1, whose trace 2 - l1 - l2 h = 2 beta
 * and determinant 1 - l1 = beta^2 put both poles at beta, the image of -wo
 * under the sampling (l1 / h -> 2 wo and l2 / h -> wo^2 as h -> 0).
 */
#ifndef LADRC_RESO_H
#define LADRC_RESO_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** RESO configuration (ladrc_reso_init validates it); can live in flash. */
typedef struct {
    ladrc_real_t dt_s;     /**< fixed step h (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t wo_rad_s; /**< observer bandwidth (rad/s), > 0 (the ZOH poles beta lie in (0, 1) for any) */
    ladrc_real_t b0;       /**< input gain: rad/s^2 of w' per unit of u, finite, non-zero */
} ladrc_reso_config_t;

/** Observer state; owned by the caller. Gains are per-sample, derived at init. */
typedef struct {
    ladrc_real_t z1; /**< estimate of the rate w (rad/s) */
    ladrc_real_t z2; /**< estimate of the total disturbance f (rad/s^2) */
    /** @{ */
    ladrc_real_t l1, l2; /**< correction gains per sample (1, 1/s) */
    /** @} */
    /** @{ */
    ladrc_real_t h_s, h2_2; /**< h (s), h^2/2 (s^2) */
    /** @} */
    ladrc_real_t b0;      /**< input gain of the config */
    ladrc_fault_t faults; /**< flags of the latest step */
} ladrc_reso_t;

/**
 * Validates cfg in the order below, derives the per-sample gains and resets
 * the estimate to 0.
 * @param[out] obs  the observer to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK           set up
 * @retval LADRC_ERR_NULL     obs or cfg is NULL
 * @retval LADRC_ERR_DT_S     dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_WO_RAD_S wo_rad_s not finite or not > 0
 * @retval LADRC_ERR_B0       b0 not finite or 0
 */
ladrc_status_t ladrc_reso_init(ladrc_reso_t *obs, const ladrc_reso_config_t *cfg);

/**
 * Restarts at rest on w0: z = (w0, 0), faults cleared.
 * @param obs   the observer; NULL: nothing happens
 * @param w0_rad_s  the rate to start on (rad/s); non-finite: 0
 */
void ladrc_reso_reset(ladrc_reso_t *obs, ladrc_real_t w0_rad_s);

/**
 * One tick: predict over the step, correct with the measured rate.
 * Any non-finite argument, or a non-finite result, leaves the estimate
 * unchanged and raises LADRC_FAULT_INPUT / LADRC_FAULT_STATE.
 * @param obs          the observer; NULL: LADRC_FAULT_STATE, nothing changes
 * @param rate_rad_s   newest measured rate (rad/s)
 * @param u            input applied over the previous step (units of 1/b0 rad/s^2)
 * @param accel_known  known acceleration added to b0 u (rad/s^2), 0 if none
 * @param f_rate_known known rate of change of f (rad/s^3), 0 if none
 * @return the step's fault flags (also kept in obs->faults)
 */
ladrc_fault_t ladrc_reso_step(ladrc_reso_t *obs, ladrc_real_t rate_rad_s, ladrc_real_t u, ladrc_real_t accel_known,
                              ladrc_real_t f_rate_known);

/** @param obs  the observer; NULL: 0
 *  @return the rate estimate z1 (rad/s) */
ladrc_real_t ladrc_reso_get_rate(const ladrc_reso_t *obs);

/** @param obs  the observer; NULL: 0
 *  @return the total disturbance estimate z2 (rad/s^2) */
ladrc_real_t ladrc_reso_get_disturbance(const ladrc_reso_t *obs);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_RESO_H */
