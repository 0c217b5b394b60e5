/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator plant: forces and their inverse, hover, and the attitude
 * dynamics term by term against closed-form solutions (the RK4 stages and
 * accuracy, the rotors and the plants side by side are in
 * test_sim_plant_rk4.c, test_sim_plant_rotors.c, test_sim_plant_group.c). */
#include "unity.h"
#include "plant/plant.h"
#include "plant_cases.h"
#include "plant/rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_forces_match_a_hand_computation(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    const double w2[4] = {1e5, 2e5, 3e5, 4e5};
    double thrust, torque[3];
    sim_plant_forces(&v, w2, &thrust, torque);
    /* U = 2.98e-5 * 1e6 = 29.8 N; tau_x = 0.165 * 2.98e-5 * (2e5 - 4e5) = -0.9834;
     * tau_y = 0.165 * 2.98e-5 * (3e5 - 1e5) = 0.9834; tau_z = 2e-6 * (-1 + 2 - 3 + 4) * 1e5 = 0.4 */
    ASSERT_CLOSE(1e-13, 29.8, thrust);
    ASSERT_CLOSE(1e-15, -0.9834, torque[0]);
    ASSERT_CLOSE(1e-15, 0.9834, torque[1]);
    ASSERT_CLOSE(1e-15, 0.4, torque[2]);
    /* thrust is optional */
    double torque2[3];
    sim_plant_forces(&v, w2, NULL, torque2);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(torque2[i] == torque[i]);
    }
}

static void test_forces_and_the_inverse_allocation_of_eq_33_round_trip(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sim_rng_t r;
    sim_rng_seed(&r, 33);
    for (int k = 0; k < 1000; ++k) {
        /* thrust 0..20 N, torques within +-0.5 N m (roll, pitch), +-0.05 (yaw) */
        const double thrust = 20.0 * sim_rng_uniform(&r);
        const double torque[3] = {sim_rng_uniform(&r) - 0.5, sim_rng_uniform(&r) - 0.5,
                                  0.1 * (sim_rng_uniform(&r) - 0.5)};
        double w2[4], thrust_back, torque_back[3];
        inverse_allocation(&v, thrust, torque, w2);
        sim_plant_forces(&v, w2, &thrust_back, torque_back);
        /* w^2 up to ~2e5: a few ulp of it (3e-11) times kL or l kL */
        ASSERT_CLOSE(1e-13, thrust, thrust_back);
        for (int i = 0; i < 3; ++i) {
            ASSERT_CLOSE(1e-13, torque[i], torque_back[i]);
        }
        /* and the other way round */
        double w2_back[4];
        inverse_allocation(&v, thrust_back, torque_back, w2_back);
        for (int i = 0; i < 4; ++i) {
            ASSERT_CLOSE(1e-9, w2[i], w2_back[i]);
        }
    }
}

static void test_hover_rotors_give_weight_and_no_torque_and_keep_the_vehicle_at_rest(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double w0 = 0.8 * 9.81 / (4.0 * 2.98e-5); /* 65839.0 rad^2/s^2 */
    double thrust, torque[3];
    for (int i = 0; i < 4; ++i) {
        ASSERT_CLOSE(1e-9, w0, p.w2_rad2_s2[i]);
    }
    sim_plant_forces(&v, p.w2_rad2_s2, &thrust, torque);
    ASSERT_CLOSE(1e-13, 0.8 * 9.81, thrust);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(torque[i] == 0.0);
    }
    /* a second of hover commands at 1 kHz leaves everything exactly at rest */
    const double cmd[4] = {w0, w0, w0, w0};
    for (int k = 0; k < 1000; ++k) {
        sim_plant_step(&p, cmd, 1e-3, 2, NULL, NULL);
    }
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(p.angle_rad[i] == 0.0);
        TEST_ASSERT_TRUE(p.rate_rad_s[i] == 0.0);
    }
    ASSERT_CLOSE(1e-12, 1.0, p.t_s);
}

static void test_constant_torque_from_rest_gives_a_parabola_on_that_axis_only(void)
{
    /* RK4 integrates angle'' = const exactly (the solution is a quadratic),
     * so only rounding remains: ~1e-16 relative per step over 1000 steps,
     * measured 5e-15 (angle) and 2e-14 (rate) relative; 1e-12 leaves a wide
     * margin while an O(h^k) integration error would be >= 1e-3 */
    const sim_vehicle_t v = vehicle_no_drag();
    for (int axis = 0; axis < 3; ++axis) {
        const double tau = axis == 2 ? 0.01 : 0.02; /* N m */
        double cmd[4];
        torque_command(&v, axis, tau, cmd);
        sim_plant_t p;
        sim_plant_init(&p, &v);
        const double alpha = tau / v.inertia_kg_m2[axis];
        for (int k = 1; k <= 1000; ++k) {
            sim_plant_step(&p, cmd, 1e-3, 1, NULL, NULL);
            const double t = k * 1e-3;
            ASSERT_CLOSE(1e-12 * 0.5 * alpha, 0.5 * alpha * t * t, p.angle_rad[axis]);
            ASSERT_CLOSE(1e-12 * alpha, alpha * t, p.rate_rad_s[axis]);
        }
        /* the other axes: no coupling, since two of the three rates are zero,
         * and no torque but the allocation's rounding: the w^2 (~6.6e4, ulp
         * 1.5e-11) leave up to b * 2 ulp / Jz = 5e-15 rad/s^2 on yaw, i.e.
         * 3e-15 rad after 1 s (measured 1.6e-15) */
        for (int i = 0; i < 3; ++i) {
            if (i != axis) {
                ASSERT_CLOSE(1e-14, 0.0, p.angle_rad[i]);
                ASSERT_CLOSE(1e-14, 0.0, p.rate_rad_s[i]);
            }
        }
    }
}

static void test_drag_decays_each_rate_as_exp_minus_kt_over_j_t(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v); /* kt = 0.09 N m s */
    for (int axis = 0; axis < 3; ++axis) {
        sim_plant_t p;
        sim_plant_init(&p, &v);
        const double w0 = 10.0; /* rad/s on one axis: no coupling */
        p.rate_rad_s[axis] = w0;
        const double cmd[4] = {p.w2_rad2_s2[0], p.w2_rad2_s2[1], p.w2_rad2_s2[2], p.w2_rad2_s2[3]};
        const double lambda = v.rot_drag_Nm_s / v.inertia_kg_m2[axis]; /* 16.5 or 8.3 1/s */
        const double h = 1e-3;
        const int n = 500;
        for (int k = 0; k < n; ++k) {
            sim_plant_step(&p, cmd, h, 1, NULL, NULL);
        }
        const double t = n * h;
        /* the RK4 amplification to rounding (1e-13 relative: 500 steps of a
         * few ulp; measured 2e-16) */
        const double rk4 = w0 * rk4_decay(-lambda * h, n);
        ASSERT_CLOSE(1e-13 * w0, rk4, p.rate_rad_s[axis]);
        /* and the exact solution within the RK4 truncation bound
         * (roll: 500 * 0.0165^5 / 120 = 5.1e-9 relative, measured 5.2e-9) */
        const double exact = w0 * exp(-lambda * t);
        ASSERT_CLOSE(rk4_decay_bound(-lambda * h, n) * exact + 1e-13 * w0, exact, p.rate_rad_s[axis]);
        /* the angle integrates the rate: lambda angle + rate = w0 is a linear
         * invariant of the ODE, which RK4 keeps to rounding */
        ASSERT_CLOSE(1e-13 * w0, w0, lambda * p.angle_rad[axis] + p.rate_rad_s[axis]);
    }
}

static void test_coupling_terms_have_the_signs_of_eq_2(void)
{
    /* distinct inertias so that every coupling coefficient is non-zero */
    sim_vehicle_t v = vehicle_no_drag();
    v.inertia_kg_m2[0] = 0.01;
    v.inertia_kg_m2[1] = 0.02;
    v.inertia_kg_m2[2] = 0.04;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    p.rate_rad_s[0] = 1.0;
    p.rate_rad_s[1] = 2.0;
    p.rate_rad_s[2] = 3.0;
    const double zero[3] = {0.0, 0.0, 0.0};
    double acc[3];
    sim_plant_accel(&p, zero, zero, acc);
    /* phi''   = (Jy - Jz) theta' psi' / Jx = (0.02 - 0.04) * 2 * 3 / 0.01 = -12
     * theta'' = (Jz - Jx) phi' psi' / Jy   = (0.04 - 0.01) * 1 * 3 / 0.02 = 4.5
     * psi''   = (Jx - Jy) theta' phi' / Jz = (0.01 - 0.02) * 2 * 1 / 0.04 = -0.5 */
    ASSERT_CLOSE(1e-12, -12.0, acc[0]);
    ASSERT_CLOSE(1e-12, 4.5, acc[1]);
    ASSERT_CLOSE(1e-12, -0.5, acc[2]);

    /* torque, drag and disturbance add as (tau - kt w) / J + d */
    v.rot_drag_Nm_s = 0.1;
    sim_plant_init(&p, &v);
    p.rate_rad_s[0] = 1.0;
    p.rate_rad_s[1] = 2.0;
    p.rate_rad_s[2] = 3.0;
    const double torque[3] = {0.05, -0.04, 0.2};
    const double dist[3] = {7.0, -8.0, 9.0};
    sim_plant_accel(&p, torque, dist, acc);
    ASSERT_CLOSE(1e-12, -12.0 + (0.05 - 0.1) / 0.01 + 7.0, acc[0]); /* -10 */
    ASSERT_CLOSE(1e-12, 4.5 + (-0.04 - 0.2) / 0.02 - 8.0, acc[1]);  /* -15.5 */
    ASSERT_CLOSE(1e-12, -0.5 + (0.2 - 0.3) / 0.04 + 9.0, acc[2]);   /* 6 */
    /* a NULL disturbance is zero */
    double acc_nodist[3];
    sim_plant_accel(&p, torque, NULL, acc_nodist);
    for (int i = 0; i < 3; ++i) {
        ASSERT_CLOSE(1e-12, acc[i] - dist[i], acc_nodist[i]);
    }

    /* the paper's vehicle: Jx = Jy, Jz = 2 Jx, so phi'' = -theta' psi',
     * theta'' = +phi' psi', psi'' = 0 */
    sim_vehicle_t pv = vehicle_no_drag();
    sim_plant_init(&p, &pv);
    p.rate_rad_s[0] = 1.0;
    p.rate_rad_s[1] = 2.0;
    p.rate_rad_s[2] = 3.0;
    sim_plant_accel(&p, zero, NULL, acc);
    ASSERT_CLOSE(1e-12, -6.0, acc[0]);
    ASSERT_CLOSE(1e-12, 3.0, acc[1]);
    ASSERT_CLOSE(1e-12, 0.0, acc[2]);
}

static void test_step_integrates_the_same_accelerations(void)
{
    /* one tiny step: the rate change over h is the acceleration to O(h) */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.inertia_kg_m2[1] = 7e-3;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    p.rate_rad_s[0] = 3.0;
    p.rate_rad_s[1] = -2.0;
    p.rate_rad_s[2] = 1.0;
    double cmd[4];
    const double torque[3] = {0.01, -0.02, 0.005};
    inverse_allocation(&v, 4.0 * v.thrust_coeff_N_s2 * hover_w2(&v), torque, cmd);
    double acc[3], rate0[3];
    sim_plant_accel(&p, torque, NULL, acc);
    for (int i = 0; i < 3; ++i) {
        rate0[i] = p.rate_rad_s[i];
    }
    const double h = 1e-7;
    sim_plant_step(&p, cmd, h, 1, NULL, NULL);
    for (int i = 0; i < 3; ++i) {
        /* jerk ~ 1e3 rad/s^3 here: h * jerk / 2 = 5e-5, plus rounding 1e-16 / h = 1e-9 */
        ASSERT_CLOSE(1e-4, acc[i], (p.rate_rad_s[i] - rate0[i]) / h);
    }
}

static double kinetic_energy(const sim_plant_t *p)
{
    double e = 0.0;
    for (int i = 0; i < 3; ++i) {
        e += 0.5 * p->v.inertia_kg_m2[i] * p->rate_rad_s[i] * p->rate_rad_s[i];
    }
    return e;
}

static double momentum_squared(const sim_plant_t *p)
{
    double m = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double l = p->v.inertia_kg_m2[i] * p->rate_rad_s[i];
        m += l * l;
    }
    return m;
}

/* Largest relative energy deviation over 10 s of torque-free motion at
 * step h, and the relative change of |J w|^2 at the end. */
static double free_motion_energy_error(double h, double *momentum_error, double *max_rate_change)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.inertia_kg_m2[1] = 7e-3; /* Jx < Jy < Jz: all three couplings act */
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double w0[3] = {3.0, -2.0, 1.0};
    for (int i = 0; i < 3; ++i) {
        p.rate_rad_s[i] = w0[i];
    }
    const double cmd[4] = {p.w2_rad2_s2[0], p.w2_rad2_s2[1], p.w2_rad2_s2[2], p.w2_rad2_s2[3]};
    const double e0 = kinetic_energy(&p), m0 = momentum_squared(&p);
    const int n = (int)(10.0 / h + 0.5);
    double de = 0.0;
    *max_rate_change = 0.0;
    for (int k = 0; k < n; ++k) {
        sim_plant_step(&p, cmd, h, 1, NULL, NULL);
        de = fmax(de, fabs(kinetic_energy(&p) / e0 - 1.0));
        for (int i = 0; i < 3; ++i) {
            *max_rate_change = fmax(*max_rate_change, fabs(p.rate_rad_s[i] - w0[i]));
        }
    }
    *momentum_error = fabs(momentum_squared(&p) / m0 - 1.0);
    return de;
}

static void test_torque_free_motion_conserves_kinetic_energy_and_momentum(void)
{
    /* With kt = 0 and no torque, d/dt 0.5 sum J w^2 = p q r ((Jy - Jz) +
     * (Jz - Jx) + (Jx - Jy)) = 0, and |J w|^2 is conserved the same way: both
     * are exact invariants of eq. 2. RK4 keeps them only to its truncation
     * error, fourth order in h. Measured largest energy deviation over 10 s
     * from w = (3, -2, 1) rad/s: 8.9e-15 (h = 1 ms, at rounding level),
     * 1.2e-13 (2 ms), 2.0e-12 (4 ms). The bound at 1 ms, 1e-12, is the 4 ms
     * figure over 4^4 = 256 with a 100x margin for rounding; a sign error in
     * any one coupling term makes dE/dt = 2 c p q r != 0, about 20% of E per
     * second here. */
    double dm, change;
    const double de = free_motion_energy_error(1e-3, &dm, &change);
    TEST_ASSERT_TRUE_MESSAGE(change > 1.0, "the rates must really change (coupling active)");
    ASSERT_CLOSE(1e-12, 0.0, de);
    ASSERT_CLOSE(1e-12, 0.0, dm);
    /* the drift is truncation: doubling h multiplies it by ~2^4 (measured
     * 15.9 from 2 ms to 4 ms, where rounding no longer matters) */
    double dm2, dm4, change2, change4;
    const double de2 = free_motion_energy_error(2e-3, &dm2, &change2);
    const double de4 = free_motion_energy_error(4e-3, &dm4, &change4);
    TEST_ASSERT_TRUE(de4 > 10.0 * de2 && de4 < 24.0 * de2);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_forces_match_a_hand_computation);
    RUN_TEST(test_forces_and_the_inverse_allocation_of_eq_33_round_trip);
    RUN_TEST(test_hover_rotors_give_weight_and_no_torque_and_keep_the_vehicle_at_rest);
    RUN_TEST(test_constant_torque_from_rest_gives_a_parabola_on_that_axis_only);
    RUN_TEST(test_drag_decays_each_rate_as_exp_minus_kt_over_j_t);
    RUN_TEST(test_coupling_terms_have_the_signs_of_eq_2);
    RUN_TEST(test_step_integrates_the_same_accelerations);
    RUN_TEST(test_torque_free_motion_conserves_kinetic_energy_and_momentum);
    return UNITY_END();
}
