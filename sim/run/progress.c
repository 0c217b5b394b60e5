/* SPDX-License-Identifier: BSD-3-Clause */
/* The progress line (see progress.h). */
#include "progress.h"

#include <stdio.h>

double sim_progress_eta_s(double fraction, double elapsed_s)
{
    if (!(fraction > 0.0 && fraction <= 1.0) || !(elapsed_s >= 0.0)) {
        return -1.0;
    }
    return elapsed_s * (1.0 - fraction) / fraction;
}

void sim_progress_duration(char *buf, size_t n, double seconds)
{
    if (seconds < 59.5) {
        snprintf(buf, n, "%.0f s", seconds);
    } else if (seconds < 3599.5) {
        const long s = (long)(seconds + 0.5);
        snprintf(buf, n, "%ld min %02ld s", s / 60, s % 60);
    } else {
        const long min = (long)(seconds / 60.0 + 0.5);
        snprintf(buf, n, "%ld h %02ld min", min / 60, min % 60);
    }
}

void sim_progress_text(char *buf, size_t n, double fraction, int runs_done, int runs, double elapsed_s)
{
    char left[48] = "";
    const double eta = sim_progress_eta_s(fraction, elapsed_s);
    if (eta >= 0.0) {
        char text[32];
        sim_progress_duration(text, sizeof text, eta);
        snprintf(left, sizeof left, ", about %s left", text);
    }
    snprintf(buf, n, "%3.0f%% (%d of %d runs done, %.1f s%s)", 100.0 * fraction, runs_done, runs, elapsed_s, left);
}
