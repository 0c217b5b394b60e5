/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Whole numbers as decimal text, for the decoders that write CSV rows
 * (log_bbl.c, log_ulog.c): faster than snprintf on millions of cells.
 */
#ifndef LADRC_SIM_LOG_DIGITS_H
#define LADRC_SIM_LOG_DIGITS_H

#include <stdint.h>

/* u's digits at p (no terminator); returns just past them. */
static inline char *sim_log_put_u64(char *p, uint64_t u)
{
    char digits[20];
    int n = 0;
    do {
        digits[n++] = (char)('0' + u % 10u);
        u /= 10u;
    } while (u != 0);
    while (n > 0) {
        *p++ = digits[--n];
    }
    return p;
}

/* v with its sign at p (no terminator); returns just past it. */
static inline char *sim_log_put_i64(char *p, int64_t v)
{
    if (v < 0) {
        *p++ = '-';
        return sim_log_put_u64(p, (uint64_t)0 - (uint64_t)v);
    }
    return sim_log_put_u64(p, (uint64_t)v);
}

#endif
