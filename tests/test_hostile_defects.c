/* SPDX-License-Identifier: BSD-3-Clause */
/* Regression tests for the defects hostile inputs found: one huge finite
 * sample must not latch an estimator, an absurd finite input must not be
 * taken at face value, and no init may accept a config whose derived
 * constants overflow or that no rigid body has. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/estimator.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/leso.h"
#include "ladrc/rls.h"
#include "test_plant.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S 0.001
#define J_KG_M2 5.445e-3
/* The paper's roll disturbance: bias 20, 120 rad/s^2 at 3 rad/s. */
static const test_sine_t paper_tone = {.bias = 20.0, .amp = 120.0, .w_rad_s = 3.0, .phase_rad = 0.0};
/* Back to normal 6 s after a glitch: the last second's largest error within
 * 10 % (+1e-5 rad for HP's near-zero error) of the same flight without it. */
#define RECOVERED_FACTOR 1.1
#define RECOVERED_FLOOR_RAD 1e-5
#define GLITCH_TICK 10000
#define END_TICK 16000

typedef enum { GLITCH_ANGLE, GLITCH_APPLIED, GLITCH_REFERENCE } glitch_t;

/* Flies an axis on the paper's tone with one glitched tick at 10 s; returns
 * the largest |error| over the last second; counts LADRC_FAULT_STATE ticks
 * and checks the glitched tick's flag and that it left the estimate alone. */
static double fly(ladrc_variant_t variant, glitch_t glitch, ladrc_real_t value, int glitch_tick, int *state_faults)
{
    ladrc_axis_config_t cfg;
    static ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    test_double_integrator_t plant;
    test_plant_init(&plant, 1.0 / J_KG_M2, test_sine_disturbance, &paper_tone);
    double worst = 0.0;
    *state_faults = 0;
    for (int k = 0; k < END_TICK; ++k) {
        ladrc_real_t angle = (ladrc_real_t)plant.y_rad;
        ladrc_real_t ref = LADRC_R(0.0);
        ladrc_real_t est[3];
        ladrc_axis_get_estimate(&axis, &est[0], &est[1], &est[2]);
        if (k == glitch_tick && glitch == GLITCH_ANGLE) {
            angle = value;
        }
        if (k == glitch_tick && glitch == GLITCH_REFERENCE) {
            ref = value;
        }
        const ladrc_real_t u = axis_command_with_rate(&axis, ref, angle, (ladrc_real_t)plant.rate_rad_s);
        if (k == glitch_tick && glitch != GLITCH_APPLIED) {
            ladrc_real_t after[3];
            ladrc_axis_get_estimate(&axis, &after[0], &after[1], &after[2]);
            TEST_ASSERT_TRUE((ladrc_axis_get_faults(&axis) & LADRC_FAULT_INPUT) != 0u);
            TEST_ASSERT_EQUAL_MEMORY(est, after, sizeof est);
        }
        if (k == glitch_tick && glitch == GLITCH_APPLIED) {
            ladrc_axis_set_applied(&axis, value);
            TEST_ASSERT_TRUE((ladrc_axis_get_faults(&axis) & LADRC_FAULT_APPLIED) != 0u);
        }
        *state_faults += (ladrc_axis_get_faults(&axis) & LADRC_FAULT_STATE) != 0u;
        test_plant_step(&plant, (double)u, DT_S, 1);
        if (k >= END_TICK - 1000) {
            worst = fmax(worst, fabs(plant.y_rad));
        }
    }
    return worst;
}

/* The glitched flight's final error against the clean one's. */
static void check_recovers(ladrc_variant_t variant, glitch_t glitch, ladrc_real_t value)
{
    int state_faults;
    const double clean = fly(variant, glitch, value, -1, &state_faults);
    const double glitched = fly(variant, glitch, value, GLITCH_TICK, &state_faults);
    TEST_ASSERT_EQUAL_INT(0, state_faults);
    TEST_ASSERT_TRUE(glitched <= RECOVERED_FACTOR * clean + RECOVERED_FLOOR_RAD);
}

static void test_one_huge_angle_sample_does_not_latch_hp_mladrc(void)
{
    /* Before: every tick after it raised LADRC_FAULT_STATE and the command froze. */
    check_recovers(LADRC_VARIANT_HP_MLADRC, GLITCH_ANGLE, (ladrc_real_t)1e17);
}

static void test_one_huge_applied_torque_does_not_latch_hp_mladrc(void)
{
    check_recovers(LADRC_VARIANT_HP_MLADRC, GLITCH_APPLIED, (ladrc_real_t)1e30);
}

static void test_an_absurd_reference_tick_never_reaches_the_levant_shaper(void)
{
    /* Before: one 1e10 rad reference kept Levant's output at 1e4..1e22 for 20 s. */
    check_recovers(LADRC_VARIANT_LP_MLADRC, GLITCH_REFERENCE, (ladrc_real_t)1e10);
}

static void test_an_absurd_finite_angle_never_reaches_the_observer(void)
{
    /* Before: an angle of 1e30 pushed the LESO to 1e33. */
    check_recovers(LADRC_VARIANT_LADRC, GLITCH_ANGLE, (ladrc_real_t)1e30);
}

static void test_indi_recovers_from_one_glitched_angle_torque_or_reference(void)
{
    /* An INDI tick with a bad angle leaves its filters alone, so the next
     * acceleration spans two steps once: a transient, no latch. */
    check_recovers(LADRC_VARIANT_INDI, GLITCH_ANGLE, (ladrc_real_t)1e30);
    check_recovers(LADRC_VARIANT_INDI, GLITCH_APPLIED, (ladrc_real_t)1e30);
    check_recovers(LADRC_VARIANT_INDI, GLITCH_REFERENCE, (ladrc_real_t)1e10);
}

static void test_absurd_samples_never_reach_the_cascaded_loops(void)
{
    check_recovers(LADRC_VARIANT_CASCADED, GLITCH_ANGLE, (ladrc_real_t)1e30);
    check_recovers(LADRC_VARIANT_CASCADED, GLITCH_APPLIED, (ladrc_real_t)1e30);
    check_recovers(LADRC_VARIANT_CASCADED, GLITCH_REFERENCE, (ladrc_real_t)1e10);
}

static void test_the_ranges_are_inclusive_and_apply_to_every_input(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.angle_limit_rad = LADRC_R(2.0);
    cfg.rate_limit_rad_s = LADRC_R(3.0);
    cfg.applied_limit_Nm = LADRC_R(0.5);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    (void)axis_command_with_rate(&axis, LADRC_R(2.0), LADRC_R(-2.0), LADRC_R(3.0));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
    (void)axis_command(&axis, LADRC_R(2.001), LADRC_R(0.0));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_axis_get_faults(&axis));
    (void)axis_command(&axis, LADRC_R(0.0), LADRC_R(-2.001));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_axis_get_faults(&axis));
    (void)axis_command_with_rate(&axis, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(-3.001));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE, ladrc_axis_get_faults(&axis));
    ladrc_axis_set_applied(&axis, LADRC_R(0.5));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE, ladrc_axis_get_faults(&axis));
    ladrc_axis_set_applied(&axis, LADRC_R(-0.501));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE | LADRC_FAULT_APPLIED, ladrc_axis_get_faults(&axis));
}

static void test_hp_refuses_a_sample_beyond_its_range_and_keeps_its_estimate(void)
{
    ladrc_axis_config_t axis_cfg;
    ladrc_axis_config_default(&axis_cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    static ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &axis_cfg));
    ladrc_hp_estimator_t *est = &axis.part.hp.est;
    for (int k = 0; k < 3000; ++k) {
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_hp_step(est, (ladrc_real_t)(50.0 * sin(3.0 * k * DT_S))));
    }
    const ladrc_real_t bias = ladrc_hp_get_bias(est);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_hp_step(est, (ladrc_real_t)1.0000001e6));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_hp_step(est, (ladrc_real_t)-1e30));
    TEST_ASSERT_TRUE(ladrc_hp_get_bias(est) == bias);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_hp_step(est, (ladrc_real_t)1e6));
}

/* Configs accepted before although their derived constants overflow. */
static void test_axis_init_refuses_what_it_cannot_discretise(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_config_t bad = cfg;
    bad.wc_rad_s = (ladrc_real_t)1e20; /* kp = wc^2 overflowed: every tick refused */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_WC_RAD_S, ladrc_axis_init(&axis, &bad));
    bad.wc_rad_s = (ladrc_real_t)(1.0 / DT_S); /* wc dt = 1: the sampled loop's stability limit */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_WC_RAD_S, ladrc_axis_init(&axis, &bad));
    bad.wc_rad_s = (ladrc_real_t)(0.99 / DT_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &bad));
    bad = cfg;
    bad.b0 = LADRC_REAL_MIN / LADRC_R(16.0); /* 1 / b0 overflows */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_axis_init(&axis, &bad));
    bad = cfg;
    bad.wo_rad_s = (ladrc_real_t)1e-30; /* HP's lead (1 + j w / wo)^3 overflowed: estimate NaN, no flag */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_SAMPLE_LAG, ladrc_axis_init(&axis, &bad));
    bad.wo_rad_s = cfg.hp_freq_max_rad_s / LADRC_R(10.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &bad));
    const ladrc_real_t bad_limits[4] = {LADRC_R(0.0), (ladrc_real_t)-1.0, (ladrc_real_t)INFINITY, (ladrc_real_t)NAN};
    for (int i = 0; i < 4; ++i) {
        bad = cfg;
        bad.angle_limit_rad = bad_limits[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_INPUT_LIMITS, ladrc_axis_init(&axis, &bad));
        bad = cfg;
        bad.rate_limit_rad_s = bad_limits[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_INPUT_LIMITS, ladrc_axis_init(&axis, &bad));
        bad = cfg;
        bad.applied_limit_Nm = bad_limits[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_INPUT_LIMITS, ladrc_axis_init(&axis, &bad));
    }
}

/* The largest angle limit init takes (axis.h), and a tick's faults: no
 * state fault may outlive the tick that raised it, whatever angle within the
 * limit a reset left the shapers at. */
#define ANGLE_LIMIT_MAX_RAD 1e6
#define GOOD_TICKS 2000
/* A reset far from the reference makes the first ticks shape a huge step; a
 * state fault there is allowed, one that keeps coming is not. */
#define STATE_FAULT_RUN_MAX 1

static void test_no_state_fault_outlives_its_tick_after_a_reset_at_the_largest_angle_limit(void)
{
    for (int v = 0; v < (int)LADRC_VARIANT_COUNT; ++v) {
        ladrc_axis_config_t cfg;
        ladrc_axis_t axis;
        ladrc_axis_config_default(&cfg, (ladrc_variant_t)v, (ladrc_real_t)DT_S, LADRC_R(5.445e-3));
        cfg.u_min_Nm = LADRC_R(-0.5);
        cfg.u_max_Nm = LADRC_R(0.5);
        cfg.angle_limit_rad = (ladrc_real_t)(1.1 * ANGLE_LIMIT_MAX_RAD);
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_INPUT_LIMITS, ladrc_axis_init(&axis, &cfg));
        cfg.angle_limit_rad = (ladrc_real_t)ANGLE_LIMIT_MAX_RAD;
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
        ladrc_axis_reset(&axis, (ladrc_real_t)(0.9 * ANGLE_LIMIT_MAX_RAD));
        int run = 0, longest = 0;
        ladrc_real_t u = LADRC_R(0.0);
        for (int k = 0; k < GOOD_TICKS; ++k) {
            const ladrc_real_t rate = LADRC_R(0.0);
            const ladrc_fault_t f = ladrc_axis_step(&axis, LADRC_R(0.1), LADRC_R(0.0), &rate, &u);
            ladrc_axis_set_applied(&axis, u);
            run = ((f & LADRC_FAULT_STATE) != 0u) ? run + 1 : 0;
            longest = (run > longest) ? run : longest;
        }
        char msg[80];
        snprintf(msg, sizeof msg, "variant %d: %d ticks of state faults in a row", v, longest);
        TEST_ASSERT_TRUE_MESSAGE(longest <= STATE_FAULT_RUN_MAX, msg);
    }
}

static void test_steps_no_module_can_discretise_are_refused(void)
{
    const ladrc_real_t steps[4] = {(ladrc_real_t)1e30, (ladrc_real_t)2.0, (ladrc_real_t)9e-7, LADRC_REAL_MIN};
    for (int i = 0; i < 4; ++i) {
        ladrc_leso_t leso;
        const ladrc_leso_config_t leso_cfg = {
            .dt_s = steps[i], .wo_rad_s = LADRC_R(75.0), .b0 = LADRC_R(100.0), .method = LADRC_LESO_ZOH};
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_leso_init(&leso, &leso_cfg));
        ladrc_rls_t rls;
        const ladrc_rls_config_t rls_cfg = {.n_params = 3u,
                                            .dt_s = steps[i],
                                            .lambda0_per_s = LADRC_R(0.0),
                                            .p_bound = LADRC_R(1e4),
                                            .p_initial = LADRC_R(1.0)};
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_rls_init(&rls, &rls_cfg));
        static ladrc_gyro_filter_t gf;
        ladrc_gyro_filter_config_t gf_cfg;
        ladrc_gyro_filter_config_default(&gf_cfg, steps[i], 3u);
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_gyro_filter_init(&gf, &gf_cfg));
    }
    ladrc_leso_t leso;
    const ladrc_leso_config_t edge[2] = {
        {.dt_s = LADRC_DT_MIN_S, .wo_rad_s = LADRC_R(75.0), .b0 = LADRC_R(100.0), .method = LADRC_LESO_ZOH},
        {.dt_s = LADRC_DT_MAX_S, .wo_rad_s = LADRC_R(75.0), .b0 = LADRC_R(100.0), .method = LADRC_LESO_ZOH}};
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&leso, &edge[0]));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_leso_init(&leso, &edge[1]));
}

static void test_attitude_init_refuses_bodies_that_cannot_exist(void)
{
    static ladrc_attitude_t att;
    ladrc_attitude_config_t cfg;
    const ladrc_real_t paper[3] = {(ladrc_real_t)J_KG_M2, (ladrc_real_t)J_KG_M2, (ladrc_real_t)1.089e-2};
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, paper, LADRC_R(0.09));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL)); /* a flat body: Jz = Jx + Jy */
    ladrc_attitude_config_t bad = cfg;
    bad.inertia_kg_m2[2] = (ladrc_real_t)1.1e-2; /* Jz > Jx + Jy */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_INERTIA_TRIANGLE, ladrc_attitude_init(&att, &bad, NULL));
    bad = cfg;
    bad.inertia_kg_m2[0] = (ladrc_real_t)2e-2; /* Jx > Jy + Jz */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_INERTIA_TRIANGLE, ladrc_attitude_init(&att, &bad, NULL));
    bad = cfg;
    bad.drag_Nms = LADRC_R(100.0); /* drag / J = 18,000 /s, 2 / dt is 2,000 /s */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DRAG_NMS, ladrc_attitude_init(&att, &bad, NULL));
    bad.drag_Nms = (ladrc_real_t)(1.99 * J_KG_M2 / DT_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &bad, NULL));
}

void setUp(void)
{
}
void tearDown(void)
{
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_one_huge_angle_sample_does_not_latch_hp_mladrc);
    RUN_TEST(test_one_huge_applied_torque_does_not_latch_hp_mladrc);
    RUN_TEST(test_an_absurd_reference_tick_never_reaches_the_levant_shaper);
    RUN_TEST(test_an_absurd_finite_angle_never_reaches_the_observer);
    RUN_TEST(test_indi_recovers_from_one_glitched_angle_torque_or_reference);
    RUN_TEST(test_absurd_samples_never_reach_the_cascaded_loops);
    RUN_TEST(test_the_ranges_are_inclusive_and_apply_to_every_input);
    RUN_TEST(test_hp_refuses_a_sample_beyond_its_range_and_keeps_its_estimate);
    RUN_TEST(test_axis_init_refuses_what_it_cannot_discretise);
    RUN_TEST(test_steps_no_module_can_discretise_are_refused);
    RUN_TEST(test_no_state_fault_outlives_its_tick_after_a_reset_at_the_largest_angle_limit);
    RUN_TEST(test_attitude_init_refuses_bodies_that_cannot_exist);
    return UNITY_END();
}
