/* SPDX-License-Identifier: BSD-3-Clause */
/* A log's airframe (log_identify.h). */
#include "log_identify.h"

#include "run/biquad.h"
#include "ident_cache.h"
#include "log_outlier.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define PROGRESS_EVERY 65536 /* ticks between progress calls */
#define LINE_MIN_RATIO 10.0  /* a vibration line: a peak 10 dB over the floor */

double sim_log_noise_corner_hz(double fs_hz)
{
    double lo, hi;
    sim_airframe_floor_band(fs_hz, &lo, &hi);
    return lo;
}

#define ROTOR_HIST_HZ 2000    /* rotor speeds counted in 1 Hz bins up to this */
#define ROTOR_SPINNING_HZ 5.0 /* slower: on the ground, not counted */
#define ROTOR_LOW_SHARE 0.05  /* the rotors' low speed: the slowest rotor's 5th percentile */

/* What pass 0 gathers: the gyro's spectrum, the slowest rotor's speeds, the noise file. */
typedef struct {
    sim_spectrum_t spectrum[3];
    long long rotor_hist[ROTOR_HIST_HZ];
    long long rotor_count;
    biquad_coef_t hp; /* the noise series' high-pass: the flight's motion out, the sensor's noise in */
    biquad_t hp_state[3];
    FILE *noise;
    long long noise_rows, noise_rows_max;
    sim_gyro_filter_t *filter; /* the log's filters, when it has the gyro before and after them */
} survey_t;

/* The most rows the noise series is given (a day at 100 kHz): beyond any
 * log, and far inside long long. */
#define NOISE_ROWS_MAX 8.64e9

static int survey_open(survey_t *s, const sim_log_identify_options_t *o, double dt_s, char *err, size_t err_len)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_init(&s->spectrum[i], 1.0 / dt_s);
        s->hp = biquad_highpass(sim_log_noise_corner_hz(1.0 / dt_s), dt_s, BIQUAD_Q_BUTTERWORTH);
    }
    if (o->noise_series == NULL) {
        return 0;
    }
    s->noise = fopen(o->noise_series, "w");
    if (s->noise == NULL) {
        snprintf(err, err_len, "%s: cannot write", o->noise_series);
        return -1;
    }
    /* in double first: rows 1e-300 s apart would overflow the conversion */
    const double rows = ceil(o->noise_series_s / dt_s);
    s->noise_rows_max = (rows < NOISE_ROWS_MAX) ? (long long)rows : (long long)NOISE_ROWS_MAX;
    fprintf(s->noise, "# the gyro's noise of the log, high-passed at %.4g Hz\n", sim_log_noise_corner_hz(1.0 / dt_s));
    fprintf(s->noise, "t [s], roll [rad/s], pitch [rad/s], yaw [rad/s]\n");
    return 0;
}

/* The slowest rotor of the tick into the histogram, when it spins. */
static void survey_rotors(survey_t *s, const sim_log_sample_t *x)
{
    double slowest = INFINITY;
    for (int m = 0; m < x->n_motors; ++m) {
        slowest = isfinite(x->rotor_hz[m]) ? fmin(slowest, x->rotor_hz[m]) : slowest;
    }
    if (slowest > ROTOR_SPINNING_HZ && slowest < ROTOR_HIST_HZ) {
        s->rotor_hist[(int)slowest]++;
        s->rotor_count++;
    }
}

/* The slowest rotor's speed (Hz) below which `share` of the ticks lie; NaN without rotor speeds. */
static double survey_rotor_hz(const survey_t *s, double share)
{
    long long below = 0;
    for (int k = 0; k < ROTOR_HIST_HZ && s->rotor_count > 0; ++k) {
        below += s->rotor_hist[k];
        if ((double)below >= share * (double)s->rotor_count) {
            return k + 1.0;
        }
    }
    return NAN;
}

/* 1 when the gyro shakes at the rotors' speeds: its PSD over the band the
 * slowest rotor spans stands LINE_MIN_RATIO above the floor on an axis. */
static int survey_rotor_lines(const survey_t *s, double lo_hz, double hi_hz, double fs_hz)
{
    double flo, fhi;
    sim_airframe_floor_band(fs_hz, &flo, &fhi);
    for (int i = 0; i < 3; ++i) {
        const double floor = sim_spectrum_floor(&s->spectrum[i], flo, fhi);
        for (int k = 1; k < SIM_SPECTRUM_BINS; ++k) {
            const double f = sim_spectrum_hz(&s->spectrum[i], k);
            if (f >= lo_hz && f <= hi_hz && sim_spectrum_psd(&s->spectrum[i], k) > LINE_MIN_RATIO * floor) {
                return 1;
            }
        }
    }
    return 0;
}

static void survey_add(survey_t *s, double t_s, const double gyro[3])
{
    double hp[3];
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_push(&s->spectrum[i], gyro[i]);
        hp[i] = biquad_step(&s->hp, &s->hp_state[i], gyro[i]);
    }
    if (s->noise != NULL && s->noise_rows < s->noise_rows_max) {
        fprintf(s->noise, "%.9g, %.9g, %.9g, %.9g\n", t_s, hp[0], hp[1], hp[2]);
        s->noise_rows++;
    }
}

static int survey_close(survey_t *s, const char *path, char *err, size_t err_len)
{
    sim_gyro_filter_free(s->filter);
    s->filter = NULL;
    if (s->noise != NULL && (ferror(s->noise) | fclose(s->noise)) != 0) {
        snprintf(err, err_len, "%s: write failed", path);
        return -1;
    }
    return 0;
}

static void report_progress(const sim_log_identify_options_t *o, int pass, long long done, long long total)
{
    o->progress(o->progress_ctx, pass + 1, 4, "identification", total > 0 ? (double)done / (double)total : 0.0);
}

/* One pass over the cache's ticks; 0, or -1 with the message. */
static int cache_pass(const sim_log_identify_options_t *o, sim_ident_cache_t *cache, sim_ident_t *id, int pass,
                      char *err, size_t err_len)
{
    if (sim_ident_cache_rewind(cache) != 0) {
        snprintf(err, err_len, "%s: identification: the temporary file of its samples cannot be read back",
                 o->log.path);
        return -1;
    }
    double gyro[3], command[3], setpoint[3];
    int rc;
    long long k = 0;
    while ((rc = sim_ident_cache_get(cache, gyro, command, setpoint)) == 1) {
        sim_ident_add_ref(id, gyro, command, setpoint);
        if (o->progress != NULL && ++k % PROGRESS_EVERY == 0) {
            long long done, total;
            sim_ident_cache_progress(cache, &done, &total);
            report_progress(o, pass, done, total);
        }
    }
    if (rc < 0) {
        snprintf(err, err_len, "%s: identification: reading the temporary file of its samples failed", o->log.path);
    }
    return rc < 0 ? -1 : 0;
}

/* What a pass over the log feeds its samples to. */
typedef struct {
    const sim_log_identify_options_t *o;
    sim_ident_t *id;
    survey_t *survey;
    sim_ident_cache_t **cache;
    unsigned has;
} pass_sinks_t;

/* One tick of the log (its outliers repaired) into the identification, the cache and the survey. */
static void pass_take(const pass_sinks_t *p, const sim_log_sample_t *s)
{
    const int raw = (p->has & SIM_LOG_HAS_GYRO_RAW) != 0;
    const double none[3] = {NAN, NAN, NAN};
    const double *gyro = raw ? s->gyro_raw_rad_s : s->gyro_rad_s;
    const double *setpoint = (p->has & SIM_LOG_HAS_REF_RATE) ? s->ref_rate_rad_s : none;
    if (p->id != NULL) {
        sim_ident_add_ref(p->id, gyro, s->command, setpoint);
    }
    if (p->cache != NULL && *p->cache != NULL && sim_ident_cache_put(*p->cache, gyro, s->command, setpoint) != 0) {
        sim_ident_cache_free(*p->cache);
        *p->cache = NULL;
    }
    survey_t *survey = p->survey;
    if (survey != NULL) {
        survey_add(survey, s->t_s, gyro);
        if (raw && survey->filter == NULL) {
            survey->filter = sim_gyro_filter_new(p->o->log.dt_s);
        }
        if (raw && survey->filter != NULL) {
            sim_gyro_filter_add(survey->filter, s->gyro_raw_rad_s, s->gyro_rad_s);
        }
        if (p->has & SIM_LOG_HAS_ROTOR_HZ) {
            survey_rotors(survey, s);
        }
    }
}

/* One pass over the log, its ticks into the cache too when one is given
 * (*cache is freed and set to NULL when it cannot be written: the later
 * passes then read the log again); every tick through the outlier filter
 * (log_outlier.h), whose count goes to *outliers when not NULL; 0, or -1
 * with the message. */
static int read_pass(const sim_log_identify_options_t *o, sim_ident_t *id, survey_t *survey, int pass,
                     sim_ident_cache_t **cache, sim_log_stats_t *stats, sim_log_outliers_t *outliers, char *err,
                     size_t err_len)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&o->log, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, err_len);
        return -1;
    }
    const unsigned has = sim_log_has(log);
    if (!(has & SIM_LOG_HAS_GYRO) || !(has & SIM_LOG_HAS_COMMAND)) {
        snprintf(err, err_len, "%s: the log has no %s: nothing to identify", o->log.path,
                 (has & SIM_LOG_HAS_GYRO) ? "command" : "gyro");
        sim_log_close(log);
        return -1;
    }
    sim_log_despike_t *despike = sim_log_despike_new(has);
    if (despike == NULL) {
        snprintf(err, err_len, "%s: identification: out of memory", o->log.path);
        sim_log_close(log);
        return -1;
    }
    const pass_sinks_t sinks = {o, id, survey, cache, has};
    sim_log_sample_t s;
    int rc;
    long long k = 0;
    while ((rc = sim_log_next_repaired(log, despike, &s, &lerr)) == 1) {
        pass_take(&sinks, &s);
        if (o->progress != NULL && ++k % PROGRESS_EVERY == 0) {
            long long done, total;
            sim_log_progress(log, &done, &total);
            report_progress(o, pass, done, total);
        }
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, err_len);
    } else {
        if (stats != NULL) {
            sim_log_stats(log, stats);
        }
        if (outliers != NULL) {
            sim_log_despike_outliers(despike, outliers);
        }
    }
    sim_log_despike_free(despike);
    sim_log_close(log);
    return rc < 0 ? -1 : 0;
}

/* The log's control period: the one asked for, else the reader's (the median row period). */
static int log_dt(const sim_log_options_t *opt, double *dt_s, char *err, size_t err_len)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(opt, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, err_len);
        return -1;
    }
    *dt_s = sim_log_dt_s(log);
    sim_log_close(log);
    return 0;
}

/* The prefilter's corner: the identification's default, or half the
 * rotors' low speed when the log has their speed and the gyro shakes there
 * (the first vibration line), else half the lowest vibration line above the default's
 * reach in the gyro's spectrum, when that is lower: a line's frequency
 * follows the command, so what leaks through would bias the fit. */
static double prefilter_corner_hz(const survey_t *s, double fs_hz, double asked_hz)
{
    if (asked_hz > 0.0) {
        return asked_hz;
    }
    double corner = fmin(SIM_IDENT_PREFILTER_MAX_HZ, 0.08 * fs_hz), lo, hi;
    const double rotor_lo_hz = survey_rotor_hz(s, ROTOR_LOW_SHARE);
    if (isfinite(rotor_lo_hz)) {
        if (survey_rotor_lines(s, rotor_lo_hz, survey_rotor_hz(s, 1.0 - ROTOR_LOW_SHARE), fs_hz)) {
            corner = fmin(corner, 0.5 * rotor_lo_hz);
        }
        return fmax(corner, SIM_IDENT_PREFILTER_MIN_HZ);
    }
    sim_airframe_floor_band(fs_hz, &lo, &hi);
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_line_t lines[SIM_SPECTRUM_MAX_LINES];
        const double floor = sim_spectrum_floor(&s->spectrum[i], lo, hi);
        const int n =
            sim_spectrum_lines(&s->spectrum[i], 1.25 * corner, floor, LINE_MIN_RATIO, lines, SIM_SPECTRUM_MAX_LINES);
        for (int k = 0; k < n; ++k) {
            corner = fmin(corner, 0.5 * lines[k].hz);
        }
    }
    return fmax(corner, SIM_IDENT_PREFILTER_MIN_HZ);
}

int sim_log_identify(const sim_log_identify_options_t *o, sim_airframe_t *out, sim_log_stats_t *stats, char *err,
                     size_t err_len)
{
    memset(out, 0, sizeof *out);
    double dt_s;
    if (log_dt(&o->log, &dt_s, err, err_len) != 0) {
        return -1;
    }
    sim_log_identify_options_t fixed = *o;
    fixed.log.dt_s = dt_s; /* every pass on the same grid */
    /* pass 0: the gyro's spectrum (and the noise file), which sets the prefilter */
    static survey_t survey; /* three spectra: large */
    int rc = survey_open(&survey, o, dt_s, err, err_len);
    sim_ident_cache_t *cache = sim_ident_cache_new(); /* NULL: every pass reads the log */
    if (rc == 0) {
        rc = read_pass(&fixed, NULL, &survey, 0, &cache, stats, &out->outliers, err, err_len);
    }
    sim_gyro_filter_t *filter = survey.filter; /* kept past the survey's close */
    survey.filter = NULL;
    if (survey_close(&survey, o->noise_series, err, err_len) != 0 || rc != 0) {
        sim_gyro_filter_free(filter);
        sim_ident_cache_free(cache);
        return -1;
    }
    const sim_ident_options_t io = {.dt_s = dt_s,
                                    .prefilter_hz = prefilter_corner_hz(&survey, 1.0 / dt_s, o->prefilter_hz),
                                    .lag_max_s = o->lag_max_s,
                                    .delay_max_ticks = o->delay_max_ticks};
    sim_ident_t *id = sim_ident_new(&io);
    if (id == NULL) {
        snprintf(err, err_len, "%s: identification: out of memory", o->log.path);
        sim_gyro_filter_free(filter);
        sim_ident_cache_free(cache);
        return -1;
    }
    int pass;
    while (rc == 0 && (pass = sim_ident_begin_pass(id)) != 0) {
        rc = cache != NULL ? cache_pass(&fixed, cache, id, pass, err, err_len)
                           : read_pass(&fixed, id, NULL, pass, NULL, NULL, NULL, err, err_len);
        sim_ident_end_pass(id);
    }
    sim_ident_cache_free(cache);
    if (rc == 0) {
        out->dt_s = dt_s;
        out->prefilter_hz = sim_ident_prefilter_hz(id);
        double lo, hi;
        sim_airframe_floor_band(1.0 / dt_s, &lo, &hi);
        for (int i = 0; i < 3; ++i) {
            sim_ident_result(id, i, &out->axis[i]);
            const double floor = sim_spectrum_floor(&survey.spectrum[i], lo, hi);
            out->noise_floor_rad_s_rthz[i] = sqrt(floor);
            out->n_lines[i] = sim_spectrum_lines(&survey.spectrum[i], lo, floor, LINE_MIN_RATIO, out->lines[i],
                                                 SIM_SPECTRUM_MAX_LINES);
            out->gyro_filter[i] = (sim_gyro_filter_axis_t){NAN, NAN, NAN, 0};
            if (filter != NULL) {
                sim_gyro_filter_result(filter, i, lo, hi, LINE_MIN_RATIO, &out->gyro_filter[i]);
            }
        }
        out->has_gyro_filter = filter != NULL;
    }
    sim_gyro_filter_free(filter);
    sim_ident_free(id);
    return rc;
}
