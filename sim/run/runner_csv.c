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
    setvbuf(f, NULL, _IOFBF, CSV_BUFFER_BYTES);
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

const char RUNNER_ATTITUDE_CSV_HEADER[] =
    "t_s,ref_roll_deg,ref_pitch_deg,ref_yaw_deg,angle_roll_deg,angle_pitch_deg,angle_yaw_deg,"
    "error_roll_deg,error_pitch_deg,error_yaw_deg,torque_cmd_roll_Nm,torque_cmd_pitch_Nm,torque_cmd_yaw_Nm,"
    "torque_roll_Nm,torque_pitch_Nm,torque_yaw_Nm,w2_1_rad2_s2,w2_2_rad2_s2,w2_3_rad2_s2,w2_4_rad2_s2,"
    "dist_roll_rad_s2,dist_pitch_rad_s2,dist_yaw_rad_s2,f_roll_rad_s2,f_pitch_rad_s2,f_yaw_rad_s2,"
    "f_est_roll_rad_s2,f_est_pitch_rad_s2,f_est_yaw_rad_s2,"
    "meas_angle_roll_deg,meas_angle_pitch_deg,meas_angle_yaw_deg,"
    "meas_rate_roll_deg_s,meas_rate_pitch_deg_s,meas_rate_yaw_deg_s,"
    "est_angle_roll_deg,est_angle_pitch_deg,est_angle_yaw_deg,"
    "est_rate_roll_deg_s,est_rate_pitch_deg_s,est_rate_yaw_deg_s,"
    "sat_roll_flag,sat_pitch_flag,sat_yaw_flag,sat_thrust_flag\n";

/* The tick's line of the time series (RUNNER_ATTITUDE_CSV_HEADER): the text of
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
    runner_line_end(line, r->csv);
}
