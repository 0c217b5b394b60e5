/* Shared types: status texts and numeric helpers. */
#include "unity.h"
#include "ladrc/types.h"

void setUp(void) {}
void tearDown(void) {}

static void test_every_status_has_a_text_that_names_it(void)
{
    for (int s = 0; s < LADRC_STATUS_COUNT; ++s) {
        const char *text = ladrc_status_str((ladrc_status_t)s);
        TEST_ASSERT_NOT_NULL(text);
        TEST_ASSERT_TRUE(text[0] == 'L' && text[5] == '_');
    }
    TEST_ASSERT_EQUAL_STRING("LADRC_OK", ladrc_status_str(LADRC_OK));
    TEST_ASSERT_EQUAL_STRING("LADRC_ERR_UNKNOWN: not a ladrc_status_t",
                             ladrc_status_str(LADRC_STATUS_COUNT));
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
    RUN_TEST(test_every_status_has_a_text_that_names_it);
    RUN_TEST(test_finite_check_and_clamp_behave_at_the_edges);
    return UNITY_END();
}
