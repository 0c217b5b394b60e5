/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Cost of one control tick on the host (plain C, the library built in
 * Release), for the same cases and inputs as bench_m4f.c (bench_case.h).
 *
 *   bench_host                      time: for each variant, one axis and
 *                                   3 axes + mixer, BENCH_HOST_REPEATS blocks
 *                                   of BENCH_TICKS ticks, each from reset and
 *                                   BENCH_WARMUP untimed ticks;
 *                                   prints the median ns/tick with the median
 *                                   of the empty loop subtracted.
 *   bench_host --callgrind CASE     runs one case once: warm-up, then
 *                                   bench_collect() over the BENCH_TICKS
 *                                   ticks; under valgrind --tool=callgrind
 *                                   --toggle-collect=bench_collect only those
 *                                   are counted. CASE: empty, or
 *                                   axis|attitude:CASE (e.g. attitude:PID,
 *                                   attitude:HP-MLADRC-2tones).
 *
 * Output: lines "BENCH host ..." for tools/bench.sh.
 */
#define _POSIX_C_SOURCE 199309L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_case.h"

#define BENCH_HOST_REPEATS 15

#if defined(__GNUC__)
#define BENCH_NOINLINE __attribute__((noinline))
#else
#define BENCH_NOINLINE
#endif

typedef enum { KIND_EMPTY, KIND_AXIS, KIND_ATTITUDE } kind_t;

static volatile ladrc_real_t sink;
static ladrc_axis_t axis;
static ladrc_attitude_t att;
static ladrc_mixer_t mixer;
static const bench_inputs_t *in;

static void run_block(kind_t kind, int from, int n)
{
    switch (kind) {
    case KIND_EMPTY:
        for (int i = from; i < from + n; ++i) {
            sink = bench_empty_tick(in, i);
        }
        break;
    case KIND_AXIS:
        for (int i = from; i < from + n; ++i) {
            sink = bench_axis_tick(&axis, in, i);
        }
        break;
    case KIND_ATTITUDE:
        for (int i = from; i < from + n; ++i) {
            sink = bench_attitude_tick(&att, &mixer, in, i);
        }
        break;
    }
}

/* The measured ticks; the name callgrind's --toggle-collect selects. */
BENCH_NOINLINE void bench_collect(kind_t kind);
BENCH_NOINLINE void bench_collect(kind_t kind)
{
    run_block(kind, BENCH_WARMUP, BENCH_TICKS);
}

static int setup(kind_t kind, int variant)
{
    in = &bench_in[bench_case_inputs[variant]];
    if (kind == KIND_AXIS) {
        return bench_setup_axis(&axis, variant);
    }
    if (kind == KIND_ATTITUDE) {
        return bench_setup_attitude(&att, &mixer, variant);
    }
    return 0;
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int compare_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median over the repeats of ns per tick of the measured block; -1 if init failed. */
static double median_ns(kind_t kind, int variant)
{
    double ns[BENCH_HOST_REPEATS];
    for (int r = 0; r < BENCH_HOST_REPEATS; ++r) {
        if (setup(kind, variant) != 0) {
            return -1.0;
        }
        run_block(kind, 0, BENCH_WARMUP);
        const double t0 = now_ns();
        run_block(kind, BENCH_WARMUP, BENCH_TICKS);
        ns[r] = (now_ns() - t0) / BENCH_TICKS;
    }
    qsort(ns, BENCH_HOST_REPEATS, sizeof ns[0], compare_double);
    return ns[BENCH_HOST_REPEATS / 2];
}

static int time_all(void)
{
    const double empty = median_ns(KIND_EMPTY, 0);
    printf("BENCH host clock CLOCK_MONOTONIC; median of %d blocks of %d ticks, each after reset "
           "and %d untimed ticks; empty loop %.2f ns/tick subtracted\n",
           BENCH_HOST_REPEATS, BENCH_TICKS, BENCH_WARMUP, empty);
    for (int v = 0; v < BENCH_CASES; ++v) {
        const double ax = median_ns(KIND_AXIS, v), at = median_ns(KIND_ATTITUDE, v);
        if (ax < 0.0 || at < 0.0) {
            printf("BENCH error: init failed for %s\n", bench_case_name[v]);
            return 1;
        }
        printf("BENCH host %s %.1f %.1f\n", bench_case_name[v], ax - empty, at - empty);
    }
    return 0;
}

static int collect_one(const char *spec)
{
    kind_t kind = KIND_EMPTY;
    int variant = 0;
    if (strcmp(spec, "empty") != 0) {
        const char *colon = strchr(spec, ':');
        const size_t len = colon ? (size_t)(colon - spec) : 0u;
        if (len == 4u && strncmp(spec, "axis", len) == 0) {
            kind = KIND_AXIS;
        } else if (len == 8u && strncmp(spec, "attitude", len) == 0) {
            kind = KIND_ATTITUDE;
        } else {
            fprintf(stderr, "bench_host: bad case '%s'\n", spec);
            return 2;
        }
        for (variant = 0; variant < BENCH_CASES; ++variant) {
            if (strcmp(colon + 1, bench_case_name[variant]) == 0) {
                break;
            }
        }
        if (variant == BENCH_CASES) {
            fprintf(stderr, "bench_host: unknown variant '%s'\n", colon + 1);
            return 2;
        }
    }
    if (setup(kind, variant) != 0) {
        printf("BENCH error: init failed for %s\n", spec);
        return 1;
    }
    run_block(kind, 0, BENCH_WARMUP);
    bench_collect(kind);
    printf("BENCH host collected %s %d ticks\n", spec, BENCH_TICKS);
    return 0;
}

int main(int argc, char **argv)
{
    if (bench_make_inputs() != 0) {
        printf("BENCH error: init failed while recording the inputs\n");
        return 1;
    }
    if (argc == 1) {
        return time_all();
    }
    if (argc == 3 && strcmp(argv[1], "--callgrind") == 0) {
        return collect_one(argv[2]);
    }
    fprintf(stderr, "usage: bench_host [--callgrind empty|axis:VARIANT|attitude:VARIANT]\n");
    return 2;
}
