/* SPDX-License-Identifier: BSD-3-Clause */
/* Controllers open loop on a log's streams (replay.h). */
#include "replay.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant/rotation.h"
#include "scenario/setup.h"

const double SIM_REPLAY_BAND_EDGES_HZ[SIM_REPLAY_BANDS + 1] = {0.0, 20.0, 100.0, INFINITY};

static void stat_add(sim_replay_stat_t *s, double x)
{
    /* Welford: stable over hours of samples */
    s->n++;
    const double d = x - s->mean;
    s->mean += d / (double)s->n;
    s->m2 += d * (x - s->mean);
}

double sim_replay_stat_std(const sim_replay_stat_t *s)
{
    return s->n > 1 ? sqrt(s->m2 / (double)(s->n - 1)) : NAN;
}

double sim_replay_stat_rms(const sim_replay_stat_t *s)
{
    return s->n > 0 ? sqrt(s->mean * s->mean + s->m2 / (double)s->n) : NAN;
}

static void axis_init(sim_replay_axis_t *a, double fs_hz)
{
    memset(a, 0, sizeof *a);
    sim_spectrum_init(&a->spectrum, fs_hz);
}

int sim_replay_init(sim_replay_t *r, const sim_scenario_t *sc, const sim_controller_id_t *ids, int n, char *err,
                    size_t err_len)
{
    memset(r, 0, sizeof *r);
    if (n < 0 || n > SIM_MAX_CONTROLLERS) { /* none: the log's own command alone */
        snprintf(err, err_len, "replay: %d controllers (0 to %d)", n, SIM_MAX_CONTROLLERS);
        return -1;
    }
    const double fs = 1.0 / sc->control_dt_s;
    r->n = n;
    r->quat_frame = sc->frame == LADRC_FRAME_QUATERNION;
    for (int i = 0; i < 3; ++i) {
        r->authority_Nm[i] = sim_setup_authority_Nm(sc, i);
        axis_init(&r->log_axis[i], fs);
        sim_spectrum_init(&r->gyro[i], fs);
        sim_spectrum_init(&r->gyro_raw[i], fs);
    }
    setpoint_smooth_init(&r->setpoint, sc->control_dt_s);
    r->filter_on = sim_setup_filters_gyro(sc);
    if (r->filter_on) {
        ladrc_gyro_filter_config_t fc;
        sim_setup_gyro_filter(sc, &fc);
        fc.channels = 3; /* the rates only */
        const ladrc_status_t st = ladrc_gyro_filter_init(&r->filter, &fc);
        if (st != LADRC_OK) {
            snprintf(err, err_len, "%s: [filter]: %s", sc->path, ladrc_status_str(st));
            return -1;
        }
        r->filter_hover_rotor_hz = sim_setup_hover_rotor_hz(sc);
    }
    for (int c = 0; c < n; ++c) {
        ladrc_attitude_config_t cfg;
        sim_setup_attitude(sc, ids[c], &cfg);
        int bad_axis = -1;
        const ladrc_status_t st = ladrc_attitude_init(&r->att[c], &cfg, &bad_axis);
        if (st != LADRC_OK) {
            snprintf(err, err_len, "%s: controller %s, axis %d: %s", sc->path, sim_controller_name(ids[c]), bad_axis,
                     ladrc_status_str(st));
            return -1;
        }
        r->ids[c] = ids[c];
        r->wrap_yaw[c] = !r->quat_frame && sim_setup_wraps_yaw(sc, ids[c]);
        r->has_estimate[c] = ids[c] != SIM_CTRL_PID && ids[c] != SIM_CTRL_CASCADED;
        for (int i = 0; i < 3; ++i) {
            axis_init(&r->axis[c][i], fs);
        }
    }
    return 0;
}

static ladrc_quat_t to_quat(const double q[4])
{
    const ladrc_quat_t out = {(ladrc_real_t)q[0], (ladrc_real_t)q[1], (ladrc_real_t)q[2], (ladrc_real_t)q[3]};
    return out;
}

/* The attitude and reference as quaternions: the log's own, else composed from the angles. */
static void quats_of(const sim_log_sample_t *s, unsigned has, const double ref_angle_rad[3], int smoothed, double q[4],
                     double q_ref[4])
{
    if (has & SIM_LOG_HAS_ANGLE) {
        memcpy(q, s->quat, 4 * sizeof q[0]);
    } else {
        sim_quat_from_euler(s->angle_rad, q);
    }
    if (smoothed) {
        sim_quat_from_euler(ref_angle_rad, q_ref); /* the smoothed setpoint's */
    } else if (has & SIM_LOG_HAS_REF_ANGLE) {
        memcpy(q_ref, s->ref_quat, 4 * sizeof q_ref[0]);
    } else {
        sim_quat_from_euler(ref_angle_rad, q_ref);
    }
}

/* The log's reference angles as the controllers get them: smoothed as a
 * stack smooths its link's steps (counted on the rate setpoint when logged). */
static int reference_of(sim_replay_t *r, const sim_log_sample_t *s, unsigned has, double ref_rad[3])
{
    memcpy(ref_rad, s->ref_angle_rad, 3 * sizeof ref_rad[0]);
    setpoint_smooth_step(&r->setpoint, (has & SIM_LOG_HAS_REF_RATE) ? s->ref_rate_rad_s : s->ref_angle_rad, ref_rad);
    return r->setpoint.state == SETPOINT_SMOOTH_ON;
}

/* The torque that acted on axis i: the log's normalised command times the
 * authority, as the simulator's controllers are told it (N m). */
static inline ladrc_real_t acting_Nm(const sim_replay_t *r, const sim_log_sample_t *s, int i)
{
    return (ladrc_real_t)(s->command[i] * r->authority_Nm[i]);
}

/* The gyro the filter stage runs on (replay.h): before the log's filters when it has it (rad/s). */
static inline ladrc_real_t stage_input_rad_s(const sim_log_sample_t *s, unsigned has, int i)
{
    return (ladrc_real_t)((has & SIM_LOG_HAS_GYRO_RAW) ? s->gyro_raw_rad_s[i] : s->gyro_rad_s[i]);
}

/* The scenario's stage over the gyro its noise came from (replay.h); a
 * sample the stage refuses keeps its latest output, as in flight. */
static void filter_rates(sim_replay_t *r, const sim_log_sample_t *s, unsigned has, ladrc_real_t rate[3])
{
    if (r->filter.rpm_rotors > 0) {
        ladrc_real_t hz[LADRC_GYRO_FILTER_MAX_ROTORS];
        for (int m = 0; m < (int)LADRC_GYRO_FILTER_MAX_ROTORS; ++m) {
            hz[m] = (ladrc_real_t)((has & SIM_LOG_HAS_ROTOR_HZ) && m < s->n_motors ? s->rotor_hz[m]
                                                                                   : r->filter_hover_rotor_hz);
        }
        ladrc_gyro_filter_set_rotor_hz(&r->filter, hz);
    }
    ladrc_real_t in[3];
    for (int i = 0; i < 3; ++i) {
        in[i] = stage_input_rad_s(s, has, i);
    }
    ladrc_gyro_filter_step(&r->filter, in, rate);
}

/* After a gap the reader skipped (replay.h): the controllers engage again
 * with the log's command acting, the smoothing and the filter stage restart
 * on the log's values, the spectra's segments start afresh. */
static void restart_after_gap(sim_replay_t *r, const sim_log_sample_t *s, unsigned has)
{
    ladrc_real_t acting[3], rate[3];
    for (int i = 0; i < 3; ++i) {
        acting[i] = acting_Nm(r, s, i);
        rate[i] = stage_input_rad_s(s, has, i);
        sim_spectrum_break(&r->gyro[i]);
        sim_spectrum_break(&r->gyro_raw[i]);
        sim_spectrum_break(&r->log_axis[i].spectrum);
        for (int c = 0; c < r->n; ++c) {
            sim_spectrum_break(&r->axis[c][i].spectrum);
        }
    }
    for (int c = 0; c < r->n; ++c) {
        ladrc_attitude_engage(&r->att[c], acting);
    }
    if (r->filter_on) {
        ladrc_gyro_filter_reset(&r->filter, rate);
    }
    setpoint_smooth_init(&r->setpoint, r->setpoint.dt_s);
    r->gap_restarts++;
}

/* The spectra a tick feeds: gyro, gyro before filters, the log's command, each controller's. */
#define TICK_SPECTRA (9 + 3 * SIM_MAX_CONTROLLERS)

void sim_replay_step(sim_replay_t *r, const sim_log_sample_t *s, unsigned has, sim_replay_tick_t *out)
{
    sim_spectrum_t *spectra[TICK_SPECTRA];
    double values[TICK_SPECTRA];
    int n_spectra = 0;
    ladrc_real_t rate[3], applied[3], angle[3], ref[3];
    double ref_rad[3];
    if (s->after_gap) {
        restart_after_gap(r, s, has);
    }
    const int smoothed = reference_of(r, s, has, ref_rad);
    for (int i = 0; i < 3; ++i) {
        rate[i] = (ladrc_real_t)s->gyro_rad_s[i];
        applied[i] = acting_Nm(r, s, i);
        angle[i] = (ladrc_real_t)s->angle_rad[i];
        ref[i] = (ladrc_real_t)ref_rad[i];
        spectra[n_spectra] = &r->gyro[i];
        values[n_spectra++] = s->gyro_rad_s[i];
        if (has & SIM_LOG_HAS_GYRO_RAW) {
            spectra[n_spectra] = &r->gyro_raw[i];
            values[n_spectra++] = s->gyro_raw_rad_s[i];
        }
        stat_add(&r->log_axis[i].command, s->command[i]);
        spectra[n_spectra] = &r->log_axis[i].spectrum;
        values[n_spectra++] = s->command[i];
    }
    if (r->filter_on) {
        filter_rates(r, s, has, rate);
    }
    ladrc_quat_t meas = {LADRC_R(1.0), 0, 0, 0}, qref = {LADRC_R(1.0), 0, 0, 0};
    if (r->quat_frame) {
        double q[4], q_ref[4];
        quats_of(s, has, ref_rad, smoothed, q, q_ref);
        meas = to_quat(q);
        qref = to_quat(q_ref);
    }
    for (int c = 0; c < r->n; ++c) {
        ladrc_real_t torque[3], a[3];
        memcpy(a, angle, sizeof a);
        if (r->wrap_yaw[c]) {
            a[2] = (ladrc_real_t)sim_wrap_pi((double)angle[2]);
        }
        const ladrc_fault_t f = r->quat_frame ? ladrc_attitude_step_quat(&r->att[c], &qref, &meas, rate, torque)
                                              : ladrc_attitude_step(&r->att[c], ref, a, rate, torque);
        ladrc_attitude_set_applied(&r->att[c], applied);
        out->faults[c] = f;
        if (f != LADRC_FAULT_NONE) {
            r->fault_ticks[c]++;
            r->faults_seen[c] |= f;
        }
        for (int i = 0; i < 3; ++i) {
            const double u = (double)torque[i] / r->authority_Nm[i];
            ladrc_real_t a_est, r_est, d_est;
            ladrc_axis_get_estimate(&r->att[c].axis[i], &a_est, &r_est, &d_est);
            out->command[c][i] = u;
            out->estimate[c][i] = r->has_estimate[c] ? (double)d_est : NAN;
            sim_replay_axis_t *ax = &r->axis[c][i];
            stat_add(&ax->command, u);
            stat_add(&ax->difference, u - s->command[i]);
            if (r->has_estimate[c]) {
                stat_add(&ax->estimate, (double)d_est);
            }
            spectra[n_spectra] = &ax->spectrum;
            values[n_spectra++] = u;
        }
    }
    sim_spectrum_push_many(spectra, values, n_spectra);
    r->ticks++;
}
