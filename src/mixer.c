/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file mixer.c
 * @brief Plus-frame allocation (paper eq. 33), priority desaturation and the
 *        forward model that reports what was achieved.
 */
#include "ladrc/mixer.h"
#include "require.h"

#include "compiler.h"

#include <stddef.h>

/* Report tolerance, relative part: 8 eps times coef sum|w_i^2|. Between a request
 * and the forward model of its allocation lie about 9 roundings (of at most eps/2)
 * of values up to coef sum|w_i^2| (the request's product, the parts of each w^2,
 * the forward model's sums and product): at most about 4.5 eps. Measured on the
 * paper's vehicle over 2e6 requests: 2.0 eps in range (thrust), 1.7 eps on an axis
 * the desaturation did not cut back. */
#define REPORT_TOL_REL (LADRC_R(8.0) * LADRC_REAL_EPS)
/* Absolute part: below LADRC_REAL_MIN, results round to multiples of the smallest
 * subnormal (LADRC_REAL_MIN * LADRC_REAL_EPS), which the relative part does not cover;
 * 16 of them cover the same handful of roundings. */
#define REPORT_TOL_ABS (LADRC_R(16.0) * LADRC_REAL_MIN * LADRC_REAL_EPS)

/* Just below pi/2 in both builds (float rounds pi/2 itself upwards). */
#define HALF_PI_BELOW LADRC_R(1.5707963)

/* 1 if the four values are all finite (one comparison, types.h). */
static int all_finite(const ladrc_real_t v[4])
{
    return ladrc_all_finite4(v[0], v[1], v[2], v[3]);
}

/* Out of line (min4, max4): only the limits need them, four times. */
LADRC_NOINLINE static ladrc_real_t min4(const ladrc_real_t v[4])
{
    const ladrc_real_t a = (v[0] < v[1]) ? v[0] : v[1];
    const ladrc_real_t b = (v[2] < v[3]) ? v[2] : v[3];
    return (a < b) ? a : b;
}

LADRC_NOINLINE static ladrc_real_t max4(const ladrc_real_t v[4])
{
    const ladrc_real_t a = (v[0] > v[1]) ? v[0] : v[1];
    const ladrc_real_t b = (v[2] > v[3]) ? v[2] : v[3];
    return (a > b) ? a : b;
}

/* 1 if x is finite and lies in [lo, hi]; lo, hi finite. */
static int within(ladrc_real_t x, ladrc_real_t lo, ladrc_real_t hi)
{
#if LADRC_FINITE_BY_BITS
    /* -ffast-math may turn a failed comparison into its reverse, which a NaN
     * would pass: finiteness first, from the bits. */
    return (ladrc_is_finite(x) && x >= lo && x <= hi) ? 1 : 0;
#else
    return (x >= lo && x <= hi) ? 1 : 0; /* false for NaN */
#endif
}

ladrc_status_t ladrc_mixer_init(ladrc_mixer_t *mx, const ladrc_mixer_config_t *cfg)
{
    const ladrc_mixer_t zero = {0};

    if (mx == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    /* A rejected config leaves an all-zero instance: limits [0, 0], rotors off. */
    *mx = zero;
    {
        /* The physical fields and their bounds (mixer.h), in the order of their
         * status codes (LADRC_ERR_MIXER_KL_N_S2 .. _G_M_S2): one check in a loop. */
        static const ladrc_real_t lo[5] = {LADRC_MIXER_KL_MIN_N_S2, LADRC_MIXER_ARM_MIN_M, LADRC_MIXER_B_MIN_NM_S2,
                                           LADRC_MIXER_MASS_MIN_KG, LADRC_MIXER_G_MIN_M_S2};
        static const ladrc_real_t hi[5] = {LADRC_MIXER_KL_MAX_N_S2, LADRC_MIXER_ARM_MAX_M, LADRC_MIXER_B_MAX_NM_S2,
                                           LADRC_MIXER_MASS_MAX_KG, LADRC_MIXER_G_MAX_M_S2};
        const ladrc_real_t value[5] = {cfg->kL_N_s2, cfg->arm_m, cfg->b_Nm_s2, cfg->mass_kg, cfg->g_m_s2};
        int i;
        for (i = 0; i < 5; ++i) {
            if (!within(value[i], lo[i], hi[i])) {
                return (ladrc_status_t)(LADRC_ERR_MIXER_KL_N_S2 + i);
            }
        }
    }
    if (cfg->mode != LADRC_MIXER_SATURATE && cfg->mode != LADRC_MIXER_IDEAL) {
        return LADRC_ERR_MIXER_MODE;
    }
    if (cfg->mode == LADRC_MIXER_SATURATE) {
        /* Rotor limits: 0 <= w2_min < w2_max, w2_max in its bounds. */
        if (!within(cfg->w2_min_rad2_s2, LADRC_R(0.0), LADRC_REAL_MAX)) {
            return LADRC_ERR_MIXER_W2_MIN;
        }
        if (!within(cfg->w2_max_rad2_s2, LADRC_MIXER_W2_MAX_MIN_RAD2_S2, LADRC_MIXER_W2_MAX_MAX_RAD2_S2) ||
            !(cfg->w2_max_rad2_s2 > cfg->w2_min_rad2_s2)) {
            return LADRC_ERR_MIXER_W2_MAX;
        }
    } else {
        /* Ideal rotors have no limits: the fields only need to be finite and ordered. */
        if (!ladrc_is_finite(cfg->w2_min_rad2_s2)) {
            return LADRC_ERR_MIXER_W2_MIN;
        }
        if (!ladrc_is_finite(cfg->w2_max_rad2_s2) || !(cfg->w2_max_rad2_s2 > cfg->w2_min_rad2_s2)) {
            return LADRC_ERR_MIXER_W2_MAX;
        }
    }
    if (!ladrc_is_positive(cfg->tilt_max_rad) || !(cfg->tilt_max_rad <= HALF_PI_BELOW)) {
        return LADRC_ERR_MIXER_TILT_MAX_RAD;
    }

    mx->kL_N_s2 = cfg->kL_N_s2;
    mx->lkL_Nm_s2 = cfg->arm_m * cfg->kL_N_s2;
    mx->b_Nm_s2 = cfg->b_Nm_s2;
    mx->a4_per_N = LADRC_R(0.25) / cfg->kL_N_s2;
    mx->p2_per_Nm = LADRC_R(0.5) / mx->lkL_Nm_s2;
    mx->r4_per_Nm = LADRC_R(0.25) / cfg->b_Nm_s2;
    mx->weight_N = cfg->mass_kg * cfg->g_m_s2;
    mx->cos_tilt_min = ladrc_cos(cfg->tilt_max_rad);
    mx->thrust_max_N = mx->weight_N / mx->cos_tilt_min;
    mx->mode = cfg->mode;
    mx->thrust_curve = LADRC_R(0.0);
    if (cfg->mode == LADRC_MIXER_IDEAL) {
        /* No limits: every w^2 whose four-term sums cannot overflow is in range. */
        mx->w2_min_rad2_s2 = -LADRC_R(0.25) * LADRC_REAL_MAX;
        mx->w2_max_rad2_s2 = LADRC_R(0.25) * LADRC_REAL_MAX;
    } else {
        const ladrc_real_t range = cfg->w2_max_rad2_s2 - cfg->w2_min_rad2_s2;
        mx->w2_min_rad2_s2 = cfg->w2_min_rad2_s2;
        mx->w2_max_rad2_s2 = cfg->w2_max_rad2_s2;
        mx->rp_limit_Nm = mx->lkL_Nm_s2 * range;
        mx->yaw_limit_Nm = LADRC_R(2.0) * cfg->b_Nm_s2 * range;
        mx->thrust_lo_N = LADRC_R(4.0) * cfg->kL_N_s2 * cfg->w2_min_rad2_s2;
        mx->thrust_hi_N = LADRC_R(4.0) * cfg->kL_N_s2 * cfg->w2_max_rad2_s2;
        mx->command_per_w2 = LADRC_R(1.0) / cfg->w2_max_rad2_s2;
    }
    {
        /* Every derived constant finite and > 0 (thrust_lo_N lies in [0, thrust_hi_N]),
         * each with the status of the last field it depends on. The bounds make these
         * hold; they are checked so that widening a bound cannot let an Inf through. */
        const ladrc_real_t derived[10] = {mx->a4_per_N,     mx->lkL_Nm_s2,    mx->p2_per_Nm,    mx->r4_per_Nm,
                                          mx->weight_N,     mx->cos_tilt_min, mx->thrust_max_N, mx->rp_limit_Nm,
                                          mx->yaw_limit_Nm, mx->thrust_hi_N};
        static const uint8_t status[10] = {LADRC_ERR_MIXER_KL_N_S2,      LADRC_ERR_MIXER_ARM_M,
                                           LADRC_ERR_MIXER_ARM_M,        LADRC_ERR_MIXER_B_NM_S2,
                                           LADRC_ERR_MIXER_G_M_S2,       LADRC_ERR_MIXER_TILT_MAX_RAD,
                                           LADRC_ERR_MIXER_TILT_MAX_RAD, LADRC_ERR_MIXER_W2_MAX,
                                           LADRC_ERR_MIXER_W2_MAX,       LADRC_ERR_MIXER_W2_MAX};
        const int n = (cfg->mode == LADRC_MIXER_IDEAL) ? 7 : 10; /* ideal: no rotor limits */
        int i;
        for (i = 0; i < n; ++i) {
            if (!ladrc_is_positive(derived[i])) {
                *mx = zero;
                return (ladrc_status_t)status[i];
            }
        }
    }
    ladrc_mixer_reset(mx);
    return LADRC_OK;
}

ladrc_real_t ladrc_mixer_thrust_from_tilt(const ladrc_mixer_t *mx, ladrc_real_t roll_rad, ladrc_real_t pitch_rad)
{
    ladrc_real_t c;

    LADRC_REQUIRE(mx != NULL, LADRC_R(0.0));
    c = ladrc_cos(roll_rad) * ladrc_cos(pitch_rad);
#if LADRC_FINITE_BY_BITS
    /* -ffast-math may turn the comparison below into its reverse, which a NaN
     * would pass: the attitude-unknown case goes first there. */
    if (!ladrc_is_finite(c)) {
        return mx->weight_N;
    }
#endif
    if (c > mx->cos_tilt_min) {
        return mx->weight_N / c;
    }
    /* Beyond the tilt limit, inverted flight (c <= 0) included: the capped thrust.
     * NaN (attitude unknown): no tilt compensation. */
#if LADRC_FINITE_BY_BITS
    return mx->thrust_max_N;
#else
    return (c == c) ? mx->thrust_max_N : mx->weight_N;
#endif
}

/* Allocation without argument checks (see ladrc_mixer_allocate); inlined so
 * that the step's common case keeps its w^2 in registers. */
static LADRC_FORCE_INLINE void allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                                        ladrc_real_t w2[4])
{
    const ladrc_real_t a4 = thrust_N * mx->a4_per_N;
    const ladrc_real_t p2 = torque_Nm[0] * mx->p2_per_Nm;
    const ladrc_real_t q2 = torque_Nm[1] * mx->p2_per_Nm;
    const ladrc_real_t r4 = torque_Nm[2] * mx->r4_per_Nm;
    w2[0] = a4 - q2 - r4;
    w2[1] = a4 + p2 + r4;
    w2[2] = a4 + q2 - r4;
    w2[3] = a4 - p2 + r4;
}

void ladrc_mixer_allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                          ladrc_real_t w2_rad2_s2[4])
{
    LADRC_REQUIRE_VOID(mx != NULL && torque_Nm != NULL && w2_rad2_s2 != NULL);
    allocate(mx, thrust_N, torque_Nm, w2_rad2_s2);
}

/* The forward model (mixer.h), the one place it is written; no argument checks:
 * f = {thrust (N), roll, pitch, yaw torque (N m)} of the w^2 in w. */
static LADRC_FORCE_INLINE void forward(const ladrc_mixer_t *mx, const ladrc_real_t w[4], ladrc_real_t f[4])
{
    f[0] = mx->kL_N_s2 * ((w[0] + w[2]) + (w[1] + w[3]));
    f[1] = mx->lkL_Nm_s2 * (w[1] - w[3]);
    f[2] = mx->lkL_Nm_s2 * (w[2] - w[0]);
    f[3] = mx->b_Nm_s2 * ((w[1] + w[3]) - (w[0] + w[2]));
}

void ladrc_mixer_forward(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4], ladrc_real_t *thrust_N,
                         ladrc_real_t torque_Nm[3])
{
    ladrc_real_t f[4];

    LADRC_REQUIRE_VOID(mx != NULL && w2_rad2_s2 != NULL && thrust_N != NULL && torque_Nm != NULL);
    forward(mx, w2_rad2_s2, f);
    *thrust_N = f[0];
    torque_Nm[0] = f[1];
    torque_Nm[1] = f[2];
    torque_Nm[2] = f[3];
}

/* Moves w2 into [w2_min, w2_max] by priority. Rotors 2 and 4 carry +yaw/4, 1 and
 * 3 -yaw/4. w2 must be the allocation of a limited request (limit_request), so
 * that every value here is on the scale of the rotor range. */
static void desaturate(const ladrc_mixer_t *mx, ladrc_real_t w2[4])
{
    const ladrc_real_t lo = mx->w2_min_rad2_s2;
    const ladrc_real_t hi = mx->w2_max_rad2_s2;
    const ladrc_real_t range = hi - lo;
    const ladrc_real_t collective = LADRC_R(0.25) * ((w2[0] + w2[2]) + (w2[1] + w2[3]));
    const ladrc_real_t yaw = LADRC_R(0.25) * ((w2[1] + w2[3]) - (w2[0] + w2[2]));
    const ladrc_real_t dy = LADRC_R(2.0) * ladrc_fabs(yaw); /* yaw spread between the pairs */
    ladrc_real_t rp[4];
    ladrc_real_t spread;
    ladrc_real_t yaw_kept = yaw;
    ladrc_real_t c;
    int i;

    rp[0] = w2[0] - collective + yaw;
    rp[1] = w2[1] - collective - yaw;
    rp[2] = w2[2] - collective + yaw;
    rp[3] = w2[3] - collective - yaw;
    /* 1. Roll and pitch alone must fit the range: scale both alike if not. */
    spread = max4(rp) - min4(rp);
    if (spread > range) {
        const ladrc_real_t k = range / spread;
        for (i = 0; i < 4; ++i) {
            rp[i] *= k;
        }
    }
    /* 2. Largest yaw share k <= 1 with the highest rotor of the pair that yaw raises
     *    and the lowest of the other within the range; at k = 0 all fit after step 1. */
    if (dy > LADRC_R(0.0)) {
        /* The pair yaw raises (2 and 4 for yaw > 0) and the other, each as its
         * first rotor; the second is two on. */
        const ladrc_real_t *raised = (yaw > LADRC_R(0.0)) ? &rp[1] : &rp[0];
        const ladrc_real_t *lowered = (yaw > LADRC_R(0.0)) ? &rp[0] : &rp[1];
        const ladrc_real_t top = (raised[0] > raised[2]) ? raised[0] : raised[2];
        const ladrc_real_t bottom = (lowered[0] < lowered[2]) ? lowered[0] : lowered[2];
        const ladrc_real_t k = (range - (top - bottom)) / dy;
        if (k < LADRC_R(1.0)) {
            yaw_kept = ((k > LADRC_R(0.0)) ? k : LADRC_R(0.0)) * yaw; /* rounding after step 1 */
        }
    }
    rp[0] -= yaw_kept;
    rp[1] += yaw_kept;
    rp[2] -= yaw_kept;
    rp[3] += yaw_kept;
    /* 3. The collective nearest the request that keeps every rotor in range. */
    c = ladrc_clamp(collective, lo - min4(rp), hi - max4(rp));
    for (i = 0; i < 4; ++i) {
        /* In exact arithmetic already within range; the clamp removes rounding. */
        w2[i] = ladrc_clamp(rp[i] + c, lo, hi);
    }
}

/* 1 when every w^2 lies within [w2_min, w2_max]: nothing to limit. NaN fails
 * every comparison, and in ideal mode the bounds are -+LADRC_REAL_MAX/4, so this is
 * also the step's finiteness test of the allocation. */
static LADRC_FORCE_INLINE int in_range(const ladrc_mixer_t *mx, const ladrc_real_t w2[4])
{
    const ladrc_real_t lo = mx->w2_min_rad2_s2;
    const ladrc_real_t hi = mx->w2_max_rad2_s2;
    return (w2[0] >= lo && w2[0] <= hi) && (w2[1] >= lo && w2[1] <= hi) && (w2[2] >= lo && w2[2] <= hi) &&
           (w2[3] >= lo && w2[3] <= hi);
}

/* The request f = {thrust, roll, pitch, yaw} (finite) limited to what the rotors
 * can give at all (mixer.h): roll and pitch scaled together to at most
 * rp_limit_Nm, yaw clamped to yaw_limit_Nm, thrust to [thrust_lo_N, thrust_hi_N].
 * Exact in exact arithmetic for the priorities; in float it keeps every part of
 * the allocation within about the rotor range, whatever the request's size. */
static void limit_request(const ladrc_mixer_t *mx, const ladrc_real_t f[4], ladrc_real_t lim[4])
{
    const ladrc_real_t roll = ladrc_fabs(f[1]);
    const ladrc_real_t pitch = ladrc_fabs(f[2]);
    const ladrc_real_t m = (roll > pitch) ? roll : pitch;
    lim[0] = ladrc_clamp(f[0], mx->thrust_lo_N, mx->thrust_hi_N);
    lim[1] = f[1];
    lim[2] = f[2];
    if (m > mx->rp_limit_Nm) {
        /* f/m first: in [-1, 1] (the larger exactly +-1), no overflow or underflow
         * of a tiny factor limit/m. */
        lim[1] = (f[1] / m) * mx->rp_limit_Nm;
        lim[2] = (f[2] / m) * mx->rp_limit_Nm;
    }
    lim[3] = ladrc_clamp(f[3], -mx->yaw_limit_Nm, mx->yaw_limit_Nm);
}

/* Writes rotor i of a good mix: w^2 and w = sqrt(max(w^2, 0)). */
static LADRC_FORCE_INLINE void put_rotor(ladrc_mixer_output_t *out, int i, ladrc_real_t w2)
{
    out->w2_rad2_s2[i] = w2;
    out->w_rad_s[i] = (w2 > LADRC_R(0.0)) ? ladrc_sqrt(w2) : LADRC_R(0.0);
}

/* One axis of the report: the request where the rotors give it within tol, with
 * no bit; the rotors' value (got) and the axis' bit otherwise. */
static LADRC_FORCE_INLINE uint8_t report(ladrc_real_t got, ladrc_real_t requested, ladrc_real_t tol, uint8_t bit,
                                         ladrc_real_t *achieved)
{
    if (ladrc_fabs(got - requested) <= tol) {
        *achieved = requested;
        return 0u;
    }
    *achieved = got;
    return bit;
}

/* Writes the mix w2 (finite, in range) of the request f = {thrust, roll, pitch,
 * yaw} to out: the rotors; per axis the forward model of w2, or the request itself
 * where the two agree within the report tolerance (mixer.h); a saturation bit for
 * every axis where they do not. In range, w^2 and the coefficients are bounded
 * (init), so the forward model and the tolerance are finite. */
static LADRC_FORCE_INLINE void commit(const ladrc_mixer_t *mx, const ladrc_real_t w2[4], const ladrc_real_t f[4],
                                      ladrc_mixer_output_t *out)
{
    /* Everything read from mx before out (which may be mx->out) is written. */
    const ladrc_real_t scale =
        REPORT_TOL_REL * ((ladrc_fabs(w2[0]) + ladrc_fabs(w2[2])) + (ladrc_fabs(w2[1]) + ladrc_fabs(w2[3])));
    const ladrc_real_t tol_kL = scale * mx->kL_N_s2 + REPORT_TOL_ABS;
    const ladrc_real_t tol_lkL = scale * mx->lkL_Nm_s2 + REPORT_TOL_ABS;
    const ladrc_real_t tol_b = scale * mx->b_Nm_s2 + REPORT_TOL_ABS;
    ladrc_real_t got[4];
    unsigned saturated;

    forward(mx, w2, got);
    put_rotor(out, 0, w2[0]);
    put_rotor(out, 1, w2[1]);
    put_rotor(out, 2, w2[2]);
    put_rotor(out, 3, w2[3]);
    saturated = report(got[0], f[0], tol_kL, LADRC_MIXER_SAT_THRUST, &out->thrust_N);
    saturated |= report(got[1], f[1], tol_lkL, LADRC_MIXER_SAT_ROLL, &out->torque_Nm[0]);
    saturated |= report(got[2], f[2], tol_lkL, LADRC_MIXER_SAT_PITCH, &out->torque_Nm[1]);
    saturated |= report(got[3], f[3], tol_b, LADRC_MIXER_SAT_YAW, &out->torque_Nm[2]);
    out->saturated = (uint8_t)saturated;
    out->faults = LADRC_FAULT_NONE;
}

/* commit() out of line, for the paths that limit (flash: one more copy only). */
LADRC_NOINLINE static void commit_cold(const ladrc_mixer_t *mx, const ladrc_real_t w2[4], const ladrc_real_t f[4],
                                       ladrc_mixer_output_t *out)
{
    commit(mx, w2, f, out);
}

/* The mix of a request f = {thrust, roll, pitch, yaw} whose allocation is out of
 * range or not finite: refused if f is not finite (every input reaches some w^2
 * with a non-zero factor, so a non-finite input always ends here), and in ideal
 * mode (an allocation beyond -+LADRC_REAL_MAX/4: nothing to cut back to); otherwise the
 * limited request is allocated, desaturated and written to out. Out of line: the
 * step's common case (in range) does not come here. */
LADRC_NOINLINE static ladrc_fault_t mix(const ladrc_mixer_t *mx, const ladrc_real_t f[4], ladrc_mixer_output_t *out)
{
    ladrc_real_t lim[4];
    ladrc_real_t w2[4];

    if (!all_finite(f)) {
        return LADRC_FAULT_INPUT;
    }
    if (mx->mode == LADRC_MIXER_IDEAL) {
        return LADRC_FAULT_STATE;
    }
    limit_request(mx, f, lim);
    allocate(mx, lim[0], &lim[1], w2);
    desaturate(mx, w2);
    commit_cold(mx, w2, f, out);
    return LADRC_FAULT_NONE;
}

void ladrc_mixer_saturate(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4], ladrc_real_t thrust_N,
                          const ladrc_real_t torque_Nm[3], ladrc_mixer_output_t *out)
{
    ladrc_real_t w2[4];
    ladrc_real_t f[4];
    int i;

    LADRC_REQUIRE_VOID(mx != NULL && w2_rad2_s2 != NULL && torque_Nm != NULL && out != NULL);
    f[0] = thrust_N;
    f[1] = torque_Nm[0];
    f[2] = torque_Nm[1];
    f[3] = torque_Nm[2];
    for (i = 0; i < 4; ++i) {
        w2[i] = w2_rad2_s2[i];
    }
    if (!all_finite(w2)) {
        return;
    }
    if (in_range(mx, w2)) {
        commit_cold(mx, w2, f, out);
    } else {
        (void)mix(mx, f, out);
    }
}

void ladrc_mixer_reset(ladrc_mixer_t *mx)
{
    static const ladrc_real_t no_torque[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};

    LADRC_REQUIRE_VOID(mx != NULL);
    (void)ladrc_mixer_step(mx, mx->weight_N, no_torque, NULL);
    mx->out.faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_mixer_step(ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                               ladrc_mixer_output_t *out)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;

    LADRC_REQUIRE(mx != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    /* The request: thrust, roll, pitch, yaw. Scalars and local arrays of
     * constant index, so that the common case below stays in registers. */
    const ladrc_real_t f[4] = {thrust_N, torque_Nm[0], torque_Nm[1], torque_Nm[2]};
    ladrc_real_t w2[4];
    allocate(mx, thrust_N, &f[1], w2);
    /* in_range() is false for NaN, so also the finiteness test. */
    if (in_range(mx, w2)) {
        /* The common case: nothing to limit. */
        commit(mx, w2, f, &mx->out);
    } else {
        faults = mix(mx, f, &mx->out);
    }
    mx->out.faults = faults;
    if (out != NULL) {
        *out = mx->out;
    }
    return faults;
}

ladrc_status_t ladrc_mixer_set_thrust_curve(ladrc_mixer_t *mx, ladrc_real_t k)
{
    if (mx == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!within(k, LADRC_R(0.0), LADRC_R(1.0))) {
        return LADRC_ERR_MIXER_THRUST_CURVE;
    }
    mx->thrust_curve = k;
    return LADRC_OK;
}

ladrc_real_t ladrc_mixer_command(const ladrc_mixer_t *mx, ladrc_real_t w2_rad2_s2)
{
    LADRC_REQUIRE(mx != NULL, LADRC_R(0.0));
    if (mx->mode != LADRC_MIXER_SATURATE || !ladrc_is_finite(w2_rad2_s2)) {
        return LADRC_R(0.0);
    }
    const ladrc_real_t f = ladrc_clamp(w2_rad2_s2 * mx->command_per_w2, LADRC_R(0.0), LADRC_R(1.0));
    const ladrc_real_t k = mx->thrust_curve;
    const ladrc_real_t lin = LADRC_R(1.0) - k;
    const ladrc_real_t den = lin + ladrc_sqrt(lin * lin + LADRC_R(4.0) * k * f);
    /* den > 0 unless k = 1 and f = 0, where the command is 0 */
    return (den > LADRC_R(0.0)) ? ladrc_clamp(LADRC_R(2.0) * f / den, LADRC_R(0.0), LADRC_R(1.0)) : LADRC_R(0.0);
}

ladrc_fault_t ladrc_mixer_get_faults(const ladrc_mixer_t *mx)
{
    LADRC_REQUIRE(mx != NULL, LADRC_FAULT_STATE);
    return mx->out.faults;
}
