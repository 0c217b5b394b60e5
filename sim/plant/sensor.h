/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Attitude sensor model for the simulator: the measured angles and rates are
 * the true ones delay_ticks calls ago plus zero-mean Gaussian noise of the
 * given standard deviations, drawn from a generator seeded at init.
 *
 * Each call draws six normal deviates, angles 0..2 then rates 0..2, whatever
 * the standard deviations: the noise of one quantity for a given seed does
 * not change when the other's is switched on or off. A standard deviation of
 * 0 passes the (delayed) truth exactly. When both are 0 nothing is drawn
 * (the generator is the sensor's own: no other output changes).
 *
 * The attitude may also be given as a quaternion (rotation.h): its
 * measurement is the delayed one turned by the angle noise as a small
 * rotation in body axes, q exp(noise / 2), with the same deviates.
 *
 * Delay: call k returns the truth of call k - delay_ticks; the first
 * delay_ticks calls return the truth of the first call (the sensor starts as
 * if the vehicle had been there forever).
 */
#ifndef LADRC_SIM_SENSOR_H
#define LADRC_SIM_SENSOR_H

#include <stdint.h>

#include "rng.h"

#define SIM_SENSOR_MAX_DELAY 512 /* past the controllers' LADRC_MAX_DELAY_TICKS (400): a sensor later than they model */

typedef struct {
    double angle_std_rad, rate_std_rad_s;
    int delay_ticks;
    sim_rng_t rng;
    /* ring of the last delay_ticks + 1 true values */
    double angle_hist[SIM_SENSOR_MAX_DELAY + 1][3];
    double rate_hist[SIM_SENSOR_MAX_DELAY + 1][3];
    double quat_hist[SIM_SENSOR_MAX_DELAY + 1][4];
    int head;   /* slot the next call writes */
    int primed; /* 0 until the first call filled the ring */
} sim_sensor_t;

/* Returns 0, or -1 (s untouched) when s is NULL, a standard deviation is
 * negative or not finite, or delay_ticks is outside [0, SIM_SENSOR_MAX_DELAY]. */
int sim_sensor_init(sim_sensor_t *s, double angle_std_rad, double rate_std_rad_s, int delay_ticks, uint64_t seed);

/* One sample per control tick; angle_out and rate_out get the measurement. */
void sim_sensor_measure(sim_sensor_t *s, const double angle_rad[3], const double rate_rad_s[3], double angle_out[3],
                        double rate_out[3]);

/* The same with the attitude as a quaternion as well: quat_out gets its
 * measurement (the same noise; the same outputs as sim_sensor_measure). A
 * sensor is measured one way or the other throughout. */
void sim_sensor_measure_quat(sim_sensor_t *s, const double angle_rad[3], const double quat[4],
                             const double rate_rad_s[3], double angle_out[3], double rate_out[3], double quat_out[4]);

#endif
