/* SPDX-License-Identifier: BSD-3-Clause */
/* The library built with HP-MLADRC and the Levant shaper alone
 * (LADRC_VARIANTS=HP_MLADRC, LADRC_SHAPERS=LEVANT): the variants and the
 * shaper left out are refused by name, and what is built still closes the
 * loop on a double integrator. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/attitude.h"

#include <math.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3             /* paper vehicle, roll axis */
#define STEP_RAD 0.17453292519943295 /* 10 deg */
#define FLIGHT_S 3.0
/* The default HP-MLADRC axis (wc = 15 rad/s, Levant shaping) settles a
 * 10 deg step within 5.8 / wc = 0.4 s plus the shaper's 1 s convergence;
 * after 3 s it sits on the reference to float rounding of the observer
 * (1e-6 rad); 1e-4 rad leaves room for the estimator's start and still
 * fails any loop that does not close (the error would stay 0.17 rad). */
#define SETTLED_ERROR_TOL_RAD 1e-4

#if LADRC_WITH_PID || LADRC_WITH_CASCADED || LADRC_WITH_INDI || LADRC_WITH_LADRC || LADRC_WITH_LP_MLADRC ||            \
    LADRC_WITH_RATE_ADRC || LADRC_WITH_TD || !LADRC_WITH_HP_MLADRC || !LADRC_WITH_LEVANT
#error "this test is built against the HP-MLADRC + Levant library only"
#endif

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_the_variants_left_out_are_refused_by_name(void)
{
    const ladrc_variant_t left_out[] = {LADRC_VARIANT_LADRC,    LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_PID,
                                        LADRC_VARIANT_CASCADED, LADRC_VARIANT_INDI,      LADRC_VARIANT_RATE_ADRC};
    for (unsigned i = 0u; i < sizeof left_out / sizeof left_out[0]; ++i) {
        ladrc_axis_config_t cfg;
        ladrc_axis_t axis;
        ladrc_axis_config_default(&cfg, left_out[i], (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_VARIANT_NOT_BUILT, ladrc_axis_init(&axis, &cfg));
    }
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, (ladrc_variant_t)LADRC_VARIANT_COUNT, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_VARIANT, ladrc_axis_init(&axis, &cfg));
}

static void test_the_shaper_left_out_is_refused_and_none_accepted(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.shaper = LADRC_SHAPER_TD;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_SHAPER_NOT_BUILT, ladrc_axis_init(&axis, &cfg));
    cfg.shaper = LADRC_SHAPER_NONE;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    cfg.shaper = (ladrc_shaper_t)7;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_SHAPER, ladrc_axis_init(&axis, &cfg));
}

static void test_the_hp_axis_built_alone_settles_a_step(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    TEST_ASSERT_NOT_NULL(ladrc_axis_get_hp(&axis));
    TEST_ASSERT_NULL(ladrc_axis_get_lp(&axis));
    /* Double integrator J theta'' = u, exact over each held step. */
    double theta = 0.0, omega = 0.0;
    const int ticks = (int)(FLIGHT_S / DT_S + 0.5);
    for (int k = 0; k < ticks; ++k) {
        const double u = (double)axis_command(&axis, (ladrc_real_t)STEP_RAD, (ladrc_real_t)theta);
        const double a = u / J_KG_M2;
        theta += omega * DT_S + 0.5 * a * DT_S * DT_S;
        omega += a * DT_S;
    }
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
    TEST_ASSERT_FLOAT_WITHIN(SETTLED_ERROR_TOL_RAD, STEP_RAD, theta);
}

static void test_the_attitude_layer_links_and_inits(void)
{
    const ladrc_real_t inertia[LADRC_AXES] = {(ladrc_real_t)J_KG_M2, (ladrc_real_t)J_KG_M2,
                                              (ladrc_real_t)(2.0 * J_KG_M2)};
    ladrc_attitude_config_t cfg;
    ladrc_attitude_t att;
    int bad_axis = 0;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, inertia, LADRC_R(0.0));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, &bad_axis));
    TEST_ASSERT_EQUAL_INT(-1, bad_axis);
    cfg.axis[LADRC_PITCH].variant = LADRC_VARIANT_PID;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_VARIANT_NOT_BUILT, ladrc_attitude_init(&att, &cfg, &bad_axis));
    TEST_ASSERT_EQUAL_INT(LADRC_PITCH, bad_axis);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_the_variants_left_out_are_refused_by_name);
    RUN_TEST(test_the_shaper_left_out_is_refused_and_none_accepted);
    RUN_TEST(test_the_hp_axis_built_alone_settles_a_step);
    RUN_TEST(test_the_attitude_layer_links_and_inits);
    return UNITY_END();
}
