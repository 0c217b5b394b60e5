/* SPDX-License-Identifier: BSD-3-Clause */
#define _POSIX_C_SOURCE 200809L
#include "tune_noise.h"

#include <stdio.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "spectrum.h"
#include "scenario/series.h"

void sim_tune_noise_request(const sim_scenario_t *sc, ladrc_margins_request_t *req)
{
    req->angle_noise_std_rad = sc->angle_noise_std_rad;
    req->rate_noise_std_rad_s = sc->rate_noise_std_rad_s;
    req->noise_corner_hz = LADRC_MARGINS_NOISE_CORNER_HZ;
}

/* The series' spectra of the latest scenario asked about: the tuning asks
 * the same for every controller and candidate on each axis, on two threads. */
static struct {
    pthread_mutex_t lock;
    char path[SIM_PATH_LEN];
    double dt_s;
    int interp, end, bins;
    double step_hz;
    double psd[3][SIM_SPECTRUM_BINS];
} cache = {.lock = PTHREAD_MUTEX_INITIALIZER};

/* Reads the series and fills the cache's spectra; 0, or -1 with why. */
static int measure(const sim_scenario_t *sc, char *why, size_t why_len)
{
    const sim_series_spec_t spec = {.dim = SIM_DIM_ANG_RATE,
                                    .key = "rate_noise_series",
                                    .interp = (sim_series_interp_t)sc->noise_series_interp,
                                    .end = (sim_series_end_t)sc->noise_series_end};
    sim_series_t series;
    sim_series_error_t e;
    if (sim_series_load(&series, sc->rate_noise_series, &spec, &e) != 0) {
        snprintf(why, why_len, "%s:%d:%d: %s", e.path, e.line, e.column, e.message);
        return -1;
    }
    sim_spectrum_t *spectrum = malloc(3 * sizeof *spectrum);
    if (spectrum == NULL) {
        sim_series_free(&series);
        snprintf(why, why_len, "%s: out of memory", sc->rate_noise_series);
        return -1;
    }
    const double span_s = series.period_s < SIM_TUNE_NOISE_SERIES_S ? series.period_s : SIM_TUNE_NOISE_SERIES_S;
    const long ticks = (long)(span_s / sc->control_dt_s);
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&spectrum[i], 1.0 / sc->control_dt_s);
    }
    sim_series_cursor_t cursor;
    sim_series_cursor_init(&cursor);
    for (long k = 0; k < ticks; ++k) {
        double v[SIM_SERIES_MAX_COLS];
        sim_series_eval(&series, &cursor, series.t_s[0] + (double)k * sc->control_dt_s, v);
        for (int i = 0; i < 3; ++i) {
            sim_spectrum_push(&spectrum[i],
                              v[i < series.n_cols ? i : series.n_cols - 1]); /* one column: every axis's */
        }
    }
    cache.bins = sim_spectrum_segments(&spectrum[0]) > 0 ? SIM_SPECTRUM_BINS : 0;
    cache.step_hz = sim_spectrum_hz(&spectrum[0], 1);
    for (int i = 0; i < 3; ++i) {
        for (int k = 0; k < cache.bins; ++k) {
            cache.psd[i][k] = sim_spectrum_psd(&spectrum[i], k);
        }
    }
    snprintf(cache.path, sizeof cache.path, "%s", sc->rate_noise_series);
    cache.dt_s = sc->control_dt_s;
    cache.interp = sc->noise_series_interp;
    cache.end = sc->noise_series_end;
    free(spectrum);
    sim_series_free(&series);
    return 0;
}

int sim_tune_noise_series(const sim_scenario_t *sc, int axis, ladrc_margins_request_t *req, char *why, size_t why_len)
{
    if (sc->rate_noise_series[0] == '\0') {
        return 0;
    }
    pthread_mutex_lock(&cache.lock);
    int rc = 0;
    if (strcmp(cache.path, sc->rate_noise_series) != 0 || cache.dt_s != sc->control_dt_s ||
        cache.interp != sc->noise_series_interp || cache.end != sc->noise_series_end) {
        cache.path[0] = '\0';
        rc = measure(sc, why, why_len);
    }
    if (rc == 0 && cache.bins > 0) {
        req->rate_noise_psd_bins =
            cache.bins < LADRC_MARGINS_NOISE_PSD_BINS ? cache.bins : LADRC_MARGINS_NOISE_PSD_BINS;
        req->rate_noise_bin_hz = cache.step_hz;
        memcpy(req->rate_noise_psd, cache.psd[axis], (size_t)req->rate_noise_psd_bins * sizeof req->rate_noise_psd[0]);
        req->noise_corner_hz = LADRC_MARGINS_NOISE_CORNER_HZ;
    }
    pthread_mutex_unlock(&cache.lock);
    return rc;
}
