/* SPDX-License-Identifier: BSD-3-Clause */
/* What ladrc_replay writes and prints (replay_report.h). */
#include "replay_report.h"

#include <math.h>
#include <string.h>

#define RAD2DEG (180.0 / 3.14159265358979323846)

static const char *const AXIS[3] = {"roll", "pitch", "yaw"};

void sim_report_identification(FILE *out, const sim_airframe_t *a)
{
    fprintf(out, "identification at %.4g Hz, prefilter %.3g Hz (95 %% intervals):\n", 1.0 / a->dt_s, a->prefilter_hz);
    fprintf(out, "%-5s %28s %24s %14s %9s %6s %6s %12s\n", "axis", "b0 (rad/s^2 per unit)", "motor lag (ms)",
            "delay (ticks)", "damping", "R^2", "band", "gyro floor");
    for (int i = 0; i < 3; ++i) {
        const sim_ident_axis_t *x = &a->axis[i];
        char b0[64], lag[64], d[32];
        snprintf(b0, sizeof b0, "%.4g [%.4g, %.4g]", x->b0, x->b0_lo, x->b0_hi);
        snprintf(lag, sizeof lag, "%.1f [%.1f, %.1f]", 1e3 * x->lag_s, 1e3 * x->lag_lo_s, 1e3 * x->lag_hi_s);
        snprintf(d, sizeof d, "%d [%d, %d]", x->delay_ticks, x->delay_lo_ticks, x->delay_hi_ticks);
        fprintf(out, "%-5s %28s %24s %14s %7.3g/s %6.3f %6.2f %6.3g deg/s/rtHz\n", AXIS[i], b0, lag, d,
                x->damping_per_s, x->r2, x->band_share, a->noise_floor_rad_s_rthz[i] * RAD2DEG);
    }
    for (int i = 0; i < 3; ++i) {
        char outliers[512];
        if (sim_log_outliers_describe(&a->outliers, i, outliers, sizeof outliers) > 0) {
            fprintf(out, "%s\n", outliers);
        }
        if (sim_log_outliers_many(&a->outliers, i)) {
            fprintf(out,
                    "warning: %s: %.2g %% of the samples were outliers (more than %.2g %%): the log may be damaged "
                    "(a corrupt blackbox or a failing sensor); the identification used them repaired\n",
                    AXIS[i], 100.0 * (double)a->outliers.rejected[i] / (double)a->outliers.samples,
                    100.0 * SIM_LOG_OUTLIER_WARN_SHARE);
        }
        for (unsigned bit = 1; bit != 0 && bit <= SIM_IDENT_WARN_LAST; bit <<= 1) {
            if (a->axis[i].warnings & bit) {
                fprintf(out, "warning: %s: %s\n", AXIS[i], sim_ident_warning_text(bit));
            }
        }
        char note[256];
        if (sim_airframe_b0_note(a, i, note, sizeof note)) {
            fprintf(out, "%s\n", note);
        }
        if (a->has_gyro_filter) {
            const sim_gyro_filter_axis_t *g = &a->gyro_filter[i];
            fprintf(out, "%s: the log's gyro filters: delay %.2f ms, %.1f dB at the vibration lines (%d)\n", AXIS[i],
                    1e3 * g->delay_s, g->vib_atten_db, g->n_lines);
        }
        if (a->n_lines[i] > 0) {
            fprintf(out, "%s gyro lines:", AXIS[i]);
            for (int k = 0; k < a->n_lines[i]; ++k) {
                fprintf(out, " %.0f Hz %.3g deg/s%s", a->lines[i][k].hz, a->lines[i][k].rms * RAD2DEG,
                        k + 1 < a->n_lines[i] ? "," : "\n");
            }
        }
    }
}

int sim_write_identification_csv(const char *path, const sim_airframe_t *a)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fprintf(f, "axis,b0_rad_s2,b0_lo_rad_s2,b0_hi_rad_s2,lag_s,lag_lo_s,lag_hi_s,delay_ticks,delay_lo_ticks,"
               "delay_hi_ticks,damping_per_s,r2,command_rms,band_share,samples,warnings,gyro_floor_rad_s_rthz,"
               "lines_hz,b0_told,b0_flown_rad_s2,b0_iv_rad_s2,b0_iv_lo_rad_s2,b0_iv_hi_rad_s2,gyro_filter_delay_s,"
               "gyro_filter_vib_atten_db,outliers\n");
    for (int i = 0; i < 3; ++i) {
        const sim_ident_axis_t *x = &a->axis[i];
        fprintf(f, "%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d,%d,%d,%.9g,%.9g,%.9g,%.9g,%lld,%u,%.9g,", AXIS[i], x->b0,
                x->b0_lo, x->b0_hi, x->lag_s, x->lag_lo_s, x->lag_hi_s, x->delay_ticks, x->delay_lo_ticks,
                x->delay_hi_ticks, x->damping_per_s, x->r2, x->command_rms, x->band_share, x->samples, x->warnings,
                a->noise_floor_rad_s_rthz[i]);
        for (int k = 0; k < a->n_lines[i]; ++k) {
            fprintf(f, "%s%.6g", k > 0 ? " " : "", a->lines[i][k].hz);
        }
        sim_airframe_b0_source_t from;
        const double b0_flown = sim_airframe_b0(a, i, &from);
        fprintf(f, ",%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%lld\n", sim_ident_b0_told(x), b0_flown, x->b0_iv, x->b0_iv_lo,
                x->b0_iv_hi, a->gyro_filter[i].delay_s, a->gyro_filter[i].vib_atten_db, a->outliers.rejected[i]);
    }
    return (ferror(f) | fclose(f)) != 0 ? -1 : 0;
}

void sim_replay_csv_header(FILE *f, const sim_replay_t *r)
{
    fprintf(f, "t_s");
    for (int i = 0; i < 3; ++i) {
        fprintf(f, ",LOG_cmd_%s", AXIS[i]);
    }
    for (int c = 0; c < r->n; ++c) {
        const char *name = sim_controller_name(r->ids[c]);
        for (int i = 0; i < 3; ++i) {
            fprintf(f, ",%s_cmd_%s", name, AXIS[i]);
        }
        for (int i = 0; i < 3; ++i) {
            fprintf(f, ",%s_dist_%s_rad_s2", name, AXIS[i]);
        }
        fprintf(f, ",%s_faults", name);
    }
    fputc('\n', f);
}

void sim_replay_csv_row(FILE *f, const sim_replay_t *r, const sim_log_sample_t *s, const sim_replay_tick_t *t)
{
    fprintf(f, "%.9g,%.9g,%.9g,%.9g", s->t_s, s->command[0], s->command[1], s->command[2]);
    for (int c = 0; c < r->n; ++c) {
        fprintf(f, ",%.9g,%.9g,%.9g,%.6g,%.6g,%.6g,%u", t->command[c][0], t->command[c][1], t->command[c][2],
                t->estimate[c][0], t->estimate[c][1], t->estimate[c][2], (unsigned)t->faults[c]);
    }
    fputc('\n', f);
}

/* The command's noise in each band (its spectrum's rms there). */
static void band_rms(const sim_replay_axis_t *a, double out[SIM_REPLAY_BANDS])
{
    for (int b = 0; b < SIM_REPLAY_BANDS; ++b) {
        out[b] = sim_spectrum_band_rms(&a->spectrum, SIM_REPLAY_BAND_EDGES_HZ[b], SIM_REPLAY_BAND_EDGES_HZ[b + 1]);
    }
}

void sim_report_replay(FILE *out, const sim_replay_t *r)
{
    char smoothing[256];
    setpoint_smooth_describe(&r->setpoint, smoothing, sizeof smoothing);
    fprintf(out, "%s (every controller)\n", smoothing);
    fprintf(out, "replay of %lld ticks: commands normalised (1: full authority); noise as rms per band\n", r->ticks);
    fprintf(out, "%-10s %-5s %9s %9s %9s %9s %9s %12s %10s\n", "source", "axis", "rms", "0-20 Hz", "20-100 Hz",
            ">100 Hz", "vs log", "est. mean", "fault ticks");
    for (int c = -1; c < r->n; ++c) {
        for (int i = 0; i < 3; ++i) {
            const sim_replay_axis_t *a = c < 0 ? &r->log_axis[i] : &r->axis[c][i];
            double bands[SIM_REPLAY_BANDS];
            band_rms(a, bands);
            fprintf(out, "%-10s %-5s %9.4f %9.4f %9.4f %9.4f", c < 0 ? "LOG" : sim_controller_name(r->ids[c]), AXIS[i],
                    sim_replay_stat_rms(&a->command), bands[0], bands[1], bands[2]);
            if (c < 0) {
                fprintf(out, " %9s %12s %10s\n", "-", "-", "-");
                continue;
            }
            char est[32] = "-";
            if (r->has_estimate[c]) {
                snprintf(est, sizeof est, "%.4g", a->estimate.mean);
            }
            fprintf(out, " %9.4f %12s %10lld\n", sim_replay_stat_rms(&a->difference), est, r->fault_ticks[c]);
        }
    }
}

void sim_report_skipped(FILE *out, const sim_replay_skipped_t *skipped, int n_skipped)
{
    for (int c = 0; c < n_skipped; ++c) {
        fprintf(out, "%s%s, not replayed: %s\n", skipped[c].untunable ? "untunable " : "",
                sim_controller_name(skipped[c].id), skipped[c].reason);
    }
}

/* text as a CSV cell: quoted, its quotes doubled, no line breaks */
static void csv_cell(FILE *f, const char *prefix, const char *text)
{
    fprintf(f, "\"%s", prefix);
    for (const char *p = text; *p != '\0'; ++p) {
        if (*p == '"') {
            fputs("\"\"", f);
        } else {
            fputc(*p == '\n' || *p == '\r' ? ' ' : *p, f);
        }
    }
    fputc('"', f);
}

static int write_summary(const char *path, const sim_replay_t *r, const sim_replay_skipped_t *skipped, int n_skipped)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fprintf(f, "source,axis,ticks,command_rms,command_std,noise_0_20hz,noise_20_100hz,noise_above_100hz,"
               "difference_rms,estimate_mean_rad_s2,estimate_std_rad_s2,fault_ticks,faults,noise_above_20hz,status\n");
    for (int c = -1; c < r->n; ++c) {
        for (int i = 0; i < 3; ++i) {
            const sim_replay_axis_t *a = c < 0 ? &r->log_axis[i] : &r->axis[c][i];
            double bands[SIM_REPLAY_BANDS];
            band_rms(a, bands);
            const int est = c >= 0 && r->has_estimate[c];
            fprintf(f, "%s,%s,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%lld,%u,%.9g,replayed\n",
                    c < 0 ? "LOG" : sim_controller_name(r->ids[c]), AXIS[i], a->command.n,
                    sim_replay_stat_rms(&a->command), sim_replay_stat_std(&a->command), bands[0], bands[1], bands[2],
                    c < 0 ? NAN : sim_replay_stat_rms(&a->difference), est ? a->estimate.mean : NAN,
                    est ? sim_replay_stat_std(&a->estimate) : NAN, c < 0 ? 0LL : r->fault_ticks[c],
                    c < 0 ? 0u : (unsigned)r->faults_seen[c],
                    sim_spectrum_band_rms(&a->spectrum, SIM_REPLAY_BAND_EDGES_HZ[1], INFINITY));
        }
    }
    for (int c = 0; c < n_skipped; ++c) {
        for (int i = 0; i < 3; ++i) {
            fprintf(f, "%s,%s", sim_controller_name(skipped[c].id), AXIS[i]);
            for (int k = 0; k < 12; ++k) { /* every value column after the axis */
                fputs(skipped[c].untunable ? ",untunable" : ",not_replayed", f);
            }
            fputc(',', f);
            csv_cell(f, skipped[c].untunable ? "untunable: " : "not replayed: ", skipped[c].reason);
            fputc('\n', f);
        }
    }
    return (ferror(f) | fclose(f)) != 0 ? -1 : 0;
}

static int write_spectrum(const char *path, const sim_replay_t *r)
{
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        return -1;
    }
    fprintf(f, "hz");
    for (int i = 0; i < 3; ++i) {
        fprintf(f, ",gyro_%s,gyro_raw_%s,LOG_%s", AXIS[i], AXIS[i], AXIS[i]);
    }
    for (int c = 0; c < r->n; ++c) {
        for (int i = 0; i < 3; ++i) {
            fprintf(f, ",%s_%s", sim_controller_name(r->ids[c]), AXIS[i]);
        }
    }
    fputc('\n', f);
    for (int k = 1; k < SIM_SPECTRUM_BINS && sim_spectrum_segments(&r->gyro[0]) > 0; ++k) {
        fprintf(f, "%.6g", sim_spectrum_hz(&r->gyro[0], k));
        for (int i = 0; i < 3; ++i) {
            fprintf(f, ",%.6g,%.6g,%.6g", sim_spectrum_psd(&r->gyro[i], k), sim_spectrum_psd(&r->gyro_raw[i], k),
                    sim_spectrum_psd(&r->log_axis[i].spectrum, k));
        }
        for (int c = 0; c < r->n; ++c) {
            for (int i = 0; i < 3; ++i) {
                fprintf(f, ",%.6g", sim_spectrum_psd(&r->axis[c][i].spectrum, k));
            }
        }
        fputc('\n', f);
    }
    return (ferror(f) | fclose(f)) != 0 ? -1 : 0;
}

int sim_write_replay_files(const char *summary_path, const char *spectrum_path, const sim_replay_t *r,
                           const sim_replay_skipped_t *skipped, int n_skipped, char *why, size_t why_len)
{
    if (write_summary(summary_path, r, skipped, n_skipped) != 0) {
        snprintf(why, why_len, "%s: write failed", summary_path);
        return -1;
    }
    if (write_spectrum(spectrum_path, r) != 0) {
        snprintf(why, why_len, "%s: write failed", spectrum_path);
        return -1;
    }
    return 0;
}
