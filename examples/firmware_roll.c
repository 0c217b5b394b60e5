/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * One roll axis as firmware runs it: the lines between the readme markers
 * are the front page's example (tools/check_links.py checks that they are
 * identical). Below them, the hardware of examples/firmware.h is a simulated
 * airframe axis (the paper's vehicle, J = 5.445e-3 kg m^2, drag 0.09 N m s,
 * rotors limited to +-0.05 N m), and main() flies a 10 deg step under a
 * constant 8 rad/s^2 disturbance for 3 s. Exit status 0 when the axis ends
 * within 0.01 deg of the setpoint without a failsafe, 1 otherwise.
 */
/* readme:begin */
#include "firmware.h" /* your sensors, setpoint and motors */
#include "ladrc/axis.h"

static ladrc_axis_t roll; /* state: yours, in RAM */

int roll_setup(void)
{
    ladrc_axis_config_t cfg; /* config: can be const, in flash */
    ladrc_axis_config_default(&cfg, LADRC_VARIANT_LP_MLADRC, 0.001f, 5.445e-3f /* Jx, kg m^2 */);
    cfg.u_min_Nm = -0.05f; /* what the motors can give */
    cfg.u_max_Nm = 0.05f;
    if (ladrc_axis_init(&roll, &cfg) != LADRC_OK) {
        return -1; /* ladrc_status_str() names the bad field */
    }
    ladrc_axis_reset(&roll, imu_roll_rad()); /* start where the vehicle is */
    return 0;
}

void control_tick_1khz(void) /* every 1 ms, fixed step */
{
    const ladrc_real_t rate_rad_s = imu_roll_rate_rad_s(); /* LP-MLADRC uses the gyro */
    ladrc_real_t torque_Nm;
    (void)ladrc_axis_step(&roll, setpoint_roll_rad(), imu_roll_rad(), &rate_rad_s, &torque_Nm);
    ladrc_axis_set_applied(&roll, motors_roll_Nm(torque_Nm)); /* the observer sees what acted */
    if (ladrc_axis_get_consecutive_faults(&roll) > 50u) {
        enter_failsafe(); /* 50 ms without a usable attitude */
    }
}
/* readme:end */

#include <math.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3
#define KT_NM_S 0.09
#define TORQUE_LIMIT_NM 0.05
#define DIST_RAD_S2 8.0
#define STEP_RAD (10.0 * 3.14159265358979 / 180.0)

static double sim_angle_rad;
static double sim_rate_rad_s;
static int failsafe;

ladrc_real_t imu_roll_rad(void)
{
    return (ladrc_real_t)sim_angle_rad;
}
ladrc_real_t imu_roll_rate_rad_s(void)
{
    return (ladrc_real_t)sim_rate_rad_s;
}
ladrc_real_t setpoint_roll_rad(void)
{
    return (ladrc_real_t)STEP_RAD;
}
void enter_failsafe(void)
{
    failsafe = 1;
}

/* The rotors give the torque within their limit; the airframe then moves
 * for one tick (semi-implicit Euler, 10 substeps). */
ladrc_real_t motors_roll_Nm(ladrc_real_t torque_Nm)
{
    const double applied_Nm = fmin(fmax((double)torque_Nm, -TORQUE_LIMIT_NM), TORQUE_LIMIT_NM);
    for (int i = 0; i < 10; ++i) {
        const double accel = (applied_Nm - KT_NM_S * sim_rate_rad_s) / J_KG_M2 + DIST_RAD_S2;
        sim_rate_rad_s += accel * DT_S / 10.0;
        sim_angle_rad += sim_rate_rad_s * DT_S / 10.0;
    }
    return (ladrc_real_t)applied_Nm;
}

int main(void)
{
    if (roll_setup() != 0) {
        return 1;
    }
    for (int k = 0; k < 3000; ++k) {
        control_tick_1khz();
    }
    const double error_deg = fabs(STEP_RAD - sim_angle_rad) * 180.0 / 3.14159265358979;
    return (failsafe == 0 && error_deg < 0.01) ? 0 : 1;
}
