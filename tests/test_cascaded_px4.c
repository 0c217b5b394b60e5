/* SPDX-License-Identifier: BSD-3-Clause */
/* The CASCADED variant's rate loop as PX4 flies it (cascaded.h): against a
 * transcription of PX4's published rate-loop equations on a step, a sine
 * and a sequence of errors beyond the 400 deg/s relax; and, one by one, the
 * integrator relax, the rate feed-forward gain, the integrator freeze while
 * landed, the yaw-only setpoint feed-forward of the attitude default and
 * the refusal of bad values of the new fields. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/cascaded.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3 /* paper vehicle, roll axis */
#define PI_D 3.14159265358979323846
#define RELAX_PX4_RAD_S (400.0 * PI_D / 180.0)

/* The acceptance bar for the library against the transcription. Both run the
 * same equations, so what separates them is float rounding (a few 1e-7 of
 * each term, summed by the integrator over 2000 ticks: 1e-5 of the peak);
 * a real difference fails it: integrating this tick's error before the
 * output instead of after would leave 1.4 % on the step, no relax 1.3 %. */
#define MATCH_TOL_OF_PEAK 0.005
/* Single steps by hand: float rounding of 1e-2..1 N m values (1e-7
 * relative) and of the setpoint att_kp (ref / att_kp) (1e-7 relative). */
#define HAND_TOL_NM 1e-6
/* The setpoint the axis forms, att_kp (r - y) + r': float rounding of rad/s values. */
#define SETPOINT_TOL_RAD_S 1e-5
/* The attitude gain that turns a reference into a rate setpoint (1/s),
 * cas_att_kp * dt_s < 1: a reference sp / ATT_KP at angle 0 asks for sp. */
#define ATT_KP_PER_S 10.0

void setUp(void)
{
}
void tearDown(void)
{
}

/* ---- PX4's rate loop, transcribed --------------------------------------- */

/*
 * PX4's multicopter rate controller on one axis, written in double from its
 * documentation (controller diagrams, the rate-controller section of the
 * multicopter PID tuning guide, the MC_*RATE_* parameter reference):
 *     e      = w_sp - w                                 rate error
 *     u      = P e + I - D w'_f + FF w_sp              (MC_ROLLRATE_P, _D, _FF)
 *     I     <- clamp(I + g(e) K_I e dt, +-I_lim)       (MC_ROLLRATE_I, MC_RR_INT_LIM)
 *     g(e)   = max(0, 1 - (e / 400 deg/s)^2)            the integrator relax
 * I is updated after the output and not at all while landed. D acts on the
 * derivative of the measured rate, not of the error; PX4 takes it filtered
 * from its sensor pipeline (IMU_DGYRO_CUTOFF), ahead of the rate loop: here
 * that pipeline is the first-order low pass of the backward difference the
 * library's axis implements (cas_d_filter_tau_s), so the rate-loop
 * equations are compared, not two filter designs.
 */
typedef struct {
    double p, i, d, ff;                     /* gains, N m s/rad, N m/rad, N m s^2/rad, N m s/rad */
    double i_lim_Nm, relax_rad_s, tau_d_s;  /* integral bound, relax, derivative filter */
    double integral_Nm, accel_f, prev_rate; /* state */
    int has_prev;
} px4_rate_t;

static double px4_rate_update(px4_rate_t *c, double rate_sp, double rate, int landed)
{
    const double raw = c->has_prev ? (rate - c->prev_rate) / DT_S : 0.0;
    c->accel_f += DT_S / (c->tau_d_s + DT_S) * (raw - c->accel_f);
    c->prev_rate = rate;
    c->has_prev = 1;
    const double e = rate_sp - rate;
    const double u = c->p * e + c->integral_Nm - c->d * c->accel_f + c->ff * rate_sp;
    if (!landed) {
        const double x = e / c->relax_rad_s, g = fmax(0.0, 1.0 - x * x);
        c->integral_Nm = fmin(fmax(c->integral_Nm + g * c->i * e * DT_S, -c->i_lim_Nm), c->i_lim_Nm);
    }
    return u;
}

/* ---- the library's rate loop behind the axis ------------------------------ */

/* CASCADED on the paper's roll axis, no shaping (r' = 0), the attitude gain
 * ATT_KP_PER_S and a rate bound of 20 rad/s, so that a reference sp /
 * ATT_KP at angle 0 is the rate setpoint sp. */
static ladrc_axis_config_t rate_loop_config(void)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_CASCADED, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.shaper = LADRC_SHAPER_NONE;
    cfg.cas_att_kp = (ladrc_real_t)ATT_KP_PER_S;
    cfg.cas_rate_max_rad_s = LADRC_R(20.0);
    return cfg;
}

static void init_axis(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(axis, cfg));
}

/* One tick with the rate setpoint sp (rad/s) and the measured rate (rad/s). */
static double library_tick(ladrc_axis_t *axis, double sp_rad_s, double rate_rad_s)
{
    const ladrc_real_t u =
        axis_command_with_rate(axis, (ladrc_real_t)(sp_rad_s / ATT_KP_PER_S), LADRC_R(0.0), (ladrc_real_t)rate_rad_s);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_axis_get_faults(axis));
    return (double)u;
}

typedef enum { SEQ_STEP, SEQ_SINE, SEQ_BEYOND_RELAX, SEQ_COUNT } sequence_t;

static const char *const sequence_name[SEQ_COUNT] = {"step", "sine", "beyond the relax"};

/* The rate setpoint of a sequence at tick k (rad/s): a 2 rad/s step at 50 ms,
 * a 3 rad/s sine at 2 Hz, and a +-12 rad/s square wave (690 deg/s) at 2 Hz,
 * whose errors reach twice that, far beyond the 400 deg/s relax. */
static double setpoint_of(sequence_t s, int k)
{
    const double t = k * DT_S;
    switch (s) {
    case SEQ_STEP:
        return (t >= 0.05) ? 2.0 : 0.0;
    case SEQ_SINE:
        return 3.0 * sin(2.0 * PI_D * 2.0 * t);
    default:
        return (((int)(t / 0.25)) % 2 == 0) ? 12.0 : -12.0;
    }
}

/* The measured rate follows the setpoint with a first-order lag (s), as a
 * rate loop would: the error and the measured rate's derivative both move. */
static const double sequence_lag_s[SEQ_COUNT] = {0.03, 0.03, 0.06};

/* Largest |library - transcription| over a sequence, as a fraction of the
 * transcription's peak |torque|. */
static double mismatch_of_peak(sequence_t s, const ladrc_axis_config_t *cfg, int n)
{
    ladrc_axis_t axis;
    init_axis(&axis, cfg);
    px4_rate_t px4 = {.p = (double)cfg->cas_rate_kp,
                      .i = (double)cfg->cas_rate_ki,
                      .d = (double)cfg->cas_rate_kd,
                      .ff = (double)cfg->cas_rate_ff,
                      .i_lim_Nm = (double)cfg->cas_i_limit_Nm,
                      .relax_rad_s = (double)cfg->cas_i_relax_rad_s,
                      .tau_d_s = (double)cfg->cas_d_filter_tau_s};
    double rate = 0.0, peak = 0.0, worst = 0.0;
    for (int k = 0; k < n; ++k) {
        const double sp = setpoint_of(s, k);
        const double u_lib = library_tick(&axis, sp, rate);
        const double u_px4 = px4_rate_update(&px4, sp, rate, 0);
        peak = fmax(peak, fabs(u_px4));
        worst = fmax(worst, fabs(u_lib - u_px4));
        rate += DT_S / sequence_lag_s[s] * (sp - rate);
    }
    return worst / peak;
}

static void test_rate_loop_matches_the_px4_transcription(void)
{
    /* given: the default rate gains and relax, an integral bound of 0.5 N m
     * (the step reaches it), without and with a rate feed-forward gain */
    for (int with_ff = 0; with_ff <= 1; ++with_ff) {
        ladrc_axis_config_t cfg = rate_loop_config();
        cfg.cas_i_limit_Nm = LADRC_R(0.5);
        cfg.cas_rate_ff = with_ff ? LADRC_R(0.25) * cfg.cas_rate_kp : LADRC_R(0.0);
        for (int s = 0; s < SEQ_COUNT; ++s) {
            /* when: 2 s of the sequence through both */
            const double m = mismatch_of_peak((sequence_t)s, &cfg, 2000);
            printf("%-16s K_ff %.4f N m s/rad: largest mismatch %.2e of the peak torque\n", sequence_name[s],
                   (double)cfg.cas_rate_ff, m);
            /* then */
            TEST_ASSERT_TRUE(m <= MATCH_TOL_OF_PEAK);
        }
    }
}

/* ---- the parts, one by one ------------------------------------------------- */

static void test_relax_stops_the_integrator_beyond_400_deg_s(void)
{
    /* given: a stalled axis (rate 0) asked for 8 rad/s, beyond the default
     * relax of 400 deg/s (6.98 rad/s) */
    const ladrc_axis_config_t cfg = rate_loop_config();
    TEST_ASSERT_TRUE(fabs((double)cfg.cas_i_relax_rad_s - RELAX_PX4_RAD_S) <= 1e-6);
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    /* when: 100 ticks */
    for (int k = 0; k < 100; ++k) {
        (void)library_tick(&axis, 8.0, 0.0);
    }
    /* then: the relax factor is 0, the integrator never moved */
    TEST_ASSERT_TRUE(axis.part.cas.integral_Nm == LADRC_R(0.0));
    /* and at 200 deg/s one tick integrates g = 1 - (200 / 400)^2 = 0.75 of
     * the plain step; without the relax (INFINITY) all of it */
    const double e = 200.0 * PI_D / 180.0, ki = (double)cfg.cas_rate_ki;
    init_axis(&axis, &cfg);
    (void)library_tick(&axis, e, 0.0);
    TEST_ASSERT_TRUE(fabs((double)axis.part.cas.integral_Nm - 0.75 * ki * DT_S * e) <= HAND_TOL_NM);
    ladrc_axis_config_t off = cfg;
    off.cas_i_relax_rad_s = (ladrc_real_t)INFINITY;
    init_axis(&axis, &off);
    (void)library_tick(&axis, e, 0.0);
    TEST_ASSERT_TRUE(fabs((double)axis.part.cas.integral_Nm - ki * DT_S * e) <= HAND_TOL_NM);
    (void)library_tick(&axis, 8.0, 0.0); /* no relax: 8 rad/s integrates too */
    TEST_ASSERT_TRUE(fabs((double)axis.part.cas.integral_Nm - ki * DT_S * (e + 8.0)) <= HAND_TOL_NM);
}

static void test_rate_feed_forward_adds_k_ff_times_the_setpoint(void)
{
    /* given: twins but for K_ff = 0.1 N m s/rad, on the sine with a lagging rate */
    const ladrc_axis_config_t plain = rate_loop_config();
    ladrc_axis_config_t fed = plain;
    fed.cas_rate_ff = LADRC_R(0.1);
    ladrc_axis_t a, b;
    init_axis(&a, &plain);
    init_axis(&b, &fed);
    double rate = 0.0, worst = 0.0;
    for (int k = 0; k < 1000; ++k) {
        /* when */
        const double sp = setpoint_of(SEQ_SINE, k);
        const double ua = library_tick(&a, sp, rate), ub = library_tick(&b, sp, rate);
        /* then: the difference is K_ff times the setpoint the loop formed,
         * and the rest of the loop (its integral) is the same */
        worst = fmax(worst, fabs((ub - ua) - 0.1 * (double)b.part.cas.rate_sp_rad_s));
        TEST_ASSERT_TRUE(a.part.cas.integral_Nm == b.part.cas.integral_Nm);
        rate += DT_S / 0.03 * (sp - rate);
    }
    TEST_ASSERT_TRUE(worst <= HAND_TOL_NM);
}

static void test_landed_holds_the_integrator_and_flight_resumes_it(void)
{
    /* given: an axis that integrated a 1 rad/s error for 100 ticks */
    const ladrc_axis_config_t cfg = rate_loop_config();
    ladrc_axis_t axis;
    init_axis(&axis, &cfg);
    for (int k = 0; k < 100; ++k) {
        (void)library_tick(&axis, 1.0, 0.0);
    }
    const ladrc_real_t held = axis.part.cas.integral_Nm;
    TEST_ASSERT_TRUE(held > LADRC_R(0.0));
    /* when: landed for 300 ticks with errors of both signs */
    ladrc_axis_set_landed(&axis, 1u);
    double u_first = 0.0, u_last = 0.0;
    for (int k = 0; k < 300; ++k) {
        const double u = library_tick(&axis, (k < 150) ? 1.0 : -2.0, 0.0);
        u_first = (k == 0) ? u : u_first;
        u_last = u;
        /* then: the integral does not change on any tick */
        TEST_ASSERT_TRUE(axis.part.cas.integral_Nm == held);
    }
    /* while the P term still acts on the error */
    const double kp = (double)cfg.cas_rate_kp;
    TEST_ASSERT_TRUE(fabs((u_first - u_last) - kp * 3.0) <= HAND_TOL_NM);
    /* a reset while landed (e.g. a fault restart) keeps the flag */
    ladrc_axis_reset(&axis, LADRC_R(0.0));
    (void)library_tick(&axis, 1.0, 0.0);
    TEST_ASSERT_TRUE(axis.part.cas.integral_Nm == LADRC_R(0.0));
    /* and in flight again the next tick integrates g ki h e */
    ladrc_axis_set_landed(&axis, 0u);
    (void)library_tick(&axis, 1.0, 0.0);
    const double x = 1.0 / RELAX_PX4_RAD_S;
    TEST_ASSERT_TRUE(fabs((double)axis.part.cas.integral_Nm - (1.0 - x * x) * (double)cfg.cas_rate_ki * DT_S) <=
                     HAND_TOL_NM);
    /* init starts in flight */
    ladrc_axis_set_landed(&axis, 7u); /* any non-zero value is landed */
    TEST_ASSERT_EQUAL_UINT8(1u, axis.part.cas.landed);
    init_axis(&axis, &cfg);
    TEST_ASSERT_EQUAL_UINT8(0u, axis.part.cas.landed);
}

static void test_landed_on_the_module_itself(void)
{
    /* given: the cascaded module alone, a rate error of 1 rad/s */
    ladrc_cascaded_config_t cfg = {.dt_s = (ladrc_real_t)DT_S,
                                   .att_kp_per_s = LADRC_R(10.0),
                                   .rate_max_rad_s = LADRC_R(5.0),
                                   .rate_kp = LADRC_R(0.4),
                                   .rate_ki = LADRC_R(6.0),
                                   .rate_kd = LADRC_R(0.001),
                                   .d_filter_tau_s = LADRC_R(0.002),
                                   .rate_filter_tau_s = LADRC_R(0.002),
                                   .i_limit_Nm = (ladrc_real_t)INFINITY,
                                   .rate_limit_rad_s = LADRC_R(100.0),
                                   .u_min_Nm = -(ladrc_real_t)INFINITY,
                                   .u_max_Nm = (ladrc_real_t)INFINITY,
                                   .wrap_angle = 0u,
                                   .i_relax_rad_s = (ladrc_real_t)INFINITY,
                                   .rate_ff = LADRC_R(0.0),
                                   .setpoint_ff = 1u};
    ladrc_cascaded_t c;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_cascaded_init(&c, &cfg));
    const ladrc_ref_t ref = {.r = LADRC_R(0.0), .dr = LADRC_R(1.0), .ddr = LADRC_R(0.0)};
    const ladrc_real_t rate = LADRC_R(0.0);
    ladrc_real_t u;
    /* when: landed for 50 ticks, then flying for 1 */
    ladrc_cascaded_set_landed(&c, 1u);
    for (int k = 0; k < 50; ++k) {
        TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_cascaded_step(&c, &ref, LADRC_R(0.0), &rate, &u));
        TEST_ASSERT_TRUE(c.integral_Nm == LADRC_R(0.0));
    }
    ladrc_cascaded_set_landed(&c, 0u);
    TEST_ASSERT_EQUAL_UINT(LADRC_FAULT_NONE, ladrc_cascaded_step(&c, &ref, LADRC_R(0.0), &rate, &u));
    /* then: the one flying tick integrated ki h e */
    TEST_ASSERT_TRUE(fabs((double)c.integral_Nm - 6.0 * DT_S * 1.0) <= HAND_TOL_NM);
}

static void test_landed_holds_the_pid_integrator_too(void)
{
    /* given: PID twins, one told it is landed; when: the same 500 ticks */
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    ladrc_axis_t a, b;
    init_axis(&a, &cfg);
    init_axis(&b, &cfg);
    ladrc_axis_set_landed(&b, 1u);
    for (int k = 0; k < 500; ++k) {
        const ladrc_real_t ref = (ladrc_real_t)(0.1 * sin(3.0 * k * DT_S));
        (void)axis_command_with_rate(&a, ref, LADRC_R(0.0), LADRC_R(0.0));
        (void)axis_command_with_rate(&b, ref, LADRC_R(0.0), LADRC_R(0.0));
        /* then: the landed one never integrates, the other does */
        TEST_ASSERT_TRUE(b.part.pid.integral_Nm == LADRC_R(0.0));
    }
    TEST_ASSERT_TRUE(a.part.pid.integral_Nm != LADRC_R(0.0));
}

/* ---- setpoint feed-forward -------------------------------------------------- */

static void test_attitude_default_feeds_the_setpoint_forward_on_yaw_only(void)
{
    /* given: the attitude default for CASCADED (as PX4: yaw only) and the
     * single-axis default (unchanged: on) */
    const ladrc_real_t inertia[LADRC_AXES] = {(ladrc_real_t)J_KG_M2, (ladrc_real_t)J_KG_M2, LADRC_R(0.01)};
    ladrc_attitude_config_t att;
    ladrc_attitude_config_default(&att, LADRC_VARIANT_CASCADED, (ladrc_real_t)DT_S, inertia, LADRC_R(0.0));
    ladrc_axis_config_t one;
    ladrc_axis_config_default(&one, LADRC_VARIANT_CASCADED, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    /* then */
    TEST_ASSERT_EQUAL_UINT8(0u, att.axis[LADRC_ROLL].cas_setpoint_ff);
    TEST_ASSERT_EQUAL_UINT8(0u, att.axis[LADRC_PITCH].cas_setpoint_ff);
    TEST_ASSERT_EQUAL_UINT8(1u, att.axis[LADRC_YAW].cas_setpoint_ff);
    TEST_ASSERT_EQUAL_UINT8(1u, one.cas_setpoint_ff);
    ladrc_attitude_t controller;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&controller, &att, NULL));
}

static void test_setpoint_feed_forward_adds_the_shaped_rate(void)
{
    /* given: twins on the TD-shaped reference (a 0.3 rad step), one with
     * cas_setpoint_ff 0; a stalled axis */
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_CASCADED, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.cas_rate_max_rad_s = LADRC_R(20.0); /* the sum stays unclamped */
    ladrc_axis_t fed, plain;
    init_axis(&fed, &cfg);
    cfg.cas_setpoint_ff = 0u;
    init_axis(&plain, &cfg);
    double worst_fed = 0.0, worst_plain = 0.0, largest_dr = 0.0;
    for (int k = 0; k < 300; ++k) {
        /* when */
        (void)axis_command_with_rate(&fed, LADRC_R(0.3), LADRC_R(0.0), LADRC_R(0.0));
        (void)axis_command_with_rate(&plain, LADRC_R(0.3), LADRC_R(0.0), LADRC_R(0.0));
        ladrc_ref_t ref;
        ladrc_axis_get_reference(&fed, &ref);
        const double p_term = (double)cfg.cas_att_kp * (double)ref.r;
        /* then: w_sp = att_kp r + r' with it, att_kp r without */
        worst_fed = fmax(worst_fed, fabs((double)fed.part.cas.rate_sp_rad_s - (p_term + (double)ref.dr)));
        worst_plain = fmax(worst_plain, fabs((double)plain.part.cas.rate_sp_rad_s - p_term));
        largest_dr = fmax(largest_dr, fabs((double)ref.dr));
    }
    TEST_ASSERT_TRUE(largest_dr > 1.0); /* the shaped rate was there to feed */
    TEST_ASSERT_TRUE(worst_fed <= SETPOINT_TOL_RAD_S);
    TEST_ASSERT_TRUE(worst_plain <= SETPOINT_TOL_RAD_S);
}

/* ---- validation --------------------------------------------------------------- */

static void test_init_refuses_bad_new_fields_with_their_own_status(void)
{
    const ladrc_real_t inf = (ladrc_real_t)INFINITY, nan_ = (ladrc_real_t)NAN;
    const ladrc_real_t relax_bad[] = {LADRC_R(0.0), LADRC_R(-1.0), nan_, -inf,
                                      LADRC_REAL_MIN * LADRC_R(1e-3)}; /* a subnormal: infinite inverse */
    ladrc_axis_t axis;
    for (size_t i = 0; i < sizeof relax_bad / sizeof relax_bad[0]; ++i) {
        ladrc_axis_config_t cfg = rate_loop_config();
        cfg.cas_i_relax_rad_s = relax_bad[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(LADRC_ERR_CAS_I_RELAX, ladrc_axis_init(&axis, &cfg), "relax");
    }
    /* the term K_ff rate_max beyond a quarter of the real type's range */
    const ladrc_real_t ff_bad[] = {LADRC_R(-1e-3), nan_, inf, LADRC_REAL_MAX * LADRC_R(0.1)};
    for (size_t i = 0; i < sizeof ff_bad / sizeof ff_bad[0]; ++i) {
        ladrc_axis_config_t cfg = rate_loop_config();
        cfg.cas_rate_ff = ff_bad[i];
        TEST_ASSERT_EQUAL_INT_MESSAGE(LADRC_ERR_CAS_RATE_FF, ladrc_axis_init(&axis, &cfg), "ff");
    }
    ladrc_axis_config_t cfg = rate_loop_config();
    cfg.cas_setpoint_ff = 2u;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_CAS_SETPOINT_FF, ladrc_axis_init(&axis, &cfg));
    /* the ends that are good: no relax, a small relax, a large gain */
    cfg = rate_loop_config();
    cfg.cas_i_relax_rad_s = inf;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    cfg.cas_i_relax_rad_s = LADRC_R(1e-3);
    cfg.cas_rate_ff = LADRC_R(1e3);
    cfg.cas_setpoint_ff = 0u;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    /* another variant does not read them */
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_PID, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.cas_i_relax_rad_s = nan_;
    cfg.cas_rate_ff = nan_;
    cfg.cas_setpoint_ff = 9u;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    /* the status texts name the fields */
    TEST_ASSERT_TRUE(strstr(ladrc_status_str(LADRC_ERR_CAS_I_RELAX), "LADRC_ERR_CAS_I_RELAX") != NULL);
    TEST_ASSERT_TRUE(strstr(ladrc_status_str(LADRC_ERR_CAS_RATE_FF), "LADRC_ERR_CAS_RATE_FF") != NULL);
    TEST_ASSERT_TRUE(strstr(ladrc_status_str(LADRC_ERR_CAS_SETPOINT_FF), "LADRC_ERR_CAS_SETPOINT_FF") != NULL);
}

static void test_landed_setters_ignore_null(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    ladrc_axis_set_landed(NULL, 1u);
    ladrc_cascaded_set_landed(NULL, 1u);
    TEST_ASSERT_TRUE(ladrc_axis_get_effectiveness(NULL) == LADRC_R(0.0));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_rate_loop_matches_the_px4_transcription);
    RUN_TEST(test_relax_stops_the_integrator_beyond_400_deg_s);
    RUN_TEST(test_rate_feed_forward_adds_k_ff_times_the_setpoint);
    RUN_TEST(test_landed_holds_the_integrator_and_flight_resumes_it);
    RUN_TEST(test_landed_on_the_module_itself);
    RUN_TEST(test_landed_holds_the_pid_integrator_too);
    RUN_TEST(test_attitude_default_feeds_the_setpoint_forward_on_yaw_only);
    RUN_TEST(test_setpoint_feed_forward_adds_the_shaped_rate);
    RUN_TEST(test_init_refuses_bad_new_fields_with_their_own_status);
    RUN_TEST(test_landed_setters_ignore_null);
    return UNITY_END();
}
