/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The library as an HP-MLADRC quadrotor firmware links it: the 3-axis
 * controller and the mixer from their defaults, the status text of a failed
 * init, and the control loop. Built like the library (-Os, one section per
 * function) and linked with --gc-sections; tools/bench.sh reads the link map
 * for the bytes of libladrc.a this image carries. It is linked, never run.
 * Linked against the lean HP build (ladrc_fw_hp_lean: no online frequency
 * search) it tells the estimators their frequency instead.
 */
#include "bench_case.h"

static volatile ladrc_real_t sensor_rad[LADRC_AXES];
static volatile ladrc_real_t gyro_rad_s[LADRC_AXES];
static volatile ladrc_real_t rotor_cmd_rad_s[4];
static volatile const char *init_error;

int main(void)
{
    static ladrc_attitude_config_t cfg;
    static ladrc_attitude_t att;
    static ladrc_mixer_t mixer;
    int bad_axis = -1;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, 0.001f, bench_inertia, 0.09f);
#if !LADRC_WITH_HP_ONLINE
    for (int a = 0; a < LADRC_AXES; ++a) {
        cfg.axis[a].hp_freq_mode = LADRC_HP_FREQ_KNOWN;
        cfg.axis[a].hp_n_tones = 1u;
        cfg.axis[a].hp_freq_rad_s[0] = BENCH_TONE1_RAD_S;
    }
#endif
    ladrc_status_t status = ladrc_attitude_init(&att, &cfg, &bad_axis);
    if (status == LADRC_OK) {
        status = ladrc_mixer_init(&mixer, &bench_mixer_cfg);
    }
    if (status != LADRC_OK) {
        init_error = ladrc_status_str(status);
        return 1;
    }
    const ladrc_real_t ref_rad[LADRC_AXES] = {0.0f, 0.0f, 0.0f};
    for (;;) {
        ladrc_real_t angle[LADRC_AXES];
        ladrc_real_t rate[LADRC_AXES];
        ladrc_real_t torque_Nm[LADRC_AXES];
        ladrc_mixer_output_t out;
        for (int a = 0; a < LADRC_AXES; ++a) {
            angle[a] = sensor_rad[a];
            rate[a] = gyro_rad_s[a];
        }
        (void)ladrc_attitude_step(&att, ref_rad, angle, rate, torque_Nm);
        (void)ladrc_mixer_step(&mixer, ladrc_mixer_thrust_from_tilt(&mixer, angle[0], angle[1]), torque_Nm, &out);
        ladrc_attitude_set_applied(&att, out.torque_Nm);
        for (int r = 0; r < 4; ++r) {
            rotor_cmd_rad_s[r] = out.w_rad_s[r];
        }
    }
}
