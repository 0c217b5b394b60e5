/* SPDX-License-Identifier: BSD-3-Clause */
/* Hostile inputs for the property tests: a small deterministic generator and
 * values drawn from the classes a glitching sensor or a corrupted parameter
 * produces (normal, huge finite, denormal, zero, NaN, +-inf). */
#ifndef LADRC_TEST_HOSTILE_H
#define LADRC_TEST_HOSTILE_H

#include "ladrc/types.h"

#include <stdint.h>

typedef struct {
    uint64_t state;
} test_rng_t;

/* splitmix64: every seed gives a full-period stream. */
uint64_t test_rng_next(test_rng_t *rng);

/* Uniform in [0, 1). */
double test_rng_uniform(test_rng_t *rng);

/* Uniform integer in [0, n). */
unsigned test_rng_below(test_rng_t *rng, unsigned n);

typedef enum {
    TEST_VALUE_NORMAL = 0, /* uniform in +-scale */
    TEST_VALUE_HUGE,       /* +-10^k, k uniform from log10(scale) + 1 to the largest finite */
    TEST_VALUE_DENORMAL,   /* +-a subnormal */
    TEST_VALUE_ZERO,       /* +-0 */
    TEST_VALUE_NAN,
    TEST_VALUE_INF, /* +-inf */
    TEST_VALUE_CLASSES
} test_value_class_t;

/* A value of the given class; `scale` sets the normal range. */
ladrc_real_t test_value_of_class(test_rng_t *rng, test_value_class_t cls, double scale);

/* A value of a random class (normal half the time). */
ladrc_real_t test_hostile_value(test_rng_t *rng, double scale, test_value_class_t *cls);

/* Special values from their bit patterns, through volatile so that no
 * compiler flag can fold them: 0 a quiet NaN, 1 +inf, 2 -inf, then NaNs
 * that are negative (3), carry a payload (4), signal (5), all ones (6). */
#define TEST_SPECIAL_VALUES 7u
ladrc_real_t test_special_value(unsigned which);

/* NaN kind k (0..TEST_NAN_KINDS-1) of those above. */
#define TEST_NAN_KINDS 5u
ladrc_real_t test_special_nan(unsigned k);

/* 1 if x is finite, from its bits (no flag can fold the test). */
int test_is_finite(ladrc_real_t x);

#endif
