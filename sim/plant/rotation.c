/* SPDX-License-Identifier: BSD-3-Clause */
#include "rotation.h"

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846

void sim_quat_mul(const double a[4], const double b[4], double out[4])
{
    const double w = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    const double x = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    const double y = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    const double z = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
    out[0] = w, out[1] = x, out[2] = y, out[3] = z;
}

void sim_quat_from_euler(const double angle_rad[3], double q[4])
{
    const double qx[4] = {cos(0.5 * angle_rad[0]), sin(0.5 * angle_rad[0]), 0.0, 0.0};
    const double qy[4] = {cos(0.5 * angle_rad[1]), 0.0, sin(0.5 * angle_rad[1]), 0.0};
    const double qz[4] = {cos(0.5 * angle_rad[2]), 0.0, 0.0, sin(0.5 * angle_rad[2])};
    double qzy[4];
    sim_quat_mul(qz, qy, qzy);
    sim_quat_mul(qzy, qx, q);
}

/* x moved by whole turns to within pi of near. */
static double near_turn(double x, double near)
{
    return x + 2.0 * PI * round((near - x) / (2.0 * PI));
}

void sim_quat_to_euler(const double q[4], const double *near_rad, double angle_rad[3])
{
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double s = 2.0 * (w * y - z * x);
    angle_rad[0] = atan2(2.0 * (w * x + y * z), 1.0 - 2.0 * (x * x + y * y));
    angle_rad[1] = asin(s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : s));
    angle_rad[2] = atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
    if (near_rad != NULL) {
        angle_rad[0] = near_turn(angle_rad[0], near_rad[0]);
        angle_rad[2] = near_turn(angle_rad[2], near_rad[2]);
    }
}

void sim_quat_rotvec(const double q[4], double vec_rad[3])
{
    const double sign = q[0] < 0.0 ? -1.0 : 1.0;
    const double s = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    /* 2 atan2(s, |w|) / s, and its limit 2 at s = 0 */
    const double g = s > 1e-150 ? 2.0 * atan2(s, sign * q[0]) / s : 2.0;
    for (int i = 0; i < 3; ++i) {
        vec_rad[i] = sign * g * q[i + 1];
    }
}

void sim_quat_from_rotvec(const double vec_rad[3], double q[4])
{
    const double angle = sqrt(vec_rad[0] * vec_rad[0] + vec_rad[1] * vec_rad[1] + vec_rad[2] * vec_rad[2]);
    /* sin(angle / 2) / angle, and its limit 1/2 at 0 */
    const double k = angle > 1e-150 ? sin(0.5 * angle) / angle : 0.5;
    q[0] = cos(0.5 * angle);
    for (int i = 0; i < 3; ++i) {
        q[i + 1] = k * vec_rad[i];
    }
}

void sim_quat_error(const double q[4], const double q_ref[4], double error_rad[3])
{
    const double conj[4] = {q[0], -q[1], -q[2], -q[3]};
    double e[4];
    sim_quat_mul(conj, q_ref, e);
    sim_quat_rotvec(e, error_rad);
}

double sim_wrap_pi(double x)
{
    const double pi = 3.14159265358979323846;
    return (x > -pi && x <= pi) ? x : x - 2.0 * pi * ceil((x - pi) / (2.0 * pi));
}
