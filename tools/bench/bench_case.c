/* SPDX-License-Identifier: BSD-3-Clause */
/* Inputs and setup of the benchmark cases (see bench_case.h). */
#include "bench_case.h"

#include <math.h>

#define PI_F 3.14159265f
#define DEG 0.0174532925f

ladrc_real_t bench_ref[BENCH_SAMPLES][LADRC_AXES];
ladrc_real_t bench_ang[BENCH_SAMPLES][LADRC_AXES];
ladrc_real_t bench_rate[BENCH_SAMPLES][LADRC_AXES];

const char *const bench_variant_name[BENCH_VARIANTS] = {"PID", "LADRC", "LP-MLADRC", "HP-MLADRC"};
const ladrc_variant_t bench_variant_id[BENCH_VARIANTS] = {
    LADRC_VARIANT_PID, LADRC_VARIANT_LADRC, LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_HP_MLADRC};
const ladrc_real_t bench_inertia[LADRC_AXES] = {5.445e-3f, 5.445e-3f, 1.089e-2f};

/* Saturating mixer with rotor limits, as flown (the paper's is ideal). */
const ladrc_mixer_config_t bench_mixer_cfg = {
    .kL_N_s2 = 2.98e-5f, .arm_m = 0.165f, .b_Nm_s2 = 2e-6f, .mass_kg = 0.8f, .g_m_s2 = 9.81f,
    .w2_min_rad2_s2 = 1e4f, .w2_max_rad2_s2 = 2e5f, .tilt_max_rad = 0.7f,
    .mode = LADRC_MIXER_SATURATE};

void bench_make_inputs(void)
{
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        const float t = 12.0f + (float)i * BENCH_DT_S;
        const float c = cosf(0.5f * PI_F * t);
        const float tl = t - 0.02f; /* the vehicle follows 20 ms late */
        const float cl = cosf(0.5f * PI_F * tl), sl = sinf(0.5f * PI_F * tl);
        const float s3 = sinf(3.0f * t), c3 = cosf(3.0f * t);
        const float a = 0.004f; /* residual of the 3 rad/s disturbance, rad */
        bench_ref[i][0] = (5.0f + 15.0f * c) * DEG;
        bench_ref[i][1] = 10.0f * c * DEG;
        bench_ref[i][2] = 0.0f;
        bench_ang[i][0] = (5.0f + 15.0f * cl) * DEG + a * s3;
        bench_ang[i][1] = 10.0f * cl * DEG - a * s3;
        bench_ang[i][2] = 0.5f * a * s3;
        bench_rate[i][0] = -15.0f * 0.5f * PI_F * sl * DEG + 3.0f * a * c3;
        bench_rate[i][1] = -10.0f * 0.5f * PI_F * sl * DEG - 3.0f * a * c3;
        bench_rate[i][2] = 1.5f * a * c3;
    }
}

int bench_setup_axis(ladrc_axis_t *axis, int variant)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, bench_variant_id[variant], BENCH_DT_S, bench_inertia[0]);
    if (ladrc_axis_init(axis, &cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_axis_reset(axis, bench_ang[0][0]);
    return 0;
}

int bench_setup_attitude(ladrc_attitude_t *att, ladrc_mixer_t *mixer, int variant)
{
    ladrc_attitude_config_t cfg;
    int bad_axis = -1;
    ladrc_attitude_config_default(&cfg, bench_variant_id[variant], BENCH_DT_S, bench_inertia, 0.09f);
    if (ladrc_attitude_init(att, &cfg, &bad_axis) != LADRC_OK ||
        ladrc_mixer_init(mixer, &bench_mixer_cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_attitude_reset(att, bench_ang[0]);
    return 0;
}
