/* SPDX-License-Identifier: BSD-3-Clause */
/* LESO: pole placement of both discretisations, disturbance estimation,
 * known inputs, validation and fault handling. */
#include "unity.h"
#include "ladrc/leso.h"
#include "test_plant.h"

#include <math.h>
#include <string.h>

#define DT_S 1e-3
#define WO_RAD_S 75.0
/* Paper vehicle roll inertia: b0 = 1/Jx rad/s^2 per N m. */
#define B0 (1.0 / 5.445e-3)

/* Residual of the pole recurrence relative to the error's peak. Float
 * rounding (6e-8 relative) through three steps stays near 1e-8 (measured
 * 9e-9 ZOH, 1.3e-7 Euler); a pole misplaced by 0.01% leaves about 1e-4. */
#define RECURRENCE_REL_TOL 1e-5
/* Float estimate of a constant 20 rad/s^2 disturbance: rounding of y
 * (ulp 1.5e-8 rad near 0.2 rad) amplified by l3 = 377 per step; measured
 * 9e-5 rad/s^2 after 1 s, so 1e-3 (5e-5 of f) leaves a 10x margin. */
#define DISTURBANCE_TOL_RAD_S2 1e-3

static ladrc_leso_config_t config(ladrc_leso_method_t method)
{
    ladrc_leso_config_t cfg = {
        .dt_s = (ladrc_real_t)DT_S, .wo_rad_s = (ladrc_real_t)WO_RAD_S, .b0 = (ladrc_real_t)B0, .method = method};
    return cfg;
}

void setUp(void)
{
}
void tearDown(void)
{
}

/* Runs the observer on an exact double-integrator with constant disturbance
 * f and a varying ZOH input, storing the estimation errors e_k = x_k - z_k. */
static void record_errors(ladrc_leso_method_t method, double f, int n, double err[][3])
{
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(method);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&obs, &cfg));
    ladrc_leso_reset(&obs, 0.0f);
    const test_sine_t d = {.bias = f, .amp = 0.0, .w_rad_s = 0.0, .phase_rad = 0.0};
    test_double_integrator_t plant;
    test_plant_init(&plant, B0, test_sine_disturbance, &d);
    plant.y_rad = 0.2;
    double u = -f / B0;
    for (int k = 0; k < n; ++k) {
        test_plant_step(&plant, u, DT_S, 1);
        ladrc_leso_step(&obs, (ladrc_real_t)plant.y_rad, (ladrc_real_t)u, 0.0f, 0.0f);
        err[k][0] = plant.y_rad - obs.z1;
        err[k][1] = plant.rate_rad_s - obs.z2;
        err[k][2] = f - obs.z3;
        /* any input works; this one holds the plant near 0.2 rad, as a loop would */
        u = (-f + 5.0 * sin(0.05 * k)) / B0;
    }
}

static void test_zoh_error_decays_per_step_as_a_triple_pole_at_exp_minus_wo_h(void)
{
    /* given a ZOH observer on an exact plant with f = 20 rad/s^2 */
    enum { N = 120 };
    static double err[N][3];
    record_errors(LADRC_LESO_ZOH, 20.0, N, err);
    const double beta = exp(-WO_RAD_S * DT_S);
    /* then every error component satisfies (q - beta)^3 e = 0 */
    for (int c = 0; c < 3; ++c) {
        double scale = 0.0;
        for (int k = 0; k < N; ++k) {
            scale = fmax(scale, fabs(err[k][c]));
        }
        for (int k = 0; k + 3 < 40; ++k) {
            const double r = err[k + 3][c] - 3.0 * beta * err[k + 2][c] + 3.0 * beta * beta * err[k + 1][c] -
                             beta * beta * beta * err[k][c];
            TEST_ASSERT_FLOAT_WITHIN(RECURRENCE_REL_TOL, 0.0, r / scale);
        }
    }
}

static void test_euler_homogeneous_error_has_a_triple_pole_at_one_minus_wo_h(void)
{
    /* given an Euler observer started away from the zero measurement */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_EULER);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&obs, &cfg));
    obs.z1 = 0.1f;
    obs.z2 = -1.0f;
    obs.z3 = 30.0f;
    enum { N = 60 };
    double z[N][3];
    for (int k = 0; k < N; ++k) {
        ladrc_leso_step(&obs, 0.0f, 0.0f, 0.0f, 0.0f);
        z[k][0] = obs.z1;
        z[k][1] = obs.z2;
        z[k][2] = obs.z3;
    }
    /* then the sequence obeys (q - (1 - wo h))^3 z = 0 */
    const double p = 1.0 - WO_RAD_S * DT_S;
    for (int c = 0; c < 3; ++c) {
        double scale = 0.0;
        for (int k = 0; k < N; ++k) {
            scale = fmax(scale, fabs(z[k][c]));
        }
        for (int k = 0; k + 3 < N; ++k) {
            const double r = z[k + 3][c] - 3.0 * p * z[k + 2][c] + 3.0 * p * p * z[k + 1][c] - p * p * p * z[k][c];
            TEST_ASSERT_FLOAT_WITHIN(RECURRENCE_REL_TOL, 0.0, r / scale);
        }
    }
}

static void test_zoh_estimates_a_constant_disturbance(void)
{
    enum { N = 1000 }; /* 1 s: 75 time constants of the observer */
    static double err[N][3];
    record_errors(LADRC_LESO_ZOH, 20.0, N, err);
    TEST_ASSERT_FLOAT_WITHIN(DISTURBANCE_TOL_RAD_S2, 0.0, err[N - 1][2]);
}

static void test_euler_is_rejected_where_its_poles_leave_the_unit_circle(void)
{
    ladrc_leso_t obs;
    ladrc_leso_config_t cfg = config(LADRC_LESO_EULER);
    cfg.wo_rad_s = 2000.0f; /* wo h = 2: pole at -1 */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_LESO_EULER_UNSTABLE, ladrc_leso_init(&obs, &cfg));
    cfg.wo_rad_s = 5000.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_LESO_EULER_UNSTABLE, ladrc_leso_init(&obs, &cfg));
}

static void test_euler_just_inside_the_limit_is_accepted_and_converges(void)
{
    ladrc_leso_t obs;
    ladrc_leso_config_t cfg = config(LADRC_LESO_EULER);
    cfg.wo_rad_s = 1500.0f; /* wo h = 1.5: pole at -0.5 */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&obs, &cfg));
    obs.z3 = 10.0f;
    for (int k = 0; k < 200; ++k) {
        ladrc_leso_step(&obs, 0.0f, 0.0f, 0.0f, 0.0f);
    }
    /* 0.5^200 times a polynomial in k: nothing measurable is left */
    TEST_ASSERT_FLOAT_WITHIN(1e-6f, 0.0f, obs.z3);
}

static void test_zoh_is_accepted_at_any_positive_bandwidth(void)
{
    ladrc_leso_t obs;
    ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    cfg.wo_rad_s = 5000.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&obs, &cfg));
}

/* Ramp disturbance f = slope * t: a LESO told the slope has no lag. */
static double ramp(double t_s, const void *ctx)
{
    return *(const double *)ctx * t_s;
}

static double ramp_estimate_error(int tell_slope)
{
    const double slope = 50.0; /* rad/s^3 */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    test_double_integrator_t plant;
    test_plant_init(&plant, B0, ramp, &slope);
    for (int k = 0; k < 1000; ++k) {
        test_plant_step(&plant, 0.0, DT_S, 4);
        ladrc_leso_step(&obs, (ladrc_real_t)plant.y_rad, 0.0f, 0.0f, tell_slope ? (ladrc_real_t)slope : 0.0f);
    }
    return slope * plant.t_s - obs.z3;
}

static void test_known_disturbance_rate_removes_the_ramp_lag(void)
{
    /* without the rate the z3 lag is slope * 3 / wo = 2 rad/s^2 */
    const double lag = ramp_estimate_error(0);
    TEST_ASSERT_FLOAT_WITHIN(0.05 * 2.0, 2.0, lag);
    /* with it, the lag is gone: float noise only, measured 6e-3 with y near
     * 8 rad (ulp 1e-6 rad times l3 = 377), 1e-11 in the double build */
    TEST_ASSERT_FLOAT_WITHIN(0.02, 0.0, ramp_estimate_error(1));
}

static void test_known_acceleration_is_not_counted_as_disturbance(void)
{
    /* given a plant pushed by a known 30 rad/s^2 that the observer is told of */
    const test_sine_t d = {.bias = 30.0, .amp = 0.0, .w_rad_s = 0.0, .phase_rad = 0.0};
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    test_double_integrator_t plant;
    test_plant_init(&plant, B0, test_sine_disturbance, &d);
    for (int k = 0; k < 1000; ++k) {
        /* the test's own compensation -30 keeps y small, as a loop would */
        test_plant_step(&plant, -30.0 / B0, DT_S, 1);
        ladrc_leso_step(&obs, (ladrc_real_t)plant.y_rad, (ladrc_real_t)(-30.0 / B0), 30.0f, 0.0f);
    }
    /* then z3 holds only the unknown part, zero */
    TEST_ASSERT_FLOAT_WITHIN(DISTURBANCE_TOL_RAD_S2, 0.0f, obs.z3);
}

static void test_every_invalid_field_is_rejected_with_its_status(void)
{
    ladrc_leso_t obs;
    const ladrc_leso_config_t good = config(LADRC_LESO_ZOH);
    ladrc_leso_config_t cfg;
    const ladrc_real_t bad[] = {0.0f, -1.0f, (ladrc_real_t)NAN, (ladrc_real_t)INFINITY};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        cfg = good;
        cfg.dt_s = bad[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_leso_init(&obs, &cfg));
        cfg = good;
        cfg.wo_rad_s = bad[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_WO_RAD_S, ladrc_leso_init(&obs, &cfg));
    }
    const ladrc_real_t bad_b0[] = {0.0f, (ladrc_real_t)NAN, (ladrc_real_t)-INFINITY};
    for (unsigned i = 0; i < sizeof bad_b0 / sizeof bad_b0[0]; ++i) {
        cfg = good;
        cfg.b0 = bad_b0[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_leso_init(&obs, &cfg));
    }
    cfg = good;
    cfg.method = (ladrc_leso_method_t)7;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_LESO_METHOD, ladrc_leso_init(&obs, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_leso_init(NULL, &good));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_leso_init(&obs, NULL));
}

static void test_negative_b0_is_accepted_for_reversed_actuators(void)
{
    ladrc_leso_t obs;
    ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    cfg.b0 = -cfg.b0;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&obs, &cfg));
}

static void test_non_finite_inputs_hold_the_state_and_raise_a_fault(void)
{
    /* both forms: the step tells a bad argument from the result it spoils */
    const ladrc_leso_method_t methods[] = {LADRC_LESO_ZOH, LADRC_LESO_EULER};
    for (unsigned m = 0; m < 2; ++m) {
        ladrc_leso_t obs;
        const ladrc_leso_config_t cfg = config(methods[m]);
        ladrc_leso_init(&obs, &cfg);
        ladrc_leso_step(&obs, 0.1f, 0.01f, 0.0f, 0.0f);
        const ladrc_leso_t before = obs;
        const ladrc_real_t bad[] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY};
        for (unsigned i = 0; i < 3; ++i) {
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_leso_step(&obs, bad[i], 0.0f, 0.0f, 0.0f));
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_leso_step(&obs, 0.1f, bad[i], 0.0f, 0.0f));
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_leso_step(&obs, 0.1f, 0.0f, bad[i], 0.0f));
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_leso_step(&obs, 0.1f, 0.0f, 0.0f, bad[i]));
        }
        TEST_ASSERT_EQUAL_MEMORY(&before.z1, &obs.z1, 3 * sizeof(ladrc_real_t));
        /* and a finite sample clears the flag */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_leso_step(&obs, 0.1f, 0.0f, 0.0f, 0.0f));
    }
}

static void test_an_overflowing_update_is_refused_and_flagged(void)
{
    /* given finite but absurd inputs whose update overflows */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    const ladrc_leso_t before = obs;
    const ladrc_real_t huge = (ladrc_real_t)(sizeof(ladrc_real_t) == 4 ? 3e38 : 1.7e308);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_leso_step(&obs, huge, huge, huge, 0.0f));
    TEST_ASSERT_EQUAL_MEMORY(&before.z1, &obs.z1, 3 * sizeof(ladrc_real_t));
}

static void test_reset_restarts_at_rest_on_the_given_output(void)
{
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    ladrc_leso_step(&obs, 1.0f, 1.0f, 0.0f, 0.0f);
    ladrc_leso_reset(&obs, 0.3f);
    TEST_ASSERT_FLOAT_WITHIN(1e-9f, 0.3f, obs.z1);
    TEST_ASSERT_FLOAT_WITHIN(1e-9f, 0.0f, obs.z2);
    TEST_ASSERT_FLOAT_WITHIN(1e-9f, 0.0f, obs.z3);
}

static void test_reset_on_a_non_finite_output_restarts_at_rest_on_zero(void)
{
    /* given an observer that has moved */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    ladrc_leso_step(&obs, 1.0f, 1.0f, 0.0f, 0.0f);
    /* when it is reset on a NaN */
    ladrc_leso_reset(&obs, (ladrc_real_t)NAN);
    /* then it rests on 0, and the next finite step runs */
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, obs.z1);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, obs.z2);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, obs.z3);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_leso_step(&obs, 0.1f, 0.0f, 0.0f, 0.0f));
}

static void test_a_twin_fed_the_same_inputs_follows_the_observer_bit_for_bit(void)
{
    /* given an observer and a twin on its gains, both at rest on 0.1 rad */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    ladrc_leso_reset(&obs, 0.1f);
    ladrc_leso_twin_t twin;
    ladrc_leso_twin_reset(&twin, 0.1f);
    const ladrc_leso_t gains_before = obs;
    for (int k = 0; k < 200; ++k) {
        /* when both see the same samples, the twin stepped first */
        const ladrc_real_t y = (ladrc_real_t)(0.1 + 0.05 * sin(0.03 * k));
        const ladrc_real_t u = (ladrc_real_t)cos(0.02 * k);
        const ladrc_leso_t untouched = obs;
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_leso_step_twin(&obs, &twin, y, u, 2.0f, 0.5f));
        /* then the observer itself was not changed by its twin */
        TEST_ASSERT_EQUAL_MEMORY(&untouched, &obs, sizeof obs);
        ladrc_leso_step(&obs, y, u, 2.0f, 0.5f);
        /* and both estimates are the same numbers */
        TEST_ASSERT_EQUAL_MEMORY(&obs.z1, &twin.z1, sizeof(ladrc_real_t));
        TEST_ASSERT_EQUAL_MEMORY(&obs.z2, &twin.z2, sizeof(ladrc_real_t));
        TEST_ASSERT_EQUAL_MEMORY(&obs.z3, &twin.z3, sizeof(ladrc_real_t));
    }
    TEST_ASSERT_EQUAL_MEMORY(&gains_before.l1, &obs.l1, 3 * sizeof(ladrc_real_t));
}

static void test_a_twin_holds_its_estimate_on_bad_input_and_restarts_on_a_finite_output(void)
{
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_EULER);
    ladrc_leso_init(&obs, &cfg);
    ladrc_leso_twin_t twin;
    ladrc_leso_twin_reset(&twin, (ladrc_real_t)NAN);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, twin.z1);
    ladrc_leso_step_twin(&obs, &twin, 0.2f, 1.0f, 0.0f, 0.0f);
    const ladrc_leso_twin_t before = twin;
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_leso_step_twin(&obs, &twin, 0.2f, (ladrc_real_t)NAN, 0.0f, 0.0f));
    TEST_ASSERT_EQUAL_MEMORY(&before, &twin, sizeof twin);
    const ladrc_real_t huge = (ladrc_real_t)(sizeof(ladrc_real_t) == 4 ? 3e38 : 1.7e308);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_leso_step_twin(&obs, &twin, huge, huge, huge, 0.0f));
    TEST_ASSERT_EQUAL_MEMORY(&before, &twin, sizeof twin);
    ladrc_leso_twin_reset(&twin, 0.3f);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.3f, twin.z1);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, twin.z2);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, twin.z3);
}

static void test_a_hand_over_moves_part_of_z3_into_the_known_input_seamlessly(void)
{
    /* given an observer that has converged on a constant disturbance of 50
     * rad/s^2, and its twin */
    ladrc_leso_t obs;
    const ladrc_leso_config_t cfg = config(LADRC_LESO_ZOH);
    ladrc_leso_init(&obs, &cfg);
    ladrc_leso_twin_t twin;
    ladrc_leso_twin_reset(&twin, 0.0f);
    for (int k = 0; k < 2000; ++k) {
        ladrc_leso_step(&obs, 0.0f, -50.0f / (ladrc_real_t)B0, 0.0f, 0.0f); /* input cancels f */
        ladrc_leso_step_twin(&obs, &twin, 0.0f, -50.0f / (ladrc_real_t)B0, 0.0f, 0.0f);
    }
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 50.0f, obs.z3);
    /* when 30 of it is handed over to a known input from now on */
    ladrc_leso_hand_over(&obs, 30.0f);
    ladrc_leso_twin_hand_over(&twin, 30.0f);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 20.0f, obs.z3);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 20.0f, twin.z3);
    /* then z3 + known input stays at 50 tick after tick: nothing to relearn */
    for (int k = 0; k < 500; ++k) {
        ladrc_leso_step(&obs, 0.0f, -50.0f / (ladrc_real_t)B0, 30.0f, 0.0f);
        TEST_ASSERT_FLOAT_WITHIN(1e-3f, 50.0f, obs.z3 + 30.0f);
    }
    /* and a non-finite hand-over is ignored */
    const ladrc_leso_t before = obs;
    ladrc_leso_hand_over(&obs, (ladrc_real_t)NAN);
    ladrc_leso_hand_over(&obs, (ladrc_real_t)INFINITY);
    TEST_ASSERT_EQUAL_MEMORY(&before, &obs, sizeof obs);
    const ladrc_leso_twin_t twin_before = twin;
    ladrc_leso_twin_hand_over(&twin, (ladrc_real_t)-INFINITY);
    TEST_ASSERT_EQUAL_MEMORY(&twin_before, &twin, sizeof twin);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_zoh_error_decays_per_step_as_a_triple_pole_at_exp_minus_wo_h);
    RUN_TEST(test_euler_homogeneous_error_has_a_triple_pole_at_one_minus_wo_h);
    RUN_TEST(test_zoh_estimates_a_constant_disturbance);
    RUN_TEST(test_euler_is_rejected_where_its_poles_leave_the_unit_circle);
    RUN_TEST(test_euler_just_inside_the_limit_is_accepted_and_converges);
    RUN_TEST(test_zoh_is_accepted_at_any_positive_bandwidth);
    RUN_TEST(test_known_disturbance_rate_removes_the_ramp_lag);
    RUN_TEST(test_known_acceleration_is_not_counted_as_disturbance);
    RUN_TEST(test_every_invalid_field_is_rejected_with_its_status);
    RUN_TEST(test_negative_b0_is_accepted_for_reversed_actuators);
    RUN_TEST(test_non_finite_inputs_hold_the_state_and_raise_a_fault);
    RUN_TEST(test_an_overflowing_update_is_refused_and_flagged);
    RUN_TEST(test_reset_restarts_at_rest_on_the_given_output);
    RUN_TEST(test_reset_on_a_non_finite_output_restarts_at_rest_on_zero);
    RUN_TEST(test_a_twin_fed_the_same_inputs_follows_the_observer_bit_for_bit);
    RUN_TEST(test_a_twin_holds_its_estimate_on_bad_input_and_restarts_on_a_finite_output);
    RUN_TEST(test_a_hand_over_moves_part_of_z3_into_the_known_input_seamlessly);
    return UNITY_END();
}
