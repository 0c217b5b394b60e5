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
 * Inputs are precomputed before timing: the paper's references
 * (roll 5 + 15 cos(pi t / 2) deg, pitch 10 cos(pi t / 2) deg, yaw 0) and a
 * measured angle that lags and carries the response to the Table 2
 * disturbance 20 -/+ 120 sin(3 t) rad/s^2, with its rate, from t = 12 s.
 *
 * Output: lines "BENCH key value..." for tools/bench.sh, and a readable table.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/estimator.h"
#include "ladrc/leso.h"
#include "ladrc/levant.h"
#include "ladrc/mixer.h"
#include "ladrc/pid.h"
#include "ladrc/rls.h"
#include "ladrc/td.h"

#define BENCH_TICKS 2000
#define BENCH_WARMUP 500
#define DT_S 0.001f
#define PI_F 3.14159265f
#define DEG 0.0174532925f

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_MASK 0x00FFFFFFu

static const ladrc_real_t inertia[LADRC_AXES] = {5.445e-3f, 5.445e-3f, 1.089e-2f};

static ladrc_real_t ref_in[BENCH_WARMUP + BENCH_TICKS][LADRC_AXES];
static ladrc_real_t ang_in[BENCH_WARMUP + BENCH_TICKS][LADRC_AXES];
static ladrc_real_t rate_in[BENCH_WARMUP + BENCH_TICKS][LADRC_AXES];

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

static void make_inputs(void)
{
    for (int i = 0; i < BENCH_WARMUP + BENCH_TICKS; ++i) {
        const float t = 12.0f + (float)i * DT_S;
        const float c = cosf(0.5f * PI_F * t);
        const float tl = t - 0.02f; /* the vehicle follows 20 ms late */
        const float cl = cosf(0.5f * PI_F * tl), sl = sinf(0.5f * PI_F * tl);
        const float s3 = sinf(3.0f * t), c3 = cosf(3.0f * t);
        const float a = 0.004f; /* residual of the 3 rad/s disturbance, rad */
        ref_in[i][0] = (5.0f + 15.0f * c) * DEG;
        ref_in[i][1] = 10.0f * c * DEG;
        ref_in[i][2] = 0.0f;
        ang_in[i][0] = (5.0f + 15.0f * cl) * DEG + a * s3;
        ang_in[i][1] = 10.0f * cl * DEG - a * s3;
        ang_in[i][2] = 0.5f * a * s3;
        rate_in[i][0] = -15.0f * 0.5f * PI_F * sl * DEG + 3.0f * a * c3;
        rate_in[i][1] = -10.0f * 0.5f * PI_F * sl * DEG - 3.0f * a * c3;
        rate_in[i][2] = 1.5f * a * c3;
    }
}

static const char *const variant_name[4] = {"PID", "LADRC", "LP-MLADRC", "HP-MLADRC"};
static const ladrc_variant_t variant_id[4] = {LADRC_VARIANT_PID, LADRC_VARIANT_LADRC,
                                              LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_HP_MLADRC};

static ladrc_axis_t axis;
static ladrc_attitude_t att;
static ladrc_mixer_t mixer;

/* Counts, not instructions: single axis (roll) over the block, and the empty loop. */
static uint32_t run_axis(int warm, int timed)
{
    const int from = warm ? 0 : BENCH_WARMUP;
    const int n = warm ? BENCH_WARMUP : BENCH_TICKS;
    uint32_t t0 = timer_now();
    for (int i = from; i < from + n; ++i) {
        if (timed) {
            sink = ladrc_axis_step_with_rate(&axis, ref_in[i][0], ang_in[i][0], rate_in[i][0]);
        } else {
            sink = ref_in[i][0] + ang_in[i][0] + rate_in[i][0];
        }
    }
    return timer_since(t0);
}

static uint32_t run_attitude(int warm, int timed)
{
    const int from = warm ? 0 : BENCH_WARMUP;
    const int n = warm ? BENCH_WARMUP : BENCH_TICKS;
    ladrc_real_t torque[LADRC_AXES];
    ladrc_mixer_output_t out;
    uint32_t t0 = timer_now();
    for (int i = from; i < from + n; ++i) {
        if (timed) {
            (void)ladrc_attitude_step(&att, ref_in[i], ang_in[i], rate_in[i], torque);
            (void)ladrc_mixer_step(&mixer, ladrc_mixer_thrust_from_tilt(&mixer, ang_in[i][0], ang_in[i][1]),
                                   torque, &out);
            ladrc_attitude_set_applied(&att, out.torque_Nm);
            sink = out.w_rad_s[0];
        } else {
            sink = ref_in[i][0] + ang_in[i][0] + rate_in[i][0];
        }
    }
    return timer_since(t0);
}

static int setup_axis(int v)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, variant_id[v], DT_S, inertia[0]);
    if (ladrc_axis_init(&axis, &cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_axis_reset(&axis, ang_in[0][0]);
    return 0;
}

static const ladrc_mixer_config_t mixer_cfg = {
    .kL_N_s2 = 2.98e-5f, .arm_m = 0.165f, .b_Nm_s2 = 2e-6f, .mass_kg = 0.8f, .g_m_s2 = 9.81f,
    .w2_min_rad2_s2 = 1e4f, .w2_max_rad2_s2 = 2e5f, .tilt_max_rad = 0.7f,
    .mode = LADRC_MIXER_SATURATE};

static int setup_attitude(int v)
{
    ladrc_attitude_config_t cfg;
    int bad_axis = -1;
    ladrc_attitude_config_default(&cfg, variant_id[v], DT_S, inertia, 0.09f);
    if (ladrc_attitude_init(&att, &cfg, &bad_axis) != LADRC_OK ||
        ladrc_mixer_init(&mixer, &mixer_cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_attitude_reset(&att, ang_in[0]);
    return 0;
}

/* Instructions per tick, in hundredths, from counts over BENCH_TICKS ticks. */
static uint32_t per_tick_x100(uint32_t counts, uint32_t empty, uint32_t insn_per_count)
{
    return (uint32_t)(((uint64_t)(counts - empty) * insn_per_count * 100u + BENCH_TICKS / 2) / BENCH_TICKS);
}

#define SIZE_LINE(type) printf("BENCH sizeof %s %u\n", #type, (unsigned)sizeof(type))

int main(void)
{
    make_inputs();
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

    for (int v = 0; v < 4; ++v) {
        if (setup_axis(v) != 0 || setup_attitude(v) != 0) {
            printf("BENCH error: init failed for %s\n", variant_name[v]);
            return 1;
        }
        (void)run_axis(1, 1);
        const uint32_t ax = run_axis(0, 1);
        const uint32_t ax0 = run_axis(0, 0);
        (void)run_attitude(1, 1);
        const uint32_t at = run_attitude(0, 1);
        const uint32_t at0 = run_attitude(0, 0);
        const uint32_t ax100 = per_tick_x100(ax, ax0, ipc), at100 = per_tick_x100(at, at0, ipc);
        printf("BENCH insn %s %lu.%02lu %lu.%02lu counts %lu %lu %lu %lu\n", variant_name[v],
               (unsigned long)(ax100 / 100u), (unsigned long)(ax100 % 100u),
               (unsigned long)(at100 / 100u), (unsigned long)(at100 % 100u),
               (unsigned long)ax, (unsigned long)ax0, (unsigned long)at, (unsigned long)at0);
    }

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
