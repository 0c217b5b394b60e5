/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file mixer.c
 * @brief Plus-frame allocation (paper eq. 33), priority desaturation and the
 *        forward model that reports what was achieved.
 */
#include "ladrc/mixer.h"

#include <float.h>
#include <stddef.h>

#ifdef LADRC_REAL_DOUBLE
#define REAL_MAX DBL_MAX
#else
#define REAL_MAX FLT_MAX
#endif

/* Just below pi/2 in both builds (float rounds pi/2 itself upwards). */
#define HALF_PI_BELOW LADRC_R(1.5707963)

/* 1 if the four values are all finite (one comparison, types.h). */
static int all_finite(const ladrc_real_t v[4])
{
    return ladrc_all_finite4(v[0], v[1], v[2], v[3]);
}

/* Out of line (min4, max4): only the limits need them, four times. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static ladrc_real_t min4(const ladrc_real_t v[4])
{
    const ladrc_real_t a = (v[0] < v[1]) ? v[0] : v[1];
    const ladrc_real_t b = (v[2] < v[3]) ? v[2] : v[3];
    return (a < b) ? a : b;
}

#if defined(__GNUC__)
__attribute__((noinline))
#endif
static ladrc_real_t max4(const ladrc_real_t v[4])
{
    const ladrc_real_t a = (v[0] > v[1]) ? v[0] : v[1];
    const ladrc_real_t b = (v[2] > v[3]) ? v[2] : v[3];
    return (a > b) ? a : b;
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
        /* The fields that must be finite and > 0, in the order of their status
         * codes (LADRC_ERR_MIXER_KL_N_S2 .. _G_M_S2): one check in a loop. */
        const ladrc_real_t positive[5] = {cfg->kL_N_s2, cfg->arm_m, cfg->b_Nm_s2, cfg->mass_kg,
                                          cfg->g_m_s2};
        int i;
        for (i = 0; i < 5; ++i) {
            if (!ladrc_is_positive(positive[i])) {
                return (ladrc_status_t)(LADRC_ERR_MIXER_KL_N_S2 + i);
            }
        }
    }
    if (cfg->mode != LADRC_MIXER_SATURATE && cfg->mode != LADRC_MIXER_IDEAL) {
        return LADRC_ERR_MIXER_MODE;
    }
    if (!ladrc_is_finite(cfg->w2_min_rad2_s2) ||
        (cfg->mode == LADRC_MIXER_SATURATE && cfg->w2_min_rad2_s2 < LADRC_R(0.0))) {
        return LADRC_ERR_MIXER_W2_MIN;
    }
    if (!ladrc_is_finite(cfg->w2_max_rad2_s2) || !(cfg->w2_max_rad2_s2 > cfg->w2_min_rad2_s2)) {
        return LADRC_ERR_MIXER_W2_MAX;
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
    mx->w2_min_rad2_s2 = cfg->w2_min_rad2_s2;
    mx->w2_max_rad2_s2 = cfg->w2_max_rad2_s2;
    if (cfg->mode == LADRC_MIXER_IDEAL) {
        /* No limits: every finite w^2 is in range. */
        mx->w2_min_rad2_s2 = -REAL_MAX;
        mx->w2_max_rad2_s2 = REAL_MAX;
    }
    mx->mode = cfg->mode;
    ladrc_mixer_reset(mx);
    return LADRC_OK;
}

ladrc_real_t ladrc_mixer_thrust_from_tilt(const ladrc_mixer_t *mx, ladrc_real_t roll_rad,
                                          ladrc_real_t pitch_rad)
{
    ladrc_real_t c;

    LADRC_ASSERT(mx != NULL);
    if (mx == NULL) {
        return LADRC_R(0.0);
    }
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

/* Allocation without argument checks (see ladrc_mixer_allocate). */
static void allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
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

void ladrc_mixer_allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                          const ladrc_real_t torque_Nm[3], ladrc_real_t w2_rad2_s2[4])
{
    LADRC_ASSERT(mx != NULL && torque_Nm != NULL && w2_rad2_s2 != NULL);
    if (mx != NULL && torque_Nm != NULL && w2_rad2_s2 != NULL) {
        allocate(mx, thrust_N, torque_Nm, w2_rad2_s2);
    }
}

/* Forward model without argument checks: f = {thrust (N), roll, pitch, yaw torque (N m)}. */
static void forward(const ladrc_mixer_t *mx, const ladrc_real_t w[4], ladrc_real_t f[4])
{
    f[0] = mx->kL_N_s2 * ((w[0] + w[2]) + (w[1] + w[3]));
    f[1] = mx->lkL_Nm_s2 * (w[1] - w[3]);
    f[2] = mx->lkL_Nm_s2 * (w[2] - w[0]);
    f[3] = mx->b_Nm_s2 * ((w[1] + w[3]) - (w[0] + w[2]));
}

void ladrc_mixer_forward(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                         ladrc_real_t *thrust_N, ladrc_real_t torque_Nm[3])
{
    ladrc_real_t f[4];

    LADRC_ASSERT(mx != NULL && w2_rad2_s2 != NULL && thrust_N != NULL && torque_Nm != NULL);
    if (mx == NULL || w2_rad2_s2 == NULL || thrust_N == NULL || torque_Nm == NULL) {
        return;
    }
    forward(mx, w2_rad2_s2, f);
    *thrust_N = f[0];
    torque_Nm[0] = f[1];
    torque_Nm[1] = f[2];
    torque_Nm[2] = f[3];
}

/* 1 when every w^2 lies within [w2_min, w2_max]: nothing to limit. NaN fails
 * every comparison, and in ideal mode the bounds are +-REAL_MAX, so this is
 * also the step's finiteness test of the allocation. */
static int in_range(const ladrc_mixer_t *mx, const ladrc_real_t w2[4])
{
    const ladrc_real_t lo = mx->w2_min_rad2_s2;
    const ladrc_real_t hi = mx->w2_max_rad2_s2;
    return (w2[0] >= lo && w2[0] <= hi) && (w2[1] >= lo && w2[1] <= hi) &&
           (w2[2] >= lo && w2[2] <= hi) && (w2[3] >= lo && w2[3] <= hi);
}

/* Moves w2 into [w2_min, w2_max] by priority; returns the LADRC_MIXER_SAT_*
 * bits of the axes it had to change. Rotors 2 and 4 carry +yaw/4, 1 and 3 -yaw/4. */
static uint8_t desaturate(const ladrc_mixer_t *mx, ladrc_real_t w2[4])
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
    uint8_t changed = 0u;
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
        changed = (uint8_t)(LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH); /* first cut */
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
            changed = (uint8_t)(changed | LADRC_MIXER_SAT_YAW);
        }
    }
    rp[0] -= yaw_kept;
    rp[1] += yaw_kept;
    rp[2] -= yaw_kept;
    rp[3] += yaw_kept;
    /* 3. The collective nearest the request that keeps every rotor in range. */
    c = ladrc_clamp(collective, lo - min4(rp), hi - max4(rp));
    if (c != collective) {
        changed = (uint8_t)(changed | LADRC_MIXER_SAT_THRUST);
    }
    for (i = 0; i < 4; ++i) {
        /* In exact arithmetic already within range; the clamp removes rounding. */
        w2[i] = ladrc_clamp(rp[i] + c, lo, hi);
    }
    return changed;
}

/* Desaturates w2 and turns f (thrust, roll, pitch, yaw: the request on entry)
 * into the achieved values: the forward model of w2 on an axis that was cut
 * back, the request itself on the others. Returns the LADRC_MIXER_SAT_* bits. */
static uint8_t limit(const ladrc_mixer_t *mx, ladrc_real_t w2[4], ladrc_real_t f[4])
{
    static const uint8_t bit[4] = {LADRC_MIXER_SAT_THRUST, LADRC_MIXER_SAT_ROLL,
                                   LADRC_MIXER_SAT_PITCH, LADRC_MIXER_SAT_YAW};
    const uint8_t changed = desaturate(mx, w2);
    ladrc_real_t mixed[4];
    uint8_t saturated = 0u;
    int i;

    forward(mx, w2, mixed);
    for (i = 0; i < 4; ++i) {
        if ((changed & bit[i]) != 0u && mixed[i] != f[i]) {
            f[i] = mixed[i];
            saturated = (uint8_t)(saturated | bit[i]);
        }
    }
    return saturated;
}

/* Writes rotor i of a good mix: w^2 and w = sqrt(max(w^2, 0)). Inlined: a
 * call would cost the step as much as the work. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline void put_rotor(ladrc_mixer_output_t *out, int i, ladrc_real_t w2)
{
    out->w2_rad2_s2[i] = w2;
    out->w_rad_s[i] = (w2 > LADRC_R(0.0)) ? ladrc_sqrt(w2) : LADRC_R(0.0);
}

/* Writes one good mix to out: rotors, achieved f = {thrust, roll, pitch, yaw}, bits. */
static void commit(ladrc_mixer_output_t *out, const ladrc_real_t w2[4], const ladrc_real_t f[4],
                   uint8_t saturated)
{
    int i;
    for (i = 0; i < 4; ++i) {
        put_rotor(out, i, w2[i]);
    }
    out->thrust_N = f[0];
    out->torque_Nm[0] = f[1];
    out->torque_Nm[1] = f[2];
    out->torque_Nm[2] = f[3];
    out->saturated = saturated;
    out->faults = LADRC_FAULT_NONE;
}

/* The mix of a request f = {thrust, roll, pitch, yaw} from its allocation w2:
 * refused if w2 is not finite (every input reaches some w^2 with a non-zero
 * factor, so a non-finite input always ends here), limited if out of range,
 * written to out unless the limits overflowed; f becomes what was achieved.
 * Out of line: the step's common case (in range) does not come here. */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static ladrc_fault_t mix(const ladrc_mixer_t *mx, ladrc_real_t w2[4], ladrc_real_t f[4],
                         ladrc_mixer_output_t *out)
{
    uint8_t saturated = 0u;

    if (!all_finite(w2)) {
        return all_finite(f) ? LADRC_FAULT_STATE : LADRC_FAULT_INPUT;
    }
    if (!in_range(mx, w2)) {
        saturated = limit(mx, w2, f);
        if (!(all_finite(w2) && all_finite(f))) {
            return LADRC_FAULT_STATE;
        }
    }
    commit(out, w2, f, saturated);
    return LADRC_FAULT_NONE;
}

void ladrc_mixer_saturate(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                          ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                          ladrc_mixer_output_t *out)
{
    ladrc_real_t w2[4];
    ladrc_real_t f[4];
    int i;

    LADRC_ASSERT(mx != NULL && w2_rad2_s2 != NULL && torque_Nm != NULL && out != NULL);
    if (mx == NULL || w2_rad2_s2 == NULL || torque_Nm == NULL || out == NULL) {
        return;
    }
    f[0] = thrust_N;
    f[1] = torque_Nm[0];
    f[2] = torque_Nm[1];
    f[3] = torque_Nm[2];
    for (i = 0; i < 4; ++i) {
        w2[i] = w2_rad2_s2[i];
    }
    (void)mix(mx, w2, f, out);
}

void ladrc_mixer_reset(ladrc_mixer_t *mx)
{
    static const ladrc_real_t no_torque[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};

    LADRC_ASSERT(mx != NULL);
    if (mx == NULL) {
        return;
    }
    (void)ladrc_mixer_step(mx, mx->weight_N, no_torque, NULL);
    mx->out.faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_mixer_step(ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                               const ladrc_real_t torque_Nm[3], ladrc_mixer_output_t *out)
{
    ladrc_fault_t faults = LADRC_FAULT_INPUT;

    LADRC_ASSERT(mx != NULL && torque_Nm != NULL);
    if (mx == NULL) {
        return LADRC_FAULT_NONE;
    }
    if (torque_Nm != NULL) {
        /* The request, then what was achieved of it: thrust, roll, pitch, yaw.
         * Scalars, so that the common case below stays in registers. */
        const ladrc_real_t roll = torque_Nm[0];
        const ladrc_real_t pitch = torque_Nm[1];
        const ladrc_real_t yaw = torque_Nm[2];
        const ladrc_real_t a4 = thrust_N * mx->a4_per_N;
        const ladrc_real_t p2 = roll * mx->p2_per_Nm;
        const ladrc_real_t q2 = pitch * mx->p2_per_Nm;
        const ladrc_real_t r4 = yaw * mx->r4_per_Nm;
        const ladrc_real_t w0 = a4 - q2 - r4; /* allocate()'s expressions, bit for bit */
        const ladrc_real_t w1 = a4 + p2 + r4;
        const ladrc_real_t w2 = a4 + q2 - r4;
        const ladrc_real_t w3 = a4 - p2 + r4;
        const ladrc_real_t lo = mx->w2_min_rad2_s2;
        const ladrc_real_t hi = mx->w2_max_rad2_s2;
        /* As in_range(): false for NaN, so also the finiteness test. */
        if ((w0 >= lo && w0 <= hi) && (w1 >= lo && w1 <= hi) && (w2 >= lo && w2 <= hi) &&
            (w3 >= lo && w3 <= hi)) {
            /* The common case: nothing to limit, the request achieved as it is. */
            put_rotor(&mx->out, 0, w0);
            put_rotor(&mx->out, 1, w1);
            put_rotor(&mx->out, 2, w2);
            put_rotor(&mx->out, 3, w3);
            mx->out.thrust_N = thrust_N;
            mx->out.torque_Nm[0] = roll;
            mx->out.torque_Nm[1] = pitch;
            mx->out.torque_Nm[2] = yaw;
            mx->out.saturated = 0u;
            faults = LADRC_FAULT_NONE;
        } else {
            ladrc_real_t w[4];
            ladrc_real_t f[4];
            w[0] = w0;
            w[1] = w1;
            w[2] = w2;
            w[3] = w3;
            f[0] = thrust_N;
            f[1] = roll;
            f[2] = pitch;
            f[3] = yaw;
            faults = mix(mx, w, f, &mx->out);
        }
    }
    mx->out.faults = faults;
    if (out != NULL) {
        *out = mx->out;
    }
    return faults;
}

ladrc_fault_t ladrc_mixer_get_faults(const ladrc_mixer_t *mx)
{
    LADRC_ASSERT(mx != NULL);
    return (mx != NULL) ? mx->out.faults : (ladrc_fault_t)LADRC_FAULT_NONE;
}
