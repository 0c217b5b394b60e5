/* SPDX-License-Identifier: BSD-3-Clause */
/* INDI in the simulator: it flies every shipped attitude scenario without
 * diverging, and its loop as flown there (tuned where the scenario tunes it),
 * analysed on each scenario's own airframe (its lag, delay and inertias;
 * roll, pitch and yaw), keeps PM >= 45 deg and GM >= 6 dB
 * (shipped_baseline.h). */
#include "shipped_baseline.h"

static ladrc_margins_workspace_t ws;
static sim_scenario_t sc;

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_indi_flies_every_shipped_scenario_with_its_margins(void)
{
    /* 13 files were shipped with this test (12 attitude scenarios) */
    TEST_ASSERT_TRUE(check_every_shipped_scenario(&sc, &ws, SIM_CTRL_INDI) >= 13);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_indi_flies_every_shipped_scenario_with_its_margins);
    return UNITY_END();
}
