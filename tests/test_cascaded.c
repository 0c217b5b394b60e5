/* SPDX-License-Identifier: BSD-3-Clause */
/* The cascaded attitude P / rate PID variant (cascaded.h) behind the axis
 * API: validation naming the field, zero steady-state error under a
 * constant disturbance, the disturbance response of the linear loop against
 * its transfer function, the rate setpoint bound, no windup in saturation,
 * the rate from the angle without a gyro, feed-forward on a ramp, and runs
 * that are bit for bit the same however they are split. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "test_plant.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3 /* paper vehicle, roll axis */
#define PI_D 3.14159265358979323846

/* Steady state under a constant disturbance: the loop's slowest pole (near
 * the integral corner, 15 rad/s) has decayed by e^-60 after 4 s; what is
 * left is float rounding of the angle (6e-9 rad at 0.1 rad) through the
 * loop: 1e-6 rad. */
#define STEADY_TOL_RAD 1e-6
/* Measured disturbance response against the continuous-time transfer
 * function: the sampled loop differs by the zero-order hold's half-tick
 * delay (w h / 2 = 1.5 % at 30 rad/s) and the backward differences of the
 * derivative (w h / 2 again); 5 % as the brief sets. */
#define TF_REL_TOL 0.05
/* Without a gyro the rate comes from a filtered angle difference, a lag of
 * about tau_w = 1.7 ms more: the steady state is still exact. */
#define NO_GYRO_STEADY_TOL_RAD 1e-6
/* Hand-computed single steps: a few float roundings of 1e-2 N m values. */
#define HAND_TOL_NM 1e-6

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_axis_config_t paper_config(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_CASCADED, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    return cfg;
}

static void init_axis(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(axis, cfg));
}

/* ---- configuration ------------------------------------------------------ */

static void test_defaults_follow_the_stated_loop_shaping_rule(void)
{
    /* given: the paper's roll axis; wr = wo = 75 rad/s */
    const ladrc_axis_config_t cfg = paper_config();
    const double wr = 75.0, kp = J_KG_M2 * wr;
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(1e-5, wr / 4.0, cfg.cas_att_kp);
    TEST_ASSERT_FLOAT_WITHIN(1e-7, kp, cfg.cas_rate_kp);
    TEST_ASSERT_FLOAT_WITHIN(1e-5, kp * wr / 5.0, cfg.cas_rate_ki);
    TEST_ASSERT_FLOAT_WITHIN(1e-9, kp / (4.0 * wr), cfg.cas_rate_kd);
    TEST_ASSERT_FLOAT_WITHIN(1e-9, 1.0 / (8.0 * wr), cfg.cas_d_filter_tau_s);
    TEST_ASSERT_FLOAT_WITHIN(1e-5, 220.0 * PI_D / 180.0, cfg.cas_rate_max_rad_s);
    TEST_ASSERT_TRUE(isinf((double)cfg.cas_i_limit_Nm));
    TEST_ASSERT_EQUAL_INT(LADRC_SHAPER_TD, cfg.shaper);
}

static void test_init_names_the_bad_field(void)
{
    typedef struct {
        size_t offset;
        float value;
        ladrc_status_t expected;
    } bad_t;
#define FIELD(f) offsetof(ladrc_axis_config_t, f)
    const float nan_ = (float)NAN, inf = (float)INFINITY;
    const bad_t cases[] = {
        {.offset = FIELD(cas_att_kp), .value = 0.0f, .expected = LADRC_ERR_CAS_ATT_KP},
        {.offset = FIELD(cas_att_kp), .value = 1000.0f, .expected = LADRC_ERR_CAS_ATT_KP}, /* att_kp dt = 1 */
        {.offset = FIELD(cas_att_kp), .value = nan_, .expected = LADRC_ERR_CAS_ATT_KP},
        {.offset = FIELD(cas_rate_max_rad_s), .value = 0.0f, .expected = LADRC_ERR_CAS_RATE_MAX},
        {.offset = FIELD(cas_rate_max_rad_s),
         .value = 101.0f,
         .expected = LADRC_ERR_CAS_RATE_MAX}, /* beyond rate_limit_rad_s */
        {.offset = FIELD(cas_rate_max_rad_s), .value = inf, .expected = LADRC_ERR_CAS_RATE_MAX},
        {.offset = FIELD(cas_rate_kp), .value = -1.0f, .expected = LADRC_ERR_CAS_RATE_KP},
        {.offset = FIELD(cas_rate_ki), .value = nan_, .expected = LADRC_ERR_CAS_RATE_KI},
        {.offset = FIELD(cas_rate_kd), .value = inf, .expected = LADRC_ERR_CAS_RATE_KD},
        {.offset = FIELD(cas_d_filter_tau_s), .value = -1e-3f, .expected = LADRC_ERR_CAS_D_TAU_S},
        {.offset = FIELD(cas_rate_filter_tau_s), .value = nan_, .expected = LADRC_ERR_CAS_RATE_TAU_S},
        {.offset = FIELD(cas_i_limit_Nm), .value = -1.0f, .expected = LADRC_ERR_CAS_I_LIMIT_NM},
        {.offset = FIELD(td_accel_rad_s2),
         .value = -1.0f,
         .expected = LADRC_ERR_TD_ACCEL_RAD_S2}, /* the shaper's fields are read */
    };
#undef FIELD
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ladrc_axis_config_t cfg = paper_config();
        ladrc_axis_t axis;
        *(ladrc_real_t *)(void *)((char *)&cfg + cases[i].offset) = (ladrc_real_t)cases[i].value;
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].expected, ladrc_axis_init(&axis, &cfg), "case");
    }
    /* gains whose terms could leave the real type: kp times 2 rate_limit
     * (200 rad/s), kd times 2 rate_limit / dt, beyond a quarter of its range */
    ladrc_axis_config_t cfg = paper_config();
    ladrc_axis_t axis;
    cfg.cas_rate_kp = LADRC_REAL_MAX / LADRC_R(100.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_CAS_RATE_KP, ladrc_axis_init(&axis, &cfg));
    cfg = paper_config();
    cfg.cas_rate_kd = LADRC_REAL_MAX / LADRC_R(1e5);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_CAS_RATE_KD, ladrc_axis_init(&axis, &cfg));
    /* the LADRC fields are not read: a nonsense wc does not matter */
    cfg = paper_config();
    cfg.wc_rad_s = LADRC_R(-1.0);
    cfg.motor_tau_s = LADRC_R(-1.0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
}

/* ---- closed loop on a small plant ---------------------------------------- */

/* Flies the axis on y'' = u / J + d(t) for n ticks, reference ref_rad (held);
 * with_rate: the gyro's rate is given. Returns the error ref - y at the end. */
static double fly_hold(ladrc_axis_t *axis, test_double_integrator_t *p, double ref_rad, int n, int with_rate)
{
    for (int k = 0; k < n; ++k) {
        const ladrc_real_t u = with_rate ? axis_command_with_rate(axis, (ladrc_real_t)ref_rad, (ladrc_real_t)p->y_rad,
                                                                  (ladrc_real_t)p->rate_rad_s)
                                         : axis_command(axis, (ladrc_real_t)ref_rad, (ladrc_real_t)p->y_rad);
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(axis));
        test_plant_step(p, (double)u, DT_S, 1);
    }
    return ref_rad - p->y_rad;
}

static void test_constant_disturbance_leaves_no_steady_state_error(void)
{
    /* given: a constant 20 rad/s^2 disturbance (the paper's bias), a held
     * 0.1 rad reference; with and without a gyro */
    static const test_sine_t bias = {.bias = 20.0, .amp = 0.0, .w_rad_s = 1.0, .phase_rad = 0.0};
    for (int with_rate = 0; with_rate <= 1; ++with_rate) {
        const ladrc_axis_config_t cfg = paper_config();
        ladrc_axis_t axis;
        init_axis(&axis, &cfg);
        test_double_integrator_t p;
        test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &bias);
        /* when */
        const double early = fly_hold(&axis, &p, 0.1, 100, with_rate);
        const double late = fly_hold(&axis, &p, 0.1, 3900, with_rate);
        /* then: the error the bias first caused is gone; the integrator holds
         * the bias's torque J d */
        TEST_ASSERT_TRUE(fabs(early) > 1e3 * STEADY_TOL_RAD);
        TEST_ASSERT_TRUE(fabs(late) <= (with_rate ? STEADY_TOL_RAD : NO_GYRO_STEADY_TOL_RAD));
        TEST_ASSERT_FLOAT_WITHIN(1e-4 * J_KG_M2 * 20.0, -J_KG_M2 * 20.0, axis.part.cas.integral_Nm);
    }
}

/*
 * Disturbance to error of the linear loop, by hand. Plant J y'' = u + J d
 * (d an acceleration). Reference 0 (the TD then gives r = r' = 0), gyro
 * rate m = s y. The controller (cascaded.h, continuous-time equivalents):
 *     w_sp = -ka y
 *     u    = (kp + ki / s)(w_sp - s y) - kd s m / (tau s + 1)
 *          = -(kp + ki / s)(s + ka) y - kd s^2 y / (tau s + 1)
 * so  J s^2 y + (kp + ki / s)(s + ka) y + kd s^2 y / (tau s + 1) = J d, and
 * with e = -y:
 *     e / d = -J / (J s^2 + (kp + ki / s)(s + ka) + kd s^2 / (tau s + 1))
 */
static double complex error_per_disturbance(const ladrc_axis_config_t *c, double w)
{
    const double complex s = I * w;
    const double kp = (double)c->cas_rate_kp, ki = (double)c->cas_rate_ki, kd = (double)c->cas_rate_kd;
    const double ka = (double)c->cas_att_kp, tau = (double)c->cas_d_filter_tau_s;
    return -J_KG_M2 / (J_KG_M2 * s * s + (kp + ki / s) * (s + ka) + kd * s * s / (tau * s + 1.0));
}

static void test_disturbance_response_matches_the_transfer_function(void)
{
    static const double tones[3] = {3.0, 10.0, 30.0};
    for (int i = 0; i < 3; ++i) {
        /* given: a 1 rad/s^2 tone at w on the paper's roll axis */
        const double w = tones[i];
        const test_sine_t tone = {.bias = 0.0, .amp = 1.0, .w_rad_s = w, .phase_rad = 0.0};
        const ladrc_axis_config_t cfg = paper_config();
        ladrc_axis_t axis;
        init_axis(&axis, &cfg);
        test_double_integrator_t p;
        test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &tone);
        /* when: 2 s of transient (the slowest pole, 15 rad/s, decays by
         * e^-30), then the error's Fourier coefficient at w over whole
         * periods (error and disturbance sampled at the same instants) */
        (void)fly_hold(&axis, &p, 0.0, 2000, 1);
        const int per = (int)lround(2.0 * PI_D / w / DT_S);
        const int n = per * (int)ceil(2000.0 / per);
        double complex e_w = 0.0, d_w = 0.0;
        for (int k = 0; k < n; ++k) {
            const double t = p.t_s;
            e_w += -p.y_rad * cexp(-I * w * t);
            d_w += sin(w * t) * cexp(-I * w * t);
            (void)fly_hold(&axis, &p, 0.0, 1, 1);
        }
        const double complex measured = e_w / d_w;
        const double complex expected = error_per_disturbance(&cfg, w);
        /* then */
        const double rel = cabs(measured - expected) / cabs(expected);
        printf("w %5.1f rad/s: |e/d| %.4e (expected %.4e), relative difference %.4f", w, cabs(measured), cabs(expected),
               rel);
        fflush(stdout);
        TEST_ASSERT_TRUE(rel <= TF_REL_TOL);
    }
}

/* ---- limits ---------------------------------------------------------------- */

static void test_rate_setpoint_is_bounded(void)
{
    /* given: a stalled axis (angle and rate 0), no shaping, a 1 rad reference:
     * att_kp e = 18.75 rad/s, above the 3.84 rad/s bound */
    ladrc_axis_config_t cfg = paper_config();
    cfg.shaper = LADRC_SHAPER_NONE;
    cfg.cas_rate_ki = LADRC_R(0.0);
    cfg.cas_rate_kd = LADRC_R(0.0);
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    /* when */
    const double u = (double)axis_command_with_rate(&axis, LADRC_R(1.0), LADRC_R(0.0), LADRC_R(0.0));
    /* then: the torque of the bounded setpoint */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, (double)cfg.cas_rate_kp * (double)cfg.cas_rate_max_rad_s, u);
    TEST_ASSERT_FLOAT_WITHIN(1e-6, (double)cfg.cas_rate_max_rad_s, axis.part.cas.rate_sp_rad_s);
}

static void test_integrator_does_not_wind_up_in_saturation(void)
{
    /* given: a stalled axis with a 0.5 rad error for 1 s, limited by the
     * command bound (a) or by the mixer reporting 0.05 N m (b), and a twin
     * without limits (c) */
    ladrc_axis_config_t cfg = paper_config();
    cfg.shaper = LADRC_SHAPER_NONE;
    ladrc_axis_t a, b, c;
    init_axis(&c, &cfg);
    init_axis(&b, &cfg);
    cfg.u_min_Nm = LADRC_R(-0.05);
    cfg.u_max_Nm = LADRC_R(0.05);
    init_axis(&a, &cfg);
    /* when */
    for (int k = 0; k < 1000; ++k) {
        (void)axis_command_with_rate(&a, LADRC_R(0.5), LADRC_R(0.0), LADRC_R(0.0));
        (void)axis_command_with_rate(&b, LADRC_R(0.5), LADRC_R(0.0), LADRC_R(0.0));
        ladrc_axis_set_applied(&b, LADRC_R(0.05));
        (void)axis_command_with_rate(&c, LADRC_R(0.5), LADRC_R(0.0), LADRC_R(0.0));
    }
    /* then: the rate error is the bounded setpoint w; the free integrator
     * took g ki w 1 s, the limited ones only their first tick, g ki h w,
     * before they saw the saturation (g = 1 - (w / e_relax)^2 = 0.70 at
     * 220 deg/s, the default relax of 400 deg/s: cascaded.h) */
    const double w = (double)cfg.cas_rate_max_rad_s, ki = (double)cfg.cas_rate_ki;
    const double g = 1.0 - (w / (double)cfg.cas_i_relax_rad_s) * (w / (double)cfg.cas_i_relax_rad_s);
    TEST_ASSERT_FLOAT_WITHIN(1e-3 * ki * w, g * ki * w * 1.0, c.part.cas.integral_Nm);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, g * ki * DT_S * w, a.part.cas.integral_Nm);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, g * ki * DT_S * w, b.part.cas.integral_Nm);
    /* and a reversed error unwinds at once */
    (void)axis_command_with_rate(&a, LADRC_R(-0.5), LADRC_R(0.0), LADRC_R(0.0));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, a.part.cas.integral_Nm);
}

static void test_integral_limit_bounds_the_integrator(void)
{
    ladrc_axis_config_t cfg = paper_config();
    cfg.shaper = LADRC_SHAPER_NONE;
    cfg.cas_i_limit_Nm = LADRC_R(0.01);
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    for (int k = 0; k < 1000; ++k) {
        (void)axis_command_with_rate(&axis, LADRC_R(0.5), LADRC_R(0.0), LADRC_R(0.0));
    }
    TEST_ASSERT_EQUAL_FLOAT(0.01f, (float)axis.part.cas.integral_Nm);
}

/* ---- rate without a gyro, feed-forward, wrap --------------------------------- */

static void test_rate_without_a_gyro_is_the_filtered_angle_difference(void)
{
    /* given: an angle rising at 2 rad/s, no rate given */
    const ladrc_axis_config_t cfg = paper_config();
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    /* when: 100 ticks (60 filter time constants) */
    for (int k = 0; k < 100; ++k) {
        (void)axis_command(&axis, LADRC_R(0.0), (ladrc_real_t)(2.0 * k * DT_S));
    }
    ladrc_real_t angle, rate, dist;
    ladrc_axis_get_estimate(&axis, &angle, &rate, &dist);
    /* then: the rate the loop used is 2 rad/s (float differences of 2e-3 rad
     * at 0.2 rad: 1e-8 / 1e-3 = 1e-5 relative) */
    TEST_ASSERT_FLOAT_WITHIN(1e-3, 2.0, rate);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, (float)dist);
}

static void test_feed_forward_follows_a_ramp_without_lag(void)
{
    /* given: a 1 rad/s ramp reference, no disturbance; with the TD's r'
     * fed forward, and without (shaper NONE: r' = 0, a plain P attitude
     * loop) */
    double lag[2];
    const double v = 1.0;
    ladrc_axis_config_t cfg = paper_config();
    for (int ff = 0; ff <= 1; ++ff) {
        cfg.shaper = ff ? LADRC_SHAPER_TD : LADRC_SHAPER_NONE;
        ladrc_axis_t axis;
        init_axis(&axis, &cfg);
        test_double_integrator_t p;
        test_plant_init(&p, 1.0 / J_KG_M2, NULL, NULL);
        for (int k = 0; k < 4000; ++k) {
            const ladrc_real_t u = axis_command_with_rate(&axis, (ladrc_real_t)(v * k * DT_S), (ladrc_real_t)p.y_rad,
                                                          (ladrc_real_t)p.rate_rad_s);
            test_plant_step(&p, (double)u, DT_S, 1);
        }
        /* error against the shaped reference the loop tracks, at its tick */
        lag[ff] = (double)axis.ref.r - (p.y_rad - p.rate_rad_s * DT_S);
    }
    printf("ramp error after 4 s: %.3e rad with r', %.3e rad without", lag[1], lag[0]);
    /* then: without feed-forward the rate integrator holds w_sp = v, so the
     * attitude error is v / att_kp (53 mrad); with it the loop follows r
     * to float rounding of the angle (1e-6 rad at 4 rad, through the loop:
     * 1e-5 rad) */
    TEST_ASSERT_FLOAT_WITHIN(0.01 * v / (double)cfg.cas_att_kp, v / (double)cfg.cas_att_kp, lag[0]);
    TEST_ASSERT_TRUE(fabs(lag[1]) < 1e-5);
}

static void test_wrapped_axis_holds_near_pi_across_the_seam(void)
{
    /* given: a wrapped axis holding 3.135 rad, told the angle as -3.148 rad
     * (the same attitude, 2 pi - 0.0012 away) */
    ladrc_axis_config_t cfg = paper_config();
    cfg.wrap_angle = 1u;
    ladrc_axis_t wrapped, twin;
    init_axis(&wrapped, &cfg);
    init_axis(&twin, &cfg);
    ladrc_axis_reset(&wrapped, LADRC_R(3.135));
    ladrc_axis_reset(&twin, LADRC_R(3.135));
    /* when */
    double worst = 0.0;
    for (int k = 0; k < 300; ++k) {
        const double uw = axis_command_with_rate(&wrapped, LADRC_R(3.135), LADRC_R(-3.148), LADRC_R(0.0));
        const double ut =
            axis_command_with_rate(&twin, LADRC_R(3.135), (ladrc_real_t)(-3.148 + 2.0 * PI_D), LADRC_R(0.0));
        worst = fmax(worst, fabs(uw - ut));
    }
    /* then: the same torque, to the float rounding of the turn (1e-6 rad
     * at 2 pi) through the cascade's angle-to-torque gain (kp att_kp =
     * 7.7 N m/rad, and the integral's ki att_kp t = 34 N m/rad after
     * 0.3 s): 4e-5 N m; 1e-4 N m */
    TEST_ASSERT_TRUE(worst <= 1e-4);
}

/* ---- bit-identical runs ---------------------------------------------------------- */

/* n ticks on the paper's roll tone from the plant state p; records u. */
static void fly_record(ladrc_axis_t *axis, test_double_integrator_t *p, int n, ladrc_real_t *u_out)
{
    for (int k = 0; k < n; ++k) {
        const double t = p->t_s;
        const ladrc_real_t ref = (ladrc_real_t)(0.2 * cos(0.5 * PI_D * t));
        const ladrc_real_t u = axis_command_with_rate(axis, ref, (ladrc_real_t)p->y_rad, (ladrc_real_t)p->rate_rad_s);
        ladrc_axis_set_applied(axis, ladrc_clamp(u, LADRC_R(-0.2), LADRC_R(0.2))); /* a mixer that saturates */
        u_out[k] = u;
        test_plant_step(p, (double)ladrc_clamp(u, LADRC_R(-0.2), LADRC_R(0.2)), DT_S, 1);
    }
}

static void test_runs_are_bit_identical_however_split(void)
{
    enum { N = 3000 };
    static ladrc_real_t whole[N], split[N], again[N], reinit[N];
    static const test_sine_t tone = {.bias = 20.0, .amp = 120.0, .w_rad_s = 3.0, .phase_rad = 0.0};
    const ladrc_axis_config_t cfg = paper_config();
    ladrc_axis_t a, b;
    test_double_integrator_t p;
    /* given: one run of N ticks */
    init_axis(&a, &cfg);
    test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &tone);
    fly_record(&a, &p, N, whole);
    /* when: (1) the same run in pieces of 1, 7, 992 and 2000 ticks, the
     * state copied between calls */
    memset(&b, 0xa5, sizeof b);
    init_axis(&b, &cfg);
    test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &tone);
    static const int pieces[4] = {1, 7, 992, 2000};
    int at = 0;
    for (int i = 0; i < 4; ++i) {
        ladrc_axis_t moved;
        memcpy(&moved, &b, sizeof moved);
        fly_record(&moved, &p, pieces[i], split + at);
        memcpy(&b, &moved, sizeof b);
        at += pieces[i];
    }
    /* (2) the first axis, after its run, reset at 0 and run again */
    ladrc_axis_reset(&a, LADRC_R(0.0));
    test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &tone);
    fly_record(&a, &p, N, again);
    /* (3) the second re-initialised over its old state */
    init_axis(&b, &cfg);
    test_plant_init(&p, 1.0 / J_KG_M2, test_sine_disturbance, &tone);
    fly_record(&b, &p, N, reinit);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(whole, split, sizeof whole);
    TEST_ASSERT_EQUAL_MEMORY(whole, again, sizeof whole);
    TEST_ASSERT_EQUAL_MEMORY(whole, reinit, sizeof whole);
}

/* ---- faults ------------------------------------------------------------------- */

static void test_non_finite_inputs_are_held_and_flagged(void)
{
    const ladrc_axis_config_t cfg = paper_config();
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    const ladrc_real_t u0 = axis_command_with_rate(&axis, LADRC_R(0.1), LADRC_R(0.0), LADRC_R(0.0));
    ladrc_cascaded_t before;
    memcpy(&before, &axis.part.cas, sizeof before);
    /* a NaN angle: held, flagged, the loops untouched */
    TEST_ASSERT_TRUE(axis_command_with_rate(&axis, LADRC_R(0.1), (ladrc_real_t)NAN, LADRC_R(0.0)) == u0);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_INPUT, ladrc_axis_get_faults(&axis));
    TEST_ASSERT_EQUAL_MEMORY(&before, &axis.part.cas, sizeof before);
    /* an infinite rate: the tick runs on the angle's difference */
    (void)axis_command_with_rate(&axis, LADRC_R(0.1), LADRC_R(0.001), (ladrc_real_t)INFINITY);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_RATE, ladrc_axis_get_faults(&axis));
    TEST_ASSERT_TRUE(isfinite((double)axis.part.cas.rate_rad_s));
    /* a NaN applied torque: the own command stands */
    ladrc_axis_set_applied(&axis, (ladrc_real_t)NAN);
    TEST_ASSERT_TRUE((ladrc_axis_get_faults(&axis) & LADRC_FAULT_APPLIED) != 0u);
    TEST_ASSERT_TRUE(axis.part.cas.applied_Nm == axis.part.cas.output_Nm);
}

static void test_an_overflowing_update_restarts_the_loops(void)
{
    /* given: an integral gain near the largest float holds (its step at a
     * rate error of 2 rate_limit within the quarter of the range init
     * allows), no integral limit, a setpoint at +rate_limit (att_kp 10 rad
     * is beyond it) and a rate of -rate_limit */
    ladrc_axis_config_t cfg = paper_config();
    cfg.shaper = LADRC_SHAPER_NONE;
    cfg.cas_rate_max_rad_s = cfg.rate_limit_rad_s;
    cfg.applied_limit_Nm = LADRC_REAL_MAX;          /* no saturation to freeze the integrator */
    cfg.cas_i_relax_rad_s = (ladrc_real_t)INFINITY; /* nor a relax to stop it (g = 0 at this error) */
    const ladrc_real_t err_max = LADRC_R(2.0) * cfg.rate_limit_rad_s;
    cfg.cas_rate_ki = LADRC_REAL_MAX * LADRC_R(0.9); /* a step of 0.9 h 2 rate_limit = 0.18 of the range */
    TEST_ASSERT_TRUE(cfg.cas_rate_ki * (ladrc_real_t)DT_S * err_max <= LADRC_REAL_MAX * LADRC_R(0.25));
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    const ladrc_real_t rate = -cfg.rate_limit_rad_s;
    /* when: each tick adds 0.18 of the range to the integral */
    ladrc_real_t held = LADRC_R(0.0);
    int tick = -1;
    for (int k = 0; k < 8 && tick < 0; ++k) {
        const ladrc_real_t u = axis_command_with_rate(&axis, LADRC_R(10.0), LADRC_R(0.0), rate);
        if ((ladrc_axis_get_faults(&axis) & LADRC_FAULT_STATE) != 0u) {
            tick = k;
            /* then: the command of the tick before is held, the loops restart */
            TEST_ASSERT_TRUE(u == held);
            TEST_ASSERT_EQUAL_FLOAT(0.0f, (float)axis.part.cas.integral_Nm);
        }
        held = u;
    }
    TEST_ASSERT_TRUE(tick >= 4); /* five steps of 0.18 still fit */
    (void)axis_command_with_rate(&axis, LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0));
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(&axis));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_follow_the_stated_loop_shaping_rule);
    RUN_TEST(test_init_names_the_bad_field);
    RUN_TEST(test_constant_disturbance_leaves_no_steady_state_error);
    RUN_TEST(test_disturbance_response_matches_the_transfer_function);
    RUN_TEST(test_rate_setpoint_is_bounded);
    RUN_TEST(test_integrator_does_not_wind_up_in_saturation);
    RUN_TEST(test_integral_limit_bounds_the_integrator);
    RUN_TEST(test_rate_without_a_gyro_is_the_filtered_angle_difference);
    RUN_TEST(test_feed_forward_follows_a_ramp_without_lag);
    RUN_TEST(test_wrapped_axis_holds_near_pi_across_the_seam);
    RUN_TEST(test_runs_are_bit_identical_however_split);
    RUN_TEST(test_non_finite_inputs_are_held_and_flagged);
    RUN_TEST(test_an_overflowing_update_restarts_the_loops);
    return UNITY_END();
}
