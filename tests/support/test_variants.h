/* SPDX-License-Identifier: BSD-3-Clause */
/* The axis variants, for the tests that loop over every variant. */
#ifndef LADRC_TEST_VARIANTS_H
#define LADRC_TEST_VARIANTS_H

#include "ladrc/axis.h"

static const ladrc_variant_t TEST_VARIANTS[] = {
    LADRC_VARIANT_LADRC,    LADRC_VARIANT_LP_MLADRC, LADRC_VARIANT_HP_MLADRC, LADRC_VARIANT_PID,
    LADRC_VARIANT_CASCADED, LADRC_VARIANT_INDI,      LADRC_VARIANT_RATE_ADRC};
#define TEST_N_VARIANTS ((int)(sizeof TEST_VARIANTS / sizeof TEST_VARIANTS[0]))

/* Short names as the simulator prints them, by variant number ("?" for a
 * number that is no variant). */
static inline const char *test_variant_name(ladrc_variant_t v)
{
    static const char *const names[LADRC_VARIANT_COUNT] = {"LADRC",    "LP-MLADRC", "HP-MLADRC", "PID",
                                                           "CASCADED", "INDI",      "RATE-ADRC"};
    const unsigned i = (unsigned)v; /* enums may be short and unsigned (-fshort-enums) */
    return (i < (unsigned)LADRC_VARIANT_COUNT) ? names[i] : "?";
}

#endif
