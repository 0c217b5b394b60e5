/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the benchmarks run, shared by bench_m4f.c (instructions on the
 * Cortex-M4F) and bench_host.c (host time and callgrind counts): the inputs,
 * the cases, the mixer and one tick of each case.
 *
 * Inputs are precomputed before timing: the paper's references
 * (roll 5 + 15 cos(pi t / 2) deg, pitch 10 cos(pi t / 2) deg, yaw 0) from
 * t = 12 s and the angles and rates of a closed loop flown by the HP-MLADRC
 * controller itself (bench_make_inputs): a rigid body with the paper's
 * inertia, rotational drag and gyroscopic coupling under a disturbance of one
 * or two tones, controlled from reset by the same code and inputs a timed
 * HP-MLADRC case runs, so that a timed HP-MLADRC case repeats that closed
 * loop exactly and its estimator takes its engaged path (compensation weight
 * 1, the tones locked) over the measured ticks; bench_make_inputs checks it.
 * The other variants see the same angles (open loop). HP-MLADRC-gyro flies
 * its own closed loop (BENCH_GYRO_LOOP) the same way, with the actuator it
 * models in the plant: on the observer loop's angles its 3-axis fit never
 * engages (its LP estimator reads the rate against its own torque, which did
 * not move that body).
 *
 * A case runs BENCH_WARMUP ticks from reset, then the measured BENCH_TICKS.
 */
#ifndef LADRC_BENCH_CASE_H
#define LADRC_BENCH_CASE_H

#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/mixer.h"

#define BENCH_TICKS 2000
/* The estimator engages about 1.3 s (one tone) to 6 s (two tones on the
 * lone axis) after a reset and keeps a longer memory 1 s after that: 8 s of
 * warm-up reach the steady state. */
#define BENCH_WARMUP 8000
#define BENCH_SAMPLES (BENCH_WARMUP + BENCH_TICKS)
#define BENCH_DT_S 0.001f
#define BENCH_T0_S 12.0f

/* Disturbances of the recorded closed loops (rad/s^2, t in s): */
#define BENCH_ONE_TONE                                                                                                 \
    0                     /* the paper's (Table 2, from 12 s): roll 20 - 120 sin(3 t), pitch 20 + 120 sin(3 t),
                             yaw a quarter of roll's (within the rotor limits) */
#define BENCH_TWO_TONES 1 /* the same plus 30 sin(8 t) (yaw: a quarter) */
#define BENCH_DISTURBANCES 2
/* The recorded closed loops (bench_in's index, a case's inputs): HP-MLADRC
 * under BENCH_ONE_TONE and BENCH_TWO_TONES (the same numbers), and
 * HP-MLADRC-gyro under BENCH_ONE_TONE with its actuator model (a first-order
 * torque lag of BENCH_ACT_MOTOR_TAU_S after BENCH_ACT_DELAY_TICKS ticks of
 * delay) in the plant. */
#define BENCH_GYRO_LOOP 2
#define BENCH_LOOPS 3
/* Their tones (rad/s): the paper's, and the second of the two-tone case. */
#define BENCH_TONE1_RAD_S 3.0f
#define BENCH_TONE2_RAD_S 8.0f

/* The angles and rates of one recorded loop, 3 axes and one axis. */
typedef struct {
    ladrc_real_t ang[BENCH_SAMPLES][LADRC_AXES];  /* 3 axes + mixer, rad */
    ladrc_real_t rate[BENCH_SAMPLES][LADRC_AXES]; /* rad/s */
    ladrc_real_t axis_ang[BENCH_SAMPLES];         /* one axis (roll inertia and disturbance), rad */
    ladrc_real_t axis_rate[BENCH_SAMPLES];        /* rad/s */
} bench_inputs_t;

/* How the HP-MLADRC estimators of a recorded closed loop behaved over the
 * measured ticks (all three axes, or the one axis). */
typedef struct {
    float weight_min;              /* smallest compensation weight */
    unsigned tones_min, tones_max; /* active tones */
    int engaged_from;              /* first tick from which every weight stays 1 to the end */
    int saturated;                 /* 3 axes: measured ticks on which the mixer cut something back */
} bench_engagement_t;

extern ladrc_real_t bench_ref[BENCH_SAMPLES][LADRC_AXES]; /* rad */
extern bench_inputs_t bench_in[BENCH_LOOPS];
extern bench_engagement_t bench_engaged_attitude[BENCH_LOOPS];
extern bench_engagement_t bench_engaged_axis[BENCH_LOOPS];
/* The case each loop flies, its disturbance (BENCH_ONE_TONE or
 * BENCH_TWO_TONES) and the tones its estimators must hold engaged. */
extern const int bench_loop_case[BENCH_LOOPS];
extern const int bench_loop_disturbance[BENCH_LOOPS];
extern const unsigned bench_loop_tones[BENCH_LOOPS];

/* The cases: PID, LADRC, LP-MLADRC, HP-MLADRC, CASCADED, INDI, RATE-ADRC and the -act ones on the one-tone
 * inputs, HP-MLADRC-2tones: HP-MLADRC on the two-tone inputs, HP-MLADRC-gyro on its own loop's. */
#define BENCH_CASES 11
#define BENCH_CASE_HP 3
#define BENCH_CASE_HP2 4
/* HP-MLADRC-act: the one-tone HP case with the actuator model on every axis
 * (motor_tau_s = 30 ms, delay_ticks = 2): its cost against HP-MLADRC. */
#define BENCH_CASE_HP_ACT 5
#define BENCH_ACT_MOTOR_TAU_S 0.03f
#define BENCH_ACT_DELAY_TICKS 2u
/* CASCADED: the attitude P / rate PID baseline on the one-tone inputs. */
#define BENCH_CASE_CASCADED 6
/* INDI: its default config on the one-tone inputs (with their measured rates). */
#define BENCH_CASE_INDI 7
/* LADRC-act: plain LADRC with the same actuator model: the model's own cost
 * (HP-MLADRC-act adds HP's command advanced over the actuator). */
#define BENCH_CASE_LADRC_ACT 8
/* RATE-ADRC: its default config on the one-tone inputs (with their measured rates). */
#define BENCH_CASE_RATE_ADRC 9
/* HP-MLADRC-gyro: HP-MLADRC with hp_sample = LADRC_HP_SAMPLE_GYRO (its fit on
 * an LP estimator's residual of the measured rate) and the actuator model of
 * HP-MLADRC-act, as it flies on an airframe with real motors. */
#define BENCH_CASE_HP_GYRO 10
extern const char *const bench_case_name[BENCH_CASES];
extern const ladrc_variant_t bench_case_variant[BENCH_CASES];
extern const int bench_case_inputs[BENCH_CASES];     /* the loop: BENCH_ONE_TONE, BENCH_TWO_TONES, BENCH_GYRO_LOOP */
extern const ladrc_real_t bench_inertia[LADRC_AXES]; /* kg m^2 */
extern const ladrc_mixer_config_t bench_mixer_cfg;

/** Disturbance of BENCH_ONE_TONE or BENCH_TWO_TONES on an axis at time t (s), rad/s^2. */
ladrc_real_t bench_disturbance(int which, int axis, ladrc_real_t t_s);

/** Fills bench_ref and flies the closed loops into bench_in, filling
 *  bench_engaged_*. @return 0, or -1 if an init failed */
int bench_make_inputs(void);

/** Single-axis case: the variant's default config on the roll inertia, reset
 *  at the first angle. @return 0, or -1 if init failed */
int bench_setup_axis(ladrc_axis_t *axis, int bench_case);

/** 3-axis case: the variant's default attitude config (drag 0.09 N m s) and the
 *  mixer, reset at the first angles. @return 0, or -1 if init failed */
int bench_setup_attitude(ladrc_attitude_t *att, ladrc_mixer_t *mixer, int bench_case);

/* One tick of sample i. Inline so that a timed loop pays the controller's
 * calls as firmware would, and nothing more. */
static inline ladrc_real_t bench_axis_tick(ladrc_axis_t *axis, const bench_inputs_t *in, int i)
{
    ladrc_real_t torque_Nm;
    (void)ladrc_axis_step(axis, bench_ref[i][0], in->axis_ang[i], &in->axis_rate[i], &torque_Nm);
    return torque_Nm;
}

/* 3 axes + mixer: attitude step, thrust from the tilt, mix, the achieved
 * torques back to the observers. */
static inline ladrc_real_t bench_attitude_tick(ladrc_attitude_t *att, ladrc_mixer_t *mixer, const bench_inputs_t *in,
                                               int i)
{
    ladrc_real_t torque[LADRC_AXES];
    ladrc_mixer_output_t out;
    (void)ladrc_attitude_step(att, bench_ref[i], in->ang[i], in->rate[i], torque);
    (void)ladrc_mixer_step(mixer, ladrc_mixer_thrust_from_tilt(mixer, in->ang[i][0], in->ang[i][1]), torque, &out);
    ladrc_attitude_set_applied(att, out.torque_Nm);
    return out.w_rad_s[0];
}

/* The loop without the controller: loads the same inputs, no call. */
static inline ladrc_real_t bench_empty_tick(const bench_inputs_t *in, int i)
{
    return bench_ref[i][0] + in->ang[i][0] + in->rate[i][0];
}

#endif /* LADRC_BENCH_CASE_H */
