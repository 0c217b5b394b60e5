/* SPDX-License-Identifier: BSD-3-Clause */
#include "test_rigid_quat.h"

#include <math.h>

static void mul(const double a[4], const double b[4], double r[4])
{
    r[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    r[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    r[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    r[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

void test_rigid_quat_init(test_rigid_quat_t *b)
{
    test_rigid_body_init(&b->body);
    b->q[0] = 1.0;
    b->q[1] = b->q[2] = b->q[3] = 0.0;
}

/* q' = q (0, w) / 2 */
static void q_dot(const double q[4], const double w[3], double dq[4])
{
    const double p[4] = {0.0, 0.5 * w[0], 0.5 * w[1], 0.5 * w[2]};
    mul(q, p, dq);
}

void test_rigid_quat_step(test_rigid_quat_t *b, const double torque_Nm[3], const double dist_rad_s2[3], double dt_s,
                          int substeps)
{
    const double h = dt_s / substeps;
    for (int s = 0; s < substeps; ++s) {
        double kw[4][3], kq[4][4], w[3], q[4];
        for (int stage = 0; stage < 4; ++stage) {
            const double f = (stage == 0) ? 0.0 : (stage == 3 ? 1.0 : 0.5);
            for (int i = 0; i < 3; ++i) {
                w[i] = b->body.rate_rad_s[i] + (stage ? f * h * kw[stage - 1][i] : 0.0);
            }
            for (int i = 0; i < 4; ++i) {
                q[i] = b->q[i] + (stage ? f * h * kq[stage - 1][i] : 0.0);
            }
            test_rigid_body_accel(&b->body, w, torque_Nm, dist_rad_s2, kw[stage]);
            q_dot(q, w, kq[stage]);
        }
        for (int i = 0; i < 3; ++i) {
            b->body.rate_rad_s[i] += h / 6.0 * (kw[0][i] + 2.0 * kw[1][i] + 2.0 * kw[2][i] + kw[3][i]);
        }
        double n2 = 0.0;
        for (int i = 0; i < 4; ++i) {
            b->q[i] += h / 6.0 * (kq[0][i] + 2.0 * kq[1][i] + 2.0 * kq[2][i] + kq[3][i]);
            n2 += b->q[i] * b->q[i];
        }
        for (int i = 0; i < 4; ++i) {
            b->q[i] /= sqrt(n2);
        }
    }
}

void test_quat_from_euler(double roll_rad, double pitch_rad, double yaw_rad, double q[4])
{
    const double qz[4] = {cos(0.5 * yaw_rad), 0.0, 0.0, sin(0.5 * yaw_rad)};
    const double qy[4] = {cos(0.5 * pitch_rad), 0.0, sin(0.5 * pitch_rad), 0.0};
    const double qx[4] = {cos(0.5 * roll_rad), sin(0.5 * roll_rad), 0.0, 0.0};
    double qzy[4];
    mul(qz, qy, qzy);
    mul(qzy, qx, q);
}

void test_quat_error(const double a[4], const double b[4], double e_rad[3])
{
    const double ac[4] = {a[0], -a[1], -a[2], -a[3]};
    double e[4];
    mul(ac, b, e);
    const double sign = e[0] < 0.0 ? -1.0 : 1.0;
    const double s = sqrt(e[1] * e[1] + e[2] * e[2] + e[3] * e[3]);
    const double g = s > 1e-300 ? 2.0 * atan2(s, sign * e[0]) / s : 2.0;
    for (int i = 0; i < 3; ++i) {
        e_rad[i] = sign * g * e[i + 1];
    }
}
