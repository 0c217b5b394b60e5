/* SPDX-License-Identifier: BSD-3-Clause */
/* Radix-2 FFT (fft.h). */
#include "fft.h"

#include <math.h>

#define PI 3.14159265358979323846

void sim_fft_twiddles(int n, double *tw_re, double *tw_im)
{
    for (int j = 0; j < n / 2; ++j) {
        tw_re[j] = cos(2.0 * PI * j / n);
        tw_im[j] = -sin(2.0 * PI * j / n);
    }
}

void sim_fft(int n, const double *tw_re, const double *tw_im, double *re, double *im)
{
    for (int i = 1, j = 0; i < n; ++i) {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1) {
            j ^= bit;
        }
        j ^= bit;
        if (i < j) {
            double t = re[i];
            re[i] = re[j];
            re[j] = t;
            t = im[i];
            im[i] = im[j];
            im[j] = t;
        }
    }
    for (int len = 2; len <= n; len <<= 1) {
        const int stride = n / len;
        for (int i = 0; i < n; i += len) {
            for (int k = 0; k < len / 2; ++k) {
                const double wr = tw_re[k * stride], wi = tw_im[k * stride];
                const int p = i + k, q = i + k + len / 2;
                const double xr = re[q] * wr - im[q] * wi, xi = re[q] * wi + im[q] * wr;
                re[q] = re[p] - xr;
                im[q] = im[p] - xi;
                re[p] += xr;
                im[p] += xi;
            }
        }
    }
}

void sim_fft_inverse(int n, const double *tw_re, const double *tw_im, double *re, double *im)
{
    for (int i = 0; i < n; ++i) {
        im[i] = -im[i];
    }
    sim_fft(n, tw_re, tw_im, re, im);
    for (int i = 0; i < n; ++i) {
        re[i] /= n;
        im[i] = -im[i] / n;
    }
}

int sim_fft_size(int n)
{
    int m = 1;
    while (m < n) {
        m <<= 1;
    }
    return m;
}
