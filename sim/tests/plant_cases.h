/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the plant tests (test_sim_plant*.c) share: a tolerance assert in
 * double, the paper's vehicle without drag, hover and the inverse
 * allocation of docs/method.md eq. 33. Included once by each of those
 * programs, after unity.h.
 */
#ifndef LADRC_SIM_TESTS_PLANT_CASES_H
#define LADRC_SIM_TESTS_PLANT_CASES_H

#include "plant/plant.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* |actual - expected| <= tol, compared in double (Unity's float asserts
 * would round both to float). */
#define ASSERT_CLOSE(tol, expected, actual) assert_close((tol), (expected), (actual), __LINE__)
static inline void assert_close(double tol, double expected, double actual, int line)
{
    char msg[160];
    const double diff = fabs(actual - expected);
    snprintf(msg, sizeof msg, "expected %.17g, was %.17g (|diff| %.3g > %.3g)", expected, actual, diff, tol);
    UNITY_TEST_ASSERT(diff <= tol, line, msg);
}

/* The paper's vehicle without drag: closed forms need kt = 0. */
static inline sim_vehicle_t vehicle_no_drag(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.rot_drag_Nm_s = 0.0;
    return v;
}

static inline double hover_w2(const sim_vehicle_t *v)
{
    return v->mass_kg * v->g_m_s2 / (4.0 * v->thrust_coeff_N_s2);
}

/* docs/method.md eq. 33, with a = U_L/kL, p = tau_x/(l kL), q = tau_y/(l kL),
 * r = tau_z/b. */
static inline void inverse_allocation(const sim_vehicle_t *v, double thrust_N, const double torque_Nm[3], double w2[4])
{
    const double a = thrust_N / v->thrust_coeff_N_s2;
    const double p = torque_Nm[0] / (v->arm_m * v->thrust_coeff_N_s2);
    const double q = torque_Nm[1] / (v->arm_m * v->thrust_coeff_N_s2);
    const double r = torque_Nm[2] / v->yaw_coeff_Nm_s2;
    w2[0] = a / 4.0 - q / 2.0 - r / 4.0;
    w2[1] = a / 4.0 + p / 2.0 + r / 4.0;
    w2[2] = a / 4.0 + q / 2.0 - r / 4.0;
    w2[3] = a / 4.0 - p / 2.0 + r / 4.0;
}

/* w^2 commands that give torque tau on `axis` alone, around hover. */
static inline void torque_command(const sim_vehicle_t *v, int axis, double tau, double cmd[4])
{
    double torque[3] = {0.0, 0.0, 0.0};
    torque[axis] = tau;
    inverse_allocation(v, 4.0 * v->thrust_coeff_N_s2 * hover_w2(v), torque, cmd);
}

/* 5 sin(7 t + axis) rad/s^2 on each axis. */
static inline void sine_disturbance(double t_s, void *ctx, double d_out[3])
{
    (void)ctx;
    for (int axis = 0; axis < 3; ++axis) {
        d_out[axis] = 5.0 * sin(7.0 * t_s + axis);
    }
}

/* n steps of RK4 on x' = -lambda x multiply x by R(z)^n, z = -lambda h,
 * R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24. Relative to exp(z n): per step
 * exp(z) - R(z) = z^5/120 + ..., so after n steps |R^n / exp(zn) - 1| ~
 * n |z|^5/120. */
static inline double rk4_decay(double z, int n)
{
    return pow(1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0, n);
}

static inline double rk4_decay_bound(double z, int n)
{
    return 1.2 * n * pow(fabs(z), 5) / 120.0; /* 20% for the z^6 terms */
}

#endif
