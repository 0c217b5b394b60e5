/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The three UDP packets of Betaflight's SITL build, as bytes: the flight
 * dynamics state it reads (port 9003), the RC channels it reads (9004) and
 * the four motor outputs it sends (9002). The SITL reads and writes them as
 * C structs of doubles, uint16 and floats in the host's byte order, without
 * padding: the layouts below are those sizes exactly (docs/betaflight.md).
 *
 * Axes, as the SITL's Gazebo bridge reads them: body rates in rad/s about
 * forward, right, down (roll right, pitch nose up, yaw nose right positive;
 * the SITL negates pitch into its own convention); specific force in m/s^2
 * along forward, right, down (level and still: 0, 0, -g); the attitude as the
 * Gazebo plugin sends it (bf_gazebo_quat).
 */
#ifndef LADRC_SIM_BF_PACKET_H
#define LADRC_SIM_BF_PACKET_H

#include <stddef.h>
#include <stdint.h>

#define BF_PORT_MOTORS 9002 /* the SITL sends the motor outputs here */
#define BF_PORT_FDM 9003    /* the SITL reads the state here */
#define BF_PORT_RC 9004     /* the SITL reads the RC channels here */

#define BF_RC_CHANNELS 16
#define BF_MOTORS 4
#define BF_FDM_BYTES (18 * 8)                /* 18 doubles */
#define BF_RC_BYTES (8 + 2 * BF_RC_CHANNELS) /* a double and 16 uint16 */
#define BF_MOTOR_BYTES (4 * BF_MOTORS)       /* 4 floats */

/* The state the SITL reads (fdm_packet). */
typedef struct {
    double t_s;             /* the simulator's time; never decreasing */
    double gyro_rad_s[3];   /* body rates, forward-right-down */
    double accel_m_s2[3];   /* specific force, forward-right-down */
    double quat_wxyz[4];    /* bf_gazebo_quat of the attitude */
    double velocity_m_s[3]; /* east, north, up (the SITL's virtual GPS) */
    double position[3];     /* longitude deg, latitude deg, altitude m (virtual GPS, baro) */
    double pressure_Pa;     /* read by the legacy bridges only */
} bf_fdm_t;

/* The RC channels (rc_packet): pulse widths in microseconds, 1000-2000. */
typedef struct {
    double t_s;
    uint16_t channel_us[BF_RC_CHANNELS];
} bf_rc_t;

void bf_fdm_encode(const bf_fdm_t *s, unsigned char out[BF_FDM_BYTES]);
void bf_rc_encode(const bf_rc_t *rc, unsigned char out[BF_RC_BYTES]);
void bf_motor_encode(const float motor[BF_MOTORS], unsigned char out[BF_MOTOR_BYTES]);

/* Decoders: 0, or -1 when n is not the packet's size. */
int bf_fdm_decode(const unsigned char *in, size_t n, bf_fdm_t *s);
int bf_rc_decode(const unsigned char *in, size_t n, bf_rc_t *rc);
int bf_motor_decode(const unsigned char *in, size_t n, float motor[BF_MOTORS]);

/* The attitude as the Gazebo plugin sends it, from the body
 * (forward-right-down) to north-east-down quaternion q_frd_ned (w, x, y, z):
 * the plugin's frames differ from those by a quarter turn about down, so
 * the packet holds Rz(-pi/2) q_frd_ned. */
void bf_gazebo_quat(const double q_frd_ned[4], double out_wxyz[4]);

#endif
