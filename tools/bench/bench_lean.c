/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The lean HP build on the Cortex-M4F (tools/bench/CMakeLists.txt:
 * HP-MLADRC and Levant alone, no online frequency search, one tone per
 * axis): the one-tone HP-MLADRC case of bench_m4f.c, 3 axes + mixer, its
 * estimators told the disturbance's frequency (bench_case.c), timed the same
 * way (bench_timer.h) on the inputs its own closed loop recorded; and the
 * size of its state.
 *
 * Output: lines "BENCH lean key value..." for tools/bench.sh.
 */
#include <stdint.h>
#include <stdio.h>

#include "bench_case.h"
#include "bench_timer.h"

#if LADRC_WITH_HP_ONLINE || LADRC_WITH_PID || LADRC_WITH_TD
#error "bench_lean.c is built against the lean HP library only"
#endif

static volatile ladrc_real_t sink;
static ladrc_attitude_t att;
static ladrc_mixer_t mixer;

/* Ticks from..from+n of the case (timed) or the same loop without the
 * controller; the SysTick counts it took. */
static uint32_t block(const bench_inputs_t *in, int from, int n, int timed)
{
    const uint32_t t0 = timer_now();
    for (int i = from; i < from + n; ++i) {
        sink = timed ? bench_attitude_tick(&att, &mixer, in, i) : bench_empty_tick(in, i);
    }
    return timer_since(t0);
}

#define SIZE_LINE(type) printf("BENCH lean sizeof %s %u\n", #type, (unsigned)sizeof(type))

int main(void)
{
    const uint32_t ipc = bench_calibrate("lean ");
    if (ipc == 0u) {
        return 1;
    }
    if (bench_make_inputs() != 0) {
        printf("BENCH error: lean: init failed while recording the inputs\n");
        return 1;
    }
    const bench_engagement_t *e = &bench_engaged_attitude[BENCH_ONE_TONE];
    printf("BENCH lean engaged weight_min %d.%03d tones %u %u from %d\n", (int)e->weight_min,
           (int)(1000.0f * (e->weight_min - (float)(int)e->weight_min)), e->tones_min, e->tones_max, e->engaged_from);
    if (e->weight_min < 1.0f || e->tones_min != 1u || e->tones_max != 1u) {
        printf("BENCH error: lean: HP-MLADRC does not run engaged with 1 tone over the measured ticks\n");
        return 1;
    }
    const bench_inputs_t *in = &bench_in[BENCH_ONE_TONE];
    if (bench_setup_attitude(&att, &mixer, BENCH_CASE_HP) != 0) {
        printf("BENCH error: lean: init failed\n");
        return 1;
    }
    (void)block(in, 0, BENCH_WARMUP, 1);
    const uint32_t at = block(in, BENCH_WARMUP, BENCH_TICKS, 1);
    const uint32_t at0 = block(in, BENCH_WARMUP, BENCH_TICKS, 0);
    const uint32_t at100 = per_tick_x100(at, at0, ipc);
    printf("BENCH lean insn HP-MLADRC %lu.%02lu counts %lu %lu\n", (unsigned long)(at100 / 100u),
           (unsigned long)(at100 % 100u), (unsigned long)at, (unsigned long)at0);
    if (bench_setup_attitude(&att, &mixer, BENCH_CASE_HP) != 0) {
        return 1;
    }
    (void)block(in, 0, BENCH_WARMUP, 1);
    printf("BENCH lean worst HP-MLADRC %lu\n", (unsigned long)worst_attitude_tick(&att, &mixer, in, ipc, &sink));
    SIZE_LINE(ladrc_attitude_t);
    SIZE_LINE(ladrc_axis_t);
    SIZE_LINE(ladrc_hp_estimator_t);
    SIZE_LINE(ladrc_rls_t);
    return 0;
}
