/* SPDX-License-Identifier: BSD-3-Clause */
/* The tiny application of the consumer tests (tools/consumer_test.sh) and the
 * cross stage's link check: the attitude controller and the mixer, set up
 * and stepped once. No stdio, so it links on bare-metal targets too; the exit
 * status is the result (0 = initialised and stepped to finite torques). */
#include "ladrc/attitude.h"
#include "ladrc/mixer.h"
#ifdef LADRC_CONSUMER_HAS_VERSION
#include "ladrc/version.h"
#if LADRC_VERSION_MAJOR != 0 || LADRC_VERSION_MINOR < 2
#error "ladrc/version.h: expected 0.2 or later"
#endif
#endif

int main(void)
{
    static const ladrc_real_t inertia[3] = {LADRC_R(5.445e-3), LADRC_R(5.445e-3), LADRC_R(1.089e-2)};
    static const ladrc_real_t ref[3] = {LADRC_R(0.1), LADRC_R(0.0), LADRC_R(0.0)};
    static const ladrc_real_t angle[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    static ladrc_attitude_t att;
    static ladrc_mixer_t mixer;
    ladrc_attitude_config_t cfg;
    ladrc_mixer_config_t mix;
    ladrc_mixer_output_t out;
    ladrc_real_t torque[3];
    int i;

    mix.kL_N_s2 = LADRC_R(2.98e-5);
    mix.arm_m = LADRC_R(0.165);
    mix.b_Nm_s2 = LADRC_R(2e-6);
    mix.mass_kg = LADRC_R(0.8);
    mix.g_m_s2 = LADRC_R(9.81);
    mix.w2_min_rad2_s2 = LADRC_R(1e4);
    mix.w2_max_rad2_s2 = LADRC_R(2e5);
    mix.tilt_max_rad = LADRC_R(0.7);
    mix.mode = LADRC_MIXER_SATURATE;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, LADRC_R(0.001), inertia, LADRC_R(0.09));
    if (ladrc_attitude_init(&att, &cfg, NULL) != LADRC_OK || ladrc_mixer_init(&mixer, &mix) != LADRC_OK) {
        return 1;
    }
    if (ladrc_attitude_step(&att, ref, angle, NULL, torque) != LADRC_FAULT_NONE) {
        return 2;
    }
    (void)ladrc_mixer_step(&mixer, ladrc_mixer_thrust_from_tilt(&mixer, angle[0], angle[1]), torque, &out);
    ladrc_attitude_set_applied(&att, out.torque_Nm);
    for (i = 0; i < 3; ++i) {
        if (!ladrc_is_finite(torque[i])) {
            return 3;
        }
    }
    return (torque[0] > LADRC_R(0.0)) ? 0 : 4;
}
