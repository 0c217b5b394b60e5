/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Number formatting for the time series, the same text as printf's "%.Pg"
 * and "%.4f" character for character, several times faster. The common
 * case scales the value to an integer of P digits with one correctly rounded
 * operation by an exact power of ten; whenever that could round differently
 * from printf (within 1e-6 of a unit of a rounding tie, beyond the exact
 * powers 1e-22..1e22, subnormal, infinite) it asks snprintf. Zeros keep
 * their sign and NaN is written as glibc writes it ("nan", "-nan"); the
 * test compares every case with snprintf.
 */
#ifndef LADRC_SIM_NUMFMT_H
#define LADRC_SIM_NUMFMT_H

#include <stddef.h>

/* Longest text either function writes, terminating NUL included (%.4f of
 * the largest double has 309 integer digits). */
#define SIM_NUMFMT_MAX 320

/* Writes x as printf's "%.<precision>g" (precision 1..15) to buf, which has
 * room for SIM_NUMFMT_MAX chars; returns the length without the NUL. */
int sim_fmt_g(char *buf, double x, int precision);

/* Writes x as printf's "%.4f"; same buffer and return value. */
int sim_fmt_f4(char *buf, double x);

#endif
