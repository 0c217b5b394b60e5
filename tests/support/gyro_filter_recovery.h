/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the gyro filter promises under hostile rotor speeds and inputs, as
 * numbers a test can check (test_gyro_filter_recovery.c, the fuzz target
 * tests/fuzz/fuzz_gyro_filter.c):
 *
 * - the output bound: |out| <= gfr_output_gain(f) times the largest |sample|
 *   the filter took (inputs, and the values it was put at rest on);
 * - the recovery: once the rotor speeds hold still and the input is steady,
 *   the output comes within gfr_tolerance of a freshly initialised twin at
 *   rest on that input and fed the same tail (its normal output), within
 *   gfr_recovery_ticks_max ticks.
 *
 * Read from the filter's state (its sections), never written.
 */
#ifndef LADRC_TEST_GYRO_FILTER_RECOVERY_H
#define LADRC_TEST_GYRO_FILTER_RECOVERY_H

#include "ladrc/gyro_filter.h"

#include <math.h>
#include <stddef.h>

/* The long loops of the checks below are the fuzz target's yardstick, not
 * what it explores: left out of libFuzzer's coverage and comparison tracing,
 * which would otherwise take most of its time. */
#if defined(__clang__)
#define GFR_NOT_TRACED __attribute__((no_sanitize("coverage")))
#else
#define GFR_NOT_TRACED
#endif

/* Longest impulse response summed for a section's gain (ticks): 40 time
 * constants of a section whose poles sit at radius 1 - 1/2000, which leaves
 * e^-40 of it. A slower section's gain is not computed (gfr_section_gain
 * gives -1): its tests skip what needs it. */
#define GFR_GAIN_TICKS_MAX 80000L
/* Sum of |h| stops once the section's history is below this part of the sum
 * so far: the geometric rest is smaller than that times its time constant,
 * under 1e-9 of the sum for any section summed (time constants under 2000). */
#define GFR_GAIN_REST 1e-12

/* Tolerance of the recovery (the channels' units; gfr_tolerance): GFR_TOL_ABS
 * is a tenth of the white noise of a MEMS gyro over a 1 kHz band (some
 * 0.01 rad/s), so the gap to the twin is below what the sensor resolves. On
 * top, for float's rounding on a steady input x, two terms of x:
 * - a section's fixed point: y = x is the difference of terms of size
 *   (|b0| + |b1| + |b2| + |a1| + |a2|) |x|, rounded, and the error feeds back
 *   with a gain of 1 / |1 + a1 + a2| (large for a section far below Nyquist
 *   or a very wide notch), so a copy rests anywhere within about an eps of
 *   that of x: GFR_DEADBAND_EPS eps per section, summed (measured 2.1e-4 of x
 *   behind two notches of Q 0.002 at 225 Hz, 8 kHz, where this gives 7.6e-4);
 * - a limit cycle of its own instead, a few ulps of x times a section's
 *   resonance: measured up to 7e-6 of x (+-0.02 on 6470, for good, behind
 *   Q 6 notches at 340-410 Hz, 1 kHz), GFR_TOL_OF_TAIL 1e-4 with a margin of 14.
 * (A worst-case bound of the rounding through each section's recursion and
 * the sections after it comes to 18 on an input of 0.5 on the full bank of
 * test_gyro_filter_recovery.c: of no use as a tolerance.) */
#define GFR_TOL_ABS 1e-3
#define GFR_TOL_OF_TAIL 1e-4
#define GFR_DEADBAND_EPS 2.0

/* Ticks added to the recovery bound: the chain's delay and a few ticks of a
 * fast section that rounds its last error away. */
#define GFR_RECOVERY_SLACK_TICKS 64.0

/* Radius of a section's largest pole: the roots of z^2 + a1 z + a2. */
static inline double gfr_pole_radius(const ladrc_gyro_filter_section_t *s)
{
    const double a1 = (double)s->a1, a2 = (double)s->a2;
    const double disc = a1 * a1 - 4.0 * a2;
    if (disc < 0.0) {
        return sqrt(a2); /* complex pair: |z|^2 = a2 */
    }
    return 0.5 * (fabs(a1) + sqrt(disc));
}

/* The section's time constant in ticks (-1 / ln of its largest pole's radius;
 * 0 for a section whose poles are at the origin). */
static inline double gfr_time_constant_ticks(const ladrc_gyro_filter_section_t *s)
{
    const double r = gfr_pole_radius(s);
    return (r > 0.0) ? -1.0 / log(r) : 0.0;
}

/* The section's gain on any bounded input: the sum of |h_k| of its impulse
 * response (its coefficients as rounded, in double); the factor by which its
 * output can exceed its largest input. -1 when the section is too slow to sum
 * (GFR_GAIN_TICKS_MAX). */
GFR_NOT_TRACED static inline double gfr_section_gain(const ladrc_gyro_filter_section_t *s)
{
    const double b0 = (double)s->b0, b1 = (double)s->b1, b2 = (double)s->b2;
    const double a1 = (double)s->a1, a2 = (double)s->a2;
    double x1 = 0.0, x2 = 0.0, y1 = 0.0, y2 = 0.0, sum = 0.0;
    for (long k = 0; k < GFR_GAIN_TICKS_MAX; ++k) {
        const double x = (k == 0) ? 1.0 : 0.0;
        const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
        sum += fabs(y);
        x2 = x1;
        x1 = x;
        y2 = y1;
        y1 = y;
        if (k > 2 && fabs(y1) + fabs(y2) < GFR_GAIN_REST * sum) {
            return sum;
        }
    }
    return -1.0;
}

/* Index one past the last RPM notch of the chain. */
static inline unsigned gfr_rpm_end(const ladrc_gyro_filter_t *f)
{
    return (unsigned)f->rpm_first + (unsigned)f->rpm_rotors * f->rpm_harmonics;
}

/*
 * The chain's output bound per unit of the largest sample taken, from its
 * design: the fixed notches are fixed linear sections, each multiplies the
 * bound on its input by its gain (gfr_section_gain); an RPM notch's output is
 * held within LADRC_GYRO_FILTER_RPM_GAIN_BOUND times the input envelope (at
 * most the largest sample) and blends with its input (out = x + w (y - x),
 * w in [0, 1]: within the larger of the two), so the bank's output is within
 * the larger of the fixed notches' bound and the RPM bound; the low-pass
 * multiplies by its gain. -1 when a section is too slow to have its gain.
 */
static inline double gfr_output_gain(const ladrc_gyro_filter_t *f)
{
    const unsigned rpm_end = gfr_rpm_end(f);
    double g = 1.0;
    for (unsigned i = 0u; i < f->rpm_first; ++i) {
        const double gi = gfr_section_gain(&f->section[i]);
        if (gi < 0.0) {
            return -1.0;
        }
        g *= gi;
    }
    if (f->rpm_rotors > 0u && g < (double)LADRC_GYRO_FILTER_RPM_GAIN_BOUND) {
        g = (double)LADRC_GYRO_FILTER_RPM_GAIN_BOUND;
    }
    if (f->n_sections > rpm_end) {
        const double glp = gfr_section_gain(&f->section[rpm_end]);
        if (glp < 0.0) {
            return -1.0;
        }
        g *= glp;
    }
    return g;
}

/* The slowest time constant (ticks) of the sections that are on (weight > 0)
 * as the filter's centres now stand; *sum gets the sum of theirs. */
static inline double gfr_slowest_ticks(const ladrc_gyro_filter_t *f, double *sum)
{
    double tau = 0.0, total = 0.0;
    for (unsigned i = 0u; i < f->n_sections; ++i) {
        if (f->section[i].weight > LADRC_R(0.0)) {
            const double t = gfr_time_constant_ticks(&f->section[i]);
            tau = fmax(tau, t);
            total += t;
        }
    }
    if (sum != NULL) {
        *sum = total;
    }
    return tau;
}

/* The recovery's tolerance for f as its centres now stand, on a steady input
 * of magnitude tail_abs. */
static inline double gfr_tolerance(const ladrc_gyro_filter_t *f, double tail_abs)
{
    double deadband = 0.0; /* per eps of the input */
    for (unsigned i = 0u; i < f->n_sections; ++i) {
        const ladrc_gyro_filter_section_t *s = &f->section[i];
        if (s->weight > LADRC_R(0.0)) {
            const double terms = fabs((double)s->b0) + fabs((double)s->b1) + fabs((double)s->b2) + fabs((double)s->a1) +
                                 fabs((double)s->a2);
            deadband += terms / fabs(1.0 + (double)s->a1 + (double)s->a2);
        }
    }
    return GFR_TOL_ABS + (GFR_TOL_OF_TAIL + GFR_DEADBAND_EPS * (double)LADRC_REAL_EPS * deadband) * tail_abs;
}

/*
 * The recovery bound (ticks). With the centres still, the chain is a fixed
 * stable filter, and the gap between two copies of it fed the same input is
 * its response to their difference of state. A cascade of m sections of time
 * constant tau answers like the tail of a Gamma(m, tau) law, e^-x x^(m-1) /
 * (m-1)! at x = k / tau, which is below e^-L (L = ln(error0 / tol)) once
 * x >= 2 L + 1.4 (m - 1) (from ln y <= y / 2 + ln 2 - 1); with unequal
 * sections, tau_max for tau and the sum of their time constants for
 * (m - 1) tau: 2 (tau_max L + sum tau), plus GFR_RECOVERY_SLACK_TICKS.
 * The input envelope's 1 s decay does not enter: each RPM notch's bound is
 * at least the twin's (the envelope of the filter that saw more is the
 * larger), so holding an output within it only brings it nearer the twin's.
 */
static inline double gfr_recovery_ticks_max(const ladrc_gyro_filter_t *f, double error0, double tol)
{
    double sum = 0.0;
    const double slowest = gfr_slowest_ticks(f, &sum);
    const double decay = (error0 > tol) ? log(error0 / tol) : 0.0;
    return 2.0 * (slowest * decay + sum) + GFR_RECOVERY_SLACK_TICKS;
}

/*
 * Flies f and twin on a steady tail: the rotors at tail_hz (NULL without an
 * RPM bank), tail_in on every tick. The twin is freshly initialised with cfg
 * and put at rest on tail_in: the filter's normal output on that tail, as if
 * it had never seen anything else.
 * Stops after max_ticks, or once every channel has stayed within tol of the
 * twin for quiet_ticks ticks in a row. Returns the ticks until the output
 * stayed within tol (the tick after the last one beyond it), or -1 when a
 * step faulted, an output was not finite, or the output was beyond tol on the
 * last tick flown. *worst_gap gets the largest |f - twin| of the last tick.
 */
GFR_NOT_TRACED static inline long gfr_fly_tail(ladrc_gyro_filter_t *f, ladrc_gyro_filter_t *twin,
                                               const ladrc_gyro_filter_config_t *cfg, const ladrc_real_t *tail_hz,
                                               const ladrc_real_t *tail_in, double tol, long max_ticks,
                                               long quiet_ticks, double *worst_gap)
{
    long last_beyond = -1;
    double gap = 0.0;
    if (ladrc_gyro_filter_init(twin, cfg) != LADRC_OK) {
        return -1;
    }
    ladrc_gyro_filter_reset(twin, tail_in); /* its normal output: as if it had seen nothing else */
    if (tail_hz != NULL && (ladrc_gyro_filter_set_rotor_hz(f, tail_hz) != LADRC_FAULT_NONE ||
                            ladrc_gyro_filter_set_rotor_hz(twin, tail_hz) != LADRC_FAULT_NONE)) {
        return -1;
    }
    for (long k = 0; k < max_ticks && k - last_beyond <= quiet_ticks; ++k) {
        ladrc_real_t y[LADRC_GYRO_FILTER_MAX_CHANNELS], y_twin[LADRC_GYRO_FILTER_MAX_CHANNELS];
        if (ladrc_gyro_filter_step(f, tail_in, y) != LADRC_FAULT_NONE ||
            ladrc_gyro_filter_step(twin, tail_in, y_twin) != LADRC_FAULT_NONE) {
            return -1;
        }
        gap = 0.0;
        for (unsigned ch = 0u; ch < cfg->channels; ++ch) {
            const double d = fabs((double)y[ch] - (double)y_twin[ch]);
            if (!(d <= tol)) { /* NaN counts as beyond */
                last_beyond = k;
            }
            gap = fmax(gap, d);
        }
    }
    if (worst_gap != NULL) {
        *worst_gap = gap;
    }
    return (gap <= tol) ? last_beyond + 1 : -1;
}

#endif
