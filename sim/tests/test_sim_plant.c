/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator plant: forces and their inverse, hover, the attitude dynamics
 * term by term against closed-form solutions, RK4 accuracy, disturbance
 * timing, the motor lag and the rotor limits. */
#include "unity.h"
#include "plant.h"
#include "rng.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

/* |actual - expected| <= tol, compared in double (Unity's float asserts
 * would round both to float). */
#define ASSERT_CLOSE(tol, expected, actual) assert_close((tol), (expected), (actual), __LINE__)
static void assert_close(double tol, double expected, double actual, int line)
{
    char msg[160];
    const double diff = fabs(actual - expected);
    snprintf(msg, sizeof msg, "expected %.17g, was %.17g (|diff| %.3g > %.3g)", expected, actual, diff, tol);
    UNITY_TEST_ASSERT(diff <= tol, line, msg);
}

/* The paper's vehicle without drag: closed forms need kt = 0. */
static sim_vehicle_t vehicle_no_drag(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.rot_drag_Nm_s = 0.0;
    return v;
}

static double hover_w2(const sim_vehicle_t *v)
{
    return v->mass_kg * v->g_m_s2 / (4.0 * v->thrust_coeff_N_s2);
}

/* docs/method.md eq. 33, with a = U_L/kL, p = tau_x/(l kL), q = tau_y/(l kL),
 * r = tau_z/b. */
static void inverse_allocation(const sim_vehicle_t *v, double thrust_N, const double torque_Nm[3], double w2[4])
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

/* w^2 commands that give torque tau on `axis` alone, around hover. */
static void torque_command(const sim_vehicle_t *v, int axis, double tau, double cmd[4])
{
    double torque[3] = {0.0, 0.0, 0.0};
    torque[axis] = tau;
    inverse_allocation(v, 4.0 * v->thrust_coeff_N_s2 * hover_w2(v), torque, cmd);
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

/* n steps of RK4 on x' = -lambda x multiply x by R(z)^n, z = -lambda h,
 * R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24. Relative to exp(z n): per step
 * exp(z) - R(z) = z^5/120 + ..., so after n steps |R^n / exp(zn) - 1| ~
 * n |z|^5/120. */
static double rk4_decay(double z, int n)
{
    return pow(1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0, n);
}

static double rk4_decay_bound(double z, int n)
{
    return 1.2 * n * pow(fabs(z), 5) / 120.0; /* 20% for the z^6 terms */
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

typedef struct {
    int n_calls;
    double t[64];
} call_log_t;

static void logging_ramp(double t_s, void *ctx, double d_out[3])
{
    call_log_t *log = ctx;
    if (log->n_calls < 64) {
        log->t[log->n_calls] = t_s;
    }
    ++log->n_calls;
    d_out[0] = t_s; /* d_phi(t) = t rad/s^2 */
    d_out[1] = 0.0;
    d_out[2] = 0.0;
}

static void test_disturbance_is_evaluated_at_the_rk4_stage_times(void)
{
    const sim_vehicle_t v = vehicle_no_drag();
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double cmd[4] = {p.w2_rad2_s2[0], p.w2_rad2_s2[1], p.w2_rad2_s2[2], p.w2_rad2_s2[3]};
    call_log_t log = {0};
    sim_plant_step(&p, cmd, 0.01, 1, logging_ramp, &log);
    log.n_calls = 0;
    /* second step from t = 0.01, two substeps of 5 ms */
    sim_plant_step(&p, cmd, 0.01, 2, logging_ramp, &log);
    /* one call per distinct stage time: k2 and k3 share t + h/2 */
    TEST_ASSERT_EQUAL_INT(2 * 3, log.n_calls);
    static const double stage[3] = {0.0, 0.5, 1.0};
    for (int s = 0; s < 2; ++s) {
        for (int k = 0; k < 3; ++k) {
            ASSERT_CLOSE(1e-15, 0.01 + 0.005 * (s + stage[k]), log.t[s * 3 + k]);
        }
    }
    ASSERT_CLOSE(1e-15, 0.02, p.t_s);
}

static void test_the_listed_stage_times_are_those_asked_bit_for_bit(void)
{
    const sim_vehicle_t v = vehicle_no_drag();
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double cmd[4] = {p.w2_rad2_s2[0], p.w2_rad2_s2[1], p.w2_rad2_s2[2], p.w2_rad2_s2[3]};
    call_log_t log = {0};
    double listed[64];
    for (int k = 0; k < 7; ++k) { /* from times that are not round: 0.0013 s steps */
        log.n_calls = 0;
        const int n = sim_plant_stage_times(&p, 1.3e-3, 7, listed);
        sim_plant_step(&p, cmd, 1.3e-3, 7, logging_ramp, &log);
        TEST_ASSERT_EQUAL_INT(3 * 7, n);
        TEST_ASSERT_EQUAL_INT(n, log.n_calls);
        for (int i = 0; i < n; ++i) {
            TEST_ASSERT_TRUE(listed[i] == log.t[i]);
        }
    }
    TEST_ASSERT_EQUAL_INT(0, sim_plant_stage_times(&p, 0.0, 7, listed));
    TEST_ASSERT_EQUAL_INT(3, sim_plant_stage_times(&p, 1e-3, 0, listed)); /* substeps below 1 count as 1 */
}

static void test_a_ramp_disturbance_gives_the_exact_cubic(void)
{
    /* phi'' = t from rest: phi = t^3 / 6, phi' = t^2 / 2. RK4 with d at the
     * stage times is Simpson's rule on each step, exact for this cubic; with
     * d held at the step start the rate would lag by t h / 2. */
    const sim_vehicle_t v = vehicle_no_drag();
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double cmd[4] = {p.w2_rad2_s2[0], p.w2_rad2_s2[1], p.w2_rad2_s2[2], p.w2_rad2_s2[3]};
    call_log_t log = {0};
    for (int k = 1; k <= 1000; ++k) {
        sim_plant_step(&p, cmd, 1e-3, 1, logging_ramp, &log);
        const double t = k * 1e-3;
        /* rounding only: measured below 1e-16 rad */
        ASSERT_CLOSE(1e-13, t * t * t / 6.0, p.angle_rad[0]);
        ASSERT_CLOSE(1e-13, t * t / 2.0, p.rate_rad_s[0]);
    }
    TEST_ASSERT_TRUE(p.angle_rad[1] == 0.0 && p.angle_rad[2] == 0.0);
}

static void test_motor_lag_follows_exp_minus_t_over_tau_and_drives_the_attitude(void)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.motor_tau_s = 0.02;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double w0 = hover_w2(&v);
    const double dw = 2e4; /* roll: rotor 2 up, rotor 4 down */
    const double cmd[4] = {w0, w0 + dw, w0, w0 - dw};
    const double h = 1e-3, tau = v.motor_tau_s;
    const double z = -h / tau; /* -0.05 */
    /* roll acceleration once the rotors have settled */
    const double alpha = v.arm_m * v.thrust_coeff_N_s2 * 2.0 * dw / v.inertia_kg_m2[0];
    for (int k = 1; k <= 200; ++k) {
        sim_plant_step(&p, cmd, h, 1, NULL, NULL);
        const double t = k * h;
        /* the lag state: RK4 amplification to rounding (measured 3e-11 on
         * 8.6e4), and the exact exponential within the truncation bound
         * (k 0.05^5 / 120 relative to the remaining step) */
        const double rk4 = dw * (1.0 - rk4_decay(z, k));
        ASSERT_CLOSE(1e-9, w0 + rk4, p.w2_rad2_s2[1]);
        ASSERT_CLOSE(1e-9, w0 - rk4, p.w2_rad2_s2[3]);
        const double settle = exp(-t / tau);
        ASSERT_CLOSE(rk4_decay_bound(z, k) * dw * settle + 1e-9, w0 + dw * (1.0 - settle), p.w2_rad2_s2[1]);
        TEST_ASSERT_TRUE(p.w2_rad2_s2[0] == w0 && p.w2_rad2_s2[2] == w0);
        /* the torque follows the lag inside the RK4 stages:
         * phi = alpha (t^2/2 - tau t + tau^2 (1 - exp(-t/tau))). RK4 leaves
         * the rate off by at most ~alpha tau (h/tau)^4 / 120 in all (the
         * lag's local errors, summed over its decay), so the angle by that
         * times t; twice that is the bound (measured 0.34 of it). A lag
         * updated once per step would be off by O(h), ~alpha h t. */
        const double phi = alpha * (t * t / 2.0 - tau * t + tau * tau * (1.0 - settle));
        ASSERT_CLOSE(alpha * tau * pow(h / tau, 4) / 60.0 * (t + h), phi, p.angle_rad[0]);
    }
    /* after 10 tau the rotors are at the command to 5e-5 of the step */
    ASSERT_CLOSE(1e-4 * dw, w0 + dw, p.w2_rad2_s2[1]);
}

static void test_limits_clamp_the_command_when_not_ideal(void)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.rotors_ideal = 0;
    v.w2_min_rad2_s2 = 1e4;
    v.w2_max_rad2_s2 = 2e5;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    /* below, inside, above the limits; once clamped only pitch has torque:
     * yaw -1e4 + 1.05e5 - 2e5 + 1.05e5 = 0, roll 1.05e5 - 1.05e5 = 0 */
    const double cmd[4] = {-5e4, 1.05e5, 3e5, 1.05e5};
    sim_plant_step(&p, cmd, 1e-3, 1, NULL, NULL);
    TEST_ASSERT_TRUE(p.w2_rad2_s2[0] == 1e4);
    TEST_ASSERT_TRUE(p.w2_rad2_s2[1] == 1.05e5);
    TEST_ASSERT_TRUE(p.w2_rad2_s2[2] == 2e5);
    TEST_ASSERT_TRUE(p.w2_rad2_s2[3] == 1.05e5);
    /* the attitude saw the clamped rotors: pitch torque l kL (2e5 - 1e4) */
    const double alpha = v.arm_m * v.thrust_coeff_N_s2 * (2e5 - 1e4) / v.inertia_kg_m2[1];
    ASSERT_CLOSE(1e-13 * alpha, alpha * 1e-3, p.rate_rad_s[1]);
    TEST_ASSERT_TRUE(p.rate_rad_s[0] == 0.0 && p.rate_rad_s[2] == 0.0);

    /* ideal rotors take the same command as it is, negative included */
    v.rotors_ideal = 1;
    sim_plant_init(&p, &v);
    sim_plant_step(&p, cmd, 1e-3, 1, NULL, NULL);
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(p.w2_rad2_s2[i] == cmd[i]);
    }

    /* with a lag the rotors approach the clamped value, never the command */
    v.rotors_ideal = 0;
    v.motor_tau_s = 0.01;
    sim_plant_init(&p, &v);
    for (int k = 0; k < 300; ++k) {
        sim_plant_step(&p, cmd, 1e-3, 1, NULL, NULL);
        TEST_ASSERT_TRUE(p.w2_rad2_s2[0] >= 1e4 && p.w2_rad2_s2[2] <= 2e5);
    }
    ASSERT_CLOSE(1e-6, 1e4, p.w2_rad2_s2[0]);
    ASSERT_CLOSE(1e-6, 2e5, p.w2_rad2_s2[2]);

    /* the initial hover is clamped too: m g / (4 kL) = 65839 > 5e4 */
    v.w2_max_rad2_s2 = 5e4;
    sim_plant_init(&p, &v);
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(p.w2_rad2_s2[i] == 5e4);
    }
}

static void sine_disturbance(double t_s, void *ctx, double d_out[3])
{
    (void)ctx;
    for (int axis = 0; axis < 3; ++axis) {
        d_out[axis] = 5.0 * sin(7.0 * t_s + axis);
    }
}

static void test_rk4_substeps_converge_at_fourth_order(void)
{
    /* everything on at once: drag, coupling, lag, a sinusoidal disturbance;
     * the error against 1/64-step runs falls ~16x per halving of h */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.inertia_kg_m2[1] = 7e-3;
    v.motor_tau_s = 0.015;
    double cmd[4];
    const double torque[3] = {0.02, -0.015, 0.004};
    inverse_allocation(&v, 4.0 * v.thrust_coeff_N_s2 * hover_w2(&v), torque, cmd);
    double final[4][3];
    static const int substeps[4] = {1, 2, 4, 64};
    for (int r = 0; r < 4; ++r) {
        sim_plant_t p;
        sim_plant_init(&p, &v);
        p.rate_rad_s[0] = 5.0;
        p.rate_rad_s[1] = -4.0;
        p.rate_rad_s[2] = 3.0;
        for (int k = 0; k < 100; ++k) {
            sim_plant_step(&p, cmd, 1e-2, substeps[r], sine_disturbance, NULL);
        }
        for (int i = 0; i < 3; ++i) {
            final[r][i] = p.rate_rad_s[i];
        }
    }
    for (int i = 0; i < 3; ++i) {
        const double e1 = fabs(final[0][i] - final[3][i]);
        const double e2 = fabs(final[1][i] - final[3][i]);
        const double e4 = fabs(final[2][i] - final[3][i]);
        /* measured 14.7 .. 16.3 */
        TEST_ASSERT_TRUE(e1 / e2 > 12.0 && e1 / e2 < 20.0);
        TEST_ASSERT_TRUE(e2 / e4 > 12.0 && e2 / e4 < 20.0);
    }
}

static void test_no_time_step_does_nothing_and_substeps_below_one_count_as_one(void)
{
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sim_plant_t a, b;
    sim_plant_init(&a, &v);
    sim_plant_init(&b, &v);
    double cmd[4];
    const double torque[3] = {0.01, 0.02, 0.003};
    inverse_allocation(&v, 4.0 * v.thrust_coeff_N_s2 * hover_w2(&v), torque, cmd);
    sim_plant_step(&a, cmd, 0.0, 1, NULL, NULL);
    sim_plant_step(&a, cmd, -1e-3, 1, NULL, NULL);
    sim_plant_step(&a, cmd, NAN, 1, NULL, NULL);
    TEST_ASSERT_TRUE(a.t_s == 0.0 && a.rate_rad_s[0] == 0.0);
    sim_plant_step(&a, cmd, 1e-3, 0, NULL, NULL);
    sim_plant_step(&b, cmd, 1e-3, 1, NULL, NULL);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(a.angle_rad[i] == b.angle_rad[i] && a.rate_rad_s[i] == b.rate_rad_s[i]);
    }
}

/* ---- plants stepped side by side -------------------------------------------- */

/* The plant's step written out plainly, one plant, one operation at a time
 * in the order of plant.h's equations: the reference the interleaved lanes
 * (SSE2 or AVX) must give bit for bit. */
static void reference_accel(const sim_vehicle_t *v, const double rate[3], const double torque[3], const double d[3],
                            double accel[3])
{
    const double *j = v->inertia_kg_m2;
    const double kt = v->rot_drag_Nm_s;
    accel[0] = (torque[0] + (j[1] - j[2]) * rate[1] * rate[2] - kt * rate[0]) / j[0] + d[0];
    accel[1] = (torque[1] + (j[2] - j[0]) * rate[0] * rate[2] - kt * rate[1]) / j[1] + d[1];
    accel[2] = (torque[2] + (j[0] - j[1]) * rate[1] * rate[0] - kt * rate[2]) / j[2] + d[2];
}

static void reference_derivative(const sim_vehicle_t *v, int lag, const double cmd[4], const double cmd_torque[3],
                                 const double x[10], const double d[3], double dx[10])
{
    double torque[3];
    if (lag) {
        const double kl = v->thrust_coeff_N_s2;
        torque[0] = v->arm_m * kl * (x[7] - x[9]);
        torque[1] = v->arm_m * kl * (x[8] - x[6]);
        torque[2] = v->yaw_coeff_Nm_s2 * (-x[6] + x[7] - x[8] + x[9]);
        for (int i = 0; i < 4; ++i) {
            dx[6 + i] = (cmd[i] - x[6 + i]) / v->motor_tau_s;
        }
    } else {
        for (int i = 0; i < 3; ++i) {
            torque[i] = cmd_torque[i];
        }
    }
    for (int i = 0; i < 3; ++i) {
        dx[i] = x[3 + i];
    }
    reference_accel(v, &x[3], torque, d, &dx[3]);
}

static double reference_clamp(const sim_vehicle_t *v, double w2)
{
    if (v->rotors_ideal) {
        return w2;
    }
    return w2 < v->w2_min_rad2_s2 ? v->w2_min_rad2_s2 : (w2 > v->w2_max_rad2_s2 ? v->w2_max_rad2_s2 : w2);
}

static void reference_step(sim_plant_t *p, const double w2_cmd[4], double dt, int substeps, sim_disturbance_fn dist)
{
    const sim_vehicle_t *v = &p->v;
    const int lag = v->motor_tau_s > 0.0;
    const int n = lag ? 10 : 6;
    const double h = dt / substeps;
    double cmd[4], cmd_torque[3], x[10];
    for (int i = 0; i < 4; ++i) {
        cmd[i] = reference_clamp(v, w2_cmd[i]);
        x[6 + i] = p->w2_rad2_s2[i];
    }
    const double kl = v->thrust_coeff_N_s2;
    cmd_torque[0] = v->arm_m * kl * (cmd[1] - cmd[3]);
    cmd_torque[1] = v->arm_m * kl * (cmd[2] - cmd[0]);
    cmd_torque[2] = v->yaw_coeff_Nm_s2 * (-cmd[0] + cmd[1] - cmd[2] + cmd[3]);
    for (int i = 0; i < 3; ++i) {
        x[i] = p->angle_rad[i];
        x[3 + i] = p->rate_rad_s[i];
    }
    for (int s = 0; s < substeps; ++s) {
        const double t = p->t_s + s * h;
        double k1[10], k2[10], k3[10], k4[10], y[10], d[3];
        dist(t, NULL, d);
        reference_derivative(v, lag, cmd, cmd_torque, x, d, k1);
        for (int i = 0; i < n; ++i)
            y[i] = x[i] + 0.5 * h * k1[i];
        dist(t + 0.5 * h, NULL, d);
        reference_derivative(v, lag, cmd, cmd_torque, y, d, k2);
        for (int i = 0; i < n; ++i)
            y[i] = x[i] + 0.5 * h * k2[i];
        reference_derivative(v, lag, cmd, cmd_torque, y, d, k3);
        for (int i = 0; i < n; ++i)
            y[i] = x[i] + h * k3[i];
        dist(t + h, NULL, d);
        reference_derivative(v, lag, cmd, cmd_torque, y, d, k4);
        for (int i = 0; i < n; ++i)
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
    for (int i = 0; i < 3; ++i) {
        p->angle_rad[i] = x[i];
        p->rate_rad_s[i] = x[3 + i];
    }
    for (int i = 0; i < 4; ++i) {
        p->w2_rad2_s2[i] = lag ? x[6 + i] : cmd[i];
    }
    p->t_s += dt;
}

static int same_plant(const sim_plant_t *a, const sim_plant_t *b)
{
    return memcmp(a->angle_rad, b->angle_rad, sizeof a->angle_rad) == 0 &&
           memcmp(a->rate_rad_s, b->rate_rad_s, sizeof a->rate_rad_s) == 0 &&
           memcmp(a->w2_rad2_s2, b->w2_rad2_s2, sizeof a->w2_rad2_s2) == 0 &&
           memcmp(&a->t_s, &b->t_s, sizeof a->t_s) == 0;
}

/* Plant g's command at step k: different for every plant and step. */
static void varied_command(const sim_vehicle_t *v, int g, int k, double cmd[4])
{
    const double torque[3] = {0.03 * sin(0.1 * k + g), -0.02 * cos(0.07 * k + 2.0 * g), 0.004 * sin(0.05 * k - g)};
    inverse_allocation(v, 4.0 * v->thrust_coeff_N_s2 * hover_w2(v) * (1.0 + 0.05 * g), torque, cmd);
}

static void test_plants_stepped_side_by_side_are_each_the_plant_alone_bit_for_bit(void)
{
    /* 1 to 8 plants (every width of the lanes, and the padding of 3, 5 and
     * 7), ideal rotors and lagged, clamped ones, a disturbance at every
     * stage: the group, each plant stepped alone and the plain reference
     * agree bit for bit at every step */
    for (int lag = 0; lag <= 1; ++lag) {
        sim_vehicle_t v;
        sim_vehicle_paper(&v);
        v.inertia_kg_m2[1] = 6.1e-3; /* coupling on every axis */
        if (lag) {
            v.rotors_ideal = 0;
            v.w2_min_rad2_s2 = 3e4;
            v.w2_max_rad2_s2 = 1.2e5;
            v.motor_tau_s = 0.02;
        }
        for (int n = 1; n <= SIM_PLANT_GROUP_MAX; ++n) {
            sim_plant_t grouped[SIM_PLANT_GROUP_MAX], alone[SIM_PLANT_GROUP_MAX], reference[SIM_PLANT_GROUP_MAX];
            sim_plant_t *lanes[SIM_PLANT_GROUP_MAX];
            for (int g = 0; g < n; ++g) {
                sim_plant_init(&grouped[g], &v);
                grouped[g].rate_rad_s[g % 3] = 0.5 * (g + 1); /* each its own state */
                alone[g] = reference[g] = grouped[g];
                lanes[g] = &grouped[g];
            }
            int mismatches = 0;
            for (int k = 0; k < 200; ++k) {
                double cmd[SIM_PLANT_GROUP_MAX][4];
                for (int g = 0; g < n; ++g) {
                    varied_command(&v, g, k, cmd[g]);
                    sim_plant_step(&alone[g], cmd[g], 1e-3, 3, sine_disturbance, NULL);
                    reference_step(&reference[g], cmd[g], 1e-3, 3, sine_disturbance);
                }
                sim_plant_step_group(lanes, (const double(*)[4])cmd, n, 1e-3, 3, sine_disturbance, NULL);
                for (int g = 0; g < n; ++g) {
                    mismatches += !same_plant(&grouped[g], &alone[g]) || !same_plant(&grouped[g], &reference[g]);
                }
            }
            char message[80];
            snprintf(message, sizeof message, "lag %d, %d plants", lag, n);
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, mismatches, message);
            TEST_ASSERT_TRUE_MESSAGE(fabs(grouped[n - 1].angle_rad[0]) > 1e-3, message); /* they did move */
        }
    }
}

/* Counts its calls (ctx: an int). */
static void counting_disturbance(double t_s, void *ctx, double d_out[3])
{
    ++*(int *)ctx;
    sine_disturbance(t_s, NULL, d_out);
}

static void test_a_group_asks_the_disturbance_once_per_stage_and_steps_misfits_alone(void)
{
    /* plants at another time, or of another vehicle (-0 and 0 as a limit
     * are another: the clamp returns the limit itself) cannot share the
     * lanes: they are stepped alone, after the group, to their own bits */
    sim_vehicle_t v, other;
    sim_vehicle_paper(&v);
    v.rotors_ideal = 0;
    v.w2_min_rad2_s2 = 0.0;
    other = v;
    other.w2_min_rad2_s2 = -0.0;
    sim_plant_t p[5], q[5];
    sim_plant_t *lanes[5];
    for (int g = 0; g < 5; ++g) {
        sim_plant_init(&p[g], g == 3 ? &other : &v);
        lanes[g] = &p[g];
    }
    double cmd[5][4];
    for (int g = 0; g < 5; ++g) {
        varied_command(&v, g, 0, cmd[g]);
        cmd[g][0] = -1e3; /* clamped to the limit */
    }
    sim_plant_step(&p[1], cmd[1], 1e-3, 1, NULL, NULL); /* p[1] a step ahead */
    for (int g = 0; g < 5; ++g) {
        q[g] = p[g];
    }
    int calls = 0;
    sim_plant_step_group(lanes, (const double(*)[4])cmd, 5, 1e-3, 2, counting_disturbance, &calls);
    /* 3 calls per substep: the group of three (0, 2, 4), then 1 and 3 alone */
    TEST_ASSERT_EQUAL_INT(3 * 2 * 3, calls);
    for (int g = 0; g < 5; ++g) {
        sim_plant_step(&q[g], cmd[g], 1e-3, 2, sine_disturbance, NULL);
        TEST_ASSERT_TRUE(same_plant(&p[g], &q[g]));
    }
    TEST_ASSERT_TRUE(signbit(p[3].w2_rad2_s2[0]) && !signbit(p[0].w2_rad2_s2[0]));
}

static void test_a_table_of_stage_disturbances_steps_as_the_calls_do(void)
{
    /* the disturbances of a step given by stage (sim_plant_stage_times'
     * order) against the same values asked for by call; a plant at another
     * time is left alone and not counted */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.motor_tau_s = 0.015;
    sim_plant_t a[4], b[4];
    sim_plant_t *lanes_a[4], *lanes_b[4];
    for (int g = 0; g < 4; ++g) {
        sim_plant_init(&a[g], &v);
        a[g].rate_rad_s[g % 3] = 0.3 * (g + 1);
        b[g] = a[g];
        lanes_a[g] = &a[g];
        lanes_b[g] = &b[g];
    }
    for (int k = 0; k < 50; ++k) {
        double cmd[4][4], times[3 * 7], table[3 * 7][3];
        for (int g = 0; g < 4; ++g) {
            varied_command(&v, g, k, cmd[g]);
        }
        const int n = sim_plant_stage_times(&a[0], 1e-3, 7, times);
        TEST_ASSERT_EQUAL_INT(21, n);
        for (int j = 0; j < n; ++j) {
            sine_disturbance(times[j], NULL, table[j]);
        }
        sim_plant_step_group(lanes_a, (const double(*)[4])cmd, 4, 1e-3, 7, sine_disturbance, NULL);
        TEST_ASSERT_EQUAL_INT(
            4, sim_plant_step_group_table(lanes_b, (const double(*)[4])cmd, 4, 1e-3, 7, (const double(*)[3])table));
        for (int g = 0; g < 4; ++g) {
            TEST_ASSERT_TRUE(same_plant(&a[g], &b[g]));
        }
    }
    b[2].t_s += 1e-3; /* another time: not stepped */
    const sim_plant_t before = b[2];
    double cmd[4][4], table[3][3] = {{0.0}};
    for (int g = 0; g < 4; ++g) {
        varied_command(&v, g, 0, cmd[g]);
    }
    TEST_ASSERT_EQUAL_INT(
        3, sim_plant_step_group_table(lanes_b, (const double(*)[4])cmd, 4, 1e-3, 1, (const double(*)[3])table));
    TEST_ASSERT_TRUE(same_plant(&before, &b[2]));
    TEST_ASSERT_FALSE(same_plant(&a[0], &b[0]));
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
    RUN_TEST(test_disturbance_is_evaluated_at_the_rk4_stage_times);
    RUN_TEST(test_a_ramp_disturbance_gives_the_exact_cubic);
    RUN_TEST(test_motor_lag_follows_exp_minus_t_over_tau_and_drives_the_attitude);
    RUN_TEST(test_limits_clamp_the_command_when_not_ideal);
    RUN_TEST(test_rk4_substeps_converge_at_fourth_order);
    RUN_TEST(test_no_time_step_does_nothing_and_substeps_below_one_count_as_one);
    RUN_TEST(test_the_listed_stage_times_are_those_asked_bit_for_bit);
    RUN_TEST(test_plants_stepped_side_by_side_are_each_the_plant_alone_bit_for_bit);
    RUN_TEST(test_a_group_asks_the_disturbance_once_per_stage_and_steps_misfits_alone);
    RUN_TEST(test_a_table_of_stage_disturbances_steps_as_the_calls_do);
    return UNITY_END();
}
