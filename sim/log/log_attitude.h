/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The reader's attitude arithmetic: ZYX angles from a quaternion (w x y z)
 * and back, and a quaternion interpolated between two rows.
 */
#ifndef LADRC_SIM_LOG_ATTITUDE_H
#define LADRC_SIM_LOG_ATTITUDE_H

/* The ZYX angles of q's direction, n2 = |q|^2: roll = atan2(2(wx + yz),
 * n2 - 2(x^2 + y^2)), pitch = asin(2(wy - zx) / n2) clamped, yaw =
 * atan2(2(wz + xy), n2 - 2(y^2 + z^2)); NaN for a q of no length or not finite. */
void sim_log_quat_to_angle(const double q[4], double angle_rad[3]);
void sim_log_angle_to_quat(const double angle_rad[3], double q[4]);

/* Component-wise linear from q0 to q1 (the short way: q1's sign flipped
 * when the two are more than half a turn apart) at frac, then normalised;
 * a zero result is q0 as it is. */
void sim_log_quat_lerp(const double q0[4], const double q1[4], double frac, double q[4]);

/* Linear from a0 to a1 at frac along the shorter way round (a wrapped angle
 * crossing +-pi), not wrapped after. */
double sim_log_angle_lerp(double a0, double a1, double frac);

#endif
