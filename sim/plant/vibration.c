/* SPDX-License-Identifier: BSD-3-Clause */
#include "vibration.h"

#include <math.h>
#include <stddef.h>

static int in_range(double x, double lo, double hi)
{
    return isfinite(x) && x >= lo && x <= hi;
}

int sim_vibration_init(sim_vibration_t *v, const sim_vibration_config_t *cfg, uint64_t seed)
{
    if (v == NULL || cfg == NULL || cfg->n_orders < 0 || cfg->n_orders > SIM_VIB_MAX_ORDERS) {
        return -1;
    }
    for (int k = 0; k < cfg->n_orders; ++k) {
        if (!in_range(cfg->order[k], SIM_VIB_ORDER_MIN, SIM_VIB_ORDER_MAX) ||
            !in_range(cfg->gyro_rad_s[k], 0.0, SIM_VIB_GYRO_MAX_RAD_S) ||
            !in_range(cfg->accel_m_s2[k], 0.0, SIM_VIB_ACCEL_MAX_M_S2)) {
            return -1;
        }
    }
    for (int a = 0; a < 3; ++a) {
        if (!in_range(cfg->axis_gain[a], 0.0, SIM_VIB_AXIS_GAIN_MAX)) {
            return -1;
        }
    }
    v->cfg = *cfg;
    sim_rng_t rng;
    sim_rng_seed(&rng, seed);
    const double two_pi = 6.283185307179586;
    for (int i = 0; i < SIM_VIB_ROTORS; ++i) {
        v->theta_rad[i] = 0.0;
        v->speed_rad_s[i] = 0.0;
        for (int k = 0; k < SIM_VIB_MAX_ORDERS; ++k) {
            for (int a = 0; a < 3; ++a) {
                const double phase_rad = two_pi * sim_rng_uniform(&rng);
                v->phase_cos[i][k][a] = cos(phase_rad);
                v->phase_sin[i][k][a] = sin(phase_rad);
            }
        }
    }
    v->started = 0;
    return 0;
}

/* A rotor's signed speed (rad/s) from its w^2; non-finite: 0 (no line). */
static double rotor_speed(double w2)
{
    if (!isfinite(w2)) {
        return 0.0;
    }
    return w2 >= 0.0 ? sqrt(w2) : -sqrt(-w2);
}

/* cos and sin of order * theta: for a whole order up to 16 by powers of
 * e^(i theta) (c1, s1: its cosine and sine), a few roundings; else directly. */
static void line_cos_sin(double order, double theta_rad, double c1, double s1, double *c, double *s)
{
    if (order == floor(order) && order <= 16.0) {
        double pc = 1.0, ps = 0.0, bc = c1, bs = s1; /* the power so far, the base squared on */
        for (unsigned k = (unsigned)order; k != 0u; k >>= 1) {
            if (k & 1u) {
                const double t = pc * bc - ps * bs;
                ps = pc * bs + ps * bc;
                pc = t;
            }
            const double t = bc * bc - bs * bs;
            bs = 2.0 * bc * bs;
            bc = t;
        }
        *c = pc;
        *s = ps;
        return;
    }
    *c = cos(order * theta_rad);
    *s = sin(order * theta_rad);
}

void sim_vibration_tick(sim_vibration_t *v, const double w2_rad2_s2[SIM_VIB_ROTORS], double dt_s, double gyro_rad_s[3],
                        double angle_rad[3], double accel_m_s2[3])
{
    const sim_vibration_config_t *c = &v->cfg;
    for (int i = 0; i < SIM_VIB_ROTORS; ++i) {
        const double w = rotor_speed(w2_rad2_s2[i]);
        if (v->started) {
            v->theta_rad[i] = fmod(v->theta_rad[i] + 0.5 * (v->speed_rad_s[i] + w) * dt_s, 6.283185307179586);
        }
        v->speed_rad_s[i] = w;
    }
    v->started = 1;
    for (int i = 0; i < SIM_VIB_ROTORS; ++i) {
        const double w = fabs(v->speed_rad_s[i]);
        const double c1 = cos(v->theta_rad[i]), s1 = sin(v->theta_rad[i]);
        for (int k = 0; k < c->n_orders; ++k) {
            const double wk = c->order[k] * w; /* the line's frequency (rad/s) */
            /* one sine and cosine per line, turned to each axis's phase */
            double cl, sl;
            line_cos_sin(c->order[k], v->theta_rad[i], c1, s1, &cl, &sl);
            for (int a = 0; a < 3; ++a) {
                const double s = sl * v->phase_cos[i][k][a] + cl * v->phase_sin[i][k][a];
                const double co = cl * v->phase_cos[i][k][a] - sl * v->phase_sin[i][k][a];
                const double g = c->gyro_rad_s[k] * c->axis_gain[a];
                if (gyro_rad_s != NULL) {
                    gyro_rad_s[a] += g * s;
                }
                if (angle_rad != NULL && wk > 0.0) {
                    angle_rad[a] -= g * co / wk;
                }
                if (accel_m_s2 != NULL) {
                    accel_m_s2[a] += c->accel_m_s2[k] * c->axis_gain[a] * co;
                }
            }
        }
    }
}

double sim_vibration_rotor_hz(const sim_vibration_t *v, int i)
{
    return fabs(v->speed_rad_s[i]) / 6.283185307179586;
}
