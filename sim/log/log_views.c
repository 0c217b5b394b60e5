/* SPDX-License-Identifier: BSD-3-Clause */
/* The field's views of flight logs as CSVs (log_views.h). */
#include "log_views.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "response.h"

#define RAD_TO_DEG (180.0 / 3.14159265358979323846)

static const char *const AXIS_NAMES[3] = {"roll", "pitch", "yaw"};
static const char *const NOISE_NAMES[SIM_NOISE_SIGNALS] = {"gyro_deg_s", "gyro_raw_deg_s", "command"};

/* One log read through a response; NULL with err set. */
static sim_response_t *read_log(const sim_views_input_t *in, char *err, size_t len)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(&in->log, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, len);
        return NULL;
    }
    sim_response_t *r = sim_response_new(sim_log_dt_s(log));
    if (r == NULL) {
        snprintf(err, len, "%s: control period %g s: no views (out of memory or not in (0, 1) s)", in->log.path,
                 sim_log_dt_s(log));
        sim_log_close(log);
        return NULL;
    }
    const unsigned has = sim_log_has(log);
    sim_log_sample_t s;
    int rc;
    while ((rc = sim_log_next(log, &s, &lerr)) == 1) {
        sim_response_push(r, &s, has);
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, len);
        sim_response_free(r);
        r = NULL;
    }
    sim_log_close(log);
    return r;
}

static void write_step(FILE *f, const char *source, sim_response_t *r)
{
    for (int a = 0; a < 3; ++a) {
        sim_step_response_t st;
        sim_response_step(r, a, &st);
        if (st.windows == 0) {
            continue;
        }
        for (int i = 0; i < st.n; ++i) {
            fprintf(f, "%s,%s,%.6g,%.6g,%.6g\n", source, AXIS_NAMES[a], i * sim_response_dt_s(r), st.mean[i],
                    st.spread[i]);
        }
    }
}

static void write_freq(FILE *f, const char *source, const sim_response_t *r)
{
    for (int a = 0; a < 3; ++a) {
        if (sim_response_freq_segments(r, a) == 0) {
            continue;
        }
        for (int k = 1; k < sim_response_freq_bins(r); ++k) {
            double hz, gain, phase, coh;
            sim_response_freq(r, a, k, &hz, &gain, &phase, &coh);
            fprintf(f, "%s,%s,%.6g,%.6g,%.6g,%.6g\n", source, AXIS_NAMES[a], hz, gain, phase * RAD_TO_DEG, coh);
        }
    }
}

static void write_noise(FILE *f, const char *source, const sim_response_t *r)
{
    for (int s = 0; s < SIM_NOISE_SIGNALS; ++s) {
        const double scale = s == SIM_NOISE_COMMAND ? 1.0 : RAD_TO_DEG * RAD_TO_DEG;
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < SIM_RESPONSE_THROTTLE_BINS; ++b) {
                const long segments = sim_response_noise_segments(r, b);
                if (segments == 0 || isnan(sim_response_noise_psd(r, (sim_noise_signal_t)s, a, b, 0))) {
                    continue;
                }
                for (int k = 0; k < sim_response_noise_bins(r); ++k) {
                    fprintf(f, "%s,%s,%s,%.2f,%.2f,%ld,%.6g,%.6g\n", source, NOISE_NAMES[s], AXIS_NAMES[a],
                            (double)b / SIM_RESPONSE_THROTTLE_BINS, (double)(b + 1) / SIM_RESPONSE_THROTTLE_BINS,
                            segments, sim_response_noise_hz(r, k),
                            scale * sim_response_noise_psd(r, (sim_noise_signal_t)s, a, b, k));
                }
            }
        }
    }
}

static void write_summary(FILE *f, FILE *report, const char *source, sim_response_t *r)
{
    for (int a = 0; a < 3; ++a) {
        sim_step_response_t st;
        sim_response_step(r, a, &st);
        fprintf(f, "%s,%s,%d,%d,%.4g,%.4g,%.4g,%.4g,%ld\n", source, AXIS_NAMES[a], st.windows, st.rejected, st.steady,
                1e3 * st.rise_s, 1e3 * st.delay_s, 100.0 * st.overshoot, sim_response_freq_segments(r, a));
        if (report == NULL) {
            continue;
        }
        const unsigned has = sim_response_has(r);
        if (!(has & SIM_LOG_HAS_REF_RATE) || !(has & SIM_LOG_HAS_GYRO)) {
            fprintf(report, "step response %s %s: the log has no %s (map it with --map %s)\n", source, AXIS_NAMES[a],
                    (has & SIM_LOG_HAS_GYRO) ? "rate setpoint" : "gyro",
                    (has & SIM_LOG_HAS_GYRO) ? "ref_rate[i]=COLUMN*deg" : "gyro[i]=COLUMN*deg");
        } else if (st.windows == 0 && st.rejected == 0) {
            fprintf(report, "step response %s %s: no %.0f s window whose setpoint reaches %.0f deg/s\n", source,
                    AXIS_NAMES[a], SIM_RESPONSE_WINDOW_S, SIM_RESPONSE_MIN_INPUT_DEG_S);
        } else if (st.windows == 0) {
            fprintf(report,
                    "step response %s %s: %d windows reach %.0f deg/s, none whose step stays within %.1f-%.0f over "
                    "%.1f-%.1f s\n",
                    source, AXIS_NAMES[a], st.rejected, SIM_RESPONSE_MIN_INPUT_DEG_S, SIM_RESPONSE_STEADY_MIN,
                    SIM_RESPONSE_STEADY_MAX, SIM_RESPONSE_STEADY_FROM_S, SIM_RESPONSE_LENGTH_S);
        } else {
            fprintf(report,
                    "step response %s %s: %d windows (%d dropped): rise %.1f ms, delay %.1f ms, overshoot %.1f %%, "
                    "steady %.3f\n",
                    source, AXIS_NAMES[a], st.windows, st.rejected, 1e3 * st.rise_s, 1e3 * st.delay_s,
                    100.0 * st.overshoot, st.steady);
        }
    }
}

/* Opens dir/name for writing with its header; NULL with err set. */
static FILE *open_csv(const char *dir, const char *name, const char *header, char *path, size_t path_len, char *err,
                      size_t len)
{
    snprintf(path, path_len, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        snprintf(err, len, "%s: cannot write: %s", path, strerror(errno));
        return NULL;
    }
    fprintf(f, "%s\n", header);
    return f;
}

enum { STEP, FREQ, NOISE, SUMMARY, FILES };

static const char *const names[FILES] = {"step_response.csv", "freq_response.csv", "noise_throttle.csv",
                                         "response_summary.csv"};

const char *sim_log_views_file(int k)
{
    return k >= 0 && k < FILES ? names[k] : NULL;
}

int sim_log_views_write(const sim_views_input_t *in, int n, const char *dir, FILE *report, char *err, size_t len)
{
    static const char *const headers[FILES] = {
        "source,axis,t_s,step,spread", "source,axis,hz,gain,phase_deg,coherence",
        "source,signal,axis,throttle_from,throttle_to,segments,hz,psd",
        "source,axis,windows,rejected,steady,rise_ms,delay_ms,overshoot_pct,freq_segments"};
    sim_response_t **resp = calloc((size_t)(n > 0 ? n : 1), sizeof *resp);
    if (resp == NULL) {
        snprintf(err, len, "out of memory");
        return -1;
    }
    int rc = 0;
    for (int i = 0; i < n && rc == 0; ++i) {
        resp[i] = read_log(&in[i], err, len);
        rc = resp[i] == NULL ? -1 : 0;
    }
    FILE *f[FILES] = {NULL, NULL, NULL, NULL};
    char path[FILES][1024];
    for (int j = 0; j < FILES && rc == 0; ++j) {
        f[j] = open_csv(dir, names[j], headers[j], path[j], sizeof path[j], err, len);
        rc = f[j] == NULL ? -1 : 0;
    }
    for (int i = 0; i < n && rc == 0; ++i) {
        write_step(f[STEP], in[i].source, resp[i]);
        write_freq(f[FREQ], in[i].source, resp[i]);
        write_noise(f[NOISE], in[i].source, resp[i]);
        write_summary(f[SUMMARY], report, in[i].source, resp[i]);
    }
    for (int j = 0; j < FILES; ++j) {
        if (f[j] != NULL && (ferror(f[j]) | fclose(f[j])) != 0 && rc == 0) {
            snprintf(err, len, "%s: write failed", path[j]);
            rc = -1;
        }
    }
    for (int i = 0; i < n; ++i) {
        sim_response_free(resp[i]);
    }
    free(resp);
    return rc;
}

int sim_log_views_of_log(const sim_log_options_t *log, const char *dir, FILE *report, char *err, size_t len)
{
    sim_views_input_t in = {.source = "LOG", .log = *log};
    return sim_log_views_write(&in, 1, dir, report, err, len);
}
