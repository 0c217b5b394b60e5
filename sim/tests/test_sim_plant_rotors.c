/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator plant, its rotors: the motor lag and the rotor limits. */
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

static void test_spin_down_follows_its_own_time_constant(void)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.motor_tau_s = 0.01;
    v.motor_tau_down_s = 0.04;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double w0 = hover_w2(&v), dw = 2e4;
    const double cmd[4] = {w0, w0 + dw, w0, w0 - dw}; /* rotor 2 speeds up, rotor 4 slows down */
    const double h = 1e-3;
    for (int k = 1; k <= 100; ++k) {
        sim_plant_step(&p, cmd, h, 1, NULL, NULL);
    }
    /* after 0.1 s: up 1 - exp(-10), down 1 - exp(-2.5), each within the
     * RK4 truncation of a decay at 0.1 and 0.025 of its time constant per
     * step (relative 1e-6 covers both, measured 2e-8) */
    ASSERT_CLOSE(1e-6 * dw, w0 + dw * (1.0 - exp(-0.1 / 0.01)), p.w2_rad2_s2[1]);
    ASSERT_CLOSE(1e-6 * dw, w0 - dw * (1.0 - exp(-0.1 / 0.04)), p.w2_rad2_s2[3]);
    /* 0 takes motor_tau_s both ways: the rotors move symmetrically */
    v.motor_tau_down_s = 0.0;
    sim_plant_init(&p, &v);
    for (int k = 1; k <= 50; ++k) {
        sim_plant_step(&p, cmd, h, 1, NULL, NULL);
    }
    ASSERT_CLOSE(1e-9, w0 - p.w2_rad2_s2[3], p.w2_rad2_s2[1] - w0);
}

static void test_battery_sag_scales_the_rotors_as_the_voltage_squared(void)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.rotors_ideal = 0;
    v.w2_max_rad2_s2 = 2e5;
    v.battery_life_s = 100.0;
    v.battery_drop = 0.2;
    /* s(t) = (1 - 0.2 min(t / 100, 1))^2: 1 at 0, 0.81 at 50 s, 0.64 from 100 s on */
    ASSERT_CLOSE(1e-15, 1.0, sim_plant_battery_factor(&v, 0.0));
    ASSERT_CLOSE(1e-15, 0.81, sim_plant_battery_factor(&v, 50.0));
    ASSERT_CLOSE(1e-15, 0.64, sim_plant_battery_factor(&v, 100.0));
    ASSERT_CLOSE(1e-15, 0.64, sim_plant_battery_factor(&v, 1e4));
    v.battery_life_s = 0.0;
    TEST_ASSERT_TRUE(sim_plant_battery_factor(&v, 50.0) == 1.0);
    /* the factor applies after the limits (a lower voltage caps the speed too) */
    v.battery_life_s = 100.0;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    p.t_s = 50.0;
    const double cmd[4] = {1e5, 1e5, 3e5, 1e5};
    sim_plant_step(&p, cmd, 1e-3, 1, NULL, NULL);
    ASSERT_CLOSE(1e-9, 0.81e5, p.w2_rad2_s2[0]);
    ASSERT_CLOSE(1e-9, 0.81 * 2e5, p.w2_rad2_s2[2]);
}

static void test_wind_acts_through_the_rotor_drag_at_the_hubs(void)
{
    sim_vehicle_t v = vehicle_no_drag();
    v.rotor_drag_N_s_m = 1e-4;
    v.rotor_height_m = 0.04;
    const double w2[4] = {4e4, 9e4, 1.6e5, 2.5e5}; /* w = 200, 300, 400, 500 rad/s */
    const double vb[3] = {3.0, -2.0, 7.0};         /* in-plane only: z does nothing */
    double t[3];
    sim_plant_wind_torque(&v, w2, vb, t);
    /* sum w = 1400; tau_x = h kd vy 1400, tau_y = -h kd vx 1400,
     * tau_z = kd l ((w3 - w1) vy + (w2 - w4) vx) = kd l (200 (-2) - 200 (3)) */
    ASSERT_CLOSE(1e-15, 0.04 * 1e-4 * -2.0 * 1400.0, t[0]);
    ASSERT_CLOSE(1e-15, -0.04 * 1e-4 * 3.0 * 1400.0, t[1]);
    ASSERT_CLOSE(1e-15, 1e-4 * v.arm_m * (-400.0 - 600.0), t[2]);
    /* a north wind in body axes: level and heading north it blows along x;
     * yawed 90 deg right (east) it comes from the left, along -y */
    const double north[3] = {5.0, 0.0, 0.0}, level[3] = {0.0, 0.0, 0.0}, east[3] = {0.0, 0.0, 1.5707963267948966};
    double b[3];
    sim_plant_wind_to_body(level, north, b);
    ASSERT_CLOSE(1e-15, 5.0, b[0]);
    ASSERT_CLOSE(1e-15, 0.0, b[1]);
    sim_plant_wind_to_body(east, north, b);
    ASSERT_CLOSE(1e-15, 0.0, b[0]);
    ASSERT_CLOSE(1e-15, -5.0, b[1]);
    /* rolled 90 deg right, body y points down: the vertical wind is in y */
    const double rolled[3] = {1.5707963267948966, 0.0, 0.0}, up[3] = {0.0, 0.0, -2.0};
    sim_plant_wind_to_body(rolled, up, b);
    ASSERT_CLOSE(1e-15, -2.0, b[1]);

    /* stepped in a steady 5 m/s north wind at hover the plant pitches at
     * tau_y / Jy exactly from rest (rotors equal: no yaw) */
    sim_plant_t p;
    sim_plant_init(&p, &v);
    const double hw = hover_w2(&v), cmd[4] = {hw, hw, hw, hw};
    double d_stage[3][3] = {{0.0}}, wind[3][3];
    for (int k = 0; k < 3; ++k) {
        wind[k][0] = 5.0;
        wind[k][1] = wind[k][2] = 0.0;
    }
    sim_plant_t *const one[1] = {&p};
    TEST_ASSERT_EQUAL_INT(1, sim_plant_step_group_air(one, (const double(*)[4]) & cmd, 1, 1e-3, 1,
                                                      (const double(*)[3])d_stage, (const double(*)[3])wind));
    const double alpha = -v.rotor_height_m * v.rotor_drag_N_s_m * 5.0 * 4.0 * sqrt(hw) / v.inertia_kg_m2[1];
    /* constant acceleration over the step (the rotation matrix is the
     * step's start's): RK4 is exact to rounding */
    ASSERT_CLOSE(1e-12 * fabs(alpha), alpha * 1e-3, p.rate_rad_s[1]);
    TEST_ASSERT_TRUE(p.rate_rad_s[0] == 0.0 && p.rate_rad_s[2] == 0.0);
    /* without drag the wind does nothing */
    v.rotor_drag_N_s_m = 0.0;
    sim_plant_init(&p, &v);
    (void)sim_plant_step_group_air(one, (const double(*)[4]) & cmd, 1, 1e-3, 1, (const double(*)[3])d_stage,
                                   (const double(*)[3])wind);
    TEST_ASSERT_TRUE(p.rate_rad_s[1] == 0.0);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_motor_lag_follows_exp_minus_t_over_tau_and_drives_the_attitude);
    RUN_TEST(test_limits_clamp_the_command_when_not_ideal);
    RUN_TEST(test_spin_down_follows_its_own_time_constant);
    RUN_TEST(test_battery_sag_scales_the_rotors_as_the_voltage_squared);
    RUN_TEST(test_wind_acts_through_the_rotor_drag_at_the_hubs);
    return UNITY_END();
}
