/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Replay: controllers run open loop on a flight log's recorded streams.
 * Each tick every controller is given the log's reference, attitude and
 * gyro (sim_log_sample_t) and steps as it would in flight; then it is told
 * the log's own command as the torque that acted (ladrc_attitude_set_applied),
 * so that its observer follows the flight that happened, not one its own
 * commands would have made. What each would have commanded, its faults and
 * its disturbance estimate are the replay's output; the log's own command is
 * the comparison.
 *
 * The controllers are configured as a scenario configures them (its airframe,
 * its tuning) and fly its frame (Euler or quaternion); the log's normalised
 * command c is the torque c * sim_setup_authority_Nm, and the replay's
 * commands are normalised the same way. The scenario's gyro filter stage
 * ([filter]), when it has one, runs as in flight on the gyro the airframe's
 * noise was measured on: the log's gyro before its filters when it has one,
 * else its gyro (filtered by the log's stack already: the stage then comes
 * on top, as flying that scenario on that gyro would); the RPM notches on
 * the log's rotor speeds, else the scenario's hover speed; the angles are
 * not filtered. The log's setpoint reaches every controller smoothed as a
 * flight stack smooths its radio link's steps (setpoint_smooth.h). Not replayed: flight phases and the gain schedule.
 *
 * After a gap the reader skipped (log.h: after_gap) every controller engages
 * again, bumpless, on the log's attitude with the log's command acting (as a
 * hand-over in flight: ladrc_attitude_engage), the setpoint's smoothing and
 * the gyro filter stage restart on the log's values, and no spectrum's
 * segment spans the gap; the summary's statistics go on over both sides.
 */
#ifndef LADRC_SIM_REPLAY_H
#define LADRC_SIM_REPLAY_H

#include <stddef.h>

#include "ladrc/attitude.h"
#include "ladrc/gyro_filter.h"
#include "log.h"
#include "scenario/scenario.h"
#include "setpoint_smooth.h"
#include "run/spectrum.h"

/* The frequency bands the command's noise is told in (Hz): [0, 20), [20, 100), [100, Nyquist]. */
#define SIM_REPLAY_BANDS 3
extern const double SIM_REPLAY_BAND_EDGES_HZ[SIM_REPLAY_BANDS + 1];

/* Running mean and spread. */
typedef struct {
    long long n;
    double mean, m2;
} sim_replay_stat_t;

/* One stream of commands (a controller's, or the log's) on one axis. */
typedef struct {
    sim_replay_stat_t command;    /* normalised */
    sim_replay_stat_t difference; /* this command - the log's */
    sim_replay_stat_t estimate;   /* the disturbance estimate, rad/s^2 (controllers with one) */
    sim_spectrum_t spectrum;      /* of the command */
} sim_replay_axis_t;

typedef struct {
    int n; /* controllers */
    sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
    ladrc_attitude_t att[SIM_MAX_CONTROLLERS];
    int wrap_yaw[SIM_MAX_CONTROLLERS];
    int has_estimate[SIM_MAX_CONTROLLERS];
    long long fault_ticks[SIM_MAX_CONTROLLERS];     /* ticks with any fault flag */
    ladrc_fault_t faults_seen[SIM_MAX_CONTROLLERS]; /* every flag raised */
    sim_replay_axis_t axis[SIM_MAX_CONTROLLERS][3];
    sim_replay_axis_t log_axis[3]; /* the log's own command */
    sim_spectrum_t gyro[3], gyro_raw[3];
    int quat_frame;
    double authority_Nm[3];
    int filter_on;                /* the scenario's gyro filter stage, run on the rates */
    ladrc_gyro_filter_t filter;   /* at rest on 0 at the start, as in flight */
    double filter_hover_rotor_hz; /* its RPM notches' speed when the log has none (Hz) */
    setpoint_smooth_t setpoint;   /* the log's setpoint as a stack smooths it, the same for every controller */
    long long ticks;
    long long gap_restarts; /* restarts after gaps the reader skipped */
} sim_replay_t;

/* What one tick gave (normalised commands, estimates in rad/s^2). */
typedef struct {
    double command[SIM_MAX_CONTROLLERS][3];
    double estimate[SIM_MAX_CONTROLLERS][3];
    ladrc_fault_t faults[SIM_MAX_CONTROLLERS];
} sim_replay_tick_t;

/* Configures the scenario's controllers ids[0..n-1] (tuned already where it
 * tunes them) for a log at sc's control period. Returns 0, or -1 with the
 * message (a controller that refuses its configuration). r is large: heap
 * or static. */
int sim_replay_init(sim_replay_t *r, const sim_scenario_t *sc, const sim_controller_id_t *ids, int n, char *err,
                    size_t err_len);

/* One tick of the log (its fields as sim_log_has gives them). */
void sim_replay_step(sim_replay_t *r, const sim_log_sample_t *s, unsigned has, sim_replay_tick_t *out);

double sim_replay_stat_std(const sim_replay_stat_t *s);
double sim_replay_stat_rms(const sim_replay_stat_t *s);

#endif
