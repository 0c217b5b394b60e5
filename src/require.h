/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The one form of the library's pointer checks (not installed). A NULL
 * where a function needs a pointer is a programmer error: LADRC_ASSERT
 * catches it when asserts are on (the LADRC_CONFIG hook); with them off the
 * function returns a safe value instead of dereferencing it: a step
 * LADRC_FAULT_STATE, a getter 0, a function without a result nothing.
 * Inits report NULL as LADRC_ERR_NULL, like any other bad config, without
 * asserting (a status is how init reports). Measured cost of the checks on
 * the tick's path (tools/bench, Cortex-M4F -Os): 16 instructions per HP
 * axis, 67 of the 3-axis HP tick with the mixer (2,804 -> 2,871, 2.4 %).
 */
#ifndef LADRC_REQUIRE_H
#define LADRC_REQUIRE_H

#include "ladrc/types.h"

/** Returns `safe` from the calling function unless cond holds. */
#define LADRC_REQUIRE(cond, safe)                                                                                      \
    do {                                                                                                               \
        LADRC_ASSERT(cond);                                                                                            \
        if (!(cond)) {                                                                                                 \
            return safe;                                                                                               \
        }                                                                                                              \
    } while (0)

/** Returns from the calling (void) function unless cond holds. */
#define LADRC_REQUIRE_VOID(cond)                                                                                       \
    do {                                                                                                               \
        LADRC_ASSERT(cond);                                                                                            \
        if (!(cond)) {                                                                                                 \
            return;                                                                                                    \
        }                                                                                                              \
    } while (0)

#endif /* LADRC_REQUIRE_H */
