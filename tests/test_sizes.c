/* SPDX-License-Identifier: BSD-3-Clause */
/* sizes.h: the library reports the sizes this compilation sees, and the
 * real type of the build (what the Python binding relies on). */
#include "unity.h"

#include <stdio.h>
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/mixer.h"
#include "ladrc/sizes.h"
#include "ladrc/td.h"

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_every_reported_size_is_the_sizeof_of_its_type(void)
{
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_real_t), ladrc_sizeof_real());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_axis_t), ladrc_sizeof_axis_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_axis_config_t), ladrc_sizeof_axis_config_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_attitude_t), ladrc_sizeof_attitude_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_attitude_config_t), ladrc_sizeof_attitude_config_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_mixer_t), ladrc_sizeof_mixer_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_mixer_config_t), ladrc_sizeof_mixer_config_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_mixer_output_t), ladrc_sizeof_mixer_output_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_ref_t), ladrc_sizeof_ref_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_gyro_filter_t), ladrc_sizeof_gyro_filter_t());
    TEST_ASSERT_EQUAL_UINT32(sizeof(ladrc_gyro_filter_config_t), ladrc_sizeof_gyro_filter_config_t());
    TEST_ASSERT_EQUAL_UINT32(LADRC_HP_MAX_TONES, ladrc_hp_max_tones());
}

static void test_the_real_size_matches_the_build(void)
{
#ifdef LADRC_REAL_DOUBLE
    TEST_ASSERT_EQUAL_UINT32(8u, ladrc_sizeof_real());
#else
    TEST_ASSERT_EQUAL_UINT32(4u, ladrc_sizeof_real());
#endif
}

static void test_the_abi_set_names_every_variant_and_shaper_of_the_build(void)
{
    char expected[] = "_v0000000_s00_o0";
    const int with[] = {LADRC_WITH_LADRC,    LADRC_WITH_LP_MLADRC, LADRC_WITH_HP_MLADRC, LADRC_WITH_PID,
                        LADRC_WITH_CASCADED, LADRC_WITH_INDI,      LADRC_WITH_RATE_ADRC};
    size_t i;
    for (i = 0u; i < sizeof with / sizeof with[0]; ++i) {
        expected[2u + i] = (char)('0' + with[i]);
    }
    expected[11] = (char)('0' + LADRC_WITH_TD);
    expected[12] = (char)('0' + LADRC_WITH_LEVANT);
    expected[15] = (char)('0' + LADRC_WITH_HP_ONLINE);
    char with_tones[sizeof expected + 16];
    (void)snprintf(with_tones, sizeof with_tones, "%s_t%d", expected, (int)LADRC_HP_MAX_TONES);
    TEST_ASSERT_EQUAL_STRING(with_tones, ladrc_abi_set());
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_reported_size_is_the_sizeof_of_its_type);
    RUN_TEST(test_the_real_size_matches_the_build);
    RUN_TEST(test_the_abi_set_names_every_variant_and_shaper_of_the_build);
    return UNITY_END();
}
