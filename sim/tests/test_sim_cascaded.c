/* SPDX-License-Identifier: BSD-3-Clause */
/* The CASCADED baseline on every shipped attitude scenario: it flies each
 * one without diverging with PM >= 45 deg and GM >= 6 dB as flown there
 * (tuned where the scenario tunes it, shipped_baseline.h); and the
 * margins-based tuning (ladrc_margins_tune) finds for the airframes of the
 * scenarios that fly its defaults gains meeting the same targets whose loop,
 * flown closed on the exact sampled plant (ladrc_margins_simulate), decays. */
#include "shipped_baseline.h"

#include <math.h>

/* The airframes the tuning is checked on here: the paper family, steps and the
 * tone sweep (the real airframes are tuned in the shipped check). */
static const char *const SCENARIOS[] = {"paper", "paper_noisy", "paper_known", "paper_noisy_known",
                                        "steps", "tone_sweep"};
#define N_SCENARIOS ((int)(sizeof SCENARIOS / sizeof SCENARIOS[0]))
/* The tuning's targets (margins.h). */
#define PM_MIN_DEG SHIPPED_PM_MIN_DEG
#define GM_MIN_DB SHIPPED_GM_MIN_DB
/* The decay check: 4 s after a pulse (margins.h); a stable loop's last
 * quarter is below the quarter before. */
#define SIMULATE_TICKS 4000L

static sim_scenario_t sc;
static ladrc_margins_workspace_t ws;
static ladrc_margins_tuning_t tuning;

void setUp(void)
{
}
void tearDown(void)
{
}

static void load(const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.ini", SIM_SCENARIO_DIR, name);
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(&sc, path, &err), err.message);
    int listed = 0;
    for (int c = 0; c < sc.n_controllers; ++c)
        listed |= sc.controllers[c] == SIM_CTRL_CASCADED;
    TEST_ASSERT_TRUE_MESSAGE(listed, "a shipped scenario lists CASCADED");
}

static void test_cascaded_flies_every_shipped_scenario_with_its_margins(void)
{
    /* 13 files were shipped with this test (12 attitude scenarios) */
    TEST_ASSERT_TRUE(check_every_shipped_scenario(&sc, &ws, SIM_CTRL_CASCADED) >= 13);
}

static void test_tuned_gains_meet_the_margins_on_every_shipped_airframe(void)
{
    /* The airframes differ by the motor lag, the delay, the rate and the
     * axis inertia: each distinct one is tuned once. */
    double done[N_SCENARIOS * 3][4];
    int n_done = 0;
    for (int s = 0; s < N_SCENARIOS; ++s) {
        load(SCENARIOS[s]);
        ladrc_attitude_config_t acfg;
        sim_setup_attitude(&sc, SIM_CTRL_CASCADED, &acfg);
        for (int i = 0; i < 3; ++i) {
            const double j = sc.inertia_kg_m2[i] * sc.inertia_scale[i];
            const double key[4] = {j, sc.motor_tau_s, (double)sc.delay_ticks, (double)sc.use_rate};
            int seen = 0;
            for (int d = 0; d < n_done; ++d)
                seen |= memcmp(done[d], key, sizeof key) == 0;
            if (seen)
                continue;
            memcpy(done[n_done++], key, sizeof key);
            const ladrc_margins_plant_t plant = {.dt_s = sc.control_dt_s,
                                                 .inertia_kg_m2 = j,
                                                 .inertia_factor = sc.inertia_kg_m2[i] / j,
                                                 .drag_Nm_s = sc.rot_drag_Nm_s,
                                                 .motor_tau_s = sc.motor_tau_s,
                                                 .delay_ticks = sc.delay_ticks};
            ladrc_margins_request_t req;
            ladrc_margins_request_default(&req, &plant);
            const ladrc_margins_controller_t ctl = {
                .attitude = &acfg, .axis_index = i, .axis = NULL, .use_rate = sc.use_rate};
            const ladrc_margins_targets_t targets = {.pm_min_deg = PM_MIN_DEG, .gm_min_db = GM_MIN_DB};
            ladrc_axis_config_t tuned;
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_tune(&ws, &ctl, &req, &targets, &tuned, &tuning));
            /* analysed again and flown, independently of the search */
            const ladrc_margins_controller_t again = {
                .attitude = NULL, .axis_index = 0, .axis = &tuned, .use_rate = sc.use_rate};
            static ladrc_margins_result_t res;
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &again, &req, &res));
            double growth = INFINITY;
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK,
                                  ladrc_margins_simulate(&ws, &again, &plant, SIMULATE_TICKS, &growth));
            printf("%-18s axis %d: J %.4g lag %.3g s delay %d: att_kp %.4g rate kp %.4g ki %.4g kd %.4g -> PM %.1f "
                   "GM %.1f dB, peak |d->e| %.3g, growth %.3g\n",
                   SCENARIOS[s], i, j, sc.motor_tau_s, sc.delay_ticks, (double)tuned.cas_att_kp,
                   (double)tuned.cas_rate_kp, (double)tuned.cas_rate_ki, (double)tuned.cas_rate_kd, res.pm_deg,
                   res.gm_db, res.dist_peak_rad, growth);
            TEST_ASSERT_TRUE(res.stable);
            TEST_ASSERT_TRUE(res.pm_deg >= PM_MIN_DEG);
            TEST_ASSERT_TRUE(res.gm_db >= GM_MIN_DB);
            TEST_ASSERT_TRUE(growth < 1.0);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_cascaded_flies_every_shipped_scenario_with_its_margins);
    RUN_TEST(test_tuned_gains_meet_the_margins_on_every_shipped_airframe);
    return UNITY_END();
}
