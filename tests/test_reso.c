/* SPDX-License-Identifier: BSD-3-Clause */
/* RESO (reso.h): its ZOH discretisation against the continuous observer,
 * pole placement, disturbance estimation, known inputs, validation and
 * fault handling. */
#include "unity.h"
#include "ladrc/reso.h"

#include <math.h>
#include <string.h>

/* Finite, yet a sum of two of them overflows the real type (float or double). */
#define BIG_REAL (LADRC_REAL_MAX * LADRC_R(0.9))

#define DT_S 1e-3
#define WO_RAD_S 200.0
/* Paper vehicle roll inertia: b0 = 1/Jx rad/s^2 per N m. */
#define B0 (1.0 / 5.445e-3)

/* Residual of the pole recurrence relative to the error's peak: float
 * rounding through two steps stays near 1e-7; a pole misplaced by 0.1 %
 * leaves about 1e-3. */
#define RECURRENCE_REL_TOL 2e-5
/* Constant 30 rad/s^2 after 0.5 s (100 time constants): float rounding of
 * the rate (ulp 6e-8 rad/s near 0.5 rad/s) times l2 = 30 per step. */
#define DISTURBANCE_TOL_RAD_S2 2e-3
/* Discrete against continuous observer on a smooth signal: they differ by
 * O(wo h) of the signal's change per time constant; at wo h = 0.02 the
 * measured gap is 0.3 % of the disturbance's amplitude. */
#define CONTINUOUS_REL_TOL 2e-2

static ladrc_reso_config_t config(double dt_s, double wo_rad_s)
{
    const ladrc_reso_config_t cfg = {
        .dt_s = (ladrc_real_t)dt_s, .wo_rad_s = (ladrc_real_t)wo_rad_s, .b0 = (ladrc_real_t)B0};
    return cfg;
}

void setUp(void)
{
}
void tearDown(void)
{
}

static void test_gains_tend_to_the_continuous_gains_as_h_shrinks(void)
{
    /* given the continuous gains 2 wo and wo^2 (reso.h) */
    const double hs[] = {1e-3, 1e-4, 1e-5};
    double prev_gap = INFINITY;
    for (size_t i = 0; i < sizeof hs / sizeof hs[0]; ++i) {
        ladrc_reso_t obs;
        const ladrc_reso_config_t cfg = config(hs[i], WO_RAD_S);
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&obs, &cfg));
        /* then l1 / h -> 2 wo and l2 / h -> wo^2 at first order in wo h */
        const double g1 = obs.l1 / hs[i] / (2.0 * WO_RAD_S) - 1.0;
        const double g2 = obs.l2 / hs[i] / (WO_RAD_S * WO_RAD_S) - 1.0;
        const double gap = fmax(fabs(g1), fabs(g2));
        TEST_ASSERT_TRUE(gap < 1.5 * WO_RAD_S * hs[i] + 1e-5);
        TEST_ASSERT_TRUE(gap < prev_gap);
        prev_gap = gap;
    }
}

/* Errors e_k = x_k - z_k of the observer on an exact plant w' = f + b0 u
 * (u held over each step, f constant: the ZOH model is exact). */
static void record_errors(double f, int n, double err[][2])
{
    ladrc_reso_t obs;
    const ladrc_reso_config_t cfg = config(DT_S, WO_RAD_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&obs, &cfg));
    double w = 0.5;
    double u = 0.0;
    for (int k = 0; k < n; ++k) {
        w += DT_S * (f + B0 * u);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_reso_step(&obs, (ladrc_real_t)w, (ladrc_real_t)u, 0.0f, 0.0f));
        err[k][0] = w - ladrc_reso_get_rate(&obs);
        err[k][1] = f - ladrc_reso_get_disturbance(&obs);
        u = (-f + 5.0 * sin(0.05 * k)) / B0; /* any input works */
    }
}

static void test_error_decays_as_a_double_pole_at_exp_minus_wo_h(void)
{
    enum { N = 60 };
    static double err[N][2];
    record_errors(30.0, N, err);
    const double beta = exp(-WO_RAD_S * DT_S);
    for (int c = 0; c < 2; ++c) {
        double scale = 0.0;
        for (int k = 0; k < N; ++k) {
            scale = fmax(scale, fabs(err[k][c]));
        }
        TEST_ASSERT_TRUE(scale > 1e-3);
        /* then (q - beta)^2 e = 0 while the error is well above rounding */
        for (int k = 0; k + 2 < 15; ++k) {
            const double r = err[k + 2][c] - 2.0 * beta * err[k + 1][c] + beta * beta * err[k][c];
            TEST_ASSERT_FLOAT_WITHIN(RECURRENCE_REL_TOL, 0.0, r / scale);
        }
    }
}

static void test_constant_disturbance_is_estimated(void)
{
    enum { N = 500 };
    static double err[N][2];
    record_errors(30.0, N, err);
    TEST_ASSERT_FLOAT_WITHIN(DISTURBANCE_TOL_RAD_S2, 0.0, err[N - 1][1]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4, 0.0, err[N - 1][0]);
}

/* The continuous observer z' = A z + L (w - z1) + B a of reso.h, RK4 on a
 * continuous measurement, against the discrete one on its samples. */
typedef struct {
    double z1, z2;
} cont_t;

static double signal_rate(double t)
{
    return 0.3 * sin(4.0 * t) + 0.1 * t;
}

static void cont_deriv(const cont_t *z, double t, double a, double wo, cont_t *dz)
{
    const double e = signal_rate(t) - z->z1;
    dz->z1 = z->z2 + 2.0 * wo * e + a;
    dz->z2 = wo * wo * e;
}

static void test_discretisation_follows_the_continuous_observer(void)
{
    /* given a rate w(t) = 0.3 sin 4t + 0.1 t, the true f = w' - b0 u */
    const double h = 1e-4, wo = WO_RAD_S;
    ladrc_reso_t obs;
    const ladrc_reso_config_t cfg = config(h, wo);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&obs, &cfg));
    cont_t z = {0.0, 0.0};
    const double u = 0.02; /* a constant torque, so the input is held exactly */
    const double a = B0 * u;
    double worst = 0.0;
    const int n = 10000;
    for (int k = 1; k <= n; ++k) {
        const double t0 = (k - 1) * h;
        const int sub = 20;
        const double hs = h / sub;
        for (int s = 0; s < sub; ++s) {
            const double t = t0 + s * hs;
            cont_t k1, k2, k3, k4, m;
            cont_deriv(&z, t, a, wo, &k1);
            m = (cont_t){z.z1 + 0.5 * hs * k1.z1, z.z2 + 0.5 * hs * k1.z2};
            cont_deriv(&m, t + 0.5 * hs, a, wo, &k2);
            m = (cont_t){z.z1 + 0.5 * hs * k2.z1, z.z2 + 0.5 * hs * k2.z2};
            cont_deriv(&m, t + 0.5 * hs, a, wo, &k3);
            m = (cont_t){z.z1 + hs * k3.z1, z.z2 + hs * k3.z2};
            cont_deriv(&m, t + hs, a, wo, &k4);
            z.z1 += hs / 6.0 * (k1.z1 + 2.0 * k2.z1 + 2.0 * k3.z1 + k4.z1);
            z.z2 += hs / 6.0 * (k1.z2 + 2.0 * k2.z2 + 2.0 * k3.z2 + k4.z2);
        }
        ladrc_reso_step(&obs, (ladrc_real_t)signal_rate(k * h), (ladrc_real_t)u, 0.0f, 0.0f);
        if (k * h > 0.1) { /* past both observers' start (20 time constants) */
            worst = fmax(worst, fabs(ladrc_reso_get_disturbance(&obs) - z.z2));
        }
    }
    /* then both estimate f = w' - b0 u (amplitude 1.2 rad/s^2 around -3.6) alike */
    const double f_amp = 0.3 * 4.0;
    TEST_ASSERT_TRUE(worst < CONTINUOUS_REL_TOL * f_amp);
    const double t_end = n * h;
    const double f_true = 1.2 * cos(4.0 * t_end) + 0.1 - a;
    TEST_ASSERT_FLOAT_WITHIN(0.05 * f_amp, f_true, ladrc_reso_get_disturbance(&obs));
}

static void test_known_inputs_remove_the_lag_on_a_ramp(void)
{
    /* given f = g t, the observer told g (and a known acceleration) */
    const double g = 200.0, known = 3.0;
    ladrc_reso_t obs, blind;
    const ladrc_reso_config_t cfg = config(DT_S, WO_RAD_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&obs, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&blind, &cfg));
    double w = 0.0;
    for (int k = 0; k < 300; ++k) {
        const double t0 = k * DT_S;
        /* exact: w' = known + g t over the step */
        w += known * DT_S + g * (t0 * DT_S + 0.5 * DT_S * DT_S);
        ladrc_reso_step(&obs, (ladrc_real_t)w, 0.0f, (ladrc_real_t)known, (ladrc_real_t)g);
        ladrc_reso_step(&blind, (ladrc_real_t)w, 0.0f, (ladrc_real_t)known, 0.0f);
    }
    const double f_end = g * 300 * DT_S;
    /* then the informed observer has no lag; the blind one lags by 2 g / wo */
    TEST_ASSERT_FLOAT_WITHIN(1e-2, f_end, ladrc_reso_get_disturbance(&obs));
    TEST_ASSERT_FLOAT_WITHIN(0.05 * 2.0 * g / WO_RAD_S, f_end - 2.0 * g / WO_RAD_S, ladrc_reso_get_disturbance(&blind));
}

static void test_init_names_the_bad_field(void)
{
    ladrc_reso_t obs;
    ladrc_reso_config_t cfg = config(DT_S, WO_RAD_S);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_reso_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_reso_init(&obs, NULL));
    cfg.dt_s = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_reso_init(&obs, &cfg));
    cfg = config(DT_S, WO_RAD_S);
    cfg.wo_rad_s = NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_WO_RAD_S, ladrc_reso_init(&obs, &cfg));
    cfg.wo_rad_s = -1.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_WO_RAD_S, ladrc_reso_init(&obs, &cfg));
    cfg = config(DT_S, WO_RAD_S);
    cfg.b0 = 0.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_reso_init(&obs, &cfg));
    cfg.b0 = INFINITY;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_B0, ladrc_reso_init(&obs, &cfg));
}

static void test_non_finite_input_keeps_the_estimate(void)
{
    ladrc_reso_t obs;
    const ladrc_reso_config_t cfg = config(DT_S, WO_RAD_S);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_reso_init(&obs, &cfg));
    ladrc_reso_reset(&obs, 1.5f);
    ladrc_reso_step(&obs, 1.6f, 0.01f, 0.0f, 0.0f);
    ladrc_reso_t before;
    memcpy(&before, &obs, sizeof obs);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_reso_step(&obs, NAN, 0.0f, 0.0f, 0.0f));
    TEST_ASSERT_EQUAL_FLOAT(before.z1, obs.z1);
    TEST_ASSERT_EQUAL_FLOAT(before.z2, obs.z2);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_reso_step(&obs, 1.0f, INFINITY, 0.0f, 0.0f));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_reso_step(&obs, 1.0f, 0.0f, NAN, 0.0f));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_reso_step(&obs, 1.0f, 0.0f, 0.0f, -INFINITY));
    TEST_ASSERT_EQUAL_FLOAT(before.z2, obs.z2);
    /* finite inputs whose result overflows: a state fault, estimate kept */
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_STATE, ladrc_reso_step(&obs, BIG_REAL, BIG_REAL, BIG_REAL, 0.0f));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_STATE, obs.faults);
    TEST_ASSERT_EQUAL_FLOAT(before.z1, obs.z1);
    /* the next good step runs and clears the flags */
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_reso_step(&obs, 1.6f, 0.0f, 0.0f, 0.0f));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, obs.faults);
    ladrc_reso_reset(&obs, NAN);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, ladrc_reso_get_rate(&obs));
    TEST_ASSERT_EQUAL_FLOAT(0.0f, ladrc_reso_get_disturbance(&obs));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_gains_tend_to_the_continuous_gains_as_h_shrinks);
    RUN_TEST(test_error_decays_as_a_double_pole_at_exp_minus_wo_h);
    RUN_TEST(test_constant_disturbance_is_estimated);
    RUN_TEST(test_discretisation_follows_the_continuous_observer);
    RUN_TEST(test_known_inputs_remove_the_lag_on_a_ramp);
    RUN_TEST(test_init_names_the_bad_field);
    RUN_TEST(test_non_finite_input_keeps_the_estimate);
    return UNITY_END();
}
