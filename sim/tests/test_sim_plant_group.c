/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator plant, plants stepped side by side (sim_plant_step_group and
 * its table form) against a plain one-plant reference, bit for bit. */
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
    RUN_TEST(test_plants_stepped_side_by_side_are_each_the_plant_alone_bit_for_bit);
    RUN_TEST(test_a_group_asks_the_disturbance_once_per_stage_and_steps_misfits_alone);
    RUN_TEST(test_a_table_of_stage_disturbances_steps_as_the_calls_do);
    return UNITY_END();
}
