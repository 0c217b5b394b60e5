/* SPDX-License-Identifier: BSD-3-Clause */
/* The one NULL convention (docs/architecture.md): with asserts off, a
 * function given NULL for a pointer it needs returns its safe value (steps
 * and fault getters LADRC_FAULT_STATE, other getters 0 or NULL), writes no
 * output and changes no state; inits return LADRC_ERR_NULL. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "ladrc/cascaded.h"
#include "ladrc/estimator.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/indi.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/mixer.h"
#include "ladrc/pid.h"
#include "ladrc/rls.h"
#include "ladrc/td.h"

#include <string.h>

/* An output the functions must leave alone: any value they would write
 * (a torque, an estimate) differs from it. */
#define UNTOUCHED LADRC_R(-12345.0)

static ladrc_axis_t axis;
static ladrc_attitude_t att;

void setUp(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, LADRC_R(0.001), LADRC_R(0.01));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    const ladrc_real_t inertia[LADRC_AXES] = {LADRC_R(0.01), LADRC_R(0.01), LADRC_R(0.02)};
    ladrc_attitude_config_t att_cfg;
    ladrc_attitude_config_default(&att_cfg, LADRC_VARIANT_LADRC, LADRC_R(0.001), inertia, LADRC_R(0.0));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &att_cfg, NULL));
}

void tearDown(void)
{
}

static void skip_with_asserts(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL: with LADRC_ASSERT on, that is the programmer error it catches");
    }
}

static void test_axis_functions_give_safe_values_for_null(void)
{
    skip_with_asserts();
    ladrc_real_t torque_Nm = UNTOUCHED;
    const ladrc_real_t rate_rad_s = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_axis_step(NULL, LADRC_R(0.1), LADRC_R(0.0), NULL, &torque_Nm));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE,
                           ladrc_axis_step(NULL, LADRC_R(0.1), LADRC_R(0.0), &rate_rad_s, &torque_Nm));
    TEST_ASSERT_TRUE(torque_Nm == UNTOUCHED);
    /* a missing output: the tick does not run (the state stays as it was) */
    const ladrc_axis_t before = axis;
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_axis_step(&axis, LADRC_R(0.1), LADRC_R(0.0), NULL, NULL));
    TEST_ASSERT_EQUAL_INT(0, memcmp(&before, &axis, sizeof axis));
    ladrc_axis_reset(NULL, LADRC_R(0.0));
    ladrc_axis_set_applied(NULL, LADRC_R(0.0));
    ladrc_axis_set_disturbance_rate(NULL, LADRC_R(0.0));
    ladrc_axis_set_known_disturbance(NULL, LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_axis_get_accel(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_axis_get_acting_Nm(NULL) == LADRC_R(0.0));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_axis_get_faults(NULL));
    TEST_ASSERT_EQUAL_UINT32(0u, ladrc_axis_get_consecutive_faults(NULL));
    TEST_ASSERT_NULL(ladrc_axis_get_hp(NULL));
    TEST_ASSERT_NULL(ladrc_axis_get_lp(NULL));
    ladrc_real_t angle = UNTOUCHED, rate = UNTOUCHED, dist = UNTOUCHED;
    ladrc_axis_get_estimate(NULL, &angle, &rate, &dist);
    ladrc_axis_get_estimate(&axis, NULL, &rate, &dist);
    TEST_ASSERT_TRUE(angle == UNTOUCHED && rate == UNTOUCHED && dist == UNTOUCHED);
    ladrc_ref_t ref = {.r = UNTOUCHED, .dr = UNTOUCHED, .ddr = UNTOUCHED};
    ladrc_axis_get_reference(NULL, &ref);
    ladrc_axis_get_reference(&axis, NULL);
    TEST_ASSERT_TRUE(ref.r == UNTOUCHED);
}

static void test_attitude_functions_give_safe_values_for_null(void)
{
    skip_with_asserts();
    const ladrc_real_t three[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    ladrc_real_t torque_Nm[LADRC_AXES] = {UNTOUCHED, UNTOUCHED, UNTOUCHED};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_attitude_step(NULL, three, three, NULL, torque_Nm));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_attitude_step(&att, NULL, three, NULL, torque_Nm));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_attitude_step(&att, three, NULL, NULL, torque_Nm));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_attitude_step(&att, three, three, NULL, NULL));
    TEST_ASSERT_TRUE(torque_Nm[0] == UNTOUCHED);
    /* the rate is optional */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_attitude_step(&att, three, three, NULL, torque_Nm));
    ladrc_attitude_reset(NULL, three);
    ladrc_attitude_reset(&att, NULL);
    ladrc_attitude_set_applied(NULL, three);
    ladrc_attitude_set_applied(&att, NULL);
    ladrc_attitude_config_default(NULL, LADRC_VARIANT_LADRC, LADRC_R(0.001), three, LADRC_R(0.0));
}

static void test_building_block_steps_give_faults_for_null(void)
{
    skip_with_asserts();
    ladrc_real_t out = UNTOUCHED;
    const ladrc_ref_t ref = {.r = LADRC_R(0.0), .dr = LADRC_R(0.0), .ddr = LADRC_R(0.0)};
    const ladrc_real_t phi[LADRC_RLS_MAX_PARAMS] = {LADRC_R(1.0)};
    ladrc_leso_twin_t twin = {.z1 = LADRC_R(0.0), .z2 = LADRC_R(0.0), .z3 = LADRC_R(0.0)};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE,
                           ladrc_leso_step(NULL, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE,
                           ladrc_leso_step_twin(NULL, &twin, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_td_step(NULL, LADRC_R(0.0), NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(NULL, LADRC_R(0.0), NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_update(NULL, phi, LADRC_R(0.0)));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_lp_step(NULL, LADRC_R(0.0), LADRC_R(0.0)));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_lp_step_lead(NULL, &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_hp_step(NULL, LADRC_R(0.0)));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_step(NULL, LADRC_R(0.0), LADRC_R(0.0), NULL, &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_cascaded_step(NULL, &ref, LADRC_R(0.0), NULL, &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_step(NULL, LADRC_R(0.0), phi, NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_step(NULL, phi, &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_gyro_filter_set_rotor_hz(NULL, phi));
    TEST_ASSERT_TRUE(out == UNTOUCHED);
    TEST_ASSERT_EQUAL_INT(0, ladrc_indi_measure(NULL, LADRC_R(0.0), NULL));
}

static void test_building_block_getters_give_zero_for_null(void)
{
    skip_with_asserts();
    TEST_ASSERT_TRUE(ladrc_levant_get_dddr(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_lp_get_estimate(NULL) == LADRC_R(0.0));
    TEST_ASSERT_FALSE(ladrc_is_finite(ladrc_lp_get_sample(NULL))); /* NaN: no sample */
    ladrc_lp_hand_over(NULL, LADRC_R(1.0));                        /* nothing happens */
    ladrc_rls_shift(NULL, 0u, LADRC_R(1.0));
    ladrc_gyro_filter_reset(NULL, NULL); /* nothing happens */
    TEST_ASSERT_TRUE(ladrc_hp_get_estimate(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_hp_get_weight(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_indi_get_disturbance(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_rls_get_p_norm(NULL) == LADRC_R(0.0));
    TEST_ASSERT_NULL(ladrc_rls_get_theta(NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_get_faults(NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_get_faults(NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_get_faults(NULL));
    TEST_ASSERT_NULL(ladrc_hp_get_fit(NULL));
    TEST_ASSERT_TRUE(ladrc_gyro_filter_get_rpm_weight(NULL, 0u, 1u) == LADRC_R(0.0));
}

static void test_status_functions_report_null_as_a_status(void)
{
    /* no assert here: a status is how these report (asserts on or off) */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_axis_init(NULL, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_rls_restart(NULL, 1u, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_rls_set_lambda0(NULL, LADRC_R(1.0)));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_gyro_filter_init(NULL, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_axis_functions_give_safe_values_for_null);
    RUN_TEST(test_attitude_functions_give_safe_values_for_null);
    RUN_TEST(test_building_block_steps_give_faults_for_null);
    RUN_TEST(test_building_block_getters_give_zero_for_null);
    RUN_TEST(test_status_functions_report_null_as_a_status);
    return UNITY_END();
}
