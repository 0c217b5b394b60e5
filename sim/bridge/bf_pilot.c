/* SPDX-License-Identifier: BSD-3-Clause */
/* The pilot of a Betaflight SITL (bf_pilot.h). */
#include "bf_pilot.h"

#include <math.h>
#include <string.h>

/* The stick's sign per axis: roll and yaw as the simulator's, pitch negated. */
static const double STICK_SIGN[3] = {1.0, -1.0, 1.0};

uint16_t bf_stick_us(double stick)
{
    const double s = isnan(stick) ? 0.0 : fmax(-1.0, fmin(1.0, stick));
    return (uint16_t)lround(BF_STICK_CENTRE_US + BF_STICK_HALF_US * s);
}

void bf_pilot_init(bf_pilot_t *p, const bf_pilot_config_t *cfg)
{
    memset(p, 0, sizeof *p);
    p->cfg = *cfg;
}

void bf_pilot_restart(bf_pilot_t *p)
{
    p->has_last = 0;
}

/* A stick's deflection, noted when the limit holds it. */
static double held(double stick, int *clipped)
{
    if (fabs(stick) > 1.0) {
        *clipped = 1;
    }
    return stick;
}

/* ZYX (yaw psi, pitch theta, roll phi): p = phi' - psi' sin(theta),
 * q = theta' cos(phi) + psi' cos(theta) sin(phi),
 * r = -theta' sin(phi) + psi' cos(theta) cos(phi). */
void bf_body_rates(const double ref_rad[3], const double euler_rate[3], double body_rad_s[3])
{
    const double sf = sin(ref_rad[0]), cf = cos(ref_rad[0]), st = sin(ref_rad[1]), ct = cos(ref_rad[1]);
    body_rad_s[0] = euler_rate[0] - euler_rate[2] * st;
    body_rad_s[1] = euler_rate[1] * cf + euler_rate[2] * ct * sf;
    body_rad_s[2] = -euler_rate[1] * sf + euler_rate[2] * ct * cf;
}

void bf_pilot_sticks(bf_pilot_t *p, double t_s, const double ref_rad[3], const double error_rad[3], double throttle,
                     int armed, bf_rc_t *rc)
{
    static const int CH[3] = {BF_CH_ROLL, BF_CH_PITCH, BF_CH_YAW};
    const bf_pilot_config_t *c = &p->cfg;
    double euler_rate[3] = {0.0, 0.0, 0.0}, ff[3];
    for (int i = 0; p->has_last && i < 3; ++i) {
        euler_rate[i] = (ref_rad[i] - p->last_ref_rad[i]) / c->dt_s;
    }
    bf_body_rates(ref_rad, euler_rate, ff);
    int clipped = 0;
    for (int i = 0; i < 3; ++i) {
        double stick;
        if (c->mode == BF_MODE_ANGLE && i < 2) {
            stick = ref_rad[i] / c->angle_limit_rad;
        } else {
            stick = (ff[i] + c->att_kp_per_s * error_rad[i]) / c->rate_max_rad_s;
        }
        rc->channel_us[CH[i]] = bf_stick_us(held(STICK_SIGN[i] * stick, &clipped));
        p->last_ref_rad[i] = ref_rad[i];
    }
    p->has_last = 1;
    p->clipped += clipped;
    rc->t_s = t_s;
    rc->channel_us[BF_CH_THROTTLE] = (uint16_t)lround(1000.0 + 1000.0 * fmax(0.0, fmin(1.0, throttle)));
    rc->channel_us[BF_CH_ARM] = armed ? 2000 : 1000;
    rc->channel_us[BF_CH_ANGLE] = c->mode == BF_MODE_ANGLE ? 2000 : 1000;
    for (int k = BF_CH_ANGLE + 1; k < BF_RC_CHANNELS; ++k) {
        rc->channel_us[k] = BF_STICK_CENTRE_US;
    }
}
