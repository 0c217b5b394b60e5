/* SPDX-License-Identifier: BSD-3-Clause */
/* The simulator's attitudes as quaternions: the rigid body's kinematics
 * through any attitude, the paper's kinematics unchanged, and the sensor's
 * attitude noise as a rotation. */
#include "unity.h"
#include "plant/plant.h"
#include "plant/rotation.h"
#include "plant/sensor.h"

#include <math.h>

#define PI 3.14159265358979323846
/* RK4 at 1 ms on a rotation of 2 rad/s: local error (w h)^5 / 120 per step,
 * some 3e-16 over 2000 steps; 1e-10 leaves room for the renormalisation. */
#define KINEMATICS_TOL 1e-10
/* The sample std of 20000 normal deviates is within 2 % of the true one
 * (its own std is 0.5 %); the rotation's small-angle map adds nothing at
 * 1 deg of noise. */
#define NOISE_STD_REL_TOL 0.02

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_rigid_body_turns_through_any_attitude(void)
{
    /* a constant pitch rate of 2 rad/s from level, torque-free without drag:
     * the attitude is q_y(2 t) exactly, through 90 deg and upside down */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    v.rigid_body = 1;
    v.rot_drag_Nm_s = 0.0;
    v.inertia_kg_m2[0] = v.inertia_kg_m2[1] = v.inertia_kg_m2[2] = 5e-3;
    sim_plant_t p;
    sim_plant_init(&p, &v);
    p.rate_rad_s[1] = 2.0;
    const double none[4] = {0, 0, 0, 0}; /* ideal rotors at 0: no torque */
    for (int k = 1; k <= 2000; ++k) {
        sim_plant_step(&p, none, 1e-3, 1, NULL, NULL);
        const double t = 1e-3 * k;
        const double want[4] = {cos(t), 0.0, sin(t), 0.0};
        double q[4];
        sim_plant_attitude(&p, q);
        for (int i = 0; i < 4; ++i) {
            TEST_ASSERT_TRUE(fabs(q[i] - want[i]) <= KINEMATICS_TOL);
        }
    }
    /* 4 rad of pitch: upside down, turned back by 180 deg of roll and yaw in ZYX */
    TEST_ASSERT_TRUE(fabs(fabs(p.angle_rad[0]) - PI) <= 1e-6 && fabs(fabs(p.angle_rad[2]) - PI) <= 1e-6);
    TEST_ASSERT_TRUE(fabs(p.angle_rad[1] - (PI - 4.0)) <= 1e-6);
}

static void test_paper_kinematics_are_unchanged(void)
{
    /* the paper's plant integrates the angles as the rates: its attitude is their ZYX quaternion */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sim_plant_t p;
    sim_plant_init(&p, &v);
    p.rate_rad_s[0] = 0.3;
    p.rate_rad_s[2] = -0.2;
    const double none[4] = {0, 0, 0, 0};
    sim_plant_step(&p, none, 1e-3, 10, NULL, NULL);
    double q[4], want[4];
    sim_plant_attitude(&p, q);
    sim_quat_from_euler(p.angle_rad, want);
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(q[i] == want[i]);
    }
}

static void test_sensor_turns_the_attitude_by_its_noise(void)
{
    sim_sensor_t s;
    const double std_rad = PI / 180.0;
    TEST_ASSERT_EQUAL_INT(0, sim_sensor_init(&s, std_rad, 0.0, 0, 7u));
    const double angle[3] = {0.2, 1.4, -2.0}, rate[3] = {0, 0, 0};
    double q_true[4];
    sim_quat_from_euler(angle, q_true);
    double sum2[3] = {0, 0, 0};
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        double a[3], r[3], q[4], e[3];
        sim_sensor_measure_quat(&s, angle, q_true, rate, a, r, q);
        sim_quat_error(q_true, q, e); /* the noise as a body-axis rotation */
        for (int i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(fabs(e[i] - (a[i] - angle[i])) <= 1e-9); /* the Euler angles' own deviates */
            sum2[i] += e[i] * e[i];
        }
    }
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(fabs(sqrt(sum2[i] / n) / std_rad - 1.0) <= NOISE_STD_REL_TOL);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_rigid_body_turns_through_any_attitude);
    RUN_TEST(test_paper_kinematics_are_unchanged);
    RUN_TEST(test_sensor_turns_the_attitude_by_its_noise);
    return UNITY_END();
}
