/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Second-order sections for the flight-log tools (the identification's
 * band-pass, the noise series' high-pass): Butterworth-type low- and
 * high-pass of quality q, bilinear with a prewarped corner, stepped in
 * transposed direct form II, in double.
 */
#ifndef LADRC_SIM_BIQUAD_H
#define LADRC_SIM_BIQUAD_H

#include <math.h>

#define BIQUAD_Q_BUTTERWORTH 0.70710678118654752 /* a second-order Butterworth section's quality */

typedef struct {
    double b0, b1, b2, a1, a2;
} biquad_coef_t;

typedef struct {
    double z1, z2;
} biquad_t;

/* The low-pass section of corner fc_hz and quality q (1/sqrt(2): Butterworth). */
static inline biquad_coef_t biquad_lowpass(double fc_hz, double dt_s, double q)
{
    const double k = tan(3.14159265358979323846 * fc_hz * dt_s), norm = 1.0 / (1.0 + k / q + k * k);
    const biquad_coef_t c = {k * k * norm, 2.0 * k * k * norm, k * k * norm, 2.0 * (k * k - 1.0) * norm,
                             (1.0 - k / q + k * k) * norm};
    return c;
}

/* The high-pass section of corner fc_hz and quality q. */
static inline biquad_coef_t biquad_highpass(double fc_hz, double dt_s, double q)
{
    const double k = tan(3.14159265358979323846 * fc_hz * dt_s), norm = 1.0 / (1.0 + k / q + k * k);
    const biquad_coef_t c = {norm, -2.0 * norm, norm, 2.0 * (k * k - 1.0) * norm, (1.0 - k / q + k * k) * norm};
    return c;
}

static inline double biquad_step(const biquad_coef_t *c, biquad_t *s, double x)
{
    const double y = c->b0 * x + s->z1;
    s->z1 = c->b1 * x - c->a1 * y + s->z2;
    s->z2 = c->b2 * x - c->a2 * y;
    return y;
}

/* The state of a section settled on a constant input x. */
static inline void biquad_settle(const biquad_coef_t *c, biquad_t *s, double x)
{
    const double gain = (c->b0 + c->b1 + c->b2) / (1.0 + c->a1 + c->a2);
    const double y = gain * x;
    s->z2 = c->b2 * x - c->a2 * y;
    s->z1 = c->b1 * x - c->a1 * y + s->z2;
}

#endif
