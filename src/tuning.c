/* SPDX-License-Identifier: BSD-3-Clause */
/* Tuning helpers (see tuning.h). */
#include "ladrc/tuning.h"

ladrc_status_t ladrc_tune_wc_from_settling(ladrc_real_t settling_time_s, int plant_order, ladrc_real_t *wc_rad_s)
{
    if (wc_rad_s == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_is_positive(settling_time_s)) {
        return LADRC_ERR_SETTLING_TIME_S;
    }
    if (plant_order < 1 || plant_order > 3) {
        return LADRC_ERR_PLANT_ORDER;
    }
    const ladrc_real_t n = (ladrc_real_t)plant_order;
    *wc_rad_s = (LADRC_R(1.09) + LADRC_R(2.09) * n - LADRC_R(0.07) * n * n) / settling_time_s;
    return LADRC_OK;
}

ladrc_status_t ladrc_tune_wc_from_settling_exact(ladrc_real_t settling_time_s, ladrc_real_t *wc_rad_s)
{
    if (wc_rad_s == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_is_positive(settling_time_s)) {
        return LADRC_ERR_SETTLING_TIME_S;
    }
    *wc_rad_s = LADRC_SETTLING_2PCT_WC / settling_time_s;
    return LADRC_OK;
}

ladrc_status_t ladrc_tune_wo_from_wc(ladrc_real_t wc_rad_s, ladrc_real_t ratio, ladrc_real_t *wo_rad_s)
{
    if (wo_rad_s == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_is_positive(wc_rad_s)) {
        return LADRC_ERR_WC_RAD_S;
    }
    if (!ladrc_is_positive(ratio)) {
        return LADRC_ERR_WO_RATIO;
    }
    *wo_rad_s = ratio * wc_rad_s;
    return LADRC_OK;
}

ladrc_status_t ladrc_tune_b0_from_inertia(ladrc_real_t inertia_kg_m2, ladrc_real_t *b0)
{
    if (b0 == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_is_positive(inertia_kg_m2)) {
        return LADRC_ERR_INERTIA_KG_M2;
    }
    *b0 = LADRC_R(1.0) / inertia_kg_m2;
    return LADRC_OK;
}
