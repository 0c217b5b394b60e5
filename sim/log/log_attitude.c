/* SPDX-License-Identifier: BSD-3-Clause */
/* The reader's attitude arithmetic (log_attitude.h). */
#include "log_attitude.h"

#include <math.h>

#define PI 3.14159265358979323846

void sim_log_quat_to_angle(const double q[4], double angle_rad[3])
{
    /* The rotation of q / |q|: every term scaled by n2 = |q|^2, so a log's
     * quaternion that is not quite unit gives the angles of its direction on
     * its rows as between them; one of no length (all zero) is no attitude. */
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    const double n2 = w * w + x * x + y * y + z * z;
    if (!(n2 > 0.0 && isfinite(n2))) {
        angle_rad[0] = angle_rad[1] = angle_rad[2] = NAN;
        return;
    }
    double s = 2.0 * (w * y - z * x) / n2;
    s = s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : s);
    angle_rad[0] = atan2(2.0 * (w * x + y * z), n2 - 2.0 * (x * x + y * y));
    angle_rad[1] = asin(s);
    angle_rad[2] = atan2(2.0 * (w * z + x * y), n2 - 2.0 * (y * y + z * z));
}

void sim_log_angle_to_quat(const double angle_rad[3], double q[4])
{
    const double cr = cos(0.5 * angle_rad[0]), sr = sin(0.5 * angle_rad[0]);
    const double cp = cos(0.5 * angle_rad[1]), sp = sin(0.5 * angle_rad[1]);
    const double cy = cos(0.5 * angle_rad[2]), sy = sin(0.5 * angle_rad[2]);
    q[0] = cr * cp * cy + sr * sp * sy;
    q[1] = sr * cp * cy - cr * sp * sy;
    q[2] = cr * sp * cy + sr * cp * sy;
    q[3] = cr * cp * sy - sr * sp * cy;
}

void sim_log_quat_lerp(const double q0[4], const double q1[4], double frac, double q[4])
{
    const double dot = q0[0] * q1[0] + q0[1] * q1[1] + q0[2] * q1[2] + q0[3] * q1[3];
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    double norm2 = 0.0;
    for (int i = 0; i < 4; ++i) {
        q[i] = q0[i] + (sign * q1[i] - q0[i]) * frac;
        norm2 += q[i] * q[i];
    }
    const double norm = sqrt(norm2);
    for (int i = 0; i < 4; ++i) {
        q[i] = norm > 0.0 ? q[i] / norm : q0[i];
    }
}

double sim_log_angle_lerp(double a0, double a1, double frac)
{
    double d = a1 - a0;
    if (fabs(d) > PI) {
        d = remainder(d, 2.0 * PI);
    }
    return a0 + d * frac;
}
