/**
 * @file mixer.c
 * @brief Plus-frame allocation (paper eq. 33), priority desaturation and the
 *        forward model that reports what was achieved.
 */
#include "ladrc/mixer.h"

#include <stddef.h>

/* Sign of each rotor's share of the yaw torque (drag direction). */
static const ladrc_real_t yaw_sign[4] = {LADRC_R(-1.0), LADRC_R(1.0), LADRC_R(-1.0), LADRC_R(1.0)};

/* Just below pi/2 in both builds (float rounds pi/2 itself upwards). */
#define HALF_PI_BELOW LADRC_R(1.5707963)

static int all_finite(const ladrc_real_t *v, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        if (!ladrc_is_finite(v[i])) {
            return 0;
        }
    }
    return 1;
}

static ladrc_real_t min4(const ladrc_real_t v[4])
{
    const ladrc_real_t a = (v[0] < v[1]) ? v[0] : v[1];
    const ladrc_real_t b = (v[2] < v[3]) ? v[2] : v[3];
    return (a < b) ? a : b;
}

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
    if (!ladrc_is_positive(cfg->kL_N_s2)) {
        return LADRC_ERR_MIXER_KL_N_S2;
    }
    if (!ladrc_is_positive(cfg->arm_m)) {
        return LADRC_ERR_MIXER_ARM_M;
    }
    if (!ladrc_is_positive(cfg->b_Nm_s2)) {
        return LADRC_ERR_MIXER_B_NM_S2;
    }
    if (!ladrc_is_positive(cfg->mass_kg)) {
        return LADRC_ERR_MIXER_MASS_KG;
    }
    if (!ladrc_is_positive(cfg->g_m_s2)) {
        return LADRC_ERR_MIXER_G_M_S2;
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
    mx->w2_min_rad2_s2 = cfg->w2_min_rad2_s2;
    mx->w2_max_rad2_s2 = cfg->w2_max_rad2_s2;
    mx->mode = cfg->mode;
    ladrc_mixer_reset(mx);
    return LADRC_OK;
}

void ladrc_mixer_reset(ladrc_mixer_t *mx)
{
    static const ladrc_real_t no_torque[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    ladrc_real_t w2[4];

    LADRC_ASSERT(mx != NULL);
    if (mx == NULL) {
        return;
    }
    ladrc_mixer_allocate(mx, mx->weight_N, no_torque, w2);
    ladrc_mixer_saturate(mx, w2, mx->weight_N, no_torque, &mx->out);
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
    if (!ladrc_is_finite(c)) {
        return mx->weight_N; /* attitude unknown: no tilt compensation */
    }
    /* The floor also catches inverted flight, where the product is <= 0. */
    return mx->weight_N / ((c > mx->cos_tilt_min) ? c : mx->cos_tilt_min);
}

void ladrc_mixer_allocate(const ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                          const ladrc_real_t torque_Nm[3], ladrc_real_t w2_rad2_s2[4])
{
    LADRC_ASSERT(mx != NULL && torque_Nm != NULL && w2_rad2_s2 != NULL);
    if (mx == NULL || torque_Nm == NULL || w2_rad2_s2 == NULL) {
        return;
    }
    {
        const ladrc_real_t a4 = thrust_N * mx->a4_per_N;
        const ladrc_real_t p2 = torque_Nm[0] * mx->p2_per_Nm;
        const ladrc_real_t q2 = torque_Nm[1] * mx->p2_per_Nm;
        const ladrc_real_t r4 = torque_Nm[2] * mx->r4_per_Nm;
        w2_rad2_s2[0] = a4 - q2 - r4;
        w2_rad2_s2[1] = a4 + p2 + r4;
        w2_rad2_s2[2] = a4 + q2 - r4;
        w2_rad2_s2[3] = a4 - p2 + r4;
    }
}

void ladrc_mixer_forward(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                         ladrc_real_t *thrust_N, ladrc_real_t torque_Nm[3])
{
    const ladrc_real_t *w = w2_rad2_s2;

    LADRC_ASSERT(mx != NULL && w2_rad2_s2 != NULL && thrust_N != NULL && torque_Nm != NULL);
    if (mx == NULL || w2_rad2_s2 == NULL || thrust_N == NULL || torque_Nm == NULL) {
        return;
    }
    *thrust_N = mx->kL_N_s2 * ((w[0] + w[2]) + (w[1] + w[3]));
    torque_Nm[0] = mx->lkL_Nm_s2 * (w[1] - w[3]);
    torque_Nm[1] = mx->lkL_Nm_s2 * (w[2] - w[0]);
    torque_Nm[2] = mx->b_Nm_s2 * ((w[1] + w[3]) - (w[0] + w[2]));
}

/* Moves w2 into [w2_min, w2_max] by priority; returns the LADRC_MIXER_SAT_*
 * bits of the axes it had to change. */
static uint8_t desaturate(const ladrc_mixer_t *mx, ladrc_real_t w2[4])
{
    const ladrc_real_t lo = mx->w2_min_rad2_s2;
    const ladrc_real_t hi = mx->w2_max_rad2_s2;
    const ladrc_real_t range = hi - lo;
    const ladrc_real_t collective = LADRC_R(0.25) * ((w2[0] + w2[2]) + (w2[1] + w2[3]));
    const ladrc_real_t yaw = LADRC_R(0.25) * ((w2[1] + w2[3]) - (w2[0] + w2[2]));
    ladrc_real_t rp[4];
    ladrc_real_t spread;
    ladrc_real_t k_yaw = LADRC_R(1.0);
    ladrc_real_t c;
    uint8_t changed = 0u;
    int i;
    int j;

    for (i = 0; i < 4; ++i) {
        rp[i] = w2[i] - collective - yaw_sign[i] * yaw;
    }
    /* 1. Roll and pitch alone must fit the range: scale both alike if not. */
    spread = max4(rp) - min4(rp);
    if (spread > range) {
        const ladrc_real_t k = range / spread;
        for (i = 0; i < 4; ++i) {
            rp[i] *= k;
        }
        changed = (uint8_t)(LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH); /* first cut */
    }
    /* 2. Largest yaw share k with every pairwise difference of rp + k yaw
     *    within the range; at k = 0 all fit after step 1. */
    for (i = 0; i < 4; ++i) {
        for (j = 0; j < 4; ++j) {
            const ladrc_real_t dy = (yaw_sign[i] - yaw_sign[j]) * yaw;
            if (dy > LADRC_R(0.0)) {
                const ladrc_real_t k = (range - (rp[i] - rp[j])) / dy;
                k_yaw = (k < k_yaw) ? k : k_yaw;
            }
        }
    }
    if (k_yaw < LADRC_R(1.0)) {
        k_yaw = (k_yaw > LADRC_R(0.0)) ? k_yaw : LADRC_R(0.0); /* rounding after step 1 */
        changed = (uint8_t)(changed | LADRC_MIXER_SAT_YAW);
    }
    for (i = 0; i < 4; ++i) {
        rp[i] += yaw_sign[i] * (k_yaw * yaw);
    }
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

/* Achieved value of one axis: its request unless the axis was cut back. */
static ladrc_real_t achieved(ladrc_real_t requested, ladrc_real_t mixed, uint8_t changed,
                             unsigned bit, uint8_t *saturated)
{
    if ((changed & bit) == 0u || mixed == requested) {
        return requested;
    }
    *saturated = (uint8_t)(*saturated | bit);
    return mixed;
}

void ladrc_mixer_saturate(const ladrc_mixer_t *mx, const ladrc_real_t w2_rad2_s2[4],
                          ladrc_real_t thrust_N, const ladrc_real_t torque_Nm[3],
                          ladrc_mixer_output_t *out)
{
    static const unsigned axis_bit[3] = {LADRC_MIXER_SAT_ROLL, LADRC_MIXER_SAT_PITCH,
                                         LADRC_MIXER_SAT_YAW};
    ladrc_real_t thrust_mixed_N;
    ladrc_real_t torque_mixed_Nm[3];
    uint8_t changed = 0u;
    int i;

    LADRC_ASSERT(mx != NULL && w2_rad2_s2 != NULL && torque_Nm != NULL && out != NULL);
    if (mx == NULL || w2_rad2_s2 == NULL || torque_Nm == NULL || out == NULL) {
        return;
    }
    for (i = 0; i < 4; ++i) {
        out->w2_rad2_s2[i] = w2_rad2_s2[i];
    }
    /* Nothing to do when every rotor is already in range. */
    if (mx->mode == LADRC_MIXER_SATURATE &&
        (min4(w2_rad2_s2) < mx->w2_min_rad2_s2 || max4(w2_rad2_s2) > mx->w2_max_rad2_s2)) {
        changed = desaturate(mx, out->w2_rad2_s2);
    }
    ladrc_mixer_forward(mx, out->w2_rad2_s2, &thrust_mixed_N, torque_mixed_Nm);
    out->saturated = 0u;
    out->thrust_N =
        achieved(thrust_N, thrust_mixed_N, changed, LADRC_MIXER_SAT_THRUST, &out->saturated);
    for (i = 0; i < 3; ++i) {
        out->torque_Nm[i] =
            achieved(torque_Nm[i], torque_mixed_Nm[i], changed, axis_bit[i], &out->saturated);
    }
    for (i = 0; i < 4; ++i) {
        const ladrc_real_t w2 = out->w2_rad2_s2[i];
        out->w_rad_s[i] = (w2 > LADRC_R(0.0)) ? ladrc_sqrt(w2) : LADRC_R(0.0);
    }
    out->faults = LADRC_FAULT_NONE;
}

ladrc_fault_t ladrc_mixer_step(ladrc_mixer_t *mx, ladrc_real_t thrust_N,
                               const ladrc_real_t torque_Nm[3], ladrc_mixer_output_t *out)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;

    LADRC_ASSERT(mx != NULL && torque_Nm != NULL);
    if (mx == NULL) {
        return LADRC_FAULT_NONE;
    }
    if (torque_Nm == NULL || !ladrc_is_finite(thrust_N) || !all_finite(torque_Nm, 3)) {
        faults = LADRC_FAULT_INPUT;
    } else {
        ladrc_real_t w2[4];
        ladrc_mixer_output_t next;
        ladrc_mixer_allocate(mx, thrust_N, torque_Nm, w2);
        /* Huge finite requests can overflow the allocation or the forward model. */
        if (!all_finite(w2, 4)) {
            faults = LADRC_FAULT_STATE;
        } else {
            ladrc_mixer_saturate(mx, w2, thrust_N, torque_Nm, &next);
            if (!all_finite(next.w2_rad2_s2, 4) || !all_finite(&next.thrust_N, 1) ||
                !all_finite(next.torque_Nm, 3)) {
                faults = LADRC_FAULT_STATE;
            } else {
                mx->out = next;
            }
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
