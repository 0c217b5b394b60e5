/* SPDX-License-Identifier: BSD-3-Clause */
/* The glue between Betaflight's pid.c and the rate-loop adapter: the one
 * instance (a static, as pid.c keeps its pidRuntime), set up on the first
 * tick from the parameters apply.sh compiled in (ladrc_rate_params.h). */
#include "ladrc_bf_hook.h"

#include "ladrc_rate.h"
#include "ladrc_rate_params.h"

#ifdef SIMULATOR_BUILD
#include <stdio.h>
#include <stdlib.h>
#endif

static const ladrc_bf_rate_params_t ladrcParams = LADRC_BF_RATE_PARAMS;

static ladrc_bf_rate_t ladrcRate;
static bool ladrcTried;   /* init attempted */
static bool ladrcRefused; /* the parameters were refused: Betaflight's PID flies */
static bool ladrcAtRest;  /* reset since the last active tick */

static void ladrcSetUp(float dtS)
{
    const ladrc_status_t status = ladrc_bf_rate_init(&ladrcRate, &ladrcParams, dtS);
    ladrcTried = true;
    ladrcRefused = (status != LADRC_OK);
    ladrcAtRest = true;
#ifdef SIMULATOR_BUILD
    if (ladrcRefused) {
        fprintf(stderr, "ladrc_rate_params.h: parameters refused at a %.6f s loop: %s\n", (double)dtS,
                ladrc_status_str(status));
        exit(EXIT_FAILURE);
    }
    printf(
        "[ladrc] rate loop on: k_w %.1f %.1f %.1f /s, wo %.1f %.1f %.1f rad/s, b0 %.5g %.5g %.5g rad/s^2 per pidSum, "
        "loop %.6f s\n",
        (double)ladrcParams.k_w_per_s[0], (double)ladrcParams.k_w_per_s[1], (double)ladrcParams.k_w_per_s[2],
        (double)ladrcParams.wo_rad_s[0], (double)ladrcParams.wo_rad_s[1], (double)ladrcParams.wo_rad_s[2],
        (double)ladrcParams.b0_rad_s2_per_pidsum[0], (double)ladrcParams.b0_rad_s2_per_pidsum[1],
        (double)ladrcParams.b0_rad_s2_per_pidsum[2], (double)dtS);
    fflush(stdout); /* a simulator's log is a file: seen even if the SITL is killed */
#endif
}

float ladrcRatePidSum(int axis, float setpointDegS, float gyroDegS, float dtS, bool active, float nativeSum)
{
    if (!ladrcTried) {
        ladrcSetUp(dtS);
    }
    if (ladrcRefused) {
        return nativeSum;
    }
    if (!active) {
        if (!ladrcAtRest) {
            ladrc_bf_rate_reset(&ladrcRate);
            ladrcAtRest = true;
        }
        return 0.0f;
    }
    ladrcAtRest = false;
    return ladrc_bf_rate_step(&ladrcRate, axis, setpointDegS, gyroDegS, dtS);
}
