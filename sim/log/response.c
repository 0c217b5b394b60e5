/* SPDX-License-Identifier: BSD-3-Clause */
/* The field's views of a log: step response, frequency response, noise against throttle (response.h). */
#include "response.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "run/fft.h"

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define NOISE_SIGNALS ((int)SIM_NOISE_SIGNALS)

/* A transform size, its Hann window over the first `len` points and its twiddles. */
typedef struct {
    int len, m; /* samples in a segment; transform points (len zero-padded) */
    double *window, *tw_re, *tw_im;
    double window_power; /* sum of window^2 */
} plan_t;

/* A ring of the last `len` samples of one stream. */
typedef struct {
    double *x;
} ring_t;

struct sim_response {
    double dt_s;
    long long ticks; /* pushed since the start or the latest skipped gap */
    unsigned has;    /* the SIM_LOG_HAS_* of the ticks pushed */
    plan_t step_plan, freq_plan, noise_plan;
    int hop, resp_n;
    ring_t step_ref[3], step_gyro[3], freq_ref[3], freq_gyro[3];
    ring_t noise_sig[NOISE_SIGNALS][3], noise_throttle;
    unsigned noise_has; /* 1 << signal, for the signals the log holds */
    /* step: sums over windows kept of the step and its square */
    double *step_sum[3], *step_sq[3], *step_mean[3], *step_spread[3];
    int step_windows[3], step_rejected[3];
    /* H1: sums over segments of |X|^2, |Y|^2 and conj(X) Y */
    double *sxx[3], *syy[3], *sxy_re[3], *sxy_im[3];
    long freq_segments[3];
    /* noise: PSD sums per signal, axis, throttle bin */
    double *noise_sum[NOISE_SIGNALS][3][SIM_RESPONSE_THROTTLE_BINS];
    long noise_segments[SIM_RESPONSE_THROTTLE_BINS];
    double *re, *im, *re2, *im2; /* work arrays of the largest transform */
};

static int plan_init(plan_t *p, int len, int m)
{
    p->len = len;
    p->m = m;
    p->window = malloc((size_t)len * sizeof *p->window);
    p->tw_re = malloc((size_t)(m / 2) * sizeof *p->tw_re);
    p->tw_im = malloc((size_t)(m / 2) * sizeof *p->tw_im);
    if (p->window == NULL || p->tw_re == NULL || p->tw_im == NULL) {
        return -1;
    }
    p->window_power = 0.0;
    for (int i = 0; i < len; ++i) {
        p->window[i] = 0.5 - 0.5 * cos(2.0 * PI * i / len);
        p->window_power += p->window[i] * p->window[i];
    }
    sim_fft_twiddles(m, p->tw_re, p->tw_im);
    return 0;
}

static void plan_free(plan_t *p)
{
    free(p->window);
    free(p->tw_re);
    free(p->tw_im);
}

static double *zeros(size_t n, int *failed)
{
    double *x = calloc(n, sizeof *x);
    *failed |= x == NULL;
    return x;
}

/* The ticks in `s` seconds at dt_s, at least `min`. */
static int ticks_in(double s, double dt_s, int min)
{
    const int n = (int)floor(s / dt_s + 0.5);
    return n < min ? min : n;
}

sim_response_t *sim_response_new(double dt_s)
{
    if (!(dt_s > 0.0) || !(dt_s < 1.0)) {
        return NULL;
    }
    sim_response_t *r = calloc(1, sizeof *r);
    if (r == NULL) {
        return NULL;
    }
    r->dt_s = dt_s;
    const int win = ticks_in(SIM_RESPONSE_WINDOW_S, dt_s, 8);
    r->hop = ticks_in(SIM_RESPONSE_HOP_S, dt_s, 1);
    r->resp_n = ticks_in(SIM_RESPONSE_LENGTH_S, dt_s, 2) + 1;
    const int freq_len = sim_fft_size(ticks_in(SIM_RESPONSE_FREQ_SEGMENT_S, dt_s, 16));
    const int noise_len = sim_fft_size(ticks_in(SIM_RESPONSE_NOISE_SEGMENT_S, dt_s, 16));
    /* the window zero-padded by the response's length: its linear convolution fits the transform */
    int failed = plan_init(&r->step_plan, win, sim_fft_size(win + r->resp_n)) != 0;
    failed |= plan_init(&r->freq_plan, freq_len, freq_len) != 0;
    failed |= plan_init(&r->noise_plan, noise_len, noise_len) != 0;
    const int m = r->step_plan.m > freq_len ? (r->step_plan.m > noise_len ? r->step_plan.m : noise_len)
                                            : (freq_len > noise_len ? freq_len : noise_len);
    r->re = zeros((size_t)m, &failed);
    r->im = zeros((size_t)m, &failed);
    r->re2 = zeros((size_t)m, &failed);
    r->im2 = zeros((size_t)m, &failed);
    const size_t fb = (size_t)(freq_len / 2 + 1), nb = (size_t)(noise_len / 2 + 1);
    for (int a = 0; a < 3; ++a) {
        r->step_ref[a].x = zeros((size_t)win, &failed);
        r->step_gyro[a].x = zeros((size_t)win, &failed);
        r->freq_ref[a].x = zeros((size_t)freq_len, &failed);
        r->freq_gyro[a].x = zeros((size_t)freq_len, &failed);
        r->step_sum[a] = zeros((size_t)r->resp_n, &failed);
        r->step_sq[a] = zeros((size_t)r->resp_n, &failed);
        r->step_mean[a] = zeros((size_t)r->resp_n, &failed);
        r->step_spread[a] = zeros((size_t)r->resp_n, &failed);
        r->sxx[a] = zeros(fb, &failed);
        r->syy[a] = zeros(fb, &failed);
        r->sxy_re[a] = zeros(fb, &failed);
        r->sxy_im[a] = zeros(fb, &failed);
        for (int s = 0; s < NOISE_SIGNALS; ++s) {
            r->noise_sig[s][a].x = zeros((size_t)noise_len, &failed);
            for (int b = 0; b < SIM_RESPONSE_THROTTLE_BINS; ++b) {
                r->noise_sum[s][a][b] = zeros(nb, &failed);
            }
        }
    }
    r->noise_throttle.x = zeros((size_t)noise_len, &failed);
    if (failed) {
        sim_response_free(r);
        return NULL;
    }
    return r;
}

void sim_response_free(sim_response_t *r)
{
    if (r == NULL) {
        return;
    }
    plan_free(&r->step_plan);
    plan_free(&r->freq_plan);
    plan_free(&r->noise_plan);
    free(r->re);
    free(r->im);
    free(r->re2);
    free(r->im2);
    for (int a = 0; a < 3; ++a) {
        free(r->step_ref[a].x);
        free(r->step_gyro[a].x);
        free(r->freq_ref[a].x);
        free(r->freq_gyro[a].x);
        free(r->step_sum[a]);
        free(r->step_sq[a]);
        free(r->step_mean[a]);
        free(r->step_spread[a]);
        free(r->sxx[a]);
        free(r->syy[a]);
        free(r->sxy_re[a]);
        free(r->sxy_im[a]);
        for (int s = 0; s < NOISE_SIGNALS; ++s) {
            free(r->noise_sig[s][a].x);
            for (int b = 0; b < SIM_RESPONSE_THROTTLE_BINS; ++b) {
                free(r->noise_sum[s][a][b]);
            }
        }
    }
    free(r->noise_throttle.x);
    free(r);
}

double sim_response_dt_s(const sim_response_t *r)
{
    return r->dt_s;
}

unsigned sim_response_has(const sim_response_t *r)
{
    return r->has;
}

/* The ring's last `len` samples, oldest first, times the window, minus their
 * mean first when `detrend`, into out[0..len-1]; out[len..m-1] zero. Ticks
 * pushed so far: `ticks` (the newest at (ticks - 1) % len). */
static void take_segment(const ring_t *ring, const plan_t *p, long long ticks, int detrend, double *out)
{
    const int len = p->len, start = (int)(ticks % len);
    double mean = 0.0;
    if (detrend) {
        for (int i = 0; i < len; ++i) {
            mean += ring->x[i];
        }
        mean /= len;
    }
    for (int i = 0; i < len; ++i) {
        out[i] = p->window[i] * (ring->x[(start + i) % len] - mean);
    }
    for (int i = len; i < p->m; ++i) {
        out[i] = 0.0;
    }
}

/* The transforms of two real segments in one: z = a + i b, then with Z' the
 * conjugate of Z at m - k, A = (Z + Z') / 2 and B = (Z - Z') / 2i, k <= m / 2,
 * into (re, im) for A and (re2, im2) for B. */
static void transform_pair(sim_response_t *r, const plan_t *p)
{
    const int m = p->m;
    sim_fft(m, p->tw_re, p->tw_im, r->re, r->im);
    for (int k = 0; k <= m / 2; ++k) {
        const int j = (m - k) % m;
        const double zr = r->re[k], zi = r->im[k], cr = r->re[j], ci = -r->im[j];
        r->re2[k] = 0.5 * (zi - ci);
        r->im2[k] = -0.5 * (zr - cr);
        r->re[k] = 0.5 * (zr + cr); /* written at k <= m / 2, read at m - k >= m / 2: k = m / 2 reads first */
        r->im[k] = 0.5 * (zi + ci);
    }
}

/* The largest |x| of a ring. */
static double ring_peak(const ring_t *ring, int len)
{
    double peak = 0.0;
    for (int i = 0; i < len; ++i) {
        peak = fmax(peak, fabs(ring->x[i]));
    }
    return peak;
}

static int window_due(long long ticks, int len, int hop)
{
    return ticks >= len && (ticks - len) % hop == 0;
}

/* One window of an axis: deconvolved, its step checked and summed. */
static void step_window(sim_response_t *r, int a)
{
    const plan_t *p = &r->step_plan;
    const int m = p->m;
    take_segment(&r->step_ref[a], p, r->ticks, 0, r->re);
    take_segment(&r->step_gyro[a], p, r->ticks, 0, r->im);
    transform_pair(r, p);
    /* lambda(f) = NSR (1 + (f / f_cut)^order) times the mean input power below the cut */
    const double df = 1.0 / (m * r->dt_s);
    int k_cut = (int)floor(SIM_RESPONSE_CUTOFF_HZ / df);
    k_cut = k_cut < 1 ? 1 : (k_cut > m / 2 ? m / 2 : k_cut);
    double power = 0.0;
    for (int k = 1; k <= k_cut; ++k) {
        power += r->re[k] * r->re[k] + r->im[k] * r->im[k];
    }
    power /= k_cut;
    if (!(power > 0.0)) {
        return;
    }
    for (int k = 0; k <= m / 2; ++k) {
        const double xr = r->re[k], xi = r->im[k], yr = r->re2[k], yi = r->im2[k];
        const double lambda =
            SIM_RESPONSE_NSR * power * (1.0 + pow(k * df / SIM_RESPONSE_CUTOFF_HZ, SIM_RESPONSE_NSR_ORDER));
        const double den = xr * xr + xi * xi + lambda;
        /* H = Y conj(X) / den */
        r->re[k] = (yr * xr + yi * xi) / den;
        r->im[k] = (yi * xr - yr * xi) / den;
    }
    for (int k = 1; k < m / 2; ++k) { /* Hermitian: the impulse response is real */
        r->re[m - k] = r->re[k];
        r->im[m - k] = -r->im[k];
    }
    r->im[0] = 0.0;
    r->im[m / 2] = 0.0;
    sim_fft_inverse(m, p->tw_re, p->tw_im, r->re, r->im);
    /* the step: the impulse response summed */
    double sum = 0.0;
    for (int i = 0; i < r->resp_n; ++i) {
        sum += r->re[i];
        r->re2[i] = sum;
    }
    const int steady_from = (int)ceil(SIM_RESPONSE_STEADY_FROM_S / r->dt_s);
    for (int i = steady_from; i < r->resp_n; ++i) {
        if (!(r->re2[i] >= SIM_RESPONSE_STEADY_MIN && r->re2[i] <= SIM_RESPONSE_STEADY_MAX)) {
            r->step_rejected[a]++;
            return;
        }
    }
    for (int i = 0; i < r->resp_n; ++i) {
        r->step_sum[a][i] += r->re2[i];
        r->step_sq[a][i] += r->re2[i] * r->re2[i];
    }
    r->step_windows[a]++;
}

/* One H1 segment of an axis. */
static void freq_segment(sim_response_t *r, int a)
{
    const plan_t *p = &r->freq_plan;
    take_segment(&r->freq_ref[a], p, r->ticks, 1, r->re);
    take_segment(&r->freq_gyro[a], p, r->ticks, 1, r->im);
    transform_pair(r, p);
    for (int k = 0; k <= p->m / 2; ++k) {
        const double xr = r->re[k], xi = r->im[k], yr = r->re2[k], yi = r->im2[k];
        r->sxx[a][k] += xr * xr + xi * xi;
        r->syy[a][k] += yr * yr + yi * yi;
        r->sxy_re[a][k] += xr * yr + xi * yi; /* conj(X) Y */
        r->sxy_im[a][k] += xr * yi - xi * yr;
    }
    r->freq_segments[a]++;
}

/* The one-sided PSD of one real segment in (re) into sum. */
static void add_psd(const plan_t *p, double fs_hz, double *re, double *im, double *sum)
{
    for (int i = 0; i < p->m; ++i) {
        im[i] = 0.0;
    }
    sim_fft(p->m, p->tw_re, p->tw_im, re, im);
    for (int k = 0; k <= p->m / 2; ++k) {
        const double one_sided = (k == 0 || k == p->m / 2) ? 1.0 : 2.0;
        sum[k] += one_sided * (re[k] * re[k] + im[k] * im[k]) / (fs_hz * p->window_power);
    }
}

static void noise_segment(sim_response_t *r)
{
    const plan_t *p = &r->noise_plan;
    double throttle = 0.0;
    for (int i = 0; i < p->len; ++i) {
        throttle += r->noise_throttle.x[i];
    }
    throttle /= p->len;
    int b = (int)floor(throttle * SIM_RESPONSE_THROTTLE_BINS);
    b = b < 0 ? 0 : (b >= SIM_RESPONSE_THROTTLE_BINS ? SIM_RESPONSE_THROTTLE_BINS - 1 : b);
    for (int s = 0; s < NOISE_SIGNALS; ++s) {
        if (!(r->noise_has & (1u << s))) {
            continue;
        }
        for (int a = 0; a < 3; ++a) {
            take_segment(&r->noise_sig[s][a], p, r->ticks, 1, r->re);
            add_psd(p, 1.0 / r->dt_s, r->re, r->im, r->noise_sum[s][a][b]);
        }
    }
    r->noise_segments[b]++;
}

void sim_response_push(sim_response_t *r, const sim_log_sample_t *s, unsigned has)
{
    if (s->after_gap) {
        r->ticks = 0; /* a skipped gap (log.h): the rings refill, no window spans it */
    }
    r->has = has;
    const int rate = (has & SIM_LOG_HAS_REF_RATE) && (has & SIM_LOG_HAS_GYRO);
    const int noise = (has & SIM_LOG_HAS_THROTTLE) != 0;
    r->noise_has = ((has & SIM_LOG_HAS_GYRO) ? 1u << SIM_NOISE_GYRO : 0u) |
                   ((has & SIM_LOG_HAS_GYRO_RAW) ? 1u << SIM_NOISE_GYRO_RAW : 0u) |
                   ((has & SIM_LOG_HAS_COMMAND) ? 1u << SIM_NOISE_COMMAND : 0u);
    const int sl = r->step_plan.len, fl = r->freq_plan.len, nl = r->noise_plan.len;
    for (int a = 0; a < 3; ++a) {
        if (rate) {
            r->step_ref[a].x[r->ticks % sl] = s->ref_rate_rad_s[a];
            r->step_gyro[a].x[r->ticks % sl] = s->gyro_rad_s[a];
            r->freq_ref[a].x[r->ticks % fl] = s->ref_rate_rad_s[a];
            r->freq_gyro[a].x[r->ticks % fl] = s->gyro_rad_s[a];
        }
        if (noise) {
            r->noise_sig[SIM_NOISE_GYRO][a].x[r->ticks % nl] = s->gyro_rad_s[a];
            r->noise_sig[SIM_NOISE_GYRO_RAW][a].x[r->ticks % nl] = s->gyro_raw_rad_s[a];
            r->noise_sig[SIM_NOISE_COMMAND][a].x[r->ticks % nl] = s->command[a];
        }
    }
    if (noise) {
        r->noise_throttle.x[r->ticks % nl] = s->throttle;
    }
    r->ticks++;
    const double gate_rad_s = SIM_RESPONSE_MIN_INPUT_DEG_S * DEG;
    for (int a = 0; a < 3 && rate; ++a) {
        if (window_due(r->ticks, sl, r->hop) && ring_peak(&r->step_ref[a], sl) >= gate_rad_s) {
            step_window(r, a);
        }
        if (window_due(r->ticks, fl, fl / 2) && ring_peak(&r->freq_ref[a], fl) >= gate_rad_s) {
            freq_segment(r, a);
        }
    }
    if (noise && window_due(r->ticks, nl, nl / 2)) {
        noise_segment(r);
    }
}

/* The first time the step reaches `level` (linear between samples; 0 when
 * its first sample does already); NaN when it does not. */
static double crossing_s(const double *step, int n, double dt_s, double level)
{
    if (n > 0 && step[0] >= level) {
        return 0.0;
    }
    for (int i = 1; i < n; ++i) {
        if (step[i] >= level && step[i - 1] < level) {
            return dt_s * (i - 1 + (level - step[i - 1]) / (step[i] - step[i - 1]));
        }
    }
    return NAN;
}

void sim_step_figures(const double *step, int n, double dt_s, sim_step_response_t *out)
{
    const int from = (int)ceil(SIM_RESPONSE_STEADY_FROM_S / dt_s);
    double steady = 0.0, peak = -INFINITY;
    int count = 0;
    for (int i = 0; i < n; ++i) {
        peak = fmax(peak, step[i]);
        if (i >= from) {
            steady += step[i];
            count++;
        }
    }
    out->steady = count > 0 ? steady / count : NAN;
    if (!(out->steady > 0.0)) {
        out->rise_s = out->delay_s = out->overshoot = NAN;
        return;
    }
    out->rise_s = crossing_s(step, n, dt_s, 0.9 * out->steady) - crossing_s(step, n, dt_s, 0.1 * out->steady);
    out->delay_s = crossing_s(step, n, dt_s, 0.5 * out->steady);
    out->overshoot = fmax(0.0, peak / out->steady - 1.0);
}

void sim_response_step(sim_response_t *r, int axis, sim_step_response_t *out)
{
    const int n = r->step_windows[axis];
    out->windows = n;
    out->rejected = r->step_rejected[axis];
    out->n = r->resp_n;
    out->mean = r->step_mean[axis];
    out->spread = r->step_spread[axis];
    for (int i = 0; i < r->resp_n; ++i) {
        const double mean = n > 0 ? r->step_sum[axis][i] / n : NAN;
        const double var = n > 1 ? (r->step_sq[axis][i] - n * mean * mean) / (n - 1) : NAN;
        r->step_mean[axis][i] = mean;
        r->step_spread[axis][i] = var > 0.0 ? sqrt(var) : (n > 1 ? 0.0 : NAN);
    }
    sim_step_figures(out->mean, out->n, r->dt_s, out);
}

int sim_response_freq_bins(const sim_response_t *r)
{
    return r->freq_plan.m / 2 + 1;
}

long sim_response_freq_segments(const sim_response_t *r, int axis)
{
    return r->freq_segments[axis];
}

void sim_response_freq(const sim_response_t *r, int axis, int k, double *hz, double *gain, double *phase_rad,
                       double *coherence)
{
    *hz = k / (r->freq_plan.m * r->dt_s);
    const double sxx = r->sxx[axis][k], syy = r->syy[axis][k], re = r->sxy_re[axis][k], im = r->sxy_im[axis][k];
    if (r->freq_segments[axis] == 0 || !(sxx > 0.0)) {
        *gain = *phase_rad = *coherence = NAN;
        return;
    }
    *gain = sqrt(re * re + im * im) / sxx;
    *phase_rad = atan2(im, re);
    *coherence = syy > 0.0 ? (re * re + im * im) / (sxx * syy) : NAN;
}

int sim_response_noise_bins(const sim_response_t *r)
{
    return r->noise_plan.m / 2 + 1;
}

double sim_response_noise_hz(const sim_response_t *r, int k)
{
    return k / (r->noise_plan.m * r->dt_s);
}

long sim_response_noise_segments(const sim_response_t *r, int throttle_bin)
{
    return r->noise_segments[throttle_bin];
}

double sim_response_noise_psd(const sim_response_t *r, sim_noise_signal_t sig, int axis, int throttle_bin, int k)
{
    const long n = r->noise_segments[throttle_bin];
    if (n == 0 || !(r->noise_has & (1u << sig))) {
        return NAN;
    }
    return r->noise_sum[sig][axis][throttle_bin][k] / (double)n;
}
