/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Propeller vibration on the simulated IMU: each rotor shakes the frame at
 * its own speed and at multiples of it, and the gyro and accelerometer
 * carry it.
 *
 * Rotor i turns through the angle theta_i, integrated from its simulated
 * speed w_i = sqrt(w_i^2) (rad/s) by the trapezoid rule, tick by tick, so
 * the lines follow the rotor speeds as throttle and attitude change. Order
 * k (a multiple of the rotor rate: 1 an imbalance, B the blade pass of a
 * B-bladed propeller, 2B its harmonic) adds, on body axis a,
 *   gyro_a  += amp_k gain_a sin(k theta_i + phase_ika)          (rad/s)
 *   angle_a += -amp_k gain_a cos(k theta_i + phase_ika) / (k w_i) (rad)
 *   accel_a += accel_k gain_a cos(k theta_i + phase_ika)        (m/s^2)
 * summed over the rotors. The angle carries what an attitude estimator
 * integrating the gyro sees of it (the integral of the gyro term at a
 * steady speed); the phases are uniform in [0, 2 pi), drawn at init from
 * the seed. Four rotors at nearly one speed add to an rms per axis of about
 * amp_k gain_a sqrt(2) per order.
 *
 * No heap, no stdio, no globals.
 */
#ifndef LADRC_SIM_VIBRATION_H
#define LADRC_SIM_VIBRATION_H

#include <stdint.h>

#include "rng.h"

#define SIM_VIB_MAX_ORDERS 4
#define SIM_VIB_ROTORS 4

/* What sim_vibration_init accepts (the scenario parser refuses the rest at
 * its key): orders in [SIM_VIB_ORDER_MIN, SIM_VIB_ORDER_MAX] multiples of
 * the rotor rate, amplitudes and axis gains from 0 to their maxima. */
#define SIM_VIB_ORDER_MIN 1e-3
#define SIM_VIB_ORDER_MAX 100.0
#define SIM_VIB_GYRO_MAX_RAD_S 100.0  /* per rotor, per order */
#define SIM_VIB_ACCEL_MAX_M_S2 1000.0 /* per rotor, per order */
#define SIM_VIB_AXIS_GAIN_MAX 100.0

typedef struct {
    int n_orders;                          /* 0: no vibration */
    double order[SIM_VIB_MAX_ORDERS];      /* multiples of the rotor rate, > 0 */
    double gyro_rad_s[SIM_VIB_MAX_ORDERS]; /* amplitude per rotor on the gyro, >= 0 */
    double accel_m_s2[SIM_VIB_MAX_ORDERS]; /* amplitude per rotor on the accelerometer, >= 0 */
    double axis_gain[3];                   /* roll, pitch, yaw (x, y, z) scale, >= 0 */
} sim_vibration_config_t;

typedef struct {
    sim_vibration_config_t cfg;
    double theta_rad[SIM_VIB_ROTORS];                        /* each rotor's angle */
    double speed_rad_s[SIM_VIB_ROTORS];                      /* its speed at the latest tick */
    double phase_cos[SIM_VIB_ROTORS][SIM_VIB_MAX_ORDERS][3]; /* each line's seeded phase per axis, */
    double phase_sin[SIM_VIB_ROTORS][SIM_VIB_MAX_ORDERS][3]; /* as its cosine and sine */
    int started;                                             /* 0 until the first tick gave the speeds */
} sim_vibration_t;

/* Returns 0, or -1 (v untouched) when v or cfg is NULL, n_orders is outside
 * [0, SIM_VIB_MAX_ORDERS], or a value is not finite or out of its range. */
int sim_vibration_init(sim_vibration_t *v, const sim_vibration_config_t *cfg, uint64_t seed);

/* One tick of dt_s with the rotors at w2_rad2_s2 (negative: turning
 * backwards at sqrt(-w2)); adds the vibration to gyro_rad_s, angle_rad and
 * accel_m_s2 (any may be NULL). The first tick starts every rotor at
 * theta 0. */
void sim_vibration_tick(sim_vibration_t *v, const double w2_rad2_s2[SIM_VIB_ROTORS], double dt_s, double gyro_rad_s[3],
                        double angle_rad[3], double accel_m_s2[3]);

/* Rotor i's speed of the latest tick as a frequency (Hz), for an RPM
 * filter the way ESC telemetry gives it; 0 before the first tick. */
double sim_vibration_rotor_hz(const sim_vibration_t *v, int i);

#endif
