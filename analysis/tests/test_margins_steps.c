/* SPDX-License-Identifier: BSD-3-Clause */
/* The tuner's time-domain objective (ladrc_margins_step_cost): the integral
 * of the squared error through a reference step and a disturbance step. A
 * linear loop's cost grows with the square of the step; lag costs more; a
 * loop that diverges costs +INFINITY; the request's step fields are checked;
 * the tuner, ranking its candidates by the two steps' costs, picks one that
 * the candidate the peak |disturbance -> error| would pick does not beat on
 * both, and falls back to that one where every candidate diverges. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "ladrc/margins.h"

#include <math.h>
#include <stdio.h>

static ladrc_margins_workspace_t ws;
static ladrc_margins_tuning_t tuning;

void setUp(void)
{
}
void tearDown(void)
{
}

/* The paper's roll axis (J 5.445e-3 kg m^2, kt 0.09 N m s) at 1 kHz. */
#define J_ROLL 5.445e-3
#define KT 0.09
/* A linear loop's cost is exactly quadratic in the step; the float
 * controller rounds its command to a relative 6e-8 per tick, which the
 * integral sums to well under this share. */
#define QUADRATIC_REL 1e-4
/* With the angle held at the reference, the float observer's innovation
 * y - z1 (about 1e-5 rad) is rounded at the ulp of that angle (3.7e-9 rad at
 * 0.05 rad). That moves the disturbance response by a few 1e-3 of itself
 * (measured 1.8e-3), a tenth of the sum: 1.7e-4 of it. */
#define SUPERPOSED_REL 1e-3

static ladrc_margins_plant_t roll_plant(double tau_s, int delay)
{
    const ladrc_margins_plant_t p = {.dt_s = 0.001,
                                     .inertia_kg_m2 = J_ROLL,
                                     .inertia_factor = 1.0,
                                     .drag_Nm_s = KT,
                                     .motor_tau_s = tau_s,
                                     .delay_ticks = delay};
    return p;
}

/* Plain LADRC without shaper or torque limits: a linear loop. */
static void linear_ladrc(ladrc_axis_config_t *cfg, double wc, double wo)
{
    ladrc_axis_config_default(cfg, LADRC_VARIANT_LADRC, 0.001f, (ladrc_real_t)J_ROLL);
    cfg->shaper = LADRC_SHAPER_NONE;
    cfg->wc_rad_s = (ladrc_real_t)wc;
    cfg->wo_rad_s = (ladrc_real_t)wo;
    cfg->u_min_Nm = -LADRC_REAL_MAX;
    cfg->u_max_Nm = LADRC_REAL_MAX;
}

static double cost_of(const ladrc_axis_config_t *cfg, const ladrc_margins_plant_t *p, double track_rad, double dist)
{
    const ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = cfg, .use_rate = 0};
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, p);
    req.track_step_rad = track_rad;
    req.dist_step_rad_s2 = dist;
    double cost = NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_step_cost(&ws, &ctl, &req, &cost));
    return cost;
}

static void test_a_linear_loop_costs_the_square_of_its_step(void)
{
    ladrc_axis_config_t cfg;
    linear_ladrc(&cfg, 10.0, 50.0);
    const ladrc_margins_plant_t p = roll_plant(0.0, 0);
    const double track = cost_of(&cfg, &p, 0.05, 0.0), track2 = cost_of(&cfg, &p, 0.1, 0.0);
    const double dist = cost_of(&cfg, &p, 0.0, 5.0), dist2 = cost_of(&cfg, &p, 0.0, 10.0);
    const double both = cost_of(&cfg, &p, 0.05, 5.0);
    printf("track %.6g / %.6g, dist %.6g / %.6g, both %.6g (rad^2 s)\n", track, track2, dist, dist2, both);
    TEST_ASSERT_TRUE(track > 0.0 && dist > 0.0);
    TEST_ASSERT_TRUE(fabs(track2 / track - 4.0) < 4.0 * QUADRATIC_REL);
    TEST_ASSERT_TRUE(fabs(dist2 / dist - 4.0) < 4.0 * QUADRATIC_REL);
    /* The disturbance comes after the tracking window, which has settled
     * (wc 10 rad/s: e^-20 after 2 s): the two costs add. */
    TEST_ASSERT_TRUE(fabs(both / (track + dist) - 1.0) < SUPERPOSED_REL);
}

static void test_lag_and_delay_cost_more(void)
{
    ladrc_axis_config_t cfg;
    linear_ladrc(&cfg, 10.0, 50.0);
    const ladrc_margins_plant_t ideal = roll_plant(0.0, 0), lagged = roll_plant(0.02, 2);
    const double c0 = cost_of(&cfg, &ideal, 0.1745, 20.0), c1 = cost_of(&cfg, &lagged, 0.1745, 20.0);
    printf("ideal %.6g, 20 ms lag and 2 ticks %.6g (rad^2 s)\n", c0, c1);
    TEST_ASSERT_TRUE(c1 > c0);
}

static void test_a_diverging_loop_costs_infinity(void)
{
    /* wc 60 rad/s behind 40 ms of lag: far beyond the lag's phase budget. */
    ladrc_axis_config_t cfg;
    linear_ladrc(&cfg, 60.0, 300.0);
    const ladrc_margins_plant_t p = roll_plant(0.04, 2);
    const double c = cost_of(&cfg, &p, 0.1745, 20.0);
    TEST_ASSERT_TRUE(c == INFINITY);
}

static void test_bad_step_fields_are_refused(void)
{
    ladrc_axis_config_t cfg;
    linear_ladrc(&cfg, 10.0, 50.0);
    const ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = 0};
    const ladrc_margins_plant_t p = roll_plant(0.0, 0);
    ladrc_margins_request_t req;
    double cost;
    const double bad_track[] = {-0.1, 0.6, NAN, INFINITY};
    for (unsigned i = 0; i < sizeof bad_track / sizeof bad_track[0]; ++i) {
        ladrc_margins_request_default(&req, &p);
        req.track_step_rad = bad_track[i];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_step_cost(&ws, &ctl, &req, &cost));
    }
    const double bad_dist[] = {-1.0, NAN, INFINITY};
    for (unsigned i = 0; i < sizeof bad_dist / sizeof bad_dist[0]; ++i) {
        ladrc_margins_request_default(&req, &p);
        req.dist_step_rad_s2 = bad_dist[i];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_step_cost(&ws, &ctl, &req, &cost));
    }
    const double bad_window[] = {0.0, -1.0, 61.0, NAN};
    for (unsigned i = 0; i < sizeof bad_window / sizeof bad_window[0]; ++i) {
        ladrc_margins_request_default(&req, &p);
        req.step_window_s = bad_window[i];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_REQUEST, ladrc_margins_step_cost(&ws, &ctl, &req, &cost));
    }
    ladrc_margins_request_default(&req, &p);
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_NULL, ladrc_margins_step_cost(&ws, &ctl, &req, NULL));
}

/* Tunes the paper's roll axis behind 20 ms of lag and 1 tick of delay as an
 * attitude controller flies it, ranked by the steps given; cost[0], cost[1]:
 * the chosen setting's costs of the default reference and disturbance
 * steps, each flown alone (rad^2 s). */
static void tune_roll(ladrc_variant_t variant, double track_rad, double dist, double cost[2])
{
    const ladrc_real_t inertia[LADRC_AXES] = {(ladrc_real_t)J_ROLL, (ladrc_real_t)J_ROLL, (ladrc_real_t)1.089e-2};
    static ladrc_attitude_config_t acfg;
    ladrc_attitude_config_default(&acfg, variant, 0.001f, inertia, (ladrc_real_t)KT);
    const ladrc_margins_controller_t ctl = {.attitude = &acfg, .axis_index = 0, .axis = NULL, .use_rate = 1};
    const ladrc_margins_plant_t p = roll_plant(0.02, 1);
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    req.track_step_rad = track_rad;
    req.dist_step_rad_s2 = dist;
    const ladrc_margins_targets_t targets = {.pm_min_deg = 45.0, .gm_min_db = 6.0};
    ladrc_axis_config_t tuned;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_tune(&ws, &ctl, &req, &targets, &tuned, &tuning));
    static ladrc_attitude_config_t again;
    again = acfg;
    again.axis[0] = tuned;
    const ladrc_margins_controller_t chk = {.attitude = &again, .axis_index = 0, .axis = NULL, .use_rate = 1};
    for (int k = 0; k < 2; ++k) {
        ladrc_margins_request_default(&req, &p);
        if (k == 0)
            req.dist_step_rad_s2 = 0.0;
        else
            req.track_step_rad = 0.0;
        cost[k] = NAN;
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_step_cost(&ws, &chk, &req, &cost[k]));
    }
}

/* Relative rounding between two flights of the same gains' costs: none (the
 * same code on the same numbers); a share only guards against a reordered
 * sum in another build. */
#define SAME_COST_REL 1e-12

static void test_the_tuners_choice_is_not_beaten_on_both_steps(void)
{
    /* Both objectives choose from the same candidates (one per shape, each
     * the largest bandwidth that meets the targets). The steps' choice
     * minimises a positive sum of its two costs, so no candidate, the
     * peak's choice included, costs less on both. */
    const ladrc_variant_t variants[] = {LADRC_VARIANT_LADRC, LADRC_VARIANT_PID, LADRC_VARIANT_INDI,
                                        LADRC_VARIANT_CASCADED, LADRC_VARIANT_RATE_ADRC};
    for (unsigned v = 0; v < sizeof variants / sizeof variants[0]; ++v) {
        double by_peak[2], by_steps[2];
        tune_roll(variants[v], 0.0, 0.0, by_peak);
        TEST_ASSERT_TRUE(isnan(tuning.step_cost_rad2_s));
        tune_roll(variants[v], 0.1745, 20.0, by_steps);
        printf("variant %d: reference / disturbance step cost of the peak's choice %.6g / %.6g, of the steps'"
               " %.6g / %.6g rad^2 s (both steps in one flight %.6g)\n",
               (int)variants[v], by_peak[0], by_peak[1], by_steps[0], by_steps[1], tuning.step_cost_rad2_s);
        const double eps0 = SAME_COST_REL * by_steps[0], eps1 = SAME_COST_REL * by_steps[1];
        TEST_ASSERT_FALSE(by_peak[0] < by_steps[0] - eps0 && by_peak[1] < by_steps[1] - eps1);
        TEST_ASSERT_TRUE(tuning.step_cost_rad2_s > 0.0 && tuning.step_cost_rad2_s < INFINITY);
    }
}

static void test_steps_too_large_fall_back_to_the_peak(void)
{
    /* 1e4 rad/s^2 against a peak |d -> e| of about 1e-3 rad per rad/s^2:
     * every candidate's error passes 1 rad. The tuning still succeeds,
     * with the candidate the peak picks, and reports the cost as infinite. */
    double by_peak[2], fallen_back[2];
    tune_roll(LADRC_VARIANT_LADRC, 0.0, 0.0, by_peak);
    const double wc_peak = tuning.wc_rad_s, wo_peak = tuning.wo_rad_s;
    tune_roll(LADRC_VARIANT_LADRC, 0.0, 1e4, fallen_back);
    TEST_ASSERT_TRUE(tuning.step_cost_rad2_s == INFINITY);
    TEST_ASSERT_TRUE(tuning.wc_rad_s == wc_peak && tuning.wo_rad_s == wo_peak);
    TEST_ASSERT_TRUE(fallen_back[0] == by_peak[0] && fallen_back[1] == by_peak[1]);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_a_linear_loop_costs_the_square_of_its_step);
    RUN_TEST(test_lag_and_delay_cost_more);
    RUN_TEST(test_a_diverging_loop_costs_infinity);
    RUN_TEST(test_bad_step_fields_are_refused);
    RUN_TEST(test_the_tuners_choice_is_not_beaten_on_both_steps);
    RUN_TEST(test_steps_too_large_fall_back_to_the_peak);
    return UNITY_END();
}
