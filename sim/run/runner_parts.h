/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The runner's parts, internal to it (runner.h is the interface):
 *   runner.c          the lockstep group's steps and the attitude entry points;
 *   runner_run.c      one run of a group: set-up, a control tick, its
 *                     metrics and divergence, the close;
 *   runner_batches.c  references and disturbances worked out in batches;
 *   runner_csv.c      the time series: files and lines;
 *   runner_log.c      the run as flight logs ([run] log);
 *   runner_diff.c     the differentiator run.
 */
#ifndef LADRC_SIM_RUNNER_PARTS_H
#define LADRC_SIM_RUNNER_PARTS_H

#include <stddef.h>
#include <stdio.h>

#include "scenario/expr.h"
#include "ladrc/attitude.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/mixer.h"
#include "biquad.h"
#include "bridge/bf_link.h"
#include "bridge/bf_pilot.h"
#include "numfmt.h"
#include "plant/plant.h"
#include "runner.h"
#include "plant/sensor.h"
#include "plant/turbulence.h"
#include "plant/vibration.h"
#include "scenario/series.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

/* Metric windows hold (from, to], as signal windows do. */
static inline int in_window(const double w[2], double t)
{
    return t > w[0] && t <= w[1];
}

/* The monotonic clock, s (runs' wall times). */
double runner_wall_now_s(void);

/* ---- runner_batches.c -------------------------------------------------------- */

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

void runner_disturbance_batch_init(disturbance_batch_t *b, const sim_scenario_t *sc);

/* ---- runner_series.c ---------------------------------------------------------- */

/* The recorded series a group's runs fly (series.h): a disturbance on the
 * plant, angles added to the references, noises on the measured rate and angle. */
typedef struct {
    int has_dist, has_ref, has_rate, has_angle;
    sim_series_t dist;  /* rad/s^2 */
    sim_series_t ref;   /* rad */
    sim_series_t rate;  /* rad/s */
    sim_series_t angle; /* rad */
} recorded_t;

/* Reads sc's series files; 0, or -1 with "file:line:column: message" in err
 * and nothing held. */
int runner_recorded_open(recorded_t *r, const sim_scenario_t *sc, char *err, size_t err_len);
void runner_recorded_close(recorded_t *r);

/* v += the series' first three columns at t_s (the missing ones 0). */
void runner_recorded_add(const sim_series_t *s, sim_series_cursor_t *cursor, double t_s, double v[3]);

/* ---- runner_wind.c ------------------------------------------------------------ */

/* The air a group's vehicles meet ([wind]). */
typedef struct {
    int on;          /* 0: still air */
    int gusts;       /* 1: Dryden turbulence on top of the mean */
    double mean_m_s; /* steady wind speed */
    double along[2]; /* north, east of the direction it blows to */
    sim_turb_t turb; /* the gusts: along, across, down the mean wind */
} wind_field_t;

/* Sets the wind up from sc; 0, or -1 when the turbulence refuses its settings. */
int runner_wind_open(wind_field_t *w, const sim_scenario_t *sc);

/* The air's velocity over the ground (m/s, north-east-down) at t_s[0..n),
 * non-decreasing, into wind_m_s. */
void runner_wind_at(wind_field_t *w, const double *t_s, int n, double (*wind_m_s)[3]);

/* The disturbances of p's next step of dt_s in substeps (sim_plant_stage_times). */
void runner_disturbance_batch_fill(disturbance_batch_t *b, const sim_plant_t *p, double dt_s, int substeps);

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

/* The rows from tick `first` on, at most up to tick n_ticks - 1. */
void runner_instants_fill(instants_t *b, const sim_scenario_t *sc, long first, long n_ticks);

/* One plant's reading of a batch: the stage time it asks for next. Runs in
 * lockstep share the batch (their plants' times are the same bits). */
typedef struct {
    const disturbance_batch_t *b;
    int next;
} batch_reader_t;

/* The plant's disturbance callback (ctx a batch_reader_t): the batch's
 * value at the stage time it lists next, else the disturbances evaluated at t_s. */
void runner_read_batch(double t_s, void *ctx, double d_out[3]);

/* The references at t, rad, as the controllers get them (ladrc_real_t). */
void runner_references(const sim_scenario_t *sc, double t_s, sim_expr_memo_t *memo, ladrc_real_t ref[3]);

/* ---- runner_csv.c ------------------------------------------------------------ */

/* A new time series at path with its header line (path NULL: none, NULL
 * returned); NULL with the message in err when it cannot be written. */
FILE *runner_open_csv(const char *path, const char *header, char *err, size_t err_len);

/* The same with a stdio buffer of buffer_bytes. */
FILE *runner_open_csv_buffered(const char *path, const char *header, size_t buffer_bytes, char *err, size_t err_len);

/* Most fields of a line: the attitude run's 51 and its estimators' (per
 * axis: HP's weight, tones, estimate, LP's estimate, and each tone's
 * frequency and amplitude). */
#define RUNNER_CSV_FIELDS_MAX (51 + 3 * (4 + 2 * LADRC_HP_MAX_TONES))

/* One CSV line in memory, written with one fwrite. */
typedef struct {
    char text[RUNNER_CSV_FIELDS_MAX * SIM_NUMFMT_MAX];
    int len;
} csv_line_t;

/* x as %.4f; then ",x" as %.{precision}g (numfmt.h); then the line's end, written to f. */
void runner_line_f4(csv_line_t *l, double x);
void runner_line_g(csv_line_t *l, double x, int precision);
void runner_line_end(csv_line_t *l, FILE *f);

/* ---- runner_log.c ------------------------------------------------------------ */

/* The files of a run's flight logs: betaflight, generic, then the PX4
 * topics a px4 log writes, one file each. */
#define RUNNER_PX4_TOPICS (SIM_RUN_LOG_FILES - 2)
#define RUNNER_LOG_FILES SIM_RUN_LOG_FILES /* Betaflight, generic and one per PX4 topic */

/* A run's flight logs ([run] log, docs/csv-format.md): each form asked for,
 * in files named after the run's time series (its path without ".csv"),
 * one line per control tick once the controller has acted. */
typedef struct {
    int forms;                    /* SIM_RUN_LOG_* bits of the files open; 0: none */
    FILE *file[RUNNER_LOG_FILES]; /* NULL: a form not asked for */
    char stem[SIM_PATH_LEN + 64]; /* the time series' path without ".csv" */
    long ticks;                   /* lines written */
    double last_ref_rad[3];       /* the reference of the tick before (rad) */
    double authority_Nm[3];       /* a normalised command of 1 (sim_setup_authority_Nm) */
    double full_w2_rad2_s2;       /* a rotor at full command (sim_setup_full_w2_rad2_s2) */
    double full_thrust_N;         /* the four of them */
} flight_log_t;

struct runner_tick; /* tick_t, below */

/* Opens the forms sc->log_forms asks for beside the time series at
 * csv_path (NULL: no time series, and no flight log either); 0, or -1 with
 * the message naming the file in err and nothing open. */
int runner_log_open(flight_log_t *log, const sim_scenario_t *sc, const char *csv_path, char *err, size_t err_len);

/* The tick's line of every open form: tk as runner_run_tick saw it, the
 * plant at the tick (its rotors' speeds), the rotors' command w2_cmd. */
void runner_log_tick(flight_log_t *log, const sim_scenario_t *sc, const sim_plant_t *plant,
                     const struct runner_tick *tk, const double w2_cmd[4]);

/* Closes every open form; 0, or -1 with "FILE: write failed" for the first
 * that failed. */
int runner_log_close(flight_log_t *log, char *err, size_t err_len);

/* ---- runner_run.c ------------------------------------------------------------ */

/* What one control tick of a run saw and did, for its metrics, time series
 * and flight logs. */
typedef struct runner_tick {
    double t;                           /* s */
    const ladrc_real_t *ref;            /* rad, as the controller got them */
    const double *ref_rad, *dist;       /* the same widened; disturbances, rad/s^2 */
    double meas_angle[3], meas_rate[3]; /* the sensor's, vibration included */
    double ctrl_rate[3];                /* the rate the controller got: filtered when [filter] is on */
    double ctrl_angle[3];               /* the angles it got (quaternion frame: the ZYX angles of ctrl_quat) */
    double ctrl_quat[4];                /* quaternion frame: the attitude it got (w x y z); else unset */
    double accel_m_s2[3];               /* the accelerometer: specific force in body axes */
    ladrc_real_t torque[3];             /* commanded by the controller, N m ([excitation]'s chirp is added after) */
    ladrc_real_t thrust_N;              /* the thrust asked of the mixer */
    ladrc_mixer_output_t out;
    /* the truth at this tick: the disturbance the observer should see is
     * the plant's acceleration minus what the applied torque explains */
    double applied[3], f_true[3], f_est[3], err_rad[3], z1[3], z2[3];
} tick_t;

/* One run of a lockstep group: what it keeps from tick to tick. */
typedef struct {
    sim_run_spec_t *spec;
    ladrc_attitude_t att;
    ladrc_mixer_t mixer;
    sim_plant_t plant;
    sim_sensor_t sensor;
    sim_vibration_t vibration;
    ladrc_gyro_filter_t filter;
    int filtered;                            /* 1: the gyro filter stage is on */
    const recorded_t *rec;                   /* the group's series; NULL: none */
    sim_series_cursor_t rate_cur, angle_cur; /* this run's places in them */
    FILE *csv;
    csv_line_t line;
    flight_log_t log;
    int excited;              /* 1: [excitation] adds its chirp to the torque */
    double authority_Nm[3];   /* the chirp's unit on each axis (sim_setup_authority_Nm) */
    ladrc_real_t asked_Nm[3]; /* excited: the torque asked of the mixer this tick */
    double last_out_s[3];
    int out_at_last[3]; /* outside the band at the settle window's latest sample so far */
    int wrap_yaw;
    int flying;               /* 1 until it diverges */
    int cmd_hp_on;            /* 1: the command noise's high-pass exists (its corner below Nyquist) */
    biquad_coef_t cmd_hp;     /* the command noise's high-pass (metrics.h cmd_noise_Nm) */
    biquad_t cmd_hp_state[3]; /* its state on each axis */
    /* [phases]: the next event of the timeline, and where the vehicle is */
    int next_event;
    int armed, on_ground;
    double ground_angle_rad[3]; /* the attitude the ground holds it at */
    struct runner_bf *bf;       /* BETAFLIGHT: its SITL (runner_bf.c); NULL for the library's controllers */
    int piloted;                /* 1: RATE-ADRC flown by Betaflight's acro pilot (runner_pilot.c) */
    int pilot_pulse;            /* 1: its demand quantized to the RC pulse */
    bf_pilot_t pilot;           /* piloted: the pilot */
    int failed;                 /* 1: stopped by a failure, its message in the spec (not a divergence) */
} attitude_run_t;

/* The tracking error of every axis (rad): ref - angle per axis in the Euler
 * frame (yaw wrapped when wrap_yaw), the body-axis rotation vector from the
 * attitude to the reference's (ZYX) in the quaternion frame. */
void runner_attitude_error_rad(const sim_scenario_t *sc, const sim_plant_t *p, const double ref_rad[3], int wrap_yaw,
                               double error_rad[3]);

/* The thrust asked of the mixer (N) at t_s for the measured tilt (angle[0..1], rad). */
ladrc_real_t runner_thrust_N(const sim_scenario_t *sc, const attitude_run_t *r, const ladrc_real_t angle[3],
                             double t_s);

/* The w^2 (rad^2/s^2) a rotor gives at the ESC command c in [0, 1]: c w2_max,
 * or through [rotors] thrust_curve k, w2_max ((1 - k) c + k c^2). */
double runner_command_w2(const sim_scenario_t *sc, double c);

/* ---- runner_pilot.c ----------------------------------------------------------- */

/* A piloted controller's configuration (sim_setup_piloted): its axes in
 * acro, in the Euler frame (the pilot gives body rates); others unchanged. */
void runner_pilot_configure(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg);

/* The pilot's configuration from a controller's keys (rate_max_deg_s,
 * angle_limit_deg, pilot_att_kp_per_s, their defaults where not given): the
 * BETAFLIGHT run's and a piloted RATE-ADRC's alike. */
void runner_pilot_config(const sim_scenario_t *sc, const sim_overrides_t *o, bf_mode_t mode, bf_pilot_config_t *pc);

/* Sets r's pilot up when controller id is flown by one (sim_setup_piloted). */
void runner_pilot_open(const sim_scenario_t *sc, sim_controller_id_t id, attitude_run_t *r);

/* The rate setpoints (rad/s) the pilot asks of the rate loop at tk: its
 * demand for tk's references and the vehicle's attitude, as the SITL would
 * read it off the sticks; the pilot moves on to tk. */
void runner_pilot_rates(const sim_scenario_t *sc, attitude_run_t *r, const struct runner_tick *tk,
                        ladrc_real_t rate_sp[3]);

/* ---- runner_bf.c -------------------------------------------------------------- */

/* A BETAFLIGHT run's SITL, its pilot, and the SITL's time at t = 0. */
typedef struct runner_bf {
    bf_link_t link;
    bf_pilot_t pilot;
    double t0_s;
    float motor[BF_MOTORS];
    long rc_every;        /* an RC frame with every rc_every-th state packet */
    long k0;              /* the exchange of t = 0 */
    double throttle;      /* the pilot's throttle stick, [0, 1] */
    double last_thrust_N; /* what the last motor outputs gave; NaN: none yet in the air */
} runner_bf_t;

/* Starts the SITL of sc->betaflight_sitl, warms it up and arms it when the
 * run starts armed (r->plant, r->armed set); 0, or -1 with the message. */
int runner_bf_open(const sim_scenario_t *sc, attitude_run_t *r, char *err, size_t err_len);

/* One tick's exchange: 1 with the rotors' command and tk's torque, thrust
 * and mixer output as the motor outputs give them; -1 with the message in
 * the run's spec. */
int runner_bf_control(const sim_scenario_t *sc, attitude_run_t *r, tick_t *tk, double w2_cmd[4]);

/* Stops the SITL; safe on any run. */
void runner_bf_close(attitude_run_t *r);

/* Sets a run up; 0, or -1 with the message in its spec (then it does not fly). */
int runner_run_open(const sim_scenario_t *sc, attitude_run_t *r, sim_run_spec_t *spec);

/* The controller's part of a tick at t: measure, check, control, record.
 * ref and dist are the references and disturbances at t. Returns 0 when the
 * run diverged (nothing of this instant or later is recorded), else 1 with
 * the rotors' command in w2_cmd. */
int runner_run_tick(const sim_scenario_t *sc, attitude_run_t *r, double t, const ladrc_real_t ref[3],
                    const double ref_rad[3], const double dist[3], double w2_cmd[4]);

/* Divergence at t (runner.h): the plant's state non-finite, or the tracking
 * error ref - angle beyond the scenario's limit on an axis while the
 * controller att (NULL: not asked) is as far from its own shaped reference;
 * beyond the limit but near its shaped reference, the reference outran the
 * shaper: recorded in m (reference_outran_*), the run goes on. Records the
 * first cause of a divergence in m and returns 1; 0 while the run is
 * healthy. */
int runner_diverged(const sim_scenario_t *sc, const sim_plant_t *p, const double ref_rad[3], int wrap_yaw, double t_s,
                    const ladrc_attitude_t *att, sim_metrics_t *m);

/* Settling times and the time series' end; 0, or -1 with the message. */
int runner_run_close(const sim_scenario_t *sc, attitude_run_t *r);

/* The header line of an attitude run's time series into out (len bytes,
 * RUNNER_CSV_HEADER_MAX do: no name and its comma is longer than 32), and
 * the tick's line of it (runner_csv.c): the text of %.4f, %.6g and %.7g
 * (numfmt.h). */
#define RUNNER_CSV_HEADER_MAX (32 * RUNNER_CSV_FIELDS_MAX)
void runner_attitude_csv_header(char *out, size_t len);
void runner_csv_line(attitude_run_t *r, const tick_t *tk);

#endif
