/* SPDX-License-Identifier: BSD-3-Clause */
/* Unit quaternions: rotation vector and attitude error with tilt priority (see quat.h). */
#include "ladrc/quat.h"
#include "require.h"

/* Below this |v|^2 the rotation vector comes from the series of asin(s) / s:
 * its first term left out, 63 u^5 / 2816, is then under the type's rounding. */
#ifdef LADRC_REAL_DOUBLE
#define QUAT_SERIES_MAX_U LADRC_R(1e-4)
#else
#define QUAT_SERIES_MAX_U LADRC_R(1e-2)
#endif
/* |v| above which the angle comes from w (asin is ill-conditioned near 1). */
#define QUAT_ASIN_SWITCH LADRC_R(0.70710678118654752)
/* |q|^2 below which a quaternion is no attitude. */
#define QUAT_NORM2_MIN LADRC_R(1e-6)
/* w^2 + z^2 of the error below which it is a pure tilt (no twist defined). */
#define QUAT_TWIST_MIN LADRC_R(1e-12)

ladrc_quat_t ladrc_quat_from_euler(ladrc_real_t roll_rad, ladrc_real_t pitch_rad, ladrc_real_t yaw_rad)
{
    const ladrc_real_t cr = ladrc_cos(LADRC_R(0.5) * roll_rad), sr = ladrc_sin(LADRC_R(0.5) * roll_rad);
    const ladrc_real_t cp = ladrc_cos(LADRC_R(0.5) * pitch_rad), sp = ladrc_sin(LADRC_R(0.5) * pitch_rad);
    const ladrc_real_t cy = ladrc_cos(LADRC_R(0.5) * yaw_rad), sy = ladrc_sin(LADRC_R(0.5) * yaw_rad);
    const ladrc_quat_t qz = {cy, LADRC_R(0.0), LADRC_R(0.0), sy};
    const ladrc_quat_t qy = {cp, LADRC_R(0.0), sp, LADRC_R(0.0)};
    const ladrc_quat_t qx = {cr, sr, LADRC_R(0.0), LADRC_R(0.0)};
    return ladrc_quat_mul(qz, ladrc_quat_mul(qy, qx));
}

int ladrc_quat_normalise(ladrc_quat_t q, ladrc_quat_t *unit)
{
    const ladrc_real_t n2 = q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
    if (!ladrc_is_finite(n2) || !(n2 >= QUAT_NORM2_MIN)) {
        return 0; /* a NaN or infinite part makes n2 non-finite */
    }
    const ladrc_real_t inv = LADRC_R(1.0) / ladrc_sqrt(n2);
    if (unit != NULL) {
        unit->w = q.w * inv;
        unit->x = q.x * inv;
        unit->y = q.y * inv;
        unit->z = q.z * inv;
    }
    return 1;
}

/* The same attitude with w >= 0 (q and -q are one rotation): the short way. */
static ladrc_quat_t short_way(ladrc_quat_t q)
{
    if (q.w < LADRC_R(0.0)) {
        q.w = -q.w;
        q.x = -q.x;
        q.y = -q.y;
        q.z = -q.z;
    }
    return q;
}

/* angle / |v| of a unit quaternion with w >= 0, from u = |v|^2. */
static ladrc_real_t angle_per_sine(ladrc_real_t w, ladrc_real_t u)
{
    if (u < QUAT_SERIES_MAX_U) {
        /* 2 asin(s) / s = 2 (1 + u/6 + 3u^2/40 + 5u^3/112 + 35u^4/1152) */
        return LADRC_R(2.0) *
               (LADRC_R(1.0) + u * (LADRC_R(1.0) / LADRC_R(6.0) +
                                    u * (LADRC_R(3.0) / LADRC_R(40.0) +
                                         u * (LADRC_R(5.0) / LADRC_R(112.0) + u * (LADRC_R(35.0) / LADRC_R(1152.0))))));
    }
    const ladrc_real_t s = ladrc_sqrt(u);
    const ladrc_real_t half = (s <= QUAT_ASIN_SWITCH)
                                  ? ladrc_asin(s)
                                  : LADRC_R(0.5) * LADRC_PI - ladrc_asin(ladrc_clamp(w, LADRC_R(0.0), LADRC_R(1.0)));
    return LADRC_R(2.0) * half / s;
}

void ladrc_quat_rotvec(ladrc_quat_t q, ladrc_real_t vec_rad[3])
{
    LADRC_REQUIRE_VOID(vec_rad != NULL);
    q = short_way(q);
    const ladrc_real_t g = angle_per_sine(q.w, q.x * q.x + q.y * q.y + q.z * q.z);
    vec_rad[0] = g * q.x;
    vec_rad[1] = g * q.y;
    vec_rad[2] = g * q.z;
}

void ladrc_quat_tilt_error(ladrc_quat_t q, ladrc_quat_t q_ref, ladrc_real_t yaw_weight, ladrc_real_t e_rad[3])
{
    LADRC_REQUIRE_VOID(e_rad != NULL);
    const ladrc_quat_t qe = short_way(ladrc_quat_mul(ladrc_quat_conj(q), q_ref));
    const ladrc_real_t k = (yaw_weight > LADRC_R(0.0) && yaw_weight < LADRC_R(1.0)) ? yaw_weight : LADRC_R(1.0);
    ladrc_quat_t err = qe;
    const ladrc_real_t n2 = qe.w * qe.w + qe.z * qe.z;
    if (k < LADRC_R(1.0) && n2 > QUAT_TWIST_MIN) {
        const ladrc_real_t inv = LADRC_R(1.0) / ladrc_sqrt(n2);
        /* swing (sw, sx, sy, 0) and the weighted twist (c, 0, 0, s):
         * (1 - k) + k twist, normalised (its scalar >= 1 - k > 0) */
        const ladrc_real_t sw = n2 * inv, sx = (qe.w * qe.x - qe.y * qe.z) * inv,
                           sy = (qe.w * qe.y + qe.x * qe.z) * inv;
        const ladrc_real_t kw = LADRC_R(1.0) - k + k * qe.w * inv, kz = k * qe.z * inv;
        const ladrc_real_t m = LADRC_R(1.0) / ladrc_sqrt(kw * kw + kz * kz);
        const ladrc_real_t c = kw * m, sn = kz * m;
        /* swing twist_k, the product written out for the zeros of both */
        err.w = sw * c;
        err.x = sx * c + sy * sn;
        err.y = sy * c - sx * sn;
        err.z = sw * sn;
    }
    ladrc_quat_rotvec(err, e_rad);
    if (k < LADRC_R(1.0)) {
        e_rad[2] = ladrc_clamp(e_rad[2] / k, -LADRC_PI, LADRC_PI);
    }
}
