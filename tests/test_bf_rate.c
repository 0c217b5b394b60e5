/* SPDX-License-Identifier: BSD-3-Clause */
/* The Betaflight rate-loop adapter (integrations/betaflight/ladrc_rate.h) on
 * a rate plant w' = b0 kappa pidSum + d simulated here (the pidSum held over
 * each tick, exact), against the library's own RATE-ADRC axis in N m. */
#include "unity.h"
#include "ladrc_rate.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S (1.0f / 8000.0f) /* Betaflight's 8 kHz PID loop */
#define J_KG_M2 5.445e-3      /* the paper's roll inertia */
/* Torque of one pidSum unit (N m): a quad X, 12 N of thrust per unit of
 * motor_speed, 0.16 m roll levers, a 0.945 motor range
 * (docs/betaflight-integration.md): 4 * 0.16 * 12 * 0.945 / 1000; the 500
 * pidSum bound is then 667 rad/s^2 on J. */
#define KAPPA_NM (4.0 * 0.16 * 12.0 * 0.945 / 1000.0)
#define K_W_PER_S 75.0f
#define WO_RAD_S 300.0f
#define PIDSUM_LIMIT 500.0f
#define DEG 0.017453292519943295

/* A 200 deg/s step, k_w = 75 /s: the loop is k_w / (s + k_w) once z2 has the
 * plant, so 90 % is reached after ln(10) / k_w = 30.7 ms; the observer's
 * double pole at 300 rad/s adds a few ms. Bounds: 0.8x to 1.5x. */
#define RISE_MIN_S (0.8 * 2.302585 / 75.0)
#define RISE_MAX_S (1.5 * 2.302585 / 75.0)
/* After 0.3 s (22 time constants of the loop) the error is float rounding of
 * the ESO's states: z2 holds the 5.2e3 rad/s^2 of b0 kappa pidSum at an ulp of
 * 5e-4 rad/s^2, which the law turns into 5e-4 / k_w = 7e-6 rad/s; 1e-4 rad/s
 * (0.006 deg/s) leaves a factor 14. */
#define STEADY_ERROR_RAD_S 1e-4
/* A constant 200 rad/s^2 disturbance: a P loop alone would stand off by
 * d / k_w = 2.7 rad/s; the ESO takes d whole, so 0.3 s after it the error is
 * rounding as above. */
#define DIST_RAD_S2 200.0
/* The adapter's command times kappa against the native axis's torque: the
 * same arithmetic in other units, so they differ by float rounding only. Both
 * observers contract their rounding (poles at exp(-wo h) = 0.963 per tick), so
 * it does not accumulate beyond about 1 / (1 - 0.963) = 27 ticks' worth: 27
 * ticks times a few ulp (1.2e-7) of the largest torque, 2e-5 of it with room. */
#define SAME_REL 2e-5

typedef struct {
    double w; /* rad/s */
} plant_t;

static double b0_pidsum(void)
{
    return KAPPA_NM / J_KG_M2;
}

static void params_of(ladrc_bf_rate_params_t *p)
{
    memset(p, 0, sizeof *p);
    for (int i = 0; i < LADRC_BF_AXES; ++i) {
        p->k_w_per_s[i] = K_W_PER_S;
        p->wo_rad_s[i] = WO_RAD_S;
        p->b0_rad_s2_per_pidsum[i] = (float)b0_pidsum();
        p->pidsum_limit[i] = PIDSUM_LIMIT;
    }
}

static void plant_step(plant_t *pl, double pidsum, double d)
{
    pl->w += (b0_pidsum() * pidsum + d) * (double)DT_S;
}

static float gyro_deg_s(const plant_t *pl)
{
    return (float)(pl->w / DEG);
}

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_tracks_a_rate_step_and_rejects_a_constant_disturbance(void)
{
    ladrc_bf_rate_params_t p;
    params_of(&p);
    ladrc_bf_rate_t rc;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&rc, &p, DT_S));
    plant_t pl = {0.0};
    const double sp = 200.0 * DEG;
    double rise_s = -1.0;
    const int n_step = (int)(0.3f / DT_S), n_dist = (int)(0.3f / DT_S);
    for (int k = 0; k < n_step; ++k) {
        const float u = ladrc_bf_rate_step(&rc, 0, 200.0f, gyro_deg_s(&pl), DT_S);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_bf_rate_faults(&rc, 0));
        TEST_ASSERT_TRUE(fabsf(u) <= PIDSUM_LIMIT);
        plant_step(&pl, u, 0.0);
        if (rise_s < 0.0 && pl.w >= 0.9 * sp) {
            rise_s = (k + 1) * (double)DT_S;
        }
    }
    printf("figures: rise %.4f s, error %.3g rad/s\n", rise_s, pl.w - sp);
    TEST_ASSERT_TRUE_MESSAGE(rise_s >= RISE_MIN_S && rise_s <= RISE_MAX_S, "90 % rise time");
    TEST_ASSERT_TRUE_MESSAGE(fabs(pl.w - sp) <= STEADY_ERROR_RAD_S, "steady rate error");
    for (int k = 0; k < n_dist; ++k) {
        const float u = ladrc_bf_rate_step(&rc, 0, 200.0f, gyro_deg_s(&pl), DT_S);
        plant_step(&pl, u, DIST_RAD_S2);
    }
    TEST_ASSERT_TRUE_MESSAGE(fabs(pl.w - sp) <= STEADY_ERROR_RAD_S, "steady rate error");
    /* the command carries the disturbance: -d / b0 more pidSum than before */
    const float u_end = ladrc_bf_rate_step(&rc, 0, 200.0f, gyro_deg_s(&pl), DT_S);
    TEST_ASSERT_FLOAT_WITHIN(0.01f, (float)(-DIST_RAD_S2 / b0_pidsum()), u_end);
}

/* The native RATE-ADRC axis, as the simulator configures it (N m, b0 = 1 / J),
 * in acro on the same rate setpoint. */
static void native_axis(ladrc_axis_t *axis, const ladrc_bf_rate_params_t *p)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_RATE_ADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.radrc_acro = 1u;
    cfg.radrc_kp_per_s = (ladrc_real_t)p->k_w_per_s[0];
    cfg.wo_rad_s = (ladrc_real_t)p->wo_rad_s[0];
    cfg.radrc_rate_max_rad_s = cfg.rate_limit_rad_s;
    cfg.u_min_Nm = (ladrc_real_t)(-PIDSUM_LIMIT * KAPPA_NM);
    cfg.u_max_Nm = (ladrc_real_t)(PIDSUM_LIMIT * KAPPA_NM);
    cfg.motor_tau_s = (ladrc_real_t)p->motor_tau_s;
    cfg.delay_ticks = p->delay_ticks;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(axis, &cfg));
}

/* Setpoint steps and a sine, a disturbance step, the motors' lag and a
 * delay in the observer's model: the adapter's pidSum times kappa is the
 * native axis's torque on every tick. */
static void test_same_command_as_the_native_rate_loop(void)
{
    ladrc_bf_rate_params_t p;
    params_of(&p);
    p.motor_tau_s = 0.02f;
    p.delay_ticks = 4u;
    ladrc_bf_rate_t rc;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&rc, &p, DT_S));
    ladrc_axis_t native;
    native_axis(&native, &p);
    plant_t pl = {0.0};
    double lag = 0.0, max_diff = 0.0, max_torque = 0.0;
    const int n = (int)(1.0f / DT_S);
    for (int k = 0; k < n; ++k) {
        const double t = k * (double)DT_S;
        const float sp_deg_s = (float)((t < 0.3 ? 300.0 : -150.0) + 80.0 * sin(2.0 * 3.14159265358979 * 7.0 * t));
        const float gyro = gyro_deg_s(&pl);
        const float u = ladrc_bf_rate_step(&rc, 0, sp_deg_s, gyro, DT_S);
        const ladrc_real_t w = ladrc_bf_rad_s(gyro);
        ladrc_real_t torque = LADRC_R(0.0);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE,
                               ladrc_axis_step(&native, ladrc_bf_rad_s(sp_deg_s), LADRC_R(0.0), &w, &torque));
        const double diff = fabs((double)u * KAPPA_NM - (double)torque);
        max_diff = diff > max_diff ? diff : max_diff;
        max_torque = fabs((double)torque) > max_torque ? fabs((double)torque) : max_torque;
        /* the plant's motors lag as the model says */
        lag += (1.0 - exp(-(double)DT_S / 0.02)) * ((double)u - lag);
        plant_step(&pl, lag, t > 0.6 ? DIST_RAD_S2 : 0.0);
    }
    TEST_ASSERT_TRUE(max_torque > 0.1 * PIDSUM_LIMIT * KAPPA_NM); /* the case exercised the loop */
    printf("figures: max diff %.3g of %.3g N m (%.3g)\n", max_diff, max_torque, max_diff / max_torque);
    TEST_ASSERT_TRUE_MESSAGE(max_diff <= SAME_REL * max_torque, "adapter vs native command");
}

static void test_bad_input_holds_the_last_good_command(void)
{
    ladrc_bf_rate_params_t p;
    params_of(&p);
    ladrc_bf_rate_t rc;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&rc, &p, DT_S));
    float good = 0.0f;
    for (int k = 0; k < 20; ++k) {
        good = ladrc_bf_rate_step(&rc, 1, 100.0f, 0.0f, DT_S);
    }
    TEST_ASSERT_TRUE(good > 0.0f);
    const float held_rate = ladrc_bf_rate_step(&rc, 1, 100.0f, NAN, DT_S);
    TEST_ASSERT_EQUAL_FLOAT(good, held_rate);
    TEST_ASSERT_TRUE(ladrc_bf_rate_faults(&rc, 1) & LADRC_FAULT_RATE);
    const float held_input = ladrc_bf_rate_step(&rc, 1, INFINITY, 0.0f, DT_S);
    TEST_ASSERT_EQUAL_FLOAT(good, held_input);
    TEST_ASSERT_TRUE(ladrc_bf_rate_faults(&rc, 1) & LADRC_FAULT_INPUT);
    /* the next good tick flies on, no fault left */
    (void)ladrc_bf_rate_step(&rc, 1, 100.0f, 0.0f, DT_S);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_bf_rate_faults(&rc, 1));
    /* other axes untouched */
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_bf_rate_faults(&rc, 0));
    const float no_axis = ladrc_bf_rate_step(&rc, 7, 0.0f, 0.0f, DT_S);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, no_axis);
}

static void test_reset_on_disarm_and_a_new_loop_time(void)
{
    ladrc_bf_rate_params_t p;
    params_of(&p);
    ladrc_bf_rate_t rc, fresh;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&rc, &p, DT_S));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&fresh, &p, DT_S));
    for (int k = 0; k < 50; ++k) {
        (void)ladrc_bf_rate_step(&rc, 2, 300.0f, 10.0f, DT_S);
    }
    ladrc_bf_rate_reset(&rc);
    /* after the reset, the same as a fresh controller */
    for (int k = 0; k < 10; ++k) {
        const float want = ladrc_bf_rate_step(&fresh, 2, 50.0f, 1.0f, DT_S);
        const float got = ladrc_bf_rate_step(&rc, 2, 50.0f, 1.0f, DT_S);
        TEST_ASSERT_EQUAL_FLOAT(want, got);
    }
    /* a 4 kHz loop: set up again for it, as a fresh 4 kHz controller */
    ladrc_bf_rate_t fresh4;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_bf_rate_init(&fresh4, &p, 2.0f * DT_S));
    const float want4 = ladrc_bf_rate_step(&fresh4, 2, 50.0f, 1.0f, 2.0f * DT_S);
    const float got4 = ladrc_bf_rate_step(&rc, 2, 50.0f, 1.0f, 2.0f * DT_S);
    TEST_ASSERT_EQUAL_FLOAT(want4, got4);
}

static void test_refused_parameters(void)
{
    ladrc_bf_rate_params_t p;
    params_of(&p);
    ladrc_bf_rate_t rc;
    p.b0_rad_s2_per_pidsum[1] = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_bf_rate_init(&rc, &p, DT_S));
    p.b0_rad_s2_per_pidsum[1] = -1.0f; /* a sign Betaflight's PID never has */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_bf_rate_init(&rc, &p, DT_S));
    const float refused = ladrc_bf_rate_step(&rc, 0, 100.0f, 0.0f, DT_S);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, refused);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_STATE, ladrc_bf_rate_faults(&rc, 0));
    params_of(&p);
    p.k_w_per_s[2] = 9000.0f; /* k_w dt = 1.1 */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_RADRC_KP, ladrc_bf_rate_init(&rc, &p, DT_S));
    params_of(&p);
    p.pidsum_limit[0] = INFINITY;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_U_LIMITS, ladrc_bf_rate_init(&rc, &p, DT_S));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_bf_rate_init(NULL, &p, DT_S));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_tracks_a_rate_step_and_rejects_a_constant_disturbance);
    RUN_TEST(test_same_command_as_the_native_rate_loop);
    RUN_TEST(test_bad_input_holds_the_last_good_command);
    RUN_TEST(test_reset_on_disarm_and_a_new_loop_time);
    RUN_TEST(test_refused_parameters);
    return UNITY_END();
}
