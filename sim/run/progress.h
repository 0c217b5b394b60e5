/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The progress line ladrc_sil prints on stderr while its runs go: the share
 * of control periods done, the runs done, the time so far and an estimate of
 * the time left, from the pace so far.
 */
#ifndef LADRC_SIM_PROGRESS_H
#define LADRC_SIM_PROGRESS_H

#include <stddef.h>

/* Seconds left when a fraction (0..1) of the work took elapsed_s:
 * elapsed_s (1 - fraction) / fraction; -1 when it cannot be told yet
 * (nothing done, or a fraction that is not a number in (0, 1]). */
double sim_progress_eta_s(double fraction, double elapsed_s);

/* "12 s", "3 min 05 s", "2 h 07 min" (rounded to the unit shown). */
void sim_progress_duration(char *buf, size_t n, double seconds);

/* " 42% (1 of 4 runs done, 3.1 s, about 4 s left)"; the estimate is left
 * out while it cannot be told. */
void sim_progress_text(char *buf, size_t n, double fraction, int runs_done, int runs, double elapsed_s);

#endif
