/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Unit suffixes of column names, as blackbox_decode writes them under its
 * unit flags: `time (us)`, `time (s)`, `gyroADC[0] (deg/s)`, `vbatLatest (V)`.
 * A column is named `BASE` or `BASE (UNIT)`; a mapping term may name the
 * unit it wants (`gyroADC[0] (deg/s)`), and a header cell of the same base
 * in another unit of the same quantity is read converted to it.
 */
#ifndef LADRC_SIM_LOG_UNITS_H
#define LADRC_SIM_LOG_UNITS_H

#include <stddef.h>

/* Splits `BASE (UNIT)` into its base (without the blank before the
 * parenthesis) and its unit; a name without a parenthesised tail is all
 * base, *unit_len 0. */
void sim_log_unit_split(const char *name, size_t len, size_t *base_len, const char **unit, size_t *unit_len);

/* The factor that takes a value in unit `from` to unit `to` (both known and
 * of one quantity): 0 with *factor set, -1 otherwise. */
int sim_log_unit_factor(const char *from, size_t from_len, const char *to, size_t to_len, double *factor);

#endif
