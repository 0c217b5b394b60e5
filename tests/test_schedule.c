/* SPDX-License-Identifier: BSD-3-Clause */
/* The plant-gain schedule: an axis scaled to its plant's gain flies the loop
 * designed for b0, the attitude layer's scale from thrust and voltage, its
 * validation; and the mixer's ESC command on a thrust curve. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "ladrc/mixer.h"
#include "test_rigid_body.h"

#include <math.h>

#define DT_S 1e-3
/* A few float roundings of a 1 s closed loop: the scaled and the nominal
 * loop agree to 1e-4 of the step (their commands differ by one division). */
#define SCALED_LOOP_TOL 1e-4
#ifdef LADRC_REAL_DOUBLE
#define SCALE_TOL 1e-12
#else
#define SCALE_TOL 1e-6
#endif

static const ladrc_real_t inertia[3] = {5.445e-3f, 5.445e-3f, 1.089e-2f};

void setUp(void)
{
}
void tearDown(void)
{
}

/* Roll after 1 s of a 0.1 rad step on the paper's body whose torque is
 * plant_gain times the command, the axis told gain_scale. */
static double fly(ladrc_variant_t variant, double plant_gain, ladrc_real_t gain_scale)
{
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, variant, (ladrc_real_t)DT_S, inertia, 9e-2f);
    ladrc_attitude_t att;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    for (int i = 0; i < 3; ++i) {
        ladrc_axis_set_gain_scale(&att.axis[i], gain_scale);
    }
    test_rigid_body_t b;
    test_rigid_body_init(&b);
    const ladrc_real_t ref[3] = {LADRC_R(0.1), 0, 0};
    const double none[3] = {0, 0, 0};
    for (int k = 0; k < 1000; ++k) {
        ladrc_real_t angle[3], rate[3], torque[3];
        for (int i = 0; i < 3; ++i) {
            angle[i] = (ladrc_real_t)b.angle_rad[i];
            rate[i] = (ladrc_real_t)b.rate_rad_s[i];
        }
        (void)ladrc_attitude_step(&att, ref, angle, rate, torque);
        ladrc_attitude_set_applied(&att, torque);
        const double tau[3] = {plant_gain * torque[0], plant_gain * torque[1], plant_gain * torque[2]};
        test_rigid_body_step(&b, tau, none, DT_S, 4);
    }
    return b.angle_rad[0];
}

static void test_a_scaled_axis_flies_the_nominal_loop(void)
{
    for (int v = 0; v < LADRC_VARIANT_COUNT; ++v) {
        const double nominal = fly((ladrc_variant_t)v, 1.0, LADRC_R(1.0));
        const double scaled = fly((ladrc_variant_t)v, 1.6, LADRC_R(1.6));
        const double unscaled = fly((ladrc_variant_t)v, 1.6, LADRC_R(1.0));
        TEST_ASSERT_TRUE(fabs(scaled - nominal) <= SCALED_LOOP_TOL * 0.1);
        (void)unscaled; /* the gain alone moves the loop (PID, CASCADED: their gains grow 1.6x) */
    }
}

static void test_gain_scale_refuses_what_is_no_gain(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, inertia[0]);
    ladrc_axis_t ax;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&ax, &cfg));
    TEST_ASSERT_TRUE(ax.gain_scale == LADRC_R(1.0));
    ladrc_axis_set_gain_scale(&ax, LADRC_R(2.0));
    const ladrc_real_t bad[4] = {(ladrc_real_t)NAN, LADRC_R(0.0), LADRC_R(0.05), LADRC_R(20.0)};
    for (int k = 0; k < 4; ++k) {
        ladrc_axis_set_gain_scale(&ax, bad[k]);
        TEST_ASSERT_TRUE(ax.gain_scale == LADRC_R(2.0));
    }
    ladrc_axis_reset(&ax, LADRC_R(0.0));
    TEST_ASSERT_TRUE(ax.gain_scale == LADRC_R(2.0)); /* the plant's, kept */
}

static void test_operating_point_scales_every_axis(void)
{
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, inertia, 9e-2f);
    ladrc_attitude_t att;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    ladrc_attitude_set_operating_point(&att, LADRC_R(5.0), LADRC_R(12.0));
    TEST_ASSERT_TRUE(att.axis[0].gain_scale == LADRC_R(1.0)); /* no schedule: 1 */
    /* quadratic rotors, 16 N full thrust, b0 at 8 N; 16.8 V full */
    cfg.gain_thrust_curve = LADRC_R(1.0);
    cfg.gain_full_thrust_N = LADRC_R(16.0);
    cfg.gain_ref_thrust_N = LADRC_R(8.0);
    cfg.gain_ref_voltage_V = LADRC_R(16.8);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    ladrc_attitude_set_operating_point(&att, LADRC_R(12.8), LADRC_R(15.12));
    /* slope 2 c: 1.6 at 80 %, over 1.0 at 50 %; voltage 0.9^2 */
    const double want = 1.6 * 0.81;
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(fabs((double)att.axis[i].gain_scale - want) <= SCALE_TOL * want);
    }
    ladrc_attitude_set_operating_point(&att, (ladrc_real_t)NAN, LADRC_R(15.12)); /* a bad thrust: kept */
    TEST_ASSERT_TRUE(fabs((double)att.axis[0].gain_scale - want) <= SCALE_TOL * want);
    ladrc_attitude_set_operating_point(&att, LADRC_R(8.0), (ladrc_real_t)NAN); /* no voltage: thrust alone */
    TEST_ASSERT_TRUE(fabs((double)att.axis[0].gain_scale - 1.0) <= SCALE_TOL);
    /* the config's checks */
    const ladrc_attitude_config_t good = cfg;
    cfg.gain_thrust_curve = LADRC_R(1.5);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GAIN_SCHEDULE, ladrc_attitude_init(&att, &cfg, NULL));
    cfg = good;
    cfg.gain_full_thrust_N = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GAIN_SCHEDULE, ladrc_attitude_init(&att, &cfg, NULL));
    cfg = good;
    cfg.gain_ref_voltage_V = LADRC_R(-1.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_GAIN_SCHEDULE, ladrc_attitude_init(&att, &cfg, NULL));
    cfg = good;
    cfg.spool_up_s = LADRC_R(11.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_SPOOL_UP_S, ladrc_attitude_init(&att, &cfg, NULL));
}

static void test_mixer_command_inverts_the_thrust_curve(void)
{
    ladrc_mixer_config_t mc = {.kL_N_s2 = 2.98e-5f,
                               .arm_m = 0.165f,
                               .b_Nm_s2 = 2e-6f,
                               .mass_kg = 0.8f,
                               .g_m_s2 = 9.81f,
                               .w2_min_rad2_s2 = 0.0f,
                               .w2_max_rad2_s2 = 1e5f,
                               .tilt_max_rad = 0.7f,
                               .mode = LADRC_MIXER_SATURATE};
    ladrc_mixer_t mx;
    const ladrc_real_t curves[3] = {LADRC_R(0.0), LADRC_R(0.3), LADRC_R(1.0)};
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_init(&mx, &mc));
    TEST_ASSERT_TRUE(mx.thrust_curve == LADRC_R(0.0)); /* linear after init */
    for (int k = 0; k < 3; ++k) {
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_set_thrust_curve(&mx, curves[k]));
        for (int i = 0; i <= 10; ++i) {
            const double f = 0.1 * i; /* the share of full thrust asked */
            const double c = (double)ladrc_mixer_command(&mx, (ladrc_real_t)(f * 1e5));
            const double thrust = (1.0 - (double)curves[k]) * c + (double)curves[k] * c * c;
            TEST_ASSERT_TRUE(fabs(thrust - f) <= SCALE_TOL * 10.0);
        }
    }
    TEST_ASSERT_TRUE(ladrc_mixer_command(&mx, LADRC_R(2e5)) == LADRC_R(1.0));  /* beyond full: full */
    TEST_ASSERT_TRUE(ladrc_mixer_command(&mx, LADRC_R(-5.0)) == LADRC_R(0.0)); /* below 0: 0 */
    TEST_ASSERT_TRUE(ladrc_mixer_command(&mx, (ladrc_real_t)NAN) == LADRC_R(0.0));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_THRUST_CURVE, ladrc_mixer_set_thrust_curve(&mx, LADRC_R(1.2)));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_THRUST_CURVE, ladrc_mixer_set_thrust_curve(&mx, (ladrc_real_t)NAN));
    TEST_ASSERT_TRUE(mx.thrust_curve == LADRC_R(1.0)); /* the last good one kept */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_scaled_axis_flies_the_nominal_loop);
    RUN_TEST(test_gain_scale_refuses_what_is_no_gain);
    RUN_TEST(test_operating_point_scales_every_axis);
    RUN_TEST(test_mixer_command_inverts_the_thrust_curve);
    return UNITY_END();
}
