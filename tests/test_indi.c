/* SPDX-License-Identifier: BSD-3-Clause */
/* INDI (indi.h) behind the axis API: the incremental law on small plants
 * simulated here, exactly sampled (torque and disturbance held over each
 * tick), in double precision. */
#include "unity.h"
#include "test_plant.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "ladrc/indi.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S 0.001
#define J_KG_M2 5.445e-3
#define PI_D 3.14159265358979323846

/* Constant disturbance: after 3 s the error is what float rounding of the
 * torque leaves (a few 1e-9 rad: an ulp of the 0.1 N m torque is 1e-6 rad/s^2
 * of acceleration, over k_att k_rate = 225 /s^2); without the increment the
 * same loop would stand off by d / 225 = 0.09 rad. */
#define STEADY_ERROR_RAD 1e-5
/* The brief's bar for the measured response against the transfer function. */
#define TF_REL_TOL 0.05
/* Filtered disturbance against the true constant one after 3 s (F(1) = 1:
 * the same float rounding, relative). */
#define DIST_REL_TOL 1e-3
/* Overshoot after 0.5 s and after 5 s of saturation on a stand: with no
 * integrator the filters reach the same fixed point in both (u_f at the
 * limit, omegadot_f at 0, within 1e-13 after 0.5 s at w_f = 75 rad/s), so the
 * flights after release agree to float rounding (relative 1e-4 of the
 * overshoot, or of 1 mrad). */
#define WINDUP_REL_TOL 1e-4

typedef struct {
    double y, w; /* angle (rad), rate (rad/s) */
    double tau;  /* motor lag (s), 0 = none */
    double m;    /* acting torque of the lag (N m) */
    int delay;   /* measurement delay (ticks) */
    double hist_y[16], hist_w[16];
    int n;
} plant_t;

static void plant_init(plant_t *p, double tau, int delay)
{
    memset(p, 0, sizeof *p);
    p->tau = tau;
    p->delay = delay;
}

/* Exact ZOH step of y'' = (acting torque) / J + d with the lag m' = (u - m) / tau. */
static void plant_step(plant_t *p, double u, double d)
{
    const double h = DT_S, b = 1.0 / J_KG_M2;
    for (int i = 15; i > 0; --i) {
        p->hist_y[i] = p->hist_y[i - 1];
        p->hist_w[i] = p->hist_w[i - 1];
    }
    double dy, dw;
    test_lag_step(h, p->tau, u, &p->m, &dy, &dw);
    p->y += p->w * h + b * dy + 0.5 * d * h * h;
    p->w += b * dw + d * h;
    p->hist_y[0] = p->y;
    p->hist_w[0] = p->w;
    p->n++;
}

static double meas_y(const plant_t *p)
{
    return p->delay == 0 ? p->y : (p->n > p->delay ? p->hist_y[p->delay] : 0.0);
}
static double meas_w(const plant_t *p)
{
    return p->delay == 0 ? p->w : (p->n > p->delay ? p->hist_w[p->delay] : 0.0);
}

static ladrc_axis_config_t config(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_INDI, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.shaper = LADRC_SHAPER_NONE;
    return cfg;
}

static ladrc_real_t tick(ladrc_axis_t *axis, plant_t *p, double ref)
{
    return axis_command_with_rate(axis, (ladrc_real_t)ref, (ladrc_real_t)meas_y(p), (ladrc_real_t)meas_w(p));
}

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_defaults_follow_the_stated_rule(void)
{
    /* the LADRC default's loop (s + 15)^2 and its observer's 75 rad/s */
    ladrc_axis_config_t ladrc, indi;
    ladrc_axis_config_default(&ladrc, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_config_default(&indi, LADRC_VARIANT_INDI, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    TEST_ASSERT_EQUAL_FLOAT(ladrc.wc_rad_s, indi.indi_att_kp_per_s);
    TEST_ASSERT_EQUAL_FLOAT(ladrc.wc_rad_s, indi.indi_rate_kp_per_s);
    TEST_ASSERT_EQUAL_FLOAT(ladrc.wo_rad_s, indi.indi_filter_rad_s);
    TEST_ASSERT_EQUAL_INT(LADRC_SHAPER_TD, indi.shaper);
}

static void test_init_names_the_bad_field(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg = config();
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    const struct {
        size_t offset;
        float value;
        ladrc_status_t status;
    } cases[] = {
        {.offset = offsetof(ladrc_axis_config_t, indi_att_kp_per_s), .value = 0.0f, .status = LADRC_ERR_INDI_ATT_KP},
        {.offset = offsetof(ladrc_axis_config_t, indi_att_kp_per_s),
         .value = 1000.0f,
         .status = LADRC_ERR_INDI_ATT_KP}, /* k dt = 1 */
        {.offset = offsetof(ladrc_axis_config_t, indi_rate_kp_per_s), .value = NAN, .status = LADRC_ERR_INDI_RATE_KP},
        {.offset = offsetof(ladrc_axis_config_t, indi_rate_kp_per_s), .value = -1.0f, .status = LADRC_ERR_INDI_RATE_KP},
        {.offset = offsetof(ladrc_axis_config_t, indi_filter_rad_s),
         .value = INFINITY,
         .status = LADRC_ERR_INDI_FILTER},
        {.offset = offsetof(ladrc_axis_config_t, indi_filter_rad_s),
         .value = 3200.0f,
         .status = LADRC_ERR_INDI_FILTER}, /* beyond pi / dt */
        {.offset = offsetof(ladrc_axis_config_t, b0), .value = 0.0f, .status = LADRC_ERR_B0},
        {.offset = offsetof(ladrc_axis_config_t, motor_tau_s), .value = -1.0f, .status = LADRC_ERR_MOTOR_TAU_S},
        {.offset = offsetof(ladrc_axis_config_t, td_accel_rad_s2), .value = -1.0f, .status = LADRC_ERR_TD_ACCEL_RAD_S2},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ladrc_axis_config_t bad = config();
        bad.shaper = LADRC_SHAPER_TD;
        ladrc_real_t *f = (ladrc_real_t *)(void *)((char *)&bad + cases[i].offset);
        *f = (ladrc_real_t)cases[i].value;
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].status, ladrc_axis_init(&axis, &bad), ladrc_status_str(cases[i].status));
    }
    /* the filter at exactly pi / dt is accepted */
    cfg.indi_filter_rad_s = (ladrc_real_t)(3.14159 / DT_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
}

/* Flies the axis on plant p against a constant d and a reference; returns the
 * largest |error| over the last 0.5 s of n ticks. increment = 0 replaces
 * the command by J nu alone (the same loop without INDI's increment). */
static double fly_constant(plant_t *p, double d, double ref, int n, ladrc_axis_t *axis_out)
{
    ladrc_axis_config_t cfg = config();
    cfg.motor_tau_s = (ladrc_real_t)p->tau;
    cfg.delay_ticks = (uint16_t)p->delay;
    static ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    double worst = 0.0;
    for (int k = 0; k < n; ++k) {
        const double u = (double)tick(&axis, p, ref);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
        plant_step(p, u, d);
        if (k >= n - 500)
            worst = fmax(worst, fabs(ref - p->y));
    }
    if (axis_out != NULL)
        *axis_out = axis;
    return worst;
}

static void test_a_constant_disturbance_leaves_no_steady_error(void)
{
    /* given: 20 rad/s^2 (the paper's bias), a 0.1 rad reference */
    plant_t p;
    plant_init(&p, 0.0, 0);
    ladrc_axis_t axis;
    /* when */
    const double worst = fly_constant(&p, 20.0, 0.1, 3000, &axis);
    ladrc_real_t y, w, dist;
    ladrc_axis_get_estimate(&axis, &y, &w, &dist);
    printf("constant d: error %.3e rad, estimate %.6f rad/s^2\n", worst, (double)dist);
    /* then: no error, and the filtered disturbance is d (F(1) = 1) */
    TEST_ASSERT_TRUE(worst < STEADY_ERROR_RAD);
    TEST_ASSERT_FLOAT_WITHIN(DIST_REL_TOL * 20.0, 20.0, (double)dist);
    /* the check can fail: the loop without the increment stands off by d / (k_att k_rate) */
    TEST_ASSERT_TRUE(20.0 / 225.0 > 1000.0 * STEADY_ERROR_RAD);
}

static void test_the_modelled_actuator_keeps_the_pair_synchronised(void)
{
    /* given: a 30 ms motor and a rate 2 ticks late, both modelled */
    plant_t p;
    plant_init(&p, 0.03, 2);
    ladrc_axis_t axis;
    /* when */
    const double worst = fly_constant(&p, 20.0, 0.1, 6000, &axis);
    ladrc_real_t y, w, dist;
    ladrc_axis_get_estimate(&axis, &y, &w, &dist);
    printf("lag + delay modelled: error %.3e rad, estimate %.6f rad/s^2\n", worst, (double)dist);
    /* then: still no steady error, still the true d */
    TEST_ASSERT_TRUE(worst < STEADY_ERROR_RAD);
    TEST_ASSERT_FLOAT_WITHIN(DIST_REL_TOL * 20.0, 20.0, (double)dist);
}

/*
 * The disturbance-to-error response of the linear loop, by hand. Tick k
 * measures theta_k, omega_k; u_k is held over (t_k, t_k+1]; d_k likewise;
 * a_k = b0 u_k + d_k. Reference 0, shaper none:
 *
 *   nu_k = -K theta_k - C omega_k,  K = k_att k_rate, C = k_att + k_rate
 *   (omega_k - omega_k-1) / h = a_k-1 and the acting torque is u_k-1, so
 *   omegadot_f = F[a_k-1] = b0 F[u_k-1] + F[d_k-1] and u_f = F[u_k-1]:
 *   u_k = J nu_k - J F z^-1 d,  i.e.  a_k = nu_k + g_k,  g = (1 - z^-1 F(z)) d
 *
 * The double integrator held over the step, theta_k+1 = theta_k + h omega_k
 * + h^2/2 a_k, omega_k+1 = omega_k + h a_k, closed by nu, gives
 *
 *   Theta / G = (h^2 / 2)(z + 1) / ((z - 1)^2 + (h C + h^2 K / 2)(z - 1) + h^2 K)
 *
 * with F(z) = (alpha / (1 - (1 - alpha) z^-1))^2, alpha = 1 - exp(-w_f h), so
 *
 *   E / D = -(h^2 / 2)(z + 1)(1 - z^-1 F(z)) / ((z - 1)^2 + (h C + h^2 K / 2)(z - 1) + h^2 K)
 *
 * at z = exp(j w h). As h -> 0 this is the continuous
 * -(1 - H(s)) / ((s + k_att)(s + k_rate)), H = w_f^2 / (s + w_f)^2,
 * 1 - H = s (s + 2 w_f) / (s + w_f)^2: a zero at s = 0 (no steady error).
 */
static double predicted_gain(double w, double ka, double kr, double wf)
{
    const double h = DT_S, K = ka * kr, C = ka + kr, alpha = -expm1(-wf * h);
    const double complex_re = cos(w * h), complex_im = sin(w * h); /* z */
    /* z^-1 */
    const double zi_re = complex_re, zi_im = -complex_im;
    /* F = (alpha / (1 - p z^-1))^2 */
    const double q_re = 1.0 - (1.0 - alpha) * zi_re, q_im = -(1.0 - alpha) * zi_im;
    const double q2 = q_re * q_re + q_im * q_im;
    const double f1_re = alpha * q_re / q2, f1_im = -alpha * q_im / q2;
    const double f_re = f1_re * f1_re - f1_im * f1_im, f_im = 2.0 * f1_re * f1_im;
    /* 1 - z^-1 F */
    const double g_re = 1.0 - (zi_re * f_re - zi_im * f_im), g_im = -(zi_re * f_im + zi_im * f_re);
    /* numerator (h^2/2)(z + 1) g */
    const double n1_re = 0.5 * h * h * (complex_re + 1.0), n1_im = 0.5 * h * h * complex_im;
    const double num = hypot(n1_re * g_re - n1_im * g_im, n1_re * g_im + n1_im * g_re);
    /* denominator (z - 1)^2 + c1 (z - 1) + h^2 K */
    const double x_re = complex_re - 1.0, x_im = complex_im, c1 = h * C + 0.5 * h * h * K;
    const double den_re = x_re * x_re - x_im * x_im + c1 * x_re + h * h * K, den_im = 2.0 * x_re * x_im + c1 * x_im;
    return num / hypot(den_re, den_im);
}

static double continuous_gain(double w, double ka, double kr, double wf)
{
    return w * hypot(w, 2.0 * wf) / ((w * w + wf * wf) * hypot(w, ka) * hypot(w, kr));
}

static void test_disturbance_response_matches_its_transfer_function(void)
{
    const double freqs[] = {2.0, 10.0, 40.0};
    const ladrc_axis_config_t cfg = config();
    for (size_t i = 0; i < sizeof freqs / sizeof freqs[0]; ++i) {
        /* given: a tone of 10 rad/s^2 at w, held over each tick */
        const double w = freqs[i], D = 10.0;
        ladrc_axis_t axis;
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
        plant_t p;
        plant_init(&p, 0.0, 0);
        /* when: 3 s to settle, then whole periods (>= 2 s) projected on the tone */
        const int settle = 3000;
        const double period = 2.0 * PI_D / w;
        const int periods = (int)ceil(2.0 / period);
        const int n = (int)floor(periods * period / DT_S);
        double s = 0.0, c = 0.0;
        for (int k = 0; k < settle + n; ++k) {
            const double t = k * DT_S;
            const double u = (double)tick(&axis, &p, 0.0);
            if (k >= settle) {
                s += -p.y * sin(w * t);
                c += -p.y * cos(w * t);
            }
            plant_step(&p, u, D * sin(w * t));
        }
        const double measured = 2.0 * hypot(s, c) / n / D;
        const double predicted =
            predicted_gain(w, cfg.indi_att_kp_per_s, cfg.indi_rate_kp_per_s, cfg.indi_filter_rad_s);
        const double cont = continuous_gain(w, cfg.indi_att_kp_per_s, cfg.indi_rate_kp_per_s, cfg.indi_filter_rad_s);
        printf("|E/D| at %5.1f rad/s: measured %.5e, sampled TF %.5e, continuous %.5e rad per rad/s^2\n", w, measured,
               predicted, cont);
        /* then */
        TEST_ASSERT_FLOAT_WITHIN(TF_REL_TOL * predicted, predicted, measured);
    }
}

/* A vehicle locked on a stand for lock_ticks while the reference asks for
 * 0.3 rad: the command saturates (the mixer reports 0.15 N m of the 0.2 the
 * command may reach) and nothing moves. Released, it flies to the reference;
 * returns the largest overshoot beyond it over 3 s. */
static double overshoot_after_lock(int lock_ticks)
{
    ladrc_axis_config_t cfg = config();
    cfg.u_min_Nm = LADRC_R(-0.2);
    cfg.u_max_Nm = LADRC_R(0.2);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p;
    plant_init(&p, 0.0, 0);
    double worst = 0.0;
    for (int k = 0; k < lock_ticks + 3000; ++k) {
        const double u = (double)tick(&axis, &p, 0.3);
        const double applied = fmax(-0.15, fmin(0.15, u));
        ladrc_axis_set_applied(&axis, (ladrc_real_t)applied);
        /* the torque filter holds what acted: never beyond the limit */
        TEST_ASSERT_TRUE(fabs((double)axis.part.indi.torque.s2) <= 0.15 * (1.0 + 1e-6));
        if (k >= lock_ticks) {
            plant_step(&p, applied, 0.0);
            worst = fmax(worst, p.y - 0.3);
        }
    }
    return worst;
}

static void test_saturation_winds_nothing_up(void)
{
    /* when: locked for 0.5 s and for 5 s */
    const double short_lock = overshoot_after_lock(500);
    const double long_lock = overshoot_after_lock(5000);
    printf("saturation: overshoot after a 0.5 s lock %.6e rad, after a 5 s lock %.6e rad\n", short_lock, long_lock);
    /* then: the same flight, however long the saturation lasted (an
     * integrator would have gathered ten times as much in the long lock) */
    TEST_ASSERT_FLOAT_WITHIN(WINDUP_REL_TOL * fmax(short_lock, 1e-3), short_lock, long_lock);
}

static void test_without_a_rate_the_command_is_held_and_flagged(void)
{
    ladrc_axis_config_t cfg = config();
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p;
    plant_init(&p, 0.0, 0);
    ladrc_real_t u = LADRC_R(0.0);
    for (int k = 0; k < 300; ++k) {
        u = tick(&axis, &p, 0.05);
        plant_step(&p, (double)u, 0.0);
    }
    TEST_ASSERT_TRUE(u != LADRC_R(0.0));
    for (int k = 0; k < 5; ++k) {
        /* when: angle-only ticks and NaN or out-of-range rates */
        const ladrc_real_t held = axis_command(&axis, LADRC_R(0.05), (ladrc_real_t)p.y);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE, ladrc_axis_get_faults(&axis));
        TEST_ASSERT_EQUAL_FLOAT(u, held);
        const ladrc_real_t bad =
            axis_command_with_rate(&axis, LADRC_R(0.05), (ladrc_real_t)p.y, (k & 1) ? (ladrc_real_t)NAN : LADRC_R(1e3));
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE, ladrc_axis_get_faults(&axis));
        TEST_ASSERT_EQUAL_FLOAT(u, bad);
    }
}

static void test_rate_gaps_keep_the_filters_synchronised(void)
{
    /* given: every third tick without a rate, a constant 20 rad/s^2 */
    ladrc_axis_config_t cfg = config();
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p;
    plant_init(&p, 0.0, 0);
    double worst = 0.0;
    for (int k = 0; k < 6000; ++k) {
        const double u =
            (k % 3 == 2) ? (double)axis_command(&axis, LADRC_R(0.1), (ladrc_real_t)p.y) : (double)tick(&axis, &p, 0.1);
        plant_step(&p, u, 20.0);
        if (k >= 5500)
            worst = fmax(worst, fabs(0.1 - p.y));
    }
    ladrc_real_t y, w, dist;
    ladrc_axis_get_estimate(&axis, &y, &w, &dist);
    printf("rate gaps: error %.3e rad, estimate %.6f rad/s^2\n", worst, (double)dist);
    /* then: the means over each gap still pair up: no steady error, true d */
    TEST_ASSERT_TRUE(worst < STEADY_ERROR_RAD);
    TEST_ASSERT_FLOAT_WITHIN(DIST_REL_TOL * 20.0, 20.0, (double)dist);
}

/* A run of n ticks from the axis's present state; outputs into u. */
static void run(ladrc_axis_t *axis, plant_t *p, int from, int n, ladrc_real_t *u)
{
    for (int k = from; k < from + n; ++k) {
        const double t = k * DT_S;
        u[k] = tick(axis, p, 0.2 * sin(2.0 * t));
        ladrc_axis_set_applied(axis, u[k]);
        plant_step(p, (double)u[k], 5.0 + 30.0 * sin(3.0 * t));
    }
}

static void test_split_runs_are_bit_identical(void)
{
    enum { N = 3000, SPLIT = 1234 };
    static ladrc_real_t whole[N], split[N], again[N];
    ladrc_axis_config_t cfg = config();
    cfg.shaper = LADRC_SHAPER_TD;
    cfg.motor_tau_s = LADRC_R(0.02);
    cfg.delay_ticks = 1u;
    static ladrc_axis_t a, b, c;
    plant_t pa, pb, pc;
    /* one run */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&a, &cfg));
    plant_init(&pa, 0.02, 1);
    run(&a, &pa, 0, N, whole);
    /* the same split across a copy of the state */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&b, &cfg));
    plant_init(&pb, 0.02, 1);
    run(&b, &pb, 0, SPLIT, split);
    c = b;
    run(&c, &pb, SPLIT, N - SPLIT, split);
    TEST_ASSERT_EQUAL_MEMORY(whole, split, sizeof whole);
    /* a used axis re-initialised, and one reset at 0, fly the first run again */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&a, &cfg));
    plant_init(&pa, 0.02, 1);
    run(&a, &pa, 0, N, again);
    TEST_ASSERT_EQUAL_MEMORY(whole, again, sizeof whole);
    ladrc_axis_reset(&c, LADRC_R(0.0));
    plant_init(&pc, 0.02, 1);
    run(&c, &pc, 0, N, again);
    TEST_ASSERT_EQUAL_MEMORY(whole, again, sizeof whole);
}

static void test_a_non_finite_result_restarts_at_rest(void)
{
    /* given: b0 at its smallest (J = 1000 kg m^2) and the largest finite
     * rates: the command overflows float */
    ladrc_axis_config_t cfg = config();
    cfg.b0 = LADRC_R(1e-3);
    cfg.rate_limit_rad_s = LADRC_REAL_MAX;
    cfg.indi_rate_kp_per_s = LADRC_R(900.0);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    const ladrc_real_t u0 = axis_command_with_rate(&axis, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0));
    const ladrc_real_t u1 = axis_command_with_rate(&axis, LADRC_R(0.0), LADRC_R(0.0), LADRC_REAL_MAX);
    TEST_ASSERT_TRUE((ladrc_axis_get_faults(&axis) & LADRC_FAULT_STATE) != 0u);
    TEST_ASSERT_EQUAL_FLOAT(u0, u1);
    TEST_ASSERT_EQUAL_INT(0, axis.part.indi.has_rate_last);
    /* the next good ticks fly on */
    const ladrc_real_t u2 = axis_command_with_rate(&axis, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
    TEST_ASSERT_TRUE(isfinite((double)u2));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_follow_the_stated_rule);
    RUN_TEST(test_init_names_the_bad_field);
    RUN_TEST(test_a_constant_disturbance_leaves_no_steady_error);
    RUN_TEST(test_the_modelled_actuator_keeps_the_pair_synchronised);
    RUN_TEST(test_disturbance_response_matches_its_transfer_function);
    RUN_TEST(test_saturation_winds_nothing_up);
    RUN_TEST(test_without_a_rate_the_command_is_held_and_flagged);
    RUN_TEST(test_rate_gaps_keep_the_filters_synchronised);
    RUN_TEST(test_split_runs_are_bit_identical);
    RUN_TEST(test_a_non_finite_result_restarts_at_rest);
    return UNITY_END();
}
