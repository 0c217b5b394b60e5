/* SPDX-License-Identifier: BSD-3-Clause */
/* Reference trace for the Python binding's test (tests/python/test_binding.py):
 * closed loops on simple float plants, each tick's inputs and outputs written
 * as the hex bits of the reals. The Python side replays the inputs through
 * the binding and must get the same bits.
 *
 * Usage: ladrc_binding_trace FILE */
#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/mixer.h"

#include <inttypes.h>
#include <stdio.h>
#include <string.h>

#define DT_S LADRC_R(0.001)
#define AXIS_TICKS 3000
#define ATT_TICKS 2000

static void put(FILE *f, ladrc_real_t x)
{
#ifdef LADRC_REAL_DOUBLE
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    fprintf(f, " %016" PRIx64, u);
#else
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    fprintf(f, " %08" PRIx32, u);
#endif
}

/* The overrides the Python test applies through its dict (keep in step). */
static void axis_overrides(ladrc_axis_config_t *cfg)
{
    cfg->wc_rad_s = LADRC_R(18.0);
    cfg->u_min_Nm = LADRC_R(-0.05);
    cfg->u_max_Nm = LADRC_R(0.05);
    cfg->motor_tau_s = LADRC_R(0.02); /* the actuator model and the wrap in the mirror */
    cfg->delay_ticks = 2u;
    cfg->wrap_angle = 1u;
    if (cfg->variant == LADRC_VARIANT_HP_MLADRC) {
        cfg->hp_freq_mode = LADRC_HP_FREQ_ONLINE;
    }
    if (cfg->variant == LADRC_VARIANT_PID) {
        cfg->pid_kp = LADRC_R(0.2);
    }
    if (cfg->variant == LADRC_VARIANT_INDI) {
        cfg->indi_rate_kp_per_s = LADRC_R(25.0);
    }
    if (cfg->variant == LADRC_VARIANT_RATE_ADRC) {
        cfg->radrc_kp_per_s = LADRC_R(30.0); /* the radrc_ block in the mirror */
        cfg->radrc_att_kp_per_s = LADRC_R(8.0);
        cfg->radrc_rate_max_rad_s = LADRC_R(2.0);
    }
    if (cfg->variant == LADRC_VARIANT_CASCADED) {
        cfg->cas_att_kp = LADRC_R(6.0); /* the cas_ block in the mirror */
        cfg->cas_rate_max_rad_s = LADRC_R(2.0);
        cfg->cas_i_limit_Nm = LADRC_R(0.01);
    }
}

static int trace_axis(FILE *f, ladrc_variant_t variant)
{
    const ladrc_real_t j = LADRC_R(5.445e-3);
    ladrc_axis_config_t cfg;
    ladrc_axis_t axis;
    ladrc_real_t angle = LADRC_R(0.0);
    ladrc_real_t rate = LADRC_R(0.0);
    int k;

    ladrc_axis_config_default(&cfg, variant, DT_S, j);
    axis_overrides(&cfg);
    if (ladrc_axis_init(&axis, &cfg) != LADRC_OK) {
        return 1;
    }
    for (k = 0; k < AXIS_TICKS; ++k) {
        const ladrc_real_t ref = (k >= 100) ? LADRC_R(0.2) : LADRC_R(0.0);
        /* 20 + 60 sin-like triangle disturbance (rad/s^2) from 1.5 s */
        const ladrc_real_t dist =
            (k >= 1500) ? LADRC_R(20.0) + LADRC_R(0.06) * (ladrc_real_t)((k % 1000) - 500) : LADRC_R(0.0);
        ladrc_real_t u;
        (void)ladrc_axis_step(&axis, ref, angle, &rate, &u);
        ladrc_axis_set_applied(&axis, u);
        fprintf(f, "axis %d", (int)variant);
        put(f, ref);
        put(f, angle);
        put(f, rate);
        put(f, u);
        fprintf(f, " %u\n", (unsigned)ladrc_axis_get_faults(&axis));
        rate += DT_S * (u / j + dist);
        angle += DT_S * rate;
    }
    return 0;
}

static int trace_attitude(FILE *f)
{
    static const ladrc_real_t inertia[3] = {LADRC_R(5.445e-3), LADRC_R(5.445e-3), LADRC_R(1.089e-2)};
    ladrc_mixer_config_t mix;
    ladrc_attitude_config_t cfg;
    ladrc_attitude_t att;
    ladrc_mixer_t mixer;
    ladrc_mixer_output_t out;
    ladrc_real_t angle[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    ladrc_real_t rate[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    int k;
    int i;

    mix.kL_N_s2 = LADRC_R(2.98e-5);
    mix.arm_m = LADRC_R(0.165);
    mix.b_Nm_s2 = LADRC_R(2e-6);
    mix.mass_kg = LADRC_R(0.8);
    mix.g_m_s2 = LADRC_R(9.81);
    mix.w2_min_rad2_s2 = LADRC_R(6.2e4);
    mix.w2_max_rad2_s2 = LADRC_R(6.9e4);
    mix.tilt_max_rad = LADRC_R(0.7);
    mix.mode = LADRC_MIXER_SATURATE;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, DT_S, inertia, LADRC_R(0.09));
    for (i = 0; i < 3; ++i) {
        cfg.axis[i].wc_rad_s = LADRC_R(16.0);
    }
    if (ladrc_attitude_init(&att, &cfg, NULL) != LADRC_OK || ladrc_mixer_init(&mixer, &mix) != LADRC_OK) {
        return 1;
    }
    for (k = 0; k < ATT_TICKS; ++k) {
        const ladrc_real_t ref[3] = {(k >= 100) ? LADRC_R(0.3) : LADRC_R(0.0),
                                     (k >= 600) ? LADRC_R(-0.1) : LADRC_R(0.0),
                                     (k >= 1100) ? LADRC_R(0.5) : LADRC_R(0.0)};
        ladrc_real_t torque[3];
        const ladrc_fault_t faults = ladrc_attitude_step(&att, ref, angle, rate, torque);
        const ladrc_real_t thrust = ladrc_mixer_thrust_from_tilt(&mixer, angle[0], angle[1]);
        (void)ladrc_mixer_step(&mixer, thrust, torque, &out);
        ladrc_attitude_set_applied(&att, out.torque_Nm);
        fprintf(f, "att");
        for (i = 0; i < 3; ++i) {
            put(f, ref[i]);
        }
        for (i = 0; i < 3; ++i) {
            put(f, angle[i]);
        }
        for (i = 0; i < 3; ++i) {
            put(f, rate[i]);
        }
        for (i = 0; i < 3; ++i) {
            put(f, torque[i]);
        }
        put(f, thrust);
        for (i = 0; i < 4; ++i) {
            put(f, out.w2_rad2_s2[i]);
        }
        for (i = 0; i < 3; ++i) {
            put(f, out.torque_Nm[i]);
        }
        fprintf(f, " %u %u\n", (unsigned)faults, (unsigned)out.saturated);
        for (i = 0; i < 3; ++i) {
            rate[i] += DT_S * (out.torque_Nm[i] / inertia[i] + ((k >= 1400) ? LADRC_R(8.0) : LADRC_R(0.0)));
            angle[i] += DT_S * rate[i];
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    FILE *f;
    int bad = 0;
    int v;

    if (argc != 2 || (f = fopen(argv[1], "w")) == NULL) {
        fprintf(stderr, "usage: ladrc_binding_trace FILE\n");
        return 2;
    }
    fprintf(f, "real %u\n", (unsigned)sizeof(ladrc_real_t));
    for (v = 0; v < (int)LADRC_VARIANT_COUNT; ++v) {
        bad |= trace_axis(f, (ladrc_variant_t)v);
    }
    bad |= trace_attitude(f);
    if (fclose(f) != 0 || bad) {
        fprintf(stderr, "ladrc_binding_trace: init failed or write error\n");
        return 1;
    }
    return 0;
}
