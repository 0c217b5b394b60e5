/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The radix-2 FFT the log tools share (spectrum.c, response.c): in place,
 * iterative, on n = 2^k points with a twiddle table of n / 2 entries
 * e^(-2 pi i j / n) (sim_fft_twiddles). Forward only; the inverse is the
 * forward transform of the conjugate (sim_fft_inverse).
 */
#ifndef LADRC_SIM_FFT_H
#define LADRC_SIM_FFT_H

/* tw_re[j], tw_im[j] = cos, -sin of 2 pi j / n for j < n / 2. */
void sim_fft_twiddles(int n, double *tw_re, double *tw_im);

/* The DFT of (re, im) in place: X[k] = sum_j x[j] e^(-2 pi i j k / n). */
void sim_fft(int n, const double *tw_re, const double *tw_im, double *re, double *im);

/* The inverse DFT in place, scaled by 1 / n. */
void sim_fft_inverse(int n, const double *tw_re, const double *tw_im, double *re, double *im);

/* The smallest power of two >= n (n >= 1). */
int sim_fft_size(int n);

#endif
