/* SPDX-License-Identifier: BSD-3-Clause */
/* A flight log's noise in one pass (log_noise.h). */
#include "log_noise.h"

#include <math.h>
#include <string.h>

static void start(sim_log_noise_t *n, double dt_s, unsigned has)
{
    memset(n, 0, sizeof *n);
    n->dt_s = dt_s;
    n->has = has;
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&n->command[i], 1.0 / dt_s);
        sim_spectrum_init(&n->gyro[i], 1.0 / dt_s);
        sim_spectrum_init(&n->gyro_raw[i], 1.0 / dt_s);
    }
}

void sim_lag_push(sim_lag_t *l, double x, double y)
{
    const int slot = (int)(l->n % SIM_LOG_NOISE_LAGS);
    l->ring[slot] = x;
    l->x_sum += x;
    l->y_sum += y;
    for (int j = 0; j < SIM_LOG_NOISE_LAGS && j <= l->n; ++j) {
        l->xcorr[j] += y * l->ring[(slot - j + SIM_LOG_NOISE_LAGS) % SIM_LOG_NOISE_LAGS];
    }
    l->n++;
}

/* The cross-covariance at lag j: the mean product less the product of the
 * means (the lagged sum's mean taken as the whole stream's: a bias of j / n). */
static double covariance(const sim_lag_t *l, int j)
{
    const double n = (double)l->n;
    return l->xcorr[j] / (n - (double)j) - (l->y_sum / n) * (l->x_sum / n);
}

double sim_lag_ticks(const sim_lag_t *l)
{
    if (l->n <= 4 * SIM_LOG_NOISE_LAGS) {
        return NAN;
    }
    int best = 0;
    for (int j = 1; j < SIM_LOG_NOISE_LAGS; ++j) {
        if (covariance(l, j) > covariance(l, best)) {
            best = j;
        }
    }
    double frac = 0.0; /* the parabola's vertex through the peak and its neighbours */
    if (best > 0 && best + 1 < SIM_LOG_NOISE_LAGS) {
        const double a = covariance(l, best - 1), b = covariance(l, best), c = covariance(l, best + 1);
        const double den = a - 2.0 * b + c;
        frac = den < 0.0 ? 0.5 * (a - c) / den : 0.0;
    }
    return (double)best + frac;
}

static void add(sim_log_noise_t *n, const sim_log_sample_t *s)
{
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_push(&n->command[i], s->command[i]);
        sim_spectrum_push(&n->gyro[i], s->gyro_rad_s[i]);
        if (n->has & SIM_LOG_HAS_GYRO_RAW) {
            sim_spectrum_push(&n->gyro_raw[i], s->gyro_raw_rad_s[i]);
            sim_lag_push(&n->chain[i], s->gyro_raw_rad_s[i], s->gyro_rad_s[i]);
        }
    }
    for (int m = 0; m < s->n_motors && (n->has & SIM_LOG_HAS_ROTOR_HZ); ++m) {
        if (isfinite(s->rotor_hz[m]) && s->rotor_hz[m] > 0.0) {
            n->rotor_hz_sum += s->rotor_hz[m];
            n->rotor_samples++;
            n->rotors = m + 1 > n->rotors ? m + 1 : n->rotors;
        }
    }
    n->ticks++;
}

int sim_log_noise_measure(const sim_log_options_t *opt, sim_log_noise_t *n, char *err, size_t err_len)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(opt, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, err_len);
        return -1;
    }
    start(n, sim_log_dt_s(log), sim_log_has(log));
    sim_log_sample_t s;
    int rc;
    while ((rc = sim_log_next(log, &s, &lerr)) == 1) {
        add(n, &s);
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, err_len);
    }
    sim_log_close(log);
    return rc < 0 ? -1 : 0;
}

double sim_log_noise_command_above(const sim_log_noise_t *n, int axis, double f_lo_hz)
{
    return sim_spectrum_band_rms(&n->command[axis], f_lo_hz, INFINITY);
}

double sim_log_noise_chain_delay_s(const sim_log_noise_t *n, int axis)
{
    return (n->has & SIM_LOG_HAS_GYRO_RAW) ? sim_lag_ticks(&n->chain[axis]) * n->dt_s : NAN;
}

double sim_log_noise_rotor_hz(const sim_log_noise_t *n)
{
    return n->rotor_samples > 0 ? n->rotor_hz_sum / (double)n->rotor_samples : 0.0;
}
