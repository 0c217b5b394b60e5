/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator plant, its integration: the disturbance at the RK4 stage
 * times, the stage times listed, exact cubics, fourth-order convergence of
 * the substeps, and steps of no time. */
#include "unity.h"
#include "plant/plant.h"
#include "plant_cases.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
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

/* The paper's vehicle without drag at rest, hovering, and the command that
 * keeps its rotors where they are. */
static void plant_at_rest(sim_plant_t *p, double cmd[4])
{
    const sim_vehicle_t v = vehicle_no_drag();
    sim_plant_init(p, &v);
    for (int i = 0; i < 4; ++i) {
        cmd[i] = p->w2_rad2_s2[i];
    }
}

static void test_disturbance_is_evaluated_at_the_rk4_stage_times(void)
{
    sim_plant_t p;
    double cmd[4];
    plant_at_rest(&p, cmd);
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
    sim_plant_t p;
    double cmd[4];
    plant_at_rest(&p, cmd);
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
    sim_plant_t p;
    double cmd[4];
    plant_at_rest(&p, cmd);
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

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_disturbance_is_evaluated_at_the_rk4_stage_times);
    RUN_TEST(test_a_ramp_disturbance_gives_the_exact_cubic);
    RUN_TEST(test_rk4_substeps_converge_at_fourth_order);
    RUN_TEST(test_no_time_step_does_nothing_and_substeps_below_one_count_as_one);
    RUN_TEST(test_the_listed_stage_times_are_those_asked_bit_for_bit);
    return UNITY_END();
}
