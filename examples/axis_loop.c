/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * One roll axis in a 1 kHz loop, as firmware would run it, against a
 * simulated airframe axis (the paper's vehicle: J = 5.445e-3 kg m^2, rotor
 * drag kt = 0.09 N m s). The reference steps by 10 deg at 0.5 s, a constant
 * 8 rad/s^2 disturbance (the paper's Table 2) acts from 1.5 s, and the motors
 * deliver at most 0.05 N m. Prints a short comparison of the four controllers.
 */
#include "ladrc/axis.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3f
#define J_KG_M2 5.445e-3f
#define KT_NM_S 0.09
#define TORQUE_LIMIT_NM 0.05f
#define DEG (3.14159265358979 / 180.0)

typedef struct {
    double settling_s;    /* last time |error| > 2% of the step, after the step */
    double peak_dist_deg; /* largest |error| after the disturbance starts */
    double final_err_deg; /* |error| at the end */
} result_t;

static int run(ladrc_variant_t variant, result_t *res)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, variant, DT_S, J_KG_M2);
    ladrc_axis_t axis;
    const ladrc_status_t status = ladrc_axis_init(&axis, &cfg);
    if (status != LADRC_OK) {
        fprintf(stderr, "axis_loop: init failed: %s\n", ladrc_status_str(status));
        return 1;
    }
    ladrc_axis_reset(&axis, 0.0f);

    double angle = 0.0;
    double rate = 0.0;
    res->settling_s = 0.0;
    res->peak_dist_deg = 0.0;
    const double step = 10.0 * DEG;
    for (int k = 0; k < 3000; ++k) {
        const double t = k * (double)DT_S;
        const double ref = (t >= 0.5) ? step : 0.0;
        const double dist = (t >= 1.5) ? 8.0 : 0.0;
        /* the tick: measure, step the controller, drive the motors */
        const ladrc_real_t rate_meas = (ladrc_real_t)rate;
        ladrc_real_t cmd;
        (void)ladrc_axis_step(&axis, (ladrc_real_t)ref, (ladrc_real_t)angle, &rate_meas, &cmd); /* flags: get_faults */
        const ladrc_real_t applied = ladrc_clamp(cmd, -TORQUE_LIMIT_NM, TORQUE_LIMIT_NM);
        ladrc_axis_set_applied(&axis, applied); /* what the motors really gave */
        /* the airframe over one tick (semi-implicit Euler, 10 substeps) */
        for (int i = 0; i < 10; ++i) {
            const double accel = ((double)applied - KT_NM_S * rate) / (double)J_KG_M2 + dist;
            rate += accel * (double)DT_S / 10.0;
            angle += rate * (double)DT_S / 10.0;
        }
        const double err = fabs(ref - angle);
        if (t >= 0.5 && t < 1.5 && err > 0.02 * step) {
            res->settling_s = t - 0.5;
        }
        if (t >= 1.5 && err / DEG > res->peak_dist_deg) {
            res->peak_dist_deg = err / DEG;
        }
        res->final_err_deg = err / DEG;
    }
    return 0;
}

int main(void)
{
    const ladrc_variant_t variants[] = {LADRC_VARIANT_LADRC, LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_HP_MLADRC,
                                        LADRC_VARIANT_PID};
    const char *const names[] = {"LADRC", "LP-MLADRC", "HP-MLADRC", "PID"};
    printf("10 deg step at 0.5 s, 8 rad/s^2 disturbance from 1.5 s, |torque| <= %.2f N m\n", (double)TORQUE_LIMIT_NM);
    printf("%-10s %16s %30s %18s\n", "", "settling 2% (s)", "peak error, disturbance (deg)", "final error (deg)");
    for (unsigned i = 0; i < 4; ++i) {
        result_t res;
        if (run(variants[i], &res) != 0) {
            return 1;
        }
        printf("%-10s %16.3f %30.3f %18.5f\n", names[i], res.settling_s, res.peak_dist_deg, res.final_err_deg);
    }
    return 0;
}
