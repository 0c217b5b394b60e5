/* SPDX-License-Identifier: BSD-3-Clause */
/* Tests of Levant's 3rd-order differentiator (levant.c): its discrete
 * equations, exactness on cubics, noise against Han's TD, chattering against
 * explicit Euler, validation, fault handling and determinism. */
#include "unity.h"
#include "ladrc/levant.h"
#include "ladrc/td.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define DT_S 1e-3

/* One step by hand: the library and the test evaluate the same few products
 * and roots of values below 100, a handful of roundings of 2^-23 each,
 * relative to the largest term. */
#define HAND_REL_TOL (1e-5)

/* In the set-valued branch s = q / (h^3 g0) divides the predicted error by
 * 1.1e-9 (L = 1000): a rounding of q at its ulp (1e-13 near 1e-6) moves s by
 * 1e-4 relative. */
#define SET_VALUED_REL_TOL (1e-3)

/* After the 16 Newton iterations allowed, a root that needs 20 is within 2 %
 * (measured: the error equation's residual is 6.7 % of q). */
#define NEWTON_CAP_REL_TOL (0.2)

/* The implicit step's root against the earlier solver (Newton from the
 * smallest bound until a step no longer decreases, reference_quartic_root):
 * both stop within about an ulp of u, and e = s u^4 multiplies that by 4
 * plus the roundings of u^2 u^2. Measured over the sweep: at most 6.0
 * LADRC_REAL_EPS relative in e in float, 6.2 in double, about 1.5 ulps of u; the
 * tolerance leaves 4 times that. Stopping one iteration early (a step of
 * 2^-12) would differ by 1e-3. */
#define ROOT_AGREEMENT_REL_TOL (24.0 * LADRC_REAL_EPS)

/* The published non-recursive coefficients 4.16 and 3.06 are the products
 * 2 * 3^(2/3) = 4.1602 and 1.5 * sqrt(2) * 3^(1/3) = 3.0596 rounded to three
 * digits: relative differences 5e-5 and 1.3e-4. */
#define COEFF_ROUNDING_REL (2e-4)

/* Cubic tests, L = 1, r in [0.1, 0.35]. Three sources of error, measured
 * from 4 s on (float / double):
 * - the rounding of the samples and of the state, eps = LADRC_REAL_EPS * 0.35,
 *   which any differentiator of this form turns into errors of order
 *   L^(i/4) eps^((4-i)/4) in the i-th derivative (Levant 2003): 4.2e-8,
 *   3.0e-6, 2.0e-4, 1.4e-2 in float. The implicit form has no other error
 *   (exact on cubics): measured 2.0e-8, 1.8e-6, 1.6e-4, 6.7e-3 in float,
 *   0, 2.0e-12, 3.5e-9, 2.2e-6 in double, the worst (double r') 2.7 times
 *   under CUBIC_NOISE_FACTOR times the scale, the float ones 13 to 21 times;
 * - for the explicit forms, the kick of g0 = h k0 per step: errors of order
 *   L h^(4-i) (Livne and Levant 2014), measured (HD, double) 8.7, 10, 7.3
 *   and 2.3 times L h^(4-i); CUBIC_STEP_FACTOR leaves 3 times of margin;
 * - Euler's chain lags: r' by h/2 r'' (1.5e-4) and r'' by h r''' (1.25e-4
 *   measured); CUBIC_EULER_LAG_STEPS steps of motion leave 2 to 4 times. */
#define CUBIC_LIPSCHITZ 1.0
#define CUBIC_R_MAX 0.35
#define CUBIC_NOISE_FACTOR 10.0
#define CUBIC_STEP_FACTOR 30.0
#define CUBIC_EULER_LAG_STEPS 2.0
/* From rest, every form is within its tolerances after 2.9 s (float) or
 * 3.0 s (double), measured; judged from 4 s to 5 s. */
#define CUBIC_SETTLED_S 4.0
#define CUBIC_END_S 5.0

/* Noisy sine (Table 3 of the paper; its Figure 5 does not give the sine):
 * r = sin(t) sampled at 1 kHz plus Gaussian noise of variance 0.001. Both
 * shapers start at rest and are judged from 2 s to 12 s (Levant with L = 10
 * is within 0.2 rad/s of r' from 1.65 s on, measured). */
#define NOISE_VARIANCE 1e-3
#define NOISE_JUDGE_FROM_S 2.0
#define NOISE_END_S 12.0
/* |sin''''| <= 1; L = 10, ten times the bound, so that the transient from
 * rest (r' starts 1 rad/s off) ends well within the first 2 s: with L = 1 it
 * lasts the whole run. Not a lucky pick: the RMS is 0.063, 0.039, 0.038,
 * 0.046, 0.057 for L = 5, 10, 20, 50, 100 against the TD's best 0.068. */
#define NOISE_LIPSCHITZ 10.0

/* Paper setting for the chattering test: L1 = L2 = L3 = 20 and L4 (not given
 * in the paper) = 1.1 (20/3)^4 = 2173, the lambda0 L of the L for which
 * L1 = 3 L^(1/4) = 20. Signal: the paper's roll reference
 * 5 deg + 15 deg cos(pi t / 2), whose r'' moves by h r''' = 7.2e-4 rad/s^2
 * per step (RMS). These gains take 2.7 s to converge from rest, so the run
 * is judged from 3 s to 7 s. Measured RMS of the r'' steps: implicit 4.5e-3
 * in float (the rounding of the samples, 1.5e-8, amplified), 7.2e-4 in
 * double (the signal's own steps: no chattering at all); Euler 0.26 in both
 * (HD 0.21). The threshold sits 6.7 times above the implicit and 8.6 times
 * below Euler. */
#define CHATTER_L123 20.0
#define CHATTER_L4 2173.0
#define CHATTER_STEP_RMS_TOL 0.03
#define CHATTER_JUDGE_FROM_S 3.0
#define CHATTER_END_S 7.0

void setUp(void)
{
}
void tearDown(void)
{
}

/* ------------------------------------------------------------ helpers */

static ladrc_levant_config_t lipschitz_config(ladrc_levant_method_t method, double lip)
{
    ladrc_levant_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dt_s = (ladrc_real_t)DT_S;
    cfg.method = method;
    cfg.gains = LADRC_LEVANT_GAINS_LIPSCHITZ;
    cfg.lipschitz_rad_s4 = (ladrc_real_t)lip;
    return cfg;
}

static ladrc_levant_config_t explicit_config(ladrc_levant_method_t method, double l1, double l2, double l3, double l4)
{
    ladrc_levant_config_t cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.dt_s = (ladrc_real_t)DT_S;
    cfg.method = method;
    cfg.gains = LADRC_LEVANT_GAINS_EXPLICIT;
    cfg.l1 = (ladrc_real_t)l1;
    cfg.l2 = (ladrc_real_t)l2;
    cfg.l3 = (ladrc_real_t)l3;
    cfg.l4 = (ladrc_real_t)l4;
    return cfg;
}

static void init_ok(ladrc_levant_t *lev, const ladrc_levant_config_t *cfg)
{
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_levant_init(lev, cfg));
}

/* The instant the state estimates after a step on the sample of t_k. */
static double estimate_time_s(ladrc_levant_method_t method, double t_k)
{
    return (method == LADRC_LEVANT_IMPLICIT) ? t_k : t_k + DT_S;
}

/* A deterministic N(0, 1) sequence: xorshift64 and Box-Muller (no libc rand). */
typedef struct {
    uint64_t s;
} gauss_rng_t;

static double rng_uniform(gauss_rng_t *g)
{
    g->s ^= g->s << 13;
    g->s ^= g->s >> 7;
    g->s ^= g->s << 17;
    return ((double)(g->s >> 11) + 0.5) / 9007199254740992.0; /* (0, 1) */
}

static double rng_gauss(gauss_rng_t *g)
{
    const double u1 = rng_uniform(g);
    const double u2 = rng_uniform(g);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

/* r = 0.1 + 0.3 t - 0.15 t^2 + 0.02 t^3 and its derivatives (r in [0.1, 0.35] on [0, 5] s). */
static double cubic(double t, int order)
{
    switch (order) {
    case 0:
        return 0.1 + t * (0.3 + t * (-0.15 + t * 0.02));
    case 1:
        return 0.3 + t * (-0.3 + t * 0.06);
    case 2:
        return -0.3 + t * 0.12;
    default:
        return 0.12;
    }
}

/* Paper roll reference (rad) and its derivatives. */
static double roll_ref(double t, int order)
{
    const double deg = 3.141592653589793 / 180.0;
    const double w = 3.141592653589793 / 2.0;
    const double a = 15.0 * deg;
    switch (order) {
    case 0:
        return 5.0 * deg + a * cos(w * t);
    case 1:
        return -a * w * sin(w * t);
    case 2:
        return -a * w * w * cos(w * t);
    default:
        return a * w * w * w * sin(w * t);
    }
}

/* ------------------------------------------------- discrete equations */

/* Non-recursive continuous gains for Levant's coefficients (levant.h). */
static void lipschitz_gains(double lip, double k[4])
{
    k[3] = 3.0 * pow(lip, 0.25);
    k[2] = 4.16 * pow(lip, 0.5);
    k[1] = 3.06 * pow(lip, 0.75);
    k[0] = 1.1 * lip;
}

static double spow(double e, double a)
{
    return (e > 0.0) ? pow(e, a) : -pow(-e, a);
}

/* Puts a fresh implicit or explicit instance (L = 1000) in motion by hand. */
static void start_moving(ladrc_levant_t *lev, ladrc_levant_method_t method, double r0, double v1, double v2, double v3)
{
    const ladrc_levant_config_t cfg = lipschitz_config(method, 1000.0);
    init_ok(lev, &cfg);
    ladrc_levant_reset(lev, (ladrc_real_t)r0);
    lev->z1 = (ladrc_real_t)v1; /* white-box: a state in motion */
    lev->z2 = (ladrc_real_t)v2;
    lev->z3 = (ladrc_real_t)v3;
}

/* The implicit step's quartic as levant.c solved it before its Newton
 * iterations started from a blend of the term bounds and stopped on the
 * step's size: from the smallest of the quartic, quadratic and linear bounds,
 * until a step no longer decreases (at most 16). */
static ladrc_real_t reference_quartic_root(ladrc_real_t d, ladrc_real_t a3, ladrc_real_t a2, ladrc_real_t a1)
{
    ladrc_real_t u = ladrc_sqrt(ladrc_sqrt(d));
    ladrc_real_t bound = ladrc_sqrt(d / a2);
    int i;
    u = (bound < u) ? bound : u;
    bound = d / a1;
    u = (bound < u) ? bound : u;
    for (i = 0; i < 16; ++i) {
        const ladrc_real_t p = (((u + a3) * u + a2) * u + a1) * u - d;
        const ladrc_real_t dp = ((LADRC_R(4.0) * u + LADRC_R(3.0) * a3) * u + LADRC_R(2.0) * a2) * u + a1;
        const ladrc_real_t next = u - p / dp;
        if (!(next < u)) {
            break;
        }
        u = next;
    }
    return u;
}

static void test_implicit_step_solves_its_error_equation_and_updates_as_documented(void)
{
    /* given: an implicit differentiator in motion, and a sample far from its prediction */
    const double h = DT_S;
    const double r0 = 0.2, v1 = 0.5, v2 = -3.0, v3 = 40.0;
    const ladrc_real_t rk = LADRC_R(0.22);
    ladrc_levant_t lev;
    ladrc_ref_t out;
    double k[4];
    lipschitz_gains(1000.0, k);
    start_moving(&lev, LADRC_LEVANT_IMPLICIT, r0, v1, v2, v3);

    /* when */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, rk, &out));

    /* then: e = z0+ - r_k solves the error equation, with p0 the Taylor prediction */
    {
        const double g3 = h * k[3], g2 = h * k[2], g1 = h * k[1], g0 = h * k[0];
        const double q = r0 + h * v1 + h * h / 2.0 * v2 + h * h * h / 6.0 * v3 - (double)rk;
        const double e = (double)out.r - (double)rk;
        const double s = (e > 0.0) ? 1.0 : -1.0;
        const double lhs =
            e + g3 * spow(e, 0.75) + h * g2 * spow(e, 0.5) + h * h * g1 * spow(e, 0.25) + h * h * h * g0 * s;
        const double p1 = v1 + h * v2 + h * h / 2.0 * v3;
        const double p2 = v2 + h * v3;
        const double z1 = p1 - g2 * spow(e, 0.5) - h * g1 * spow(e, 0.25) - 11.0 / 6.0 * h * h * g0 * s;
        const double z2 = p2 - g1 * spow(e, 0.25) - 2.0 * h * g0 * s;
        const double z3 = v3 - g0 * s;
        TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * fabs(q), q, lhs);
        /* and the other states take the documented corrections */
        TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(p1) + fabs(z1)), z1, out.dr);
        TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(p2) + fabs(z2)), z2, out.ddr);
        TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(v3) + fabs(z3)), z3, ladrc_levant_get_dddr(&lev));
    }
}

static void test_implicit_root_agrees_with_the_earlier_solver_over_forty_decades_of_error(void)
{
    /* given: Levant's gains for three L and the paper's, each at rest at 0 */
    const ladrc_levant_config_t cfgs[] = {
        lipschitz_config(LADRC_LEVANT_IMPLICIT, 1.0), lipschitz_config(LADRC_LEVANT_IMPLICIT, 1000.0),
        lipschitz_config(LADRC_LEVANT_IMPLICIT, 1e6),
        explicit_config(LADRC_LEVANT_IMPLICIT, CHATTER_L123, CHATTER_L123, CHATTER_L123, CHATTER_L4)};
    double worst = 0.0;
    int steps = 0;
    size_t c;
    for (c = 0; c < sizeof cfgs / sizeof cfgs[0]; ++c) {
        ladrc_levant_t lev;
        init_ok(&lev, &cfgs[c]);
        {
            const ladrc_real_t h = lev.h_s;
            const ladrc_real_t a0 = h * h * h * lev.g0; /* as the step forms it */
            double mag;
            /* when: one step on a sample -q, from just above the set-valued
             * band up to 1e30 rad, both signs; from rest the predicted error is q */
            for (mag = (double)a0 * 1.001; mag < 1e30; mag *= 1.1) {
                int sign;
                for (sign = -1; sign <= 1; sign += 2) {
                    const ladrc_real_t q = (ladrc_real_t)(sign * mag);
                    ladrc_real_t u;
                    ladrc_real_t u2;
                    double expected;
                    ladrc_levant_reset(&lev, LADRC_R(0.0));
                    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, -q, NULL));
                    /* then: the new error e = s u^4 (white-box: kept in w) is the earlier one */
                    u = reference_quartic_root(ladrc_fabs(q) - a0, lev.g3, h * lev.g2, h * h * lev.g1);
                    u2 = u * u;
                    expected = (double)((ladrc_real_t)sign * u2 * u2);
                    {
                        const double rel = fabs((double)lev.w - expected) / fabs(expected);
                        TEST_ASSERT_LESS_THAN_FLOAT(ROOT_AGREEMENT_REL_TOL, rel);
                        worst = (rel > worst) ? rel : worst;
                    }
                    ++steps;
                }
            }
        }
    }
    {
        char msg[120];
        snprintf(msg, sizeof msg, "%d steps: largest relative difference in e %.3g (%.2f LADRC_REAL_EPS)", steps, worst,
                 worst / LADRC_REAL_EPS);
        TEST_MESSAGE(msg);
    }
}

static void test_implicit_step_absorbs_a_small_error_with_the_set_valued_sign(void)
{
    /* given: an implicit differentiator in motion near 0 (so that rounding is
     * far below h^3 g0 = 1.1e-9), and a sample 0.3 h^3 g0 below its prediction */
    const double h = DT_S;
    const double v1 = 1e-3;
    double k[4];
    ladrc_levant_t lev;
    ladrc_ref_t out;
    lipschitz_gains(1000.0, k);
    start_moving(&lev, LADRC_LEVANT_IMPLICIT, 0.0, v1, 0.0, 0.0);
    {
        const double g0 = h * k[0];
        const double a0 = h * h * h * g0;
        const ladrc_real_t rk = (ladrc_real_t)(h * v1 - 0.3 * a0);
        const double s = (h * v1 - (double)rk) / a0;
        const double tol = SET_VALUED_REL_TOL * g0 * s;
        /* when */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, rk, &out));
        /* then: the error is zero, r is the sample itself */
        TEST_ASSERT_EQUAL_MEMORY(&rk, &out.r, sizeof rk);
        /* and the sign term s = q / (h^3 g0), inside [-1, 1], moves the rest */
        TEST_ASSERT_FLOAT_WITHIN(tol, -g0 * s, ladrc_levant_get_dddr(&lev));
        TEST_ASSERT_FLOAT_WITHIN(2.0 * h * tol, -2.0 * h * g0 * s, out.ddr);
        TEST_ASSERT_FLOAT_WITHIN(11.0 / 6.0 * h * h * tol + 2.0 * LADRC_REAL_EPS * v1, v1 - 11.0 / 6.0 * h * h * g0 * s,
                                 out.dr);
    }
}

static void test_explicit_steps_follow_the_hd_and_euler_equations(void)
{
    const double lip = 1000.0;
    const double h = DT_S;
    const double r0 = 0.2, v1 = 0.5, v2 = -3.0, v3 = 40.0, rk = 0.21;
    const ladrc_levant_method_t methods[] = {LADRC_LEVANT_HD, LADRC_LEVANT_EULER};
    double k[4];
    size_t i;
    lipschitz_gains(lip, k);

    for (i = 0; i < 2; ++i) {
        /* given: the same state in motion */
        ladrc_levant_t lev;
        ladrc_ref_t out;
        const int hd = (methods[i] == LADRC_LEVANT_HD);
        start_moving(&lev, methods[i], r0, v1, v2, v3);
        /* when */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, (ladrc_real_t)rk, &out));
        /* then: corrections from the prediction error e = z0 - r_k */
        {
            const double e = r0 - (double)(ladrc_real_t)rk;
            const double p0 = r0 + h * v1 + (hd ? h * h / 2.0 * v2 + h * h * h / 6.0 * v3 : 0.0);
            const double p1 = v1 + h * v2 + (hd ? h * h / 2.0 * v3 : 0.0);
            const double p2 = v2 + h * v3;
            const double z0 = p0 - h * k[3] * spow(e, 0.75);
            const double z1 = p1 - h * k[2] * spow(e, 0.5);
            const double z2 = p2 - h * k[1] * spow(e, 0.25);
            const double z3 = v3 - h * k[0] * (e > 0 ? 1 : -1);
            TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * fabs(z0), z0, out.r);
            TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(p1) + fabs(z1)), z1, out.dr);
            TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(p2) + fabs(z2)), z2, out.ddr);
            TEST_ASSERT_FLOAT_WITHIN(HAND_REL_TOL * (fabs(v3) + fabs(z3)), z3, ladrc_levant_get_dddr(&lev));
        }
    }
}

static void test_recursive_gains_convert_to_the_published_non_recursive_ones(void)
{
    /* given: the recursive gains of Levant's coefficients 1.1, 1.5, 2, 3 for L = 50 */
    const double lip = 50.0;
    const ladrc_levant_config_t by_bound = lipschitz_config(LADRC_LEVANT_IMPLICIT, lip);
    const ladrc_levant_config_t by_gains = explicit_config(LADRC_LEVANT_IMPLICIT, 3.0 * pow(lip, 0.25),
                                                           2.0 * pow(lip, 1.0 / 3.0), 1.5 * pow(lip, 0.5), 1.1 * lip);
    ladrc_levant_t a;
    ladrc_levant_t b;
    /* when */
    init_ok(&a, &by_bound);
    init_ok(&b, &by_gains);
    /* then: the same per-sample gains up to the rounding of the published table */
    TEST_ASSERT_FLOAT_WITHIN(COEFF_ROUNDING_REL * a.g3, a.g3, b.g3);
    TEST_ASSERT_FLOAT_WITHIN(COEFF_ROUNDING_REL * a.g2, a.g2, b.g2);
    TEST_ASSERT_FLOAT_WITHIN(COEFF_ROUNDING_REL * a.g1, a.g1, b.g1);
    TEST_ASSERT_FLOAT_WITHIN(COEFF_ROUNDING_REL * a.g0, a.g0, b.g0);
}

/* ---------------------------------------------------------- accuracy */

/* Tolerance on the i-th derivative of the cubic (see the CUBIC_ constants). */
static double cubic_tol(ladrc_levant_method_t method, int i)
{
    /* Largest |r^(i+1)| on [0, 5] s where Euler's chain lags: r' by half a
     * step (h/2 |r''|), r'' by one (h |r'''|); r and r''' show no lag. */
    const double lagging_rate[4] = {0.0, 0.3, 0.12, 0.0};
    const double eps = LADRC_REAL_EPS * CUBIC_R_MAX;
    double tol = CUBIC_NOISE_FACTOR * pow(CUBIC_LIPSCHITZ, i / 4.0) * pow(eps, (4.0 - i) / 4.0);
    if (method != LADRC_LEVANT_IMPLICIT) {
        tol += CUBIC_STEP_FACTOR * CUBIC_LIPSCHITZ * pow(DT_S, 4.0 - i);
    }
    if (method == LADRC_LEVANT_EULER) {
        tol += CUBIC_EULER_LAG_STEPS * DT_S * lagging_rate[i];
    }
    return tol;
}

/* Follows the cubic from rest on r(0) for CUBIC_END_S; returns the last
 * instant at which an estimate was off by more than its tolerance, and the
 * largest errors from CUBIC_SETTLED_S on. */
static double run_cubic(ladrc_levant_method_t method, double worst[4])
{
    const ladrc_levant_config_t cfg = lipschitz_config(method, CUBIC_LIPSCHITZ);
    double tol[4];
    double last_out_s = 0.0;
    ladrc_levant_t lev;
    int i;
    int k;
    for (i = 0; i < 4; ++i) {
        tol[i] = cubic_tol(method, i);
        worst[i] = 0.0;
    }
    init_ok(&lev, &cfg);
    ladrc_levant_reset(&lev, (ladrc_real_t)cubic(0.0, 0));
    for (k = 1; k <= (int)(CUBIC_END_S / DT_S + 0.5); ++k) {
        const double t = k * DT_S;
        const double te = estimate_time_s(method, t);
        ladrc_ref_t out;
        double est[4];
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, (ladrc_real_t)cubic(t, 0), &out));
        est[0] = out.r;
        est[1] = out.dr;
        est[2] = out.ddr;
        est[3] = ladrc_levant_get_dddr(&lev);
        for (i = 0; i < 4; ++i) {
            const double err = fabs(est[i] - cubic(te, i));
            if (err > tol[i]) {
                last_out_s = t;
            }
            if (t >= CUBIC_SETTLED_S && err > worst[i]) {
                worst[i] = err;
            }
        }
    }
    return last_out_s;
}

static void test_implicit_estimates_a_cubic_exactly_after_a_finite_transient(void)
{
    /* given: the default differentiator at rest on r(0) of a cubic (r'''' = 0) */
    double worst[4];
    char msg[160];
    /* when: sampled at 1 kHz for 5 s */
    const double last_out_s = run_cubic(LADRC_LEVANT_IMPLICIT, worst);
    /* then: every estimate stays within its rounding tolerance after a finite transient */
    snprintf(msg, sizeof msg,
             "implicit cubic: within tolerance from %.3f s; max errors r %.2e r' %.2e r'' %.2e r''' %.2e", last_out_s,
             worst[0], worst[1], worst[2], worst[3]);
    TEST_MESSAGE(msg);
    TEST_ASSERT_LESS_THAN_FLOAT(CUBIC_SETTLED_S, last_out_s);
}

static void test_explicit_forms_track_a_cubic_within_their_discretisation_error(void)
{
    const ladrc_levant_method_t methods[] = {LADRC_LEVANT_HD, LADRC_LEVANT_EULER};
    size_t m;
    for (m = 0; m < 2; ++m) {
        /* given / when: the same cubic */
        double worst[4];
        char msg[160];
        const double last_out_s = run_cubic(methods[m], worst);
        /* then */
        snprintf(msg, sizeof msg,
                 "%s cubic: within tolerance from %.3f s; max errors r %.2e r' %.2e r'' %.2e r''' %.2e",
                 (methods[m] == LADRC_LEVANT_HD) ? "HD" : "Euler", last_out_s, worst[0], worst[1], worst[2], worst[3]);
        TEST_MESSAGE(msg);
        TEST_ASSERT_LESS_THAN_FLOAT(CUBIC_SETTLED_S, last_out_s);
    }
}

/* RMS of the r' error of the best TD of a small grid, on the noisy sine. */
static double best_td_rms(double *best_accel, double *best_h0)
{
    /* The best of this grid, R = 10 rad/s^2 and h0 = 10 dt (measured), lies
     * inside it; its neighbours are 0.1 to 22 % worse, the corners up to 3.4
     * times, so a finer grid would gain little. */
    const double accels[] = {2.0, 5.0, 10.0, 20.0, 50.0};
    const double h0_steps[] = {5.0, 10.0, 20.0, 40.0, 80.0};
    double best = HUGE_VAL;
    size_t ia, ih;
    for (ia = 0; ia < 5; ++ia) {
        for (ih = 0; ih < 5; ++ih) {
            ladrc_td_t td;
            ladrc_td_config_t cfg;
            gauss_rng_t rng = {.s = 0x9E3779B97F4A7C15ull};
            double sum = 0.0;
            int n = 0;
            int k;
            cfg.dt_s = (ladrc_real_t)DT_S;
            cfg.accel_rad_s2 = (ladrc_real_t)accels[ia];
            cfg.h0_s = (ladrc_real_t)(h0_steps[ih] * DT_S);
            TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_td_init(&td, &cfg));
            for (k = 0; k < (int)(NOISE_END_S / DT_S); ++k) {
                const double t = k * DT_S;
                const double r = sin(t) + sqrt(NOISE_VARIANCE) * rng_gauss(&rng);
                ladrc_ref_t out;
                (void)ladrc_td_step(&td, (ladrc_real_t)r, &out);
                if (t >= NOISE_JUDGE_FROM_S) {
                    const double e = (double)out.dr - cos(t + DT_S); /* TD output: t + dt */
                    sum += e * e;
                    ++n;
                }
            }
            if (sqrt(sum / n) < best) {
                best = sqrt(sum / n);
                *best_accel = accels[ia];
                *best_h0 = h0_steps[ih] * DT_S;
            }
        }
    }
    return best;
}

static void test_derivative_of_a_noisy_sine_has_a_lower_rms_error_than_the_best_td(void)
{
    /* given: the default differentiator with L from the sine's 4th-derivative
     * bound, and the same noisy samples for both shapers */
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, NOISE_LIPSCHITZ);
    gauss_rng_t rng = {.s = 0x9E3779B97F4A7C15ull};
    ladrc_levant_t lev;
    double sum = 0.0;
    double td_accel = 0.0;
    double td_h0 = 0.0;
    double levant_rms;
    double td_rms;
    char msg[200];
    int n = 0;
    int k;
    init_ok(&lev, &cfg);

    /* when */
    for (k = 0; k < (int)(NOISE_END_S / DT_S); ++k) {
        const double t = k * DT_S;
        const double r = sin(t) + sqrt(NOISE_VARIANCE) * rng_gauss(&rng);
        ladrc_ref_t out;
        (void)ladrc_levant_step(&lev, (ladrc_real_t)r, &out);
        if (t >= NOISE_JUDGE_FROM_S) {
            const double e = (double)out.dr - cos(t);
            sum += e * e;
            ++n;
        }
    }
    levant_rms = sqrt(sum / n);
    td_rms = best_td_rms(&td_accel, &td_h0);

    /* then */
    snprintf(msg, sizeof msg,
             "noisy sine, r' error RMS: Levant (implicit, L = %.0f) %.4f, best TD (R = %.0f, h0 = %.3f s) %.4f"
             " (paper: TD 2.767, Levant 0.695)",
             NOISE_LIPSCHITZ, levant_rms, td_accel, td_h0, td_rms);
    TEST_MESSAGE(msg);
    TEST_ASSERT_LESS_THAN_FLOAT(td_rms, levant_rms);
}

/* RMS of the steps of r'' on the paper's roll reference with the paper's gains. */
static double r2_step_rms(ladrc_levant_method_t method, double *err_rms)
{
    const ladrc_levant_config_t cfg = explicit_config(method, CHATTER_L123, CHATTER_L123, CHATTER_L123, CHATTER_L4);
    ladrc_levant_t lev;
    double prev = 0.0;
    double sum = 0.0;
    double sum_err = 0.0;
    int n = 0;
    int k;
    init_ok(&lev, &cfg);
    ladrc_levant_reset(&lev, (ladrc_real_t)roll_ref(0.0, 0));
    for (k = 1; k <= (int)(CHATTER_END_S / DT_S + 0.5); ++k) {
        const double t = k * DT_S;
        ladrc_ref_t out;
        (void)ladrc_levant_step(&lev, (ladrc_real_t)roll_ref(t, 0), &out);
        if (t >= CHATTER_JUDGE_FROM_S) {
            const double d = (double)out.ddr - prev;
            const double e = (double)out.ddr - roll_ref(estimate_time_s(method, t), 2);
            sum += d * d;
            sum_err += e * e;
            ++n;
        }
        prev = out.ddr;
    }
    *err_rms = sqrt(sum_err / n);
    return sqrt(sum / n);
}

static void test_implicit_does_not_chatter_with_the_paper_gains_where_euler_does(void)
{
    double implicit_err;
    double euler_err;
    double hd_err;
    char msg[240];
    /* given / when: the paper's gains on the paper's smooth roll reference at 1 kHz */
    const double implicit_steps = r2_step_rms(LADRC_LEVANT_IMPLICIT, &implicit_err);
    const double euler_steps = r2_step_rms(LADRC_LEVANT_EULER, &euler_err);
    const double hd_steps = r2_step_rms(LADRC_LEVANT_HD, &hd_err);
    /* then */
    snprintf(msg, sizeof msg,
             "paper gains, RMS r'' step (error): implicit %.2e (%.2e), Euler %.2e (%.2e), HD %.2e (%.2e);"
             " smooth signal 7.2e-04",
             implicit_steps, implicit_err, euler_steps, euler_err, hd_steps, hd_err);
    TEST_MESSAGE(msg);
    TEST_ASSERT_LESS_THAN_FLOAT(CHATTER_STEP_RMS_TOL, implicit_steps);
    TEST_ASSERT_GREATER_THAN_FLOAT(CHATTER_STEP_RMS_TOL, euler_steps);
}

/* -------------------------------------------------------- validation */

typedef struct {
    ladrc_levant_config_t cfg;
    ladrc_status_t expected;
} config_case_t;

/* Every field of a rejected instance is zero (field by field: the padding
 * bytes of "*lev = zero" are not defined, and optimised builds leave them). */
static void assert_levant_zeroed(const ladrc_levant_t *lev, const char *msg)
{
    const ladrc_real_t fields[] = {lev->w,   lev->r_last, lev->z1, lev->z2, lev->z3,
                                   lev->h_s, lev->g3,     lev->g2, lev->g1, lev->g0};
    const ladrc_real_t zeros[sizeof fields / sizeof fields[0]] = {0};
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(zeros, fields, sizeof fields, msg);
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, lev->method, msg);
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(0u, lev->faults, msg);
}

static void test_init_rejects_each_invalid_field_with_its_own_status(void)
{
    const double bad[] = {0.0, -1.0, (double)NAN, (double)INFINITY, (double)-INFINITY};
    const ladrc_levant_config_t lip_ok = lipschitz_config(LADRC_LEVANT_IMPLICIT, 10.0);
    const ladrc_levant_config_t exp_ok = explicit_config(LADRC_LEVANT_HD, 20.0, 20.0, 20.0, 100.0);
    config_case_t cases[64];
    size_t n = 0;
    size_t i;
    size_t b;

    for (b = 0; b < 5; ++b) {
        const ladrc_real_t v = (ladrc_real_t)bad[b];
        cases[n].cfg = lip_ok;
        cases[n].cfg.dt_s = v;
        cases[n++].expected = LADRC_ERR_DT_S;
        cases[n].cfg = lip_ok;
        cases[n].cfg.lipschitz_rad_s4 = v;
        cases[n++].expected = LADRC_ERR_LEVANT_LIPSCHITZ;
        cases[n].cfg = exp_ok;
        cases[n].cfg.l1 = v;
        cases[n++].expected = LADRC_ERR_LEVANT_L1;
        cases[n].cfg = exp_ok;
        cases[n].cfg.l2 = v;
        cases[n++].expected = LADRC_ERR_LEVANT_L2;
        cases[n].cfg = exp_ok;
        cases[n].cfg.l3 = v;
        cases[n++].expected = LADRC_ERR_LEVANT_L3;
        cases[n].cfg = exp_ok;
        cases[n].cfg.l4 = v;
        cases[n++].expected = LADRC_ERR_LEVANT_L4;
    }
    cases[n].cfg = lip_ok;
    cases[n].cfg.method = (ladrc_levant_method_t)3;
    cases[n++].expected = LADRC_ERR_LEVANT_METHOD;
    cases[n].cfg = lip_ok;
    cases[n].cfg.method = (ladrc_levant_method_t)-1;
    cases[n++].expected = LADRC_ERR_LEVANT_METHOD;
    cases[n].cfg = lip_ok;
    cases[n].cfg.gains = (ladrc_levant_gains_t)2;
    cases[n++].expected = LADRC_ERR_LEVANT_GAINS;
    cases[n].cfg = lip_ok;
    cases[n].cfg.gains = (ladrc_levant_gains_t)-1;
    cases[n++].expected = LADRC_ERR_LEVANT_GAINS;
    /* steps no module discretises (types.h) */
    cases[n].cfg = lip_ok;
    cases[n].cfg.dt_s = (ladrc_real_t)sqrt((double)LADRC_REAL_MAX);
    cases[n++].expected = LADRC_ERR_DT_S;
    cases[n].cfg = lip_ok;
    cases[n].cfg.dt_s = (ladrc_real_t)cbrt((double)LADRC_REAL_MIN);
    cases[n++].expected = LADRC_ERR_DT_S;
    /* 1.1 L overflows */
    cases[n].cfg = lip_ok;
    cases[n].cfg.lipschitz_rad_s4 = LADRC_REAL_MAX;
    cases[n++].expected = LADRC_ERR_LEVANT_RANGE;
    /* h^3 g0 = 1.1 h^4 L underflows to 0 */
    cases[n].cfg = lip_ok;
    cases[n].cfg.dt_s = LADRC_DT_MIN_S;
    cases[n].cfg.lipschitz_rad_s4 = LADRC_REAL_MIN;
    cases[n++].expected = LADRC_ERR_LEVANT_RANGE;
    /* (g3 = h L1 cannot overflow: h <= LADRC_DT_MAX_S = 1 s) */
    /* k1 = L3 L2^(1/2) L1^(1/3) overflows */
    cases[n].cfg = exp_ok;
    cases[n].cfg.l3 = LADRC_REAL_MAX;
    cases[n++].expected = LADRC_ERR_LEVANT_RANGE;
    /* L2 L1^(2/3) overflows */
    cases[n].cfg = exp_ok;
    cases[n].cfg.l1 = LADRC_REAL_MAX;
    cases[n].cfg.l2 = LADRC_REAL_MAX;
    cases[n++].expected = LADRC_ERR_LEVANT_RANGE;
    /* the fields of the unused gain mode are not read */
    cases[n].cfg = lip_ok;
    cases[n].cfg.l1 = (ladrc_real_t)NAN;
    cases[n++].expected = LADRC_OK;
    cases[n].cfg = exp_ok;
    cases[n].cfg.lipschitz_rad_s4 = (ladrc_real_t)NAN;
    cases[n++].expected = LADRC_OK;

    for (i = 0; i < n; ++i) {
        /* given: an instance holding garbage */
        ladrc_levant_t lev;
        char msg[48];
        memset(&lev, 0x5a, sizeof lev);
        snprintf(msg, sizeof msg, "case %u", (unsigned)i);
        /* when / then */
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].expected, ladrc_levant_init(&lev, &cases[i].cfg), msg);
        if (cases[i].expected != LADRC_OK) {
            assert_levant_zeroed(&lev, msg);
        }
    }
}

static void test_init_rejects_null_pointers(void)
{
    ladrc_levant_t lev;
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 10.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_levant_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_levant_init(&lev, NULL));
}

static void test_rejected_instance_refuses_every_step_and_outputs_zero(void)
{
    /* given: an instance whose init failed */
    ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 10.0);
    ladrc_levant_t lev;
    ladrc_ref_t out;
    cfg.dt_s = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_levant_init(&lev, &cfg));
    /* when / then */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(&lev, LADRC_R(1.0), &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(&lev, LADRC_R(0.0), &out));
    /* and a non-finite sample is named as the cause */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_levant_step(&lev, (ladrc_real_t)NAN, &out));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.r);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.dr);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.ddr);
}

/* --------------------------------------------------------------- reset */

static void test_reset_starts_at_rest_on_the_given_reference_and_stays_there(void)
{
    const ladrc_levant_method_t methods[] = {LADRC_LEVANT_IMPLICIT, LADRC_LEVANT_HD, LADRC_LEVANT_EULER};
    const ladrc_real_t r0 = LADRC_R(0.37);
    size_t m;
    for (m = 0; m < 3; ++m) {
        /* given: an instance that has been moving */
        const ladrc_levant_config_t cfg = lipschitz_config(methods[m], 100.0);
        ladrc_levant_t lev;
        ladrc_ref_t out;
        int k;
        init_ok(&lev, &cfg);
        for (k = 0; k < 50; ++k) {
            (void)ladrc_levant_step(&lev, (ladrc_real_t)sin(0.1 * k), NULL);
        }
        (void)ladrc_levant_step(&lev, (ladrc_real_t)NAN, NULL);
        /* when */
        ladrc_levant_reset(&lev, r0);
        /* then: at rest on r0, faults cleared */
        ladrc_levant_get_ref(&lev, &out);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, lev.faults);
        TEST_ASSERT_EQUAL_MEMORY(&r0, &out.r, sizeof r0);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.dr);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.ddr);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_levant_get_dddr(&lev));
        /* and a constant reference r0 leaves it exactly there */
        for (k = 0; k < 100; ++k) {
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, r0, &out));
        }
        TEST_ASSERT_EQUAL_MEMORY(&r0, &out.r, sizeof r0);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.dr);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.ddr);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_levant_get_dddr(&lev));
    }
}

static void test_reset_on_a_non_finite_reference_stops_where_it_is_and_raises_input_fault(void)
{
    /* given: an instance moving on a ramp */
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 100.0);
    ladrc_levant_t lev;
    ladrc_ref_t before;
    ladrc_ref_t after;
    int k;
    init_ok(&lev, &cfg);
    for (k = 0; k < 300; ++k) {
        (void)ladrc_levant_step(&lev, (ladrc_real_t)(0.5 * k * DT_S), NULL);
    }
    ladrc_levant_get_ref(&lev, &before);
    /* when */
    ladrc_levant_reset(&lev, (ladrc_real_t)INFINITY);
    /* then: at rest on the current estimate of r */
    ladrc_levant_get_ref(&lev, &after);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, lev.faults);
    TEST_ASSERT_EQUAL_MEMORY(&before.r, &after.r, sizeof after.r);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, after.dr);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, after.ddr);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_levant_get_dddr(&lev));
}

/* -------------------------------------------------------------- faults */

static void test_non_finite_input_holds_the_state_and_recovers_as_if_skipped(void)
{
    const ladrc_levant_method_t methods[] = {LADRC_LEVANT_IMPLICIT, LADRC_LEVANT_HD, LADRC_LEVANT_EULER};
    const double bad[] = {(double)NAN, (double)INFINITY, (double)-INFINITY};
    size_t m;
    for (m = 0; m < 3; ++m) {
        /* given: two identical instances on the same signal */
        const ladrc_levant_config_t cfg = lipschitz_config(methods[m], 50.0);
        ladrc_levant_t lev;
        ladrc_levant_t skip;
        int k;
        init_ok(&lev, &cfg);
        init_ok(&skip, &cfg);
        for (k = 0; k < 400; ++k) {
            const ladrc_real_t r = (ladrc_real_t)(0.3 * sin(2.0 * k * DT_S));
            (void)ladrc_levant_step(&lev, r, NULL);
            (void)ladrc_levant_step(&skip, r, NULL);
        }
        /* when: one of them receives three bad samples */
        {
            size_t b;
            for (b = 0; b < 3; ++b) {
                ladrc_levant_t held;
                ladrc_ref_t out;
                ladrc_ref_t expected;
                memcpy(&held, &lev, sizeof held);
                ladrc_levant_get_ref(&lev, &expected);
                /* then: state unchanged, input fault, held estimate written */
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_levant_step(&lev, (ladrc_real_t)bad[b], &out));
                TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, lev.faults);
                held.faults = LADRC_FAULT_INPUT;
                TEST_ASSERT_EQUAL_MEMORY(&held, &lev, sizeof lev);
                TEST_ASSERT_EQUAL_MEMORY(&expected, &out, sizeof out);
            }
        }
        /* then: with finite samples again it goes on exactly as the one that skipped them */
        for (k = 400; k < 600; ++k) {
            const ladrc_real_t r = (ladrc_real_t)(0.3 * sin(2.0 * k * DT_S));
            ladrc_ref_t a;
            ladrc_ref_t b;
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, r, &a));
            (void)ladrc_levant_step(&skip, r, &b);
            TEST_ASSERT_EQUAL_MEMORY(&b, &a, sizeof a);
        }
    }
}

static void test_an_update_that_would_overflow_is_refused_with_a_state_fault(void)
{
    const ladrc_levant_method_t methods[] = {LADRC_LEVANT_IMPLICIT, LADRC_LEVANT_HD, LADRC_LEVANT_EULER};
    size_t m;
    for (m = 0; m < 3; ++m) {
        /* given: an instance at rest near the bottom of the range */
        const ladrc_levant_config_t cfg = lipschitz_config(methods[m], 10.0);
        ladrc_levant_t lev;
        ladrc_levant_t held;
        ladrc_ref_t out;
        init_ok(&lev, &cfg);
        ladrc_levant_reset(&lev, -LADRC_REAL_MAX * LADRC_R(0.75));
        memcpy(&held, &lev, sizeof held);
        /* when: the reference jumps to the top, so the error overflows */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(&lev, LADRC_REAL_MAX * LADRC_R(0.75), &out));
        /* then: nothing moved, the held estimate is written */
        held.faults = LADRC_FAULT_STATE;
        TEST_ASSERT_EQUAL_MEMORY(&held, &lev, sizeof lev);
        TEST_ASSERT_EQUAL_MEMORY(&held.r_last, &out.r, sizeof out.r);
        /* and a reachable reference is followed again */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, -LADRC_REAL_MAX * LADRC_R(0.5), &out));
        TEST_ASSERT_TRUE(isfinite((double)out.r) && isfinite((double)out.dr) && isfinite((double)out.ddr));
    }
}

static void test_an_update_that_would_overflow_any_derivative_is_refused(void)
{
    /* Three white-box states, each pushing one derivative past the range in
     * one Euler step of h = 1 s while the estimate of r stays finite. */
    const ladrc_real_t big = LADRC_REAL_MAX * LADRC_R(0.9);
    const ladrc_real_t state[3][3] = {{big, big, LADRC_R(0.0)},            /* z1 + h z2 */
                                      {LADRC_R(0.0), big, big},            /* z2 + h z3 */
                                      {LADRC_R(0.0), LADRC_R(0.0), -big}}; /* z3 - g0 */
    size_t c;
    for (c = 0; c < 3; ++c) {
        /* given: L = LADRC_REAL_MAX / 2, so that g0 = 1.1 h L is a large push */
        ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_EULER, (double)LADRC_REAL_MAX / 2.0);
        ladrc_levant_t lev;
        ladrc_levant_t held;
        ladrc_ref_t out;
        cfg.dt_s = LADRC_R(1.0);
        init_ok(&lev, &cfg);
        lev.z1 = state[c][0];
        lev.z2 = state[c][1];
        lev.z3 = state[c][2];
        memcpy(&held, &lev, sizeof held);
        /* when: a sample just below the estimate (e > 0 pushes z3 down) */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(&lev, LADRC_R(-1.0), &out));
        /* then */
        held.faults = LADRC_FAULT_STATE;
        TEST_ASSERT_EQUAL_MEMORY(&held, &lev, sizeof lev);
        TEST_ASSERT_EQUAL_MEMORY(&held.z1, &out.dr, sizeof out.dr);
        TEST_ASSERT_EQUAL_MEMORY(&held.z2, &out.ddr, sizeof out.ddr);
    }
}

static void test_implicit_step_with_extremely_skewed_gains_stays_finite_near_its_solution(void)
{
    /* given: L1 = 1e8 against L2 = L3 = L4 = 1e-6, where the cubic term of
     * the error equation dominates and Newton's first bound is 400 times the
     * root: 20 iterations would be needed, the cap stops at 16 */
    const ladrc_levant_config_t cfg = explicit_config(LADRC_LEVANT_IMPLICIT, 1e8, 1e-6, 1e-6, 1e-6);
    const double h = DT_S;
    const ladrc_real_t rk = (ladrc_real_t)-5.36e-15;
    ladrc_levant_t lev;
    ladrc_ref_t out;
    init_ok(&lev, &cfg);
    /* when: one step from rest at 0 */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, rk, &out));
    /* then: a finite step whose error equation holds to NEWTON_CAP_REL_TOL */
    {
        const double q = -(double)rk;
        const double e = (double)lev.w; /* white-box: out.r = r_k + e rounds e away */
        const double g3 = (double)lev.g3, g2 = (double)lev.g2, g1 = (double)lev.g1, g0 = (double)lev.g0;
        const double lhs = e + g3 * spow(e, 0.75) + h * g2 * spow(e, 0.5) + h * h * g1 * spow(e, 0.25) +
                           h * h * h * g0 * ((e > 0.0) ? 1.0 : -1.0);
        TEST_ASSERT_TRUE(isfinite((double)out.dr) && isfinite((double)out.ddr));
        TEST_ASSERT_FLOAT_WITHIN(NEWTON_CAP_REL_TOL * q, q, lhs);
    }
}

static void test_step_reset_and_getters_tolerate_null_pointers(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL instances: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    /* given */
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 10.0);
    ladrc_levant_t lev;
    ladrc_ref_t out = {.r = LADRC_R(7.0), .dr = LADRC_R(7.0), .ddr = LADRC_R(7.0)};
    init_ok(&lev, &cfg);
    /* when / then: no crash; a NULL instance reports a state fault, a NULL output is allowed */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_levant_step(NULL, LADRC_R(1.0), &out));
    ladrc_levant_reset(NULL, LADRC_R(1.0));
    ladrc_levant_get_ref(NULL, &out);
    ladrc_levant_get_ref(&lev, NULL);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 7.0, out.r);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_levant_get_dddr(NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_levant_step(&lev, LADRC_R(1.0), NULL));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_levant_step(&lev, (ladrc_real_t)NAN, NULL));
    TEST_ASSERT_GREATER_THAN_FLOAT(0.0, lev.z1);
}

/* --------------------------------------------------------- determinism */

static void run_square_wave(ladrc_levant_t *lev, ladrc_ref_t *out, int from, int to)
{
    int k;
    for (k = from; k < to; ++k) {
        (void)ladrc_levant_step(lev, ((k / 100) % 2 != 0) ? LADRC_R(0.3) : LADRC_R(-0.2), &out[k]);
    }
}

static void test_repeats_bitwise_after_reset(void)
{
    /* given: one run from init */
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 500.0);
    static ladrc_ref_t first[600];
    static ladrc_ref_t second[600];
    ladrc_levant_t lev;
    init_ok(&lev, &cfg);
    run_square_wave(&lev, first, 0, 600);
    /* when: reset to the initial state and run again */
    ladrc_levant_reset(&lev, LADRC_R(0.0));
    run_square_wave(&lev, second, 0, 600);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(first, second, sizeof first);
}

static void test_a_run_split_across_a_copied_state_matches_one_run_bitwise(void)
{
    /* given: one uninterrupted run */
    const ladrc_levant_config_t cfg = lipschitz_config(LADRC_LEVANT_IMPLICIT, 500.0);
    static ladrc_ref_t whole[600];
    static ladrc_ref_t split[600];
    ladrc_levant_t lev;
    ladrc_levant_t first_half;
    ladrc_levant_t second_half;
    init_ok(&lev, &cfg);
    run_square_wave(&lev, whole, 0, 600);
    /* when: the same input in two runs, the second on a copy of the state */
    init_ok(&first_half, &cfg);
    run_square_wave(&first_half, split, 0, 250);
    memcpy(&second_half, &first_half, sizeof second_half);
    run_square_wave(&second_half, split, 250, 600);
    /* then */
    TEST_ASSERT_EQUAL_MEMORY(whole, split, sizeof whole);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_implicit_step_solves_its_error_equation_and_updates_as_documented);
    RUN_TEST(test_implicit_root_agrees_with_the_earlier_solver_over_forty_decades_of_error);
    RUN_TEST(test_implicit_step_absorbs_a_small_error_with_the_set_valued_sign);
    RUN_TEST(test_explicit_steps_follow_the_hd_and_euler_equations);
    RUN_TEST(test_recursive_gains_convert_to_the_published_non_recursive_ones);
    RUN_TEST(test_implicit_estimates_a_cubic_exactly_after_a_finite_transient);
    RUN_TEST(test_explicit_forms_track_a_cubic_within_their_discretisation_error);
    RUN_TEST(test_derivative_of_a_noisy_sine_has_a_lower_rms_error_than_the_best_td);
    RUN_TEST(test_implicit_does_not_chatter_with_the_paper_gains_where_euler_does);
    RUN_TEST(test_init_rejects_each_invalid_field_with_its_own_status);
    RUN_TEST(test_init_rejects_null_pointers);
    RUN_TEST(test_rejected_instance_refuses_every_step_and_outputs_zero);
    RUN_TEST(test_reset_starts_at_rest_on_the_given_reference_and_stays_there);
    RUN_TEST(test_reset_on_a_non_finite_reference_stops_where_it_is_and_raises_input_fault);
    RUN_TEST(test_non_finite_input_holds_the_state_and_recovers_as_if_skipped);
    RUN_TEST(test_an_update_that_would_overflow_is_refused_with_a_state_fault);
    RUN_TEST(test_an_update_that_would_overflow_any_derivative_is_refused);
    RUN_TEST(test_implicit_step_with_extremely_skewed_gains_stays_finite_near_its_solution);
    RUN_TEST(test_step_reset_and_getters_tolerate_null_pointers);
    RUN_TEST(test_repeats_bitwise_after_reset);
    RUN_TEST(test_a_run_split_across_a_copied_state_matches_one_run_bitwise);
    return UNITY_END();
}
