/* SPDX-License-Identifier: BSD-3-Clause */
/* The predicted stability boundary (ladrc_analysis, frequency domain) against
 * the one found by bisection in the simulator (nonlinear rigid body, RK4,
 * ideal rotors with a first-order lag, the controllers as ladrc_sil flies
 * them): the largest stable motor lag and sensor delay agree within 10 %. */
#include "unity.h"
#include "ladrc/margins.h"
#include "run/runner.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The brief's acceptance bound on the boundary. */
#define BOUNDARY_REL_TOL 0.10
/* Divergence in the simulator: over a run of RUN_S seconds after a 10 ms,
 * 1 rad/s^2 roll pulse (0.06 to 0.2 deg of roll), the roll error exceeds
 * LIMIT_DEG (ten times the pulse's effect: a fast divergence that the
 * nonlinear body then turns into a bounded tumble), or the largest roll
 * error of the last second exceeds that of the second before (the slowest
 * mode grows) and is above NOISE_DEG (a decayed response is far below: 1e-3
 * of the pulse's effect; float rounding in the controller leaves 1e-6 deg).
 * 6 s holds 20 periods of the slowest boundary oscillation seen (3.5 Hz),
 * so a mode growing or decaying by a few percent a period shows. */
#define RUN_S 6.0
#define NOISE_DEG 1e-4
#define LIMIT_DEG 2.0
#define SIM_BISECTIONS 7

static ladrc_margins_workspace_t ws;
static sim_scenario_t sc;

void setUp(void)
{
}
void tearDown(void)
{
}

static void load(const char *controller, double inertia, double tau_s, int delay)
{
    /* The controller's actuator model stays fixed (none) while the plant's
     * lag and delay vary: the boundary of one configured controller. */
    char model[128] = "";
    if (strcmp(controller, "PID") != 0) {
        snprintf(model, sizeof model, "[controller %s]\nmodel_motor_tau_s = 0\nmodel_delay_ticks = 0\n", controller);
    }
    char text[2048];
    snprintf(text, sizeof text,
             "[run]\nduration_s = %g\ncontrol_dt_s = 0.001\nplant_substeps = 10\ncontrollers = %s\n"
             "[vehicle]\nmass_kg = 0.8\ninertia_kg_m2 = %g %g %g\narm_m = 0.165\nthrust_coeff_N_s2 = 2.98e-5\n"
             "yaw_coeff_Nm_s2 = 2e-6\nrot_drag_Nm_s = 0.09\ng_m_s2 = 9.81\n"
             "[rotors]\nideal = yes\nmotor_tau_s = %.9g\n[sensors]\ndelay_ticks = %d\n"
             "[disturbance]\nroll = 0.1 .. 0.11 : 1\n%s"
             "[metrics]\nerror_window_s = %g %g\nsteady_window_s = %g %g\nsettle_band_deg = %g\n"
             "settle_window_s = 0 %g\n",
             RUN_S, controller, inertia, inertia, 2.0 * inertia, tau_s, delay, model, RUN_S - 1.0, RUN_S, RUN_S - 2.0,
             RUN_S - 1.0, LIMIT_DEG, RUN_S);
    sim_parse_error_t err;
    const int rc = sim_scenario_parse(&sc, text, "boundary.ini", &err);
    if (rc != 0)
        printf("%s:%d: %s\n", err.path, err.line, err.message);
    TEST_ASSERT_EQUAL_INT(0, rc);
}

static int sim_stable(const char *controller, double inertia, double tau_s, int delay)
{
    load(controller, inertia, tau_s, delay);
    sim_metrics_t m;
    char err[256];
    TEST_ASSERT_EQUAL_INT(0, sim_run_attitude(&sc, sc.controllers[0], NULL, NULL, &m, err, sizeof err));
    /* settle_s is 0 when the error never left the +-LIMIT_DEG band */
    if (!m.finite || m.settle_s[0] != 0.0)
        return 0;
    return !(m.max_error_deg[0] > m.band_deg[0] && m.max_error_deg[0] > NOISE_DEG);
}

/* The analysis of the roll axis exactly as configured for the simulator. */
static void predict(const char *controller, double inertia, double *tau_s, int *delay)
{
    load(controller, inertia, 0.0, 0);
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(&sc, sc.controllers[0], &acfg);
    const ladrc_margins_plant_t plant = {.dt_s = 0.001,
                                         .inertia_kg_m2 = inertia,
                                         .inertia_factor = 1.0,
                                         .drag_Nm_s = 0.09,
                                         .motor_tau_s = 0.0,
                                         .delay_ticks = 0};
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &plant);
    /* Linearised where the simulated runs fly: at rest, no tone (LP's gain
     * bound adapts to the excitation it sees). */
    req.tone_rad_s2 = 0.0;
    const ladrc_margins_controller_t ctl = {.attitude = &acfg, .axis_index = 0, .axis = NULL, .use_rate = sc.use_rate};
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_max_motor_tau(&ws, &plant, 0.5, tau_s));
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_max_delay(&ws, &plant, delay));
}

static void check(const char *controller, double inertia)
{
    double tau_pred = 0.0;
    int delay_pred = -1;
    predict(controller, inertia, &tau_pred, &delay_pred);
    printf("%s J %g: predicted lag %.2f ms delay %d\n", controller, inertia, tau_pred * 1e3, delay_pred);
    TEST_ASSERT_TRUE(tau_pred > 0.0 && tau_pred < 0.5 && delay_pred >= 1);
    /* The simulator's boundary by bisection in [0.5, 1.5] x the prediction:
     * both ends must be on their sides, and the boundary within 10 %. */
    double lo = 0.5 * tau_pred, hi = 1.5 * tau_pred;
    TEST_ASSERT_TRUE_MESSAGE(sim_stable(controller, inertia, lo, 0), "stable at half the predicted lag");
    TEST_ASSERT_FALSE_MESSAGE(sim_stable(controller, inertia, hi, 0), "unstable at 1.5 x the predicted lag");
    for (int i = 0; i < SIM_BISECTIONS; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (sim_stable(controller, inertia, mid, 0))
            lo = mid;
        else
            hi = mid;
    }
    const double tau_sim = 0.5 * (lo + hi);
    printf("%s J %g: largest stable lag predicted %.2f ms, simulated %.2f ms\n", controller, inertia, tau_pred * 1e3,
           tau_sim * 1e3);
    TEST_ASSERT_TRUE(fabs(tau_sim - tau_pred) <= BOUNDARY_REL_TOL * tau_pred);
    /* Delay: whole ticks; the simulator's largest stable one, searched from
     * the predicted one, within 10 % (rounded to whole ticks: at least 1). */
    int d_sim = delay_pred;
    if (sim_stable(controller, inertia, 0.0, d_sim)) {
        while (d_sim < LADRC_MARGINS_MAX_DELAY && sim_stable(controller, inertia, 0.0, d_sim + 1))
            ++d_sim;
    } else {
        while (d_sim >= 0 && !sim_stable(controller, inertia, 0.0, d_sim))
            --d_sim;
    }
    printf("%s J %g: largest stable delay predicted %d ticks, simulated %d ticks\n", controller, inertia, delay_pred,
           d_sim);
    const double tol = fmax(1.0, floor(BOUNDARY_REL_TOL * delay_pred));
    TEST_ASSERT_TRUE(fabs((double)(d_sim - delay_pred)) <= tol);
}

static void test_boundary_ladrc_paper_airframe(void)
{
    check("LADRC", 5.445e-3);
}
static void test_boundary_lp_mladrc_paper_airframe(void)
{
    check("LP-MLADRC", 5.445e-3);
}
static void test_boundary_pid_paper_airframe(void)
{
    check("PID", 5.445e-3);
}
static void test_boundary_ladrc_heavy_airframe(void)
{
    check("LADRC", 0.025);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_boundary_ladrc_paper_airframe);
    RUN_TEST(test_boundary_lp_mladrc_paper_airframe);
    RUN_TEST(test_boundary_pid_paper_airframe);
    RUN_TEST(test_boundary_ladrc_heavy_airframe);
    return UNITY_END();
}
