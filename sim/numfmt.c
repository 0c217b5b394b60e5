#include "numfmt.h"

#include <math.h>
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

/* Rounds m >= 0 to the nearest integer; 0 when m is too close to a tie. */
static int round_clear(double m, double *r)
{
    const double fl = floor(m);
    const double frac = m - fl;
    if (fabs(frac - 0.5) < TIE_MARGIN) {
        return 0;
    }
    *r = frac > 0.5 ? fl + 1.0 : fl;
    return 1;
}

/* Writes the decimal digits of the integer r (< 10^16) right-aligned into
 * digits[0..n); returns n. */
static int integer_digits(double r, char *digits)
{
    char tmp[24];
    int n = 0;
    unsigned long long v = (unsigned long long)r;
    do {
        tmp[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v != 0u);
    for (int i = 0; i < n; ++i) {
        digits[i] = tmp[n - 1 - i];
    }
    return n;
}

int sim_fmt_g(char *buf, double x, int precision)
{
    const int p = precision < 1 ? 1 : precision;
    if (p > 15 || !isfinite(x)) {
        return slow_g(buf, x, p);
    }
    if (x == 0.0) {
        strcpy(buf, signbit(x) ? "-0" : "0");
        return signbit(x) ? 2 : 1;
    }
    const double ax = fabs(x);
    /* first guess of the decimal exponent from the binary one: low by at
     * most one (log10(2) rounded down) */
    int be;
    (void)frexp(ax, &be);
    int e = (int)floor((double)(be - 1) * 0.30102999566398119);
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
    int nd = integer_digits(r, digits); /* p digits: 10^(p-1) <= r < 10^p */
    if (nd != p) {
        return slow_g(buf, x, p);
    }
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
    const int nd = integer_digits(r, digits);
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
