/* SPDX-License-Identifier: BSD-3-Clause */
/* Shared types: status texts and numeric helpers. */
#include "unity.h"
#include "ladrc/types.h"

#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

/* The enum's names, in its order: what each text must start with. */
static const char *const status_names[LADRC_STATUS_COUNT] = {
    "LADRC_OK",
    "LADRC_ERR_NULL",
    "LADRC_ERR_DT_S",
    "LADRC_ERR_WO_RAD_S",
    "LADRC_ERR_WC_RAD_S",
    "LADRC_ERR_B0",
    "LADRC_ERR_LESO_METHOD",
    "LADRC_ERR_LESO_EULER_UNSTABLE",
    "LADRC_ERR_SHAPER",
    "LADRC_ERR_TD_ACCEL_RAD_S2",
    "LADRC_ERR_TD_H0_S",
    "LADRC_ERR_VARIANT",
    "LADRC_ERR_U_LIMITS",
    "LADRC_ERR_PID_KP",
    "LADRC_ERR_PID_KI",
    "LADRC_ERR_PID_KD",
    "LADRC_ERR_PID_D_TAU_S",
    "LADRC_ERR_PID_I_LIMIT_NM",
    "LADRC_ERR_SETTLING_TIME_S",
    "LADRC_ERR_PLANT_ORDER",
    "LADRC_ERR_INERTIA_KG_M2",
    "LADRC_ERR_WO_RATIO",
    "LADRC_ERR_RLS_N_PARAMS",
    "LADRC_ERR_RLS_LAMBDA0",
    "LADRC_ERR_RLS_P_BOUND",
    "LADRC_ERR_RLS_P_INITIAL",
    "LADRC_ERR_MIXER_KL_N_S2",
    "LADRC_ERR_MIXER_ARM_M",
    "LADRC_ERR_MIXER_B_NM_S2",
    "LADRC_ERR_MIXER_MASS_KG",
    "LADRC_ERR_MIXER_G_M_S2",
    "LADRC_ERR_MIXER_MODE",
    "LADRC_ERR_MIXER_W2_MIN",
    "LADRC_ERR_MIXER_W2_MAX",
    "LADRC_ERR_MIXER_TILT_MAX_RAD",
    "LADRC_ERR_EST_LAMBDA0",
    "LADRC_ERR_EST_K0",
    "LADRC_ERR_HP_FREQ_MODE",
    "LADRC_ERR_HP_FREQ_RAD_S",
    "LADRC_ERR_HP_FREQ_RANGE",
    "LADRC_ERR_HP_N_TONES",
    "LADRC_ERR_HP_SAMPLE_LAG",
    "LADRC_ERR_DRAG_NMS",
    "LADRC_ERR_COUPLING_FEED",
    "LADRC_ERR_LEVANT_METHOD",
    "LADRC_ERR_LEVANT_GAINS",
    "LADRC_ERR_LEVANT_LIPSCHITZ",
    "LADRC_ERR_LEVANT_L1",
    "LADRC_ERR_LEVANT_L2",
    "LADRC_ERR_LEVANT_L3",
    "LADRC_ERR_LEVANT_L4",
    "LADRC_ERR_LEVANT_RANGE",
    "LADRC_ERR_HP_FIT_DECIMATION",
    "LADRC_ERR_HP_FREQ_LAMBDA0",
    "LADRC_ERR_HP_FREQ_FILTER",
    "LADRC_ERR_INPUT_LIMITS",
    "LADRC_ERR_INERTIA_TRIANGLE",
    "LADRC_ERR_MOTOR_TAU_S",
    "LADRC_ERR_DELAY_TICKS",
    "LADRC_ERR_WRAP_ANGLE",
    "LADRC_ERR_INDI_ATT_KP",
    "LADRC_ERR_INDI_RATE_KP",
    "LADRC_ERR_INDI_FILTER",
    "LADRC_ERR_CAS_ATT_KP",
    "LADRC_ERR_CAS_RATE_MAX",
    "LADRC_ERR_CAS_RATE_KP",
    "LADRC_ERR_CAS_RATE_KI",
    "LADRC_ERR_CAS_RATE_KD",
    "LADRC_ERR_CAS_D_TAU_S",
    "LADRC_ERR_CAS_RATE_TAU_S",
    "LADRC_ERR_CAS_I_LIMIT_NM",
    "LADRC_ERR_VARIANT_NOT_BUILT",
    "LADRC_ERR_SHAPER_NOT_BUILT",
    "LADRC_ERR_FEATURE_NOT_BUILT",
    "LADRC_ERR_RADRC_KP",
    "LADRC_ERR_RADRC_ATT_KP",
    "LADRC_ERR_RADRC_RATE_MAX",
    "LADRC_ERR_RADRC_ACRO",
    "LADRC_ERR_HP_SAMPLE",
    "LADRC_ERR_GYRO_CHANNELS",
    "LADRC_ERR_GYRO_LPF_ORDER",
    "LADRC_ERR_GYRO_LPF_CUTOFF_HZ",
    "LADRC_ERR_GYRO_N_NOTCHES",
    "LADRC_ERR_GYRO_NOTCH_HZ",
    "LADRC_ERR_GYRO_NOTCH_Q",
    "LADRC_ERR_GYRO_RPM_ROTORS",
    "LADRC_ERR_GYRO_RPM_HARMONICS",
    "LADRC_ERR_GYRO_RPM_MIN_HZ",
    "LADRC_ERR_GYRO_RPM_FADE_HZ",
    "LADRC_ERR_GYRO_RPM_Q",
    "LADRC_ERR_ATTITUDE_FRAME",
    "LADRC_ERR_YAW_WEIGHT",
    "LADRC_ERR_CAS_I_RELAX",
    "LADRC_ERR_CAS_RATE_FF",
    "LADRC_ERR_CAS_SETPOINT_FF",
    "LADRC_ERR_INDI_ADAPT",
    "LADRC_ERR_INDI_ADAPT_MU",
    "LADRC_ERR_INDI_ADAPT_EXCITATION",
    "LADRC_ERR_INDI_ADAPT_MIN",
    "LADRC_ERR_INDI_ADAPT_MAX",
    "LADRC_ERR_SPOOL_UP_S",
    "LADRC_ERR_MIXER_THRUST_CURVE",
    "LADRC_ERR_GAIN_SCHEDULE",
};

/* 1 if text is name alone (names-only build) or name ": " and an explanation. */
static int text_names(const char *text, const char *name)
{
    const size_t n = strlen(name);
    if (strncmp(text, name, n) != 0) {
        return 0;
    }
#ifdef LADRC_STATUS_NAMES_ONLY
    return text[n] == '\0';
#else
    return text[n] == ':' && text[n + 1] == ' ' && text[n + 2] != '\0';
#endif
}

static void test_every_status_has_a_text_that_starts_with_its_enum_name(void)
{
    /* given: every status code; when: its text; then: the name, then the explanation
     * unless the build keeps names only */
    for (int s = 0; s < LADRC_STATUS_COUNT; ++s) {
        const char *text = ladrc_status_str((ladrc_status_t)s);
        TEST_ASSERT_NOT_NULL(text);
        TEST_ASSERT_TRUE_MESSAGE(text_names(text, status_names[s]), status_names[s]);
    }
}

static void test_every_status_text_is_distinct(void)
{
    /* given: every pair of status codes; then: different texts */
    for (int a = 0; a < LADRC_STATUS_COUNT; ++a) {
        for (int b = a + 1; b < LADRC_STATUS_COUNT; ++b) {
            TEST_ASSERT_TRUE_MESSAGE(
                strcmp(ladrc_status_str((ladrc_status_t)a), ladrc_status_str((ladrc_status_t)b)) != 0, status_names[a]);
        }
    }
}

static void test_a_value_outside_the_enum_has_the_unknown_text(void)
{
    /* when: the count itself and a negative value; then: the unknown text */
    TEST_ASSERT_TRUE(text_names(ladrc_status_str(LADRC_STATUS_COUNT), "LADRC_ERR_UNKNOWN"));
    TEST_ASSERT_TRUE(text_names(ladrc_status_str((ladrc_status_t)-1), "LADRC_ERR_UNKNOWN"));
}

static void test_finite_check_and_clamp_behave_at_the_edges(void)
{
    TEST_ASSERT_FALSE(ladrc_is_finite((ladrc_real_t)NAN));
    TEST_ASSERT_FALSE(ladrc_is_finite((ladrc_real_t)-INFINITY));
    TEST_ASSERT_TRUE(ladrc_is_finite(0.0f));
    TEST_ASSERT_FALSE(ladrc_is_positive(0.0f));
    TEST_ASSERT_FALSE(ladrc_is_positive((ladrc_real_t)INFINITY));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 1.0f, ladrc_clamp(2.0f, -1.0f, 1.0f));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, -1.0f, ladrc_clamp(-2.0f, -1.0f, 1.0f));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.5f, ladrc_clamp(0.5f, (ladrc_real_t)-INFINITY, (ladrc_real_t)INFINITY));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, -1.0f, ladrc_sign(-3.0f));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_sign(0.0f));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_status_has_a_text_that_starts_with_its_enum_name);
    RUN_TEST(test_every_status_text_is_distinct);
    RUN_TEST(test_a_value_outside_the_enum_has_the_unknown_text);
    RUN_TEST(test_finite_check_and_clamp_behave_at_the_edges);
    return UNITY_END();
}
