/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file quat.h
 * @brief Unit quaternions for attitude: the product, the rotation vector and
 *        the attitude error with tilt priority the attitude layer's
 *        quaternion frame takes (docs/method.md, "Quaternion attitude").
 *
 * Convention: Hamilton product, scalar first, q = (w, x, y, z) rotates body
 * vectors into the world frame (v_world = q v_body q*), as the attitude
 * estimators of PX4, ArduPilot and Betaflight give it. From roll phi, pitch
 * theta and yaw psi (ZYX): q = q_z(psi) q_y(theta) q_x(phi).
 *
 * Attitude error with tilt priority. The error of q against a reference
 * q_ref, in body axes, is qe = q* q_ref (taken with qe.w >= 0: the short
 * way). It splits into a twist about body z and a swing that moves the
 * thrust axis, qe = swing twist:
 *
 *     twist = (w, 0, 0, z) / sqrt(w^2 + z^2)
 *     swing = (w^2 + z^2, w x - y z, w y + x z, 0) / sqrt(w^2 + z^2)
 *
 * (a pure 180 deg tilt, w = z = 0, has no twist: swing = qe). The twist is
 * weighted by k = yaw_weight, in (0, 1], as the normalised interpolation
 * from the identity, twist_k = normalise((1 - k) + k twist), and the
 * error is the rotation vector e of swing twist_k with its z component
 * divided by k. Near the reference e is the rotation vector of qe itself,
 * the per-axis error (roll, pitch, yaw) to first order, whatever k; with
 * large errors the swing (tilt) is served first and the yaw follows, as
 * Brescianini et al. (2013) and PX4 weigh their yaw (PX4: 0.4).
 */
#ifndef LADRC_QUAT_H
#define LADRC_QUAT_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A quaternion (w, x, y, z), scalar first; an attitude when of unit norm. */
typedef struct {
    ladrc_real_t w; /**< scalar part, cos(angle / 2) */
    ladrc_real_t x; /**< vector part along x, axis_x sin(angle / 2) */
    ladrc_real_t y; /**< vector part along y */
    ladrc_real_t z; /**< vector part along z */
} ladrc_quat_t;

/** The Hamilton product a b (rotation b, then a, in the frame of a).
 *  @param a  left factor
 *  @param b  right factor
 *  @return a b */
static inline ladrc_quat_t ladrc_quat_mul(ladrc_quat_t a, ladrc_quat_t b)
{
    ladrc_quat_t r;
    r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    return r;
}

/** The conjugate q* (the inverse of a unit quaternion).
 *  @param q  the quaternion
 *  @return (w, -x, -y, -z) */
static inline ladrc_quat_t ladrc_quat_conj(ladrc_quat_t q)
{
    ladrc_quat_t r = {q.w, -q.x, -q.y, -q.z};
    return r;
}

/** The attitude of roll, pitch and yaw taken ZYX, q_z(yaw) q_y(pitch)
 *  q_x(roll): smooth in every angle, pitch beyond 90 deg included.
 *  @param roll_rad   roll phi (rad)
 *  @param pitch_rad  pitch theta (rad)
 *  @param yaw_rad    yaw psi (rad)
 *  @return the unit quaternion (non-finite angles give non-finite parts) */
ladrc_quat_t ladrc_quat_from_euler(ladrc_real_t roll_rad, ladrc_real_t pitch_rad, ladrc_real_t yaw_rad);

/** q scaled to unit norm, for attitudes read from an estimator.
 *  @param q     the quaternion
 *  @param unit  out: q / |q|; NULL: nothing written
 *  @return 1, or 0 (nothing written) when a part is not finite or |q|^2 is
 *          below 1e-6 (no attitude) */
int ladrc_quat_normalise(ladrc_quat_t q, ladrc_quat_t *unit);

/** The rotation vector (axis times angle, rad) of a unit quaternion, the
 *  short way (angle in [0, pi]; q and -q give the same). Exact to the real
 *  type's rounding for every angle: a series near 0, asin elsewhere on the
 *  better-conditioned of |v| and w.
 *  @param q        a unit quaternion
 *  @param vec_rad  out: the rotation vector (rad); NULL: nothing written */
void ladrc_quat_rotvec(ladrc_quat_t q, ladrc_real_t vec_rad[3]);

/** The attitude error with tilt priority of the file comment, in body axes.
 *  @param q           the measured attitude (unit)
 *  @param q_ref       the reference attitude (unit)
 *  @param yaw_weight  k in (0, 1] (1: the plain rotation vector of q* q_ref;
 *                     values outside are taken as 1)
 *  @param e_rad       out: roll, pitch, yaw error (rad), each within
 *                     [-pi, pi]; NULL: nothing written */
void ladrc_quat_tilt_error(ladrc_quat_t q, ladrc_quat_t q_ref, ladrc_real_t yaw_weight, ladrc_real_t e_rad[3]);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_QUAT_H */
