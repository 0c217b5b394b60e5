/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of the PID baseline (pid.c). */
#include "unity.h"
#include "ladrc/pid.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#ifdef LADRC_REAL_DOUBLE
#define REAL_MAX DBL_MAX
#else
#define REAL_MAX FLT_MAX
#endif

/* Hand computations: at most 100 accumulated roundings (2^-24 relative in
 * the float build) on values up to 4 N m: 100 * 4 * 6e-8 = 2.4e-5 N m. */
#define HAND_TOL_NM (3e-5)

/* Derivative filter: each step adds up to 2 roundings of 2^-24 on a value
 * <= 1 and the filter contracts old errors by (1 - alpha) per step, so the
 * error stays below 2 * 2^-24 / alpha = 2.5e-6 for alpha = 1/21; times kd = 1. */
#define FILTER_TOL_NM (1e-5)

/* Paper baseline gains and the test plant J theta'' = tau - kt theta' + tau_d. */
static const double dt_s = 1e-3;
static const double kp_paper = 20.0;
static const double ki_paper = 20.0;
static const double kd_paper = 0.05;
static const double inertia_kg_m2 = 5.445e-3;
static const double damping_Nms = 0.09;

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_pid_config_t make_config(double kp, double ki, double kd)
{
    ladrc_pid_config_t cfg;
    cfg.dt_s = (ladrc_real_t)dt_s;
    cfg.kp = (ladrc_real_t)kp;
    cfg.ki = (ladrc_real_t)ki;
    cfg.kd = (ladrc_real_t)kd;
    cfg.d_filter_tau_s = LADRC_R(0.0);
    cfg.i_limit_Nm = (ladrc_real_t)INFINITY;
    cfg.u_min_Nm = (ladrc_real_t)-INFINITY;
    cfg.u_max_Nm = (ladrc_real_t)INFINITY;
    cfg.wrap_angle = 0u;
    return cfg;
}

/* One tick's torque command (N m); the step's returned flags are the
 * tick's flags, as ladrc_pid_get_faults reports them. */
static ladrc_real_t pid_command(ladrc_pid_t *pid, ladrc_real_t ref_rad, ladrc_real_t meas_rad,
                                const ladrc_real_t *rate_rad_s)
{
    ladrc_real_t torque_Nm = LADRC_R(0.0);
    const ladrc_fault_t faults = ladrc_pid_step(pid, ref_rad, meas_rad, rate_rad_s, &torque_Nm);
    TEST_ASSERT_EQUAL_HEX8(ladrc_pid_get_faults(pid), faults);
    return torque_Nm;
}

static void init_pid(ladrc_pid_t *pid, const ladrc_pid_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_pid_init(pid, cfg));
}

/* ------------------------------------------------------------ test plant */

/* One rigid axis, J theta'' = tau - kt theta' + tau_d, torque held over each
 * step and integrated exactly (zero-order hold), in double. */
typedef struct {
    double theta_rad;
    double rate_rad_s;
    double decay;          /* exp(-kt dt / J) */
    double disturbance_Nm; /* constant tau_d */
} rigid_axis_t;

static void axis_init(rigid_axis_t *p, double disturbance_Nm)
{
    p->theta_rad = 0.0;
    p->rate_rad_s = 0.0;
    p->decay = exp(-damping_Nms / inertia_kg_m2 * dt_s);
    p->disturbance_Nm = disturbance_Nm;
}

static void axis_step(rigid_axis_t *p, double torque_Nm)
{
    const double a_per_s = damping_Nms / inertia_kg_m2;
    const double rate_ss = (torque_Nm + p->disturbance_Nm) / damping_Nms; /* terminal rate */
    const double rate0 = p->rate_rad_s;
    p->rate_rad_s = rate_ss + (rate0 - rate_ss) * p->decay;
    p->theta_rad += rate_ss * dt_s + (rate0 - rate_ss) * (1.0 - p->decay) / a_per_s;
}

/* ------------------------------------------------------- the three terms */

static void test_pid_proportional_term_is_kp_times_error(void)
{
    /* given: P only */
    const ladrc_pid_config_t cfg = make_config(20.0, 0.0, 0.0);
    ladrc_pid_t pid;
    init_pid(&pid, &cfg);
    /* when */
    const ladrc_real_t u = pid_command(&pid, LADRC_R(0.3), LADRC_R(0.1), NULL);
    /* then: 20 * (0.3 - 0.1) */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 4.0, u);
}

static void test_pid_integral_term_adds_ki_dt_error_every_step(void)
{
    /* given: I only, constant error 0.2 rad */
    const ladrc_pid_config_t cfg = make_config(0.0, 20.0, 0.0);
    ladrc_pid_t pid;
    ladrc_real_t u_first;
    ladrc_real_t u = LADRC_R(0.0);
    int k;
    init_pid(&pid, &cfg);
    /* when: 100 steps */
    u_first = pid_command(&pid, LADRC_R(0.2), LADRC_R(0.0), NULL);
    for (k = 1; k < 100; ++k) {
        u = pid_command(&pid, LADRC_R(0.2), LADRC_R(0.0), NULL);
    }
    /* then: the first step already integrates its error; 100 steps give 100 ki dt e */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 20.0 * 1e-3 * 0.2, u_first);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 100.0 * 20.0 * 1e-3 * 0.2, u);
}

static void test_pid_derivative_term_is_minus_kd_times_the_measurement_difference(void)
{
    /* given: D only, seeded at 0 */
    const ladrc_pid_config_t cfg = make_config(0.0, 0.0, 0.05);
    ladrc_pid_t pid;
    ladrc_real_t u1;
    ladrc_real_t u2;
    init_pid(&pid, &cfg);
    ladrc_pid_reset(&pid, LADRC_R(0.0));
    /* when: the measurement ramps by 0.01 rad per step (10 rad/s) */
    u1 = pid_command(&pid, LADRC_R(0.0), LADRC_R(0.01), NULL);
    u2 = pid_command(&pid, LADRC_R(0.0), LADRC_R(0.02), NULL);
    /* then: -kd * 10 rad/s on each step */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.5, u1);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.5, u2);
}

static void test_pid_derivative_uses_the_measured_rate_when_given(void)
{
    /* given: D only, a still measurement but a gyro reading 2 rad/s */
    const ladrc_pid_config_t cfg = make_config(0.0, 0.0, 0.05);
    const ladrc_real_t rate = LADRC_R(2.0);
    ladrc_pid_t with_rate;
    ladrc_pid_t without_rate;
    init_pid(&with_rate, &cfg);
    init_pid(&without_rate, &cfg);
    ladrc_pid_reset(&with_rate, LADRC_R(0.1));
    ladrc_pid_reset(&without_rate, LADRC_R(0.1));
    /* when */
    const ladrc_real_t u_rate = pid_command(&with_rate, LADRC_R(0.0), LADRC_R(0.1), &rate);
    const ladrc_real_t u_diff = pid_command(&without_rate, LADRC_R(0.0), LADRC_R(0.1), NULL);
    /* then: the gyro counts; the still measurement alone gives no derivative */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.1, u_rate);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, u_diff);
}

static void test_pid_first_step_after_init_has_no_derivative(void)
{
    /* given: D only, freshly initialised (no previous measurement) */
    const ladrc_pid_config_t cfg = make_config(0.0, 0.0, 0.05);
    ladrc_pid_t pid;
    init_pid(&pid, &cfg);
    /* when: the first measurement is far from 0 */
    const ladrc_real_t u = pid_command(&pid, LADRC_R(0.0), LADRC_R(1.0), NULL);
    /* then: no spurious kick from differencing against nothing */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, u);
}

static void test_pid_reference_step_gives_no_derivative_kick(void)
{
    /* given: the paper PID at rest on 0 */
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t pid;
    const double step_rad = 0.1745;
    init_pid(&pid, &cfg);
    ladrc_pid_reset(&pid, LADRC_R(0.0));
    (void)pid_command(&pid, LADRC_R(0.0), LADRC_R(0.0), NULL);
    /* when: the reference steps, the measurement has not moved */
    const ladrc_real_t u = pid_command(&pid, (ladrc_real_t)step_rad, LADRC_R(0.0), NULL);
    /* then: P and one step of I only (a derivative on the error would add 8.7 N m) */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, kp_paper * step_rad + ki_paper * dt_s * step_rad, u);
}

static void test_pid_derivative_filter_step_response_matches_the_first_order_formula(void)
{
    /* given: D only (kd = 1), tau = 20 dt, at rest */
    ladrc_pid_config_t cfg = make_config(0.0, 0.0, 1.0);
    const double tau_s = 0.02;
    const double alpha = dt_s / (tau_s + dt_s);
    const ladrc_real_t rate = LADRC_R(1.0);
    ladrc_pid_t pid;
    int k;
    cfg.d_filter_tau_s = (ladrc_real_t)tau_s;
    init_pid(&pid, &cfg);
    for (k = 1; k <= 200; ++k) {
        /* when: the measured rate steps to 1 rad/s */
        const ladrc_real_t u = pid_command(&pid, LADRC_R(0.0), LADRC_R(0.0), &rate);
        /* then: d_k = 1 - (1 - alpha)^k */
        TEST_ASSERT_FLOAT_WITHIN(FILTER_TOL_NM, -(1.0 - pow(1.0 - alpha, k)), u);
    }
}

/* ------------------------------------------------------------- clamps */

static void test_pid_integrator_is_clamped_to_i_limit(void)
{
    /* given: I only with a 0.5 N m clamp; 1000 steps of 1 rad would reach 20 N m */
    ladrc_pid_config_t cfg = make_config(0.0, 20.0, 0.0);
    ladrc_pid_t pid;
    ladrc_real_t u = LADRC_R(0.0);
    int k;
    cfg.i_limit_Nm = LADRC_R(0.5);
    init_pid(&pid, &cfg);
    /* when: positive error, then negative */
    for (k = 0; k < 1000; ++k) {
        u = pid_command(&pid, LADRC_R(1.0), LADRC_R(0.0), NULL);
    }
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.5, u);
    for (k = 0; k < 1000; ++k) {
        u = pid_command(&pid, LADRC_R(-1.0), LADRC_R(0.0), NULL);
    }
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.5, u);
}

static void test_pid_output_is_clamped_to_its_limits(void)
{
    /* given: P only, output within [-0.2, 0.3] */
    ladrc_pid_config_t cfg = make_config(20.0, 0.0, 0.0);
    ladrc_pid_t pid;
    cfg.u_min_Nm = LADRC_R(-0.2);
    cfg.u_max_Nm = LADRC_R(0.3);
    init_pid(&pid, &cfg);
    /* when / then */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.3, pid_command(&pid, LADRC_R(1.0), LADRC_R(0.0), NULL));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.2, pid_command(&pid, LADRC_R(-1.0), LADRC_R(0.0), NULL));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.1, pid_command(&pid, LADRC_R(0.005), LADRC_R(0.0), NULL));
}

static void test_pid_held_output_after_reset_lies_within_the_limits(void)
{
    /* given: an output range that excludes 0 */
    ladrc_pid_config_t cfg = make_config(20.0, 0.0, 0.0);
    ladrc_pid_t pid;
    cfg.u_min_Nm = LADRC_R(0.1);
    cfg.u_max_Nm = LADRC_R(0.3);
    init_pid(&pid, &cfg);
    /* when: the very first sample is bad, so the output is the held one */
    const ladrc_real_t u = pid_command(&pid, (ladrc_real_t)NAN, LADRC_R(0.0), NULL);
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.1, u);
}

/* ---------------------------------------------------------- anti-windup */

static void test_pid_integrator_does_not_wind_up_while_output_saturates(void)
{
    /* given: the paper PID on a stalled axis (meas stays 0) with a 0.5 N m output
     * limit, and its twin without limits; error 0.5 rad for 1 s */
    ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t saturated;
    ladrc_pid_t free_running;
    const ladrc_real_t ref = LADRC_R(0.5);
    int k;
    init_pid(&free_running, &cfg);
    cfg.u_min_Nm = LADRC_R(-0.5);
    cfg.u_max_Nm = LADRC_R(0.5);
    init_pid(&saturated, &cfg);

    /* when */
    for (k = 0; k < 1000; ++k) {
        (void)pid_command(&saturated, ref, LADRC_R(0.0), NULL);
        (void)pid_command(&free_running, ref, LADRC_R(0.0), NULL);
    }

    /* then: the unlimited one integrated ki * 1 s * 0.5 rad = 10 N m; the saturated
     * one only its first step (ki dt e = 0.01 N m), before it saw saturation */
    TEST_ASSERT_FLOAT_WITHIN(1000.0 * HAND_TOL_NM, 10.0, free_running.integral_Nm);
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, ki_paper * dt_s * 0.5, saturated.integral_Nm);
}

/* Which loop the recovery scenario runs. */
typedef enum { LOOP_PID_CLAMPS, LOOP_MIXER_CLAMPS, LOOP_UNLIMITED, LOOP_NAIVE_PID } loop_kind_t;

/* The reference sits at +A for t_hold_s, then reverses to -A for t_after_s.
 * Returns the time after the reversal when |theta + A| entered 2 % of A for
 * good (t_after_s if it never did); records theta of each step if theta_out. */
static double recovery_time_s(loop_kind_t kind, double limit_Nm, double amp_rad, double t_hold_s, double t_after_s,
                              double *theta_out)
{
    const ladrc_real_t limit = (ladrc_real_t)limit_Nm;
    ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t pid;
    rigid_axis_t axis;
    double naive_integral_Nm = 0.0;
    const int n_hold = (int)(t_hold_s / dt_s + 0.5);
    const int n_total = n_hold + (int)(t_after_s / dt_s + 0.5);
    int last_outside = n_total;
    int k;
    if (kind == LOOP_PID_CLAMPS) {
        cfg.u_min_Nm = -limit;
        cfg.u_max_Nm = limit;
    }
    init_pid(&pid, &cfg);
    axis_init(&axis, 0.0);

    for (k = 0; k < n_total; ++k) {
        const double ref = (k < n_hold) ? amp_rad : -amp_rad;
        const ladrc_real_t rate = (ladrc_real_t)axis.rate_rad_s;
        double torque_Nm;
        if (kind == LOOP_NAIVE_PID) {
            /* textbook PID in double, clamped output, integrator always running */
            const double e = ref - axis.theta_rad;
            naive_integral_Nm += ki_paper * dt_s * e;
            torque_Nm = kp_paper * e + naive_integral_Nm - kd_paper * axis.rate_rad_s;
            torque_Nm = (torque_Nm > limit_Nm) ? limit_Nm : ((torque_Nm < -limit_Nm) ? -limit_Nm : torque_Nm);
        } else {
            const ladrc_real_t u = pid_command(&pid, (ladrc_real_t)ref, (ladrc_real_t)axis.theta_rad, &rate);
            if (kind == LOOP_MIXER_CLAMPS) {
                const ladrc_real_t applied = ladrc_clamp(u, -limit, limit);
                ladrc_pid_set_applied(&pid, applied);
                torque_Nm = (double)applied;
            } else {
                torque_Nm = (double)u;
            }
        }
        axis_step(&axis, torque_Nm);
        if (theta_out != NULL) {
            theta_out[k] = axis.theta_rad;
        }
        if (k >= n_hold && fabs(axis.theta_rad + amp_rad) > 0.02 * amp_rad) {
            last_outside = k;
        }
        if (k < n_hold) {
            last_outside = k; /* only the time after the reversal counts */
        }
    }
    return (double)(last_outside + 1 - n_hold) * dt_s + dt_s;
}

/* Scenario: 0.5 rad, torque limit 0.3 N m (the proportional term alone asks
 * for 20 N m after the reversal), 1.5 s hold, 3 s after the reversal. */
#define RECOVERY_AMP_RAD (0.5)
#define RECOVERY_LIMIT_NM (0.3)
#define RECOVERY_HOLD_S (1.5)
#define RECOVERY_AFTER_S (3.0)

static void test_pid_recovers_quickly_after_the_reference_reverses_under_saturation(void)
{
    /* given / when: the same reversal with the PID's own clamp, without any
     * limit, and with a textbook PID that has no anti-windup */
    const double t_frozen =
        recovery_time_s(LOOP_PID_CLAMPS, RECOVERY_LIMIT_NM, RECOVERY_AMP_RAD, RECOVERY_HOLD_S, RECOVERY_AFTER_S, NULL);
    const double t_unlimited =
        recovery_time_s(LOOP_UNLIMITED, RECOVERY_LIMIT_NM, RECOVERY_AMP_RAD, RECOVERY_HOLD_S, RECOVERY_AFTER_S, NULL);
    const double t_naive =
        recovery_time_s(LOOP_NAIVE_PID, RECOVERY_LIMIT_NM, RECOVERY_AMP_RAD, RECOVERY_HOLD_S, RECOVERY_AFTER_S, NULL);
    /* The limited axis cannot go faster than its terminal rate limit / kt, so
     * travelling 2 A costs at least 2 A kt / limit = 0.3 s more than nothing;
     * allow that on top of the unlimited loop's own settling. */
    const double travel_s = 2.0 * RECOVERY_AMP_RAD * damping_Nms / RECOVERY_LIMIT_NM;

    /* then: the freeze keeps recovery within the physical bound; the naive
     * integrator (the check's counter-example) needs far longer */
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(t_unlimited + travel_s, t_frozen);
    TEST_ASSERT_GREATER_THAN_FLOAT(t_unlimited + travel_s, t_naive);
}

static void test_pid_integrator_freezes_when_the_mixer_reports_saturation(void)
{
    /* given: the same reversal, clamped either by the PID or by a mixer after
     * an unlimited PID that learns the applied torque from set_applied */
    static double theta_pid_clamps[4500];
    static double theta_mixer_clamps[4500];
    (void)recovery_time_s(LOOP_PID_CLAMPS, RECOVERY_LIMIT_NM, RECOVERY_AMP_RAD, RECOVERY_HOLD_S, RECOVERY_AFTER_S,
                          theta_pid_clamps);
    /* when */
    (void)recovery_time_s(LOOP_MIXER_CLAMPS, RECOVERY_LIMIT_NM, RECOVERY_AMP_RAD, RECOVERY_HOLD_S, RECOVERY_AFTER_S,
                          theta_mixer_clamps);
    /* then: the freeze acted the same in both: identical trajectories, bit for bit */
    TEST_ASSERT_EQUAL_MEMORY(theta_pid_clamps, theta_mixer_clamps, sizeof theta_pid_clamps);
}

static void test_pid_integrator_freezes_on_a_stalled_axis_when_the_mixer_saturates(void)
{
    /* given: the paper PID without limits; the mixer delivers at most 0.5 N m
     * and the axis is stalled (meas stays 0) */
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t pid;
    int k;
    init_pid(&pid, &cfg);
    /* when: 1 s of 0.5 rad error */
    for (k = 0; k < 1000; ++k) {
        const ladrc_real_t u = pid_command(&pid, LADRC_R(0.5), LADRC_R(0.0), NULL);
        ladrc_pid_set_applied(&pid, ladrc_clamp(u, LADRC_R(-0.5), LADRC_R(0.5)));
    }
    /* then: only the first step integrated (ki dt e = 0.01 N m) */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, ki_paper * dt_s * 0.5, pid.integral_Nm);
}

/* One step on error e after a step that commanded `unclamped` and reported `applied`. */
static double integral_after(double error_rad, double applied_Nm)
{
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, 0.0);
    ladrc_pid_t pid;
    init_pid(&pid, &cfg);
    ladrc_pid_reset(&pid, LADRC_R(0.0));
    /* the first step commands 20 * e + I_1 */
    (void)pid_command(&pid, (ladrc_real_t)error_rad, LADRC_R(0.0), NULL);
    ladrc_pid_set_applied(&pid, (ladrc_real_t)applied_Nm);
    (void)pid_command(&pid, (ladrc_real_t)error_rad, LADRC_R(0.0), NULL);
    return (double)pid.integral_Nm;
}

static void test_pid_integrator_freezes_only_when_integrating_would_deepen_the_saturation(void)
{
    /* given: error +-0.1 rad, so the command is about +-2 N m and one step
     * integrates ki dt e = +-0.002 N m */
    const double one_step = ki_paper * dt_s * 0.1;
    /* when / then: applied below the command, positive error: frozen */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, one_step, integral_after(0.1, 1.0));
    /* applied above the command, positive error: integrating moves the command towards it */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 2.0 * one_step, integral_after(0.1, 3.0));
    /* applied above the command, negative error: frozen */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -one_step, integral_after(-0.1, -1.0));
    /* applied below the command, negative error: integrating unwinds */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -2.0 * one_step, integral_after(-0.1, -3.0));
}

/* ----------------------------------------------------------- closed loop */

/* 10 degree step against a constant 0.1 N m disturbance torque, 10 s, rate from the "gyro". */
static double steady_error_after_10_degree_step(double ki)
{
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki, kd_paper);
    const double ref_rad = 10.0 * 3.14159265358979323846 / 180.0;
    ladrc_pid_t pid;
    rigid_axis_t axis;
    int k;
    init_pid(&pid, &cfg);
    axis_init(&axis, 0.1);
    for (k = 0; k < 10000; ++k) {
        const ladrc_real_t rate = (ladrc_real_t)axis.rate_rad_s;
        axis_step(&axis, (double)pid_command(&pid, (ladrc_real_t)ref_rad, (ladrc_real_t)axis.theta_rad, &rate));
    }
    return ref_rad - axis.theta_rad;
}

/* The closed loop J s^3 + (kt + kd) s^2 + kp s + ki has a slow pole at
 * -1.007 /s (near -ki / kp) and a fast pair at -12.4 +- 59.1j. The slow mode
 * carries the P-only offset tau_d / kp = 5e-3 rad (measured amplitude 1.25
 * times that); after 10 s it is left with 1.25 * 5e-3 * e^-10.07 = 2.7e-7 rad.
 * Allow 1e-6 rad: that plus 30 ulps of a float angle near 0.17 rad (4.5e-7). */
#define STEADY_ERR_TOL_RAD (1e-6)

static void test_pid_closed_loop_settles_a_10_degree_step_with_zero_steady_error(void)
{
    /* given / when */
    const double err_pid = steady_error_after_10_degree_step(ki_paper);
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(STEADY_ERR_TOL_RAD, 0.0, err_pid);
}

static void test_pid_without_integral_action_keeps_the_disturbance_offset(void)
{
    /* given / when: the same loop with ki = 0 (the counter-example of the test above) */
    const double err_pd = steady_error_after_10_degree_step(0.0);
    /* then: the offset tau_d / kp = -0.1 / 20 rad remains (same margin as above) */
    TEST_ASSERT_FLOAT_WITHIN(STEADY_ERR_TOL_RAD, -0.1 / kp_paper, err_pd);
}

/* ------------------------------------------------------------------ init */

static void expect_rejected(const ladrc_pid_config_t *cfg, ladrc_status_t status)
{
    ladrc_pid_t pid;
    TEST_ASSERT_EQUAL_INT(status, ladrc_pid_init(&pid, cfg));
}

static void test_pid_init_rejects_an_invalid_dt_s(void)
{
    const double bad[] = {0.0, -1e-3, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ladrc_pid_config_t cfg = make_config(1.0, 1.0, 1.0);
        cfg.dt_s = (ladrc_real_t)bad[i];
        expect_rejected(&cfg, LADRC_ERR_DT_S);
    }
}

static void test_pid_init_rejects_invalid_gains_each_with_its_own_status(void)
{
    const double bad[] = {-1.0, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        const ladrc_real_t b = (ladrc_real_t)bad[i];
        ladrc_pid_config_t cfg_p = make_config(1.0, 1.0, 1.0);
        ladrc_pid_config_t cfg_i = make_config(1.0, 1.0, 1.0);
        ladrc_pid_config_t cfg_d = make_config(1.0, 1.0, 1.0);
        ladrc_pid_config_t cfg_tau = make_config(1.0, 1.0, 1.0);
        cfg_p.kp = b;
        cfg_i.ki = b;
        cfg_d.kd = b;
        cfg_tau.d_filter_tau_s = b;
        expect_rejected(&cfg_p, LADRC_ERR_PID_KP);
        expect_rejected(&cfg_i, LADRC_ERR_PID_KI);
        expect_rejected(&cfg_d, LADRC_ERR_PID_KD);
        expect_rejected(&cfg_tau, LADRC_ERR_PID_D_TAU_S);
    }
}

static void test_pid_init_rejects_an_invalid_integrator_limit(void)
{
    const double bad[] = {-0.1, (double)NAN, (double)-INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ladrc_pid_config_t cfg = make_config(1.0, 1.0, 1.0);
        cfg.i_limit_Nm = (ladrc_real_t)bad[i];
        expect_rejected(&cfg, LADRC_ERR_PID_I_LIMIT_NM);
    }
}

static void test_pid_init_rejects_invalid_output_limits(void)
{
    const double bad_min[] = {(double)NAN, 0.0, 0.5, 1.0, (double)INFINITY, -1.0};
    const double bad_max[] = {1.0, (double)NAN, 0.5, 0.5, (double)INFINITY, (double)-INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad_min / sizeof bad_min[0]; ++i) {
        ladrc_pid_config_t cfg = make_config(1.0, 1.0, 1.0);
        cfg.u_min_Nm = (ladrc_real_t)bad_min[i];
        cfg.u_max_Nm = (ladrc_real_t)bad_max[i];
        expect_rejected(&cfg, LADRC_ERR_U_LIMITS);
    }
}

static void test_pid_init_rejects_null_pointers(void)
{
    const ladrc_pid_config_t cfg = make_config(1.0, 1.0, 1.0);
    ladrc_pid_t pid;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_pid_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_pid_init(&pid, NULL));
}

static void test_pid_init_accepts_zero_gains_and_infinite_limits(void)
{
    /* given: every field at the edge of its valid range */
    ladrc_pid_config_t cfg = make_config(0.0, 0.0, 0.0);
    ladrc_pid_t pid;
    cfg.i_limit_Nm = LADRC_R(0.0);
    /* when / then */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_pid_init(&pid, &cfg));
    cfg.i_limit_Nm = (ladrc_real_t)INFINITY;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_pid_init(&pid, &cfg));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, pid_command(&pid, LADRC_R(1.0), LADRC_R(0.0), NULL));
}

static void test_pid_rejected_by_init_outputs_zero(void)
{
    /* given: a PID whose init failed */
    ladrc_pid_config_t cfg = make_config(20.0, 20.0, 0.05);
    ladrc_pid_t pid;
    ladrc_real_t u = LADRC_R(1.0);
    int k;
    cfg.u_max_Nm = (ladrc_real_t)NAN;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_U_LIMITS, ladrc_pid_init(&pid, &cfg));
    /* when: it is stepped anyway */
    for (k = 0; k < 10; ++k) {
        u = pid_command(&pid, LADRC_R(1.0), (ladrc_real_t)(0.01 * k), NULL);
    }
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, u);
}

/* ---------------------------------------------------------------- faults */

static ladrc_real_t ref_at(int k)
{
    return (ladrc_real_t)(0.3 * sin(0.01 * k));
}
static ladrc_real_t meas_at(int k)
{
    return (ladrc_real_t)(0.25 * sin(0.01 * k - 0.2));
}

static void test_pid_holds_on_non_finite_reference_or_measurement_and_recovers_as_if_skipped(void)
{
    /* given: two PIDs on the same data (finite differences, filter, saturation);
     * one also sees bad samples */
    const ladrc_real_t nan_r = (ladrc_real_t)NAN;
    const ladrc_real_t inf_r = (ladrc_real_t)INFINITY;
    const ladrc_real_t bad_ref[] = {nan_r, LADRC_R(0.0), inf_r, -inf_r};
    const ladrc_real_t bad_meas[] = {LADRC_R(0.0), nan_r, -inf_r, nan_r};
    ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t clean;
    ladrc_pid_t faulty;
    ladrc_real_t u_clean[300];
    ladrc_real_t u_faulty[300];
    int k;
    cfg.d_filter_tau_s = LADRC_R(0.005);
    cfg.u_min_Nm = LADRC_R(-2.0);
    cfg.u_max_Nm = LADRC_R(2.0);
    init_pid(&clean, &cfg);
    init_pid(&faulty, &cfg);

    for (k = 0; k < 300; ++k) {
        u_clean[k] = pid_command(&clean, ref_at(k), meas_at(k), NULL);
        if (k % 60 == 30) {
            size_t i;
            for (i = 0; i < sizeof bad_ref / sizeof bad_ref[0]; ++i) {
                /* when: a bad sample */
                const ladrc_pid_t before = faulty;
                const ladrc_real_t held = pid_command(&faulty, bad_ref[i], bad_meas[i], NULL);
                /* then: input fault, previous output, state untouched */
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_pid_get_faults(&faulty));
                TEST_ASSERT_EQUAL_MEMORY(&before.output_Nm, &held, sizeof held);
                TEST_ASSERT_EQUAL_MEMORY(&before.integral_Nm, &faulty.integral_Nm, sizeof held);
                TEST_ASSERT_EQUAL_MEMORY(&before.d_filtered_rad_s, &faulty.d_filtered_rad_s, sizeof held);
                TEST_ASSERT_EQUAL_MEMORY(&before.prev_meas_rad, &faulty.prev_meas_rad, sizeof held);
            }
        }
        u_faulty[k] = pid_command(&faulty, ref_at(k), meas_at(k), NULL);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_pid_get_faults(&faulty));
    }

    /* then: the good steps match the run without bad samples, bit for bit */
    TEST_ASSERT_EQUAL_MEMORY(u_clean, u_faulty, sizeof u_clean);
}

static void test_pid_falls_back_to_the_finite_difference_on_a_non_finite_rate(void)
{
    /* given: two PIDs, one told a NaN or infinite rate, one given no rate */
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    const ladrc_real_t bad_rate[] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY};
    ladrc_pid_t told;
    ladrc_pid_t no_rate;
    int k;
    init_pid(&told, &cfg);
    init_pid(&no_rate, &cfg);
    for (k = 0; k < 100; ++k) {
        /* when */
        const ladrc_real_t u_told = pid_command(&told, ref_at(k), meas_at(k), &bad_rate[k % 2]);
        const ladrc_real_t u_no_rate = pid_command(&no_rate, ref_at(k), meas_at(k), NULL);
        /* then: same command, rate fault raised */
        TEST_ASSERT_EQUAL_MEMORY(&u_no_rate, &u_told, sizeof u_told);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_RATE, ladrc_pid_get_faults(&told));
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_pid_get_faults(&no_rate));
    }
}

static void test_pid_reports_both_faults_when_input_and_rate_are_bad(void)
{
    /* given */
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    const ladrc_real_t bad_rate = (ladrc_real_t)NAN;
    ladrc_pid_t pid;
    init_pid(&pid, &cfg);
    /* when */
    (void)pid_command(&pid, LADRC_R(0.0), (ladrc_real_t)NAN, &bad_rate);
    /* then */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT | LADRC_FAULT_RATE, ladrc_pid_get_faults(&pid));
}

static void test_pid_ignores_a_non_finite_applied_torque(void)
{
    /* given: two saturating PIDs; one is told a NaN or infinite applied torque */
    ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    const ladrc_real_t bad[] = {(ladrc_real_t)NAN, (ladrc_real_t)-INFINITY};
    ladrc_pid_t told;
    ladrc_pid_t untold;
    int k;
    cfg.u_min_Nm = LADRC_R(-1.0);
    cfg.u_max_Nm = LADRC_R(1.0);
    init_pid(&told, &cfg);
    init_pid(&untold, &cfg);
    for (k = 0; k < 100; ++k) {
        const ladrc_real_t u_told = pid_command(&told, ref_at(k), meas_at(k), NULL);
        const ladrc_real_t u_untold = pid_command(&untold, ref_at(k), meas_at(k), NULL);
        TEST_ASSERT_EQUAL_MEMORY(&u_untold, &u_told, sizeof u_told);
        /* when: a bad report, even after a good one (the mixer answering twice) */
        if (k % 3 == 0) {
            ladrc_pid_set_applied(&told, LADRC_R(0.0));
        }
        ladrc_pid_set_applied(&told, bad[k % 2]);
        /* then: applied fault added, the clamped output counts as applied */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_APPLIED, ladrc_pid_get_faults(&told));
    }
    TEST_ASSERT_EQUAL_MEMORY(&untold.integral_Nm, &told.integral_Nm, sizeof told.integral_Nm);
}

static void test_pid_holds_its_state_when_an_update_would_overflow(void)
{
    /* given: a PID with some history, and its twin */
    const ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    ladrc_pid_t pid;
    ladrc_pid_t twin;
    ladrc_real_t held;
    int k;
    init_pid(&pid, &cfg);
    init_pid(&twin, &cfg);
    for (k = 0; k < 10; ++k) {
        (void)pid_command(&pid, ref_at(k), meas_at(k), NULL);
        (void)pid_command(&twin, ref_at(k), meas_at(k), NULL);
    }
    /* when: finite inputs whose difference overflows */
    held = pid_command(&pid, REAL_MAX, -REAL_MAX, NULL);
    /* then: state fault, previous output held, state finite */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_get_faults(&pid));
    TEST_ASSERT_EQUAL_MEMORY(&twin.output_Nm, &held, sizeof held);
    TEST_ASSERT_FLOAT_IS_DETERMINATE(pid.integral_Nm);
    TEST_ASSERT_FLOAT_IS_DETERMINATE(pid.d_filtered_rad_s);
    /* and when sane inputs return, it continues as if the sample was skipped */
    for (k = 10; k < 20; ++k) {
        const ladrc_real_t u = pid_command(&pid, ref_at(k), meas_at(k), NULL);
        const ladrc_real_t u_twin = pid_command(&twin, ref_at(k), meas_at(k), NULL);
        TEST_ASSERT_EQUAL_MEMORY(&u_twin, &u, sizeof u);
    }
}

static void test_pid_holds_its_state_when_the_error_overflows_without_a_measurement_jump(void)
{
    /* given: PIDs with and without an integrator limit, resting on a measurement at -0.6 max */
    const double i_limits[] = {(double)INFINITY, 1.0};
    const ladrc_real_t far = REAL_MAX * LADRC_R(0.6);
    size_t i;
    for (i = 0; i < 2; ++i) {
        ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
        ladrc_pid_t pid;
        ladrc_real_t held;
        cfg.i_limit_Nm = (ladrc_real_t)i_limits[i];
        init_pid(&pid, &cfg);
        ladrc_pid_reset(&pid, -far);
        /* when: the reference is at +0.6 max: the derivative is 0, the error overflows */
        held = pid_command(&pid, far, -far, NULL);
        /* then: state fault, held output and integral */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_get_faults(&pid));
        TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, held);
        TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, pid.integral_Nm);
    }
}

static void test_pid_reset_with_a_non_finite_measurement_waits_for_a_good_one(void)
{
    /* given: D only */
    const ladrc_pid_config_t cfg = make_config(0.0, 0.0, 0.05);
    ladrc_pid_t pid;
    init_pid(&pid, &cfg);
    /* when */
    ladrc_pid_reset(&pid, (ladrc_real_t)NAN);
    /* then: input fault; the next measurement seeds the derivative without a kick */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_pid_get_faults(&pid));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, 0.0, pid_command(&pid, LADRC_R(0.0), LADRC_R(0.7), NULL));
    TEST_ASSERT_FLOAT_WITHIN(HAND_TOL_NM, -0.5, pid_command(&pid, LADRC_R(0.0), LADRC_R(0.71), NULL));
}

static void test_pid_functions_tolerate_a_null_instance(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL instances: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    /* when / then: no crash, neutral results */
    const ladrc_real_t rate = LADRC_R(1.0);
    ladrc_real_t torque_Nm = LADRC_R(1.0);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_step(NULL, LADRC_R(1.0), LADRC_R(0.0), &rate, &torque_Nm));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, torque_Nm); /* not written */
    ladrc_pid_reset(NULL, LADRC_R(0.0));
    ladrc_pid_set_applied(NULL, LADRC_R(0.0));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_pid_get_faults(NULL));
}

/* ----------------------------------------------------------- determinism */

/* Closed loop with mixer saturation and a filtered D on the finite difference. */
typedef struct {
    ladrc_pid_t pid;
    rigid_axis_t axis;
    int k;
} loop_t;

static void loop_run(loop_t *loop, ladrc_real_t *u_out, int n)
{
    int i;
    for (i = 0; i < n; ++i, ++loop->k) {
        const double ref = ((loop->k / 300) % 2 != 0) ? 0.4 : -0.3;
        const ladrc_real_t u = pid_command(&loop->pid, (ladrc_real_t)ref, (ladrc_real_t)loop->axis.theta_rad, NULL);
        const ladrc_real_t applied = ladrc_clamp(u, LADRC_R(-0.4), LADRC_R(0.4));
        ladrc_pid_set_applied(&loop->pid, applied);
        axis_step(&loop->axis, (double)applied);
        u_out[i] = u;
    }
}

static void loop_init(loop_t *loop)
{
    ladrc_pid_config_t cfg = make_config(kp_paper, ki_paper, kd_paper);
    cfg.d_filter_tau_s = LADRC_R(0.002);
    cfg.i_limit_Nm = LADRC_R(0.3);
    init_pid(&loop->pid, &cfg);
    axis_init(&loop->axis, 0.05);
    loop->k = 0;
}

static void test_pid_repeats_bitwise_after_reset(void)
{
    /* given: one run from init and reset */
    static loop_t loop;
    static ladrc_real_t first[1200];
    static ladrc_real_t second[1200];
    loop_init(&loop);
    ladrc_pid_reset(&loop.pid, LADRC_R(0.0));
    loop_run(&loop, first, 1200);
    /* when: the controller is reset and the plant restarted */
    ladrc_pid_reset(&loop.pid, LADRC_R(0.0));
    axis_init(&loop.axis, 0.05);
    loop.k = 0;
    loop_run(&loop, second, 1200);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(first, second, sizeof first);
}

static void test_pid_run_split_into_chunks_equals_a_single_run(void)
{
    /* given: one run in a single call */
    static loop_t single;
    static loop_t chunked;
    static loop_t moved;
    static ladrc_real_t u_single[1200];
    static ladrc_real_t u_chunked[1200];
    loop_init(&single);
    loop_run(&single, u_single, 1200);
    /* when: the same run in uneven chunks, with the state moved to new memory half way */
    loop_init(&chunked);
    loop_run(&chunked, u_chunked, 1);
    loop_run(&chunked, u_chunked + 1, 436);
    memcpy(&moved, &chunked, sizeof moved);
    loop_run(&moved, u_chunked + 437, 763);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(u_single, u_chunked, sizeof u_single);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_pid_proportional_term_is_kp_times_error);
    RUN_TEST(test_pid_integral_term_adds_ki_dt_error_every_step);
    RUN_TEST(test_pid_derivative_term_is_minus_kd_times_the_measurement_difference);
    RUN_TEST(test_pid_derivative_uses_the_measured_rate_when_given);
    RUN_TEST(test_pid_first_step_after_init_has_no_derivative);
    RUN_TEST(test_pid_reference_step_gives_no_derivative_kick);
    RUN_TEST(test_pid_derivative_filter_step_response_matches_the_first_order_formula);
    RUN_TEST(test_pid_integrator_is_clamped_to_i_limit);
    RUN_TEST(test_pid_output_is_clamped_to_its_limits);
    RUN_TEST(test_pid_held_output_after_reset_lies_within_the_limits);
    RUN_TEST(test_pid_integrator_does_not_wind_up_while_output_saturates);
    RUN_TEST(test_pid_recovers_quickly_after_the_reference_reverses_under_saturation);
    RUN_TEST(test_pid_integrator_freezes_when_the_mixer_reports_saturation);
    RUN_TEST(test_pid_integrator_freezes_on_a_stalled_axis_when_the_mixer_saturates);
    RUN_TEST(test_pid_integrator_freezes_only_when_integrating_would_deepen_the_saturation);
    RUN_TEST(test_pid_closed_loop_settles_a_10_degree_step_with_zero_steady_error);
    RUN_TEST(test_pid_without_integral_action_keeps_the_disturbance_offset);
    RUN_TEST(test_pid_init_rejects_an_invalid_dt_s);
    RUN_TEST(test_pid_init_rejects_invalid_gains_each_with_its_own_status);
    RUN_TEST(test_pid_init_rejects_an_invalid_integrator_limit);
    RUN_TEST(test_pid_init_rejects_invalid_output_limits);
    RUN_TEST(test_pid_init_rejects_null_pointers);
    RUN_TEST(test_pid_init_accepts_zero_gains_and_infinite_limits);
    RUN_TEST(test_pid_rejected_by_init_outputs_zero);
    RUN_TEST(test_pid_holds_on_non_finite_reference_or_measurement_and_recovers_as_if_skipped);
    RUN_TEST(test_pid_falls_back_to_the_finite_difference_on_a_non_finite_rate);
    RUN_TEST(test_pid_reports_both_faults_when_input_and_rate_are_bad);
    RUN_TEST(test_pid_ignores_a_non_finite_applied_torque);
    RUN_TEST(test_pid_holds_its_state_when_an_update_would_overflow);
    RUN_TEST(test_pid_holds_its_state_when_the_error_overflows_without_a_measurement_jump);
    RUN_TEST(test_pid_reset_with_a_non_finite_measurement_waits_for_a_good_one);
    RUN_TEST(test_pid_functions_tolerate_a_null_instance);
    RUN_TEST(test_pid_repeats_bitwise_after_reset);
    RUN_TEST(test_pid_run_split_into_chunks_equals_a_single_run);
    return UNITY_END();
}
