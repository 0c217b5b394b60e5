/* SPDX-License-Identifier: BSD-3-Clause */
/* tune = margins on airframes people fly (scenarios/airframes/): a 30 g
 * brushed micro at 500 Hz, a 5 kg quad at 500 Hz behind 60/90 ms motors in
 * gusts, a 9-inch long-range craft, a drag-free airframe whose inertia the
 * controllers over-estimate by 30 %. Every controller of the LADRC family
 * gets gains that fly (never untunable); no controller's gains diverge in
 * the run; and the gains flown are never beaten in the check flight by a
 * candidate of equal standing (docs/margins.md, "Candidates"). */
#include "unity.h"
#include "ladrc/margins.h"
#include "run/runner.h"
#include "run/tune.h"
#include "scenario/scenario.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static ladrc_margins_workspace_t ws;
static sim_scenario_t sc;

void setUp(void)
{
}
void tearDown(void)
{
}

static int in_family(sim_controller_id_t id)
{
    return id == SIM_CTRL_HP_MLADRC || id == SIM_CTRL_LP_MLADRC || id == SIM_CTRL_LADRC || id == SIM_CTRL_RATE_ADRC;
}

/* Index of the candidate flown (tune.h's order), -1 if none. */
static int flown_candidate(const sim_tuning_t *t)
{
    static const sim_tuned_by_t BY[SIM_N_CANDIDATES] = {SIM_TUNED_MARGINS, SIM_TUNED_DEFAULTS, SIM_TUNED_SCENARIO};
    for (int c = 0; c < SIM_N_CANDIDATES; ++c) {
        if (BY[c] == t->by)
            return c;
    }
    return -1;
}

static void tune_and_fly(const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/airframes/%s.ini", SIM_SCENARIO_DIR, name);
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(&sc, path, &err), err.message);
    for (int c = 0; c < sc.n_controllers; ++c) {
        const sim_controller_id_t id = sc.controllers[c];
        const int rc = sim_tune_controller(&sc, id, &ws, &err);
        const sim_tuning_t *t = &sc.tuning[id];
        char msg[900];
        snprintf(msg, sizeof msg, "%s %s: rc %d (%s) %s", name, sim_controller_name(id), rc, sim_tuned_by_name(t->by),
                 rc != SIM_TUNE_OK ? err.message : "");
        printf("%s\n", msg);
        if (in_family(id))
            TEST_ASSERT_TRUE_MESSAGE(rc != SIM_TUNE_UNTUNABLE, msg);
        if (rc == SIM_TUNE_UNTUNABLE)
            continue;
        const int win = flown_candidate(t);
        TEST_ASSERT_TRUE_MESSAGE(win >= 0 && t->check_cost_deg[win] < INFINITY, msg);
        for (int k = 0; k < SIM_N_CANDIDATES; ++k) {
            if (k == win || !(t->check_cost_deg[k] < INFINITY))
                continue;
            TEST_ASSERT_TRUE_MESSAGE(t->candidate_met[k] <= t->candidate_met[win], msg);
            if (t->candidate_met[k] == t->candidate_met[win])
                TEST_ASSERT_TRUE_MESSAGE(t->check_cost_deg[win] <= t->check_cost_deg[k], msg);
        }
        sim_metrics_t m;
        char run_err[160] = "";
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(&sc, id, NULL, NULL, &m, run_err, sizeof run_err), run_err);
        TEST_ASSERT_FALSE_MESSAGE(m.diverged, msg);
    }
}

static void test_a_brushed_micro_at_500_hz(void)
{
    tune_and_fly("micro_brushed");
}

static void test_a_5_kg_quad_behind_slow_motors_in_gusts(void)
{
    tune_and_fly("heavy_5kg");
}

static void test_a_9_inch_long_range_craft(void)
{
    tune_and_fly("longrange_9in");
}

static void test_a_drag_free_airframe_with_its_inertia_over_estimated(void)
{
    tune_and_fly("mismatch_nodrag");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_brushed_micro_at_500_hz);
    RUN_TEST(test_a_5_kg_quad_behind_slow_motors_in_gusts);
    RUN_TEST(test_a_9_inch_long_range_craft);
    RUN_TEST(test_a_drag_free_airframe_with_its_inertia_over_estimated);
    return UNITY_END();
}
