/* SPDX-License-Identifier: BSD-3-Clause */
/* Non-finite inputs through the public API, checked without relying on IEEE
 * comparisons: the values are made from bit patterns and the results are
 * compared by their bits. The same program runs in the normal suites and in
 * the fast-math stage of tools/run_tests.sh, where the library and this file
 * are compiled with -ffast-math: the guards must hold there too. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/mixer.h"
#include "test_hostile.h"

#include <stdint.h>
#include <string.h>

#define DT_S LADRC_R(0.001)
#define N_TICKS 400
#define BAD_AT 200

void setUp(void)
{
}
void tearDown(void)
{
}

static int same_bits(ladrc_real_t a, ladrc_real_t b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* A deterministic, non-trivial input sequence: reference steps and a
 * lagging angle. */
static ladrc_real_t ref_at(int k)
{
    return (k < 50) ? LADRC_R(0.0) : LADRC_R(0.17);
}
static ladrc_real_t angle_at(int k)
{
    return LADRC_R(0.17) * (ladrc_real_t)k / (ladrc_real_t)(k + 150);
}
static ladrc_real_t rate_at(int k)
{
    return LADRC_R(25.5) / (ladrc_real_t)((k + 150) * (k + 150)) * LADRC_R(1000.0);
}

static void check_axis_variant(ladrc_variant_t variant)
{
    static const int kinds[4][2] = {{0, -1}, {-1, 0}, {1, -1}, {-1, 2}}; /* bad ref / bad angle */
    ladrc_axis_config_t cfg;
    ladrc_axis_t clean;
    ladrc_axis_t hit;
    ladrc_real_t held;
    int k;
    int b;

    ladrc_axis_config_default(&cfg, variant, DT_S, LADRC_R(5.445e-3));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&clean, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&hit, &cfg));
    for (k = 0; k < N_TICKS; ++k) {
        const ladrc_real_t u_clean = axis_command_with_rate(&clean, ref_at(k), angle_at(k), rate_at(k));
        ladrc_real_t u_hit;
        if (k == BAD_AT - 1) {
            /* the last good tick, then four bad ones in between */
            u_hit = axis_command_with_rate(&hit, ref_at(k), angle_at(k), rate_at(k));
            TEST_ASSERT_TRUE(same_bits(u_clean, u_hit));
            for (b = 0; b < 4; ++b) {
                const ladrc_real_t r = kinds[b][0] >= 0 ? test_special_value(kinds[b][0]) : ref_at(k + 1);
                const ladrc_real_t y = kinds[b][1] >= 0 ? test_special_value(kinds[b][1]) : angle_at(k + 1);
                held = axis_command_with_rate(&hit, r, y, rate_at(k + 1));
                TEST_ASSERT_TRUE_MESSAGE(ladrc_axis_get_faults(&hit) & LADRC_FAULT_INPUT, "no input fault");
                TEST_ASSERT_TRUE_MESSAGE(test_is_finite(held), "command not finite");
                TEST_ASSERT_TRUE_MESSAGE(same_bits(held, u_hit), "command not held");
                TEST_ASSERT_EQUAL_UINT32((uint32_t)(b + 1), ladrc_axis_get_consecutive_faults(&hit));
            }
            /* a non-finite applied torque is ignored with its own flag */
            ladrc_axis_set_applied(&hit, test_special_value(0));
            TEST_ASSERT_TRUE(ladrc_axis_get_faults(&hit) & LADRC_FAULT_APPLIED);
            ladrc_axis_set_applied(&clean, u_clean);
            ladrc_axis_set_applied(&hit, u_hit);
            continue;
        }
        u_hit = axis_command_with_rate(&hit, ref_at(k), angle_at(k), rate_at(k));
        /* then: every tick equals the run without the bad ticks, bit for bit */
        TEST_ASSERT_TRUE_MESSAGE(test_is_finite(u_hit), "command not finite");
        TEST_ASSERT_TRUE_MESSAGE(same_bits(u_clean, u_hit), "run differs from the clean run");
        ladrc_axis_set_applied(&clean, u_clean);
        ladrc_axis_set_applied(&hit, u_hit);
        if (k == BAD_AT) {
            TEST_ASSERT_EQUAL_UINT32(0u, ladrc_axis_get_consecutive_faults(&hit));
        }
    }
}

static void test_axis_ladrc_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_LADRC);
}
static void test_axis_lp_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_LP_MLADRC);
}
static void test_axis_hp_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_HP_MLADRC);
}
static void test_axis_pid_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_PID);
}
static void test_axis_indi_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_INDI);
}
static void test_axis_cascaded_holds_on_non_finite_input(void)
{
    check_axis_variant(LADRC_VARIANT_CASCADED);
}

static void test_attitude_and_mixer_hold_on_non_finite_input(void)
{
    static const ladrc_real_t inertia[3] = {LADRC_R(5.445e-3), LADRC_R(5.445e-3), LADRC_R(1.089e-2)};
    static const ladrc_mixer_config_t mix = {.kL_N_s2 = LADRC_R(2.98e-5),
                                             .arm_m = LADRC_R(0.165),
                                             .b_Nm_s2 = LADRC_R(2e-6),
                                             .mass_kg = LADRC_R(0.8),
                                             .g_m_s2 = LADRC_R(9.81),
                                             .w2_min_rad2_s2 = LADRC_R(1e4),
                                             .w2_max_rad2_s2 = LADRC_R(2e5),
                                             .tilt_max_rad = LADRC_R(0.7),
                                             .mode = LADRC_MIXER_SATURATE};
    ladrc_attitude_config_t cfg;
    ladrc_attitude_t att;
    ladrc_mixer_t mixer;
    ladrc_mixer_output_t out;
    ladrc_mixer_output_t before;
    ladrc_real_t torque[3];
    ladrc_real_t held[3];
    int k;
    int i;

    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, DT_S, inertia, LADRC_R(0.09));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_init(&mixer, &mix));
    for (k = 0; k < N_TICKS; ++k) {
        const ladrc_real_t ref[3] = {ref_at(k), -ref_at(k), LADRC_R(0.5) * ref_at(k)};
        const ladrc_real_t angle[3] = {angle_at(k), -angle_at(k), LADRC_R(0.5) * angle_at(k)};
        const ladrc_fault_t f = ladrc_attitude_step(&att, ref, angle, NULL, torque);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, f);
        TEST_ASSERT_EQUAL_HEX8(
            LADRC_FAULT_NONE,
            ladrc_mixer_step(&mixer, ladrc_mixer_thrust_from_tilt(&mixer, angle[0], angle[1]), torque, &out));
        ladrc_attitude_set_applied(&att, out.torque_Nm);
    }
    /* a NaN angle on one axis: input fault, torques held */
    {
        const ladrc_real_t ref[3] = {LADRC_R(0.1), LADRC_R(0.1), LADRC_R(0.1)};
        const ladrc_real_t angle[3] = {LADRC_R(0.1), test_special_value(0), LADRC_R(0.1)};
        const ladrc_fault_t f = ladrc_attitude_step(&att, ref, angle, NULL, held);
        TEST_ASSERT_TRUE(f & LADRC_FAULT_INPUT);
        TEST_ASSERT_TRUE(same_bits(held[1], torque[1]));
        for (i = 0; i < 3; ++i) {
            TEST_ASSERT_TRUE(test_is_finite(held[i]));
        }
        /* thrust of an unknown attitude: the weight, finite */
        TEST_ASSERT_TRUE(test_is_finite(ladrc_mixer_thrust_from_tilt(&mixer, LADRC_R(0.1), test_special_value(0))));
    }
    /* the mixer: a non-finite torque or thrust request is refused, output held */
    memcpy(&before, &out, sizeof out);
    for (i = 0; i < 4; ++i) {
        ladrc_real_t t[3] = {torque[0], torque[1], torque[2]};
        ladrc_real_t thrust = LADRC_R(8.0);
        if (i < 3) {
            t[i] = test_special_value(i);
        } else {
            thrust = test_special_value(0);
        }
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_mixer_step(&mixer, thrust, t, &out));
        TEST_ASSERT_EQUAL_MEMORY(before.w2_rad2_s2, out.w2_rad2_s2, sizeof out.w2_rad2_s2);
        TEST_ASSERT_EQUAL_MEMORY(before.torque_Nm, out.torque_Nm, sizeof out.torque_Nm);
    }
}

/* The gyro filter: bad samples and rotor speeds of every special kind put in
 * between the ticks of a clean run change nothing of it, bit for bit. */
static void test_gyro_filter_holds_on_non_finite_input(void)
{
    static ladrc_gyro_filter_t clean;
    static ladrc_gyro_filter_t hit;
    ladrc_gyro_filter_config_t cfg;
    int k;
    unsigned b;
    ladrc_gyro_filter_config_default(&cfg, DT_S, 3u);
    cfg.lpf_order = 2u;
    cfg.n_notches = 1u;
    cfg.notch_hz[0] = LADRC_R(170.0);
    cfg.rpm_rotors = 4u;
    cfg.rpm_min_hz = LADRC_R(60.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_gyro_filter_init(&clean, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_gyro_filter_init(&hit, &cfg));
    for (k = 0; k < N_TICKS; ++k) {
        const ladrc_real_t rotors[4] = {LADRC_R(80.0) + rate_at(k), LADRC_R(95.0), LADRC_R(110.0),
                                        LADRC_R(125.0) - rate_at(k)};
        const ladrc_real_t in[3] = {rate_at(k), angle_at(k), ref_at(k) - rate_at(k)};
        ladrc_real_t out_clean[3], out_hit[3];
        if (k == BAD_AT) {
            for (b = 0; b < TEST_SPECIAL_VALUES; ++b) {
                const ladrc_real_t bad_in[3] = {test_special_value(b),
                                                test_special_value((b + 1u) % TEST_SPECIAL_VALUES),
                                                test_special_value((b + 2u) % TEST_SPECIAL_VALUES)};
                ladrc_real_t bad_rotors[4];
                ladrc_real_t held[3];
                ladrc_gyro_filter_section_t sections[LADRC_GYRO_FILTER_MAX_STAGES];
                memcpy(bad_rotors, rotors, sizeof bad_rotors);
                bad_rotors[b % 4u] = test_special_value(b);
                memcpy(sections, hit.section, sizeof sections);
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_gyro_filter_set_rotor_hz(&hit, bad_rotors));
                TEST_ASSERT_EQUAL_MEMORY(&sections[1u + 3u * (b % 4u)], &hit.section[1u + 3u * (b % 4u)],
                                         3u * sizeof sections[0]);
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_gyro_filter_step(&hit, bad_in, held));
                for (unsigned i = 0; i < 3u; ++i) {
                    TEST_ASSERT_TRUE_MESSAGE(test_is_finite(held[i]), "output not finite");
                    TEST_ASSERT_TRUE_MESSAGE(same_bits(held[i], hit.out[i]), "output not held");
                }
            }
        }
        (void)ladrc_gyro_filter_set_rotor_hz(&clean, rotors);
        (void)ladrc_gyro_filter_set_rotor_hz(&hit, rotors);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&clean, in, out_clean));
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_gyro_filter_step(&hit, in, out_hit));
        for (unsigned i = 0; i < 3u; ++i) {
            TEST_ASSERT_TRUE_MESSAGE(same_bits(out_clean[i], out_hit[i]), "run differs from the clean run");
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_axis_ladrc_holds_on_non_finite_input);
    RUN_TEST(test_axis_lp_holds_on_non_finite_input);
    RUN_TEST(test_axis_hp_holds_on_non_finite_input);
    RUN_TEST(test_axis_pid_holds_on_non_finite_input);
    RUN_TEST(test_axis_indi_holds_on_non_finite_input);
    RUN_TEST(test_axis_cascaded_holds_on_non_finite_input);
    RUN_TEST(test_attitude_and_mixer_hold_on_non_finite_input);
    RUN_TEST(test_gyro_filter_holds_on_non_finite_input);
    return UNITY_END();
}
