/* SPDX-License-Identifier: BSD-3-Clause */
#include "sensor.h"
#include "rotation.h"

#include <math.h>
#include <stddef.h>

static int valid_std(double std)
{
    return isfinite(std) && std >= 0.0;
}

/* Without noise the truth passes bit for bit (-0.0 included). */
static double with_noise(double truth, double std, double unit_noise)
{
    return std > 0.0 ? truth + std * unit_noise : truth;
}

int sim_sensor_init(sim_sensor_t *s, double angle_std_rad, double rate_std_rad_s, int delay_ticks, uint64_t seed)
{
    if (s == NULL || !valid_std(angle_std_rad) || !valid_std(rate_std_rad_s) || delay_ticks < 0 ||
        delay_ticks > SIM_SENSOR_MAX_DELAY) {
        return -1;
    }
    s->angle_std_rad = angle_std_rad;
    s->rate_std_rad_s = rate_std_rad_s;
    s->delay_ticks = delay_ticks;
    sim_rng_seed(&s->rng, seed);
    for (int k = 0; k <= SIM_SENSOR_MAX_DELAY; ++k) {
        for (int i = 0; i < 3; ++i) {
            s->angle_hist[k][i] = 0.0;
            s->rate_hist[k][i] = 0.0;
        }
        s->quat_hist[k][0] = 1.0;
        s->quat_hist[k][1] = s->quat_hist[k][2] = s->quat_hist[k][3] = 0.0;
    }
    s->head = 0;
    s->primed = 0;
    return 0;
}

void sim_sensor_measure_quat(sim_sensor_t *s, const double angle_rad[3], const double quat[4],
                             const double rate_rad_s[3], double angle_out[3], double rate_out[3], double quat_out[4])
{
    const int len = s->delay_ticks + 1;
    if (!s->primed) {
        for (int k = 0; k < len; ++k) {
            for (int i = 0; i < 3; ++i) {
                s->angle_hist[k][i] = angle_rad[i];
                s->rate_hist[k][i] = rate_rad_s[i];
            }
            for (int i = 0; quat != NULL && i < 4; ++i) {
                s->quat_hist[k][i] = quat[i];
            }
        }
        s->primed = 1;
    }
    for (int i = 0; i < 3; ++i) {
        s->angle_hist[s->head][i] = angle_rad[i];
        s->rate_hist[s->head][i] = rate_rad_s[i];
    }
    for (int i = 0; quat != NULL && i < 4; ++i) {
        s->quat_hist[s->head][i] = quat[i];
    }
    /* the slot after the newest is the oldest: written delay_ticks calls ago */
    const int oldest = (s->head + 1) % len;
    s->head = oldest;
    /* Without any noise nothing is drawn: the generator feeds this sensor
     * alone, so no other stream shifts. With noise on one quantity all six
     * are drawn, as the header promises. */
    double noise[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    if (s->angle_std_rad > 0.0 || s->rate_std_rad_s > 0.0) {
        for (int i = 0; i < 6; ++i) {
            noise[i] = sim_rng_gauss(&s->rng);
        }
    }
    double turn_rad[3];
    for (int i = 0; i < 3; ++i) {
        angle_out[i] = with_noise(s->angle_hist[oldest][i], s->angle_std_rad, noise[i]);
        rate_out[i] = with_noise(s->rate_hist[oldest][i], s->rate_std_rad_s, noise[3 + i]);
        turn_rad[i] = s->angle_std_rad * noise[i];
    }
    if (quat_out != NULL) {
        double turn[4];
        sim_quat_from_rotvec(turn_rad, turn);
        sim_quat_mul(s->quat_hist[oldest], turn, quat_out);
    }
}

void sim_sensor_measure(sim_sensor_t *s, const double angle_rad[3], const double rate_rad_s[3], double angle_out[3],
                        double rate_out[3])
{
    sim_sensor_measure_quat(s, angle_rad, NULL, rate_rad_s, angle_out, rate_out, NULL);
}
