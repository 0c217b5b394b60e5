/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Attitudes as unit quaternions in double precision for the simulator: the
 * plant's rigid-body kinematics, the sensor's noise as a small rotation and
 * the tracking error in body axes. Convention as the library's quat.h:
 * q = (w, x, y, z), scalar first, Hamilton product, body to world; from
 * roll, pitch, yaw taken ZYX, q = q_z(yaw) q_y(pitch) q_x(roll).
 */
#ifndef LADRC_SIM_ROTATION_H
#define LADRC_SIM_ROTATION_H

/* An angle (rad) into (-pi, pi], and itself bit for bit when it is there
 * already (as an attitude estimator gives yaw to a wrapping controller). */
double sim_wrap_pi(double x);

/* a b */
void sim_quat_mul(const double a[4], const double b[4], double out[4]);

/* q of roll, pitch, yaw (rad), ZYX; any angles. */
void sim_quat_from_euler(const double angle_rad[3], double q[4]);

/* The ZYX angles of q: pitch in [-pi/2, pi/2] (at +-90 deg roll and yaw
 * share one degree of freedom, split as atan2 gives them); roll and yaw are
 * moved by whole turns to within pi of near_rad's, so that a continuous
 * attitude gives continuous angles (near_rad NULL: roll and yaw in
 * (-pi, pi]). */
void sim_quat_to_euler(const double q[4], const double *near_rad, double angle_rad[3]);

/* The rotation vector (rad) of q, the short way (angle in [0, pi]). */
void sim_quat_rotvec(const double q[4], double vec_rad[3]);

/* The rotation of the rotation vector v (rad): exp(v / 2). */
void sim_quat_from_rotvec(const double vec_rad[3], double q[4]);

/* The attitude error of q against q_ref in body axes, the rotation vector
 * of q* q_ref (rad). */
void sim_quat_error(const double q[4], const double q_ref[4], double error_rad[3]);

#endif
