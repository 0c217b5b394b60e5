/* SPDX-License-Identifier: BSD-3-Clause */
/* Stability analysis (margins.h): plant discretisation, measured controller
 * response, margins of a textbook loop, and the Nyquist verdict against long
 * simulations of the same sampled loop. */
#include "unity.h"
#include "ladrc/margins.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>

#define PI 3.14159265358979323846

/* The matrix exponential (Taylor series after scaling below 0.5, 20 terms)
 * and the 2x2 solve are exact to double rounding amplified by |z - 1|^-2 at
 * the lowest test frequency (1e4): 1e-9 relative leaves a wide berth. */
#define PLANT_REL_TOL 1e-9
/* The library computes in float: its impulse response carries a relative
 * rounding of 6e-8 per operation over some ten operations a tick; the
 * measured PID response must match its transfer function to 1e-5. */
#define CTL_REL_TOL 1e-5
/* Textbook loop: crossings are bisected to 1e-12 in w, so the margins agree
 * to far better than 1e-6 (deg, dB). */
#define TEXTBOOK_TOL 1e-6

static ladrc_margins_workspace_t ws;
static ladrc_margins_result_t res;

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_margins_plant_t paper_plant(double tau_s, int delay)
{
    const ladrc_margins_plant_t p = {.dt_s = 0.001,
                                     .inertia_kg_m2 = 5.445e-3,
                                     .inertia_factor = 1.0,
                                     .drag_Nm_s = 0.09,
                                     .motor_tau_s = tau_s,
                                     .delay_ticks = delay};
    return p;
}

static void test_double_integrator_matches_its_zoh_closed_form(void)
{
    const double dt = 0.002, j = 0.02;
    for (int delay = 0; delay <= 2; ++delay) {
        const ladrc_margins_plant_t p = {.dt_s = dt,
                                         .inertia_kg_m2 = j,
                                         .inertia_factor = 1.0,
                                         .drag_Nm_s = 0.0,
                                         .motor_tau_s = 0.0,
                                         .delay_ticks = delay};
        const double ws_test[] = {0.5, 20.0, 900.0};
        for (int i = 0; i < 3; ++i) {
            double out[4];
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_plant_freq(&p, ws_test[i], out));
            const double complex z = cexp(I * ws_test[i] * dt);
            /* P(z) = T^2 (z + 1) / (2 J (z - 1)^2), rate T (z^-1) / (J (1 - z^-1)) ... */
            const double complex pa = dt * dt * (z + 1.0) / (2.0 * j * (z - 1.0) * (z - 1.0)) / cpow(z, delay);
            const double complex pr = dt / (j * (z - 1.0)) / cpow(z, delay);
            TEST_ASSERT_TRUE(cabs(out[0] + I * out[1] - pa) <= PLANT_REL_TOL * cabs(pa));
            TEST_ASSERT_TRUE(cabs(out[2] + I * out[3] - pr) <= PLANT_REL_TOL * cabs(pr));
        }
    }
}

static void test_first_order_lag_and_drag_match_their_continuous_limits(void)
{
    /* At w far below the sampling rate the sampled plant is the continuous
     * one with half a tick of hold delay: 1 / ((tau s + 1)(J s^2 + kt s)).
     * The hold's phase w T / 2 and the sampling's gain error (w T)^2 / 12
     * are below 2e-6 at w = 1 rad/s, T = 1 ms: 1e-5 relative. */
    const ladrc_margins_plant_t p = paper_plant(0.03, 0);
    const double w = 1.0;
    double out[4];
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_plant_freq(&p, w, out));
    const double complex s = I * w;
    const double complex pa = cexp(-s * 0.0005) / ((0.03 * s + 1.0) * (5.445e-3 * s * s + 0.09 * s));
    TEST_ASSERT_TRUE(cabs(out[0] + I * out[1] - pa) <= 1e-5 * cabs(pa));
}

static void test_measured_pid_matches_its_transfer_function(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, 0.001f, 5.445e-3f);
    cfg.pid_d_filter_tau_s = 0.004f;
    const ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = 0};
    ladrc_margins_plant_t p = paper_plant(0.0, 0);
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    const double dt = 0.001, kp = cfg.pid_kp, ki = cfg.pid_ki, kd = cfg.pid_kd;
    const double alpha = dt / (0.004 + dt);
    const double w_test[] = {1.0, 60.0, 2000.0};
    for (int i = 0; i < 3; ++i) {
        double out[4];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_controller_freq(&ws, w_test[i], out));
        const double complex zi = cexp(-I * w_test[i] * dt);
        /* pid.c: u = kp e + I - kd d, I += ki dt e, d = (1 - a) d + a (y - y-) / dt, e = -y */
        const double complex c = -kp - ki * dt / (1.0 - zi) - kd * alpha * (1.0 - zi) / dt / (1.0 - (1.0 - alpha) * zi);
        TEST_ASSERT_TRUE(cabs(out[0] + I * out[1] - c) <= CTL_REL_TOL * cabs(c));
        TEST_ASSERT_TRUE(out[2] == 0.0); /* no rate given: no rate path */
    }
}

/* A filter's sections in float: coefficients rounded to 6e-8 relative, and
 * the cascade's float arithmetic on the impulse, put its measured response
 * within 1e-4 of the closed form at frequencies away from its notches. */
#define FILTER_REL_TOL 1e-4

/* The bilinear notch at f0 (prewarped zeros) and the Butterworth low-pass
 * at fc, as docs/method.md section 7 writes them, at z^-1 = zi. */
static double complex notch_at(double f0_hz, double q, double dt, double complex zi)
{
    const double w0 = 2.0 * PI * f0_hz * dt, c = cos(w0), alpha = sin(w0) / (2.0 * q);
    return (1.0 - 2.0 * c * zi + zi * zi) / ((1.0 + alpha) - 2.0 * c * zi + (1.0 - alpha) * zi * zi);
}

static double complex butterworth2_at(double fc_hz, double dt, double complex zi)
{
    const double k = tan(PI * fc_hz * dt), r2 = sqrt(2.0);
    return k * k * (1.0 + zi) * (1.0 + zi) /
           ((1.0 + r2 * k + k * k) + 2.0 * (k * k - 1.0) * zi + (1.0 - r2 * k + k * k) * zi * zi);
}

static void test_a_gyro_filter_before_the_controller_multiplies_its_response(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, 0.001f, 5.445e-3f);
    ladrc_gyro_filter_config_t fc;
    ladrc_gyro_filter_config_default(&fc, 0.001f, 3u); /* channels: the analysis sets its own */
    fc.n_notches = 1u;
    fc.notch_hz[0] = 50.0f;
    fc.rpm_rotors = 1u;
    fc.rpm_harmonics = 1u;
    fc.rpm_min_hz = 20.0f;
    fc.rpm_fade_hz = 0.0f;
    fc.lpf_order = 2u;
    const ladrc_real_t rotor_hz[1] = {70.0f};
    ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = 0};
    ladrc_margins_plant_t p = paper_plant(0.0, 0);
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    const double w_test[] = {1.0, 60.0, 2000.0};
    double bare[3][4];
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_controller_freq(&ws, w_test[i], bare[i]));
    }
    ctl.filter = &fc;
    ctl.filter_rotor_hz = rotor_hz;
    /* the rates only: the PID reads no rate here, so nothing changes */
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    for (int i = 0; i < 3; ++i) {
        double out[4];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_controller_freq(&ws, w_test[i], out));
        TEST_ASSERT_TRUE(out[0] == bare[i][0] && out[1] == bare[i][1]);
    }
    ctl.filter_angle = 1;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    for (int i = 0; i < 3; ++i) {
        double out[4];
        TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_controller_freq(&ws, w_test[i], out));
        const double complex zi = cexp(-I * w_test[i] * 0.001);
        const double complex h =
            notch_at(50.0, 5.0, 0.001, zi) * notch_at(70.0, 5.0, 0.001, zi) * butterworth2_at(100.0, 0.001, zi);
        const double complex want = (bare[i][0] + I * bare[i][1]) * h;
        TEST_ASSERT_TRUE(cabs(out[0] + I * out[1] - want) <= FILTER_REL_TOL * cabs(want));
    }
    /* an RPM bank with no rotor rates to sit on is refused */
    ctl.filter_rotor_hz = NULL;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_CONTROLLER, ladrc_margins_measure(&ws, &ctl, &req));
}

/* L(z) = k T z^-d / (z - 1): an integrator with d ticks of delay. On the
 * unit circle |L| = k T / (2 sin(w/2)), arg L = -pi/2 - w/2 - w d (w per
 * tick): crossover 2 asin(k T / 2), PM = pi/2 - w_c (d + 1/2), phase
 * crossover w = pi / (2 d + 1) with GM = 2 sin(w/2) / (k T). */
typedef struct {
    double k, dt;
    int d;
} integrator_t;

static void integrator_loop(void *ctx, double re, double im, double *l_re, double *l_im)
{
    const integrator_t *c = (const integrator_t *)ctx;
    const double complex z = re + I * im;
    const double complex l = c->k * c->dt / ((z - 1.0) * cpow(z, c->d));
    *l_re = creal(l);
    *l_im = cimag(l);
}

static void test_integrator_with_delay_has_its_textbook_margins(void)
{
    const double ks[] = {20.0, 150.0, 400.0};
    for (int d = 1; d <= 3; ++d) {
        for (int i = 0; i < 3; ++i) {
            integrator_t c = {.k = ks[i], .dt = 0.001, .d = d};
            ladrc_margins_of_loop(integrator_loop, &c, c.dt, &res);
            const double wc = 2.0 * asin(c.k * c.dt / 2.0);
            const double pm = (PI / 2.0 - wc * (d + 0.5)) * 180.0 / PI;
            const double wp = PI / (2.0 * d + 1.0);
            const double gm = 20.0 * log10(2.0 * sin(wp / 2.0) / (c.k * c.dt));
            TEST_ASSERT_FLOAT_WITHIN(TEXTBOOK_TOL * 1e3, wc / c.dt, res.wc_rad_s);
            TEST_ASSERT_FLOAT_WITHIN(TEXTBOOK_TOL, pm, res.pm_deg);
            if (gm > 0.0) {
                TEST_ASSERT_FLOAT_WITHIN(TEXTBOOK_TOL, gm, res.gm_db);
            } else {
                TEST_ASSERT_FLOAT_WITHIN(TEXTBOOK_TOL, gm, res.gm_low_db);
            }
            /* z^d (z - 1) + k T: stable exactly when the gain margin is positive */
            TEST_ASSERT_EQUAL_INT(gm > 0.0, res.stable);
            TEST_ASSERT_FLOAT_WITHIN(1e-9, pm > 0.0 ? pm * PI / 180.0 / (wc / c.dt) : 0.0, res.dm_s);
        }
    }
}

/* The verdict against a 30 s simulation of the same sampled loop (library
 * controller, exact discrete plant): stable when the angle after a pulse
 * has decayed (last quarter below the second eighth). Close to the boundary
 * a slow growth or decay still shows within 30 s: the sweep's points were
 * chosen by neither method, and both sides of each boundary are present. */
static void sweep(ladrc_variant_t variant, int use_rate, double wc, double kp_scale)
{
    const double lags[] = {0.0, 0.005, 0.01, 0.02, 0.03, 0.05, 0.08};
    const int delays[] = {0, 2, 6, 15};
    int stable_seen = 0, unstable_seen = 0;
    for (int i = 0; i < 7; ++i) {
        for (int j = 0; j < 4; ++j) {
            ladrc_axis_config_t cfg;
            ladrc_axis_config_default(&cfg, variant, 0.001f, 5.445e-3f);
            cfg.wc_rad_s = (ladrc_real_t)wc;
            cfg.wo_rad_s = (ladrc_real_t)(5.0 * wc);
            cfg.pid_kp *= (ladrc_real_t)kp_scale;
            const ladrc_margins_controller_t ctl = {
                .attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = use_rate};
            const ladrc_margins_plant_t p = paper_plant(lags[i], delays[j]);
            ladrc_margins_request_t req;
            ladrc_margins_request_default(&req, &p);
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
            const int verdict = ladrc_margins_is_stable(&ws, &p);
            double growth = 0.0;
            TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_simulate(&ws, &ctl, &p, 30000, &growth));
            if ((growth < 1.0) != verdict)
                printf("variant %d rate %d wc %g lag %g delay %d growth %g verdict %d\n", variant, use_rate, wc,
                       lags[i], delays[j], growth, verdict);
            TEST_ASSERT_EQUAL_INT_MESSAGE(growth < 1.0, verdict, "Nyquist verdict disagrees with the simulation");
            stable_seen += verdict;
            unstable_seen += !verdict;
        }
    }
    /* Both outcomes occur: the sweep tests the verdict, not a constant. */
    TEST_ASSERT_TRUE(stable_seen > 0 && unstable_seen > 0);
}

static void test_verdict_agrees_with_simulation_ladrc(void)
{
    sweep(LADRC_VARIANT_LADRC, 0, 15.0, 1.0);
}
static void test_verdict_agrees_with_simulation_ladrc_fast(void)
{
    sweep(LADRC_VARIANT_LADRC, 0, 40.0, 1.0);
}
static void test_verdict_agrees_with_simulation_pid(void)
{
    sweep(LADRC_VARIANT_PID, 0, 15.0, 0.3);
}
static void test_verdict_agrees_with_simulation_pid_rate(void)
{
    sweep(LADRC_VARIANT_PID, 1, 15.0, 0.3);
}
static void test_verdict_agrees_with_simulation_lp(void)
{
    sweep(LADRC_VARIANT_LP_MLADRC, 1, 15.0, 1.0);
}

static void test_boundaries_bracket_the_verdict(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, 0.001f, 5.445e-3f);
    const ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = 0};
    const ladrc_margins_plant_t p = paper_plant(0.0, 0);
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_measure(&ws, &ctl, &req));
    double tau = 0.0;
    int ticks = -2;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_max_motor_tau(&ws, &p, 1.0, &tau));
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_max_delay(&ws, &p, &ticks));
    ladrc_margins_plant_t q = p;
    q.motor_tau_s = tau;
    TEST_ASSERT_TRUE(ladrc_margins_is_stable(&ws, &q));
    q.motor_tau_s = tau * 1.01;
    TEST_ASSERT_FALSE(ladrc_margins_is_stable(&ws, &q));
    q = p;
    q.delay_ticks = ticks;
    TEST_ASSERT_TRUE(ladrc_margins_is_stable(&ws, &q));
    q.delay_ticks = ticks + 1;
    TEST_ASSERT_FALSE(ladrc_margins_is_stable(&ws, &q));
    /* The delay margin of the undelayed loop bounds the whole ticks. */
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_OK, ladrc_margins_loop(&ws, &req, &res));
    TEST_ASSERT_TRUE(ticks <= res.dm_ticks && res.dm_ticks < ticks + 1.5);
}

static void test_bad_requests_are_refused_by_name(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, 0.001f, 5.445e-3f);
    const ladrc_margins_controller_t ctl = {.attitude = NULL, .axis_index = 0, .axis = &cfg, .use_rate = 0};
    ladrc_margins_plant_t p = paper_plant(0.0, 0);
    ladrc_margins_request_t req;
    ladrc_margins_request_default(&req, &p);
    req.plant.motor_tau_s = -1.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_MOTOR_TAU, ladrc_margins_measure(&ws, &ctl, &req));
    req.plant = p;
    req.plant.delay_ticks = LADRC_MARGINS_MAX_DELAY + 1;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_DELAY, ladrc_margins_measure(&ws, &ctl, &req));
    req.plant = p;
    req.plant.dt_s = 0.002;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_DT_S, ladrc_margins_measure(&ws, &ctl, &req));
    req.plant = p;
    req.plant.inertia_factor = 0.0;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_INERTIA, ladrc_margins_measure(&ws, &ctl, &req));
    req.plant = p;
    cfg.wc_rad_s = -1.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_CONTROLLER, ladrc_margins_measure(&ws, &ctl, &req));
    TEST_ASSERT_EQUAL_INT(LADRC_MARGINS_ERR_NOT_MEASURED, ladrc_margins_loop(&ws, &req, &res));
    TEST_ASSERT_NOT_NULL(ladrc_margins_status_str(LADRC_MARGINS_ERR_TARGETS_NOT_MET));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_double_integrator_matches_its_zoh_closed_form);
    RUN_TEST(test_first_order_lag_and_drag_match_their_continuous_limits);
    RUN_TEST(test_measured_pid_matches_its_transfer_function);
    RUN_TEST(test_a_gyro_filter_before_the_controller_multiplies_its_response);
    RUN_TEST(test_integrator_with_delay_has_its_textbook_margins);
    RUN_TEST(test_verdict_agrees_with_simulation_ladrc);
    RUN_TEST(test_verdict_agrees_with_simulation_ladrc_fast);
    RUN_TEST(test_verdict_agrees_with_simulation_pid);
    RUN_TEST(test_verdict_agrees_with_simulation_pid_rate);
    RUN_TEST(test_verdict_agrees_with_simulation_lp);
    RUN_TEST(test_boundaries_bracket_the_verdict);
    RUN_TEST(test_bad_requests_are_refused_by_name);
    return UNITY_END();
}
