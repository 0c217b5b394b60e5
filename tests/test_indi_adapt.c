/* SPDX-License-Identifier: BSD-3-Clause */
/* INDI with its control effectiveness adapted online (indi.h): on a rigid
 * axis behind a first-order motor lag, simulated here exactly sampled in
 * double precision, the estimate follows a 30 % rise and a 30 % fall of the
 * true effectiveness, never leaves its bounds, holds without excitation and
 * on non-finite samples, does not move with the adaptation off; bad values
 * of the new fields are refused with their own status. */
#include "unity.h"
#include "test_plant.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "ladrc/indi.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S 0.001
#define J_KG_M2 5.445e-3 /* paper vehicle, roll axis: b0 = 1 / J = 183.7 rad/s^2 per N m */
#define MOTOR_TAU_S 0.02 /* the plant's motor lag, and the axis's model of it */

/* The acceptance bars: within 10 % of the true effectiveness within 5 s of a change. */
#define ADAPT_REL_TOL 0.10
#define ADAPT_TIME_S 5.0
/* Where the estimate ends, 10 s after the change, on the noiseless plant:
 * the identity domegadot_f = G du_f holds there to the float rounding of
 * the filters' increments (a few 1e-6 relative at the threshold), which the
 * LMS averages (1e-6 measured); 1 % is far from both. */
#define FINAL_REL_TOL 0.01

/* Where the estimate ends through gyro noise of up to 1e-2 rad/s per sample
 * (three times a hobby-grade MEMS gyro's at 1 kHz): the noise that passes
 * the filter F and the threshold jitters the LMS's average, by up to 1.9 %
 * at that level (measured); 5 % leaves room. */
#define NOISY_FINAL_REL_TOL 0.05

/* Without excitation, gyro noise of 3e-3 rad/s alone: its increments stay
 * below the threshold (none passed it in this run); should a few pass, they
 * must move G by far less than the acceptance bar of 10 %: 2 %. */
#define NOISE_DRIFT_TOL 0.02

void setUp(void)
{
}
void tearDown(void)
{
}

/* omega' = g_true m + d with the motor lag m' = (u - m) / tau, stepped
 * exactly for u held over the tick (test_lag_step gives the increments per
 * unit of 1/J; here per unit of g_true). */
typedef struct {
    double y, w, m; /* angle (rad), rate (rad/s), acting torque (N m) */
    double g_true;  /* true effectiveness (rad/s^2 per N m) */
    double d;       /* constant disturbance (rad/s^2) */
} plant_t;

static void plant_step(plant_t *p, double u)
{
    double dy, dw;
    test_lag_step(DT_S, MOTOR_TAU_S, u, &p->m, &dy, &dw);
    p->y += p->w * DT_S + p->g_true * dy + 0.5 * p->d * DT_S * DT_S;
    p->w += p->g_true * dw + p->d * DT_S;
}

static ladrc_axis_config_t adapt_config(uint8_t adapt)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_INDI, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.motor_tau_s = (ladrc_real_t)MOTOR_TAU_S;
    cfg.indi_adapt = adapt;
    return cfg;
}

/* Gyro noise: uniform, zero mean, of standard deviation sigma (rad/s), from a
 * fixed-seed generator (the run is the same every time). */
static double noise(uint64_t *state, double sigma)
{
    *state = *state * UINT64_C(6364136223846793005) + UINT64_C(1442695040888963407);
    const double u = (double)(*state >> 11) / 9007199254740992.0; /* 53 bits: [0, 1) */
    return sigma * sqrt(12.0) * (u - 0.5);
}

/* The exciting reference: +-0.2 rad steps every 0.5 s through the TD. */
static double reference_at(double t_s)
{
    return (((long)(t_s / 0.5)) % 2 == 0) ? 0.2 : -0.2;
}

typedef struct {
    double settle_s;  /* first time after the change from which the estimate stays within ADAPT_REL_TOL */
    double final_rel; /* |G - g_true| / g_true at the end */
    double worst_rel; /* largest relative error after the settling time */
    int left_bounds;  /* 1 if the estimate ever left [b0 / 4, 4 b0] */
} adapt_run_t;

/* Flies change_s of the nominal plant, then end_s - change_s with the true
 * effectiveness times ratio, on the steps, the disturbance d (rad/s^2) and
 * gyro noise of gyro_sigma_rad_s. Returns the estimate's record after the
 * change. */
static adapt_run_t fly(const ladrc_axis_config_t *cfg, double ratio, double change_s, double end_s, double d,
                       double gyro_sigma_rad_s)
{
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, cfg));
    const double b0 = (double)cfg->b0;
    plant_t p = {.y = 0.0, .w = 0.0, .m = 0.0, .g_true = b0, .d = d};
    adapt_run_t run = {.settle_s = -1.0, .final_rel = 0.0, .worst_rel = 0.0, .left_bounds = 0};
    uint64_t seed = 12345u;
    const long n = (long)(end_s / DT_S + 0.5);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * DT_S;
        if (t >= change_s) {
            p.g_true = ratio * b0;
        }
        const double gyro = p.w + noise(&seed, gyro_sigma_rad_s);
        const ladrc_real_t u =
            axis_command_with_rate(&axis, (ladrc_real_t)reference_at(t), (ladrc_real_t)p.y, (ladrc_real_t)gyro);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
        plant_step(&p, (double)u);
        const double g = (double)ladrc_axis_get_effectiveness(&axis);
        TEST_ASSERT_TRUE(g == (double)ladrc_indi_get_effectiveness(&axis.part.indi));
        /* the bounds, to the float rounding of b0 / 4 and 4 b0 */
        if (g < 0.25 * b0 * (1.0 - 1e-6) || g > 4.0 * b0 * (1.0 + 1e-6)) {
            run.left_bounds = 1;
        }
        if (t >= change_s) {
            const double rel = fabs(g - p.g_true) / p.g_true;
            if (rel > ADAPT_REL_TOL) {
                run.settle_s = -1.0; /* not yet, or left again */
            } else if (run.settle_s < 0.0) {
                run.settle_s = t - change_s;
            }
            run.final_rel = rel;
        }
    }
    return run;
}

static void test_estimate_follows_a_30_percent_change_within_5_s(void)
{
    static const double ratios[2] = {1.3, 0.7};
    for (int i = 0; i < 2; ++i) {
        /* given: the adaptation on at its defaults, the true effectiveness
         * 30 % up (then down) from b0 at t = 2 s; when: 12 s of steps */
        const ladrc_axis_config_t cfg = adapt_config(1u);
        const adapt_run_t run = fly(&cfg, ratios[i], 2.0, 12.0, 0.0, 0.0);
        printf("true effectiveness x %.1f: within 10 %% after %.3f s, final error %.4f %%\n", ratios[i], run.settle_s,
               100.0 * run.final_rel);
        /* then */
        TEST_ASSERT_FALSE(run.left_bounds);
        TEST_ASSERT_TRUE(run.settle_s >= 0.0 && run.settle_s <= ADAPT_TIME_S);
        TEST_ASSERT_TRUE(run.final_rel <= FINAL_REL_TOL);
    }
}

static void test_estimate_follows_through_gyro_noise(void)
{
    /* given: white gyro noise of 1e-3, 3e-3 and 1e-2 rad/s; when: a 30 %
     * rise (then fall) at 2 s, 10 s of steps after it */
    static const double sigmas[3] = {1e-3, 3e-3, 1e-2};
    static const double ratios[2] = {1.3, 0.7};
    for (int s = 0; s < 3; ++s) {
        for (int i = 0; i < 2; ++i) {
            const ladrc_axis_config_t cfg = adapt_config(1u);
            const adapt_run_t run = fly(&cfg, ratios[i], 2.0, 12.0, 0.0, sigmas[s]);
            printf("noise %.0e rad/s, x %.1f: within 10 %% after %.3f s, final error %.3f %%\n", sigmas[s], ratios[i],
                   run.settle_s, 100.0 * run.final_rel);
            TEST_ASSERT_FALSE(run.left_bounds);
            TEST_ASSERT_TRUE(run.settle_s >= 0.0 && run.settle_s <= ADAPT_TIME_S);
            TEST_ASSERT_TRUE(run.final_rel <= NOISY_FINAL_REL_TOL);
        }
    }
}

static void test_estimate_follows_under_a_constant_disturbance(void)
{
    /* given: the paper's 20 rad/s^2 bias on the axis (steady, so its
     * increments vanish once the filters settled); when: a 30 % rise */
    const ladrc_axis_config_t cfg = adapt_config(1u);
    const adapt_run_t run = fly(&cfg, 1.3, 2.0, 12.0, 20.0, 0.0);
    printf("with a 20 rad/s^2 bias: within 10 %% after %.3f s, final error %.3f %%\n", run.settle_s,
           100.0 * run.final_rel);
    /* then */
    TEST_ASSERT_FALSE(run.left_bounds);
    TEST_ASSERT_TRUE(run.settle_s >= 0.0 && run.settle_s <= ADAPT_TIME_S);
}

static void test_estimate_stays_within_its_bounds(void)
{
    /* given: a true effectiveness 8 times b0 (above the bound 4 b0), then
     * one 8 times below (under b0 / 4) */
    static const double ratios[2] = {8.0, 0.125};
    for (int i = 0; i < 2; ++i) {
        const ladrc_axis_config_t cfg = adapt_config(1u);
        const adapt_run_t run = fly(&cfg, ratios[i], 1.0, 8.0, 0.0, 0.0);
        /* then: the estimate goes to the bound and no further */
        TEST_ASSERT_FALSE(run.left_bounds);
    }
    /* and a narrower pair of bounds, [0.9, 1.1] b0, holds a 30 % change at 1.1 b0 */
    ladrc_axis_config_t cfg = adapt_config(1u);
    cfg.indi_adapt_min_ratio = LADRC_R(0.9);
    cfg.indi_adapt_max_ratio = LADRC_R(1.1);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p = {.y = 0.0, .w = 0.0, .m = 0.0, .g_true = 1.3 * (double)cfg.b0, .d = 0.0};
    double highest = 0.0;
    for (long k = 0; k < 5000; ++k) {
        const ladrc_real_t u = axis_command_with_rate(&axis, (ladrc_real_t)reference_at((double)k * DT_S),
                                                      (ladrc_real_t)p.y, (ladrc_real_t)p.w);
        plant_step(&p, (double)u);
        highest = fmax(highest, (double)ladrc_axis_get_effectiveness(&axis));
    }
    TEST_ASSERT_TRUE(highest <= (double)(cfg.b0 * cfg.indi_adapt_max_ratio));
    TEST_ASSERT_TRUE(highest >= (double)(cfg.b0 * cfg.indi_adapt_max_ratio)); /* it got there */
}

static void test_without_excitation_the_estimate_holds(void)
{
    /* given: a slow sway, 0.01 rad at 0.2 Hz (its jerk, 0.02 rad/s^3, far
     * below the 50 rad/s^3 threshold), the true effectiveness 30 % up from
     * the start; when: 5 s */
    const ladrc_axis_config_t cfg = adapt_config(1u);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p = {.y = 0.0, .w = 0.0, .m = 0.0, .g_true = 1.3 * (double)cfg.b0, .d = 0.0};
    for (long k = 0; k < 5000; ++k) {
        const double ref = 0.01 * sin(2.0 * 3.14159265358979323846 * 0.2 * (double)k * DT_S);
        const ladrc_real_t u = axis_command_with_rate(&axis, (ladrc_real_t)ref, (ladrc_real_t)p.y, (ladrc_real_t)p.w);
        plant_step(&p, (double)u);
        /* then: below the excitation threshold nothing is learnt */
        TEST_ASSERT_TRUE(ladrc_axis_get_effectiveness(&axis) == cfg.b0);
    }
    /* and with gyro noise of 3e-3 rad/s the noise alone barely moves it */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t q = {.y = 0.0, .w = 0.0, .m = 0.0, .g_true = 1.3 * (double)cfg.b0, .d = 0.0};
    uint64_t seed = 777u;
    double drift = 0.0;
    for (long k = 0; k < 5000; ++k) {
        const double ref = 0.01 * sin(2.0 * 3.14159265358979323846 * 0.2 * (double)k * DT_S);
        const ladrc_real_t u = axis_command_with_rate(&axis, (ladrc_real_t)ref, (ladrc_real_t)q.y,
                                                      (ladrc_real_t)(q.w + noise(&seed, 3e-3)));
        plant_step(&q, (double)u);
        drift = fmax(drift, fabs((double)ladrc_axis_get_effectiveness(&axis) / (double)cfg.b0 - 1.0));
    }
    printf("slow sway, gyro noise 3e-3 rad/s: the estimate drifted %.3f %% at most\n", 100.0 * drift);
    TEST_ASSERT_TRUE(drift <= NOISE_DRIFT_TOL);
}

static void test_with_the_adaptation_off_the_estimate_never_moves(void)
{
    /* given: the default (off), a 30 % change and the exciting steps */
    const ladrc_axis_config_t cfg = adapt_config(0u);
    TEST_ASSERT_EQUAL_UINT8(0u, cfg.indi_adapt);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    plant_t p = {.y = 0.0, .w = 0.0, .m = 0.0, .g_true = 1.3 * (double)cfg.b0, .d = 0.0};
    for (long k = 0; k < 5000; ++k) {
        const ladrc_real_t u = axis_command_with_rate(&axis, (ladrc_real_t)reference_at((double)k * DT_S),
                                                      (ladrc_real_t)p.y, (ladrc_real_t)p.w);
        plant_step(&p, (double)u);
        /* then */
        TEST_ASSERT_TRUE(ladrc_axis_get_effectiveness(&axis) == cfg.b0);
        TEST_ASSERT_TRUE(axis.part.indi.j == LADRC_R(1.0) / cfg.b0);
    }
}

static void test_non_finite_samples_leave_the_estimate(void)
{
    /* given: the module alone, adapting, after 200 excited steps */
    const ladrc_indi_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                     .b0 = LADRC_R(100.0),
                                     .att_kp_per_s = LADRC_R(15.0),
                                     .rate_kp_per_s = LADRC_R(15.0),
                                     .filter_rad_s = LADRC_R(75.0),
                                     .adapt = 1u,
                                     .adapt_mu = LADRC_R(0.01),
                                     .adapt_jerk_min_rad_s3 = LADRC_R(50.0),
                                     .adapt_min_ratio = LADRC_R(0.25),
                                     .adapt_max_ratio = LADRC_R(4.0)};
    ladrc_indi_t indi;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_indi_init(&indi, &cfg));
    /* a plant of effectiveness 130 with the torque ramping: omega_k = 130 sum u */
    double w = 0.0;
    for (int k = 0; k < 200; ++k) {
        const double u = 0.01 * k;
        w += 130.0 * u * DT_S;
        const ladrc_real_t rate = (ladrc_real_t)w;
        TEST_ASSERT_EQUAL_INT(1, ladrc_indi_measure(&indi, (ladrc_real_t)u, &rate));
    }
    const ladrc_real_t learnt = ladrc_indi_get_effectiveness(&indi);
    TEST_ASSERT_TRUE(learnt > LADRC_R(100.0)); /* it moved toward 130 */
    /* when: a NaN rate, then an infinite torque */
    const ladrc_real_t nan_rate = (ladrc_real_t)NAN, rate = (ladrc_real_t)w;
    (void)ladrc_indi_measure(&indi, LADRC_R(2.0), &nan_rate);
    /* then: the estimate keeps its last good value */
    TEST_ASSERT_TRUE(ladrc_indi_get_effectiveness(&indi) == learnt);
    TEST_ASSERT_TRUE(isfinite((double)indi.j));
    (void)ladrc_indi_measure(&indi, (ladrc_real_t)INFINITY, &rate);
    TEST_ASSERT_TRUE(ladrc_indi_get_effectiveness(&indi) == learnt);
    /* a reset restarts it at b0 */
    ladrc_indi_reset(&indi);
    TEST_ASSERT_TRUE(ladrc_indi_get_effectiveness(&indi) == cfg.b0);
    TEST_ASSERT_TRUE(indi.j == LADRC_R(1.0) / cfg.b0);
}

static void test_a_negative_b0_keeps_its_sign(void)
{
    /* given: b0 < 0 (a torque axis mounted reversed), bounds [4 b0, b0 / 4] */
    ladrc_indi_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                               .b0 = LADRC_R(-100.0),
                               .att_kp_per_s = LADRC_R(15.0),
                               .rate_kp_per_s = LADRC_R(15.0),
                               .filter_rad_s = LADRC_R(75.0),
                               .adapt = 1u,
                               .adapt_mu = LADRC_R(0.05),
                               .adapt_jerk_min_rad_s3 = LADRC_R(50.0),
                               .adapt_min_ratio = LADRC_R(0.25),
                               .adapt_max_ratio = LADRC_R(4.0)};
    ladrc_indi_t indi;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_indi_init(&indi, &cfg));
    TEST_ASSERT_TRUE(indi.g_lo == LADRC_R(-400.0) && indi.g_hi == LADRC_R(-25.0));
    /* when: the plant's effectiveness is +130 (the wrong sign) */
    double w = 0.0;
    for (int k = 0; k < 2000; ++k) {
        const double u = 0.01 * sin(0.01 * k);
        w += 130.0 * u * DT_S;
        const ladrc_real_t rate = (ladrc_real_t)w;
        (void)ladrc_indi_measure(&indi, (ladrc_real_t)u, &rate);
        /* then: the estimate stays negative, within its bounds */
        TEST_ASSERT_TRUE(indi.g >= LADRC_R(-400.0) && indi.g <= LADRC_R(-25.0));
    }
}

static void test_init_refuses_bad_adaptation_fields_with_their_own_status(void)
{
    typedef struct {
        size_t offset;
        double value;
        ladrc_status_t expected;
    } bad_t;
#define FIELD(f) offsetof(ladrc_axis_config_t, f)
    const double inf = INFINITY, nan_ = NAN;
    const bad_t cases[] = {
        {FIELD(indi_adapt_mu), 0.0, LADRC_ERR_INDI_ADAPT_MU},
        {FIELD(indi_adapt_mu), -0.1, LADRC_ERR_INDI_ADAPT_MU},
        {FIELD(indi_adapt_mu), 1.5, LADRC_ERR_INDI_ADAPT_MU},
        {FIELD(indi_adapt_mu), nan_, LADRC_ERR_INDI_ADAPT_MU},
        {FIELD(indi_adapt_jerk_min_rad_s3), 0.0, LADRC_ERR_INDI_ADAPT_EXCITATION},
        {FIELD(indi_adapt_jerk_min_rad_s3), -1.0, LADRC_ERR_INDI_ADAPT_EXCITATION},
        {FIELD(indi_adapt_jerk_min_rad_s3), inf, LADRC_ERR_INDI_ADAPT_EXCITATION},
        {FIELD(indi_adapt_jerk_min_rad_s3), nan_, LADRC_ERR_INDI_ADAPT_EXCITATION},
        {FIELD(indi_adapt_min_ratio), 0.0, LADRC_ERR_INDI_ADAPT_MIN},
        {FIELD(indi_adapt_min_ratio), 1.5, LADRC_ERR_INDI_ADAPT_MIN},
        {FIELD(indi_adapt_min_ratio), nan_, LADRC_ERR_INDI_ADAPT_MIN},
        {FIELD(indi_adapt_min_ratio), 1e-6, LADRC_ERR_INDI_ADAPT_MIN}, /* |b0| 1e-6 below 1e-3 */
        {FIELD(indi_adapt_max_ratio), 0.5, LADRC_ERR_INDI_ADAPT_MAX},
        {FIELD(indi_adapt_max_ratio), inf, LADRC_ERR_INDI_ADAPT_MAX},
        {FIELD(indi_adapt_max_ratio), nan_, LADRC_ERR_INDI_ADAPT_MAX},
        {FIELD(indi_adapt_max_ratio), 1e6, LADRC_ERR_INDI_ADAPT_MAX}, /* |b0| 1e6 above 1e7 */
    };
#undef FIELD
    ladrc_axis_t axis;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ladrc_axis_config_t cfg = adapt_config(1u);
        *(ladrc_real_t *)(void *)((char *)&cfg + cases[i].offset) = (ladrc_real_t)cases[i].value;
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].expected, ladrc_axis_init(&axis, &cfg), "case");
        /* with the adaptation off the same values are not read */
        cfg.indi_adapt = 0u;
        TEST_ASSERT_EQUAL_INT_MESSAGE(LADRC_OK, ladrc_axis_init(&axis, &cfg), "off");
    }
    ladrc_axis_config_t cfg = adapt_config(2u);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_INDI_ADAPT, ladrc_axis_init(&axis, &cfg));
    /* the defaults and the edges are good: mu 1, bounds [b0, b0] */
    cfg = adapt_config(1u);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    cfg.indi_adapt_mu = LADRC_R(1.0);
    cfg.indi_adapt_min_ratio = LADRC_R(1.0);
    cfg.indi_adapt_max_ratio = LADRC_R(1.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    /* a jerk threshold whose torque threshold vanishes in the real type */
    cfg = adapt_config(1u);
    cfg.b0 = LADRC_R(1e7);
    cfg.indi_adapt_max_ratio = LADRC_R(1.0);
    cfg.indi_adapt_jerk_min_rad_s3 = LADRC_REAL_MIN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_INDI_ADAPT_EXCITATION, ladrc_axis_init(&axis, &cfg));
    TEST_ASSERT_TRUE(strstr(ladrc_status_str(LADRC_ERR_INDI_ADAPT_MU), "LADRC_ERR_INDI_ADAPT_MU") != NULL);
}

static void test_getters_give_safe_values_for_null(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    TEST_ASSERT_TRUE(ladrc_indi_get_effectiveness(NULL) == LADRC_R(0.0));
    TEST_ASSERT_TRUE(ladrc_axis_get_effectiveness(NULL) == LADRC_R(0.0));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_estimate_follows_a_30_percent_change_within_5_s);
    RUN_TEST(test_estimate_follows_through_gyro_noise);
    RUN_TEST(test_estimate_follows_under_a_constant_disturbance);
    RUN_TEST(test_estimate_stays_within_its_bounds);
    RUN_TEST(test_without_excitation_the_estimate_holds);
    RUN_TEST(test_with_the_adaptation_off_the_estimate_never_moves);
    RUN_TEST(test_non_finite_samples_leave_the_estimate);
    RUN_TEST(test_a_negative_b0_keeps_its_sign);
    RUN_TEST(test_init_refuses_bad_adaptation_fields_with_their_own_status);
    RUN_TEST(test_getters_give_safe_values_for_null);
    return UNITY_END();
}
