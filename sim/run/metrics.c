/* SPDX-License-Identifier: BSD-3-Clause */
#include "metrics.h"

#include <math.h>

void sim_stat_add(sim_stat_t *s, double x)
{
    s->n++;
    const double delta = x - s->mean;
    s->mean += delta / (double)s->n;
    s->m2 += delta * (x - s->mean);
    if (fabs(x) > s->max_abs) {
        s->max_abs = fabs(x);
    }
}

double sim_stat_std(const sim_stat_t *s)
{
    return s->n > 0 ? sqrt(s->m2 / (double)s->n) : 0.0;
}

double sim_stat_rms(const sim_stat_t *s)
{
    const double sd = sim_stat_std(s);
    return sqrt(sd * sd + s->mean * s->mean);
}
