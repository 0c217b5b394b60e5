/* SPDX-License-Identifier: BSD-3-Clause */
#define _POSIX_C_SOURCE 200809L
/* One simulation run (see runner.h). */
#include "runner.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ladrc/attitude.h"
#include "ladrc/levant.h"
#include "ladrc/mixer.h"
#include "ladrc/td.h"
#include "numfmt.h"
#include "plant.h"
#include "rng.h"
#include "sensor.h"
#include "setup.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

/* A group's plants step side by side (sim_plant_step_group). */
typedef char plant_group_fits_t[SIM_MAX_CONTROLLERS <= SIM_PLANT_GROUP_MAX ? 1 : -1];

long sim_run_ticks(const sim_scenario_t *sc)
{
    return (long)floor(sc->duration_s / sc->control_dt_s + 0.5);
}

static double wall_now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The controller and mixer of the run, configured as the parser checked them. */
static int configure(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_t *att, ladrc_mixer_t *mixer,
                     char *err, size_t err_len)
{
    ladrc_attitude_config_t cfg;
    sim_setup_attitude(sc, id, &cfg);
    int bad_axis = -1;
    ladrc_status_t st = ladrc_attitude_init(att, &cfg, &bad_axis);
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: controller %s, axis %d: %s", sc->path, sim_controller_name(id), bad_axis,
                 ladrc_status_str(st));
        return -1;
    }
    ladrc_mixer_config_t mix;
    sim_setup_mixer(sc, &mix);
    st = ladrc_mixer_init(mixer, &mix);
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: mixer: %s", sc->path, ladrc_status_str(st));
        return -1;
    }
    return 0;
}

/* The disturbances of the three axes at t_s; the axes often share sin(w t). */
static void disturbances_at(const sim_scenario_t *sc, double t_s, double d_out[3])
{
    sim_expr_memo_t memo;
    sim_expr_memo_clear(&memo);
    for (int i = 0; i < 3; ++i) {
        d_out[i] = sim_signal_eval_memo(&sc->disturbance[i], t_s, &memo);
    }
}

/* The disturbances of one plant step, worked out in one batch before it:
 * the plant lists its stage times (sim_plant_stage_times), each distinct
 * time is evaluated once (t + h of a substep is often the next one's t, and
 * the last of a step the next step's first), and the plant's calls, in the
 * listed order, read the table. The same values bit for bit as evaluating
 * at every call. */
#define STAGES_MAX (3 * SIM_PLANT_SUBSTEPS_MAX)
typedef struct {
    const sim_scenario_t *sc;
    int n; /* stage times of the step */
    double t_s[STAGES_MAX];
    int slot[STAGES_MAX];        /* its row of value */
    double value[STAGES_MAX][3]; /* by distinct time, in order */
    double stage[STAGES_MAX][3]; /* by stage time: value[slot[k]] */
    double last_t_s;             /* the last distinct time (NaN: none) */
    int last;                    /* and its row */
} disturbance_batch_t;

static void disturbance_batch_init(disturbance_batch_t *b, const sim_scenario_t *sc)
{
    b->sc = sc;
    b->n = b->last = 0;
    b->last_t_s = NAN; /* never equal: empty */
}

/* Metric windows hold (from, to], as signal windows do. */
static int in_window(const double w[2], double t)
{
    return t > w[0] && t <= w[1];
}

static void disturbance_batch_fill(disturbance_batch_t *b, const sim_plant_t *p, double dt_s, int substeps)
{
    /* more than the parser lets through: no table, every call evaluates */
    b->n = substeps <= SIM_PLANT_SUBSTEPS_MAX ? sim_plant_stage_times(p, dt_s, substeps, b->t_s) : 0;
    int rows = 0, carried = 0;
    double distinct[STAGES_MAX];
    if (b->n > 0 && b->t_s[0] == b->last_t_s) { /* carried over from the step before */
        for (int i = 0; i < 3; ++i) {
            b->value[0][i] = b->value[b->last][i];
        }
        distinct[0] = b->t_s[0];
        rows = carried = 1;
    }
    for (int k = 0; k < b->n; ++k) {
        if (rows == 0 || b->t_s[k] != distinct[rows - 1]) {
            distinct[rows++] = b->t_s[k];
        }
        b->slot[k] = rows - 1;
    }
    /* the new rows, SIM_EXPR_BATCH_MAX instants at a time, the three axes
     * sharing their function results */
    for (int r = carried; r < rows; r += SIM_EXPR_BATCH_MAX) {
        const int m = rows - r < SIM_EXPR_BATCH_MAX ? rows - r : SIM_EXPR_BATCH_MAX;
        double lo, hi;
        sim_signal_batch_range(&distinct[r], m, &lo, &hi);
        sim_expr_batch_memo_t memo;
        sim_expr_batch_memo_clear(&memo);
        for (int i = 0; i < 3; ++i) {
            double d[SIM_EXPR_BATCH_MAX];
            sim_signal_eval_batch(&b->sc->disturbance[i], &distinct[r], m, lo, hi, d, &memo);
            for (int j = 0; j < m; ++j) {
                b->value[r + j][i] = d[j];
            }
        }
    }
    for (int k = 0; k < b->n; ++k) {
        for (int i = 0; i < 3; ++i) {
            b->stage[k][i] = b->value[b->slot[k]][i];
        }
    }
    if (rows > 0) {
        b->last_t_s = distinct[rows - 1];
    }
    b->last = rows - 1;
}

/* The control instants t = k dt of SIM_EXPR_BATCH_MAX ticks from `first`,
 * with the references and disturbances there, worked out together: each
 * signal's program interpreted once for all of them, the function results
 * shared by the six signals (sim_signal_eval's values, bit for bit). */
typedef struct {
    long first; /* the tick of row 0 */
    int n;      /* rows */
    double t_s[SIM_EXPR_BATCH_MAX];
    ladrc_real_t ref[3][SIM_EXPR_BATCH_MAX]; /* rad, as the controllers get them */
    double dist[3][SIM_EXPR_BATCH_MAX];
} instants_t;

static void instants_fill(instants_t *b, const sim_scenario_t *sc, long first, long n_ticks)
{
    b->first = first;
    b->n = n_ticks - first < SIM_EXPR_BATCH_MAX ? (int)(n_ticks - first) : SIM_EXPR_BATCH_MAX;
    for (int j = 0; j < b->n; ++j) {
        b->t_s[j] = (double)(first + j) * sc->control_dt_s;
    }
    double lo, hi;
    sim_signal_batch_range(b->t_s, b->n, &lo, &hi);
    sim_expr_batch_memo_t memo;
    sim_expr_batch_memo_clear(&memo);
    for (int i = 0; i < 3; ++i) {
        double ref[SIM_EXPR_BATCH_MAX];
        sim_signal_eval_batch(&sc->reference[i], b->t_s, b->n, lo, hi, ref, &memo);
        for (int j = 0; j < b->n; ++j) {
            b->ref[i][j] = (ladrc_real_t)ref[j];
        }
    }
    for (int i = 0; i < 3; ++i) {
        sim_signal_eval_batch(&sc->disturbance[i], b->t_s, b->n, lo, hi, b->dist[i], &memo);
    }
}

/* One plant's reading of a batch: the stage time it asks for next. Runs in
 * lockstep share the batch (their plants' times are the same bits). */
typedef struct {
    const disturbance_batch_t *b;
    int next;
} batch_reader_t;

static void disturbance(double t_s, void *ctx, double d_out[3])
{
    batch_reader_t *r = (batch_reader_t *)ctx;
    const disturbance_batch_t *b = r->b;
    if (r->next < b->n && b->t_s[r->next] == t_s) {
        const double *v = b->value[b->slot[r->next++]];
        for (int i = 0; i < 3; ++i) {
            d_out[i] = v[i];
        }
    } else { /* not the listed time: evaluated as asked */
        disturbances_at(b->sc, t_s, d_out);
    }
}

/* stdio buffer of a time series: fewer, larger writes */
#define CSV_BUFFER_BYTES (1 << 20)

static FILE *open_csv(const char *path, const char *header, char *err, size_t err_len)
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

/* One CSV line in memory, written with one fwrite. */
typedef struct {
    char text[64 * SIM_NUMFMT_MAX];
    int len;
} csv_line_t;

static void line_f4(csv_line_t *l, double x)
{
    l->len += sim_fmt_f4(l->text + l->len, x);
}

static void line_g(csv_line_t *l, double x, int precision)
{
    l->text[l->len++] = ',';
    l->len += sim_fmt_g(l->text + l->len, x, precision);
}

static void line_end(csv_line_t *l, FILE *f)
{
    l->text[l->len++] = '\n';
    fwrite(l->text, 1, (size_t)l->len, f);
    l->len = 0;
}

static const char ATTITUDE_CSV_HEADER[] =
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

/* An angle into (-pi, pi], and itself bit for bit when it is there already. */
static double wrap_pi(double x)
{
    const double pi = 3.14159265358979323846;
    return (x > -pi && x <= pi) ? x : x - 2.0 * pi * ceil((x - pi) / (2.0 * pi));
}

/* ref - angle (rad); on a wrapped axis taken into (-pi, pi]: 359 deg of error is 1 deg. */
static double tracking_error_rad(double ref_rad, double angle_rad, int wrapped)
{
    const double e = ref_rad - angle_rad;
    return wrapped ? wrap_pi(e) : e;
}

/* Divergence at t (runner.h): the plant's state non-finite, or the tracking
 * error ref - angle beyond the scenario's limit on an axis. Records the first
 * cause found in m and returns 1; 0 while the run is healthy. */
static int diverged(const sim_scenario_t *sc, const sim_plant_t *p, const double ref_rad[3], int wrap_yaw, double t_s,
                    sim_metrics_t *m)
{
    int axis = -2;
    double error_deg = NAN;
    for (int i = 0; i < 3 && axis == -2; ++i) {
        const double e_deg = tracking_error_rad(ref_rad[i], p->angle_rad[i], i == 2 && wrap_yaw) * RAD2DEG;
        if (!isfinite(e_deg) || !isfinite(p->rate_rad_s[i])) {
            axis = i;
            m->finite = 0;
        } else if (fabs(e_deg) > sc->diverge_limit_deg) {
            axis = i;
            error_deg = fabs(e_deg);
        }
    }
    for (int r = 0; r < 4 && axis == -2; ++r) {
        if (!isfinite(p->w2_rad2_s2[r])) {
            axis = -1;
            m->finite = 0;
        }
    }
    if (axis == -2) {
        return 0;
    }
    m->diverged = 1;
    m->diverged_at_s = t_s;
    m->diverged_axis = axis;
    m->diverged_error_deg = error_deg;
    return 1;
}

/* The references at t, rad, as the controllers get them (ladrc_real_t). */
static void references(const sim_scenario_t *sc, double t_s, sim_expr_memo_t *memo, ladrc_real_t ref[3])
{
    for (int i = 0; i < 3; ++i) {
        ref[i] = (ladrc_real_t)sim_signal_eval_memo(&sc->reference[i], t_s, memo);
    }
}

static void widen(const ladrc_real_t x[3], double out[3])
{
    for (int i = 0; i < 3; ++i) {
        out[i] = (double)x[i];
    }
}

/* One run of a lockstep group: what it keeps from tick to tick. */
typedef struct {
    sim_run_spec_t *spec;
    ladrc_attitude_t att;
    ladrc_mixer_t mixer;
    sim_plant_t plant;
    sim_sensor_t sensor;
    FILE *csv;
    csv_line_t line;
    double last_out_s[3];
    int out_at_last[3]; /* outside the band at the settle window's latest sample so far */
    int wrap_yaw;
    int flying; /* 1 until it diverges */
} attitude_run_t;

/* Sets a run up; 0, or -1 with the message in its spec (then it does not fly). */
static int run_open(const sim_scenario_t *sc, attitude_run_t *r, sim_run_spec_t *spec)
{
    sim_metrics_t *m = spec->metrics;
    r->spec = spec;
    r->flying = 0;
    r->csv = NULL;
    memset(m, 0, sizeof *m);
    if (configure(sc, spec->ctrl, &r->att, &r->mixer, spec->err, spec->err_len) != 0) {
        return -1;
    }
    const sim_vehicle_t vehicle = {
        sc->mass_kg,         {sc->inertia_kg_m2[0], sc->inertia_kg_m2[1], sc->inertia_kg_m2[2]},
        sc->arm_m,           sc->thrust_coeff_N_s2,
        sc->yaw_coeff_Nm_s2, sc->rot_drag_Nm_s,
        sc->g_m_s2,          sc->rotors_ideal,
        sc->w2_min_rad2_s2,  sc->w2_max_rad2_s2,
        sc->motor_tau_s};
    sim_plant_init(&r->plant, &vehicle);
    if (sim_sensor_init(&r->sensor, sc->angle_noise_std_rad, sc->rate_noise_std_rad_s, sc->delay_ticks, sc->seed) !=
        0) {
        snprintf(spec->err, spec->err_len, "%s: bad sensor settings", sc->path);
        return -1;
    }
    r->csv = open_csv(spec->csv_path, ATTITUDE_CSV_HEADER, spec->err, spec->err_len);
    if (spec->csv_path != NULL && r->csv == NULL) {
        return -1;
    }
    r->line.len = 0;
    for (int i = 0; i < 3; ++i) {
        r->last_out_s[i] = sc->settle_after_s;
        r->out_at_last[i] = 0;
        m->settle_s[i] = SIM_NOT_SETTLED;
    }
    /* A wrapping controller is told yaw as an attitude estimator gives it,
     * in (-pi, pi]; the plant's own yaw is continuous (not wrapped). */
    r->wrap_yaw = sim_setup_wraps_yaw(sc, spec->ctrl);
    m->has_estimate = spec->ctrl != SIM_CTRL_PID && spec->ctrl != SIM_CTRL_CASCADED;
    m->finite = 1;
    m->diverged_axis = -1;
    m->diverged_at_s = m->diverged_error_deg = NAN;
    r->flying = 1;
    return 0;
}

/* What one control tick of a run saw and did, for its metrics and time series. */
typedef struct {
    double t;                     /* s */
    const ladrc_real_t *ref;      /* rad, as the controller got them */
    const double *ref_rad, *dist; /* the same widened; disturbances, rad/s^2 */
    double meas_angle[3], meas_rate[3];
    ladrc_real_t torque[3]; /* commanded, N m */
    ladrc_mixer_output_t out;
    /* the truth at this tick: the disturbance the observer should see is
     * the plant's acceleration minus what the applied torque explains */
    double applied[3], f_true[3], f_est[3], err_rad[3], z1[3], z2[3];
} tick_t;

/* Measure, check, control and mix at tk->t; 0 when the run diverged (nothing
 * of this instant or later is recorded), else 1 with the rotors' command. */
static int run_control(const sim_scenario_t *sc, attitude_run_t *r, tick_t *tk, double w2_cmd[4])
{
    const sim_plant_t *plant = &r->plant;
    sim_sensor_measure(&r->sensor, plant->angle_rad, plant->rate_rad_s, tk->meas_angle, tk->meas_rate);
    if (r->wrap_yaw) {
        tk->meas_angle[2] = wrap_pi(tk->meas_angle[2]);
    }
    if (diverged(sc, plant, tk->ref_rad, r->wrap_yaw, tk->t, r->spec->metrics)) {
        return 0;
    }
    ladrc_real_t angle[3], rate[3];
    for (int i = 0; i < 3; ++i) {
        angle[i] = (ladrc_real_t)tk->meas_angle[i];
        rate[i] = (ladrc_real_t)tk->meas_rate[i];
    }
    if (ladrc_attitude_step(&r->att, tk->ref, angle, sc->use_rate ? rate : NULL, tk->torque) != LADRC_FAULT_NONE) {
        r->spec->metrics->faults++;
    }
    ladrc_mixer_step(&r->mixer, ladrc_mixer_thrust_from_tilt(&r->mixer, angle[0], angle[1]), tk->torque, &tk->out);
    ladrc_attitude_set_applied(&r->att, tk->out.torque_Nm);
    for (int q = 0; q < 4; ++q) {
        w2_cmd[q] = tk->out.w2_rad2_s2[q];
    }
    return 1;
}

/* The truth of the tick and the controller's estimates (tick_t). */
static void run_truth(const sim_scenario_t *sc, const attitude_run_t *r, tick_t *tk)
{
    const sim_plant_t *plant = &r->plant;
    double accel[3], thrust_actual, torque_actual[3];
    for (int i = 0; i < 3; ++i) {
        tk->applied[i] = tk->out.torque_Nm[i];
    }
    sim_plant_forces(&plant->v, plant->w2_rad2_s2, &thrust_actual, torque_actual);
    sim_plant_accel(plant, torque_actual, tk->dist, accel);
    for (int i = 0; i < 3; ++i) {
        tk->f_true[i] = accel[i] - tk->applied[i] / (sc->inertia_kg_m2[i] * sc->inertia_scale[i]);
        ladrc_real_t a_est, r_est, d_est;
        ladrc_axis_get_estimate(&r->att.axis[i], &a_est, &r_est, &d_est);
        tk->f_est[i] = d_est;
        tk->z1[i] = a_est;
        tk->z2[i] = r_est;
        tk->err_rad[i] = tracking_error_rad(tk->ref_rad[i], plant->angle_rad[i], i == 2 && r->wrap_yaw);
    }
}

/* The tick into the run's statistics (metrics.h) and settling. */
static void run_metrics(const sim_scenario_t *sc, attitude_run_t *r, const tick_t *tk)
{
    sim_metrics_t *m = r->spec->metrics;
    const double t = tk->t;
    const double band_rad = sc->settle_band_deg / RAD2DEG;
    for (int i = 0; i < 3; ++i) {
        const double e_deg = tk->err_rad[i] * RAD2DEG;
        if (in_window(sc->error_window_s, t)) {
            sim_stat_add(&m->error_deg[i], e_deg);
            if (fabs(e_deg) > m->max_error_deg[i])
                m->max_error_deg[i] = fabs(e_deg);
            if (m->has_estimate)
                sim_stat_add(&m->dist_error[i], tk->f_est[i] - tk->f_true[i]);
        }
        if (in_window(sc->steady_window_s, t) && fabs(e_deg) > m->band_deg[i]) {
            m->band_deg[i] = fabs(e_deg);
        }
        if (t >= sc->settle_after_s && t <= sc->settle_until_s) {
            r->out_at_last[i] = fabs(tk->err_rad[i]) > band_rad;
            if (r->out_at_last[i]) {
                r->last_out_s[i] = t + sc->control_dt_s;
            }
        }
    }
    for (int q = 0; q < 4; ++q) {
        sim_stat_add(&m->rotor_w2[q], r->plant.w2_rad2_s2[q]);
    }
}

/* The tick's line of the time series (ATTITUDE_CSV_HEADER): the text of
 * %.4f, %.6g and %.7g (numfmt.h). */
static void run_csv_line(attitude_run_t *r, const tick_t *tk)
{
    const sim_plant_t *plant = &r->plant;
    const int has_estimate = r->spec->metrics->has_estimate;
    csv_line_t *line = &r->line;
    line_f4(line, tk->t);
    for (int i = 0; i < 3; ++i)
        line_g(line, (double)tk->ref[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, plant->angle_rad[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->err_rad[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, (double)tk->torque[i], 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->applied[i], 6);
    for (int q = 0; q < 4; ++q)
        line_g(line, plant->w2_rad2_s2[q], 7);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->dist[i], 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->f_true[i], 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, has_estimate ? tk->f_est[i] : NAN, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->meas_angle[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->meas_rate[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->z1[i] * RAD2DEG, 6);
    for (int i = 0; i < 3; ++i)
        line_g(line, tk->z2[i] * RAD2DEG, 6);
    static const unsigned SAT_BITS[4] = {LADRC_MIXER_SAT_ROLL, LADRC_MIXER_SAT_PITCH, LADRC_MIXER_SAT_YAW,
                                         LADRC_MIXER_SAT_THRUST};
    for (int b = 0; b < 4; ++b)
        line_g(line, (tk->out.saturated & SAT_BITS[b]) != 0u ? 1.0 : 0.0, 6);
    line_end(line, r->csv);
}

/* The controller's part of a tick at t: measure, check, control, record.
 * ref and dist are the references and disturbances at t. Returns 0 when the
 * run diverged (nothing of this instant or later is recorded), else 1. */
static int run_tick(const sim_scenario_t *sc, attitude_run_t *r, double t, const ladrc_real_t ref[3],
                    const double ref_rad[3], const double dist[3], double w2_cmd[4])
{
    tick_t tk;
    tk.t = t;
    tk.ref = ref;
    tk.ref_rad = ref_rad;
    tk.dist = dist;
    if (!run_control(sc, r, &tk, w2_cmd)) {
        return 0;
    }
    run_truth(sc, r, &tk);
    run_metrics(sc, r, &tk);
    if (r->csv != NULL) {
        run_csv_line(r, &tk);
    }
    return 1;
}

/* Settling times and the time series' end; 0, or -1 with the message. */
static int run_close(const sim_scenario_t *sc, attitude_run_t *r)
{
    sim_metrics_t *m = r->spec->metrics;
    for (int i = 0; i < 3; ++i) {
        m->settle_s[i] = r->out_at_last[i] ? SIM_NOT_SETTLED : r->last_out_s[i] - sc->settle_after_s;
    }
    if (r->csv != NULL && fclose(r->csv) != 0) {
        snprintf(r->spec->err, r->spec->err_len, "%s: write failed", r->spec->csv_path);
        return -1;
    }
    return 0;
}

/* A lockstep group of runs on one scenario (sim_run_attitude_group). */
typedef struct {
    const sim_scenario_t *sc;
    sim_run_spec_t *runs;
    attitude_run_t run[SIM_MAX_CONTROLLERS];
    int n;                     /* runs in the group */
    int n_flying;              /* of them, flying */
    instants_t at;             /* the control instants' references and disturbances */
    disturbance_batch_t batch; /* the disturbances of a plant step */
} group_t;

/* Opens every run (those beyond SIM_MAX_CONTROLLERS fail). */
static void group_open(group_t *g, const sim_scenario_t *sc, sim_run_spec_t *runs, int n_runs)
{
    g->sc = sc;
    g->runs = runs;
    g->n_flying = 0;
    for (int k = 0; k < n_runs && k < SIM_MAX_CONTROLLERS; ++k) {
        runs[k].rc = run_open(sc, &g->run[k], &runs[k]);
        g->n_flying += runs[k].rc == 0;
    }
    for (int k = SIM_MAX_CONTROLLERS; k < n_runs; ++k) {
        snprintf(runs[k].err, runs[k].err_len, "%s: more than %d runs in one group", sc->path, SIM_MAX_CONTROLLERS);
        runs[k].rc = -1;
    }
    g->n = n_runs < SIM_MAX_CONTROLLERS ? n_runs : SIM_MAX_CONTROLLERS;
    disturbance_batch_init(&g->batch, sc);
    g->at.first = g->at.n = 0;
}

/* Every flying run's controller at tick k of n_ticks, its rotors' command
 * into w2_cmd; returns the first run still flying (its plant leads the
 * step), NULL when none is. */
static const sim_plant_t *group_control(group_t *g, long k, long n_ticks, double w2_cmd[][4])
{
    if (k - g->at.first >= g->at.n) {
        instants_fill(&g->at, g->sc, k, n_ticks);
    }
    const int j = (int)(k - g->at.first);
    const double t = g->at.t_s[j];
    /* the references rounded to ladrc_real_t where they are worked out, in
     * instants_fill: GCC 12 turns a float rounding and the widening back,
     * side by side in one loop and vectorized, into no rounding at all */
    ladrc_real_t ref[3];
    double ref_rad[3], dist[3];
    for (int i = 0; i < 3; ++i) {
        ref[i] = g->at.ref[i][j];
        dist[i] = g->at.dist[i][j];
    }
    widen(ref, ref_rad);
    const sim_plant_t *lead = NULL; /* the plants' times are the same bits */
    for (int q = 0; q < g->n; ++q) {
        attitude_run_t *r = &g->run[q];
        if (r->flying && !run_tick(g->sc, r, t, ref, ref_rad, dist, w2_cmd[q])) {
            r->flying = 0; /* diverged: it stops here */
            --g->n_flying;
        }
        if (r->flying && lead == NULL) {
            lead = &r->plant;
        }
    }
    return lead;
}

/* The flying runs' plants through one control period, side by side, the
 * step's disturbances read from one batch: they are all at the lead's time
 * (they have flown every step together), but should one not be, every
 * plant asks for its own. */
static void group_step_plants(group_t *g, const sim_plant_t *lead, const double w2_cmd[][4])
{
    const sim_scenario_t *sc = g->sc;
    const double dt = sc->control_dt_s;
    disturbance_batch_fill(&g->batch, lead, dt, sc->plant_substeps);
    sim_plant_t *plants[SIM_MAX_CONTROLLERS];
    double cmds[SIM_MAX_CONTROLLERS][4];
    int n_plants = 0;
    for (int q = 0; q < g->n; ++q) {
        if (g->run[q].flying) {
            plants[n_plants] = &g->run[q].plant;
            memcpy(cmds[n_plants++], w2_cmd[q], sizeof cmds[0]);
        }
    }
    int same_time = 1;
    for (int q = 1; q < n_plants; ++q) {
        same_time = same_time && memcmp(&plants[q]->t_s, &lead->t_s, sizeof lead->t_s) == 0;
    }
    if (g->batch.n > 0 && same_time) {
        (void)sim_plant_step_group_table(plants, (const double(*)[4])cmds, n_plants, dt, sc->plant_substeps,
                                         (const double(*)[3])g->batch.stage);
    } else {
        batch_reader_t reader = {&g->batch, 0};
        sim_plant_step_group(plants, (const double(*)[4])cmds, n_plants, dt, sc->plant_substeps, disturbance, &reader);
    }
}

/* The state the last step left, at t = duration (n_ticks periods), checked
 * for divergence like every tick's. */
static void group_check_end(group_t *g, long n_ticks)
{
    const sim_scenario_t *sc = g->sc;
    const double t = (double)n_ticks * sc->control_dt_s;
    sim_expr_memo_t memo;
    sim_expr_memo_clear(&memo);
    ladrc_real_t ref[3];
    double ref_rad[3];
    references(sc, t, &memo, ref);
    widen(ref, ref_rad);
    for (int q = 0; q < g->n; ++q) {
        if (g->run[q].flying) {
            (void)diverged(sc, &g->run[q].plant, ref_rad, g->run[q].wrap_yaw, t, g->runs[q].metrics);
        }
    }
}

/* Closes every run that started; each gets the group's wall time. */
static void group_close(group_t *g, double wall_s)
{
    for (int q = 0; q < g->n; ++q) {
        if (g->runs[q].rc == 0) {
            g->runs[q].metrics->wall_s = wall_s;
            g->runs[q].rc = run_close(g->sc, &g->run[q]);
        }
    }
}

void sim_run_attitude_group(const sim_scenario_t *sc, sim_run_spec_t *runs, int n_runs, const sim_progress_t *progress)
{
    group_t g;
    group_open(&g, sc, runs, n_runs);
    const double start = wall_now_s();
    const long n = sim_run_ticks(sc);
    long k = 0;
    for (; k < n && g.n_flying > 0; ++k) {
        double w2_cmd[SIM_MAX_CONTROLLERS][4];
        const sim_plant_t *lead = group_control(&g, k, n, w2_cmd);
        if (lead == NULL) {
            break;
        }
        group_step_plants(&g, lead, (const double(*)[4])w2_cmd);
        if (progress != NULL && progress->ticks_done != NULL && (k & 1023) == 1023) {
            *progress->ticks_done += 1024L * g.n_flying;
        }
    }
    if (k == n) {
        group_check_end(&g, n);
    }
    group_close(&g, wall_now_s() - start);
}

int sim_run_attitude(const sim_scenario_t *sc, sim_controller_id_t ctrl, const char *csv_path,
                     const sim_progress_t *progress, sim_metrics_t *m, char *err, size_t err_len)
{
    sim_run_spec_t spec = {ctrl, csv_path, m, err, err_len, 0};
    sim_run_attitude_group(sc, &spec, 1, progress);
    return spec.rc;
}

int sim_run_differentiator(const sim_scenario_t *sc, const char *csv_path, const sim_progress_t *progress,
                           sim_diff_metrics_t *m, char *err, size_t err_len)
{
    memset(m, 0, sizeof *m);
    ladrc_levant_config_t lcfg;
    ladrc_td_config_t tcfg;
    sim_setup_differentiators(sc, &lcfg, &tcfg);
    ladrc_levant_t lev;
    ladrc_td_t td;
    ladrc_status_t st = ladrc_levant_init(&lev, &lcfg);
    if (st == LADRC_OK) {
        st = ladrc_td_init(&td, &tcfg);
    }
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: differentiator: %s", sc->path, ladrc_status_str(st));
        return -1;
    }
    const double r0 = sim_signal_eval(&sc->diff_signal, 0.0);
    ladrc_levant_reset(&lev, (ladrc_real_t)r0);
    ladrc_td_reset(&td, (ladrc_real_t)r0);
    sim_rng_t rng;
    sim_rng_seed(&rng, sc->seed);
    FILE *csv = open_csv(csv_path, "t_s,r_noisy,dr_true,dr_levant,dr_td\n", err, err_len);
    if (csv_path != NULL && csv == NULL) {
        return -1;
    }
    csv_line_t line;
    line.len = 0;
    const double start = wall_now_s();
    const long n = sim_run_ticks(sc);
    const double noise_std = sqrt(sc->diff_noise_var);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * sc->control_dt_s;
        const double r = sim_signal_eval(&sc->diff_signal, t) + noise_std * sim_rng_gauss(&rng);
        const double dr = sim_signal_eval(&sc->diff_derivative, t);
        /* the TD's output belongs to the next instant (td.h), Levant's to this one */
        const double dr_next = sim_signal_eval(&sc->diff_derivative, t + sc->control_dt_s);
        ladrc_ref_t lev_out, td_out;
        ladrc_levant_step(&lev, (ladrc_real_t)r, &lev_out);
        ladrc_td_step(&td, (ladrc_real_t)r, &td_out);
        if (in_window(sc->error_window_s, t)) {
            sim_stat_add(&m->levant_error, (double)lev_out.dr - dr);
            sim_stat_add(&m->td_error, (double)td_out.dr - dr_next);
        }
        if (csv != NULL) { /* "%.4f,%.7g,%.7g,%.7g,%.7g\n" */
            line_f4(&line, t);
            line_g(&line, r, 7);
            line_g(&line, dr, 7);
            line_g(&line, (double)lev_out.dr, 7);
            line_g(&line, (double)td_out.dr, 7);
            line_end(&line, csv);
        }
        if (progress != NULL && progress->ticks_done != NULL && (k & 1023) == 1023) {
            *progress->ticks_done += 1024;
        }
    }
    m->wall_s = wall_now_s() - start;
    if (csv != NULL && fclose(csv) != 0) {
        snprintf(err, err_len, "%s: write failed", csv_path);
        return -1;
    }
    return 0;
}
