/* SPDX-License-Identifier: BSD-3-Clause */
/* INDI in the simulator: it flies every shipped attitude scenario without
 * diverging, and its loop as configured there, analysed on each scenario's
 * own airframe (its lag, delay and inertias; roll, pitch and yaw), keeps
 * PM >= 45 deg and GM >= 6 dB. */
#include "unity.h"
#include "ladrc/margins.h"
#include "runner.h"
#include "scenario.h"
#include "setup.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The margin targets of the tuning (docs/margins.md). */
#define PM_MIN_DEG 45.0
#define GM_MIN_DB 6.0

static ladrc_margins_workspace_t ws;
static sim_scenario_t sc;

void setUp(void) {}
void tearDown(void) {}

static void check_scenario(const char *path)
{
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(&sc, path, &perr), perr.message);
    if (sc.kind != SIM_KIND_ATTITUDE) {
        return;
    }
    /* flies without diverging */
    sim_metrics_t m;
    char err[256] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(&sc, SIM_CTRL_INDI, NULL, NULL, &m, err, sizeof err), err);
    TEST_ASSERT_TRUE_MESSAGE(m.finite && !m.diverged, path);
    /* margins of each axis as configured, on the scenario's airframe */
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(&sc, SIM_CTRL_INDI, &acfg);
    for (int i = 0; i < 3; ++i) {
        const ladrc_margins_plant_t plant = {sc.control_dt_s,   sc.inertia_kg_m2[i] * sc.inertia_scale[i],
                                             1.0 / sc.inertia_scale[i], sc.rot_drag_Nm_s,
                                             sc.motor_tau_s,    sc.delay_ticks};
        ladrc_margins_request_t req;
        ladrc_margins_request_default(&req, &plant);
        const ladrc_margins_controller_t ctl = {&acfg, i, NULL, sc.use_rate};
        ladrc_margins_result_t res;
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(&ws, &ctl, &req, &res));
        printf("%s axis %d: max |error| %.3f deg; PM %.1f deg, GM %.1f dB, stable %d\n", sc.name, i,
               m.max_error_deg[i], res.pm_deg, res.gm_db, res.stable);
        TEST_ASSERT_TRUE_MESSAGE(res.stable, path);
        TEST_ASSERT_TRUE_MESSAGE(res.pm_deg >= PM_MIN_DEG, path);
        TEST_ASSERT_TRUE_MESSAGE(res.gm_db >= GM_MIN_DB, path);
    }
}

static void test_indi_flies_every_shipped_scenario_with_its_margins(void)
{
    DIR *dir = opendir(SIM_SCENARIO_DIR);
    TEST_ASSERT_NOT_NULL(dir);
    int n = 0;
    for (struct dirent *e = readdir(dir); e != NULL; e = readdir(dir)) {
        const size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".ini") != 0) {
            continue;
        }
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", SIM_SCENARIO_DIR, e->d_name);
        check_scenario(path);
        ++n;
    }
    closedir(dir);
    TEST_ASSERT_TRUE(n >= 7); /* the shipped scenarios were found */
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_indi_flies_every_shipped_scenario_with_its_margins);
    return UNITY_END();
}
