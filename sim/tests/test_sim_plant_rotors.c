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

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_motor_lag_follows_exp_minus_t_over_tau_and_drives_the_attitude);
    RUN_TEST(test_limits_clamp_the_command_when_not_ideal);
    return UNITY_END();
}
