/* SPDX-License-Identifier: BSD-3-Clause */
#include "test_hostile.h"

#include <math.h>
#include <string.h>

#ifdef LADRC_REAL_DOUBLE
#define REAL_MAX_LOG10 308.0
#define REAL_DENORM_MIN 4.9406564584124654e-324
#else
#define REAL_MAX_LOG10 38.0
#define REAL_DENORM_MIN 1.40129846e-45
#endif

uint64_t test_rng_next(test_rng_t *rng)
{
    uint64_t z = (rng->state += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

double test_rng_uniform(test_rng_t *rng)
{
    return (double)(test_rng_next(rng) >> 11) * (1.0 / 9007199254740992.0);
}

unsigned test_rng_below(test_rng_t *rng, unsigned n)
{
    return (unsigned)(test_rng_uniform(rng) * (double)n);
}

ladrc_real_t test_special_value(unsigned which)
{
#ifdef LADRC_REAL_DOUBLE
    static const uint64_t bits[TEST_SPECIAL_VALUES] = {UINT64_C(0x7ff8000000000000), UINT64_C(0x7ff0000000000000),
                                                       UINT64_C(0xfff0000000000000), UINT64_C(0xfff8000000000000),
                                                       UINT64_C(0x7ff8000000012345), UINT64_C(0x7ff0000000000001),
                                                       UINT64_C(0xffffffffffffffff)};
    volatile uint64_t b = bits[which % TEST_SPECIAL_VALUES];
    uint64_t u = b;
#else
    static const uint32_t bits[TEST_SPECIAL_VALUES] = {UINT32_C(0x7fc00000), UINT32_C(0x7f800000), UINT32_C(0xff800000),
                                                       UINT32_C(0xffc00000), UINT32_C(0x7fc12345), UINT32_C(0x7f800001),
                                                       UINT32_C(0xffffffff)};
    volatile uint32_t b = bits[which % TEST_SPECIAL_VALUES];
    uint32_t u = b;
#endif
    ladrc_real_t x;
    memcpy(&x, &u, sizeof x);
    return x;
}

ladrc_real_t test_special_nan(unsigned k)
{
    static const unsigned nans[TEST_NAN_KINDS] = {0u, 3u, 4u, 5u, 6u};
    return test_special_value(nans[k % TEST_NAN_KINDS]);
}

static double random_sign(test_rng_t *rng)
{
    return (test_rng_next(rng) & 1u) ? -1.0 : 1.0;
}

ladrc_real_t test_value_of_class(test_rng_t *rng, test_value_class_t cls, double scale)
{
    volatile ladrc_real_t x; /* volatile: no flag folds the specials away */
    switch (cls) {
    case TEST_VALUE_NORMAL:
        x = (ladrc_real_t)((2.0 * test_rng_uniform(rng) - 1.0) * scale);
        break;
    case TEST_VALUE_HUGE: {
        const double lo = log10(scale) + 1.0;
        double v = random_sign(rng) * pow(10.0, lo + test_rng_uniform(rng) * (REAL_MAX_LOG10 - lo));
        if (test_rng_below(rng, 16u) == 0u) {
            v = random_sign(rng) * (double)(ladrc_real_t)LADRC_REAL_MAX; /* the edge itself */
        }
        x = (ladrc_real_t)v;
        break;
    }
    case TEST_VALUE_DENORMAL: {
        const double span = LADRC_REAL_MIN / REAL_DENORM_MIN;
        x = (ladrc_real_t)(random_sign(rng) * REAL_DENORM_MIN * (1.0 + test_rng_uniform(rng) * (span - 2.0)));
        break;
    }
    case TEST_VALUE_ZERO:
        x = (ladrc_real_t)(random_sign(rng) * 0.0);
        break;
    case TEST_VALUE_NAN:
        x = test_special_value(0u);
        break;
    default:
        x = test_special_value((random_sign(rng) > 0.0) ? 1u : 2u);
        break;
    }
    return x;
}

ladrc_real_t test_hostile_value(test_rng_t *rng, double scale, test_value_class_t *cls)
{
    test_value_class_t c = TEST_VALUE_NORMAL;
    if (test_rng_next(rng) & 1u) {
        c = (test_value_class_t)test_rng_below(rng, (unsigned)TEST_VALUE_CLASSES);
    }
    if (cls != NULL) {
        *cls = c;
    }
    return test_value_of_class(rng, c, scale);
}

int test_is_finite(ladrc_real_t x)
{
#ifdef LADRC_REAL_DOUBLE
    uint64_t u;
    memcpy(&u, &x, sizeof u);
    return (u & UINT64_C(0x7ff0000000000000)) != UINT64_C(0x7ff0000000000000);
#else
    uint32_t u;
    memcpy(&u, &x, sizeof u);
    return (u & UINT32_C(0x7f800000)) != UINT32_C(0x7f800000);
#endif
}
