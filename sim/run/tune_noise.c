/* SPDX-License-Identifier: BSD-3-Clause */
#include "tune_noise.h"

void sim_tune_noise_request(const sim_scenario_t *sc, ladrc_margins_request_t *req)
{
    req->angle_noise_std_rad = sc->angle_noise_std_rad;
    req->rate_noise_std_rad_s = sc->rate_noise_std_rad_s;
    req->noise_corner_hz = LADRC_MARGINS_NOISE_CORNER_HZ;
}
