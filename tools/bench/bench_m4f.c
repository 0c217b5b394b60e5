/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Cost of one control tick on the Cortex-M4F, run under qemu mps2-an386 in
 * icount mode (qemu -icount shift=S: every instruction advances virtual time
 * by 2^S ns, so any clock that follows virtual time counts instructions).
 *
 * The clock (bench_timer.h) is SysTick on the processor clock, its rate
 * relative to instructions measured on a loop of known length. Each
 * measurement times one block of BENCH_TICKS ticks and subtracts the same
 * loop with the call removed (it still loads the inputs and stores the
 * output), so the figure includes the call, argument passing and return as
 * firmware would pay them.
 *
 * Cases (bench_case.h): each variant on one axis and on 3 axes + mixer, and
 * HP-MLADRC on a two-tone disturbance.
 * Modules: each building block of a tick timed alone the same way, on the
 * inputs it sees in a tick (see setup_modules), to show where the
 * instructions of the HP-MLADRC 3-axis tick go, and those of the
 * HP-MLADRC-gyro one (its LP estimator, lead and gyro-fed fit).
 *
 * Output: lines "BENCH key value..." for tools/bench.sh.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "bench_case.h"
#include "bench_timer.h"
#include "ladrc/estimator.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/pid.h"
#include "ladrc/reso.h"
#include "ladrc/rls.h"
#include "ladrc/td.h"

static volatile ladrc_real_t sink;

/* What a block runs. */
typedef enum {
    RUN_AXIS,      /* one axis of the current case */
    RUN_ATTITUDE,  /* 3 axes + mixer of the current case */
    RUN_LONE_AXES, /* the three HP-MLADRC axes of the 3-axis case side by side, no attitude, no mixer */
    RUN_LONE_GYRO, /* the same for the HP-MLADRC-gyro case */
    RUN_LESO,
    RUN_TWIN,
    RUN_TD,
    RUN_LEVANT,
    RUN_LP,
    RUN_LP_ACT,
    RUN_LP_LEAD,
    RUN_HP,
    RUN_HP_GYRO,
    RUN_HP2,
    RUN_RLS3,
    RUN_RLS5,
    RUN_PID,
    RUN_THRUST,
    RUN_MIXER,
    RUN_GF_NOTCH,   /* one fixed notch on one channel */
    RUN_GF_LPF2,    /* the second-order low-pass on one channel */
    RUN_GF_CENTRES, /* the RPM bank's 12 centres moved (4 rotors x 3 harmonics) */
    RUN_GF_RPM3,    /* centres moved, then the 12 notches on 3 channels */
    RUN_GF_FULL3,   /* the same with the second-order low-pass after them */
    RUN_ATT_EULER,  /* LADRC's 3 axes in the Euler frame (ladrc_attitude_step, no mixer) */
    RUN_ATT_QUAT,   /* the same in the quaternion frame on the same attitudes (ladrc_attitude_step_quat) */
    RUN_DELAY       /* one LADRC axis with a 30 ms motor and a long delay modelled (delay_axis) */
} run_t;

static ladrc_axis_t axis;
static ladrc_axis_t delay_axis;
static ladrc_attitude_t att;
static ladrc_mixer_t mixer;
static const bench_inputs_t *in;   /* inputs of the current case */
static const bench_inputs_t *gyro; /* inputs of the HP-MLADRC-gyro case */

/* The modules alone, and what they are fed. */
static struct {
    ladrc_axis_t lone[LADRC_AXES];
    ladrc_axis_t lone_gyro[LADRC_AXES];
    ladrc_leso_t leso;
    ladrc_leso_twin_t twin;
    ladrc_td_t td;
    ladrc_levant_t levant;
    ladrc_lp_estimator_t lp, lp_act; /* LP-MLADRC's; the gyro axis's (actuator model) */
    ladrc_hp_estimator_t hp, hp2, hp_gyro;
    ladrc_rls_t rls3, rls5;
    ladrc_pid_t pid;
    ladrc_mixer_t mixer;
    ladrc_mixer_output_t out;
    ladrc_gyro_filter_t gf_notch, gf_lpf2, gf_rpm3, gf_full3;
    ladrc_real_t gf_out[LADRC_AXES];
    ladrc_attitude_t att_euler, att_quat;
    ladrc_real_t torque[LADRC_AXES];
    ladrc_real_t b0;
    ladrc_real_t fit_rate_per_s, fit_rate2_per_s; /* the engaged fits' forgetting, one and two tones */
    uint16_t fit_decimation;
} mod;

/* Recorded from the HP-MLADRC 3-axis case (one tone unless named 2). */
static ladrc_real_t torque_in[BENCH_SAMPLES][LADRC_AXES];  /* commanded, N m */
static ladrc_real_t applied_in[BENCH_SAMPLES][LADRC_AXES]; /* achieved, N m */
static ladrc_real_t thrust_in[BENCH_SAMPLES];              /* N */
static ladrc_real_t known_in[BENCH_SAMPLES][LADRC_AXES];   /* known part of f told each axis, rad/s^2 */
static ladrc_real_t frate_in[BENCH_SAMPLES][LADRC_AXES];   /* fed rate h, rad/s^3 */
static ladrc_real_t dhat_in[BENCH_SAMPLES];                /* roll d_hat, rad/s^2 */
static ladrc_real_t hp_in[BENCH_SAMPLES];                  /* roll HP sample z3 - z3_shadow, rad/s^2 */
static ladrc_real_t hp2_in[BENCH_SAMPLES];
/* Recorded from the HP-MLADRC-gyro 3-axis case: what its axes are fed, and
 * roll's LP estimator's known input and its fit's sample. */
static ladrc_real_t gyro_applied_in[BENCH_SAMPLES][LADRC_AXES];
static ladrc_real_t gyro_known_in[BENCH_SAMPLES][LADRC_AXES];
static ladrc_real_t gyro_frate_in[BENCH_SAMPLES][LADRC_AXES];
static ladrc_real_t gyro_accel_in[BENCH_SAMPLES]; /* b0 times the acting torque plus the fit's estimate, rad/s^2 */
static ladrc_real_t gyro_hp_in[BENCH_SAMPLES];    /* LP's sample plus the fit's estimate, rad/s^2 */
/* Regressors and samples of the fits at the fit samples' times. */
static ladrc_real_t phi5_in[BENCH_SAMPLES][5];
/* Rotor rates for the RPM bank (Hz): four rotors each wandering +-10 %
 * about 120 Hz at its own pace, so every centre moves every tick. */
static ladrc_real_t rotor_hz_in[BENCH_SAMPLES][4];
static ladrc_real_t y3_in[BENCH_SAMPLES], y5_in[BENCH_SAMPLES];
/* The one-tone loop's attitudes and the references as quaternions (ZYX). */
static ladrc_quat_t q_meas_in[BENCH_SAMPLES], q_ref_in[BENCH_SAMPLES];

/* Ticks the block from the first sample (warm-up) or after it; "empty" runs
 * the same loop and loads with the call left out. */
#define BLOCK(call, empty)                                                                                             \
    for (int i = from; i < from + n; ++i) {                                                                            \
        if (timed) {                                                                                                   \
            call;                                                                                                      \
        } else {                                                                                                       \
            sink = (empty);                                                                                            \
        }                                                                                                              \
    }

static ladrc_real_t lone_tick(int i)
{
    ladrc_real_t u = 0.0f;
    for (int a = 0; a < LADRC_AXES; ++a) {
        ladrc_axis_set_disturbance_rate(&mod.lone[a], frate_in[i][a]);
        ladrc_axis_set_known_disturbance(&mod.lone[a], known_in[i][a]);
        (void)ladrc_axis_step(&mod.lone[a], bench_ref[i][a], in->ang[i][a], &in->rate[i][a], &u);
        ladrc_axis_set_applied(&mod.lone[a], applied_in[i][a]);
    }
    return u;
}

static ladrc_real_t lone_gyro_tick(int i)
{
    ladrc_real_t u = 0.0f;
    for (int a = 0; a < LADRC_AXES; ++a) {
        ladrc_axis_set_disturbance_rate(&mod.lone_gyro[a], gyro_frate_in[i][a]);
        ladrc_axis_set_known_disturbance(&mod.lone_gyro[a], gyro_known_in[i][a]);
        (void)ladrc_axis_step(&mod.lone_gyro[a], bench_ref[i][a], gyro->ang[i][a], &gyro->rate[i][a], &u);
        ladrc_axis_set_applied(&mod.lone_gyro[a], gyro_applied_in[i][a]);
    }
    return u;
}

static ladrc_real_t lone_gyro_empty(int i)
{
    ladrc_real_t s = 0.0f;
    for (int a = 0; a < LADRC_AXES; ++a) {
        s += gyro_frate_in[i][a] + gyro_known_in[i][a] + bench_ref[i][a] + gyro->ang[i][a] + gyro->rate[i][a] +
             gyro_applied_in[i][a];
    }
    return s;
}

static inline ladrc_real_t pid_tick(int i)
{
    ladrc_real_t torque_Nm;
    (void)ladrc_pid_step(&mod.pid, bench_ref[i][0], in->ang[i][0], &in->rate[i][0], &torque_Nm);
    return torque_Nm;
}

static ladrc_real_t lone_empty(int i)
{
    ladrc_real_t s = 0.0f;
    for (int a = 0; a < LADRC_AXES; ++a) {
        s += frate_in[i][a] + known_in[i][a] + bench_ref[i][a] + in->ang[i][a] + in->rate[i][a] + applied_in[i][a];
    }
    return s;
}

static uint32_t run(run_t what, int warm, int timed)
{
    const int from = warm ? 0 : BENCH_WARMUP;
    const int n = warm ? BENCH_WARMUP : BENCH_TICKS;
    uint32_t t0 = timer_now();
    switch (what) {
    case RUN_AXIS:
        BLOCK(sink = bench_axis_tick(&axis, in, i), bench_empty_tick(in, i));
        break;
    case RUN_DELAY:
        BLOCK(sink = bench_axis_tick(&delay_axis, in, i), bench_empty_tick(in, i));
        break;
    case RUN_ATTITUDE:
        BLOCK(sink = bench_attitude_tick(&att, &mixer, in, i), bench_empty_tick(in, i));
        break;
    case RUN_LONE_AXES:
        BLOCK(sink = lone_tick(i), lone_empty(i));
        break;
    case RUN_LONE_GYRO:
        BLOCK(sink = lone_gyro_tick(i), lone_gyro_empty(i));
        break;
    case RUN_LESO:
        BLOCK((void)ladrc_leso_step(&mod.leso, in->ang[i][0], applied_in[i][0], dhat_in[i], frate_in[i][0]),
              in->ang[i][0] + applied_in[i][0] + dhat_in[i] + frate_in[i][0]);
        break;
    case RUN_TWIN:
        BLOCK((void)ladrc_leso_step_twin(&mod.leso, &mod.twin, 0.0f, 0.0f, dhat_in[i] - known_in[i][0], frate_in[i][0]),
              dhat_in[i] - known_in[i][0] + frate_in[i][0]);
        break;
    case RUN_TD: {
        ladrc_ref_t r;
        BLOCK((void)ladrc_td_step(&mod.td, bench_ref[i][0], &r); sink = r.dr, bench_ref[i][0]);
        break;
    }
    case RUN_LEVANT: {
        ladrc_ref_t r;
        BLOCK((void)ladrc_levant_step(&mod.levant, bench_ref[i][0], &r); sink = r.dr, bench_ref[i][0]);
        break;
    }
    case RUN_LP:
        BLOCK((void)ladrc_lp_step(&mod.lp, in->rate[i][0], mod.b0 * applied_in[i][0]),
              in->rate[i][0] + mod.b0 * applied_in[i][0]);
        break;
    case RUN_LP_ACT:
        BLOCK((void)ladrc_lp_step(&mod.lp_act, gyro->rate[i][0], gyro_accel_in[i]),
              gyro->rate[i][0] + gyro_accel_in[i]);
        break;
    case RUN_LP_LEAD: {
        ladrc_real_t c;
        BLOCK((void)ladrc_lp_step_lead(&mod.lp_act, &c); sink = c, gyro->rate[i][0]);
        break;
    }
    case RUN_HP:
        BLOCK((void)ladrc_hp_step(&mod.hp, hp_in[i]), hp_in[i]);
        break;
    case RUN_HP_GYRO:
        BLOCK((void)ladrc_hp_step(&mod.hp_gyro, gyro_hp_in[i]), gyro_hp_in[i]);
        break;
    case RUN_HP2:
        BLOCK((void)ladrc_hp_step(&mod.hp2, hp2_in[i]), hp2_in[i]);
        break;
    case RUN_RLS3:
        BLOCK((void)ladrc_rls_update(&mod.rls3, phi5_in[i], y3_in[i]), phi5_in[i][1] + y3_in[i]);
        break;
    case RUN_RLS5:
        BLOCK((void)ladrc_rls_update(&mod.rls5, phi5_in[i], y5_in[i]), phi5_in[i][1] + y5_in[i]);
        break;
    case RUN_PID:
        BLOCK(sink = pid_tick(i), bench_empty_tick(in, i));
        break;
    case RUN_THRUST:
        BLOCK(sink = ladrc_mixer_thrust_from_tilt(&mod.mixer, in->ang[i][0], in->ang[i][1]),
              in->ang[i][0] + in->ang[i][1]);
        break;
    case RUN_MIXER:
        BLOCK((void)ladrc_mixer_step(&mod.mixer, thrust_in[i], torque_in[i], &mod.out), thrust_in[i] + torque_in[i][0]);
        break;
    case RUN_GF_NOTCH:
        BLOCK((void)ladrc_gyro_filter_step(&mod.gf_notch, &in->rate[i][0], mod.gf_out), in->rate[i][0]);
        break;
    case RUN_GF_LPF2:
        BLOCK((void)ladrc_gyro_filter_step(&mod.gf_lpf2, &in->rate[i][0], mod.gf_out), in->rate[i][0]);
        break;
    case RUN_GF_CENTRES:
        BLOCK((void)ladrc_gyro_filter_set_rotor_hz(&mod.gf_rpm3, rotor_hz_in[i]), rotor_hz_in[i][0]);
        break;
    case RUN_GF_RPM3:
        BLOCK((void)ladrc_gyro_filter_set_rotor_hz(&mod.gf_rpm3, rotor_hz_in[i]);
              (void)ladrc_gyro_filter_step(&mod.gf_rpm3, in->rate[i], mod.gf_out), rotor_hz_in[i][0] + in->rate[i][0]);
        break;
    case RUN_GF_FULL3:
        BLOCK((void)ladrc_gyro_filter_set_rotor_hz(&mod.gf_full3, rotor_hz_in[i]);
              (void)ladrc_gyro_filter_step(&mod.gf_full3, in->rate[i], mod.gf_out), rotor_hz_in[i][0] + in->rate[i][0]);
        break;
    case RUN_ATT_EULER:
        BLOCK((void)ladrc_attitude_step(&mod.att_euler, bench_ref[i], in->ang[i], in->rate[i], mod.torque),
              bench_ref[i][0] + in->ang[i][0] + in->rate[i][0] + q_ref_in[i].w + q_meas_in[i].w);
        break;
    case RUN_ATT_QUAT:
        BLOCK((void)ladrc_attitude_step_quat(&mod.att_quat, &q_ref_in[i], &q_meas_in[i], in->rate[i], mod.torque),
              bench_ref[i][0] + in->ang[i][0] + in->rate[i][0] + q_ref_in[i].w + q_meas_in[i].w);
        break;
    }
    return timer_since(t0);
}

/* Replays the HP-MLADRC 3-axis case of one disturbance (as bench_attitude_tick)
 * and records what its modules see; sample: roll's HP sample. Returns the
 * roll fit's forgetting rate at the end (the engaged one). */
static ladrc_real_t record_attitude(int bench_case, int full, ladrc_real_t *sample)
{
    const bench_inputs_t *r = &bench_in[bench_case_inputs[bench_case]];
    (void)bench_setup_attitude(&att, &mixer, bench_case);
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        ladrc_real_t torque[LADRC_AXES];
        ladrc_mixer_output_t out;
        const ladrc_real_t thrust = ladrc_mixer_thrust_from_tilt(&mixer, r->ang[i][0], r->ang[i][1]);
        (void)ladrc_attitude_step(&att, bench_ref[i], r->ang[i], r->rate[i], torque);
        (void)ladrc_mixer_step(&mixer, thrust, torque, &out);
        ladrc_attitude_set_applied(&att, out.torque_Nm);
        const ladrc_axis_t *roll = &att.axis[0];
        sample[i] = roll->leso.z3 - roll->part.hp.source.shadow.z3;
        if (full) {
            thrust_in[i] = thrust;
            dhat_in[i] = roll->d_hat_rad_s2;
            for (int a = 0; a < LADRC_AXES; ++a) {
                torque_in[i][a] = torque[a];
                applied_in[i][a] = out.torque_Nm[a];
                known_in[i][a] = att.axis[a].f_known_rad_s2;
                frate_in[i][a] = att.axis[a].f_rate_rad_s3;
            }
        }
    }
    return att.axis[0].part.hp.est.fit_rate_per_s;
}

/* Replays the HP-MLADRC-gyro 3-axis case (as bench_attitude_tick) and
 * records what its axes are fed and what roll's LP estimator and fit see. */
static void record_gyro(void)
{
    (void)bench_setup_attitude(&att, &mixer, BENCH_CASE_HP_GYRO);
    const ladrc_axis_t *roll = &att.axis[0];
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        /* before the tick: LP's known input of this tick */
        const ladrc_real_t fitted = ladrc_hp_get_estimate(&roll->part.hp.est);
        gyro_accel_in[i] = roll->b0 * ladrc_axis_get_acting_Nm(roll) + fitted;
        ladrc_real_t torque[LADRC_AXES];
        ladrc_mixer_output_t out;
        (void)ladrc_attitude_step(&att, bench_ref[i], gyro->ang[i], gyro->rate[i], torque);
        (void)ladrc_mixer_step(&mixer, ladrc_mixer_thrust_from_tilt(&mixer, gyro->ang[i][0], gyro->ang[i][1]), torque,
                               &out);
        ladrc_attitude_set_applied(&att, out.torque_Nm);
        gyro_hp_in[i] = ladrc_lp_get_sample(&roll->part.hp.source.lp) + fitted;
        for (int a = 0; a < LADRC_AXES; ++a) {
            gyro_applied_in[i][a] = out.torque_Nm[a];
            gyro_known_in[i][a] = att.axis[a].f_known_rad_s2;
            gyro_frate_in[i][a] = att.axis[a].f_rate_rad_s3;
        }
    }
}

/* Inputs of the modules: the torques, thrust, feeds and HP samples of the
 * HP-MLADRC 3-axis cases (replayed), and the regressors of the HP fit at its
 * sample times (bias and the phasors at 3 and 8 rad/s) with the disturbance
 * they fit. */
static void record_inputs(void)
{
    mod.fit_rate_per_s = record_attitude(BENCH_CASE_HP, 1, hp_in);
    mod.fit_rate2_per_s = record_attitude(BENCH_CASE_HP2, 0, hp2_in);
    record_gyro();
    const float period_s = (float)mod.fit_decimation * BENCH_DT_S;
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        const float t = BENCH_T0_S + (float)i * period_s;
        phi5_in[i][0] = 1.0f;
        phi5_in[i][1] = cosf(3.0f * t);
        phi5_in[i][2] = sinf(3.0f * t);
        phi5_in[i][3] = cosf(8.0f * t);
        phi5_in[i][4] = sinf(8.0f * t);
        y3_in[i] = bench_disturbance(BENCH_ONE_TONE, 0, t);
        y5_in[i] = bench_disturbance(BENCH_TWO_TONES, 0, t);
    }
}

/* ladrc_hp_config_t of a 3-axis HP axis config, as ladrc_axis_init builds it. */
/* Each module configured as the axis defaults configure it (HP-MLADRC for
 * the LESO, Levant and estimators, LADRC for TD, PID for PID), the HP axes as
 * the attitude defaults configure them. */
/* The gyro filter stages timed at the cases' control step: an RPM bank of
 * 4 rotors x 3 harmonics (Q 5, on from 20 Hz, fading in over 10 Hz; the
 * rotors near 120 Hz keep all 12 centres below the Nyquist guard), one
 * fixed notch, a second-order low-pass. */
static int setup_gyro_filters(ladrc_real_t dt_s)
{
    ladrc_gyro_filter_config_t one, rpm3, full3;
    ladrc_gyro_filter_config_default(&one, dt_s, 1u);
    ladrc_gyro_filter_config_default(&rpm3, dt_s, LADRC_AXES);
    rpm3.rpm_rotors = 4u;
    rpm3.rpm_harmonics = 3u;
    rpm3.rpm_min_hz = LADRC_R(20.0);
    rpm3.rpm_fade_hz = LADRC_R(10.0);
    full3 = rpm3;
    full3.lpf_order = 2u;
    one.lpf_order = 2u;
    if (ladrc_gyro_filter_init(&mod.gf_lpf2, &one) != LADRC_OK) {
        return -1;
    }
    one.lpf_order = 0u;
    one.n_notches = 1u;
    one.notch_hz[0] = LADRC_R(0.15) / dt_s;
    if (ladrc_gyro_filter_init(&mod.gf_notch, &one) != LADRC_OK ||
        ladrc_gyro_filter_init(&mod.gf_rpm3, &rpm3) != LADRC_OK ||
        ladrc_gyro_filter_init(&mod.gf_full3, &full3) != LADRC_OK) {
        return -1;
    }
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        for (int r = 0; r < 4; ++r) {
            rotor_hz_in[i][r] =
                LADRC_R(120.0) * (LADRC_R(1.0) + LADRC_R(0.1) * sinf(LADRC_R(0.01) * (float)(i * (r + 1))));
        }
    }
    /* every centre on from the first timed tick */
    (void)ladrc_gyro_filter_set_rotor_hz(&mod.gf_rpm3, rotor_hz_in[0]);
    (void)ladrc_gyro_filter_set_rotor_hz(&mod.gf_full3, rotor_hz_in[0]);
    return 0;
}

/* LADRC's 3 axes in both frames, on the one-tone loop's attitudes. */
static int setup_frames(void)
{
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, LADRC_VARIANT_LADRC, BENCH_DT_S, bench_inertia, 0.09f);
    if (ladrc_attitude_init(&mod.att_euler, &cfg, NULL) != LADRC_OK) {
        return -1;
    }
    ladrc_attitude_config_quaternion(&cfg);
    if (ladrc_attitude_init(&mod.att_quat, &cfg, NULL) != LADRC_OK) {
        return -1;
    }
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        q_meas_in[i] = ladrc_quat_from_euler(in->ang[i][0], in->ang[i][1], in->ang[i][2]);
        q_ref_in[i] = ladrc_quat_from_euler(bench_ref[i][0], bench_ref[i][1], bench_ref[i][2]);
    }
    ladrc_attitude_reset(&mod.att_euler, in->ang[0]);
    return 0;
}

static int setup_modules(void)
{
    ladrc_attitude_config_t hp3;
    ladrc_axis_config_t ladrc, pid;
    ladrc_attitude_config_default(&hp3, LADRC_VARIANT_HP_MLADRC, BENCH_DT_S, bench_inertia, 0.09f);
    const ladrc_axis_config_t *hp = &hp3.axis[0];
    ladrc_axis_config_default(&ladrc, LADRC_VARIANT_LADRC, BENCH_DT_S, bench_inertia[0]);
    ladrc_axis_config_default(&pid, LADRC_VARIANT_PID, BENCH_DT_S, bench_inertia[0]);
    /* HP-MLADRC-gyro's axes: the same with the gyro sample and the actuator
     * model (bench_case.c; its loop's body without drag). */
    ladrc_attitude_config_t gyro3;
    ladrc_attitude_config_default(&gyro3, LADRC_VARIANT_HP_MLADRC, BENCH_DT_S, bench_inertia, 0.0f);
    for (int a = 0; a < LADRC_AXES; ++a) {
        gyro3.axis[a].hp_sample = LADRC_HP_SAMPLE_GYRO;
        gyro3.axis[a].motor_tau_s = BENCH_ACT_MOTOR_TAU_S;
        gyro3.axis[a].delay_ticks = BENCH_ACT_DELAY_TICKS;
    }
    const ladrc_axis_config_t *hpg = &gyro3.axis[0];
    mod.b0 = hp->b0;
    mod.fit_decimation = hp->hp_fit_decimation;
    gyro = &bench_in[BENCH_GYRO_LOOP];
    record_inputs();
    in = &bench_in[BENCH_ONE_TONE];
    for (int a = 0; a < LADRC_AXES; ++a) {
        if (ladrc_axis_init(&mod.lone[a], &hp3.axis[a]) != LADRC_OK ||
            ladrc_axis_init(&mod.lone_gyro[a], &gyro3.axis[a]) != LADRC_OK) {
            return -1;
        }
        ladrc_axis_reset(&mod.lone[a], in->ang[0][a]);
        ladrc_axis_reset(&mod.lone_gyro[a], gyro->ang[0][a]);
    }
    const ladrc_leso_config_t leso = {
        .dt_s = hp->dt_s, .wo_rad_s = hp->wo_rad_s, .b0 = hp->b0, .method = hp->leso_method};
    const ladrc_td_config_t td = {.dt_s = ladrc.dt_s, .accel_rad_s2 = ladrc.td_accel_rad_s2, .h0_s = ladrc.td_h0_s};
    const ladrc_levant_config_t lev = {.dt_s = hp->dt_s,
                                       .method = hp->levant_method,
                                       .gains = LADRC_LEVANT_GAINS_LIPSCHITZ,
                                       .lipschitz_rad_s4 = hp->levant_lipschitz_rad_s4};
    const ladrc_lp_config_t lp = {.dt_s = hp->dt_s,
                                  .lambda0_per_s = hp->lp_lambda0_per_s,
                                  .k0_per_s = hp->lp_k0_per_s,
                                  .act_tau_s = hp->motor_tau_s,
                                  .act_delay_ticks = hp->delay_ticks};
    const ladrc_lp_config_t lp_act = {.dt_s = hpg->dt_s,
                                      .lambda0_per_s = hpg->lp_lambda0_per_s,
                                      .k0_per_s = hpg->lp_k0_per_s,
                                      .act_tau_s = hpg->motor_tau_s,
                                      .act_delay_ticks = hpg->delay_ticks};
    ladrc_hp_config_t hpc, hpc_gyro;
    ladrc_axis_hp_config(hp, &hpc);
    ladrc_axis_hp_config(hpg, &hpc_gyro);
    /* The HP fit as the estimator runs it engaged: P bound 1e4 and initial P
     * 1e3 per sample, its engaged forgetting rate. */
    const float t3 = (float)hp->hp_fit_decimation * hp->dt_s;
    const ladrc_rls_config_t rls3 = {
        .n_params = 3u, .dt_s = t3, .lambda0_per_s = mod.fit_rate_per_s, .p_bound = 1e4f / t3, .p_initial = 1e3f / t3};
    const ladrc_rls_config_t rls5 = {
        .n_params = 5u, .dt_s = t3, .lambda0_per_s = mod.fit_rate2_per_s, .p_bound = 1e4f / t3, .p_initial = 1e3f / t3};
    const ladrc_pid_config_t pidc = {.dt_s = pid.dt_s,
                                     .kp = pid.pid_kp,
                                     .ki = pid.pid_ki,
                                     .kd = pid.pid_kd,
                                     .d_filter_tau_s = pid.pid_d_filter_tau_s,
                                     .i_limit_Nm = pid.pid_i_limit_Nm,
                                     .u_min_Nm = pid.u_min_Nm,
                                     .u_max_Nm = pid.u_max_Nm,
                                     .wrap_angle = 0u};
    if (ladrc_leso_init(&mod.leso, &leso) != LADRC_OK || ladrc_td_init(&mod.td, &td) != LADRC_OK ||
        ladrc_levant_init(&mod.levant, &lev) != LADRC_OK || ladrc_lp_init(&mod.lp, &lp) != LADRC_OK ||
        ladrc_lp_init(&mod.lp_act, &lp_act) != LADRC_OK || ladrc_hp_init(&mod.hp, &hpc) != LADRC_OK ||
        ladrc_hp_init(&mod.hp2, &hpc) != LADRC_OK || ladrc_hp_init(&mod.hp_gyro, &hpc_gyro) != LADRC_OK ||
        ladrc_rls_init(&mod.rls3, &rls3) != LADRC_OK || ladrc_rls_init(&mod.rls5, &rls5) != LADRC_OK ||
        ladrc_pid_init(&mod.pid, &pidc) != LADRC_OK || ladrc_mixer_init(&mod.mixer, &bench_mixer_cfg) != LADRC_OK) {
        return -1;
    }
    if (setup_gyro_filters(hp->dt_s) != 0 || setup_frames() != 0) {
        return -1;
    }
    ladrc_leso_reset(&mod.leso, in->ang[0][0]);
    ladrc_leso_twin_reset(&mod.twin, 0.0f);
    ladrc_td_reset(&mod.td, bench_ref[0][0]);
    ladrc_levant_reset(&mod.levant, bench_ref[0][0]);
    ladrc_pid_reset(&mod.pid, in->ang[0][0]);
    return 0;
}

/* Warm-up, measured block, empty block; instructions per tick in hundredths. */
static uint32_t measure(run_t what, uint32_t ipc, uint32_t *counts, uint32_t *empty)
{
    (void)run(what, 1, 1);
    *counts = run(what, 0, 1);
    *empty = run(what, 0, 0);
    return per_tick_x100(*counts, *empty, ipc);
}

static void print_module(const char *name, run_t what, uint32_t ipc)
{
    uint32_t c, c0;
    const uint32_t x100 = measure(what, ipc, &c, &c0);
    printf("BENCH module %s %lu.%02lu counts %lu %lu\n", name, (unsigned long)(x100 / 100u),
           (unsigned long)(x100 % 100u), (unsigned long)c, (unsigned long)c0);
}

/* An HP estimator's state after its measured block (it should be engaged). */
static void print_hp_state(const char *name, const ladrc_hp_estimator_t *est)
{
    const float w = (float)ladrc_hp_get_weight(est);
    printf("BENCH hp_state %s weight %d.%03d tones %u\n", name, (int)w, (int)(1000.0f * (w - (float)(int)w)),
           ladrc_hp_get_active_tones(est));
}

#define SIZE_LINE(type) printf("BENCH sizeof %s %u\n", #type, (unsigned)sizeof(type))

int main(void)
{
    const uint32_t ipc = bench_calibrate("");
    if (ipc == 0u) {
        return 1;
    }

    if (bench_make_inputs() != 0) {
        printf("BENCH error: init failed while recording the inputs\n");
        return 1;
    }
    /* The HP-MLADRC cases must run their estimators engaged over the measured
     * ticks (weight 1, the disturbance's tones active). */
    for (int l = 0; l < BENCH_LOOPS; ++l) {
        static const char *const kind[2] = {"attitude", "axis"};
        const char *name = bench_case_name[bench_loop_case[l]];
        const bench_engagement_t *e[2] = {&bench_engaged_attitude[l], &bench_engaged_axis[l]};
        for (int k = 0; k < 2; ++k) {
            const unsigned tones = bench_loop_tones[l];
            printf("BENCH engaged %s %s weight_min %d.%03d tones %u %u from %d\n", name, kind[k], (int)e[k]->weight_min,
                   (int)(1000.0f * (e[k]->weight_min - (float)(int)e[k]->weight_min)), e[k]->tones_min, e[k]->tones_max,
                   e[k]->engaged_from);
            if (e[k]->weight_min < 1.0f || e[k]->tones_min != tones || e[k]->tones_max != tones) {
                printf("BENCH error: %s (%s) does not run engaged with %u tone(s) over the measured ticks\n", name,
                       kind[k], tones);
                return 1;
            }
        }
        printf("BENCH saturated %s %d\n", name, bench_engaged_attitude[l].saturated);
    }

    for (int v = 0; v < BENCH_CASES; ++v) {
        in = &bench_in[bench_case_inputs[v]];
        if (bench_setup_axis(&axis, v) != 0 || bench_setup_attitude(&att, &mixer, v) != 0) {
            printf("BENCH error: init failed for %s\n", bench_case_name[v]);
            return 1;
        }
        uint32_t ax, ax0, at, at0;
        const uint32_t ax100 = measure(RUN_AXIS, ipc, &ax, &ax0);
        const uint32_t at100 = measure(RUN_ATTITUDE, ipc, &at, &at0);
        printf("BENCH insn %s %lu.%02lu %lu.%02lu counts %lu %lu %lu %lu\n", bench_case_name[v],
               (unsigned long)(ax100 / 100u), (unsigned long)(ax100 % 100u), (unsigned long)(at100 / 100u),
               (unsigned long)(at100 % 100u), (unsigned long)ax, (unsigned long)ax0, (unsigned long)at,
               (unsigned long)at0);
        if (bench_setup_attitude(&att, &mixer, v) != 0) {
            return 1;
        }
        (void)run(RUN_ATTITUDE, 1, 1);
        printf("BENCH worst %s %lu\n", bench_case_name[v],
               (unsigned long)worst_attitude_tick(&att, &mixer, in, ipc, &sink));
    }

    if (setup_modules() != 0) {
        printf("BENCH error: init of a module failed\n");
        return 1;
    }
    printf("BENCH hp_fit_decimation %u\n", (unsigned)mod.fit_decimation);
    print_module("lone_hp_axes_x3", RUN_LONE_AXES, ipc);
    print_module("lone_hp_gyro_axes_x3", RUN_LONE_GYRO, ipc);
    print_module("ladrc_leso_step", RUN_LESO, ipc);
    print_module("ladrc_leso_step_twin", RUN_TWIN, ipc);
    print_module("ladrc_td_step", RUN_TD, ipc);
    print_module("ladrc_levant_step", RUN_LEVANT, ipc);
    print_module("ladrc_lp_step", RUN_LP, ipc);
    print_module("ladrc_lp_step_act", RUN_LP_ACT, ipc);
    print_module("ladrc_lp_step_lead", RUN_LP_LEAD, ipc);
    print_module("ladrc_hp_step", RUN_HP, ipc);
    print_hp_state("ladrc_hp_step", &mod.hp);
    print_module("ladrc_hp_step_2tones", RUN_HP2, ipc);
    print_hp_state("ladrc_hp_step_2tones", &mod.hp2);
    print_module("ladrc_hp_step_gyro", RUN_HP_GYRO, ipc);
    print_hp_state("ladrc_hp_step_gyro", &mod.hp_gyro);
    print_module("ladrc_rls_update_3", RUN_RLS3, ipc);
    print_module("ladrc_rls_update_5", RUN_RLS5, ipc);
    print_module("ladrc_pid_step", RUN_PID, ipc);
    print_module("ladrc_mixer_thrust_from_tilt", RUN_THRUST, ipc);
    print_module("ladrc_mixer_step", RUN_MIXER, ipc);
    print_module("ladrc_gyro_filter_step_notch_1ch", RUN_GF_NOTCH, ipc);
    print_module("ladrc_gyro_filter_step_lpf2_1ch", RUN_GF_LPF2, ipc);
    print_module("ladrc_gyro_filter_set_rotor_hz_4x3", RUN_GF_CENTRES, ipc);
    print_module("gyro_filter_rpm_4x3_3ch", RUN_GF_RPM3, ipc);
    print_module("gyro_filter_rpm_4x3_lpf2_3ch", RUN_GF_FULL3, ipc);
    print_module("attitude_step_ladrc_euler", RUN_ATT_EULER, ipc);
    print_module("attitude_step_ladrc_quat", RUN_ATT_QUAT, ipc);
    for (int a = 0; a < LADRC_AXES; ++a) {
        print_hp_state("lone_hp_axis", &mod.lone[a].part.hp.est);
    }
    for (int a = 0; a < LADRC_AXES; ++a) {
        print_hp_state("lone_hp_gyro_axis", &mod.lone_gyro[a].part.hp.est);
    }

    /* A long delay modelled: 20 and 50 ms at 1, 2, 4 and 8 kHz (d = 20 .. 400),
     * one LADRC axis with a 30 ms motor on the one-tone axis inputs. */
    in = &bench_in[BENCH_ONE_TONE];
    static const unsigned delay_hz[] = {1000u, 2000u, 4000u, 8000u};
    for (unsigned r = 0u; r < sizeof delay_hz / sizeof delay_hz[0]; ++r) {
        for (unsigned ms = 20u; ms <= 50u; ms += 30u) {
            ladrc_axis_config_t dc;
            ladrc_axis_config_default(&dc, LADRC_VARIANT_LADRC, 1.0f / (float)delay_hz[r], bench_inertia[0]);
            dc.motor_tau_s = BENCH_ACT_MOTOR_TAU_S;
            dc.delay_ticks = (uint16_t)(ms * delay_hz[r] / 1000u);
            if (ladrc_axis_init(&delay_axis, &dc) != LADRC_OK) {
                printf("BENCH error: init failed for the delay of %u ticks\n", (unsigned)dc.delay_ticks);
                return 1;
            }
            ladrc_axis_reset(&delay_axis, in->axis_ang[0]);
            char name[40];
            snprintf(name, sizeof name, "ladrc_axis_delay_%uhz_%u", delay_hz[r], (unsigned)dc.delay_ticks);
            print_module(name, RUN_DELAY, ipc);
        }
    }

    SIZE_LINE(ladrc_attitude_t);
    SIZE_LINE(ladrc_attitude_config_t);
    SIZE_LINE(ladrc_axis_t);
    SIZE_LINE(ladrc_actuator_t);
    SIZE_LINE(ladrc_axis_config_t);
    SIZE_LINE(ladrc_mixer_t);
    SIZE_LINE(ladrc_mixer_config_t);
    SIZE_LINE(ladrc_mixer_output_t);
    SIZE_LINE(ladrc_pid_t);
    SIZE_LINE(ladrc_pid_config_t);
    SIZE_LINE(ladrc_cascaded_t);
    SIZE_LINE(ladrc_indi_t);
    SIZE_LINE(ladrc_reso_t);
    SIZE_LINE(ladrc_leso_t);
    SIZE_LINE(ladrc_leso_config_t);
    SIZE_LINE(ladrc_td_t);
    SIZE_LINE(ladrc_td_config_t);
    SIZE_LINE(ladrc_levant_t);
    SIZE_LINE(ladrc_levant_config_t);
    SIZE_LINE(ladrc_lp_estimator_t);
    SIZE_LINE(ladrc_lp_config_t);
    SIZE_LINE(ladrc_hp_estimator_t);
    SIZE_LINE(ladrc_hp_config_t);
    SIZE_LINE(ladrc_rls_t);
    SIZE_LINE(ladrc_rls_config_t);
    SIZE_LINE(ladrc_gyro_filter_t);
    SIZE_LINE(ladrc_gyro_filter_config_t);
    return 0;
}
