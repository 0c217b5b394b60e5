/* SPDX-License-Identifier: BSD-3-Clause */
/* Betaflight SITL packets (bf_packet.h): host byte order, no padding. */
#include "bf_packet.h"

#include <string.h>

static unsigned char *put_doubles(unsigned char *p, const double *v, int n)
{
    memcpy(p, v, (size_t)n * sizeof *v);
    return p + (size_t)n * sizeof *v;
}

static const unsigned char *get_doubles(const unsigned char *p, double *v, int n)
{
    memcpy(v, p, (size_t)n * sizeof *v);
    return p + (size_t)n * sizeof *v;
}

void bf_fdm_encode(const bf_fdm_t *s, unsigned char out[BF_FDM_BYTES])
{
    unsigned char *p = put_doubles(out, &s->t_s, 1);
    p = put_doubles(p, s->gyro_rad_s, 3);
    p = put_doubles(p, s->accel_m_s2, 3);
    p = put_doubles(p, s->quat_wxyz, 4);
    p = put_doubles(p, s->velocity_m_s, 3);
    p = put_doubles(p, s->position, 3);
    put_doubles(p, &s->pressure_Pa, 1);
}

int bf_fdm_decode(const unsigned char *in, size_t n, bf_fdm_t *s)
{
    if (n != BF_FDM_BYTES) {
        return -1;
    }
    const unsigned char *p = get_doubles(in, &s->t_s, 1);
    p = get_doubles(p, s->gyro_rad_s, 3);
    p = get_doubles(p, s->accel_m_s2, 3);
    p = get_doubles(p, s->quat_wxyz, 4);
    p = get_doubles(p, s->velocity_m_s, 3);
    p = get_doubles(p, s->position, 3);
    get_doubles(p, &s->pressure_Pa, 1);
    return 0;
}

void bf_rc_encode(const bf_rc_t *rc, unsigned char out[BF_RC_BYTES])
{
    unsigned char *p = put_doubles(out, &rc->t_s, 1);
    memcpy(p, rc->channel_us, sizeof rc->channel_us);
}

int bf_rc_decode(const unsigned char *in, size_t n, bf_rc_t *rc)
{
    if (n != BF_RC_BYTES) {
        return -1;
    }
    const unsigned char *p = get_doubles(in, &rc->t_s, 1);
    memcpy(rc->channel_us, p, sizeof rc->channel_us);
    return 0;
}

void bf_motor_encode(const float motor[BF_MOTORS], unsigned char out[BF_MOTOR_BYTES])
{
    memcpy(out, motor, BF_MOTORS * sizeof *motor);
}

int bf_motor_decode(const unsigned char *in, size_t n, float motor[BF_MOTORS])
{
    if (n != BF_MOTOR_BYTES) {
        return -1;
    }
    memcpy(motor, in, BF_MOTORS * sizeof *motor);
    return 0;
}

/* Rz(-pi/2) q: the quaternion (cos(-pi/4), 0, 0, sin(-pi/4)) times q. */
void bf_gazebo_quat(const double q[4], double out[4])
{
    const double c = 0.70710678118654752440, s = -0.70710678118654752440;
    out[0] = c * q[0] - s * q[3];
    out[1] = c * q[1] - s * q[2];
    out[2] = c * q[2] + s * q[1];
    out[3] = c * q[3] + s * q[0];
}
