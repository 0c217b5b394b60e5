/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Counter-based draws of campaign runs (campaign.h): SplitMix64 streams
 * keyed by (seed, run, key), a [draw] key's value for a run, and the texts
 * of values and run names.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "campaign.h"
#include "run/numfmt.h"
#include "plant/rng.h"

#define TWO_PI 6.28318530717958647692

/* The first SplitMix64 output from counter x: a bijective 64-bit mix. */
static uint64_t mix64(uint64_t x)
{
    return sim_rng_splitmix64(&x);
}

uint64_t sim_campaign_stream(uint64_t seed, long r, int k, int i)
{
    uint64_t state = mix64(mix64(mix64(seed) ^ (uint64_t)r) ^ (uint64_t)k);
    uint64_t out = 0;
    for (int j = 0; j < i; ++j) {
        out = sim_rng_splitmix64(&state);
    }
    return out;
}

double sim_campaign_uniform(uint64_t seed, long r, int k, int i)
{
    /* the top 53 bits, centred in their interval: 2^53 values evenly spaced
     * in (0, 1), symmetric about 1/2, never 0 (log) nor 1 */
    return ((double)(sim_campaign_stream(seed, r, k, i) >> 11) + 0.5) * 0x1.0p-53;
}

static double clamp(double v, double lo, double hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

double sim_campaign_draw(const sim_campaign_t *c, const sim_campaign_key_t *key, long r)
{
    const double u = sim_campaign_uniform(c->seed, r, key->draw_index, 1);
    switch (key->dist) {
    case SIM_DRAW_NORMAL: {
        /* Box-Muller: u and a second uniform of the same stream */
        const double u2 = sim_campaign_uniform(c->seed, r, key->draw_index, 2);
        return key->a + key->b * sqrt(-2.0 * log(u)) * cos(TWO_PI * u2);
    }
    case SIM_DRAW_LOG_UNIFORM: {
        const double la = log(key->a);
        return clamp(exp(la + (log(key->b) - la) * u), key->a, key->b);
    }
    default:
        return clamp(key->a + (key->b - key->a) * u, key->a, key->b);
    }
}

int sim_campaign_format_value(char *buf, double x)
{
    /* the shortest of the texts %.Pg, P = 1..17, that read back (the
     * smallest P among equals): 100 is "100" rather than %.1g's "1e+02" */
    char tmp[SIM_NUMFMT_MAX];
    int best = -1;
    for (int p = 1; p <= 17; ++p) {
        /* sim_fmt_g is printf's %.Pg up to 15 digits; 16 and 17 from printf */
        const int len = p <= 15 ? sim_fmt_g(tmp, x, p) : snprintf(tmp, sizeof tmp, "%.*g", p, x);
        if ((best < 0 || len < best) && len < SIM_CAMPAIGN_VALUE_LEN && strtod(tmp, NULL) == x) {
            memcpy(buf, tmp, (size_t)len + 1u);
            best = len;
        }
    }
    /* %.17g of a finite double always reads back, in at most 24 chars */
    return best;
}

void sim_campaign_run_name(char *buf, size_t n, long r)
{
    snprintf(buf, n, "%05ld", r);
}
