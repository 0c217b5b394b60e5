/* SPDX-License-Identifier: BSD-3-Clause */
/* What the firmware of examples/firmware_roll.c provides (sensors, setpoint,
 * motors) and what it calls (setup once, then one tick per millisecond).
 * examples/firmware_roll.c implements the hardware side with a simulated
 * roll axis so that the example runs on a PC. */
#ifndef LADRC_EXAMPLE_FIRMWARE_H
#define LADRC_EXAMPLE_FIRMWARE_H

#include "ladrc/types.h"

ladrc_real_t imu_roll_rad(void);                     /* attitude estimate, rad */
ladrc_real_t imu_roll_rate_rad_s(void);              /* gyro rate, rad/s */
ladrc_real_t setpoint_roll_rad(void);                /* pilot or autopilot, rad */
ladrc_real_t motors_roll_Nm(ladrc_real_t torque_Nm); /* returns the torque the rotors give, N m */
void enter_failsafe(void);

int roll_setup(void);
void control_tick_1khz(void);

#endif
