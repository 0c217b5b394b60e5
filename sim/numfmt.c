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
    *r = frac > 0.5 ? fl + 1.0 : fl;
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

int sim_fmt_g(char *buf, double x, int precision)
{
    const int p = precision < 1 ? 1 : precision;
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
