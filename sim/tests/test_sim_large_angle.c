/* SPDX-License-Identifier: BSD-3-Clause */
/* The flight stack's scenarios, every controller tuned as ladrc_sil tunes
 * it: the quaternion frame through the shipped flips and the yaw turn held
 * at 60 deg of pitch (scenarios/large_angle), and a flight from a sloped
 * ground with a land, disarm, arm cycle (scenarios/phases). */
#include "unity.h"
#include "ladrc/margins.h"
#include "run/runner.h"
#include "run/tune.h"
#include "scenario/scenario.h"

#include <stdio.h>

#ifndef SIM_SCENARIO_DIR
#error "SIM_SCENARIO_DIR must name the scenarios folder"
#endif

/* After each manoeuvre (and after take-off) every controller settles within
 * the scenario's band (0.5 deg) and stays there: its steady band, with the
 * measurement noise (0.05 deg, 0.5 deg/s), is a few hundredths of a degree. */
#define STEADY_BAND_MAX_DEG 0.5

void setUp(void)
{
}
void tearDown(void)
{
}

/* Every controller of a shipped scenario (folder/file): tuned, flown, settled. */
static void fly_every_controller(const char *folder, const char *file)
{
    static sim_scenario_t sc;
    static ladrc_margins_workspace_t ws;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s/%s", SIM_SCENARIO_DIR, folder, file);
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(&sc, path, &perr), perr.message);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_LIBRARY_COUNT, sc.n_controllers);
    for (int c = 0; c < sc.n_controllers; ++c) {
        const sim_controller_id_t id = sc.controllers[c];
        if (sim_tune_wanted(&sc, id)) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_tune_controller(&sc, id, &ws, &perr), perr.message);
        }
        static sim_metrics_t m;
        char err[256] = "";
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(&sc, id, NULL, NULL, &m, err, sizeof err), err);
        for (int i = 0; i < 3; ++i) {
            printf("%s %-9s axis %d: max %.2f deg, band %.4f deg, settled after %.3f s\n", file,
                   sim_controller_name(id), i, m.max_error_deg[i], m.band_deg[i], m.settle_s[i]);
            TEST_ASSERT_TRUE_MESSAGE(m.finite && !m.diverged, sim_controller_name(id));
            TEST_ASSERT_TRUE_MESSAGE(m.band_deg[i] <= STEADY_BAND_MAX_DEG, sim_controller_name(id));
            TEST_ASSERT_TRUE_MESSAGE(m.settle_s[i] != SIM_NOT_SETTLED, sim_controller_name(id));
        }
        TEST_ASSERT_TRUE_MESSAGE(m.faults == 0, sim_controller_name(id));
    }
}

static void test_every_controller_flips(void)
{
    fly_every_controller("large_angle", "flips.ini");
}

static void test_every_controller_turns_yaw_at_60_deg_of_pitch(void)
{
    fly_every_controller("large_angle", "yaw_turn_pitched.ini");
}

static void test_every_controller_takes_off_lands_and_takes_off_again(void)
{
    fly_every_controller("phases", "takeoff_land.ini");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_controller_flips);
    RUN_TEST(test_every_controller_turns_yaw_at_60_deg_of_pitch);
    RUN_TEST(test_every_controller_takes_off_lands_and_takes_off_again);
    return UNITY_END();
}
