/* SPDX-License-Identifier: BSD-3-Clause */
#include "test_noise.h"

#include <math.h>

double test_gaussian(unsigned *state)
{
    double u[2];
    for (int i = 0; i < 2; ++i) {
        *state ^= *state << 13;
        *state ^= *state >> 17;
        *state ^= *state << 5;
        u[i] = ((*state >> 8) + 0.5) / 16777216.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(2.0 * 3.14159265358979 * u[1]);
}
