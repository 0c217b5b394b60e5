/* SPDX-License-Identifier: BSD-3-Clause */
/* RLS: agreement with the textbook update, convergence, forgetting, the
 * covariance guards over long and hostile runs, validation and faults. */
#include "unity.h"
#include "ladrc/rls.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The paper's estimator settings (docs/method.md section 5) at 1 kHz, 3 parameters:
 * p_initial = k0 / 3, so P starts on the bound. */
#define DT_S 1e-3
#define LAMBDA0_PER_S 100.0
#define K0 300.0
#define P0 100.0
#define NP 3
#define MAXP LADRC_RLS_MAX_PARAMS

/* Factored float update against the plain update in double, 300 random
 * samples for each n: float rounding (6e-8 per operation) accumulated over
 * the forgetting window of about 20 samples; measured 2.1e-7 (theta, over
 * its size 3) and 4.4e-7 (P, over tr P) in float, 1.3e-15 in double.
 * 5e-6 leaves a 10x margin; an error in the factor update shows at 1e-2. */
#define REFERENCE_REL_TOL 5e-6
/* Noise-free fit: the error left is float rounding of y and phi^T theta
 * (values near 5, ulp 5e-7) spread by the gain; measured 2.4e-7 in float,
 * 4e-16 in double. 3e-6 leaves a 12x margin. */
#define NOISE_FREE_TOL 3e-6
/* 100 scalar updates against their closed form: one or two roundings per
 * step, measured 1.9e-7 relative (P) and 9e-8 (theta, of size 0.4) in
 * float. 2e-6 leaves a 10x margin. */
#define CLOSED_FORM_REL_TOL 2e-6
/* Noisy fit: the estimate's error decorrelates within about 20 samples
 * (1 / (lambda h)), so the RMS over 8000 samples averages some 400
 * independent stretches and scatters by about 4% around the prediction
 * sigma sqrt(lambda h / 2); measured ratios 0.986, 1.027, 1.005.
 * [0.7, 1.3] keeps over 5 sigma each way; a window off by a factor of 2
 * moves the ratio by 1.41 or 0.71. */
#define NOISE_RATIO_MIN 0.7
#define NOISE_RATIO_MAX 1.3
/* Forgetting-rate readings: lambda = lambda0 (1 - tr/k0) with tr/k0 exact
 * in these cases up to one rounding (6e-8): 1e-4 of lambda0 is loose. */
#define LAMBDA_TOL_PER_S 1e-2
/* The clamp scales every D by one factor: their ratio keeps to two
 * roundings (1.2e-7); 1e-6 is 8x that. */
#define RATIO_REL_TOL 1e-6

#ifdef __arm__
/* Under QEMU the 4x4 update costs about 10 us: 10^5 steps is 1 s. The host
 * runs the full 10^7, and the fixed-point test proves the rest. */
#define LONG_RUN_STEPS 100000L
#else
#define LONG_RUN_STEPS 10000000L
#endif

void setUp(void)
{
}
void tearDown(void)
{
}

/* ------------------------------------------------------------ helpers */

static ladrc_rls_config_t config(unsigned n, double lambda0, double p0)
{
    ladrc_rls_config_t cfg;
    cfg.n_params = (uint8_t)n;
    cfg.dt_s = (ladrc_real_t)DT_S;
    cfg.lambda0_per_s = (ladrc_real_t)lambda0;
    cfg.p_bound = (ladrc_real_t)K0;
    cfg.p_initial = (ladrc_real_t)p0;
    return cfg;
}

static void init_rls(ladrc_rls_t *rls, unsigned n, double lambda0, double p0)
{
    const ladrc_rls_config_t cfg = config(n, lambda0, p0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_rls_init(rls, &cfg));
}

/* A seeded generator (64-bit LCG): uniform in [0, 1) and standard normal. */
typedef struct {
    unsigned long long s;
} rng_t;

static double rng_uniform(rng_t *r)
{
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(r->s >> 11) * (1.0 / 9007199254740992.0);
}

static double rng_normal(rng_t *r)
{
    const double u1 = 1.0 - rng_uniform(r); /* in (0, 1] */
    const double u2 = rng_uniform(r);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

/* The estimator's state, without padding, for bitwise comparisons. */
typedef struct {
    ladrc_real_t theta[MAXP];
    ladrc_real_t u[LADRC_RLS_U_SIZE];
    ladrc_real_t d[MAXP];
    ladrc_real_t lambda;
} snapshot_t;

static snapshot_t snapshot(const ladrc_rls_t *rls)
{
    snapshot_t s;
    memcpy(s.theta, rls->theta, sizeof s.theta);
    memcpy(s.u, rls->u, sizeof s.u);
    memcpy(s.d, rls->d, sizeof s.d);
    s.lambda = rls->lambda_per_s;
    return s;
}

static int same_state(const snapshot_t *a, const snapshot_t *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* P = U D U^T rebuilt in double from the stored factors, exactly as stored. */
static void p_from_factors(const ladrc_rls_t *rls, double p[MAXP][MAXP])
{
    const unsigned n = rls->n_params;
    double u[MAXP][MAXP] = {{0.0}};
    for (unsigned j = 0; j < n; ++j) {
        u[j][j] = 1.0;
        for (unsigned i = 0; i < j; ++i) {
            u[i][j] = rls->u[j * (j - 1) / 2 + i];
        }
    }
    for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = 0; j < n; ++j) {
            double s = 0.0;
            for (unsigned k = 0; k < n; ++k) {
                s += u[i][k] * (double)rls->d[k] * u[j][k];
            }
            p[i][j] = s;
        }
    }
}

/* 1 if the symmetric matrix is positive definite: every LDL^T pivot > 0. */
static int positive_definite(double p[MAXP][MAXP], unsigned n)
{
    double l[MAXP][MAXP] = {{0.0}};
    double dd[MAXP];
    for (unsigned j = 0; j < n; ++j) {
        double dj = p[j][j];
        for (unsigned k = 0; k < j; ++k) {
            dj -= l[j][k] * l[j][k] * dd[k];
        }
        if (!(dj > 0.0) || !isfinite(dj)) {
            return 0;
        }
        dd[j] = dj;
        for (unsigned i = j + 1; i < n; ++i) {
            double lij = p[i][j];
            for (unsigned k = 0; k < j; ++k) {
                lij -= l[i][k] * l[j][k] * dd[k];
            }
            l[i][j] = lij / dj;
        }
    }
    return 1;
}

/* The guards the estimator promises at every step: P read through get_p
 * symmetric bit for bit, the factors finite with D > 0, U D U^T positive
 * definite in double, tr P <= k0. Returns 0 and says why otherwise. */
static int covariance_is_sound(const ladrc_rls_t *rls, char *why, size_t why_size)
{
    const unsigned n = rls->n_params;
    for (unsigned i = 0; i < n; ++i) {
        for (unsigned j = 0; j < n; ++j) {
            const ladrc_real_t pij = ladrc_rls_get_p(rls, (uint8_t)i, (uint8_t)j);
            const ladrc_real_t pji = ladrc_rls_get_p(rls, (uint8_t)j, (uint8_t)i);
            if (memcmp(&pij, &pji, sizeof pij) != 0) {
                snprintf(why, why_size, "P(%u,%u) != P(%u,%u)", i, j, j, i);
                return 0;
            }
        }
        if (!(rls->d[i] > 0.0f) || !isfinite((double)rls->d[i])) {
            snprintf(why, why_size, "D(%u) = %g", i, (double)rls->d[i]);
            return 0;
        }
    }
    for (unsigned k = 0; k < n * (n - 1) / 2; ++k) {
        if (!isfinite((double)rls->u[k])) {
            snprintf(why, why_size, "U entry %u not finite", k);
            return 0;
        }
    }
    double p[MAXP][MAXP];
    p_from_factors(rls, p);
    if (!positive_definite(p, n)) {
        snprintf(why, why_size, "U D U^T not positive definite");
        return 0;
    }
    const double tr = (double)ladrc_rls_get_p_norm(rls);
    if (!(tr <= (double)rls->p_bound)) {
        snprintf(why, why_size, "trace %.9g above the bound %.9g", tr, (double)rls->p_bound);
        return 0;
    }
    return 1;
}

static void assert_sound(const ladrc_rls_t *rls, long step)
{
    char why[96];
    char msg[140];
    if (!covariance_is_sound(rls, why, sizeof why)) {
        snprintf(msg, sizeof msg, "step %ld: %s", step, why);
        TEST_FAIL_MESSAGE(msg);
    }
}

/* The plain (unfactored) update of rls.h in double, as the reference. */
typedef struct {
    unsigned n;
    double theta[MAXP];
    double p[MAXP][MAXP];
    double lambda;
} ref_rls_t;

static void ref_init(ref_rls_t *r, unsigned n, double p0)
{
    memset(r, 0, sizeof *r);
    r->n = n;
    for (unsigned i = 0; i < n; ++i) {
        r->p[i][i] = p0;
    }
}

static void ref_update(ref_rls_t *r, const double *phi, double y, double lambda0)
{
    const unsigned n = r->n;
    double tr = 0.0;
    for (unsigned i = 0; i < n; ++i) {
        tr += r->p[i][i];
    }
    const double room = 1.0 - tr / K0;
    r->lambda = room > 1e-4 ? lambda0 * room : 0.0;
    const double mu = exp(-r->lambda * DT_S);
    double v[MAXP];
    double s = 0.0;
    double e = y;
    for (unsigned i = 0; i < n; ++i) {
        v[i] = 0.0;
        for (unsigned j = 0; j < n; ++j) {
            v[i] += r->p[i][j] * phi[j];
        }
        s += phi[i] * v[i];
        e -= phi[i] * r->theta[i];
    }
    const double denom = mu + DT_S * s;
    for (unsigned i = 0; i < n; ++i) {
        r->theta[i] += DT_S * v[i] * e / denom;
        /* upper triangle, mirrored: any asymmetry would grow as 1/mu per step */
        for (unsigned j = i; j < n; ++j) {
            r->p[i][j] = (r->p[i][j] - DT_S * v[i] * v[j] / denom) / mu;
            r->p[j][i] = r->p[i][j];
        }
    }
}

/* --------------------------------------------------- the update itself */

static void test_init_starts_at_zero_with_p_initial_times_identity(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    for (uint8_t i = 0; i < NP; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_theta(&rls)[i]);
        for (uint8_t j = 0; j < NP; ++j) {
            TEST_ASSERT_FLOAT_WITHIN(0.0f, i == j ? (ladrc_real_t)P0 : 0.0f, ladrc_rls_get_p(&rls, i, j));
        }
    }
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)(NP * P0), ladrc_rls_get_p_norm(&rls));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)K0, ladrc_rls_get_p_bound(&rls));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_lambda(&rls));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_get_faults(&rls));
}

static void test_factored_update_matches_the_plain_update_computed_in_double(void)
{
    double worst_theta = 0.0;
    double worst_p = 0.0;
    for (unsigned n = 1; n <= MAXP; ++n) {
        /* given the estimator and the plain update of rls.h in double, with
         * P starting below the bound so that forgetting acts from the start */
        ladrc_rls_t rls;
        const double p0 = 20.0;
        init_rls(&rls, n, LAMBDA0_PER_S, p0);
        ref_rls_t ref;
        ref_init(&ref, n, p0);
        rng_t rng = {.s = 12345u + n};
        const double theta_true[MAXP] = {1.5, -2.0, 0.7};
        for (int k = 0; k < 300; ++k) {
            /* when both see the same noisy samples of a random regressor */
            double phi[MAXP];
            ladrc_real_t phi_r[MAXP];
            double y = 0.05 * rng_normal(&rng);
            for (unsigned i = 0; i < n; ++i) {
                phi_r[i] = (ladrc_real_t)(2.0 * rng_normal(&rng));
                phi[i] = (double)phi_r[i];
                y += phi[i] * theta_true[i];
            }
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, phi_r, (ladrc_real_t)y));
            ref_update(&ref, phi, (double)(ladrc_real_t)y, LAMBDA0_PER_S);
            /* then lambda, theta and P agree to rounding */
            TEST_ASSERT_FLOAT_WITHIN(REFERENCE_REL_TOL * LAMBDA0_PER_S, ref.lambda, ladrc_rls_get_lambda(&rls));
            double tr = 0.0;
            for (unsigned i = 0; i < n; ++i) {
                tr += ref.p[i][i];
            }
            for (unsigned i = 0; i < n; ++i) {
                const double dt = fabs(ref.theta[i] - (double)rls.theta[i]) / 3.0;
                worst_theta = fmax(worst_theta, dt);
                TEST_ASSERT_FLOAT_WITHIN(REFERENCE_REL_TOL, 0.0, dt);
                for (unsigned j = 0; j < n; ++j) {
                    const double dp = fabs(ref.p[i][j] - (double)ladrc_rls_get_p(&rls, (uint8_t)i, (uint8_t)j)) / tr;
                    worst_p = fmax(worst_p, dp);
                    TEST_ASSERT_FLOAT_WITHIN(REFERENCE_REL_TOL, 0.0, dp);
                }
            }
        }
    }
    char msg[120];
    snprintf(msg, sizeof msg, "vs double reference: theta %.2e (of 3), P %.2e (of tr P)", worst_theta, worst_p);
    TEST_MESSAGE(msg);
}

static void test_scalar_update_gives_the_closed_form_p(void)
{
    /* given one parameter and no forgetting: P_k^-1 = P_0^-1 + h sum phi^2 */
    ladrc_rls_t rls;
    init_rls(&rls, 1, 0.0, 50.0);
    const ladrc_real_t phi[1] = {2.0f};
    for (int k = 0; k < 100; ++k) {
        ladrc_rls_update(&rls, phi, 1.0f);
    }
    const double expected = 1.0 / (1.0 / 50.0 + DT_S * 100 * 4.0);
    TEST_ASSERT_FLOAT_WITHIN(CLOSED_FORM_REL_TOL * expected, expected, ladrc_rls_get_p(&rls, 0, 0));
    /* and theta is the least-squares fit pulled toward the prior 0 */
    const double theta = (DT_S * 100 * 2.0 * 1.0) * expected;
    TEST_ASSERT_FLOAT_WITHIN(CLOSED_FORM_REL_TOL * theta, theta, ladrc_rls_get_theta(&rls)[0]);
}

/* -------------------------------------------------------- convergence */

static void test_noise_free_regression_converges_to_the_true_parameters(void)
{
    /* given 3 parameters, a rich regressor (bias and two independent
     * Gaussian signals) and exact measurements */
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const double theta_true[NP] = {0.5, -2.0, 3.0};
    rng_t rng = {.s = 7u};
    /* when 1 s of samples has been seen */
    for (int k = 0; k < 1000; ++k) {
        const ladrc_real_t phi[NP] = {1.0f, (ladrc_real_t)rng_normal(&rng), (ladrc_real_t)rng_normal(&rng)};
        double y = 0.0;
        for (int i = 0; i < NP; ++i) {
            y += (double)phi[i] * theta_true[i];
        }
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, phi, (ladrc_real_t)y));
    }
    /* then theta equals the truth to float rounding */
    double worst = 0.0;
    for (int i = 0; i < NP; ++i) {
        worst = fmax(worst, fabs((double)ladrc_rls_get_theta(&rls)[i] - theta_true[i]));
    }
    char msg[80];
    snprintf(msg, sizeof msg, "noise-free error after 1 s: %.2e, lambda %.1f/s", worst,
             (double)ladrc_rls_get_lambda(&rls));
    TEST_MESSAGE(msg);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(NOISE_FREE_TOL, 0.0, worst, msg);
}

static void test_noisy_regression_error_matches_the_noise_and_the_forgetting_window(void)
{
    /* given unit-variance regressors and Gaussian measurement noise sigma */
    const double sigma = 0.2;
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const double theta_true[NP] = {0.5, -2.0, 3.0};
    rng_t rng = {.s = 2024u};
    double sum_sq[NP] = {0.0, 0.0, 0.0};
    double sum_lambda = 0.0;
    long count = 0;
    for (int k = 0; k < 10000; ++k) {
        const ladrc_real_t phi[NP] = {1.0f, (ladrc_real_t)rng_normal(&rng), (ladrc_real_t)rng_normal(&rng)};
        double y = sigma * rng_normal(&rng);
        for (int i = 0; i < NP; ++i) {
            y += (double)phi[i] * theta_true[i];
        }
        ladrc_rls_update(&rls, phi, (ladrc_real_t)y);
        if (k >= 2000) { /* after the start-up transient */
            for (int i = 0; i < NP; ++i) {
                const double err = (double)ladrc_rls_get_theta(&rls)[i] - theta_true[i];
                sum_sq[i] += err * err;
            }
            sum_lambda += (double)ladrc_rls_get_lambda(&rls);
            ++count;
        }
    }
    /* then each parameter's RMS error is sigma sqrt(lambda h / 2): the
     * noise averaged over the window 1/lambda, with R = E[phi phi^T] = I */
    const double lambda = sum_lambda / (double)count;
    const double predicted = sigma * sqrt(lambda * DT_S / 2.0);
    /* the forgetting settles where P = lambda R^-1 meets lambda = lambda0 (1 - tr P / k0) */
    const double lambda_eq = LAMBDA0_PER_S / (1.0 + LAMBDA0_PER_S * NP / K0);
    char msg[160];
    for (int i = 0; i < NP; ++i) {
        const double rms = sqrt(sum_sq[i] / (double)count);
        snprintf(msg, sizeof msg, "theta[%d]: RMS error %.4f, predicted %.4f (ratio %.3f), mean lambda %.1f/s (%.1f)",
                 i, rms, predicted, rms / predicted, lambda, lambda_eq);
        TEST_MESSAGE(msg);
        TEST_ASSERT_GREATER_THAN_FLOAT_MESSAGE(NOISE_RATIO_MIN, rms / predicted, msg);
        TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE(NOISE_RATIO_MAX, rms / predicted, msg);
    }
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.1 * lambda_eq, lambda_eq, lambda, msg);
}

/* Time after a parameter step until max_i |theta_i - new_i| stays within 5%
 * of the step, for a run of n_steps after the step (noise-free). */
static double time_to_track_a_step(double lambda0, int n_steps)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, lambda0, P0);
    const double before[NP] = {1.0, 2.0, -1.0};
    const double after[NP] = {2.0, 1.0, 0.0};
    rng_t rng = {.s = 99u};
    long last_out = -1;
    for (long k = -1000; k < n_steps; ++k) { /* 1 s on the old parameters first */
        const double *theta_true = k < 0 ? before : after;
        const ladrc_real_t phi[NP] = {1.0f, (ladrc_real_t)rng_normal(&rng), (ladrc_real_t)rng_normal(&rng)};
        double y = 0.0;
        for (int i = 0; i < NP; ++i) {
            y += (double)phi[i] * theta_true[i];
        }
        ladrc_rls_update(&rls, phi, (ladrc_real_t)y);
        double err = 0.0;
        for (int i = 0; i < NP; ++i) {
            err = fmax(err, fabs((double)ladrc_rls_get_theta(&rls)[i] - after[i]));
        }
        if (k >= 0 && err > 0.05 * 1.0) { /* every component steps by 1 */
            last_out = k;
        }
    }
    return (double)(last_out + 1) * DT_S;
}

static void test_forgetting_tracks_a_parameter_step_much_faster_than_plain_least_squares(void)
{
    /* given a step of every parameter after 1 s of data, when each estimator runs on */
    const double with = time_to_track_a_step(LAMBDA0_PER_S, 2000);
    const double without = time_to_track_a_step(0.0, 30000);
    char msg[120];
    snprintf(msg, sizeof msg, "time to within 5%%: %.3f s with forgetting, %.2f s without", with, without);
    TEST_MESSAGE(msg);
    /* then forgetting at about 50/s takes ln(20)/50 = 0.06 s; without it the
     * 1 s of old data is outweighed 19:1 only after 19 s */
    TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE(0.1, with, msg);
    TEST_ASSERT_FLOAT_WITHIN_MESSAGE(2.0, 19.0, without, msg);
}

/* --------------------------------------------------- variable forgetting */

static double first_lambda_at_trace(unsigned n, double trace)
{
    ladrc_rls_t rls;
    init_rls(&rls, n, LAMBDA0_PER_S, trace / n);
    const ladrc_real_t zeros[MAXP] = {0.0f};
    ladrc_rls_update(&rls, zeros, 0.0f);
    return (double)ladrc_rls_get_lambda(&rls);
}

static void test_forgetting_rate_is_lambda0_when_p_is_tiny(void)
{
    TEST_ASSERT_FLOAT_WITHIN(LAMBDA_TOL_PER_S, LAMBDA0_PER_S, first_lambda_at_trace(NP, 1e-6 * K0));
    TEST_ASSERT_FLOAT_WITHIN(LAMBDA_TOL_PER_S, LAMBDA0_PER_S, first_lambda_at_trace(1, 1e-9));
}

static void test_forgetting_rate_is_zero_when_the_trace_is_at_the_bound(void)
{
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, first_lambda_at_trace(NP, K0));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, first_lambda_at_trace(MAXP, K0));
}

static void test_forgetting_rate_falls_linearly_with_the_trace(void)
{
    TEST_ASSERT_FLOAT_WITHIN(LAMBDA_TOL_PER_S, 0.5 * LAMBDA0_PER_S, first_lambda_at_trace(NP, 0.5 * K0));
    TEST_ASSERT_FLOAT_WITHIN(LAMBDA_TOL_PER_S, 0.75 * LAMBDA0_PER_S, first_lambda_at_trace(MAXP, 0.25 * K0));
    /* forgetting stops 1e-4 below the bound: 2e-4 below still forgets */
    TEST_ASSERT_FLOAT_WITHIN(LAMBDA_TOL_PER_S, 2e-4 * LAMBDA0_PER_S, first_lambda_at_trace(2, (1.0 - 2e-4) * K0));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, first_lambda_at_trace(2, (1.0 - 0.5e-4) * K0));
}

static void test_without_excitation_p_grows_as_the_bounded_gain_law_says(void)
{
    /* given one parameter with P well below the bound and phi = 0, the law
     * per step is P <- P exp(lambda0 h (1 - P / k0)) */
    ladrc_rls_t rls;
    init_rls(&rls, 1, LAMBDA0_PER_S, 1.0);
    const ladrc_real_t zero[1] = {0.0f};
    double p = 1.0;
    for (int k = 0; k < 100; ++k) {
        ladrc_rls_update(&rls, zero, 0.0f);
        p *= exp(LAMBDA0_PER_S * DT_S * (1.0 - p / K0));
    }
    /* then P follows it: measured 1.05e-7 relative after 100 steps */
    TEST_ASSERT_FLOAT_WITHIN(CLOSED_FORM_REL_TOL * p, p, ladrc_rls_get_p(&rls, 0, 0));
}

/* ------------------------------------------------ guards on the covariance */

/* Runs phi = 0 until the state stops changing; returns the steps taken or -1. */
static long steps_to_fixed_point(ladrc_rls_t *rls, long max_steps)
{
    const ladrc_real_t zeros[MAXP] = {0.0f};
    snapshot_t prev = snapshot(rls);
    for (long k = 1; k <= max_steps; ++k) {
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(rls, zeros, 1.0f));
        const snapshot_t now = snapshot(rls);
        if (same_state(&prev, &now)) {
            return k;
        }
        prev = now;
    }
    return -1;
}

static void test_without_excitation_p_reaches_an_exact_fixed_point_on_the_bound(void)
{
    /* given estimators of every size and forgetting rates up to the
     * largest allowed (lambda0 h = 1), some after excitation left U full */
    const double lambda0s[] = {10.0, 100.0, 1000.0};
    for (unsigned n = 1; n <= MAXP; ++n) {
        for (unsigned m = 0; m < 3; ++m) {
            ladrc_rls_t rls;
            init_rls(&rls, n, lambda0s[m], 1.0 / n);
            rng_t rng = {.s = n * 10u + m};
            for (int k = 0; k < 50; ++k) {
                ladrc_real_t phi[MAXP];
                for (unsigned i = 0; i < MAXP; ++i) {
                    phi[i] = (ladrc_real_t)rng_normal(&rng);
                }
                ladrc_rls_update(&rls, phi, (ladrc_real_t)rng_normal(&rng));
            }
            /* when phi = 0 from then on */
            const long steps = steps_to_fixed_point(&rls, 200000);
            char msg[100];
            snprintf(msg, sizeof msg, "n %u, lambda0 %.0f/s: fixed point after %ld steps, tr P / k0 = %.7f", n,
                     lambda0s[m], steps, (double)ladrc_rls_get_p_norm(&rls) / K0);
            TEST_MESSAGE(msg);
            /* then an update leaves the state bit for bit unchanged, with
             * forgetting stopped and tr P in the last 1e-4 below the bound */
            TEST_ASSERT_GREATER_THAN_INT_MESSAGE(0, steps, msg);
            TEST_ASSERT_FLOAT_WITHIN_MESSAGE(0.0, 0.0, ladrc_rls_get_lambda(&rls), msg);
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE(K0, ladrc_rls_get_p_norm(&rls), msg);
            TEST_ASSERT_GREATER_OR_EQUAL_FLOAT_MESSAGE((1.0 - 1e-4) * K0, ladrc_rls_get_p_norm(&rls), msg);
            assert_sound(&rls, steps);
        }
    }
}

static void test_a_long_run_without_excitation_keeps_p_bounded_and_definite(void)
{
    /* given a full-size estimator after some excitation */
    ladrc_rls_t rls;
    init_rls(&rls, MAXP, LAMBDA0_PER_S, 1.0);
    rng_t rng = {.s = 31u};
    for (int k = 0; k < 100; ++k) {
        const ladrc_real_t phi[MAXP] = {1.0f, (ladrc_real_t)rng_normal(&rng), (ladrc_real_t)rng_normal(&rng)};
        ladrc_rls_update(&rls, phi, 0.5f);
    }
    /* when phi = 0 for LONG_RUN_STEPS steps (10^7 on the host) */
    const ladrc_real_t zeros[MAXP] = {0.0f};
    const ladrc_real_t k0 = (ladrc_real_t)K0;
    for (long k = 0; k < LONG_RUN_STEPS; ++k) {
        const ladrc_fault_t f = ladrc_rls_update(&rls, zeros, 0.5f);
        /* then every step is clean and bounded, and the full check holds */
        if (f != LADRC_FAULT_NONE || !(ladrc_rls_get_p_norm(&rls) <= k0)) {
            char msg[80];
            snprintf(msg, sizeof msg, "step %ld: faults %u, trace %.9g", k, (unsigned)f,
                     (double)ladrc_rls_get_p_norm(&rls));
            TEST_FAIL_MESSAGE(msg);
        }
        if ((k & 4095) == 0 || k < 5000) {
            assert_sound(&rls, k);
        }
    }
    assert_sound(&rls, LONG_RUN_STEPS);
    char msg[80];
    snprintf(msg, sizeof msg, "%ld steps, final tr P / k0 = %.7f", LONG_RUN_STEPS,
             (double)ladrc_rls_get_p_norm(&rls) / K0);
    TEST_MESSAGE(msg);
}

static void test_bursts_of_huge_excitation_keep_p_bounded_and_definite(void)
{
    /* given a full-size estimator alternating quiet spells (P grows to the
     * bound) with bursts of regressors up to 1e6 and noisy y */
    ladrc_rls_t rls;
    init_rls(&rls, MAXP, LAMBDA0_PER_S, 10.0);
    rng_t rng = {.s = 4242u};
    const double theta_true[MAXP] = {1.0, -1.0, 0.5};
    long repairs = 0;
    double smallest_d = 1e300;
    for (long k = 0; k < 20000; ++k) {
        const int burst = (k / 1000) % 2 == 1;
        ladrc_real_t phi[MAXP] = {0.0f};
        double y = 0.01 * rng_normal(&rng);
        if (burst) {
            /* magnitudes log-uniform over 1e0..1e6, often along one axis only */
            const int single = rng_uniform(&rng) < 0.5;
            const unsigned axis = (unsigned)(rng_uniform(&rng) * MAXP);
            for (unsigned i = 0; i < MAXP; ++i) {
                const double mag = pow(10.0, 6.0 * rng_uniform(&rng));
                phi[i] = (single && i != axis) ? 0.0f : (ladrc_real_t)(mag * rng_normal(&rng));
                y += (double)phi[i] * theta_true[i];
            }
        }
        const ladrc_fault_t f = ladrc_rls_update(&rls, phi, (ladrc_real_t)y);
        if (f == LADRC_FAULT_STATE) {
            ++repairs;
        }
        /* then the guards hold at every step */
        assert_sound(&rls, k);
        for (unsigned i = 0; i < MAXP; ++i) {
            smallest_d = fmin(smallest_d, (double)rls.d[i]);
            TEST_ASSERT_TRUE(isfinite((double)ladrc_rls_get_theta(&rls)[i]));
        }
    }
    char msg[100];
    snprintf(msg, sizeof msg, "20000 steps of bursts: %ld repairs, smallest D %.3g", repairs, smallest_d);
    TEST_MESSAGE(msg);
    /* and the factored form needed no repair */
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, repairs, msg);
    /* and the estimate is right after the last burst */
    for (unsigned i = 0; i < MAXP; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(1e-3, theta_true[i], ladrc_rls_get_theta(&rls)[i]);
    }
}

static void test_a_trace_above_the_bound_is_scaled_back_inside(void)
{
    /* given factors whose trace is twice the bound (only rounding or a
     * corrupted state can do this) */
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    rls.d[0] = (ladrc_real_t)(2.0 * P0);
    rls.d[1] = (ladrc_real_t)(3.0 * P0);
    rls.d[2] = (ladrc_real_t)(1.0 * P0);
    /* when the next update runs, without excitation */
    const ladrc_real_t zeros[NP] = {0.0f, 0.0f, 0.0f};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, zeros, 0.0f));
    /* then P is scaled, shape kept, to just inside the bound, where it stays */
    const double tr = (double)ladrc_rls_get_p_norm(&rls);
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT(K0, tr);
    TEST_ASSERT_GREATER_OR_EQUAL_FLOAT((1.0 - 1e-4) * K0, tr);
    TEST_ASSERT_FLOAT_WITHIN(RATIO_REL_TOL * 3.0, 3.0, (double)rls.d[1] / (double)rls.d[2]);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_rls_get_lambda(&rls));
    const snapshot_t before = snapshot(&rls);
    ladrc_rls_update(&rls, zeros, 0.0f);
    const snapshot_t after = snapshot(&rls);
    TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof before);
}

static void test_a_covariance_that_loses_definiteness_restarts_at_p_initial_keeping_theta(void)
{
    /* given an estimator that has learned something */
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const ladrc_real_t phi[NP] = {1.0f, 0.5f, -0.25f};
    for (int k = 0; k < 10; ++k) {
        ladrc_rls_update(&rls, phi, 2.0f);
    }
    const double theta_before = (double)ladrc_rls_get_theta(&rls)[0];
    /* when a corrupted factor makes the updated D negative */
    rls.d[1] = -1.0f;
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_update(&rls, phi, 2.0f));
    /* then P restarts at p_initial I, and theta took the (finite) update */
    for (uint8_t i = 0; i < NP; ++i) {
        for (uint8_t j = 0; j < NP; ++j) {
            TEST_ASSERT_FLOAT_WITHIN(0.0f, i == j ? (ladrc_real_t)P0 : 0.0f, ladrc_rls_get_p(&rls, i, j));
        }
    }
    TEST_ASSERT_TRUE(isfinite((double)ladrc_rls_get_theta(&rls)[0]));
    TEST_ASSERT_TRUE(fabs((double)ladrc_rls_get_theta(&rls)[0] - theta_before) < 1.0);
    /* and the next update is clean */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, phi, 2.0f));
    assert_sound(&rls, 0);
}

static void test_a_non_finite_factor_after_an_update_restarts_p(void)
{
    /* given a regressor so large that h phi^T P phi overflows */
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const ladrc_real_t huge = (ladrc_real_t)(sizeof(ladrc_real_t) == 4 ? 1e20 : 1e160);
    const ladrc_real_t phi[NP] = {huge, 0.0f, 0.0f};
    /* when it is fed */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_update(&rls, phi, 1.0f));
    /* then P restarts and theta is still finite */
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)P0, ladrc_rls_get_p(&rls, 0, 0));
    TEST_ASSERT_TRUE(isfinite((double)ladrc_rls_get_theta(&rls)[0]));
    /* and a NaN planted in U is caught the same way */
    rls.u[0] = (ladrc_real_t)NAN;
    const ladrc_real_t ok_phi[NP] = {1.0f, 1.0f, 1.0f};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_update(&rls, ok_phi, 1.0f));
    assert_sound(&rls, 0);
}

static void test_an_update_whose_theta_would_overflow_is_refused(void)
{
    /* given an estimate near the largest finite value and a P that learnt */
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const ladrc_real_t big = (ladrc_real_t)(sizeof(ladrc_real_t) == 4 ? 3e38 : 1.7e308);
    const ladrc_real_t theta0[NP] = {big, 0.0f, 0.0f};
    ladrc_rls_reset(&rls, theta0);
    const ladrc_real_t other[NP] = {0.0f, 1.0f, 0.0f};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, other, 0.0f));
    TEST_ASSERT_TRUE(ladrc_rls_get_p(&rls, 1, 1) < (ladrc_real_t)P0);
    const ladrc_real_t theta_before = ladrc_rls_get_theta(&rls)[0];
    /* when the prediction error overflows */
    const ladrc_real_t phi[NP] = {1.0f, 0.0f, 0.0f};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_update(&rls, phi, -big));
    /* then theta is held and P restarts: a P that made theta overflow is not kept */
    TEST_ASSERT_FLOAT_WITHIN(0.0f, theta_before, ladrc_rls_get_theta(&rls)[0]);
    for (uint8_t i = 0; i < NP; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)P0, ladrc_rls_get_p(&rls, i, i));
    }
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_rls_get_faults(&rls));
}

/* ------------------------------------------------------- input faults */

static void test_non_finite_samples_are_skipped_with_the_state_held(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const ladrc_real_t phi[NP] = {1.0f, 0.5f, -0.25f};
    ladrc_rls_update(&rls, phi, 2.0f);
    const snapshot_t before = snapshot(&rls);
    const ladrc_real_t bad[] = {(ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY};
    for (unsigned b = 0; b < 3; ++b) {
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_rls_update(&rls, phi, bad[b]));
        for (unsigned i = 0; i < NP; ++i) {
            ladrc_real_t p[NP] = {1.0f, 0.5f, -0.25f};
            p[i] = bad[b];
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_rls_update(&rls, p, 2.0f));
        }
    }
    const snapshot_t after = snapshot(&rls);
    TEST_ASSERT_EQUAL_MEMORY(&before, &after, sizeof before);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_rls_get_faults(&rls));
    /* and a finite sample clears the flag */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, phi, 2.0f));
}

static void test_entries_beyond_n_params_are_ignored(void)
{
    /* a NaN past the n_params entries of phi is never read */
    ladrc_rls_t rls;
    init_rls(&rls, 2, LAMBDA0_PER_S, P0);
    const ladrc_real_t phi[MAXP] = {1.0f, 2.0f, (ladrc_real_t)NAN};
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_update(&rls, phi, 1.0f));
    TEST_ASSERT_TRUE(isfinite((double)ladrc_rls_predict(&rls, phi)));
}

static void run_samples(ladrc_rls_t *rls, int with_bad)
{
    rng_t rng = {.s = 555u};
    for (int k = 0; k < 500; ++k) {
        const ladrc_real_t phi[NP] = {1.0f, (ladrc_real_t)rng_normal(&rng), (ladrc_real_t)rng_normal(&rng)};
        const ladrc_real_t y = (ladrc_real_t)(1.0 + 2.0 * (double)phi[1] + 0.1 * rng_normal(&rng));
        if (with_bad && k % 7 == 3) {
            const ladrc_real_t nan_phi[NP] = {1.0f, (ladrc_real_t)NAN, 0.0f};
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_rls_update(rls, nan_phi, y));
            TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_rls_update(rls, phi, (ladrc_real_t)INFINITY));
        }
        ladrc_rls_update(rls, phi, y);
    }
}

static void test_a_run_with_bad_samples_inserted_equals_the_clean_run_bit_for_bit(void)
{
    ladrc_rls_t clean;
    ladrc_rls_t dirty;
    init_rls(&clean, NP, LAMBDA0_PER_S, P0);
    init_rls(&dirty, NP, LAMBDA0_PER_S, P0);
    run_samples(&clean, 0);
    run_samples(&dirty, 1);
    const snapshot_t a = snapshot(&clean);
    const snapshot_t b = snapshot(&dirty);
    TEST_ASSERT_EQUAL_MEMORY(&a, &b, sizeof a);
}

/* ---------------------------------------------------- reset and repeat */

static void test_a_run_repeated_after_reset_is_bitwise_identical(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    run_samples(&rls, 0);
    const snapshot_t first = snapshot(&rls);
    ladrc_rls_reset(&rls, NULL);
    run_samples(&rls, 0);
    const snapshot_t second = snapshot(&rls);
    TEST_ASSERT_EQUAL_MEMORY(&first, &second, sizeof first);
}

static void test_reset_takes_theta0_and_restarts_p(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    run_samples(&rls, 0);
    /* NULL: zeros */
    ladrc_rls_reset(&rls, NULL);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_theta(&rls)[1]);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)(NP * P0), ladrc_rls_get_p_norm(&rls));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_lambda(&rls));
    /* given values, a non-finite one read as 0 */
    const ladrc_real_t theta0[NP] = {1.5f, (ladrc_real_t)NAN, -2.0f};
    ladrc_rls_reset(&rls, theta0);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 1.5f, ladrc_rls_get_theta(&rls)[0]);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_theta(&rls)[1]);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, -2.0f, ladrc_rls_get_theta(&rls)[2]);
    /* its own estimate: P only restarts */
    run_samples(&rls, 0);
    const ladrc_real_t kept = ladrc_rls_get_theta(&rls)[1];
    ladrc_rls_update(&rls, (const ladrc_real_t[NP]){(ladrc_real_t)NAN, 0.0f, 0.0f}, 0.0f);
    ladrc_rls_reset(&rls, ladrc_rls_get_theta(&rls));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, kept, ladrc_rls_get_theta(&rls)[1]);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)P0, ladrc_rls_get_p(&rls, 1, 1));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_p(&rls, 0, 1));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_rls_get_faults(&rls));
}

/* --------------------------------------------------------- accessors */

static void test_predict_is_phi_dot_theta(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, NP, LAMBDA0_PER_S, P0);
    const ladrc_real_t theta0[NP] = {1.0f, -2.0f, 0.5f};
    ladrc_rls_reset(&rls, theta0);
    const ladrc_real_t phi[NP] = {3.0f, 1.0f, 4.0f};
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 3.0f, ladrc_rls_predict(&rls, phi));
}

static void test_p_outside_n_params_reads_as_zero(void)
{
    ladrc_rls_t rls;
    init_rls(&rls, 2, LAMBDA0_PER_S, P0);
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_p(&rls, 2, 0));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, 0.0f, ladrc_rls_get_p(&rls, 0, 2));
    TEST_ASSERT_FLOAT_WITHIN(0.0f, (ladrc_real_t)P0, ladrc_rls_get_p(&rls, 1, 1));
}

static void test_state_holds_the_factors_and_six_scalars(void)
{
    char msg[64];
    snprintf(msg, sizeof msg, "sizeof(ladrc_rls_t) = %u bytes", (unsigned)sizeof(ladrc_rls_t));
    TEST_MESSAGE(msg);
    /* theta n + U n(n-1)/2 + D n + trace + 5 scalars, plus two bytes and
     * padding (one real) */
    const unsigned n = LADRC_RLS_MAX_PARAMS;
    const unsigned reals = n + n * (n - 1u) / 2u + n + 1u + 5u + 1u;
    TEST_ASSERT_LESS_OR_EQUAL_MESSAGE(reals * sizeof(ladrc_real_t), sizeof(ladrc_rls_t), msg);
}

/* ------------------------------------------------------- validation */

static void test_every_invalid_config_field_is_rejected_with_its_status(void)
{
    ladrc_rls_t rls;
    const ladrc_rls_config_t good = config(NP, LAMBDA0_PER_S, P0);
    ladrc_rls_config_t cfg;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_rls_init(NULL, &good));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_rls_init(&rls, NULL));
    const uint8_t bad_n[] = {0u, (uint8_t)(MAXP + 1), 255u};
    for (unsigned i = 0; i < 3; ++i) {
        cfg = good;
        cfg.n_params = bad_n[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_RLS_N_PARAMS, ladrc_rls_init(&rls, &cfg));
    }
    const ladrc_real_t bad[] = {0.0f, -1.0f, (ladrc_real_t)NAN, (ladrc_real_t)INFINITY, (ladrc_real_t)-INFINITY};
    for (unsigned i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        cfg = good;
        cfg.dt_s = bad[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_DT_S, ladrc_rls_init(&rls, &cfg));
        cfg = good;
        cfg.p_bound = bad[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_RLS_P_BOUND, ladrc_rls_init(&rls, &cfg));
        cfg = good;
        cfg.p_initial = bad[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_RLS_P_INITIAL, ladrc_rls_init(&rls, &cfg));
    }
    /* lambda0: 0 is allowed, negative, non-finite or above 1/h is not */
    const ladrc_real_t bad_lambda[] = {-1.0f, (ladrc_real_t)NAN, (ladrc_real_t)INFINITY, 1001.0f};
    for (unsigned i = 0; i < 4; ++i) {
        cfg = good;
        cfg.lambda0_per_s = bad_lambda[i];
        TEST_ASSERT_EQUAL_INT(LADRC_ERR_RLS_LAMBDA0, ladrc_rls_init(&rls, &cfg));
    }
    /* p_initial I must start inside the bound: n p_initial <= k0 */
    cfg = good;
    cfg.p_initial = (ladrc_real_t)(K0 / NP * 1.001);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_RLS_P_INITIAL, ladrc_rls_init(&rls, &cfg));
}

static void test_limit_values_of_the_config_are_accepted(void)
{
    ladrc_rls_t rls;
    ladrc_rls_config_t cfg = config(1, 0.0, K0);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_rls_init(&rls, &cfg));
    cfg = config(MAXP, 1.0 / DT_S, K0 / MAXP);
    cfg.lambda0_per_s = (ladrc_real_t)1.0 / cfg.dt_s;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_rls_init(&rls, &cfg));
}

static void assert_text_names(const char *name, ladrc_status_t status)
{
    /* the enum name, then ": why" unless built with LADRC_STATUS_TEXTS=names */
    const char *text = ladrc_status_str(status);
    const size_t n = strlen(name);
    TEST_ASSERT_EQUAL_INT(0, strncmp(name, text, n));
    TEST_ASSERT_TRUE(text[n] == '\0' || text[n] == ':');
}

static void test_every_status_of_the_module_has_its_text(void)
{
    assert_text_names("LADRC_ERR_RLS_N_PARAMS", LADRC_ERR_RLS_N_PARAMS);
    assert_text_names("LADRC_ERR_RLS_LAMBDA0", LADRC_ERR_RLS_LAMBDA0);
    assert_text_names("LADRC_ERR_RLS_P_BOUND", LADRC_ERR_RLS_P_BOUND);
    assert_text_names("LADRC_ERR_RLS_P_INITIAL", LADRC_ERR_RLS_P_INITIAL);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_starts_at_zero_with_p_initial_times_identity);
    RUN_TEST(test_factored_update_matches_the_plain_update_computed_in_double);
    RUN_TEST(test_scalar_update_gives_the_closed_form_p);
    RUN_TEST(test_noise_free_regression_converges_to_the_true_parameters);
    RUN_TEST(test_noisy_regression_error_matches_the_noise_and_the_forgetting_window);
    RUN_TEST(test_forgetting_tracks_a_parameter_step_much_faster_than_plain_least_squares);
    RUN_TEST(test_forgetting_rate_is_lambda0_when_p_is_tiny);
    RUN_TEST(test_forgetting_rate_is_zero_when_the_trace_is_at_the_bound);
    RUN_TEST(test_forgetting_rate_falls_linearly_with_the_trace);
    RUN_TEST(test_without_excitation_p_grows_as_the_bounded_gain_law_says);
    RUN_TEST(test_without_excitation_p_reaches_an_exact_fixed_point_on_the_bound);
    RUN_TEST(test_a_long_run_without_excitation_keeps_p_bounded_and_definite);
    RUN_TEST(test_bursts_of_huge_excitation_keep_p_bounded_and_definite);
    RUN_TEST(test_a_trace_above_the_bound_is_scaled_back_inside);
    RUN_TEST(test_a_covariance_that_loses_definiteness_restarts_at_p_initial_keeping_theta);
    RUN_TEST(test_a_non_finite_factor_after_an_update_restarts_p);
    RUN_TEST(test_an_update_whose_theta_would_overflow_is_refused);
    RUN_TEST(test_non_finite_samples_are_skipped_with_the_state_held);
    RUN_TEST(test_entries_beyond_n_params_are_ignored);
    RUN_TEST(test_a_run_with_bad_samples_inserted_equals_the_clean_run_bit_for_bit);
    RUN_TEST(test_a_run_repeated_after_reset_is_bitwise_identical);
    RUN_TEST(test_reset_takes_theta0_and_restarts_p);
    RUN_TEST(test_predict_is_phi_dot_theta);
    RUN_TEST(test_p_outside_n_params_reads_as_zero);
    RUN_TEST(test_state_holds_the_factors_and_six_scalars);
    RUN_TEST(test_every_invalid_config_field_is_rejected_with_its_status);
    RUN_TEST(test_limit_values_of_the_config_are_accepted);
    RUN_TEST(test_every_status_of_the_module_has_its_text);
    return UNITY_END();
}
