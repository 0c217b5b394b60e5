/* SPDX-License-Identifier: BSD-3-Clause */
/* DataFlash field kinds: sizes, values, text (log_dataflash_fields.h). */
#include "log_dataflash_fields.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The field kinds' sizes in bytes; 0: not a kind. */
int df_kind_size(char k)
{
    switch (k) {
    case 'b':
    case 'B':
    case 'M':
        return 1;
    case 'h':
    case 'H':
    case 'c':
    case 'C':
    case 'g':
        return 2;
    case 'i':
    case 'I':
    case 'f':
    case 'e':
    case 'E':
    case 'L':
    case 'n':
        return 4;
    case 'd':
    case 'q':
    case 'Q':
        return 8;
    case 'N':
        return 16;
    case 'Z':
    case 'a':
        return 64;
    default:
        return 0;
    }
}

int df_is_integer_kind(char k)
{
    return strchr("bBMhHiIqQcCeEL", k) != NULL;
}

int df_is_text_kind(char k)
{
    return k == 'n' || k == 'N' || k == 'Z';
}

/* Little-endian fields, whatever the host's order. */
uint64_t df_get_le(const unsigned char *p, int size)
{
    uint64_t v = 0;
    for (int i = size - 1; i >= 0; --i) {
        v = (v << 8) | p[i];
    }
    return v;
}

static int64_t get_signed(const unsigned char *p, int size)
{
    const uint64_t v = df_get_le(p, size);
    const int bits = 8 * size;
    if (bits < 64 && (v >> (bits - 1)) != 0) {
        return (int64_t)(v | (~(uint64_t)0 << bits));
    }
    return (int64_t)v;
}

static float get_float(const unsigned char *p)
{
    const uint32_t u = (uint32_t)df_get_le(p, 4);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

double df_get_double(const unsigned char *p)
{
    const uint64_t u = df_get_le(p, 8);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

/* IEEE 754 binary16 to float. */
static float half_to_float(unsigned h)
{
    const int sign = (h >> 15) & 1, e = (h >> 10) & 0x1f;
    const unsigned m = h & 0x3ff;
    float v;
    if (e == 0) {
        v = ldexpf((float)m, -24);
    } else if (e == 31) {
        v = m == 0 ? HUGE_VALF : NAN;
    } else {
        v = ldexpf((float)(m | 0x400), e - 25);
    }
    return sign ? -v : v;
}

/* Raw integer field: its value's magnitude and sign. */
void df_get_integer(const unsigned char *p, char kind, int size, uint64_t *mag, int *neg)
{
    if (strchr("BMHCIEQ", kind) != NULL) {
        *mag = df_get_le(p, size);
        *neg = 0;
    } else {
        const int64_t v = get_signed(p, size);
        *neg = v < 0;
        *mag = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    }
}

/* mag * 10^exp10 in decimal, exactly: the characters written. */
static int put_decimal(char *p, uint64_t mag, int neg, int exp10)
{
    char digits[48];
    int n = 0, w = 0;
    do {
        digits[n++] = (char)('0' + (int)(mag % 10));
        mag /= 10;
    } while (mag != 0);
    const int frac = exp10 < 0 ? -exp10 : 0;
    while (n <= frac) {
        digits[n++] = '0';
    }
    if (neg) {
        p[w++] = '-';
    }
    for (int i = n - 1; i >= 0; --i) {
        p[w++] = digits[i];
        if (i == frac && frac > 0) {
            p[w++] = '.';
        }
    }
    for (int i = 0; i < exp10; ++i) {
        p[w++] = '0';
    }
    return w;
}

static int put_number(char *p, double v, int digits);

/* 10^k for 0 <= k <= 22, each exact in a double. */
static double pow10_exact(int k)
{
    static const double P[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    return P[k];
}

/* A float in 9 significant digits, as "%.9g" writes it but some ten times
 * faster: the float times an exact power of ten, rounded once (so the
 * digits are within one unit of the ninth of the exact ones, 1e-8 relative
 * at most, under half a float's spacing: the text reads back to the
 * float). Values beyond 1e-14..1e30 and non-finite ones go to snprintf. */
static int put_float9(char *p, float f)
{
    const double v = fabs((double)f);
    if (!(v >= 1e-14 && v < 1e30)) {
        return v == 0.0 ? (signbit(f) ? (p[0] = '-', p[1] = '0', 2) : (p[0] = '0', 1)) : put_number(p, (double)f, 9);
    }
    int e10 = (int)floor(log10(v));
    const int k = 8 - e10;
    double scaled = k >= 0 ? v * pow10_exact(k) : v / pow10_exact(-k);
    double n = floor(scaled + 0.5);
    if (n >= 1e9) { /* log10 rounded up to the next decade */
        ++e10;
        n = floor(n / 10.0 + 0.5);
    } else if (n < 1e8) {
        --e10;
        scaled = (k + 1) >= 0 ? v * pow10_exact(k + 1) : v / pow10_exact(-(k + 1));
        n = floor(scaled + 0.5);
    }
    char digits[10];
    uint32_t m = (uint32_t)n;
    for (int i = 8; i >= 0; --i) {
        digits[i] = (char)('0' + (int)(m % 10));
        m /= 10;
    }
    int nd = 9;
    while (nd > 1 && digits[nd - 1] == '0') {
        --nd;
    }
    int w = 0;
    if (f < 0.0f) {
        p[w++] = '-';
    }
    if (e10 < -4 || e10 >= 9) { /* d.ddde[+-]XX */
        p[w++] = digits[0];
        if (nd > 1) {
            p[w++] = '.';
            memcpy(p + w, digits + 1, (size_t)(nd - 1));
            w += nd - 1;
        }
        w += sprintf(p + w, "e%c%02d", e10 < 0 ? '-' : '+', e10 < 0 ? -e10 : e10);
    } else if (e10 < 0) { /* 0.000ddd */
        p[w++] = '0';
        p[w++] = '.';
        for (int i = -1; i > e10; --i) {
            p[w++] = '0';
        }
        memcpy(p + w, digits, (size_t)nd);
        w += nd;
    } else { /* ddd.ddd */
        for (int i = 0; i < nd || i <= e10; ++i) {
            if (i == e10 + 1) {
                p[w++] = '.';
            }
            p[w++] = i < nd ? digits[i] : '0';
        }
    }
    return w;
}

static int put_number(char *p, double v, int digits)
{
    const int n = snprintf(p, DF_CELL_MAX, "%.*g", digits, v);
    return n < 0 ? 0 : (n >= DF_CELL_MAX ? DF_CELL_MAX - 1 : n);
}

/* Text up to its first NUL, with what would break a CSV cell replaced. */
static int put_text(char *p, const unsigned char *s, int size)
{
    int w = 0;
    for (int i = 0; i < size && s[i] != 0; ++i) {
        const unsigned char ch = s[i];
        p[w++] = (ch < 0x20 || ch > 0x7e || ch == ',' || ch == '"') ? '_' : (char)ch;
    }
    return w;
}

/* The field's value as text: the characters written. */
int df_put_field(char *p, const field_t *f, const unsigned char *m)
{
    const unsigned char *v = m + f->offset;
    uint64_t mag;
    int neg;
    switch (f->kind) {
    case 'f': /* a float times its multiplier: a float's digits */
        return put_float9(p, f->mult == 1.0 ? get_float(v) : (float)((double)get_float(v) * f->mult));
    case 'd':
        return put_number(p, df_get_double(v) * f->mult, 17);
    case 'g':
        return put_float9(p, (float)((double)half_to_float((unsigned)df_get_le(v, 2)) * f->mult));
    case 'n':
    case 'N':
    case 'Z':
        return put_text(p, v, f->size);
    case 'a': {
        int w = 0;
        for (int i = 0; i < DF_ARRAY_N; ++i) {
            if (i > 0) {
                p[w++] = ',';
            }
            df_get_integer(v + 2 * i, 'h', 2, &mag, &neg);
            w += put_decimal(p + w, mag, neg, 0);
        }
        return w;
    }
    default:
        df_get_integer(v, f->kind, f->size, &mag, &neg);
        if (f->mult != 1.0) {
            return put_number(p, (neg ? -(double)mag : (double)mag) * f->mult, 17);
        }
        return put_decimal(p, mag, neg, f->exp10);
    }
}
