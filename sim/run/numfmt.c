/* SPDX-License-Identifier: BSD-3-Clause */
#include "numfmt.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* 10^0 .. 10^22 are exact in double. */
static const double POW10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* Half-way cases closer than this (in units of the last digit) go to
 * snprintf: the scaled value carries a relative error of 2^-53, below 1e-9
 * of a unit for the at most 15 digits asked for. */
#define TIE_MARGIN 1e-6

static int slow_g(char *buf, double x, int precision)
{
    return snprintf(buf, SIM_NUMFMT_MAX, "%.*g", precision, x);
}

/* x * 10^k with one rounding, for |k| <= 22; 0 when out of that range. */
static int scale10(double x, int k, double *out)
{
    if (k > 22 || k < -22) {
        return 0;
    }
    *out = k >= 0 ? x * POW10[k] : x / POW10[-k];
    return 1;
}

/* Rounds m >= 0 (below 2^62) to the nearest integer; 0 when m is too close
 * to a tie. */
static int round_clear(double m, double *r)
{
    const double fl = (double)(long long)m; /* floor for these m, without a call */
    const double frac = m - fl;
    if (fabs(frac - 0.5) < TIE_MARGIN) {
        return 0;
    }
    *r = fl + (double)(frac > 0.5); /* no branch: the digit after is anything */
    return 1;
}

static const char PAIRS[] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                            "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                            "8081828384858687888990919293949596979899";

/* Writes the n lowest decimal digits of v into digits[0..n), two at a time. */
static void write_digits(uint64_t v, int n, char *digits)
{
    int i = n;
    while (v >= UINT64_C(0x100000000) && i >= 2) {
        const uint64_t q = v / 100u;
        memcpy(&digits[i - 2], &PAIRS[2u * (unsigned)(v - 100u * q)], 2);
        v = q;
        i -= 2;
    }
    uint32_t w = (uint32_t)v;
    while (i >= 2) {
        const uint32_t q = w / 100u;
        memcpy(&digits[i - 2], &PAIRS[2u * (w - 100u * q)], 2);
        w = q;
        i -= 2;
    }
    if (i == 1) {
        digits[0] = (char)('0' + w % 10u);
    }
}

/* Number of decimal digits of v (1 for 0). */
static int count_digits(uint64_t v)
{
    int n = 1;
    while (n < 20 && v >= (uint64_t)POW10[n]) {
        ++n;
    }
    return n;
}

/* "%.<p>g" for any p (1 .. 15 through the scaled integer, others and the
 * cases it cannot decide through snprintf). */
static int fmt_g_general(char *buf, double x, int p)
{
    if (p > 15 || isinf(x)) {
        return slow_g(buf, x, p);
    }
    if (isnan(x)) { /* the PID's missing estimate: every row */
        strcpy(buf, signbit(x) ? "-nan" : "nan");
        return signbit(x) ? 4 : 3;
    }
    if (x == 0.0) {
        strcpy(buf, signbit(x) ? "-0" : "0");
        return signbit(x) ? 2 : 1;
    }
    const double ax = fabs(x);
    /* first guess of the decimal exponent from the binary one: low by at
     * most one (log10(2) rounded down) */
    uint64_t bits;
    memcpy(&bits, &ax, sizeof bits);
    const int be = (int)(bits >> 52) - 1022; /* ax in [2^(be-1), 2^be) when normal */
    if (be <= -1021) {
        return slow_g(buf, x, p); /* subnormal */
    }
    /* floor((be - 1) log10(2)) with 78913 / 2^18 just below log10(2) */
    const int q = (be - 1) * 78913;
    int e = q >= 0 ? q / (1 << 18) : -((-q + (1 << 18) - 1) / (1 << 18));
    double m = 0.0, r = 0.0;
    int settled = 0;
    for (int tries = 0; tries < 3 && !settled; ++tries) {
        if (!scale10(ax, p - 1 - e, &m)) {
            return slow_g(buf, x, p);
        }
        const double low = POW10[p - 1] - 0.5, high = POW10[p] - 0.5;
        if (fabs(m - low) < TIE_MARGIN || fabs(m - high) < TIE_MARGIN) {
            return slow_g(buf, x, p); /* a tie at a change of exponent */
        }
        if (m < low) {
            --e; /* the guess was one too high */
        } else if (m >= high) {
            ++e; /* one too low, or rounds up to the next power */
        } else {
            settled = 1;
        }
    }
    if (!settled || !round_clear(m, &r)) {
        return slow_g(buf, x, p);
    }
    char digits[24];
    int nd = p; /* settled: 10^(p-1) <= r < 10^p */
    write_digits((uint64_t)r, p, digits);
    while (nd > 1 && digits[nd - 1] == '0') {
        --nd; /* %g drops trailing zeros */
    }
    char *o = buf;
    if (x < 0.0) {
        *o++ = '-';
    }
    if (e < -4 || e >= p) {
        *o++ = digits[0];
        if (nd > 1) {
            *o++ = '.';
            memcpy(o, digits + 1, (size_t)(nd - 1));
            o += nd - 1;
        }
        *o++ = 'e';
        *o++ = e < 0 ? '-' : '+';
        const int ae = e < 0 ? -e : e;
        if (ae >= 100) {
            *o++ = (char)('0' + ae / 100);
        }
        *o++ = (char)('0' + (ae / 10) % 10);
        *o++ = (char)('0' + ae % 10);
    } else if (e >= 0) {
        const int int_digits = e + 1;
        for (int i = 0; i < int_digits; ++i) {
            *o++ = i < nd ? digits[i] : '0';
        }
        if (nd > int_digits) {
            *o++ = '.';
            memcpy(o, digits + int_digits, (size_t)(nd - int_digits));
            o += nd - int_digits;
        }
    } else {
        *o++ = '0';
        *o++ = '.';
        for (int i = 0; i < -e - 1; ++i) {
            *o++ = '0';
        }
        memcpy(o, digits, (size_t)nd);
        o += nd;
    }
    *o = '\0';
    return (int)(o - buf);
}

/* Precisions up to this many digits take the short path: the digits of one
 * 32-bit integer, written 8 at a time. */
#define SHORT_DIGITS 8

/* The 8 decimal digits of v < 10^8, zero-padded, into d[0..8). */
static void write8(uint32_t v, char *d)
{
    const uint32_t hi = v / 10000u, lo = v - 10000u * hi;
    const uint32_t h1 = hi / 100u, h2 = hi - 100u * h1, l1 = lo / 100u, l2 = lo - 100u * l1;
    memcpy(d, &PAIRS[2u * h1], 2);
    memcpy(d + 2, &PAIRS[2u * h2], 2);
    memcpy(d + 4, &PAIRS[2u * l1], 2);
    memcpy(d + 6, &PAIRS[2u * l2], 2);
}

/* "%.<p>g" for p <= SHORT_DIGITS of the values the time series mostly hold:
 * from 1e-300 to 1e300 in magnitude. The same scaling, tie margin and rounding
 * as fmt_g_general, with fewer branches: fixed-size copies (the buffer has
 * room for SIM_NUMFMT_MAX chars, beyond what is written). Returns -1 for
 * everything else, and for whatever fmt_g_general would hand to snprintf. */
static int fmt_g_short(char *buf, double x, int p)
{
    const double ax = fabs(x);
    if (!(ax >= 1e-300 && ax <= 1e300)) {
        return -1; /* zero, NaN, infinite, tiny or huge: fmt_g_general's */
    }
    uint64_t bits;
    memcpy(&bits, &ax, sizeof bits);
    const int be = (int)(bits >> 52) - 1022; /* ax in [2^(be-1), 2^be) */
    /* floor((be - 1) log10(2)): the decimal exponent, or one below it */
    const int q = (be - 1) * 78913;
    int e = q >= 0 ? q / (1 << 18) : -((-q + (1 << 18) - 1) / (1 << 18));
    double m;
    if (!scale10(ax, p - 1 - e, &m)) {
        return -1;
    }
    const double low = POW10[p - 1] - 0.5, high = POW10[p] - 0.5;
    if (m >= high - TIE_MARGIN) { /* one too low, or rounds up to the next power */
        ++e;
        if (fabs(m - high) < TIE_MARGIN || !scale10(ax, p - 1 - e, &m)) {
            return -1;
        }
    }
    double r;
    if (!(m > low + TIE_MARGIN && m < high - TIE_MARGIN) || !round_clear(m, &r)) {
        return -1;
    }
    char d[2 * SHORT_DIGITS];
    memset(d + SHORT_DIGITS, '0', SHORT_DIGITS); /* read by the fixed-size copies, never written out */
    write8((uint32_t)r, d);
    const char *digits = d + SHORT_DIGITS - p; /* 10^(p-1) <= r < 10^p: p digits */
    int nd = p;
    while (nd > 1 && digits[nd - 1] == '0') {
        --nd; /* %g drops trailing zeros */
    }
    char *o = buf;
    *o = '-';
    o += x < 0.0;
    if (e < -4 || e >= p) { /* d.ddde+XX */
        *o = digits[0];
        o += 1;
        if (nd > 1) {
            *o = '.';
            memcpy(o + 1, digits + 1, SHORT_DIGITS);
            o += nd;
        }
        o[0] = 'e';
        o[1] = e < 0 ? '-' : '+';
        o += 2;
        const unsigned ae = (unsigned)(e < 0 ? -e : e); /* below 310 */
        *o = (char)('0' + ae / 100u);
        o += ae >= 100u;
        memcpy(o, &PAIRS[2u * (ae % 100u)], 2);
        o += 2;
    } else if (e >= 0) { /* e + 1 integer digits, then the fraction if any */
        memcpy(o, digits, SHORT_DIGITS);
        o += e + 1;
        if (nd > e + 1) {
            *o = '.';
            memcpy(o + 1, digits + e + 1, SHORT_DIGITS);
            o += nd - e;
        }
    } else { /* "0." and -e - 1 zeros before the digits */
        memcpy(o, "0.000000", SHORT_DIGITS);
        o += 1 - e;
        memcpy(o, digits, SHORT_DIGITS);
        o += nd;
    }
    *o = '\0';
    return (int)(o - buf);
}

int sim_fmt_g(char *buf, double x, int precision)
{
    const int p = precision < 1 ? 1 : precision;
    if (x == 0.0) { /* the zeros of a time series: many */
        strcpy(buf, signbit(x) ? "-0" : "0");
        return signbit(x) ? 2 : 1;
    }
    const int n = p <= SHORT_DIGITS ? fmt_g_short(buf, x, p) : -1;
    return n >= 0 ? n : fmt_g_general(buf, x, p);
}

int sim_fmt_f4(char *buf, double x)
{
    double r;
    if (!isfinite(x) || fabs(x) >= 1e11 || !round_clear(fabs(x) * 1e4, &r)) {
        return snprintf(buf, SIM_NUMFMT_MAX, "%.4f", x);
    }
    char digits[24];
    const int nd = count_digits((uint64_t)r);
    write_digits((uint64_t)r, nd, digits);
    char *o = buf;
    if (signbit(x)) {
        *o++ = '-'; /* printf keeps the sign of values that round to 0 */
    }
    const int int_digits = nd > 4 ? nd - 4 : 0;
    if (int_digits == 0) {
        *o++ = '0';
    } else {
        memcpy(o, digits, (size_t)int_digits);
        o += int_digits;
    }
    *o++ = '.';
    for (int i = nd; i < 4; ++i) {
        *o++ = '0';
    }
    memcpy(o, digits + int_digits, (size_t)(nd - int_digits));
    o += nd - int_digits;
    *o = '\0';
    return (int)(o - buf);
}
