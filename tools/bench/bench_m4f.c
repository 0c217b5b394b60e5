/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Cost of one control tick on the Cortex-M4F, run under qemu mps2-an386 in
 * icount mode (qemu -icount shift=S: every instruction advances virtual time
 * by 2^S ns, so any clock that follows virtual time counts instructions).
 *
 * The clock is SysTick on the processor clock (qemu does not model the DWT
 * cycle counter). Its rate relative to instructions is measured here, on a
 * loop of known length, and not assumed. Each measurement times one block of
 * BENCH_TICKS ticks and subtracts the same loop with the call removed (it
 * still loads the inputs and stores the output), so the figure includes the
 * call, argument passing and return as firmware would pay them.
 *
 * Cases (bench_case.h): each variant on one axis and on 3 axes + mixer.
 * Modules: each building block of a tick timed alone the same way, on the
 * inputs it sees in a tick (see setup_modules), to show where the
 * instructions of the HP-MLADRC 3-axis tick go.
 *
 * Output: lines "BENCH key value..." for tools/bench.sh.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "bench_case.h"
#include "ladrc/estimator.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/pid.h"
#include "ladrc/rls.h"
#include "ladrc/td.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_MASK 0x00FFFFFFu

static volatile ladrc_real_t sink;

static void timer_start(void)
{
    SYST_CSR = 0u;
    SYST_RVR = SYST_MASK;
    SYST_CVR = 0u;
    SYST_CSR = 5u; /* enable, processor clock, no interrupt */
}

static inline uint32_t timer_now(void) { return SYST_CVR; }

/* The counter counts down; blocks are far shorter than one wrap. */
static inline uint32_t timer_since(uint32_t start) { return (start - SYST_CVR) & SYST_MASK; }

/* 2 * n + 2 instructions from the first subs to the final bne falling through:
 * measured between two timer reads, so the fixed cost of the reads cancels
 * out in the difference of two lengths. */
static uint32_t timed_spin(uint32_t n)
{
    uint32_t t0 = timer_now();
    __asm__ volatile("1:\n\tsubs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
    return timer_since(t0);
}

/* What a block runs. */
typedef enum {
    RUN_AXIS,        /* one axis of the current variant */
    RUN_ATTITUDE,    /* 3 axes + mixer of the current variant */
    RUN_LONE_AXES,   /* three HP-MLADRC axes side by side, no attitude, no mixer */
    RUN_LESO,
    RUN_TD,
    RUN_LEVANT,
    RUN_LP,
    RUN_HP,
    RUN_RLS3,
    RUN_RLS2,
    RUN_PID,
    RUN_THRUST,
    RUN_MIXER
} run_t;

static ladrc_axis_t axis;
static ladrc_attitude_t att;
static ladrc_mixer_t mixer;

/* The modules alone, and what they are fed. */
static struct {
    ladrc_axis_t lone[LADRC_AXES];
    ladrc_leso_t leso;
    ladrc_td_t td;
    ladrc_levant_t levant;
    ladrc_lp_estimator_t lp;
    ladrc_hp_estimator_t hp;
    ladrc_rls_t rls3, rls2;
    ladrc_pid_t pid;
    ladrc_mixer_t mixer;
    ladrc_mixer_output_t out;
    ladrc_real_t b0;
    uint16_t decimation;
    uint16_t fit_decimation;
} mod;

static ladrc_real_t torque_in[BENCH_SAMPLES][LADRC_AXES]; /* commanded, N m */
static ladrc_real_t applied_in[BENCH_SAMPLES];            /* achieved roll torque, N m */
static ladrc_real_t thrust_in[BENCH_SAMPLES];             /* N */
static ladrc_real_t hp_in[BENCH_SAMPLES];                 /* rad/s^2 */
static ladrc_real_t phi3_in[BENCH_SAMPLES][3];
static ladrc_real_t phi2_in[BENCH_SAMPLES][2];
static ladrc_real_t y2_in[BENCH_SAMPLES];

/* Ticks the block from the first sample (warm-up) or after it; "empty" runs
 * the same loop and loads with the call left out. */
#define BLOCK(call, empty)                                                                         \
    for (int i = from; i < from + n; ++i) {                                                        \
        if (timed) {                                                                               \
            call;                                                                                  \
        } else {                                                                                   \
            sink = (empty);                                                                        \
        }                                                                                          \
    }

static uint32_t run(run_t what, int warm, int timed)
{
    const int from = warm ? 0 : BENCH_WARMUP;
    const int n = warm ? BENCH_WARMUP : BENCH_TICKS;
    uint32_t t0 = timer_now();
    switch (what) {
    case RUN_AXIS:
        BLOCK(sink = bench_axis_tick(&axis, i), bench_empty_tick(i));
        break;
    case RUN_ATTITUDE:
        BLOCK(sink = bench_attitude_tick(&att, &mixer, i), bench_empty_tick(i));
        break;
    case RUN_LONE_AXES:
        BLOCK(for (int a = 0; a < LADRC_AXES; ++a) sink = ladrc_axis_step_with_rate(
                  &mod.lone[a], bench_ref[i][a], bench_ang[i][a], bench_rate[i][a]),
              bench_empty_tick(i) + bench_ref[i][1] + bench_ang[i][1] + bench_rate[i][1] +
                  bench_ref[i][2] + bench_ang[i][2] + bench_rate[i][2]);
        break;
    case RUN_LESO:
        BLOCK((void)ladrc_leso_step(&mod.leso, bench_ang[i][0], applied_in[i], 0.0f, 0.0f),
              bench_ang[i][0] + applied_in[i]);
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
        BLOCK((void)ladrc_lp_step(&mod.lp, bench_rate[i][0], mod.b0 * applied_in[i]),
              bench_rate[i][0] + mod.b0 * applied_in[i]);
        break;
    case RUN_HP:
        BLOCK((void)ladrc_hp_step(&mod.hp, hp_in[i]), hp_in[i]);
        break;
    case RUN_RLS3:
        BLOCK((void)ladrc_rls_update(&mod.rls3, phi3_in[i], hp_in[i]), phi3_in[i][1] + hp_in[i]);
        break;
    case RUN_RLS2:
        BLOCK((void)ladrc_rls_update(&mod.rls2, phi2_in[i], y2_in[i]), phi2_in[i][0] + y2_in[i]);
        break;
    case RUN_PID:
        BLOCK(sink = ladrc_pid_step(&mod.pid, bench_ref[i][0], bench_ang[i][0], &bench_rate[i][0]),
              bench_empty_tick(i));
        break;
    case RUN_THRUST:
        BLOCK(sink = ladrc_mixer_thrust_from_tilt(&mod.mixer, bench_ang[i][0], bench_ang[i][1]),
              bench_ang[i][0] + bench_ang[i][1]);
        break;
    case RUN_MIXER:
        BLOCK((void)ladrc_mixer_step(&mod.mixer, thrust_in[i], torque_in[i], &mod.out),
              thrust_in[i] + torque_in[i][0]);
        break;
    }
    return timer_since(t0);
}

/* Deterministic noise in [-1, 1). */
static float noise(uint32_t *seed)
{
    *seed = *seed * 1664525u + 1013904223u;
    return (float)(*seed >> 8) * (2.0f / 16777216.0f) - 1.0f;
}

/* The Table 2 disturbance with a little measurement noise, rad/s^2. */
static float disturbance(float t, uint32_t *seed) { return 20.0f + 120.0f * sinf(3.0f * t) + 0.5f * noise(seed); }

/* Inputs of the modules: the torques and thrust of the HP-MLADRC 3-axis case
 * (recorded from a run), the disturbance for the HP estimator, and the
 * regressors its two RLS see (3 params: bias and the phasor at 3 rad/s;
 * 2 params: second differences of the decimated samples). */
static int record_inputs(uint16_t decimation)
{
    if (bench_setup_attitude(&att, &mixer, BENCH_VARIANTS - 1) != 0) {
        return -1;
    }
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        ladrc_mixer_output_t out;
        thrust_in[i] = ladrc_mixer_thrust_from_tilt(&mixer, bench_ang[i][0], bench_ang[i][1]);
        (void)ladrc_attitude_step(&att, bench_ref[i], bench_ang[i], bench_rate[i], torque_in[i]);
        (void)ladrc_mixer_step(&mixer, thrust_in[i], torque_in[i], &out);
        ladrc_attitude_set_applied(&att, out.torque_Nm);
        applied_in[i] = out.torque_Nm[0];
    }
    uint32_t seed = 1u, seed2 = 2u;
    const float period_s = (float)decimation * BENCH_DT_S;
    float x0 = disturbance(0.0f, &seed2), x1 = disturbance(period_s, &seed2);
    for (int i = 0; i < BENCH_SAMPLES; ++i) {
        const float t = (float)i * BENCH_DT_S;
        hp_in[i] = disturbance(t, &seed);
        phi3_in[i][0] = 1.0f;
        phi3_in[i][1] = cosf(3.0f * t);
        phi3_in[i][2] = sinf(3.0f * t);
        const float x2 = disturbance((float)(i + 2) * period_s, &seed2);
        phi2_in[i][0] = -x1;
        phi2_in[i][1] = 1.0f;
        y2_in[i] = x2 - 2.0f * x1 + x0;
        x0 = x1;
        x1 = x2;
    }
    return 0;
}

/* Each module configured as the axis defaults configure it (HP-MLADRC for
 * the LESO, Levant and estimators, LADRC for TD, PID for PID). */
static int setup_modules(void)
{
    ladrc_axis_config_t hp, ladrc, pid;
    ladrc_axis_config_default(&hp, LADRC_VARIANT_HP_MLADRC, BENCH_DT_S, bench_inertia[0]);
    ladrc_axis_config_default(&ladrc, LADRC_VARIANT_LADRC, BENCH_DT_S, bench_inertia[0]);
    ladrc_axis_config_default(&pid, LADRC_VARIANT_PID, BENCH_DT_S, bench_inertia[0]);
    mod.b0 = hp.b0;
    mod.decimation = hp.hp_decimation;
    mod.fit_decimation = hp.hp_fit_decimation;
    if (record_inputs(hp.hp_decimation) != 0) {
        return -1;
    }
    for (int a = 0; a < LADRC_AXES; ++a) {
        ladrc_axis_config_t cfg;
        ladrc_axis_config_default(&cfg, LADRC_VARIANT_HP_MLADRC, BENCH_DT_S, bench_inertia[a]);
        if (ladrc_axis_init(&mod.lone[a], &cfg) != LADRC_OK) {
            return -1;
        }
        ladrc_axis_reset(&mod.lone[a], bench_ang[0][a]);
    }
    const ladrc_leso_config_t leso = {hp.dt_s, hp.wo_rad_s, hp.b0, hp.leso_method};
    const ladrc_td_config_t td = {ladrc.dt_s, ladrc.td_accel_rad_s2, ladrc.td_h0_s};
    const ladrc_levant_config_t lev = {hp.dt_s, hp.levant_method, LADRC_LEVANT_GAINS_LIPSCHITZ,
                                       hp.levant_lipschitz_rad_s4, 0.0f, 0.0f, 0.0f, 0.0f};
    const ladrc_lp_config_t lp = {hp.dt_s, hp.lp_lambda0_per_s, hp.lp_k0_per_s};
    const ladrc_hp_config_t hpc = {hp.dt_s, hp.hp_freq_mode, hp.hp_freq_rad_s,
                                   hp.hp_freq_min_rad_s, hp.hp_freq_max_rad_s, hp.hp_lambda0_per_s,
                                   hp.hp_freq_lambda0_per_s, hp.hp_decimation, hp.wo_rad_s,
                                   hp.hp_fit_decimation, hp.hp_fit_phase};
    /* The HP estimator's two fits: P bound 1e4 and initial P 1e3 per sample. */
    const float h2 = (float)hp.hp_decimation * hp.dt_s;
    const float h3 = (float)hp.hp_fit_decimation * hp.dt_s;
    const ladrc_rls_config_t rls3 = {3u, h3, hp.hp_lambda0_per_s, 1e4f / h3, 1e3f / h3};
    const ladrc_rls_config_t rls2 = {2u, h2, hp.hp_freq_lambda0_per_s, 1e4f / h2, 1e3f / h2};
    const ladrc_pid_config_t pidc = {pid.dt_s, pid.pid_kp, pid.pid_ki, pid.pid_kd,
                                     pid.pid_d_filter_tau_s, pid.pid_i_limit_Nm, pid.u_min_Nm,
                                     pid.u_max_Nm};
    if (ladrc_leso_init(&mod.leso, &leso) != LADRC_OK || ladrc_td_init(&mod.td, &td) != LADRC_OK ||
        ladrc_levant_init(&mod.levant, &lev) != LADRC_OK || ladrc_lp_init(&mod.lp, &lp) != LADRC_OK ||
        ladrc_hp_init(&mod.hp, &hpc) != LADRC_OK || ladrc_rls_init(&mod.rls3, &rls3) != LADRC_OK ||
        ladrc_rls_init(&mod.rls2, &rls2) != LADRC_OK || ladrc_pid_init(&mod.pid, &pidc) != LADRC_OK ||
        ladrc_mixer_init(&mod.mixer, &bench_mixer_cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_leso_reset(&mod.leso, bench_ang[0][0]);
    ladrc_td_reset(&mod.td, bench_ref[0][0]);
    ladrc_levant_reset(&mod.levant, bench_ref[0][0]);
    ladrc_pid_reset(&mod.pid, bench_ang[0][0]);
    return 0;
}

/* Instructions per tick, in hundredths, from counts over BENCH_TICKS ticks. */
static uint32_t per_tick_x100(uint32_t counts, uint32_t empty, uint32_t insn_per_count)
{
    return (uint32_t)(((uint64_t)(counts - empty) * insn_per_count * 100u + BENCH_TICKS / 2) / BENCH_TICKS);
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

/* The dearest single 3-axis tick of the block, in instructions to within one
 * SysTick count (ipc instructions): each tick timed alone, less the cheapest
 * empty tick. Averages hide the ticks on which decimated work falls. */
static uint32_t worst_attitude_tick(uint32_t ipc)
{
    uint32_t worst = 0u;
    uint32_t empty = UINT32_MAX;
    for (int i = BENCH_WARMUP; i < BENCH_WARMUP + BENCH_TICKS; ++i) {
        const uint32_t t0 = timer_now();
        sink = bench_attitude_tick(&att, &mixer, i);
        const uint32_t c = timer_since(t0);
        worst = (c > worst) ? c : worst;
    }
    for (int i = BENCH_WARMUP; i < BENCH_WARMUP + BENCH_TICKS; ++i) {
        const uint32_t t0 = timer_now();
        sink = bench_empty_tick(i);
        const uint32_t c = timer_since(t0);
        empty = (c < empty) ? c : empty;
    }
    return (worst - empty) * ipc;
}

#define SIZE_LINE(type) printf("BENCH sizeof %s %u\n", #type, (unsigned)sizeof(type))

int main(void)
{
    bench_make_inputs();
    timer_start();

    /* Calibration: the difference of two spins is exactly 2 * (n2 - n1) instructions;
     * each timed interval is read to within one count, so the quotient is rounded. */
    const uint32_t n1 = 1000u, n2 = 101000u;
    const uint32_t c1 = timed_spin(n1), c2 = timed_spin(n2);
    const uint32_t insns = 2u * (n2 - n1);
    const uint32_t counts = c2 - c1;
    const uint32_t ipc = counts == 0u ? 0u : (insns + counts / 2u) / counts;
    if (ipc == 0u || (insns > ipc * counts ? insns - ipc * counts : ipc * counts - insns) > 2u * ipc) {
        printf("BENCH error: SysTick does not follow the instruction count "
               "(%lu instructions, %lu counts); run qemu with -icount shift=S\n",
               (unsigned long)insns, (unsigned long)counts);
        return 1;
    }
    printf("BENCH clock SysTick(processor clock) under qemu -icount: %lu instructions per count "
           "(%lu instructions in %lu counts); %d ticks per block after %d warm-up ticks\n",
           (unsigned long)ipc, (unsigned long)insns, (unsigned long)counts, BENCH_TICKS, BENCH_WARMUP);

    for (int v = 0; v < BENCH_VARIANTS; ++v) {
        if (bench_setup_axis(&axis, v) != 0 || bench_setup_attitude(&att, &mixer, v) != 0) {
            printf("BENCH error: init failed for %s\n", bench_variant_name[v]);
            return 1;
        }
        uint32_t ax, ax0, at, at0;
        const uint32_t ax100 = measure(RUN_AXIS, ipc, &ax, &ax0);
        const uint32_t at100 = measure(RUN_ATTITUDE, ipc, &at, &at0);
        printf("BENCH insn %s %lu.%02lu %lu.%02lu counts %lu %lu %lu %lu\n", bench_variant_name[v],
               (unsigned long)(ax100 / 100u), (unsigned long)(ax100 % 100u),
               (unsigned long)(at100 / 100u), (unsigned long)(at100 % 100u),
               (unsigned long)ax, (unsigned long)ax0, (unsigned long)at, (unsigned long)at0);
        if (bench_setup_attitude(&att, &mixer, v) != 0) {
            return 1;
        }
        (void)run(RUN_ATTITUDE, 1, 1);
        printf("BENCH worst %s %lu\n", bench_variant_name[v], (unsigned long)worst_attitude_tick(ipc));
    }

    if (setup_modules() != 0) {
        printf("BENCH error: init of a module failed\n");
        return 1;
    }
    printf("BENCH hp_decimation %u\n", (unsigned)mod.decimation);
    printf("BENCH hp_fit_decimation %u\n", (unsigned)mod.fit_decimation);
    print_module("lone_hp_axes_x3", RUN_LONE_AXES, ipc);
    print_module("ladrc_leso_step", RUN_LESO, ipc);
    print_module("ladrc_td_step", RUN_TD, ipc);
    print_module("ladrc_levant_step", RUN_LEVANT, ipc);
    print_module("ladrc_lp_step", RUN_LP, ipc);
    print_module("ladrc_hp_step", RUN_HP, ipc);
    print_module("ladrc_rls_update_3", RUN_RLS3, ipc);
    print_module("ladrc_rls_update_2", RUN_RLS2, ipc);
    print_module("ladrc_pid_step", RUN_PID, ipc);
    print_module("ladrc_mixer_thrust_from_tilt", RUN_THRUST, ipc);
    print_module("ladrc_mixer_step", RUN_MIXER, ipc);

    SIZE_LINE(ladrc_attitude_t);
    SIZE_LINE(ladrc_attitude_config_t);
    SIZE_LINE(ladrc_axis_t);
    SIZE_LINE(ladrc_axis_config_t);
    SIZE_LINE(ladrc_mixer_t);
    SIZE_LINE(ladrc_mixer_config_t);
    SIZE_LINE(ladrc_mixer_output_t);
    SIZE_LINE(ladrc_pid_t);
    SIZE_LINE(ladrc_pid_config_t);
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
    return 0;
}
