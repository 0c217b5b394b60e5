/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file tuning.h
 * @brief Tuning helpers for LADRC: controller bandwidth from a settling time,
 *        observer bandwidth from the controller's, b0 from an axis inertia.
 *
 * Every helper validates its arguments, writes its result only on success and
 * returns a status naming the bad argument.
 */
#ifndef LADRC_TUNING_H
#define LADRC_TUNING_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** 2% settling time of the ideal loop (s + wc)^2 in units of 1/wc: the root
 *  of (1 + x) exp(-x) = 0.02. */
#define LADRC_SETTLING_2PCT_WC LADRC_R(5.8339217)

/**
 * The paper's empirical rule (eq. 17): wc = (1.09 + 2.09 N - 0.07 N^2) / T,
 * N the plant order (1..3), T the 98% settling time (s). For N = 2 it gives
 * 4.99 / T, which settles about 17% later than T (see the exact helper).
 * @param settling_time_s  T (s), finite, > 0
 * @param plant_order      N, 1..3
 * @param wc_rad_s         out: wc (rad/s), written only on LADRC_OK
 * @retval LADRC_OK                  wc written
 * @retval LADRC_ERR_NULL            wc_rad_s is NULL
 * @retval LADRC_ERR_SETTLING_TIME_S settling_time_s not finite or not > 0
 * @retval LADRC_ERR_PLANT_ORDER     plant_order outside 1..3
 */
ladrc_status_t ladrc_tune_wc_from_settling(ladrc_real_t settling_time_s, int plant_order, ladrc_real_t *wc_rad_s);

/** Exact for the second-order loop: wc = LADRC_SETTLING_2PCT_WC / T.
 *  @param settling_time_s  T (s), finite, > 0
 *  @param wc_rad_s         out: wc (rad/s), written only on LADRC_OK
 *  @retval LADRC_OK                  wc written
 *  @retval LADRC_ERR_NULL            wc_rad_s is NULL
 *  @retval LADRC_ERR_SETTLING_TIME_S settling_time_s not finite or not > 0 */
ladrc_status_t ladrc_tune_wc_from_settling_exact(ladrc_real_t settling_time_s, ladrc_real_t *wc_rad_s);

/** wo = ratio * wc; the paper uses ratio 5 (usual range 3..10).
 *  @param wc_rad_s  wc (rad/s), finite, > 0
 *  @param ratio     wo / wc, finite, > 0
 *  @param wo_rad_s  out: wo (rad/s), written only on LADRC_OK
 *  @retval LADRC_OK           wo written
 *  @retval LADRC_ERR_NULL     wo_rad_s is NULL
 *  @retval LADRC_ERR_WC_RAD_S wc_rad_s not finite or not > 0
 *  @retval LADRC_ERR_WO_RATIO ratio not finite or not > 0 */
ladrc_status_t ladrc_tune_wo_from_wc(ladrc_real_t wc_rad_s, ladrc_real_t ratio, ladrc_real_t *wo_rad_s);

/** b0 = 1 / J in rad/s^2 per N m, for a torque command on an axis of inertia J.
 *  @param inertia_kg_m2  J (kg m^2), finite, > 0
 *  @param b0             out: b0 (rad/s^2 per N m), written only on LADRC_OK
 *  @retval LADRC_OK              b0 written
 *  @retval LADRC_ERR_NULL        b0 is NULL
 *  @retval LADRC_ERR_INERTIA_KG_M2 inertia_kg_m2 not finite or not > 0 */
ladrc_status_t ladrc_tune_b0_from_inertia(ladrc_real_t inertia_kg_m2, ladrc_real_t *b0);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_TUNING_H */
