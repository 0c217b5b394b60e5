/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file ladrc_bf_hook.h
 * @brief What Betaflight's pid.c calls at its hook point in pidController
 *        (docs/betaflight-integration.md): the per-axis pidSum from the
 *        library's rate loop (ladrc_rate.h) instead of P + I + D + F + S.
 */
#ifndef LADRC_BF_HOOK_H
#define LADRC_BF_HOOK_H

#include <stdbool.h>

/**
 * The pidSum of one axis for this PID loop tick.
 * @param axis            FD_ROLL, FD_PITCH or FD_YAW (0..2)
 * @param setpointDegS    Betaflight's rate setpoint (deg/s) after its rates,
 *                        angle mode and acro trainer (currentPidSetpoint)
 * @param gyroDegS        Betaflight's filtered gyro (deg/s, gyro.gyroADCf)
 * @param dtS             the PID loop period (s, pidRuntime.dT)
 * @param active          armed and stabilising: false restarts the rate loop
 *                        at rest and returns 0 (as Betaflight zeroes its
 *                        sum and resets its I term)
 * @param nativeSum       Betaflight's own P + I + D + F + S, flown only when
 *                        the compiled-in parameters were refused (a
 *                        simulator build stops instead)
 * @return the pidSum (Betaflight's units, within the configured bound)
 */
float ladrcRatePidSum(int axis, float setpointDegS, float gyroDegS, float dtS, bool active, float nativeSum);

#endif /* LADRC_BF_HOOK_H */
