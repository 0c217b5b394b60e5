/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file ladrc_rate.h
 * @brief The library's RATE-ADRC rate loop (axis.h, radrc_acro = 1) as a
 *        flight stack's rate controller: per axis, from the stack's rate
 *        setpoint and filtered gyro (deg/s) to the stack's per-axis PID sum
 *        (Betaflight's pidSum, the unit its mixer divides by
 *        PID_MIXER_SCALING).
 *
 * The rate loop is the library's own, unchanged: the rate ESO (reso.h) on
 * the gyro, the law u = (k_w (w_ref - z1) - z2) / b0, the actuator model.
 * Only its command unit differs from the simulator's: there u is a torque
 * in N m and b0 = 1 / J (rad/s^2 per N m); here u is a pidSum and b0 is in
 * rad/s^2 per pidSum unit, b0 = kappa / J with kappa the torque (N m) one
 * pidSum unit makes through the mixer and motors
 * (docs/betaflight-integration.md derives kappa). The observer's states
 * are accelerations and rates, so both loops run the same arithmetic on the
 * same inputs; pidSum * kappa is the simulator's torque.
 *
 * No heap, no stdio, no globals: the caller owns one ladrc_bf_rate_t (the
 * Betaflight glue holds one static instance, as pid.c holds its pidRuntime).
 */
#ifndef LADRC_BF_RATE_H
#define LADRC_BF_RATE_H

#include <stdint.h>

#include "ladrc/axis.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Axes in Betaflight's order (FD_ROLL, FD_PITCH, FD_YAW). */
#define LADRC_BF_AXES 3

/** One airframe's rate-loop parameters; can live in flash. */
typedef struct {
    float k_w_per_s[LADRC_BF_AXES];            /**< rate-loop crossover k_w (1/s), radrc_kp_per_s */
    float wo_rad_s[LADRC_BF_AXES];             /**< rate observer bandwidth (rad/s) */
    float b0_rad_s2_per_pidsum[LADRC_BF_AXES]; /**< kappa / J: rad/s^2 per pidSum unit, > 0 */
    float pidsum_limit[LADRC_BF_AXES];         /**< |command| bound (pidSum units): Betaflight's
                                                    pidsum_limit, pidsum_limit_yaw */
    float motor_tau_s;                         /**< motors' first-order lag (s), 0 = none */
    uint16_t delay_ticks;                      /**< measurement delay (PID loop ticks), 0 = none */
} ladrc_bf_rate_params_t;

/** The rate controller of three axes; owned by the caller. */
typedef struct {
    ladrc_axis_t axis[LADRC_BF_AXES];
    ladrc_bf_rate_params_t params;       /**< a copy, for the restart on a new loop time */
    float dt_s;                          /**< the loop time the axes were set up for (s) */
    float pidsum[LADRC_BF_AXES];         /**< last good command of each axis (pidSum units) */
    ladrc_fault_t faults[LADRC_BF_AXES]; /**< flags of each axis's latest step */
    uint8_t ready;                       /**< 1 after a successful init */
} ladrc_bf_rate_t;

/** deg/s to rad/s, the one conversion between Betaflight's rates and the library's. */
static inline ladrc_real_t ladrc_bf_rad_s(float deg_s)
{
    return (ladrc_real_t)deg_s * (LADRC_R(3.14159265358979323846) / LADRC_R(180.0));
}

/**
 * Configures the three axes as RATE-ADRC in acro (the reference is the rate
 * setpoint) from the library's defaults, then params; validates through
 * ladrc_axis_init and resets.
 * @param rc      the controller
 * @param params  the airframe's parameters (copied)
 * @param dt_s    the PID loop's period (s): Betaflight's pidRuntime.dT
 * @return LADRC_OK, LADRC_ERR_NULL, or the first axis's refusal (the
 *         axis.h status naming the field); on a refusal rc is not ready and
 *         ladrc_bf_rate_step returns 0 with LADRC_FAULT_STATE
 */
ladrc_status_t ladrc_bf_rate_init(ladrc_bf_rate_t *rc, const ladrc_bf_rate_params_t *params, float dt_s);

/**
 * Restarts every axis at rest (disarm): observers at 0, commands 0.
 * @param rc  the controller; NULL: nothing happens
 */
void ladrc_bf_rate_reset(ladrc_bf_rate_t *rc);

/**
 * One tick of one axis. A dt_s other than the one of init (Betaflight's
 * loop time changed) sets the axes up again for it first (a restart at rest).
 * A non-finite setpoint or gyro, or one beyond the axis's plausible range,
 * keeps the last good command and raises the axis's fault flags
 * (ladrc_bf_rate_faults); so does a step on a controller that is not ready.
 * @param rc           the controller
 * @param axis         0 roll, 1 pitch, 2 yaw
 * @param setpoint_deg_s  the rate setpoint (deg/s)
 * @param gyro_deg_s   the filtered gyro rate (deg/s)
 * @param dt_s         the loop period (s)
 * @return the command (pidSum units, within +-pidsum_limit); rc NULL or
 *         axis out of range: 0
 */
float ladrc_bf_rate_step(ladrc_bf_rate_t *rc, int axis, float setpoint_deg_s, float gyro_deg_s, float dt_s);

/** @param rc    the controller
 *  @param axis  0..2
 *  @return the fault flags of the axis's latest step (types.h);
 *          rc NULL or axis out of range: LADRC_FAULT_STATE */
ladrc_fault_t ladrc_bf_rate_faults(const ladrc_bf_rate_t *rc, int axis);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_BF_RATE_H */
