/* SPDX-License-Identifier: BSD-3-Clause */
/* A rigid body with quaternion kinematics for closed-loop tests through any
 * attitude, in double precision: the body rates follow the dynamics of
 * test_rigid_body.h (Euler's equations in body axes with drag), the attitude
 * q (w, x, y, z, body to world) follows q' = q (0, rate) / 2. */
#ifndef LADRC_TEST_RIGID_QUAT_H
#define LADRC_TEST_RIGID_QUAT_H

#include "test_rigid_body.h"

typedef struct {
    test_rigid_body_t body; /* rates, inertia and drag; its angles are unused */
    double q[4];            /* attitude, unit */
} test_rigid_quat_t;

/* The paper's vehicle at rest, level. */
void test_rigid_quat_init(test_rigid_quat_t *b);

/* One step of dt_s with torques and disturbances held, `substeps` RK4
 * steps; q is renormalised after each. */
void test_rigid_quat_step(test_rigid_quat_t *b, const double torque_Nm[3], const double dist_rad_s2[3], double dt_s,
                          int substeps);

/* q of roll, pitch, yaw taken ZYX (q_z q_y q_x). */
void test_quat_from_euler(double roll_rad, double pitch_rad, double yaw_rad, double q[4]);

/* The rotation vector (rad, body axes) of a* b, the short way: the attitude
 * error of a against b. */
void test_quat_error(const double a[4], const double b[4], double e_rad[3]);

#endif
