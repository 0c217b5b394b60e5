/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The runs' time series (runner_parts.h): new files with large buffers,
 * lines built in memory with numfmt.h's texts, and the attitude runs' line.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "runner_parts.h"

/* stdio buffer of a time series: fewer, larger writes */
#define CSV_BUFFER_BYTES (1 << 20)

FILE *runner_open_csv(const char *path, const char *header, char *err, size_t err_len)
{
    return runner_open_csv_buffered(path, header, CSV_BUFFER_BYTES, err, err_len);
}

FILE *runner_open_csv_buffered(const char *path, const char *header, size_t buffer_bytes, char *err, size_t err_len)
{
    if (path == NULL) {
        return NULL;
    }
    /* A new file rather than the old one truncated: a file system may flush
     * a truncated file's new data when it is closed (ext4's auto_da_alloc),
     * and a rerun would wait for that. */
    (void)unlink(path); /* not remove(): never a directory */
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        snprintf(err, err_len, "%s: cannot write: %s", path, strerror(errno));
        return NULL;
    }
    setvbuf(f, NULL, _IOFBF, buffer_bytes);
    fputs(header, f);
    return f;
}

void runner_line_f4(csv_line_t *l, double x)
{
    l->len += sim_fmt_f4(l->text + l->len, x);
}

void runner_line_g(csv_line_t *l, double x, int precision)
{
    l->text[l->len++] = ',';
    l->len += sim_fmt_g(l->text + l->len, x, precision);
}

void runner_line_end(csv_line_t *l, FILE *f)
{
    l->text[l->len++] = '\n';
    fwrite(l->text, 1, (size_t)l->len, f);
    l->len = 0;
}

/* The columns every attitude run has, in their order (docs/csv-format.md). */
static const char BASE_COLUMNS[] =
    "t_s,ref_roll_deg,ref_pitch_deg,ref_yaw_deg,angle_roll_deg,angle_pitch_deg,angle_yaw_deg,"
    "error_roll_deg,error_pitch_deg,error_yaw_deg,torque_cmd_roll_Nm,torque_cmd_pitch_Nm,torque_cmd_yaw_Nm,"
    "torque_roll_Nm,torque_pitch_Nm,torque_yaw_Nm,w2_1_rad2_s2,w2_2_rad2_s2,w2_3_rad2_s2,w2_4_rad2_s2,"
    "dist_roll_rad_s2,dist_pitch_rad_s2,dist_yaw_rad_s2,f_roll_rad_s2,f_pitch_rad_s2,f_yaw_rad_s2,"
    "f_est_roll_rad_s2,f_est_pitch_rad_s2,f_est_yaw_rad_s2,"
    "meas_angle_roll_deg,meas_angle_pitch_deg,meas_angle_yaw_deg,"
    "meas_rate_roll_deg_s,meas_rate_pitch_deg_s,meas_rate_yaw_deg_s,"
    "est_angle_roll_deg,est_angle_pitch_deg,est_angle_yaw_deg,"
    "est_rate_roll_deg_s,est_rate_pitch_deg_s,est_rate_yaw_deg_s,"
    "sat_roll_flag,sat_pitch_flag,sat_yaw_flag,sat_thrust_flag,"
    "ctrl_rate_roll_deg_s,ctrl_rate_pitch_deg_s,ctrl_rate_yaw_deg_s,"
    "accel_x_m_s2,accel_y_m_s2,accel_z_m_s2";

static const char *const AXIS_NAMES[3] = {"roll", "pitch", "yaw"};

/* ",{prefix}{axis}{unit}" for roll, pitch and yaw at out[*at]; stops at the end. */
static void axis_columns(char *out, size_t len, size_t *at, const char *prefix, const char *unit)
{
    for (int i = 0; i < 3 && *at < len; ++i) {
        const int n = snprintf(out + *at, len - *at, ",%s%s%s", prefix, AXIS_NAMES[i], unit);
        *at += n > 0 ? (size_t)n : 0u;
    }
}

/* The estimators' columns follow the base ones, so their readers keep working;
 * one frequency and amplitude pair per tone the build can model. */
void runner_attitude_csv_header(char *out, size_t len)
{
    size_t at = (size_t)snprintf(out, len, "%s", BASE_COLUMNS);
    axis_columns(out, len, &at, "hp_weight_", "_frac");
    axis_columns(out, len, &at, "hp_tones_", "_count");
    /* per tone k, in this order: its frequency, amplitude, gate evidence and coherence */
    static const char *const tone_families[][2] = {
        {"hp_freq", "_rad_s"}, {"hp_amp", "_rad_s2"}, {"hp_evidence", "_ratio"}, {"hp_coherence", "_frac"}};
    for (int k = 1; k <= LADRC_HP_MAX_TONES; ++k) {
        for (size_t f = 0; f < sizeof tone_families / sizeof tone_families[0]; ++f) {
            char prefix[32];
            snprintf(prefix, sizeof prefix, "%s%d_", tone_families[f][0], k);
            axis_columns(out, len, &at, prefix, tone_families[f][1]);
        }
    }
    axis_columns(out, len, &at, "hp_est_", "_rad_s2");
    axis_columns(out, len, &at, "lp_est_", "_rad_s2");
    if (at + 1 < len) {
        out[at++] = '\n';
        out[at] = '\0';
    }
}

/* The estimators' cells of the tick (runner_attitude_csv_header's order),
 * read through the library's getters: nan where the axis has no such
 * estimator, and for the tones beyond those active now. */
static void estimator_cells(csv_line_t *line, const ladrc_attitude_t *att)
{
    const ladrc_hp_estimator_t *hp[3];
    const ladrc_lp_estimator_t *lp[3];
    unsigned tones[3];
    for (int i = 0; i < 3; ++i) {
        hp[i] = att != NULL ? ladrc_axis_get_hp(&att->axis[i]) : NULL;
        lp[i] = att != NULL ? ladrc_axis_get_lp(&att->axis[i]) : NULL;
        tones[i] = hp[i] != NULL ? ladrc_hp_get_active_tones(hp[i]) : 0u;
    }
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, hp[i] != NULL ? (double)ladrc_hp_get_weight(hp[i]) : NAN, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, hp[i] != NULL ? (double)tones[i] : NAN, 6);
    for (unsigned k = 0; k < LADRC_HP_MAX_TONES; ++k) {
        ladrc_real_t (*const getters[])(const ladrc_hp_estimator_t *, unsigned) = {
            ladrc_hp_get_freq, ladrc_hp_get_amplitude, ladrc_hp_get_evidence, ladrc_hp_get_coherence};
        for (size_t g = 0; g < sizeof getters / sizeof getters[0]; ++g) {
            for (int i = 0; i < 3; ++i)
                runner_line_g(line, k < tones[i] ? (double)getters[g](hp[i], k) : NAN, 6);
        }
    }
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, hp[i] != NULL ? (double)ladrc_hp_get_estimate(hp[i]) : NAN, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, lp[i] != NULL ? (double)ladrc_lp_get_estimate(lp[i]) : NAN, 6);
}

/* The tick's line of the time series (runner_attitude_csv_header): the text of
 * %.4f, %.6g and %.7g (numfmt.h). */
void runner_csv_line(attitude_run_t *r, const tick_t *tk)
{
    const sim_plant_t *plant = &r->plant;
    const int has_estimate = r->spec->metrics->has_estimate;
    csv_line_t *line = &r->line;
    runner_line_f4(line, tk->t);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, (double)tk->ref[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, plant->angle_rad[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->err_rad[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, (double)tk->torque[i], 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->applied[i], 6);
    for (int q = 0; q < 4; ++q)
        runner_line_g(line, plant->w2_rad2_s2[q], 7);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->dist[i], 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->f_true[i], 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, has_estimate ? tk->f_est[i] : NAN, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->meas_angle[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->meas_rate[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->z1[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->z2[i] * RAD2DEG, 6);
    static const unsigned SAT_BITS[4] = {LADRC_MIXER_SAT_ROLL, LADRC_MIXER_SAT_PITCH, LADRC_MIXER_SAT_YAW,
                                         LADRC_MIXER_SAT_THRUST};
    for (int b = 0; b < 4; ++b)
        runner_line_g(line, (tk->out.saturated & SAT_BITS[b]) != 0u ? 1.0 : 0.0, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->ctrl_rate[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        runner_line_g(line, tk->accel_m_s2[i], 6);
    estimator_cells(line, r->bf != NULL ? NULL : &r->att); /* a SITL's estimators are not ours to read */
    runner_line_end(line, r->csv);
}
