/* SPDX-License-Identifier: BSD-3-Clause */
#include "rng.h"

#include <math.h>

uint64_t sim_rng_splitmix64(uint64_t *x)
{
    *x += UINT64_C(0x9E3779B97F4A7C15);
    uint64_t z = *x;
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

void sim_rng_seed(sim_rng_t *r, uint64_t seed)
{
    uint64_t x = seed;
    /* SplitMix64 is a bijection of its counter, so at most one of four
     * consecutive outputs can be zero: the state is never all zero. */
    for (int i = 0; i < 4; ++i) {
        r->s[i] = sim_rng_splitmix64(&x);
    }
    r->spare = 0.0;
    r->has_spare = 0;
}

static uint64_t rotl64(uint64_t v, unsigned k)
{
    return (v << k) | (v >> (64u - k));
}

uint64_t sim_rng_next(sim_rng_t *r)
{
    uint64_t *s = r->s;
    const uint64_t out = rotl64(s[1] * 5u, 7u) * 9u;
    const uint64_t shifted = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= shifted;
    s[3] = rotl64(s[3], 45u);
    return out;
}

double sim_rng_uniform(sim_rng_t *r)
{
    /* 2^53 values evenly spaced by 2^-53: exact in double, never 1. */
    return (double)(sim_rng_next(r) >> 11) * 0x1.0p-53;
}

double sim_rng_gauss(sim_rng_t *r)
{
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    double u, v, s;
    do {
        u = 2.0 * sim_rng_uniform(r) - 1.0;
        v = 2.0 * sim_rng_uniform(r) - 1.0;
        s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = sqrt(-2.0 * log(s) / s);
    r->spare = v * f;
    r->has_spare = 1;
    return u * f;
}
