/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of Han's tracking differentiator (fhan, td.c). */
#include "unity.h"
#include "ladrc/td.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

/* Hand computations below chain about ten roundings of values up to |a0| = 6.4,
 * scaled by accel / d = 10: 10 * 6.4 * 10 * 2^-23 = 7.6e-5. */
#define FHAN_HAND_TOL (1e-4)

/* "Settled" means within 0.1 % of the step size, and the rate within 0.1 % of
 * step / t_opt (0.05 % of the peak rate 2 step / t_opt of the optimal profile). */
#define SETTLE_REL (1e-3)

/* With h0 = dt the discrete fhan is the time-optimal sampled control. The
 * settle time is a whole number of samples, so t_opt rounds up to the grid;
 * the switch and the arrival can each fall one sample late on top of that. */
#define SETTLE_MARGIN_STEPS_H0_EQ_DT (2.0)

/* With h0 > dt the last part of the approach runs in fhan's linear zone, a
 * critically damped pair with both poles at -1/h0; its error envelope
 * (1 + t/h0) exp(-t/h0) falls below SETTLE_REL at t = 9.23 h0. */
#define SETTLE_MARGIN_H0_MULTIPLES (9.3)

/* r' moves by h r'' per step; rounding the product and the sum costs up to
 * 4 eps relative (2 roundings of 2 eps bounds, generous). */
#define ACCEL_BOUND_REL (4.0 * LADRC_REAL_EPS)

static const double dt_s = 1e-3;

void setUp(void)
{
}
void tearDown(void)
{
}

static ladrc_td_config_t make_config(double dt, double accel, double h0)
{
    ladrc_td_config_t cfg;
    cfg.dt_s = (ladrc_real_t)dt;
    cfg.accel_rad_s2 = (ladrc_real_t)accel;
    cfg.h0_s = (ladrc_real_t)h0;
    return cfg;
}

static void init_td(ladrc_td_t *td, double accel, double h0)
{
    const ladrc_td_config_t cfg = make_config(dt_s, accel, h0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_td_init(td, &cfg));
}

/* A deterministic pseudo-random sequence in [-1, 1) (no libc rand state). */
static double lcg_uniform(unsigned long *seed)
{
    *seed = (*seed * 1103515245ul + 12345ul) & 0x7ffffffful;
    return (double)*seed / 1073741824.0 - 1.0;
}

/* ---------------------------------------------------------------- fhan */

static void test_fhan_never_exceeds_its_acceleration_bound(void)
{
    /* given: accelerations and filter factors from tiny to huge, and states
     * from 0 to the largest finite value with both signs */
    const double accels[] = {1e-20, 0.1, 50.0, 1e4, 1e30};
    const double h0s[] = {1e-20, 1e-3, 0.05, 2.0};
    const double mags[] = {
        0.0, 1e-30, 1e-6, 1e-3, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 1e3, 1e6, 1e15, 1e30, (double)LADRC_REAL_MAX};
    const size_t n_mag = sizeof mags / sizeof mags[0];
    size_t ia, ih, i1, i2;
    int s1, s2;

    for (ia = 0; ia < sizeof accels / sizeof accels[0]; ++ia) {
        for (ih = 0; ih < sizeof h0s / sizeof h0s[0]; ++ih) {
            const ladrc_real_t accel = (ladrc_real_t)accels[ia];
            const ladrc_real_t h0 = (ladrc_real_t)h0s[ih];
            for (i1 = 0; i1 < n_mag; ++i1) {
                for (i2 = 0; i2 < n_mag; ++i2) {
                    for (s1 = -1; s1 <= 1; s1 += 2) {
                        for (s2 = -1; s2 <= 1; s2 += 2) {
                            /* when */
                            const ladrc_real_t u =
                                ladrc_fhan((ladrc_real_t)(s1 * mags[i1]), (ladrc_real_t)(s2 * mags[i2]), accel, h0);
                            /* then */
                            TEST_ASSERT_FLOAT_IS_DETERMINATE(u);
                            /* exact (no float cast): checks the double build too */
                            TEST_ASSERT_TRUE(fabs((double)u) <= (double)accel);
                        }
                    }
                }
            }
        }
    }
}

static void test_fhan_never_exceeds_its_bound_on_the_edge_of_its_linear_zone(void)
{
    /* given: states exactly on the edge |a| = d = accel h0 (y = 0, x2 = +-d), where
     * accel a / d rounds to one ulp above accel unless the code guards it,
     * for 3000 pseudo-random (accel, h0) pairs spread over many octaves */
    unsigned long seed = 2024ul;
    int i;
    for (i = 0; i < 3000; ++i) {
        const ladrc_real_t accel =
            (ladrc_real_t)ldexp(1.5 + 0.5 * lcg_uniform(&seed), (int)(20.0 * lcg_uniform(&seed)));
        const ladrc_real_t h0 =
            (ladrc_real_t)ldexp(1.5 + 0.5 * lcg_uniform(&seed), -(int)(6.0 + 6.0 * lcg_uniform(&seed)));
        const ladrc_real_t x2 = (i % 2 != 0) ? accel * h0 : -(accel * h0);
        /* when */
        const ladrc_real_t u = ladrc_fhan(-h0 * x2, x2, accel, h0);
        /* then */
        TEST_ASSERT_TRUE(fabs((double)u) <= (double)accel);
    }
}

static void test_fhan_matches_hand_computation_in_each_zone(void)
{
    /* given: accel = 10, h0 = 0.1, so d = 1 and the linear zone is |y| <= 0.1 */
    const ladrc_real_t accel = LADRC_R(10.0);
    const ladrc_real_t h0 = LADRC_R(0.1);

    /* then: y = 0.05 (linear zone), a = 0.3 + 0.5 = 0.8, fhan = -10 * 0.8 / 1 */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -8.0, ladrc_fhan(LADRC_R(0.02), LADRC_R(0.3), accel, h0));
    /* then: y = 0.5, a0 = sqrt(41), a = (sqrt(41) - 1) / 2 = 2.70 > d: full braking */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -10.0, ladrc_fhan(LADRC_R(0.5), LADRC_R(0.0), accel, h0));
    /* then: mirrored error, mirrored answer */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 10.0, ladrc_fhan(LADRC_R(-0.5), LADRC_R(0.0), accel, h0));
    /* then: y = 0.25 - 0.1 = 0.15, beyond the linear zone: a0 = sqrt(13),
     * a = -1 + (sqrt(13) - 1) / 2 = 0.30 inside the boundary layer, fhan = -10 a */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -10.0 * (-1.0 + (sqrt(13.0) - 1.0) / 2.0),
                             ladrc_fhan(LADRC_R(0.25), LADRC_R(-1.0), accel, h0));
    /* then: approaching too fast: y = 0.25, a0 = sqrt(21), a = -2.5 + (sqrt(21) - 1) / 2,
     * inside the boundary layer, so fhan = -10 a (it brakes against the motion) */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -10.0 * (-2.5 + (sqrt(21.0) - 1.0) / 2.0),
                             ladrc_fhan(LADRC_R(0.5), LADRC_R(-2.5), accel, h0));
    /* then: at the origin nothing is pushed */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(0.0), LADRC_R(0.0), accel, h0));
}

static void test_fhan_saturates_towards_the_origin_for_an_infinite_error(void)
{
    /* given / when: an error so large it is infinite */
    const ladrc_real_t up = ladrc_fhan((ladrc_real_t)INFINITY, LADRC_R(0.0), LADRC_R(5.0), LADRC_R(0.01));
    const ladrc_real_t down = ladrc_fhan(LADRC_R(0.0), (ladrc_real_t)-INFINITY, LADRC_R(5.0), LADRC_R(0.01));

    /* then: full acceleration back towards the origin */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -5.0, up);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 5.0, down);
}

static void test_fhan_returns_zero_when_its_result_is_undefined(void)
{
    const ladrc_real_t nan_r = (ladrc_real_t)NAN;
    const ladrc_real_t inf_r = (ladrc_real_t)INFINITY;

    /* when / then: NaN state, opposite infinities, or an invalid bound or filter factor */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(nan_r, LADRC_R(1.0), LADRC_R(5.0), LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(1.0), nan_r, LADRC_R(5.0), LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(inf_r, -inf_r, LADRC_R(5.0), LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(1.0), LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(1.0), LADRC_R(0.0), inf_r, LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(1.0), LADRC_R(0.0), LADRC_R(5.0), -LADRC_R(0.01)));
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 0.0, ladrc_fhan(LADRC_R(1.0), LADRC_R(0.0), LADRC_R(5.0), nan_r));
}

/* ------------------------------------------------------------ TD steps */

/* Steps to a constant reference; returns the time (s) after which every
 * output stayed within the settle band, the output of step k standing for t = (k + 1) dt. */
static double settle_time_s(ladrc_td_t *td, double step_rad, double t_opt_s, int n_steps)
{
    const double pos_tol = SETTLE_REL * fabs(step_rad);
    const double vel_tol = SETTLE_REL * fabs(step_rad) / t_opt_s;
    int last_outside = -1;
    int k;
    for (k = 0; k < n_steps; ++k) {
        ladrc_ref_t out;
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_td_step(td, (ladrc_real_t)step_rad, &out));
        if (fabs((double)out.r - step_rad) > pos_tol || fabs((double)out.dr) > vel_tol) {
            last_outside = k;
        }
    }
    return (double)(last_outside + 2) * dt_s;
}

static void test_td_step_outputs_the_next_state_and_the_acceleration_that_moved_it(void)
{
    /* given: a TD at rest at 0, R = 100, far from the reference (full acceleration) */
    ladrc_td_t td;
    ladrc_ref_t first;
    ladrc_ref_t second;
    init_td(&td, 100.0, 0.01);
    /* when: two steps towards 1 */
    (void)ladrc_td_step(&td, LADRC_R(1.0), &first);
    (void)ladrc_td_step(&td, LADRC_R(1.0), &second);
    /* then: (x1_k+1, x2_k+1, a_k) with x1_k+1 = x1_k + h x2_k, x2_k+1 = x2_k + h a_k */
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL * dt_s, 0.0, first.r);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL * dt_s, 100.0 * dt_s, first.dr);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 100.0, first.ddr);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL * dt_s, dt_s * 100.0 * dt_s, second.r);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL * dt_s, 2.0 * 100.0 * dt_s, second.dr);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, 100.0, second.ddr);
}

static void test_td_reaches_a_step_within_the_time_optimal_bound_when_h0_equals_dt(void)
{
    const double accels[] = {50.0, 400.0, 5000.0};
    const double steps[] = {1.0, 0.1745, -0.5};
    size_t ia, is;
    for (ia = 0; ia < 3; ++ia) {
        for (is = 0; is < 3; ++is) {
            /* given: a TD at rest at 0 with h0 = dt */
            ladrc_td_t td;
            const double t_opt_s = 2.0 * sqrt(fabs(steps[is]) / accels[ia]);
            double t_settle_s;
            init_td(&td, accels[ia], dt_s);
            /* when: the reference steps, and we watch for 1 s beyond t_opt */
            t_settle_s = settle_time_s(&td, steps[is], t_opt_s, (int)(t_opt_s / dt_s) + 1000);
            /* then: it arrived and stayed within the bang-bang time plus the sampling margin */
            /* (half a sample of slack: both sides are sums of dt in double) */
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT((ceil(t_opt_s / dt_s) + SETTLE_MARGIN_STEPS_H0_EQ_DT + 0.5) * dt_s,
                                            t_settle_s);
        }
    }
}

static void test_td_reaches_a_step_within_the_time_optimal_bound_plus_its_filter_tail(void)
{
    const double accels[] = {50.0, 400.0, 5000.0};
    const double steps[] = {1.0, 0.1745, -0.5};
    const double h0_s = 5.0 * dt_s;
    size_t ia, is;
    for (ia = 0; ia < 3; ++ia) {
        for (is = 0; is < 3; ++is) {
            /* given: a TD at rest at 0 with a filtering h0 = 5 dt */
            ladrc_td_t td;
            const double t_opt_s = 2.0 * sqrt(fabs(steps[is]) / accels[ia]);
            double t_settle_s;
            init_td(&td, accels[ia], h0_s);
            /* when */
            t_settle_s = settle_time_s(&td, steps[is], t_opt_s, (int)(t_opt_s / dt_s) + 1000);
            /* then */
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT(t_opt_s + SETTLE_MARGIN_H0_MULTIPLES * h0_s, t_settle_s);
        }
    }
}

static void test_td_shaped_acceleration_never_exceeds_its_bound(void)
{
    /* given: a TD and a hostile reference: random jumps, large steps, noise, huge values */
    const double accel = 300.0;
    const double bound = accel * (1.0 + ACCEL_BOUND_REL);
    unsigned long seed = 12345ul;
    ladrc_td_t td;
    ladrc_ref_t prev = {0};
    int k;
    init_td(&td, accel, 3.0 * dt_s);

    for (k = 0; k < 20000; ++k) {
        double ref;
        ladrc_ref_t out;
        if (k < 5000) {
            ref = ((k / 250) % 2 != 0) ? 1.0 : -1.0; /* square wave */
        } else if (k < 10000) {
            ref = 0.3 * lcg_uniform(&seed); /* white noise */
        } else if (k < 15000) {
            ref = ((k / 1000) % 2 != 0) ? 1e6 : -1e6; /* huge steps */
        } else {
            ref = 1e30 * lcg_uniform(&seed); /* absurd values */
        }
        /* when */
        (void)ladrc_td_step(&td, (ladrc_real_t)ref, &out);
        /* then: |r''| <= R exactly, and r' moved by at most R dt up to rounding */
        TEST_ASSERT_TRUE(fabs((double)out.ddr) <= accel);
        if (k > 0) {
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT(bound * dt_s + 4.0 * LADRC_REAL_EPS * fabs((double)out.dr),
                                            fabs((double)out.dr - (double)prev.dr));
        }
        prev = out;
    }
}

static void test_td_tracks_a_slow_sinusoid_with_a_lag_of_about_two_h0(void)
{
    /* given: r = A sin(w t) with A w^2 = 0.8 << R = 400, and h0 = 10 dt. The
     * error y stays below 3 h0 A w = 0.012 < R h0^2 = 0.04, so fhan runs in its
     * linear zone: x1'' = -(2 x2 / h0 + (x1 - r) / h0^2), whose steady error to
     * a sinusoid has amplitude A h0 w sqrt(4 + h0^2 w^2) / (1 + h0^2 w^2)
     * (about 2 h0 A w: a lag of 2 h0), and in the rate w times that. The output
     * of step k is one sample ahead of r_k, so the discrete error is smaller;
     * one sample of reference motion (dt A w, dt A w^2) covers the sampling. */
    const double amp_rad = 0.2;
    const double w_rad_s = 2.0;
    const double h0_s = 10.0 * dt_s;
    const double g =
        h0_s * w_rad_s * sqrt(4.0 + h0_s * h0_s * w_rad_s * w_rad_s) / (1.0 + h0_s * h0_s * w_rad_s * w_rad_s);
    const double pos_bound = amp_rad * g + dt_s * amp_rad * w_rad_s;
    const double rate_bound = amp_rad * w_rad_s * g + dt_s * amp_rad * w_rad_s * w_rad_s;
    double max_pos_err = 0.0;
    double max_rate_err = 0.0;
    ladrc_td_t td;
    int k;
    init_td(&td, 400.0, h0_s);

    /* when: 7 s (2.2 periods), judging after a 1 s transient (100 h0) */
    for (k = 0; k < 7000; ++k) {
        const double t = k * dt_s;
        const double ref = amp_rad * sin(w_rad_s * t);
        ladrc_ref_t out;
        (void)ladrc_td_step(&td, (ladrc_real_t)ref, &out);
        if (t >= 1.0) {
            const double pos_err = fabs((double)out.r - ref);
            const double rate_err = fabs((double)out.dr - amp_rad * w_rad_s * cos(w_rad_s * t));
            max_pos_err = (pos_err > max_pos_err) ? pos_err : max_pos_err;
            max_rate_err = (rate_err > max_rate_err) ? rate_err : max_rate_err;
        }
    }

    /* then */
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(pos_bound, max_pos_err);
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(rate_bound, max_rate_err);
}

/* ----------------------------------------------------------- init/reset */

static void test_td_init_rejects_an_invalid_dt_s(void)
{
    const double bad[] = {0.0, -1e-3, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        /* given */
        const ladrc_td_config_t cfg = make_config(bad[i], 100.0, 0.01);
        ladrc_td_t td;
        /* when / then */
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_td_init(&td, &cfg));
    }
}

static void test_td_init_rejects_an_invalid_acceleration_bound(void)
{
    const double bad[] = {0.0, -100.0, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        const ladrc_td_config_t cfg = make_config(dt_s, bad[i], 0.01);
        ladrc_td_t td;
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_TD_ACCEL_RAD_S2, ladrc_td_init(&td, &cfg));
    }
}

static void test_td_init_rejects_an_invalid_h0(void)
{
    const double bad[] = {0.5 * 1e-3, 0.0, -0.01, (double)NAN, (double)INFINITY};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        const ladrc_td_config_t cfg = make_config(dt_s, 100.0, bad[i]);
        ladrc_td_t td;
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_TD_H0_S, ladrc_td_init(&td, &cfg));
    }
}

static void test_td_init_rejects_null_pointers(void)
{
    const ladrc_td_config_t cfg = make_config(dt_s, 100.0, 0.01);
    ladrc_td_t td;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_td_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_td_init(&td, NULL));
}

static void test_td_init_accepts_h0_equal_to_dt_and_starts_at_rest_at_zero(void)
{
    /* given */
    const ladrc_td_config_t cfg = make_config(dt_s, 100.0, dt_s);
    ladrc_td_t td;
    ladrc_ref_t out;
    /* when */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_td_init(&td, &cfg));
    (void)ladrc_td_step(&td, LADRC_R(0.0), &out);
    /* then: zero reference from rest stays exactly at rest */
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.r);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.dr);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.ddr);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, td.faults);
}

static void test_td_rejected_by_init_outputs_zero_and_never_moves(void)
{
    /* given: a TD whose init failed */
    const ladrc_td_config_t cfg = make_config(dt_s, (double)NAN, 0.01);
    ladrc_td_t td;
    ladrc_ref_t out;
    int k;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_TD_ACCEL_RAD_S2, ladrc_td_init(&td, &cfg));
    /* when: it is stepped anyway */
    for (k = 0; k < 10; ++k) {
        (void)ladrc_td_step(&td, LADRC_R(1.0), &out);
    }
    /* then */
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.r);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.dr);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.ddr);
}

static void test_td_reset_restarts_at_rest_on_the_given_reference(void)
{
    /* given: a TD in motion */
    ladrc_td_t td;
    ladrc_ref_t out;
    int k;
    init_td(&td, 100.0, 0.01);
    for (k = 0; k < 50; ++k) {
        (void)ladrc_td_step(&td, LADRC_R(1.0), &out);
    }
    /* when */
    ladrc_td_reset(&td, LADRC_R(0.25));
    (void)ladrc_td_step(&td, LADRC_R(0.25), &out);
    /* then: it sits still on the new reference */
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.25, out.r);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.dr);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.ddr);
}

static void test_td_reset_on_a_non_finite_reference_stops_where_it_is_and_raises_input_fault(void)
{
    /* given: a TD part way to 1 */
    ladrc_td_t td;
    ladrc_ref_t out;
    ladrc_real_t x1_before;
    int k;
    init_td(&td, 100.0, 0.01);
    for (k = 0; k < 50; ++k) {
        (void)ladrc_td_step(&td, LADRC_R(1.0), &out);
    }
    x1_before = td.x1;
    /* when */
    ladrc_td_reset(&td, (ladrc_real_t)NAN);
    /* then */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, td.faults);
    TEST_ASSERT_EQUAL_MEMORY(&x1_before, &td.x1, sizeof x1_before);
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, td.x2);
}

/* ------------------------------------------------------------- faults */

static void test_td_holds_on_non_finite_reference_and_recovers_as_if_it_was_skipped(void)
{
    /* given: two TDs on the same reference; one also sees NaN and +-inf samples */
    const ladrc_real_t bad[] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY};
    ladrc_td_t clean;
    ladrc_td_t faulty;
    ladrc_ref_t out_clean[200];
    ladrc_ref_t out_faulty[200];
    int k;
    init_td(&clean, 200.0, 0.005);
    init_td(&faulty, 200.0, 0.005);

    for (k = 0; k < 200; ++k) {
        const ladrc_real_t ref = (ladrc_real_t)(0.5 * sin(0.05 * k));
        (void)ladrc_td_step(&clean, ref, &out_clean[k]);
        if (k == 40 || k == 100 || k == 150) {
            /* when: a burst of bad samples arrives before this good one */
            size_t i;
            for (i = 0; i < 3; ++i) {
                ladrc_ref_t held;
                const ladrc_td_t before = faulty;
                /* then: input fault, state held, the held state written out */
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_td_step(&faulty, bad[i], &held));
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, faulty.faults);
                TEST_ASSERT_EQUAL_MEMORY(&before.x1, &faulty.x1, sizeof before.x1);
                TEST_ASSERT_EQUAL_MEMORY(&before.x2, &faulty.x2, sizeof before.x2);
                TEST_ASSERT_EQUAL_MEMORY(&before.x1, &held.r, sizeof held.r);
                TEST_ASSERT_EQUAL_MEMORY(&before.x2, &held.dr, sizeof held.dr);
                TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, held.ddr);
            }
        }
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_td_step(&faulty, ref, &out_faulty[k]));
    }

    /* then: the good steps match the run that never saw the bad samples, bit for bit */
    TEST_ASSERT_EQUAL_MEMORY(out_clean, out_faulty, sizeof out_clean);
}

static void test_td_holds_its_state_when_the_position_would_overflow(void)
{
    /* given: a TD at the top of the range, still moving up */
    ladrc_td_t td;
    ladrc_ref_t out;
    ladrc_real_t x1_before;
    ladrc_real_t x2_before;
    init_td(&td, 100.0, 0.01);
    ladrc_td_reset(&td, LADRC_REAL_MAX);
    td.x2 = LADRC_REAL_MAX; /* white-box: no valid config gets here quickly */
    x1_before = td.x1;
    x2_before = td.x2;

    /* when */
    const ladrc_fault_t faults = ladrc_td_step(&td, LADRC_REAL_MAX, &out);

    /* then: state fault, state and output held and finite */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, faults);
    TEST_ASSERT_EQUAL_MEMORY(&x1_before, &td.x1, sizeof x1_before);
    TEST_ASSERT_EQUAL_MEMORY(&x2_before, &td.x2, sizeof x2_before);
    TEST_ASSERT_EQUAL_MEMORY(&x1_before, &out.r, sizeof out.r);
    TEST_ASSERT_TRUE(isfinite((double)out.dr)); /* not a float assert: DBL_MAX overflows float */
    TEST_ASSERT_FLOAT_WITHIN(1e-30, 0.0, out.ddr);
}

static void test_td_holds_its_state_when_the_rate_would_overflow(void)
{
    /* given: a valid but extreme TD (dt = h0 = 1 s, R = max / 4) at -0.6 max rising
     * at 0.9 max, its reference at +0.6 max: x1 - r overflows, fhan accelerates at +R */
    const ladrc_td_config_t extreme = make_config(1.0, (double)LADRC_REAL_MAX / 4.0, 1.0);
    ladrc_td_t td;
    ladrc_ref_t out;
    ladrc_real_t x1_before;
    ladrc_real_t x2_before;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_td_init(&td, &extreme));
    ladrc_td_reset(&td, -LADRC_REAL_MAX * LADRC_R(0.6));
    td.x2 = LADRC_REAL_MAX * LADRC_R(0.9); /* white-box, as above */
    x1_before = td.x1;
    x2_before = td.x2;

    /* when: x1 + h x2 stays finite, x2 + h R does not */
    const ladrc_fault_t faults = ladrc_td_step(&td, LADRC_REAL_MAX * LADRC_R(0.6), &out);

    /* then */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, faults);
    TEST_ASSERT_EQUAL_MEMORY(&x1_before, &td.x1, sizeof x1_before);
    TEST_ASSERT_EQUAL_MEMORY(&x2_before, &td.x2, sizeof x2_before);
    TEST_ASSERT_EQUAL_MEMORY(&x2_before, &out.dr, sizeof out.dr);
}

static void test_td_brakes_at_full_bound_when_the_error_overflows(void)
{
    /* given: a TD at the top of the range */
    ladrc_td_t td;
    ladrc_ref_t out;
    init_td(&td, 100.0, 0.01);
    ladrc_td_reset(&td, LADRC_REAL_MAX);
    /* when: the reference is at the bottom, so x1 - r overflows to +inf */
    const ladrc_fault_t faults = ladrc_td_step(&td, -LADRC_REAL_MAX, &out);
    /* then: a normal step at full braking, with a finite state */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, faults);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -100.0, out.ddr);
    TEST_ASSERT_FLOAT_WITHIN(FHAN_HAND_TOL, -100.0 * dt_s, out.dr);
    TEST_ASSERT_TRUE(isfinite((double)td.x1)); /* not a float assert: DBL_MAX overflows float */
}

static void test_td_step_and_reset_tolerate_null_pointers(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL instances: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    /* given */
    ladrc_td_t td;
    init_td(&td, 100.0, 0.01);
    /* when / then: no crash; a NULL instance reports a state fault, a NULL output is allowed */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_td_step(NULL, LADRC_R(1.0), NULL));
    ladrc_td_reset(NULL, LADRC_R(1.0));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_td_step(&td, LADRC_R(1.0), NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_td_step(&td, (ladrc_real_t)NAN, NULL));
    TEST_ASSERT_GREATER_THAN_FLOAT(0.0, td.x2);
}

/* ------------------------------------------------------ determinism */

static void run_square_wave(ladrc_td_t *td, ladrc_ref_t *out, int n)
{
    int k;
    for (k = 0; k < n; ++k) {
        (void)ladrc_td_step(td, ((k / 100) % 2 != 0) ? LADRC_R(0.3) : LADRC_R(-0.2), &out[k]);
    }
}

static void test_td_repeats_bitwise_after_reset(void)
{
    /* given: one run from init */
    ladrc_td_t td;
    ladrc_ref_t first[500];
    ladrc_ref_t second[500];
    init_td(&td, 250.0, 0.004);
    run_square_wave(&td, first, 500);
    /* when: reset to the initial state and run again */
    ladrc_td_reset(&td, LADRC_R(0.0));
    run_square_wave(&td, second, 500);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(first, second, sizeof first);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_fhan_never_exceeds_its_acceleration_bound);
    RUN_TEST(test_fhan_never_exceeds_its_bound_on_the_edge_of_its_linear_zone);
    RUN_TEST(test_fhan_matches_hand_computation_in_each_zone);
    RUN_TEST(test_fhan_saturates_towards_the_origin_for_an_infinite_error);
    RUN_TEST(test_fhan_returns_zero_when_its_result_is_undefined);
    RUN_TEST(test_td_step_outputs_the_next_state_and_the_acceleration_that_moved_it);
    RUN_TEST(test_td_reaches_a_step_within_the_time_optimal_bound_when_h0_equals_dt);
    RUN_TEST(test_td_reaches_a_step_within_the_time_optimal_bound_plus_its_filter_tail);
    RUN_TEST(test_td_shaped_acceleration_never_exceeds_its_bound);
    RUN_TEST(test_td_tracks_a_slow_sinusoid_with_a_lag_of_about_two_h0);
    RUN_TEST(test_td_init_rejects_an_invalid_dt_s);
    RUN_TEST(test_td_init_rejects_an_invalid_acceleration_bound);
    RUN_TEST(test_td_init_rejects_an_invalid_h0);
    RUN_TEST(test_td_init_rejects_null_pointers);
    RUN_TEST(test_td_init_accepts_h0_equal_to_dt_and_starts_at_rest_at_zero);
    RUN_TEST(test_td_rejected_by_init_outputs_zero_and_never_moves);
    RUN_TEST(test_td_reset_restarts_at_rest_on_the_given_reference);
    RUN_TEST(test_td_reset_on_a_non_finite_reference_stops_where_it_is_and_raises_input_fault);
    RUN_TEST(test_td_holds_on_non_finite_reference_and_recovers_as_if_it_was_skipped);
    RUN_TEST(test_td_holds_its_state_when_the_position_would_overflow);
    RUN_TEST(test_td_holds_its_state_when_the_rate_would_overflow);
    RUN_TEST(test_td_brakes_at_full_bound_when_the_error_overflows);
    RUN_TEST(test_td_step_and_reset_tolerate_null_pointers);
    RUN_TEST(test_td_repeats_bitwise_after_reset);
    return UNITY_END();
}
