/* SPDX-License-Identifier: BSD-3-Clause */
/* Angles on a circle: the far branch of ladrc_wrap_pi (see types.h). */
#include "ladrc/types.h"

/* Beyond this many turns a float has no fraction of a turn left. */
#define ANGLE_TURNS_MAX LADRC_R(1e9)

ladrc_real_t ladrc_wrap_pi_far(ladrc_real_t x)
{
    const ladrc_real_t turns = x / LADRC_TWO_PI;
    if (!(ladrc_fabs(turns) < ANGLE_TURNS_MAX)) {
        return ladrc_is_finite(x) ? LADRC_R(0.0) : x - x;
    }
    /* Truncation leaves |x| below 2 pi (plus rounding): one more turn at most. */
    x -= LADRC_TWO_PI * (ladrc_real_t)(int32_t)turns;
    if (x > LADRC_PI) {
        x -= LADRC_TWO_PI;
    } else if (x <= -LADRC_PI) {
        x += LADRC_TWO_PI;
    }
    return x;
}
