/* SPDX-License-Identifier: BSD-3-Clause */
/* Deterministic noise for the tests: the same sequence on every build. */
#ifndef LADRC_TEST_NOISE_H
#define LADRC_TEST_NOISE_H

/* A standard Gaussian deviate: xorshift32 on state (nonzero) + Box-Muller. */
double test_gaussian(unsigned *state);

#endif
