/* SPDX-License-Identifier: BSD-3-Clause */
/* One axis in closed loop on a double-integrator test plant: settling,
 * disturbance rejection against the analytic transfer function, saturation
 * handling, validation, faults and determinism. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "test_plant.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3 /* paper vehicle, roll axis */
#define WC_RAD_S 15.0
#define WO_RAD_S 75.0
#define STEP_RAD 0.17453292519943295 /* 10 deg */
#define PLANT_SUBSTEPS 4

/* The LESO poles (5x faster) and the one-tick measurement-to-command path
 * shift settling from the ideal 5.834 / wc; the issue allows 15%. */
#define SETTLING_REL_TOL 0.15
/* Disturbance amplitude vs the continuous-time transfer function: the
 * issue allows 10%; sampling at 1 kHz (wo h = 0.075) costs about 1%. */
#define AMPLITUDE_REL_TOL 0.10
/* Steady error under a constant 20 rad/s^2: float rounding of the observer
 * only (z3 noise ~1e-4 rad/s^2 over wc^2 = 225 gives 1e-6 rad); 1e-5 rad. */
#define STEADY_ERROR_TOL_RAD 1e-5

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_axis_config_t ladrc_config(ladrc_shaper_t shaper)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.shaper = shaper;
    return cfg;
}

/* Closed loop: ref constant, plant disturbance d; records y per tick. */
typedef struct {
    double ref_rad;
    const test_sine_t *d;
    double torque_limit_Nm; /* the "mixer": clamp outside the axis, 0 = none */
    int report_applied;
} loop_t;

static void run_loop(ladrc_axis_t *axis, const loop_t *loop, int n, double *y, double *z3, double *peak_u)
{
    const test_sine_t none = {.bias = 0.0, .amp = 0.0, .w_rad_s = 0.0, .phase_rad = 0.0};
    test_double_integrator_t plant;
    test_plant_init(&plant, 1.0 / J_KG_M2, test_sine_disturbance, loop->d ? loop->d : &none);
    for (int k = 0; k < n; ++k) {
        double u = axis_command(axis, (ladrc_real_t)loop->ref_rad, (ladrc_real_t)plant.y_rad);
        if (loop->torque_limit_Nm > 0.0) {
            u = fmax(-loop->torque_limit_Nm, fmin(loop->torque_limit_Nm, u));
            if (loop->report_applied) {
                ladrc_axis_set_applied(axis, (ladrc_real_t)u);
            }
        }
        test_plant_step(&plant, u, DT_S, PLANT_SUBSTEPS);
        if (peak_u) {
            *peak_u = fmax(*peak_u, fabs(u));
        }
        if (y) {
            y[k] = plant.y_rad;
        }
        if (z3) {
            z3[k] = axis->leso.z3;
        }
    }
}

static double settling_time_s(const double *y, int n, double target, double band)
{
    int last_out = -1;
    for (int k = 0; k < n; ++k) {
        if (fabs(y[k] - target) > band) {
            last_out = k;
        }
    }
    return (last_out + 1) * DT_S;
}

static void test_ladrc_step_settles_as_its_closed_loop_poles_predict(void)
{
    /* given LADRC with raw reference (no shaping) on y'' = u / J */
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_NONE);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    enum { N = 2000 };
    static double y[N];
    const loop_t loop = {.ref_rad = STEP_RAD, .d = NULL, .torque_limit_Nm = 0.0, .report_applied = 0};
    /* when the reference steps by 10 deg */
    run_loop(&axis, &loop, N, y, NULL, NULL);
    /* then 2% settling matches the double pole at -wc: 5.834 / wc */
    const double ts = settling_time_s(y, N, STEP_RAD, 0.02 * STEP_RAD);
    const double predicted = 5.8339217 / WC_RAD_S;
    char msg[80];
    snprintf(msg, sizeof msg, "settling %.4f s, predicted %.4f s", ts, predicted);
    TEST_MESSAGE(msg);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(SETTLING_REL_TOL * predicted, predicted, ts, msg);
}

static void test_ladrc_rejects_a_constant_disturbance_to_zero_steady_error(void)
{
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&axis, &cfg);
    const test_sine_t d = {.bias = 20.0, .amp = 0.0, .w_rad_s = 0.0, .phase_rad = 0.0}; /* the paper's bias, rad/s^2 */
    enum { N = 3000 };
    static double y[N];
    const loop_t loop = {.ref_rad = 0.0, .d = &d, .torque_limit_Nm = 0.0, .report_applied = 0};
    run_loop(&axis, &loop, N, y, NULL, NULL);
    TEST_ASSERT_FLOAT_WITHIN(STEADY_ERROR_TOL_RAD, 0.0, y[N - 1]);
}

/* |Y/D|(jw) = w |(jw)^2 + a jw + b| / ((w^2 + wc^2) (w^2 + wo^2)^1.5) with
 * a = 2 wc + 3 wo and b = wc^2 + 2 wc 3 wo + 3 wo^2 (derived from the
 * observer error transfer functions; see docs/design.md). */
static double disturbance_gain(double w)
{
    const double wc = WC_RAD_S;
    const double wo = WO_RAD_S;
    const double a = 2.0 * wc + 3.0 * wo;
    const double b = wc * wc + 2.0 * wc * 3.0 * wo + 3.0 * wo * wo;
    const double num = w * hypot(b - w * w, a * w);
    const double den = (w * w + wc * wc) * pow(w * w + wo * wo, 1.5);
    return num / den;
}

static double sine_error_amplitude(double w_rad_s)
{
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&axis, &cfg);
    const test_sine_t d = {.bias = 0.0, .amp = 120.0, .w_rad_s = w_rad_s, .phase_rad = 0.0};
    const double period_s = 2.0 * 3.14159265358979 / w_rad_s;
    /* 2 s lets the loop transient (slowest pole -15 rad/s) fade to 1e-13 */
    const int n_settle = 2000;
    const int n = n_settle + (int)(2.0 * period_s / DT_S);
    static double y[40000];
    const loop_t loop = {.ref_rad = 0.0, .d = &d, .torque_limit_Nm = 0.0, .report_applied = 0};
    run_loop(&axis, &loop, n, y, NULL, NULL);
    double peak = 0.0;
    for (int k = n_settle; k < n; ++k) {
        peak = fmax(peak, fabs(y[k]));
    }
    return peak;
}

static void test_ladrc_sine_disturbance_error_matches_its_transfer_function(void)
{
    const double freqs[] = {3.0, 10.0, 40.0};
    for (unsigned i = 0; i < sizeof freqs / sizeof freqs[0]; ++i) {
        const double expected = 120.0 * disturbance_gain(freqs[i]);
        const double measured = sine_error_amplitude(freqs[i]);
        char msg[96];
        snprintf(msg, sizeof msg, "w %.0f rad/s: amplitude %.5f rad, predicted %.5f rad", freqs[i], measured, expected);
        TEST_MESSAGE(msg);
        TEST_ASSERT_FLOAT_WITHIN_MESSAGE(AMPLITUDE_REL_TOL * expected, expected, measured, msg);
    }
}

static double peak_torque_for_step(ladrc_shaper_t shaper)
{
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(shaper);
    ladrc_axis_init(&axis, &cfg);
    const loop_t loop = {.ref_rad = STEP_RAD, .d = NULL, .torque_limit_Nm = 0.0, .report_applied = 0};
    double peak = 0.0;
    run_loop(&axis, &loop, 1000, NULL, NULL, &peak);
    return peak;
}

static void test_td_shaping_lowers_the_torque_peak_of_a_reference_step(void)
{
    /* the first tick without shaping asks J wc^2 * step = 0.21 N m at once;
     * the default TD bounds the reference acceleration to 20 rad/s^2, whose
     * feedforward is J * 20 = 0.11 N m: the peak must fall by a third at least */
    const double raw = peak_torque_for_step(LADRC_SHAPER_NONE);
    const double shaped = peak_torque_for_step(LADRC_SHAPER_TD);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(raw * 2.0 / 3.0), (float)shaped);
}

static void test_observer_fed_the_applied_torque_does_not_wind_up(void)
{
    /* given an outside limit of 0.02 N m (3.7 rad/s^2) and a 30 deg step */
    enum { N = 3000 };
    static double z3_reported[N];
    static double z3_ignored[N];
    static double y[N];
    const loop_t reported = {.ref_rad = 3.0 * STEP_RAD, .d = NULL, .torque_limit_Nm = 0.02, .report_applied = 1};
    const loop_t ignored = {.ref_rad = 3.0 * STEP_RAD, .d = NULL, .torque_limit_Nm = 0.02, .report_applied = 0};
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&axis, &cfg);
    run_loop(&axis, &reported, N, y, z3_reported, NULL);
    const double y_final = y[N - 1];
    ladrc_axis_init(&axis, &cfg);
    run_loop(&axis, &ignored, N, NULL, z3_ignored, NULL);
    double worst_reported = 0.0;
    double worst_ignored = 0.0;
    for (int k = 0; k < N; ++k) {
        worst_reported = fmax(worst_reported, fabs(z3_reported[k]));
        worst_ignored = fmax(worst_ignored, fabs(z3_ignored[k]));
    }
    /* then the true disturbance (0) stays estimated within 1 rad/s^2 (the
     * TD's reference acceleration steps are the only excitation), whereas
     * an observer fed the unclamped command books the clamp as disturbance */
    TEST_ASSERT_LESS_THAN_FLOAT(1.0f, (float)worst_reported);
    TEST_ASSERT_GREATER_THAN_FLOAT(10.0f, (float)worst_ignored);
    /* and the loop still reaches the reference within 2% in 3 s */
    TEST_ASSERT_FLOAT_WITHIN(0.02 * 3.0 * STEP_RAD, 3.0 * STEP_RAD, y_final);
}

static void test_output_stays_within_the_configured_torque_limits(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_NONE);
    cfg.u_min_Nm = -0.01f;
    cfg.u_max_Nm = 0.03f;
    ladrc_axis_init(&axis, &cfg);
    for (int k = 0; k < 100; ++k) {
        const float u = (float)axis_command(&axis, (ladrc_real_t)(k < 50 ? 1.0 : -1.0), 0.0f);
        TEST_ASSERT_TRUE(u >= -0.01f && u <= 0.03f);
    }
}

static void test_pid_variant_settles_a_step_through_the_axis_api(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    enum { N = 5000 };
    static double y[N];
    const loop_t loop = {.ref_rad = STEP_RAD, .d = NULL, .torque_limit_Nm = 0.0, .report_applied = 0};
    run_loop(&axis, &loop, N, y, NULL, NULL);
    /* kp / J = 3673 s^-2 and kd / J = 9.2 s^-1: lightly damped but stable;
     * after 5 s (23 time constants of the 1 / (kd/J/2) envelope) within 0.1% */
    TEST_ASSERT_FLOAT_WITHIN(1e-3 * STEP_RAD, STEP_RAD, y[N - 1]);
}

typedef struct {
    ladrc_variant_t variant;
    size_t offset;
    float value;
    ladrc_status_t expected;
} bad_field_t;

#define FIELD(f) offsetof(ladrc_axis_config_t, f)

static void test_every_invalid_field_is_rejected_with_its_status(void)
{
    const float nan_ = NAN;
    const float inf = INFINITY;
    const bad_field_t cases[] = {
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(dt_s), .value = 0.0f, .expected = LADRC_ERR_DT_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(dt_s), .value = nan_, .expected = LADRC_ERR_DT_S},
        {.variant = LADRC_VARIANT_PID, .offset = FIELD(dt_s), .value = -1e-3f, .expected = LADRC_ERR_DT_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(u_min_Nm), .value = nan_, .expected = LADRC_ERR_U_LIMITS},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(u_max_Nm), .value = -inf, .expected = LADRC_ERR_U_LIMITS},
        {.variant = LADRC_VARIANT_PID, .offset = FIELD(u_max_Nm), .value = nan_, .expected = LADRC_ERR_U_LIMITS},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(wc_rad_s), .value = 0.0f, .expected = LADRC_ERR_WC_RAD_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(wc_rad_s), .value = inf, .expected = LADRC_ERR_WC_RAD_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(wo_rad_s), .value = -75.0f, .expected = LADRC_ERR_WO_RAD_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(wo_rad_s), .value = nan_, .expected = LADRC_ERR_WO_RAD_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(b0), .value = 0.0f, .expected = LADRC_ERR_B0},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(b0), .value = inf, .expected = LADRC_ERR_B0},
        {.variant = LADRC_VARIANT_LADRC,
         .offset = FIELD(td_accel_rad_s2),
         .value = 0.0f,
         .expected = LADRC_ERR_TD_ACCEL_RAD_S2},
        {.variant = LADRC_VARIANT_LADRC,
         .offset = FIELD(td_accel_rad_s2),
         .value = nan_,
         .expected = LADRC_ERR_TD_ACCEL_RAD_S2},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(td_h0_s), .value = 1e-4f, .expected = LADRC_ERR_TD_H0_S},
        {.variant = LADRC_VARIANT_LADRC, .offset = FIELD(td_h0_s), .value = nan_, .expected = LADRC_ERR_TD_H0_S},
        {.variant = LADRC_VARIANT_PID, .offset = FIELD(pid_kp), .value = -1.0f, .expected = LADRC_ERR_PID_KP},
        {.variant = LADRC_VARIANT_PID, .offset = FIELD(pid_ki), .value = nan_, .expected = LADRC_ERR_PID_KI},
        {.variant = LADRC_VARIANT_PID, .offset = FIELD(pid_kd), .value = inf, .expected = LADRC_ERR_PID_KD},
        {.variant = LADRC_VARIANT_PID,
         .offset = FIELD(pid_d_filter_tau_s),
         .value = -1.0f,
         .expected = LADRC_ERR_PID_D_TAU_S},
        {.variant = LADRC_VARIANT_PID,
         .offset = FIELD(pid_i_limit_Nm),
         .value = -1.0f,
         .expected = LADRC_ERR_PID_I_LIMIT_NM},
        {.variant = LADRC_VARIANT_HP_MLADRC,
         .offset = FIELD(levant_lipschitz_rad_s4),
         .value = 0.0f,
         .expected = LADRC_ERR_LEVANT_LIPSCHITZ},
        {.variant = LADRC_VARIANT_HP_MLADRC,
         .offset = FIELD(hp_freq_rad_s[0]),
         .value = nan_,
         .expected = LADRC_ERR_HP_FREQ_RAD_S},
        {.variant = LADRC_VARIANT_HP_MLADRC,
         .offset = FIELD(hp_lambda0_per_s),
         .value = 0.0f,
         .expected = LADRC_ERR_EST_LAMBDA0},
        {.variant = LADRC_VARIANT_LP_MLADRC,
         .offset = FIELD(lp_lambda0_per_s),
         .value = inf,
         .expected = LADRC_ERR_EST_LAMBDA0},
        {.variant = LADRC_VARIANT_LP_MLADRC,
         .offset = FIELD(lp_k0_per_s),
         .value = -300.0f,
         .expected = LADRC_ERR_EST_K0},
        {.variant = LADRC_VARIANT_LP_MLADRC, .offset = FIELD(wo_rad_s), .value = 0.0f, .expected = LADRC_ERR_WO_RAD_S},
    };
    for (unsigned i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ladrc_axis_config_t cfg;
        ladrc_axis_config_default(&cfg, cases[i].variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
        *(ladrc_real_t *)((char *)&cfg + cases[i].offset) = (ladrc_real_t)cases[i].value;
        ladrc_axis_t axis;
        char msg[48];
        snprintf(msg, sizeof msg, "case %u", i);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].expected, ladrc_axis_init(&axis, &cfg), msg);
    }
}

static void test_invalid_enums_and_null_are_rejected(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    cfg.leso_method = (ladrc_leso_method_t)9;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_LESO_METHOD, ladrc_axis_init(&axis, &cfg));
    cfg = ladrc_config(LADRC_SHAPER_TD);
    cfg.leso_method = LADRC_LESO_EULER;
    cfg.wo_rad_s = 2500.0f;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_LESO_EULER_UNSTABLE, ladrc_axis_init(&axis, &cfg));
    cfg = ladrc_config((ladrc_shaper_t)5);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_SHAPER, ladrc_axis_init(&axis, &cfg));
    cfg = ladrc_config(LADRC_SHAPER_TD);
    cfg.variant = LADRC_VARIANT_COUNT;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_VARIANT, ladrc_axis_init(&axis, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_axis_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_axis_init(&axis, NULL));
}

static void test_unused_fields_of_other_variants_are_not_checked(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_NONE);
    cfg.td_accel_rad_s2 = (ladrc_real_t)NAN; /* no TD */
    cfg.pid_kp = -1.0f;                      /* no PID */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
}

/* Drives one variant on a fixed input sequence; bad ticks get `bad` inputs. */
static void run_sequence(ladrc_variant_t variant, int n, float *out, int bad_from, int bad_to, float bad)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_init(&axis, &cfg);
    for (int k = 0; k < n; ++k) {
        const ladrc_real_t ref = (ladrc_real_t)(0.2 * sin(0.01 * k));
        const ladrc_real_t y = (ladrc_real_t)(0.19 * sin(0.01 * k - 0.1));
        for (uint32_t rep = 1; k >= bad_from && k < bad_to && rep <= 3; ++rep) {
            const ladrc_real_t held = axis.output_Nm;
            const ladrc_real_t u = axis_command(&axis, (rep & 1) ? bad : ref, (rep & 1) ? y : bad);
            TEST_ASSERT_EQUAL_MEMORY(&held, &u, sizeof u);
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_axis_get_faults(&axis));
            TEST_ASSERT_EQUAL_UINT32(rep, ladrc_axis_get_consecutive_faults(&axis));
        }
        out[k] = (float)axis_command(&axis, ref, y);
        TEST_ASSERT_EQUAL_UINT32(0u, ladrc_axis_get_consecutive_faults(&axis));
    }
}

static void test_non_finite_inputs_hold_the_state_and_the_run_resumes_unchanged(void)
{
    /* A faulty tick must be as if it never happened: outputs of the clean
     * run and of the run with NaN/Inf ticks inserted are bitwise equal. */
    const ladrc_variant_t variants[] = {LADRC_VARIANT_LADRC, LADRC_VARIANT_PID};
    const float bad[] = {NAN, INFINITY, -INFINITY};
    enum { N = 400 };
    static float clean[N];
    static float faulty[N];
    for (unsigned v = 0; v < 2; ++v) {
        run_sequence(variants[v], N, clean, -1, -1, 0.0f);
        for (unsigned b = 0; b < 3; ++b) {
            run_sequence(variants[v], N, faulty, 100, 110, bad[b]);
            TEST_ASSERT_EQUAL_MEMORY(clean, faulty, sizeof clean);
        }
    }
}

static void test_non_finite_rate_raises_a_flag_and_the_tick_runs_without_it(void)
{
    ladrc_axis_t a;
    ladrc_axis_t b;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&a, &cfg);
    ladrc_axis_init(&b, &cfg);
    const float ua = (float)axis_command(&a, 0.1f, 0.0f);
    const float ub = (float)axis_command_with_rate(&b, 0.1f, 0.0f, (ladrc_real_t)NAN);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_RATE, ladrc_axis_get_faults(&b));
    TEST_ASSERT_EQUAL_MEMORY(&ua, &ub, sizeof ua);
    TEST_ASSERT_EQUAL_UINT32(0u, ladrc_axis_get_consecutive_faults(&b));
}

static void test_non_finite_applied_torque_is_ignored_and_flagged(void)
{
    ladrc_axis_t axis;
    const ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&axis, &cfg);
    const ladrc_real_t u = axis_command(&axis, 0.1f, 0.0f);
    ladrc_axis_set_applied(&axis, (ladrc_real_t)NAN);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_APPLIED, ladrc_axis_get_faults(&axis));
    TEST_ASSERT_EQUAL_MEMORY(&u, &axis.applied_Nm, sizeof u);
}

static void run_outputs(ladrc_axis_t *axis, int from, int to, float *out)
{
    for (int k = from; k < to; ++k) {
        const ladrc_real_t ref = (ladrc_real_t)(k < 300 ? 0.0 : 0.3);
        const ladrc_real_t y = (ladrc_real_t)(0.25 * (1.0 - exp(-0.004 * k)));
        out[k] = (float)axis_command_with_rate(axis, ref, y, (ladrc_real_t)(0.001 * exp(-0.004 * k)));
    }
}

static void test_a_run_repeated_after_reset_or_split_across_calls_is_identical(void)
{
    const ladrc_variant_t variants[] = {LADRC_VARIANT_LADRC, LADRC_VARIANT_PID};
    enum { N = 1000 };
    static float first[N];
    static float again[N];
    static float split[N];
    for (unsigned v = 0; v < 2; ++v) {
        ladrc_axis_t axis;
        ladrc_axis_config_t cfg;
        ladrc_axis_config_default(&cfg, variants[v], (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
        ladrc_axis_init(&axis, &cfg);
        run_outputs(&axis, 0, N, first);
        ladrc_axis_reset(&axis, 0.0f);
        run_outputs(&axis, 0, N, again);
        ladrc_axis_reset(&axis, 0.0f);
        ladrc_ref_t ref;
        ladrc_real_t angle, rate, dist;
        for (int from = 0; from < N; from += 137) { /* uneven chunks with reads between */
            run_outputs(&axis, from, from + 137 < N ? from + 137 : N, split);
            ladrc_axis_get_reference(&axis, &ref);
            ladrc_axis_get_estimate(&axis, &angle, &rate, &dist);
        }
        TEST_ASSERT_EQUAL_MEMORY(first, again, sizeof first);
        TEST_ASSERT_EQUAL_MEMORY(first, split, sizeof first);
    }
}

static void test_lp_treats_a_tick_without_rate_as_a_gap(void)
{
    /* given LP with a rate, then a tick without one, then a rate 1 rad/s higher */
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_init(&axis, &cfg);
    axis_command_with_rate(&axis, 0.0f, 0.0f, 0.0f);
    axis_command(&axis, 0.0f, 0.0f);
    axis_command_with_rate(&axis, 0.0f, 0.0f, 1.0f);
    /* then no 1 / (2 dt) = 500 rad/s^2 sample reached the estimate */
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 0.0f, axis.d_hat_rad_s2);
}

/* HP axis on y'' = b u + 50 (rad/s^2) for 3 s with the given known part
 * of f; returns the bias HP fitted to its sample. */
static double hp_bias_with_known_part(double known_rad_s2)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    const test_sine_t d = {.bias = 50.0, .amp = 0.0, .w_rad_s = 0.0, .phase_rad = 0.0};
    test_double_integrator_t plant;
    test_plant_init(&plant, 1.0 / J_KG_M2, test_sine_disturbance, &d);
    for (int k = 0; k < 3000; ++k) {
        ladrc_axis_set_known_disturbance(&axis, (ladrc_real_t)known_rad_s2);
        const double u = axis_command(&axis, 0.0f, (ladrc_real_t)plant.y_rad);
        test_plant_step(&plant, u, DT_S, 1);
    }
    return ladrc_hp_get_bias(&axis.part.hp.est);
}

static void test_hp_samples_only_the_part_of_f_that_is_not_known(void)
{
    /* given a constant disturbance of 50 rad/s^2: unknown, HP's sample holds
     * it; known, the shadow observer takes it out and the sample holds ~0
     * (1% of it: the fit's settling after the onset) */
    TEST_ASSERT_FLOAT_WITHIN(0.5f, 50.0f, (float)hp_bias_with_known_part(0.0));
    TEST_ASSERT_FLOAT_WITHIN(0.5f, 0.0f, (float)hp_bias_with_known_part(50.0));
    /* a non-finite known part counts as none */
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_init(&axis, &cfg);
    ladrc_axis_set_known_disturbance(&axis, 3.0f);
    ladrc_axis_set_known_disturbance(&axis, (ladrc_real_t)NAN);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, axis.f_known_rad_s2);
}

static void test_estimates_report_the_observer_or_the_pid_measurement(void)
{
    ladrc_axis_t axis;
    ladrc_axis_config_t cfg = ladrc_config(LADRC_SHAPER_TD);
    ladrc_axis_init(&axis, &cfg);
    ladrc_axis_reset(&axis, 0.2f);
    ladrc_real_t angle, rate, dist;
    ladrc_axis_get_estimate(&axis, &angle, &rate, &dist);
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.2f, angle);
    ladrc_ref_t ref;
    ladrc_axis_get_reference(&axis, &ref);
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.2f, ref.r);

    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_init(&axis, &cfg);
    axis_command(&axis, 0.0f, 0.1f);
    ladrc_axis_get_estimate(&axis, &angle, &rate, &dist);
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.1f, angle);
    TEST_ASSERT_FLOAT_WITHIN(1e-7f, 0.0f, dist);
}

static void test_estimators_are_reachable_only_on_their_variant(void)
{
    const ladrc_variant_t variants[] = {LADRC_VARIANT_LADRC, LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_HP_MLADRC,
                                        LADRC_VARIANT_PID};
    for (unsigned i = 0; i < sizeof variants / sizeof variants[0]; ++i) {
        ladrc_axis_config_t cfg;
        ladrc_axis_config_default(&cfg, variants[i], (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
        ladrc_axis_t axis;
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
        const ladrc_hp_estimator_t *hp = ladrc_axis_get_hp(&axis);
        const ladrc_lp_estimator_t *lp = ladrc_axis_get_lp(&axis);
        TEST_ASSERT_TRUE(hp == (variants[i] == LADRC_VARIANT_HP_MLADRC ? &axis.part.hp.est : NULL));
        TEST_ASSERT_TRUE(lp == (variants[i] == LADRC_VARIANT_LP_MLADRC ? &axis.part.lp : NULL));
    }
    /* what they show is what the axis applies */
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LP_MLADRC, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_t axis;
    ladrc_axis_init(&axis, &cfg);
    for (int k = 0; k < 100; ++k) {
        axis_command_with_rate(&axis, 0.0f, 0.0f, (ladrc_real_t)(0.01 * k));
    }
    TEST_ASSERT_TRUE(ladrc_lp_get_estimate(ladrc_axis_get_lp(&axis)) != 0.0f);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, axis.d_hat_rad_s2, ladrc_lp_get_estimate(ladrc_axis_get_lp(&axis)));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ladrc_step_settles_as_its_closed_loop_poles_predict);
    RUN_TEST(test_ladrc_rejects_a_constant_disturbance_to_zero_steady_error);
    RUN_TEST(test_ladrc_sine_disturbance_error_matches_its_transfer_function);
    RUN_TEST(test_td_shaping_lowers_the_torque_peak_of_a_reference_step);
    RUN_TEST(test_observer_fed_the_applied_torque_does_not_wind_up);
    RUN_TEST(test_output_stays_within_the_configured_torque_limits);
    RUN_TEST(test_pid_variant_settles_a_step_through_the_axis_api);
    RUN_TEST(test_every_invalid_field_is_rejected_with_its_status);
    RUN_TEST(test_invalid_enums_and_null_are_rejected);
    RUN_TEST(test_unused_fields_of_other_variants_are_not_checked);
    RUN_TEST(test_non_finite_inputs_hold_the_state_and_the_run_resumes_unchanged);
    RUN_TEST(test_non_finite_rate_raises_a_flag_and_the_tick_runs_without_it);
    RUN_TEST(test_non_finite_applied_torque_is_ignored_and_flagged);
    RUN_TEST(test_a_run_repeated_after_reset_or_split_across_calls_is_identical);
    RUN_TEST(test_lp_treats_a_tick_without_rate_as_a_gap);
    RUN_TEST(test_hp_samples_only_the_part_of_f_that_is_not_known);
    RUN_TEST(test_estimates_report_the_observer_or_the_pid_measurement);
    RUN_TEST(test_estimators_are_reachable_only_on_their_variant);
    return UNITY_END();
}
