/* SPDX-License-Identifier: BSD-3-Clause */
/* The paper's attitude dynamics (docs/method.md eq. 2) for closed-loop tests, in
 * double precision:
 *   phi''   = (tau_x + (Jy - Jz) theta' psi' - kt phi'  ) / Jx + d_phi
 *   theta'' = (tau_y + (Jz - Jx) phi'   psi' - kt theta') / Jy + d_theta
 *   psi''   = (tau_z + (Jx - Jy) theta' phi' - kt psi'  ) / Jz + d_psi */
#ifndef LADRC_TEST_RIGID_BODY_H
#define LADRC_TEST_RIGID_BODY_H

typedef struct {
    double angle_rad[3];
    double rate_rad_s[3];
    double inertia_kg_m2[3];
    double drag_Nms;
} test_rigid_body_t;

/* The paper's vehicle (Table 1) at rest. */
void test_rigid_body_init(test_rigid_body_t *b);

/* Angular accelerations for the given torques and disturbance accelerations. */
void test_rigid_body_accel(const test_rigid_body_t *b, const double rate[3], const double torque_Nm[3],
                           const double dist_rad_s2[3], double accel[3]);

/* One step of dt_s with torques and disturbances held, `substeps` RK4 steps. */
void test_rigid_body_step(test_rigid_body_t *b, const double torque_Nm[3], const double dist_rad_s2[3], double dt_s,
                          int substeps);

#endif
