/* SPDX-License-Identifier: BSD-3-Clause */
/* The small plant the HP-on-the-gyro tests fly (test_hp_gyro.c,
 * test_hp_gate.c): one axis of a 1.96 kg quad, J = 0.0139 kg m^2, a 30 ms
 * motor lag the axis models, 1 kHz, wc = 6.4, wo = 51 (what tune = margins
 * gives LP-MLADRC there), 0.5 deg/s of white gyro noise and 0.05 deg of
 * angle noise. */
#ifndef LADRC_TEST_GYRO_QUAD_H
#define LADRC_TEST_GYRO_QUAD_H

#include "ladrc/axis.h"
#include "test_noise.h"
#include "test_plant.h"

#include <math.h>

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

/* The realistic sensor and air the gate tests fly (test_hp_gate.c,
 * test_hp_gate_faults.c). The gyro: white noise and the first two rotor
 * lines of a hovering quad as a 100 Hz low-pass leaves them, 0.7 deg/s at
 * 130 Hz and 0.1 deg/s at 260 Hz. Turbulence: 1 rad/s^2 RMS with a 3 rad/s
 * corner, so it has power at the tones' frequencies (at 2 rad/s^2 the
 * online search no longer moves a tone from its 3 rad/s first guess). */
#define LINE1_RAD_S (0.7 * DEG)
#define LINE1_HZ 130.0
#define LINE2_RAD_S (0.1 * DEG)
#define LINE2_HZ 260.0
#define TURB_RMS_RAD_S2 1.0
#define TURB_CORNER_RAD_S 3.0

/* The rotor lines on the gyro at t (rad/s). */
static inline double test_gyro_quad_lines_rad_s(double t_s)
{
    return LINE1_RAD_S * sin(2.0 * PI * LINE1_HZ * t_s) + LINE2_RAD_S * sin(2.0 * PI * LINE2_HZ * t_s);
}

/* The axis in turbulence: angle y, rate w, the motor's torque m (N m) and
 * the turbulence's low-pass state (rad/s^2). */
typedef struct {
    double y_rad, w_rad_s, m_Nm, turb_rad_s2;
} test_gyro_quad_air_t;

/* One tick: the command u (N m) through the motor lag, the turbulence and
 * d_rad_s2 more on the axis. */
static inline void test_gyro_quad_air_step(test_gyro_quad_air_t *p, double u_Nm, double d_rad_s2, unsigned *seed)
{
    const double a = exp(-TURB_CORNER_RAD_S * DT_S);
    p->turb_rad_s2 = a * p->turb_rad_s2 + TURB_RMS_RAD_S2 * sqrt(1.0 - a * a) * test_gaussian(seed);
    const double d = p->turb_rad_s2 + d_rad_s2;
    double dy, dw;
    test_lag_step(DT_S, TAU_S, u_Nm, &p->m_Nm, &dy, &dw);
    p->y_rad += p->w_rad_s * DT_S + dy / J_KG_M2 + 0.5 * d * DT_S * DT_S;
    p->w_rad_s += dw / J_KG_M2 + d * DT_S;
}

#endif
