/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Deterministic pseudo-random numbers for the simulator: xoshiro256**
 * (Blackman and Vigna, "Scrambled linear pseudorandom number generators",
 * 2018/2021) with its 256-bit state filled by SplitMix64 (Steele, Lea and
 * Flood, 2014) from a 64-bit seed. All state is in sim_rng_t: two generators
 * seeded alike give the same sequence on every host, and copying a generator
 * copies its future.
 */
#ifndef LADRC_SIM_RNG_H
#define LADRC_SIM_RNG_H

#include <stdint.h>

typedef struct {
    uint64_t s[4]; /* xoshiro256** state, never all zero after seeding */
    double spare;  /* second normal deviate of the last polar pair */
    int has_spare; /* 1 when spare is the next sim_rng_gauss value */
} sim_rng_t;

/* One SplitMix64 step: advances *x by the golden-ratio increment and returns
 * the mixed value (seed 0 gives 0xE220A8397B1DCDAF first). */
uint64_t sim_rng_splitmix64(uint64_t *x);

/* s[0..3] = the first four SplitMix64 outputs from seed; drops any spare. */
void sim_rng_seed(sim_rng_t *r, uint64_t seed);

/* Next 64-bit output of xoshiro256**. */
uint64_t sim_rng_next(sim_rng_t *r);

/* Uniform in [0, 1): the top 53 bits of sim_rng_next times 2^-53. */
double sim_rng_uniform(sim_rng_t *r);

/* Standard normal (mean 0, variance 1), Marsaglia's polar method: pairs of
 * uniforms in (-1, 1)^2 are drawn until one falls strictly inside the unit
 * circle (and off its centre); the pair gives two deviates, the second is
 * kept in r for the next call. */
double sim_rng_gauss(sim_rng_t *r);

#endif
