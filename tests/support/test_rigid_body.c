/* SPDX-License-Identifier: BSD-3-Clause */
#include "test_rigid_body.h"

void test_rigid_body_init(test_rigid_body_t *b)
{
    for (int i = 0; i < 3; ++i) {
        b->angle_rad[i] = 0.0;
        b->rate_rad_s[i] = 0.0;
    }
    b->inertia_kg_m2[0] = 5.445e-3;
    b->inertia_kg_m2[1] = 5.445e-3;
    b->inertia_kg_m2[2] = 1.089e-2;
    b->drag_Nms = 9e-2;
}

void test_rigid_body_accel(const test_rigid_body_t *b, const double rate[3], const double torque_Nm[3],
                           const double dist_rad_s2[3], double accel[3])
{
    const double *j = b->inertia_kg_m2;
    accel[0] = (torque_Nm[0] + (j[1] - j[2]) * rate[1] * rate[2] - b->drag_Nms * rate[0]) / j[0] + dist_rad_s2[0];
    accel[1] = (torque_Nm[1] + (j[2] - j[0]) * rate[0] * rate[2] - b->drag_Nms * rate[1]) / j[1] + dist_rad_s2[1];
    accel[2] = (torque_Nm[2] + (j[0] - j[1]) * rate[1] * rate[0] - b->drag_Nms * rate[2]) / j[2] + dist_rad_s2[2];
}

void test_rigid_body_step(test_rigid_body_t *b, const double torque_Nm[3], const double dist_rad_s2[3], double dt_s,
                          int substeps)
{
    const double h = dt_s / substeps;
    for (int s = 0; s < substeps; ++s) {
        double k[4][2][3]; /* stage, (angle', rate'), axis */
        double rate[3];
        for (int stage = 0; stage < 4; ++stage) {
            const double f = (stage == 0) ? 0.0 : (stage == 3 ? 1.0 : 0.5);
            for (int i = 0; i < 3; ++i) {
                rate[i] = b->rate_rad_s[i] + (stage ? f * h * k[stage - 1][1][i] : 0.0);
                k[stage][0][i] = rate[i];
            }
            test_rigid_body_accel(b, rate, torque_Nm, dist_rad_s2, k[stage][1]);
        }
        for (int i = 0; i < 3; ++i) {
            b->angle_rad[i] += h / 6.0 * (k[0][0][i] + 2.0 * k[1][0][i] + 2.0 * k[2][0][i] + k[3][0][i]);
            b->rate_rad_s[i] += h / 6.0 * (k[0][1][i] + 2.0 * k[1][1][i] + 2.0 * k[2][1][i] + k[3][1][i]);
        }
    }
}
