/* SPDX-License-Identifier: BSD-3-Clause */
/* The small plant the HP-on-the-gyro tests fly (test_hp_gyro.c,
 * test_hp_gate.c): one axis of a 1.96 kg quad, J = 0.0139 kg m^2, a 30 ms
 * motor lag the axis models, 1 kHz, wc = 6.4, wo = 51 (what tune = margins
 * gives LP-MLADRC there), 0.5 deg/s of white gyro noise and 0.05 deg of
 * angle noise. */
#ifndef LADRC_TEST_GYRO_QUAD_H
#define LADRC_TEST_GYRO_QUAD_H

#include "ladrc/axis.h"

#define DT_S 1e-3
#define J_KG_M2 0.0139
#define TAU_S 0.03
#define WC_RAD_S 6.4
#define WO_RAD_S 51.0
#define PI 3.14159265358979
#define DEG (PI / 180.0)
#define GYRO_NOISE_RAD_S (0.5 * DEG)
#define ANGLE_NOISE_RAD (0.05 * DEG)

/* The axis's config: the library's defaults for the variant, these gains
 * and motor, and HP's fit on the gyro. */
static inline ladrc_axis_config_t test_gyro_quad_config(ladrc_variant_t variant)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.wc_rad_s = (ladrc_real_t)WC_RAD_S;
    cfg.wo_rad_s = (ladrc_real_t)WO_RAD_S;
    cfg.motor_tau_s = (ladrc_real_t)TAU_S;
    cfg.hp_sample = LADRC_HP_SAMPLE_GYRO;
    return cfg;
}

#endif
