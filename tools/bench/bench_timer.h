/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The Cortex-M4F benchmarks' clock (bench_m4f.c, bench_lean.c), run under
 * qemu mps2-an386 in icount mode (qemu -icount shift=S: every instruction
 * advances virtual time by 2^S ns, so any clock that follows virtual time
 * counts instructions).
 *
 * The clock is SysTick on the processor clock (qemu does not model the DWT
 * cycle counter). Its rate relative to instructions is measured
 * (bench_calibrate), on a loop of known length, and not assumed.
 */
#ifndef LADRC_BENCH_TIMER_H
#define LADRC_BENCH_TIMER_H

#include <stdint.h>
#include <stdio.h>

#include "bench_case.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define SYST_MASK 0x00FFFFFFu

static inline void timer_start(void)
{
    SYST_CSR = 0u;
    SYST_RVR = SYST_MASK;
    SYST_CVR = 0u;
    SYST_CSR = 5u; /* enable, processor clock, no interrupt */
}

static inline uint32_t timer_now(void)
{
    return SYST_CVR;
}

/* The counter counts down; blocks are far shorter than one wrap. */
static inline uint32_t timer_since(uint32_t start)
{
    return (start - SYST_CVR) & SYST_MASK;
}

/* 2 * n + 2 instructions from the first subs to the final bne falling through:
 * measured between two timer reads, so the fixed cost of the reads cancels
 * out in the difference of two lengths. */
static inline uint32_t timed_spin(uint32_t n)
{
    uint32_t t0 = timer_now();
    __asm__ volatile("1:\n\tsubs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
    return timer_since(t0);
}

/* Starts the clock and prints "BENCH <who>clock ..."; returns the instructions
 * per SysTick count, or 0 (after "BENCH error ...") when the clock does not
 * follow the instruction count. The difference of two spins is exactly
 * 2 * (n2 - n1) instructions; each timed interval is read to within one
 * count, so the quotient is rounded. */
static inline uint32_t bench_calibrate(const char *who)
{
    timer_start();
    const uint32_t n1 = 1000u, n2 = 101000u;
    const uint32_t c1 = timed_spin(n1), c2 = timed_spin(n2);
    const uint32_t insns = 2u * (n2 - n1);
    const uint32_t counts = c2 - c1;
    const uint32_t ipc = counts == 0u ? 0u : (insns + counts / 2u) / counts;
    if (ipc == 0u || (insns > ipc * counts ? insns - ipc * counts : ipc * counts - insns) > 2u * ipc) {
        printf("BENCH error: SysTick does not follow the instruction count "
               "(%lu instructions, %lu counts); run qemu with -icount shift=S\n",
               (unsigned long)insns, (unsigned long)counts);
        return 0u;
    }
    printf("BENCH %sclock SysTick(processor clock) under qemu -icount: %lu instructions per count "
           "(%lu instructions in %lu counts); %d ticks per block after %d warm-up ticks\n",
           who, (unsigned long)ipc, (unsigned long)insns, (unsigned long)counts, BENCH_TICKS, BENCH_WARMUP);
    return ipc;
}

/* Instructions per tick, in hundredths, from counts over BENCH_TICKS ticks. */
static inline uint32_t per_tick_x100(uint32_t counts, uint32_t empty, uint32_t insn_per_count)
{
    return (uint32_t)(((uint64_t)(counts - empty) * insn_per_count * 100u + BENCH_TICKS / 2) / BENCH_TICKS);
}

/* The dearest single 3-axis tick of the measured ticks, in instructions to
 * within one SysTick count (ipc instructions): each tick timed alone, less
 * the cheapest empty tick. Averages hide the ticks on which decimated work
 * falls. The controller must have run the warm-up. */
static inline uint32_t worst_attitude_tick(ladrc_attitude_t *att, ladrc_mixer_t *mixer, const bench_inputs_t *in,
                                           uint32_t ipc, volatile ladrc_real_t *sink)
{
    uint32_t worst = 0u;
    uint32_t empty = UINT32_MAX;
    for (int i = BENCH_WARMUP; i < BENCH_WARMUP + BENCH_TICKS; ++i) {
        const uint32_t t0 = timer_now();
        *sink = bench_attitude_tick(att, mixer, in, i);
        const uint32_t c = timer_since(t0);
        worst = (c > worst) ? c : worst;
    }
    for (int i = BENCH_WARMUP; i < BENCH_WARMUP + BENCH_TICKS; ++i) {
        const uint32_t t0 = timer_now();
        *sink = bench_empty_tick(in, i);
        const uint32_t c = timer_since(t0);
        empty = (c < empty) ? c : empty;
    }
    return (worst - empty) * ipc;
}

#endif /* LADRC_BENCH_TIMER_H */
