/* SPDX-License-Identifier: BSD-3-Clause */
/* The log's gyro filters' delay and attenuation (gyro_filter.h). */
#include "gyro_filter.h"

#include <math.h>
#include <stdlib.h>

#define TAPS SIM_GYRO_FILTER_TAPS
#define PI 3.14159265358979323846

typedef struct {
    double raw_prev, filt_prev;
    int started;
    double ring_x[TAPS + 1], ring_y[TAPS + 1]; /* the differences, newest at pos */
    int pos;
    long long n;
    double auto_raw[TAPS + 1];  /* sum dx[k] dx[k - m] */
    double cross_pos[TAPS + 1]; /* sum dy[k] dx[k - m]: the filter's output after its input */
    double cross_neg[TAPS + 1]; /* sum dy[k - m] dx[k] */
    sim_spectrum_t raw, filtered;
} axis_state_t;

struct sim_gyro_filter {
    double dt_s;
    axis_state_t axis[3];
};

sim_gyro_filter_t *sim_gyro_filter_new(double dt_s)
{
    if (!(dt_s > 0.0)) {
        return NULL;
    }
    sim_gyro_filter_t *g = calloc(1, sizeof *g);
    if (g == NULL) {
        return NULL;
    }
    g->dt_s = dt_s;
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&g->axis[i].raw, 1.0 / dt_s);
        sim_spectrum_init(&g->axis[i].filtered, 1.0 / dt_s);
    }
    return g;
}

void sim_gyro_filter_free(sim_gyro_filter_t *g)
{
    free(g);
}

static void add_axis(axis_state_t *a, double x, double y)
{
    if (!isfinite(x) || !isfinite(y)) {
        a->started = 0;
        sim_spectrum_break(&a->raw); /* no segment across the gap */
        sim_spectrum_break(&a->filtered);
        return;
    }
    sim_spectrum_push(&a->raw, x);
    sim_spectrum_push(&a->filtered, y);
    if (!a->started) {
        a->raw_prev = x;
        a->filt_prev = y;
        a->started = 1;
        a->n = 0; /* the rings refill after a gap: no product spans it */
        return;
    }
    const double dx = x - a->raw_prev, dy = y - a->filt_prev;
    a->raw_prev = x;
    a->filt_prev = y;
    a->pos = (a->pos + 1) % (TAPS + 1);
    a->ring_x[a->pos] = dx;
    a->ring_y[a->pos] = dy;
    a->n++;
    const int reach = a->n <= TAPS ? (int)a->n : TAPS + 1;
    for (int m = 0; m < reach; ++m) {
        const int at = (a->pos - m + TAPS + 1) % (TAPS + 1);
        a->auto_raw[m] += dx * a->ring_x[at];
        a->cross_pos[m] += dy * a->ring_x[at];
        a->cross_neg[m] += dx * a->ring_y[at];
    }
}

void sim_gyro_filter_add(sim_gyro_filter_t *g, const double raw_rad_s[3], const double filtered_rad_s[3])
{
    for (int i = 0; i < 3; ++i) {
        add_axis(&g->axis[i], raw_rad_s[i], filtered_rad_s[i]);
    }
}

/* Hann lag window over +-TAPS. */
static double lag_window(int m)
{
    return 0.5 * (1.0 + cos(PI * m / (TAPS + 1)));
}

/* The cross-spectrum (raw to filtered) and the raw auto-spectrum at w rad/tick. */
static void spectra_at(const axis_state_t *a, double w, double *re, double *im, double *sxx)
{
    *re = a->cross_pos[0];
    *im = 0.0;
    *sxx = a->auto_raw[0];
    for (int m = 1; m <= TAPS; ++m) {
        const double lw = lag_window(m), c = cos(w * m), s = sin(w * m);
        /* output lagging input by m: phase -w m */
        *re += lw * (a->cross_pos[m] + a->cross_neg[m]) * c;
        *im += lw * (a->cross_neg[m] - a->cross_pos[m]) * s;
        *sxx += 2.0 * lw * a->auto_raw[m] * c;
    }
}

/* The phase slope's delay (ticks) over the low band, weighted by the
 * cross-spectrum's magnitude; the gain at its first frequency into *gain. */
static double phase_delay_ticks(const axis_state_t *a, double *gain)
{
    const int bins = (int)floor(SIM_GYRO_FILTER_BAND_SHARE * 2.0 * (TAPS + 1));
    double num = 0.0, den = 0.0;
    *gain = NAN;
    for (int k = 1; k <= (bins > 1 ? bins : 1); ++k) {
        const double w = PI * k / (TAPS + 1);
        double re, im, sxx;
        spectra_at(a, w, &re, &im, &sxx);
        const double mag = hypot(re, im);
        if (!(mag > 0.0) || !(sxx > 0.0)) {
            continue;
        }
        if (!isfinite(*gain)) {
            *gain = mag / sxx;
        }
        const double phase = atan2(im, re);
        num += mag * (-phase) * w;
        den += mag * w * w;
    }
    return den > 0.0 ? num / den : NAN;
}

void sim_gyro_filter_result(const sim_gyro_filter_t *g, int axis, double floor_lo_hz, double floor_hi_hz,
                            double min_ratio, sim_gyro_filter_axis_t *out)
{
    const axis_state_t *a = &g->axis[axis];
    out->delay_s = out->gain_low = out->vib_atten_db = NAN;
    out->n_lines = 0;
    if (a->n > 4 * TAPS && a->auto_raw[0] > 0.0) {
        out->delay_s = phase_delay_ticks(a, &out->gain_low) * g->dt_s;
    }
    if (sim_spectrum_segments(&a->raw) == 0) {
        return;
    }
    sim_spectrum_line_t lines[SIM_SPECTRUM_MAX_LINES];
    const double floor = sim_spectrum_floor(&a->raw, floor_lo_hz, floor_hi_hz);
    const int n = sim_spectrum_lines(&a->raw, floor_lo_hz, floor, min_ratio, lines, SIM_SPECTRUM_MAX_LINES);
    double before = 0.0, after = 0.0;
    for (int l = 0; l < n; ++l) {
        /* the line's bin and its two neighbours: a Hann window spreads a tone over three */
        const int k = (int)lround(lines[l].hz / sim_spectrum_hz(&a->raw, 1));
        for (int j = k - 1; j <= k + 1; ++j) {
            if (j > 0 && j < SIM_SPECTRUM_BINS) {
                before += sim_spectrum_psd(&a->raw, j);
                after += sim_spectrum_psd(&a->filtered, j);
            }
        }
    }
    out->n_lines = n;
    if (n > 0 && before > 0.0 && after > 0.0) {
        out->vib_atten_db = 10.0 * log10(after / before);
    }
}
