/* SPDX-License-Identifier: BSD-3-Clause */
/* tune = margins flies the whole scenario with the tuned gains before it
 * accepts them: gains whose margins hold on the modelled airframe but that
 * diverge on the one flown are refused at the `tune` key, naming the
 * controller, the axis and the time; gains that fly are kept. The
 * objective's keys reach the tuning. */
#include "unity.h"
#include "ladrc/margins.h"
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

/* The paper's airframe with a 20 ms motor lag; LADRC tuned on inertias
 * `scale` times the true ones, a 5 deg roll step at 1 s. */
static int tune_on(double scale, sim_parse_error_t *err)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[run]\nduration_s = 4\ncontrol_dt_s = 0.001\nplant_substeps = 10\ncontrollers = LADRC\n"
             "[vehicle]\nmass_kg = 0.8\ninertia_kg_m2 = 5.445e-3 5.445e-3 1.089e-2\narm_m = 0.165\n"
             "thrust_coeff_N_s2 = 2.98e-5\nyaw_coeff_Nm_s2 = 2e-6\nrot_drag_Nm_s = 0.09\ng_m_s2 = 9.81\n"
             "[rotors]\nideal = yes\nmotor_tau_s = 0.02\n[mismatch]\ninertia_scale = %g %g %g\n"
             "[reference]\nroll = 1 .. : 5\n[controller LADRC]\ntune = margins\n",
             scale, scale, scale);
    const int rc = sim_scenario_parse(&sc, text, "check.ini", err);
    if (rc != 0)
        printf("%s:%d: %s\n", err->path, err->line, err->message);
    TEST_ASSERT_EQUAL_INT(0, rc);
    return sim_tune_controller(&sc, SIM_CTRL_LADRC, &ws, err);
}

static void test_gains_that_diverge_are_refused(void)
{
    /* Modelled 8 times heavier: the loop flown has 18 dB more gain than
     * the one tuned, beyond its gain margin. */
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT(-1, tune_on(8.0, &err));
    printf("%s:%d:%d: %s\n", err.path, err.line, err.column, err.message);
    TEST_ASSERT_EQUAL_INT(0, sc.tuning[SIM_CTRL_LADRC].tuned);
    /* "NAME on AXIS: ...", as tools/suite.sh reads a failed tuning */
    TEST_ASSERT_NOT_NULL(strstr(err.message, "tune = margins: LADRC on roll: the tuned gains diverge at "));
    TEST_ASSERT_EQUAL_STRING("check.ini", err.path);
    TEST_ASSERT_EQUAL_INT(sc.tune_line[SIM_CTRL_LADRC], err.line);
}

static void test_gains_that_fly_are_kept(void)
{
    sim_parse_error_t err;
    const int rc = tune_on(1.0, &err);
    if (rc != 0)
        printf("%s\n", err.message);
    TEST_ASSERT_EQUAL_INT(0, rc);
    TEST_ASSERT_EQUAL_INT(1, sc.tuning[SIM_CTRL_LADRC].tuned);
}

/* RATE-ADRC on the same airframe (its true inertias), the tuning's
 * objective given by `keys`; returns its roll step cost (rad^2 s). */
static double rate_adrc_roll_cost(const char *keys)
{
    char text[1024];
    snprintf(text, sizeof text,
             "[run]\nduration_s = 4\ncontrol_dt_s = 0.001\nplant_substeps = 10\ncontrollers = RATE-ADRC\n"
             "[vehicle]\nmass_kg = 0.8\ninertia_kg_m2 = 5.445e-3 5.445e-3 1.089e-2\narm_m = 0.165\n"
             "thrust_coeff_N_s2 = 2.98e-5\nyaw_coeff_Nm_s2 = 2e-6\nrot_drag_Nm_s = 0.09\ng_m_s2 = 9.81\n"
             "[rotors]\nideal = yes\nmotor_tau_s = 0.02\n[sensors]\nuse_rate = yes\ndelay_ticks = 1\n"
             "[reference]\nroll = 1 .. : 5\n[controller RATE-ADRC]\ntune = margins\n%s",
             keys);
    sim_parse_error_t err;
    const int rc = sim_scenario_parse(&sc, text, "objective.ini", &err);
    if (rc != 0)
        printf("%s:%d: %s\n", err.path, err.line, err.message);
    TEST_ASSERT_EQUAL_INT(0, rc);
    TEST_ASSERT_EQUAL_INT(0, sim_tune_controller(&sc, SIM_CTRL_RATE_ADRC, &ws, &err));
    return sc.tuning[SIM_CTRL_RATE_ADRC].step_cost_rad2_s[0];
}

static void test_the_objective_keys_reach_the_tuning(void)
{
    /* The cost of the steps the file asks for: a larger reference step
     * costs more; both steps 0 rank by the peak and report no cost. */
    const double by_default = rate_adrc_roll_cost("");
    const double big_step = rate_adrc_roll_cost("tune_step_deg = 28\n");
    const double none = rate_adrc_roll_cost("tune_step_deg = 0\ntune_disturbance_step_rad_s2 = 0\n");
    printf("RATE-ADRC roll step cost: %.4g (defaults), %.4g (a 28 deg step), %.4g (steps off) rad^2 s\n", by_default,
           big_step, none);
    TEST_ASSERT_TRUE(by_default > 0.0 && big_step > by_default);
    TEST_ASSERT_TRUE(isnan(none));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_gains_that_diverge_are_refused);
    RUN_TEST(test_gains_that_fly_are_kept);
    RUN_TEST(test_the_objective_keys_reach_the_tuning);
    return UNITY_END();
}
