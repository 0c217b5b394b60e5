/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the benchmarks run, shared by bench_m4f.c (instructions on the
 * Cortex-M4F) and bench_host.c (host time and callgrind counts): the inputs,
 * the four variants, the mixer and one tick of each case.
 *
 * Inputs are precomputed before timing: the paper's references
 * (roll 5 + 15 cos(pi t / 2) deg, pitch 10 cos(pi t / 2) deg, yaw 0) and a
 * measured angle that lags and carries the response to the Table 2
 * disturbance 20 -/+ 120 sin(3 t) rad/s^2, with its rate, from t = 12 s.
 * A case runs BENCH_WARMUP ticks from reset, then the measured BENCH_TICKS.
 */
#ifndef LADRC_BENCH_CASE_H
#define LADRC_BENCH_CASE_H

#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/mixer.h"

#define BENCH_TICKS 2000
#define BENCH_WARMUP 500
#define BENCH_SAMPLES (BENCH_WARMUP + BENCH_TICKS)
#define BENCH_DT_S 0.001f
#define BENCH_VARIANTS 4

extern ladrc_real_t bench_ref[BENCH_SAMPLES][LADRC_AXES];  /* rad */
extern ladrc_real_t bench_ang[BENCH_SAMPLES][LADRC_AXES];  /* rad */
extern ladrc_real_t bench_rate[BENCH_SAMPLES][LADRC_AXES]; /* rad/s */

extern const char *const bench_variant_name[BENCH_VARIANTS]; /* PID, LADRC, LP-MLADRC, HP-MLADRC */
extern const ladrc_variant_t bench_variant_id[BENCH_VARIANTS];
extern const ladrc_real_t bench_inertia[LADRC_AXES];        /* kg m^2 */
extern const ladrc_mixer_config_t bench_mixer_cfg;

/** Fills bench_ref, bench_ang and bench_rate. */
void bench_make_inputs(void);

/** Single-axis case: the variant's default config on the roll inertia, reset
 *  at the first angle. @return 0, or -1 if init failed */
int bench_setup_axis(ladrc_axis_t *axis, int variant);

/** 3-axis case: the variant's default attitude config (drag 0.09 N m s) and the
 *  mixer, reset at the first angles. @return 0, or -1 if init failed */
int bench_setup_attitude(ladrc_attitude_t *att, ladrc_mixer_t *mixer, int variant);

/* One tick of sample i. Inline so that a timed loop pays the controller's
 * calls as firmware would, and nothing more. */
static inline ladrc_real_t bench_axis_tick(ladrc_axis_t *axis, int i)
{
    return ladrc_axis_step_with_rate(axis, bench_ref[i][0], bench_ang[i][0], bench_rate[i][0]);
}

/* 3 axes + mixer: attitude step, thrust from the tilt, mix, the achieved
 * torques back to the observers. */
static inline ladrc_real_t bench_attitude_tick(ladrc_attitude_t *att, ladrc_mixer_t *mixer, int i)
{
    ladrc_real_t torque[LADRC_AXES];
    ladrc_mixer_output_t out;
    (void)ladrc_attitude_step(att, bench_ref[i], bench_ang[i], bench_rate[i], torque);
    (void)ladrc_mixer_step(mixer, ladrc_mixer_thrust_from_tilt(mixer, bench_ang[i][0], bench_ang[i][1]),
                           torque, &out);
    ladrc_attitude_set_applied(att, out.torque_Nm);
    return out.w_rad_s[0];
}

/* The loop without the controller: loads the same inputs, no call. */
static inline ladrc_real_t bench_empty_tick(int i)
{
    return bench_ref[i][0] + bench_ang[i][0] + bench_rate[i][0];
}

#endif /* LADRC_BENCH_CASE_H */
