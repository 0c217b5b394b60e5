/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The pilot of a Betaflight SITL: the scenario's references as RC sticks,
 * on the channel map AETR1234 (roll, pitch, throttle, yaw, AUX1 arms,
 * AUX2 selects angle mode), pulses 1000-2000 us, centre 1500.
 *
 * Acro (rate) mode: the pilot closes the angle loop, as a pilot flying by
 * sight does: the sticks ask for the body rates w = w_ref + att_kp e, where
 * w_ref are the body rates of the reference's change over the last tick
 * (its ZYX angles' rates turned into body rates at the reference's
 * attitude, so a flip's reference is followed through any angle) and e the
 * body-axis attitude error the caller gives (the rotation from the attitude
 * to the reference's), through the SITL's rates set linear (full stick =
 * rate_max). Angle mode: roll and pitch sticks ask for ref / angle_limit
 * (the SITL's angle mode maps the stick linearly onto its angle limit), yaw
 * as in acro. Sticks beyond full deflection are held there (counted:
 * bf_pilot_t.clipped).
 *
 * Signs: the simulator's axes are forward-right-down (roll right, pitch
 * nose up, yaw nose right positive); Betaflight's pitch stick forward pitches
 * nose down, so the pitch stick is the negated nose-up demand.
 */
#ifndef LADRC_SIM_BF_PILOT_H
#define LADRC_SIM_BF_PILOT_H

#include "bf_packet.h"

typedef enum { BF_MODE_ACRO = 0, BF_MODE_ANGLE = 1 } bf_mode_t;

#define BF_STICK_CENTRE_US 1500
#define BF_STICK_HALF_US 500
#define BF_CH_ROLL 0
#define BF_CH_PITCH 1
#define BF_CH_THROTTLE 2
#define BF_CH_YAW 3
#define BF_CH_ARM 4
#define BF_CH_ANGLE 5

/* The pilot's defaults: full stick in acro as tools/betaflight/sitl.cli
 * makes the SITL's rates (linear, deg/s), and its angle loop (1/s): a
 * crossover near 1 Hz, well below any rate loop's, as a pilot holding an
 * attitude by sight */
#define BF_RATE_MAX_DEG_S_DEFAULT 700.0
#define BF_PILOT_ATT_KP_DEFAULT 6.0
#define BF_ANGLE_LIMIT_DEG_DEFAULT 60.0 /* Betaflight's angle_limit default */

typedef struct {
    bf_mode_t mode;
    double rate_max_rad_s;  /* full stick, acro (the SITL's linear rates) */
    double angle_limit_rad; /* full stick, angle mode (the SITL's angle_limit) */
    double att_kp_per_s;    /* the pilot's angle loop */
    double dt_s;            /* the control period */
} bf_pilot_config_t;

typedef struct {
    bf_pilot_config_t cfg;
    double last_ref_rad[3];
    int has_last;
    long clipped; /* ticks with a stick held at full deflection by the limit */
} bf_pilot_t;

void bf_pilot_init(bf_pilot_t *p, const bf_pilot_config_t *cfg);

/* The channels of a tick at t_s: the references (ZYX angles, rad), the
 * attitude error (body axes, rad, forward-right-down), throttle in [0, 1],
 * armed 0/1. */
void bf_pilot_sticks(bf_pilot_t *p, double t_s, const double ref_rad[3], const double error_rad[3], double throttle,
                     int armed, bf_rc_t *rc);

/* The body rates (rad/s) of ZYX angles at ref_rad changing at euler_rate. */
void bf_body_rates(const double ref_rad[3], const double euler_rate[3], double body_rad_s[3]);

/* Forgets the last reference: the next tick has no feed-forward (a new
 * flight starts from where the pilot is, not with a jump). */
void bf_pilot_restart(bf_pilot_t *p);

/* The body rates (rad/s) the acro sticks ask for at this tick, before they
 * become pulses: w_ref + att_kp e (the file's comment), w_ref from the
 * reference's change since the last tick bf_pilot_sticks or
 * bf_pilot_advance saw (none on the first). Does not advance the pilot. */
void bf_pilot_rate_demand(const bf_pilot_t *p, const double ref_rad[3], const double error_rad[3],
                          double rate_rad_s[3]);

/* The rate (rad/s) the SITL reads on axis (0 roll, 1 pitch, 2 yaw) for a
 * demand: held within full stick, and with pulse 1 as the link carries it,
 * a whole-microsecond pulse (rate_max / 500 per us). */
double bf_pilot_stick_rate(const bf_pilot_t *p, int axis, double rate_rad_s, int pulse);

/* Remembers the tick's reference (the next tick's feed-forward), as
 * bf_pilot_sticks does. */
void bf_pilot_advance(bf_pilot_t *p, const double ref_rad[3]);

/* A stick in [-1, 1] as a pulse (us), rounded; beyond: held at the end. */
uint16_t bf_stick_us(double stick);

#endif
