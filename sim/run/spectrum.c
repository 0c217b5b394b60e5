/* SPDX-License-Identifier: BSD-3-Clause */
/* Welch's PSD (spectrum.h): the FFT (fft.h) of Hann-windowed half-overlapping segments. */
#include "spectrum.h"

#include "fft.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

void sim_spectrum_init(sim_spectrum_t *s, double fs_hz)
{
    memset(s, 0, sizeof *s);
    s->fs_hz = fs_hz;
    for (int i = 0; i < SIM_SPECTRUM_N; ++i) {
        s->window[i] = 0.5 - 0.5 * cos(2.0 * PI * i / SIM_SPECTRUM_N);
        s->window_power += s->window[i] * s->window[i];
    }
    sim_fft_twiddles(SIM_SPECTRUM_N, s->twiddle_re, s->twiddle_im);
}

/* The last SIM_SPECTRUM_N samples, windowed about their mean, into out. */
static void windowed_segment(const sim_spectrum_t *s, double *out)
{
    const int n = SIM_SPECTRUM_N;
    const int start = (int)(s->pushed % n); /* the oldest sample of the ring */
    double mean = 0.0;
    for (int i = 0; i < n; ++i) {
        mean += s->buf[i];
    }
    mean /= n;
    for (int i = 0; i < n; ++i) {
        out[i] = s->window[i] * (s->buf[(start + i) % n] - mean);
    }
}

/* |X[k]|^2 of a segment's transform into the sum, one-sided. */
static void accumulate(sim_spectrum_t *s, int k, double power)
{
    const double one_sided = (k == 0 || k == SIM_SPECTRUM_N / 2) ? 1.0 : 2.0;
    s->sum_psd[k] += one_sided * power / (s->fs_hz * s->window_power);
}

/* The periodogram of the last SIM_SPECTRUM_N samples into the sum. */
static void add_segment(sim_spectrum_t *s)
{
    double re[SIM_SPECTRUM_N], im[SIM_SPECTRUM_N] = {0.0};
    windowed_segment(s, re);
    sim_fft(SIM_SPECTRUM_N, s->twiddle_re, s->twiddle_im, re, im);
    for (int k = 0; k < SIM_SPECTRUM_BINS; ++k) {
        accumulate(s, k, re[k] * re[k] + im[k] * im[k]);
    }
    s->segments++;
}

/* Two spectra's segments in one transform: z = a + i b, and with
 * Z' the conjugate of Z at N - k, A = (Z + Z') / 2 and B = (Z - Z') / 2i. */
static void add_segment_pair(sim_spectrum_t *a, sim_spectrum_t *b)
{
    const int n = SIM_SPECTRUM_N;
    double re[SIM_SPECTRUM_N], im[SIM_SPECTRUM_N];
    windowed_segment(a, re);
    windowed_segment(b, im);
    sim_fft(SIM_SPECTRUM_N, a->twiddle_re, a->twiddle_im, re, im);
    for (int k = 0; k < SIM_SPECTRUM_BINS; ++k) {
        const int m = (n - k) % n;
        const double ar = 0.5 * (re[k] + re[m]), ai = 0.5 * (im[k] - im[m]);
        const double br = 0.5 * (im[k] + im[m]), bi = -0.5 * (re[k] - re[m]);
        accumulate(a, k, ar * ar + ai * ai);
        accumulate(b, k, br * br + bi * bi);
    }
    a->segments++;
    b->segments++;
}

/* 1 when the sample just pushed completes a segment. */
static int segment_due(const sim_spectrum_t *s)
{
    return s->pushed >= SIM_SPECTRUM_N && (s->pushed - SIM_SPECTRUM_N) % (SIM_SPECTRUM_N / 2) == 0;
}

static void store(sim_spectrum_t *s, double x)
{
    s->buf[s->pushed % SIM_SPECTRUM_N] = x;
    s->pushed++;
}

void sim_spectrum_push(sim_spectrum_t *s, double x)
{
    store(s, x);
    if (segment_due(s)) {
        add_segment(s);
    }
}

void sim_spectrum_push_many(sim_spectrum_t *const *s, const double *x, int n)
{
    sim_spectrum_t *waiting = NULL; /* a due segment without its pair yet */
    for (int i = 0; i < n; ++i) {
        store(s[i], x[i]);
        if (!segment_due(s[i])) {
            continue;
        }
        if (waiting != NULL && waiting->fs_hz == s[i]->fs_hz) {
            add_segment_pair(waiting, s[i]);
            waiting = NULL;
        } else if (waiting == NULL) {
            waiting = s[i];
        } else {
            add_segment(s[i]);
        }
    }
    if (waiting != NULL) {
        add_segment(waiting);
    }
}

void sim_spectrum_break(sim_spectrum_t *s)
{
    s->pushed = 0; /* the ring refills before the next segment is due */
}

long sim_spectrum_segments(const sim_spectrum_t *s)
{
    return s->segments;
}

double sim_spectrum_psd(const sim_spectrum_t *s, int k)
{
    return s->segments > 0 ? s->sum_psd[k] / (double)s->segments : NAN;
}

double sim_spectrum_hz(const sim_spectrum_t *s, int k)
{
    return k * s->fs_hz / SIM_SPECTRUM_N;
}

double sim_spectrum_band_rms(const sim_spectrum_t *s, double f_lo_hz, double f_hi_hz)
{
    if (s->segments == 0) {
        return NAN;
    }
    const double df = s->fs_hz / SIM_SPECTRUM_N;
    double power = 0.0;
    for (int k = 1; k < SIM_SPECTRUM_BINS; ++k) {
        const double f = k * df;
        if (f >= f_lo_hz && f < f_hi_hz) {
            power += sim_spectrum_psd(s, k) * df;
        }
    }
    return sqrt(power);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double sim_spectrum_floor(const sim_spectrum_t *s, double f_lo_hz, double f_hi_hz)
{
    double v[SIM_SPECTRUM_BINS];
    int n = 0;
    for (int k = 1; k < SIM_SPECTRUM_BINS && s->segments > 0; ++k) {
        const double f = sim_spectrum_hz(s, k);
        if (f >= f_lo_hz && f <= f_hi_hz) {
            v[n++] = sim_spectrum_psd(s, k);
        }
    }
    if (n == 0) {
        return NAN;
    }
    qsort(v, (size_t)n, sizeof v[0], cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

int sim_spectrum_lines(const sim_spectrum_t *s, double f_lo_hz, double floor_psd, double min_ratio,
                       sim_spectrum_line_t *lines, int max)
{
    int n = 0;
    if (s->segments == 0 || !(floor_psd > 0.0)) {
        return 0;
    }
    const double df = s->fs_hz / SIM_SPECTRUM_N;
    for (int k = 1; k + 1 < SIM_SPECTRUM_BINS; ++k) {
        const double p = sim_spectrum_psd(s, k);
        if (sim_spectrum_hz(s, k) < f_lo_hz || p < min_ratio * floor_psd || p < sim_spectrum_psd(s, k - 1) ||
            p < sim_spectrum_psd(s, k + 1)) {
            continue;
        }
        /* the line's power: its peak and the Hann window's two neighbours, less the floor */
        double power = 0.0;
        for (int j = k - 2; j <= k + 2; ++j) {
            if (j >= 1 && j < SIM_SPECTRUM_BINS) {
                const double excess = sim_spectrum_psd(s, j) - floor_psd;
                power += excess > 0.0 ? excess * df : 0.0;
            }
        }
        const sim_spectrum_line_t line = {sim_spectrum_hz(s, k), sqrt(power), p / floor_psd};
        /* keep the strongest `max`, in order */
        int at = n;
        while (at > 0 && lines[at - 1].rms < line.rms) {
            --at;
        }
        if (at >= max) {
            continue;
        }
        if (n < max) {
            ++n;
        }
        memmove(&lines[at + 1], &lines[at], (size_t)(n - 1 - at) * sizeof lines[0]);
        lines[at] = line;
    }
    return n;
}
