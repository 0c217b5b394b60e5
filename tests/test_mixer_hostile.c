/* SPDX-License-Identifier: BSD-3-Clause */
/* Mixer under hostile input: property tests over many generated vectors.
 *
 * 1. Requests: bursts of huge finite values (up to +-largest float), subnormals,
 *    zeros, NaN and +-Inf mixed with normal requests, on several vehicles and
 *    both modes. After every step the promises of mixer.h are checked: outputs
 *    finite and within the rotor limits, achieved values the forward model of
 *    the output, saturation bits consistent with them, priorities, the fault
 *    flags, the held output after a non-finite request; after every burst a
 *    nominal request must be mixed exactly as a fresh mixer mixes it.
 * 2. Configs: random and boundary values of every field. Init must accept a
 *    config exactly when every field lies within its documented bounds (and
 *    return the status of the first field that does not), and every accepted
 *    config must run nominal requests without a fault, finite and in range.
 *
 * Sizes: MIXER_HOSTILE_VECTORS, MIXER_HOSTILE_CONFIGS and MIXER_HOSTILE_STEPS
 * at compile time, or the environment variables of the same names prefixed
 * LADRC_ (e.g. LADRC_MIXER_HOSTILE_VECTORS=1e8) for a long run. Each test
 * prints how many it ran and how many violations it found; any violation fails.
 */
#include "unity.h"
#include "ladrc/mixer.h"
#include "test_hostile.h"

#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef LADRC_REAL_DOUBLE
#define REAL_MAX DBL_MAX
#define REAL_MIN DBL_MIN
#define REAL_EPS DBL_EPSILON
#else
#define REAL_MAX FLT_MAX
#define REAL_MIN FLT_MIN
#define REAL_EPS FLT_EPSILON
#endif

/* Default sizes. The host runs the full figures in a few seconds; under QEMU
 * (Cortex-M4F, soft double for the checks) a step with its checks costs some
 * 100x more, so the cross build runs a tenth of the vectors and configs and a
 * tenth of the steps per accepted config. */
#ifndef MIXER_HOSTILE_VECTORS
#ifdef __arm__
#define MIXER_HOSTILE_VECTORS 100000.0
#else
#define MIXER_HOSTILE_VECTORS 1000000.0
#endif
#endif
#ifndef MIXER_HOSTILE_CONFIGS
#ifdef __arm__
#define MIXER_HOSTILE_CONFIGS 10000.0
#else
#define MIXER_HOSTILE_CONFIGS 100000.0
#endif
#endif
#ifndef MIXER_HOSTILE_STEPS
#ifdef __arm__
#define MIXER_HOSTILE_STEPS 1000.0
#else
#define MIXER_HOSTILE_STEPS 10000.0
#endif
#endif

/* The report promise (mixer.h): an axis reports its request while the rotors give
 * it within 8 eps coef sum|w^2| (+ 16 subnormals), the forward model otherwise. */
#define REPORT_TOL_EPS 8.0
#define REPORT_TOL_SUBNORMALS 16.0
/* The float forward model the mixer compares with lies off the exact one by at
 * most two sums and a product on sum|w^2|: 2 eps coef sum|w^2| (+ a few
 * subnormals where a product underflows). */
#define FORWARD_ROUNDING_EPS 2.0
#define FORWARD_ROUNDING_SUBNORMALS 4.0
/* "Fits" margin of the priority checks, relative to w2_max: the mixer works on
 * w^2 parts rounded to a few eps of w2_max, so requests within 64 eps (7.6e-6 in
 * float) of a limit may go either way; they are not judged. */
#define FIT_MARGIN (64.0 * REAL_EPS)
/* Direction of scaled roll and pitch: cross product of the unit request and the
 * achieved pair, relative to the achieved size; a handful of roundings of w^2
 * on the scale of the range. */
#define DIRECTION_TOL (64.0 * REAL_EPS)
/* Ideal mode refuses (state fault) only a w^2 beyond REAL_MAX/4; its float
 * allocation lies within a few eps of the exact one. */
#define IDEAL_STATE_MARGIN (1.0 - 16.0 * REAL_EPS)

void setUp(void)
{
}
void tearDown(void)
{
}

/* ------------------------------------------------------------------ sizes */

static double size_from_env(const char *name, double fallback)
{
    const char *text = getenv(name);
    if (text != NULL && text[0] != '\0') {
        char *end = NULL;
        const double v = strtod(text, &end);
        if (end != text && v >= 1.0) {
            return floor(v);
        }
    }
    return fallback;
}

/* -------------------------------------------------------------------- rng */

/* The shared generator (tests/support/test_hostile.h); draws below n by
 * modulo, as this campaign's recorded figures were drawn. */
typedef test_rng_t rng_t;

static uint64_t next_u64(rng_t *r)
{
    return test_rng_next(r);
}

static double next_unit(rng_t *r)
{
    return test_rng_uniform(r);
}

static double next_range(rng_t *r, double lo, double hi)
{
    return lo + (hi - lo) * next_unit(r);
}

static unsigned next_below(rng_t *r, unsigned n)
{
    return (unsigned)(next_u64(r) % n);
}

/* Log-uniform in [lo, hi], lo > 0. */
static double next_log(rng_t *r, double lo, double hi)
{
    return lo * pow(hi / lo, next_unit(r));
}

static double next_sign(rng_t *r)
{
    return (next_u64(r) & 1u) ? -1.0 : 1.0;
}

/* ---------------------------------------------------------- real values */

static ladrc_real_t nan_value(rng_t *r)
{
    return test_special_nan(next_below(r, TEST_NAN_KINDS));
}
static ladrc_real_t inf_value(rng_t *r)
{
    return test_special_value(1u + next_below(r, 2u));
}

/* A macro, not a function: the checks call it a dozen times per step. */
#define is_finite_real(x) (isfinite(x) ? 1 : 0)

/* A subnormal, a zero or the smallest normal, either sign. */
static ladrc_real_t tiny_value(rng_t *r)
{
    switch (next_below(r, 5u)) {
    case 0:
        return (ladrc_real_t)(next_sign(r) * 0.0);
    case 1:
        return (ladrc_real_t)(next_sign(r) * REAL_MIN);
    case 2:
        return (ladrc_real_t)(next_sign(r) * REAL_MIN * REAL_EPS); /* smallest subnormal */
    default:
        return (ladrc_real_t)(next_sign(r) * next_unit(r) * REAL_MIN);
    }
}

/* A finite value from 1e3 up to the largest, either sign. */
static ladrc_real_t huge_value(rng_t *r)
{
    if (next_below(r, 4u) == 0u) {
        return (ladrc_real_t)(next_sign(r) * REAL_MAX);
    }
    return (ladrc_real_t)(next_sign(r) * pow(10.0, next_range(r, 3.0, log10(REAL_MAX))));
}

/* ------------------------------------------------------------- vehicles */

typedef struct {
    const char *name;
    ladrc_mixer_config_t cfg;
} vehicle_t;

static vehicle_t vehicle(const char *name, double kL, double arm, double b, double mass, double w2_min, double w2_max,
                         ladrc_mixer_mode_t mode)
{
    vehicle_t v;
    v.name = name;
    v.cfg.kL_N_s2 = (ladrc_real_t)kL;
    v.cfg.arm_m = (ladrc_real_t)arm;
    v.cfg.b_Nm_s2 = (ladrc_real_t)b;
    v.cfg.mass_kg = (ladrc_real_t)mass;
    v.cfg.g_m_s2 = (ladrc_real_t)9.81;
    v.cfg.w2_min_rad2_s2 = (ladrc_real_t)w2_min;
    v.cfg.w2_max_rad2_s2 = (ladrc_real_t)w2_max;
    v.cfg.tilt_max_rad = (ladrc_real_t)0.7;
    v.cfg.mode = mode;
    return v;
}

/* Coefficients of the forward model per axis: thrust, roll, pitch, yaw. */
static void coefficients(const ladrc_mixer_config_t *c, double coef[4])
{
    coef[0] = (double)c->kL_N_s2;
    coef[1] = (double)c->arm_m * (double)c->kL_N_s2;
    coef[2] = coef[1];
    coef[3] = (double)c->b_Nm_s2;
}

/* Forward model in long double from the output's w^2. */
static void forward_exact(const ladrc_mixer_config_t *c, const ladrc_real_t w2[4], long double f[4])
{
    const long double w[4] = {w2[0], w2[1], w2[2], w2[3]};
    const long double kL = c->kL_N_s2;
    const long double lkL = (long double)c->arm_m * kL;
    f[0] = kL * (w[0] + w[1] + w[2] + w[3]);
    f[1] = lkL * (w[1] - w[3]);
    f[2] = lkL * (w[2] - w[0]);
    f[3] = (long double)c->b_Nm_s2 * (-w[0] + w[1] - w[2] + w[3]);
}

static double sum_abs(const ladrc_real_t w2[4])
{
    return fabs((double)w2[0]) + fabs((double)w2[1]) + fabs((double)w2[2]) + fabs((double)w2[3]);
}

/* ------------------------------------------------------------ violations */

enum {
    V_FAULTS,
    V_FINITE,
    V_RANGE,
    V_SQRT,
    V_REPORT,
    V_BITS,
    V_NO_CUT,
    V_PRIORITY,
    V_DIRECTION,
    V_HELD,
    V_RECOVERY,
    V_INIT,
    V_KINDS
};

typedef struct {
    unsigned long long count;
    unsigned long long by_kind[V_KINDS];
    int printed;
} violations_t;

static const char *const violation_names[V_KINDS] = {"fault flags",
                                                     "not finite",
                                                     "w2 out of range",
                                                     "w not sqrt(w2)",
                                                     "report != forward model",
                                                     "bit != (achieved != requested)",
                                                     "bit without a cut",
                                                     "priority",
                                                     "direction",
                                                     "held output",
                                                     "recovery",
                                                     "init decision"};

/* What a violation is about: a step (request, output, flags) or a config. */
typedef struct {
    const char *where;
    const ladrc_mixer_config_t *cfg;
    const ladrc_real_t *f; /* thrust, roll, pitch, yaw; NULL for a config */
    const ladrc_mixer_output_t *out;
    ladrc_fault_t faults;
} context_t;

/* Counts a violation; the first few are printed (formatted only then). */
static void violate(violations_t *v, int kind, const context_t *x)
{
    ++v->count;
    ++v->by_kind[kind];
    if (v->printed < 12) {
        const ladrc_mixer_config_t *c = x->cfg;
        char msg[600];
        int len = snprintf(msg, sizeof msg,
                           "violation (%s), %s: config kL %.9g arm %.9g b %.9g m %.9g g %.9g w2 [%.9g, %.9g] "
                           "tilt %.9g mode %d",
                           violation_names[kind], x->where, (double)c->kL_N_s2, (double)c->arm_m, (double)c->b_Nm_s2,
                           (double)c->mass_kg, (double)c->g_m_s2, (double)c->w2_min_rad2_s2, (double)c->w2_max_rad2_s2,
                           (double)c->tilt_max_rad, (int)c->mode);
        if (x->f != NULL && len > 0 && (size_t)len < sizeof msg) {
            const ladrc_mixer_output_t *o = x->out;
            (void)snprintf(msg + len, sizeof msg - (size_t)len,
                           "; request %.9g %.9g %.9g %.9g; faults %u, saturated 0x%x, w2 %.9g %.9g %.9g %.9g, "
                           "achieved %.9g %.9g %.9g %.9g",
                           (double)x->f[0], (double)x->f[1], (double)x->f[2], (double)x->f[3], (unsigned)x->faults,
                           (unsigned)o->saturated, (double)o->w2_rad2_s2[0], (double)o->w2_rad2_s2[1],
                           (double)o->w2_rad2_s2[2], (double)o->w2_rad2_s2[3], (double)o->thrust_N,
                           (double)o->torque_Nm[0], (double)o->torque_Nm[1], (double)o->torque_Nm[2]);
        }
        ++v->printed;
        TEST_MESSAGE(msg);
    }
}

static void report_violations(const violations_t *v, const char *what)
{
    char msg[600];
    int len;
    int k;
    len = snprintf(msg, sizeof msg, "%s: %llu violations", what, v->count);
    for (k = 0; k < V_KINDS; ++k) {
        if (v->by_kind[k] != 0u && len > 0 && (size_t)len < sizeof msg) {
            len += snprintf(msg + len, sizeof msg - (size_t)len, "; %s %llu", violation_names[k], v->by_kind[k]);
        }
    }
    TEST_MESSAGE(msg);
}

static int same_output(const ladrc_mixer_output_t *a, const ladrc_mixer_output_t *b, int with_faults)
{
    return memcmp(a->w2_rad2_s2, b->w2_rad2_s2, sizeof a->w2_rad2_s2) == 0 &&
           memcmp(a->w_rad_s, b->w_rad_s, sizeof a->w_rad_s) == 0 &&
           memcmp(&a->thrust_N, &b->thrust_N, sizeof a->thrust_N) == 0 &&
           memcmp(a->torque_Nm, b->torque_Nm, sizeof a->torque_Nm) == 0 && a->saturated == b->saturated &&
           (!with_faults || a->faults == b->faults);
}

/* ------------------------------------------------------ the step's promises */

/* Checks one step: request f = {thrust, roll, pitch, yaw}, the output before
 * (prev) and after (out), and the returned flags. Counts what it finds. */
static void check_step(const char *where, const ladrc_mixer_config_t *c, const ladrc_real_t f[4],
                       const ladrc_mixer_output_t *prev, const ladrc_mixer_output_t *out, ladrc_fault_t returned,
                       violations_t *v)
{
    static const uint8_t bit[4] = {LADRC_MIXER_SAT_THRUST, LADRC_MIXER_SAT_ROLL, LADRC_MIXER_SAT_PITCH,
                                   LADRC_MIXER_SAT_YAW};
    const int ideal = (c->mode == LADRC_MIXER_IDEAL);
    const double lo = ideal ? -0.25 * REAL_MAX : (double)c->w2_min_rad2_s2;
    const double hi = ideal ? 0.25 * REAL_MAX : (double)c->w2_max_rad2_s2;
    const int finite_in = is_finite_real(f[0]) && is_finite_real(f[1]) && is_finite_real(f[2]) && is_finite_real(f[3]);
    const ladrc_real_t achieved[4] = {out->thrust_N, out->torque_Nm[0], out->torque_Nm[1], out->torque_Nm[2]};
    context_t x;
    double coef[4];
    long double fwd[4];
    double sum;
    int i;

    x.where = where;
    x.cfg = c;
    x.f = f;
    x.out = out;
    x.faults = returned;

    /* fault flags: input fault exactly for a non-finite request; a finite one
     * mixes in saturate mode, and in ideal mode mixes or is refused as too large */
    if (out->faults != returned) {
        violate(v, V_FAULTS, &x);
    }
    if (!finite_in) {
        if (returned != LADRC_FAULT_INPUT) {
            violate(v, V_FAULTS, &x);
        }
    } else if (returned != LADRC_FAULT_NONE && !(ideal && returned == LADRC_FAULT_STATE)) {
        violate(v, V_FAULTS, &x);
    }
    if (returned != LADRC_FAULT_NONE) {
        /* refused: the previous output, held */
        if (!same_output(prev, out, 0)) {
            violate(v, V_HELD, &x);
        }
        if (finite_in && ideal && returned == LADRC_FAULT_STATE) {
            /* only a w^2 beyond REAL_MAX/4 is refused */
            const long double kL = c->kL_N_s2;
            const long double lkL = (long double)c->arm_m * kL;
            const long double a4 = (long double)f[0] / (4.0L * kL);
            const long double p2 = (long double)f[1] / (2.0L * lkL);
            const long double q2 = (long double)f[2] / (2.0L * lkL);
            const long double r4 = (long double)f[3] / (4.0L * c->b_Nm_s2);
            const long double w[4] = {a4 - q2 - r4, a4 + p2 + r4, a4 + q2 - r4, a4 - p2 + r4};
            long double m = 0.0L;
            for (i = 0; i < 4; ++i) {
                m = fmaxl(m, fabsl(w[i]));
            }
            if (!(m > 0.25L * REAL_MAX * IDEAL_STATE_MARGIN)) {
                violate(v, V_FAULTS, &x);
            }
        }
        return;
    }

    /* finite, within the limits, w = sqrt(max(w^2, 0)) */
    for (i = 0; i < 4; ++i) {
        const ladrc_real_t w2 = out->w2_rad2_s2[i];
        if (!is_finite_real(w2) || !is_finite_real(out->w_rad_s[i]) || !is_finite_real(achieved[i])) {
            violate(v, V_FINITE, &x);
            return;
        }
        if (!((double)w2 >= lo && (double)w2 <= hi)) {
            violate(v, V_RANGE, &x);
        }
        if (out->w_rad_s[i] != ((w2 > 0) ? (ladrc_real_t)sqrt((double)w2) : (ladrc_real_t)0.0)) {
            violate(v, V_SQRT, &x);
        }
    }

    /* the report is the forward model of the output, within the tolerance;
     * a bit is set exactly when achieved != requested, and only for a real cut */
    coefficients(c, coef);
    forward_exact(c, out->w2_rad2_s2, fwd);
    sum = sum_abs(out->w2_rad2_s2);
    for (i = 0; i < 4; ++i) {
        const long double tol = (REPORT_TOL_EPS + FORWARD_ROUNDING_EPS) * REAL_EPS * coef[i] * sum +
                                (REPORT_TOL_SUBNORMALS + FORWARD_ROUNDING_SUBNORMALS) * REAL_MIN * REAL_EPS;
        const long double cut_tol = (REPORT_TOL_EPS - FORWARD_ROUNDING_EPS) * REAL_EPS * coef[i] * sum +
                                    (REPORT_TOL_SUBNORMALS - FORWARD_ROUNDING_SUBNORMALS) * REAL_MIN * REAL_EPS;
        const int flagged = (out->saturated & bit[i]) != 0u;
        const int differs = memcmp(&achieved[i], &f[i], sizeof f[i]) != 0;
        if (fabsl((long double)achieved[i] - fwd[i]) > tol) {
            violate(v, V_REPORT, &x);
        }
        if (flagged != differs) {
            violate(v, V_BITS, &x);
        }
        if (flagged && !(fabsl(fwd[i] - (long double)f[i]) > cut_tol)) {
            violate(v, V_NO_CUT, &x);
        }
        if (i > 0) {
            /* a torque is never raised beyond its request nor turned around */
            const long double a = achieved[i];
            const long double r = f[i];
            if ((r >= 0.0L && (a < -tol || a > r + tol)) || (r < 0.0L && (a > tol || a < r - tol))) {
                violate(v, V_PRIORITY, &x);
            }
        }
    }
    if ((out->saturated & ~0x0fu) != 0u) {
        violate(v, V_BITS, &x);
    }

    if (ideal) {
        /* no limits: nothing is ever cut */
        if (out->saturated != 0u) {
            violate(v, V_PRIORITY, &x);
        }
        return;
    }
    {
        /* priorities, judged on the exact allocation of the request */
        const long double range = (long double)c->w2_max_rad2_s2 - (long double)c->w2_min_rad2_s2;
        const long double margin = FIT_MARGIN * (long double)c->w2_max_rad2_s2;
        const long double lkL = (long double)c->arm_m * c->kL_N_s2;
        const long double p2 = fabsl((long double)f[1]) / (2.0L * lkL);
        const long double q2 = fabsl((long double)f[2]) / (2.0L * lkL);
        const long double r4 = fabsl((long double)f[3]) / (4.0L * c->b_Nm_s2);
        const int rp_fits = 2.0L * fmaxl(p2, q2) <= range - margin;
        const int yaw_fits = rp_fits && p2 + q2 + 2.0L * r4 <= range - margin;
        if (rp_fits && (out->saturated & (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH)) != 0u) {
            violate(v, V_PRIORITY, &x);
        }
        if (yaw_fits && (out->saturated & LADRC_MIXER_SAT_YAW) != 0u) {
            violate(v, V_PRIORITY, &x);
        }
        if (2.0L * fmaxl(p2, q2) > range + margin) {
            /* roll and pitch scaled alike: the achieved pair points where the request
             * does and uses the whole range */
            const long double m = fmaxl(fabsl((long double)f[1]), fabsl((long double)f[2]));
            const long double ur = (long double)f[1] / m; /* unit request, max norm */
            const long double up = (long double)f[2] / m;
            const long double ar = fwd[1];
            const long double ap = fwd[2];
            const long double size = fmaxl(fabsl(ar), fabsl(ap));
            if (!(fabsl(ar * up - ap * ur) <= DIRECTION_TOL * size) || !(ar * ur + ap * up > 0.0L) ||
                !(fabsl(size / lkL - range) <= margin)) {
                violate(v, V_DIRECTION, &x);
            }
        }
    }
}

/* --------------------------------------------------- request generation */

/* A request a flight could ask for, on the vehicle's scale: thrust from below 0 to
 * 3x the weight, roll and pitch up to 2x what the rotors give (torque_scale), yaw
 * in proportion b / (l kL). */
static void normal_request(rng_t *r, const ladrc_mixer_config_t *c, double torque_scale, ladrc_real_t f[4])
{
    const double weight = (double)c->mass_kg * (double)c->g_m_s2;
    const double yaw_ratio = (double)c->b_Nm_s2 / ((double)c->arm_m * (double)c->kL_N_s2);
    f[0] = (ladrc_real_t)(weight * next_range(r, -0.5, 3.0));
    f[1] = (ladrc_real_t)(torque_scale * next_range(r, -2.0, 2.0));
    f[2] = (ladrc_real_t)(torque_scale * next_range(r, -2.0, 2.0));
    f[3] = (ladrc_real_t)(torque_scale * yaw_ratio * next_range(r, -4.0, 4.0));
}

/* One component of a burst: normal, huge, tiny, NaN or infinite. */
static ladrc_real_t burst_value(rng_t *r, ladrc_real_t normal)
{
    const unsigned k = next_below(r, 100u);
    if (k < 35u) {
        return normal;
    }
    if (k < 60u) {
        return huge_value(r);
    }
    if (k < 75u) {
        return tiny_value(r);
    }
    if (k < 90u) {
        return nan_value(r);
    }
    return inf_value(r);
}

static void test_mixer_step_keeps_its_promises_under_hostile_requests(void)
{
    const double n_vectors = size_from_env("LADRC_MIXER_HOSTILE_VECTORS", MIXER_HOSTILE_VECTORS);
    vehicle_t vehicles[5];
    const size_t n_vehicles = sizeof vehicles / sizeof vehicles[0];
    violations_t v;
    /* vectors, with a non-finite value, bursts, mixed with saturation, refused */
    unsigned long long counts[5] = {0, 0, 0, 0, 0};
    char msg[300];
    rng_t r;
    size_t k;
    memset(&v, 0, sizeof v);
    r.state = UINT64_C(20240611);
    vehicles[0] = vehicle("paper", 2.98e-5, 0.165, 2e-6, 0.8, 1e4, 2e5, LADRC_MIXER_SATURATE);
    vehicles[1] = vehicle("20 g micro", 2.9e-8, 0.046, 7e-10, 0.02, 0.0, 3.6e7, LADRC_MIXER_SATURATE);
    vehicles[2] = vehicle("50 kg lifter", 3e-3, 1.5, 1e-4, 50.0, 400.0, 9e4, LADRC_MIXER_SATURATE);
    vehicles[3] = vehicle("at the bounds", (double)LADRC_MIXER_KL_MAX_N_S2, (double)LADRC_MIXER_ARM_MAX_M,
                          (double)LADRC_MIXER_B_MIN_NM_S2, (double)LADRC_MIXER_MASS_MIN_KG, 0.0,
                          (double)LADRC_MIXER_W2_MAX_MAX_RAD2_S2, LADRC_MIXER_SATURATE);
    vehicles[4] = vehicle("paper, ideal", 2.98e-5, 0.165, 2e-6, 0.8, 0.0, 1e12, LADRC_MIXER_IDEAL);

    for (k = 0; k < n_vehicles; ++k) {
        const ladrc_mixer_config_t *c = &vehicles[k].cfg;
        const double share =
            floor(n_vectors / (double)n_vehicles) + ((k == 0) ? fmod(n_vectors, (double)n_vehicles) : 0.0);
        const double torque_scale =
            (c->mode == LADRC_MIXER_IDEAL)
                ? 0.1 * (double)c->mass_kg * (double)c->g_m_s2 * (double)c->arm_m
                : (double)c->arm_m * (double)c->kL_N_s2 * ((double)c->w2_max_rad2_s2 - (double)c->w2_min_rad2_s2);
        ladrc_mixer_t mx;
        ladrc_mixer_t fresh;
        ladrc_mixer_output_t prev;
        double n = 0.0;
        int in_burst = 0;
        long left = 0;
        TEST_ASSERT_EQUAL_INT_MESSAGE(LADRC_OK, ladrc_mixer_init(&mx, c), vehicles[k].name);
        TEST_ASSERT_EQUAL_INT_MESSAGE(LADRC_OK, ladrc_mixer_init(&fresh, c), vehicles[k].name);
        prev = mx.out;
        while (n < share) {
            ladrc_real_t f[4];
            ladrc_mixer_output_t out;
            ladrc_fault_t faults;
            int probe = 0;
            if (left <= 0) {
                /* a phase ends; after a burst, probe recovery with a nominal request */
                probe = in_burst;
                in_burst = !in_burst;
                left = (long)next_below(&r, 48u) + 1;
                counts[2] += (unsigned long long)in_burst;
            }
            normal_request(&r, c, torque_scale, f);
            if (probe) {
                f[0] = (ladrc_real_t)((double)c->mass_kg * (double)c->g_m_s2);
                f[1] = (ladrc_real_t)(0.1 * torque_scale * next_range(&r, -1.0, 1.0));
                f[2] = (ladrc_real_t)(0.1 * torque_scale * next_range(&r, -1.0, 1.0));
                f[3] = (ladrc_real_t)(0.01 * torque_scale * next_range(&r, -1.0, 1.0));
            } else {
                if (in_burst) {
                    int i;
                    for (i = 0; i < 4; ++i) {
                        f[i] = burst_value(&r, f[i]);
                    }
                }
                --left;
            }
            faults = ladrc_mixer_step(&mx, f[0], &f[1], &out);
            check_step(vehicles[k].name, c, f, &prev, &out, faults, &v);
            if (probe) {
                /* memoryless: a mixer that never saw the burst mixes the request alike */
                ladrc_mixer_output_t expected;
                context_t x;
                (void)ladrc_mixer_step(&fresh, f[0], &f[1], &expected);
                x.where = "recovery after a burst";
                x.cfg = c;
                x.f = f;
                x.out = &out;
                x.faults = faults;
                if (faults != LADRC_FAULT_NONE || !same_output(&expected, &out, 1)) {
                    violate(&v, V_RECOVERY, &x);
                }
            }
            counts[0] += 1u;
            counts[1] += (unsigned long long)!(is_finite_real(f[0]) && is_finite_real(f[1]) && is_finite_real(f[2]) &&
                                               is_finite_real(f[3]));
            counts[3] += (unsigned long long)(faults == LADRC_FAULT_NONE && out.saturated != 0u);
            counts[4] += (unsigned long long)(faults != LADRC_FAULT_NONE);
            prev = out;
            n += 1.0;
        }
    }
    snprintf(msg, sizeof msg,
             "%llu request vectors on %u vehicles: %llu bursts, %llu vectors with a non-finite value, "
             "%llu refused (held), %llu mixed with a saturation bit",
             counts[0], (unsigned)n_vehicles, counts[2], counts[1], counts[4], counts[3]);
    TEST_MESSAGE(msg);
    report_violations(&v, "request vectors");
    TEST_ASSERT_TRUE_MESSAGE(v.count == 0u, "the mixer broke a promise of mixer.h (see the messages above)");
}

/* ----------------------------------------------------------- config test */

/* The documented bounds (mixer.h), read independently of the library: the status
 * init must return, LADRC_OK when every field is in bounds. */
static ladrc_status_t expected_status(const ladrc_mixer_config_t *c)
{
    const double value[5] = {c->kL_N_s2, c->arm_m, c->b_Nm_s2, c->mass_kg, c->g_m_s2};
    const double lo[5] = {LADRC_MIXER_KL_MIN_N_S2, LADRC_MIXER_ARM_MIN_M, LADRC_MIXER_B_MIN_NM_S2,
                          LADRC_MIXER_MASS_MIN_KG, LADRC_MIXER_G_MIN_M_S2};
    const double hi[5] = {LADRC_MIXER_KL_MAX_N_S2, LADRC_MIXER_ARM_MAX_M, LADRC_MIXER_B_MAX_NM_S2,
                          LADRC_MIXER_MASS_MAX_KG, LADRC_MIXER_G_MAX_M_S2};
    const double min2 = (double)c->w2_min_rad2_s2;
    const double max2 = (double)c->w2_max_rad2_s2;
    const double tilt = (double)c->tilt_max_rad;
    int i;
    for (i = 0; i < 5; ++i) {
        if (!(isfinite(value[i]) && value[i] >= lo[i] && value[i] <= hi[i])) {
            return (ladrc_status_t)(LADRC_ERR_MIXER_KL_N_S2 + i);
        }
    }
    if ((int)c->mode != (int)LADRC_MIXER_SATURATE && (int)c->mode != (int)LADRC_MIXER_IDEAL) {
        return LADRC_ERR_MIXER_MODE;
    }
    if (c->mode == LADRC_MIXER_SATURATE) {
        if (!(isfinite(min2) && min2 >= 0.0)) {
            return LADRC_ERR_MIXER_W2_MIN;
        }
        if (!(isfinite(max2) && max2 >= (double)LADRC_MIXER_W2_MAX_MIN_RAD2_S2 &&
              max2 <= (double)LADRC_MIXER_W2_MAX_MAX_RAD2_S2 && max2 > min2)) {
            return LADRC_ERR_MIXER_W2_MAX;
        }
    } else {
        if (!isfinite(min2)) {
            return LADRC_ERR_MIXER_W2_MIN;
        }
        if (!(isfinite(max2) && max2 > min2)) {
            return LADRC_ERR_MIXER_W2_MAX;
        }
    }
    /* (0, pi/2); the last value accepted is 1.5707963 rounded to ladrc_real_t */
    if (!(isfinite(tilt) && tilt > 0.0 && tilt <= (double)(ladrc_real_t)1.5707963)) {
        return LADRC_ERR_MIXER_TILT_MAX_RAD;
    }
    return LADRC_OK;
}

static ladrc_real_t next_down(ladrc_real_t x)
{
#ifdef LADRC_REAL_DOUBLE
    return nextafter(x, -INFINITY);
#else
    return nextafterf(x, -INFINITY);
#endif
}

static ladrc_real_t next_up(ladrc_real_t x)
{
#ifdef LADRC_REAL_DOUBLE
    return nextafter(x, INFINITY);
#else
    return nextafterf(x, INFINITY);
#endif
}

/* A hostile or boundary value for a field whose bounds are [lo, hi]. */
static ladrc_real_t boundary_value(rng_t *r, ladrc_real_t lo, ladrc_real_t hi)
{
    switch (next_below(r, 18u)) {
    case 0:
        return (ladrc_real_t)0.0;
    case 1:
        return (ladrc_real_t)-0.0;
    case 2:
        return (ladrc_real_t)(REAL_MIN * REAL_EPS); /* smallest subnormal */
    case 3:
        return (ladrc_real_t)(next_unit(r) * REAL_MIN); /* a subnormal */
    case 4:
        return (ladrc_real_t)REAL_MIN;
    case 5:
        return (ladrc_real_t)REAL_MAX;
    case 6:
        return (ladrc_real_t)-REAL_MAX;
    case 7:
        return inf_value(r);
    case 8:
        return nan_value(r);
    case 9:
        return (ladrc_real_t)1e-40;
    case 10:
        return (ladrc_real_t)1e38;
    case 11:
        return (ladrc_real_t)-next_log(r, 1e-6, 1e6);
    case 12:
        return lo;
    case 13:
        return hi;
    case 14:
        return next_down(lo);
    case 15:
        return next_up(hi);
    case 16:
        return (ladrc_real_t)(0.5 * (double)lo);
    default:
        return (ladrc_real_t)(2.0 * (double)hi);
    }
}

/* Share of fields given a hostile or boundary value; the rest are drawn
 * log-uniform over their bounds widened 300x each way (so some fall outside).
 * About 0.4 % of the configs come out valid: some 400 of 10^5, each stepped
 * MIXER_HOSTILE_STEPS times, which sets the test's run time. */
#define P_HOSTILE 0.3
#define WIDEN 300.0

static ladrc_real_t field_value(rng_t *r, ladrc_real_t lo, ladrc_real_t hi)
{
    if (next_unit(r) < P_HOSTILE) {
        return boundary_value(r, lo, hi);
    }
    return (ladrc_real_t)next_log(r, (double)lo / WIDEN, (double)hi * WIDEN);
}

static void random_config(rng_t *r, ladrc_mixer_config_t *c)
{
    const unsigned m = next_below(r, 100u);
    double w2_max;
    c->kL_N_s2 = field_value(r, LADRC_MIXER_KL_MIN_N_S2, LADRC_MIXER_KL_MAX_N_S2);
    c->arm_m = field_value(r, LADRC_MIXER_ARM_MIN_M, LADRC_MIXER_ARM_MAX_M);
    c->b_Nm_s2 = field_value(r, LADRC_MIXER_B_MIN_NM_S2, LADRC_MIXER_B_MAX_NM_S2);
    c->mass_kg = field_value(r, LADRC_MIXER_MASS_MIN_KG, LADRC_MIXER_MASS_MAX_KG);
    c->g_m_s2 = field_value(r, LADRC_MIXER_G_MIN_M_S2, LADRC_MIXER_G_MAX_M_S2);
    c->mode = (m < 70u) ? LADRC_MIXER_SATURATE
                        : ((m < 95u) ? LADRC_MIXER_IDEAL : (ladrc_mixer_mode_t)(2u + next_below(r, 3u)));
    c->w2_max_rad2_s2 = field_value(r, LADRC_MIXER_W2_MAX_MIN_RAD2_S2, LADRC_MIXER_W2_MAX_MAX_RAD2_S2);
    w2_max = (double)c->w2_max_rad2_s2;
    if (next_unit(r) < P_HOSTILE) {
        c->w2_min_rad2_s2 = boundary_value(r, LADRC_R(0.0), c->w2_max_rad2_s2);
    } else {
        switch (next_below(r, 10u)) {
        case 0:
        case 1:
        case 2:
        case 3:
            c->w2_min_rad2_s2 = (ladrc_real_t)0.0;
            break;
        case 4:
        case 5:
        case 6:
        case 7:
            c->w2_min_rad2_s2 = (ladrc_real_t)(w2_max * next_range(r, 0.0, 0.9));
            break;
        case 8:
            c->w2_min_rad2_s2 = (ladrc_real_t)(w2_max * next_range(r, 1.0, 2.0)); /* swapped */
            break;
        default:
            c->w2_min_rad2_s2 = (ladrc_real_t)(-w2_max * next_unit(r));
            break;
        }
    }
    if (next_unit(r) < P_HOSTILE) {
        c->tilt_max_rad = boundary_value(r, (ladrc_real_t)1e-3, (ladrc_real_t)1.5707963);
    } else {
        c->tilt_max_rad = (ladrc_real_t)next_range(r, -0.2, 1.8);
    }
}

static void test_mixer_init_accepts_exactly_the_documented_configs_and_each_runs(void)
{
    const double n_configs = size_from_env("LADRC_MIXER_HOSTILE_CONFIGS", MIXER_HOSTILE_CONFIGS);
    const double n_steps = size_from_env("LADRC_MIXER_HOSTILE_STEPS", MIXER_HOSTILE_STEPS);
    violations_t v;
    unsigned long long tried = 0u;
    unsigned long long accepted[2] = {0u, 0u}; /* saturate, ideal */
    unsigned long long steps = 0u;
    unsigned long long saturated_steps = 0u;
    char msg[300];
    rng_t r;
    double n;
    memset(&v, 0, sizeof v);
    r.state = UINT64_C(77777);
    for (n = 0.0; n < n_configs; n += 1.0) {
        ladrc_mixer_config_t c;
        ladrc_mixer_t mx;
        ladrc_status_t st;
        ladrc_status_t expected;
        context_t x;
        random_config(&r, &c);
        st = ladrc_mixer_init(&mx, &c);
        expected = expected_status(&c);
        ++tried;
        x.where = "init";
        x.cfg = &c;
        x.f = NULL;
        x.out = NULL;
        x.faults = 0u;
        if (st != expected) {
            violate(&v, V_INIT, &x);
        }
        if (st != LADRC_OK) {
            /* a rejected mixer is all zero: rotors off, finite */
            const ladrc_real_t torque_Nm[3] = {(ladrc_real_t)0.1, (ladrc_real_t)0.0, (ladrc_real_t)0.0};
            ladrc_mixer_output_t out;
            int i;
            (void)ladrc_mixer_step(&mx, (ladrc_real_t)10.0, torque_Nm, &out);
            for (i = 0; i < 4; ++i) {
                if (out.w2_rad2_s2[i] != (ladrc_real_t)0.0 || !is_finite_real(out.thrust_N)) {
                    violate(&v, V_FINITE, &x);
                    break;
                }
            }
            continue;
        }
        ++accepted[c.mode == LADRC_MIXER_IDEAL];
        {
            /* nominal flight: thrust from a small tilt, torques of a few percent of
             * m g l (yaw: of m g b / kL), for n_steps steps */
            const double weight = (double)c.mass_kg * (double)c.g_m_s2;
            const double rp_scale = 0.05 * weight * (double)c.arm_m;
            const double yaw_scale = 0.05 * weight * (double)c.b_Nm_s2 / (double)c.kL_N_s2;
            ladrc_mixer_output_t prev = mx.out;
            double k;
            x.where = "nominal flight";
            for (k = 0.0; k < n_steps; k += 1.0) {
                ladrc_real_t f[4];
                ladrc_mixer_output_t out;
                ladrc_fault_t faults;
                f[0] = ladrc_mixer_thrust_from_tilt(&mx, (ladrc_real_t)next_range(&r, -0.4, 0.4),
                                                    (ladrc_real_t)next_range(&r, -0.4, 0.4));
                f[1] = (ladrc_real_t)(rp_scale * next_range(&r, -1.0, 1.0));
                f[2] = (ladrc_real_t)(rp_scale * next_range(&r, -1.0, 1.0));
                f[3] = (ladrc_real_t)(yaw_scale * next_range(&r, -1.0, 1.0));
                faults = ladrc_mixer_step(&mx, f[0], &f[1], &out);
                x.f = f;
                x.out = &out;
                x.faults = faults;
                if (faults != LADRC_FAULT_NONE) {
                    violate(&v, V_FAULTS, &x);
                }
                check_step("nominal flight", &c, f, &prev, &out, faults, &v);
                saturated_steps += (unsigned long long)(out.saturated != 0u);
                prev = out;
                ++steps;
            }
        }
    }
    snprintf(msg, sizeof msg,
             "%llu configs tried, %llu accepted (%llu saturate, %llu ideal), %llu rejected; "
             "%llu nominal steps on the accepted (%.0f each), %llu of them saturated",
             tried, accepted[0] + accepted[1], accepted[0], accepted[1], tried - accepted[0] - accepted[1], steps,
             n_steps, saturated_steps);
    TEST_MESSAGE(msg);
    report_violations(&v, "configs");
    TEST_ASSERT_TRUE_MESSAGE(v.count == 0u, "init or a step broke a promise of mixer.h (see the messages above)");
    /* the draw must exercise both outcomes in both modes (judged at the default sizes) */
    if (n_configs >= 10000.0) {
        TEST_ASSERT_TRUE(accepted[0] > 0u && accepted[1] > 0u && tried > accepted[0] + accepted[1]);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mixer_step_keeps_its_promises_under_hostile_requests);
    RUN_TEST(test_mixer_init_accepts_exactly_the_documented_configs_and_each_runs);
    return UNITY_END();
}
