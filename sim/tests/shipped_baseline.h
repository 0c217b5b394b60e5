/* SPDX-License-Identifier: BSD-3-Clause */
/* A baseline (CASCADED or INDI) on every shipped attitude scenario, for
 * test_sim_cascaded.c and test_sim_indi.c: where the scenario says
 * tune = margins for it, tuned first as ladrc_sil tunes it; then flown
 * (finite, not diverged); then its loop as flown (sim_setup_attitude: the
 * tuned gains where tuned, else the defaults and the file's keys) analysed
 * on each axis's airframe as the controller models it (sim_tune_plant):
 * stable with PM >= 45 deg and GM >= 6 dB (the tuning's default targets). */
#ifndef LADRC_SIM_TESTS_SHIPPED_BASELINE_H
#define LADRC_SIM_TESTS_SHIPPED_BASELINE_H

#include "unity.h"
#include "ladrc/margins.h"
#include "run/runner.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"
#include "run/tune.h"

#include <dirent.h>
#include <stdio.h>
#include <string.h>

#ifndef SIM_SCENARIO_DIR
#error "SIM_SCENARIO_DIR must name the scenarios folder"
#endif

/* The margin targets of the tuning (docs/margins.md). */
#define SHIPPED_PM_MIN_DEG SIM_TUNE_PM_DEG_DEFAULT
#define SHIPPED_GM_MIN_DB SIM_TUNE_GM_DB_DEFAULT

static void check_shipped_scenario(sim_scenario_t *sc, ladrc_margins_workspace_t *ws, sim_controller_id_t id,
                                   const char *path)
{
    sim_parse_error_t perr;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(sc, path, &perr), perr.message);
    if (sc->kind != SIM_KIND_ATTITUDE) {
        return;
    }
    if (sim_tune_wanted(sc, id)) {
        const int rc = sim_tune_controller(sc, id, ws, &perr);
        if (rc != 0)
            printf("%s:%d:%d: %s\n", perr.path, perr.line, perr.column, perr.message);
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, path);
    }
    static sim_metrics_t m;
    char err[256] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(sc, id, NULL, NULL, &m, err, sizeof err), err);
    TEST_ASSERT_TRUE_MESSAGE(m.finite && !m.diverged, path);
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(sc, id, &acfg);
    for (int i = 0; i < 3; ++i) {
        ladrc_margins_plant_t plant;
        sim_tune_plant(sc, i, &plant);
        ladrc_margins_request_t req;
        ladrc_margins_request_default(&req, &plant);
        const ladrc_margins_controller_t ctl = {
            .attitude = &acfg, .axis_index = i, .axis = NULL, .use_rate = sc->use_rate};
        static ladrc_margins_result_t res;
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_analyse(ws, &ctl, &req, &res));
        printf("%-18s %s %s axis %d: RMS error %.4f deg, band %.4f deg; PM %.1f deg, GM %.1f dB, stable %d\n", sc->name,
               sim_controller_name(id), sc->tuning[id].tuned ? "tuned" : "default", i, sim_stat_rms(&m.error_deg[i]),
               m.band_deg[i], res.pm_deg, res.gm_db, res.stable);
        TEST_ASSERT_TRUE_MESSAGE(res.stable, path);
        TEST_ASSERT_TRUE_MESSAGE(res.pm_deg >= SHIPPED_PM_MIN_DEG, path);
        TEST_ASSERT_TRUE_MESSAGE(res.gm_db >= SHIPPED_GM_MIN_DB, path);
    }
}

/* Every scenario file shipped; returns how many were checked. */
static int check_every_shipped_scenario(sim_scenario_t *sc, ladrc_margins_workspace_t *ws, sim_controller_id_t id)
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
        check_shipped_scenario(sc, ws, id, path);
        ++n;
    }
    closedir(dir);
    return n;
}

#endif
