/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * From a log to a scenario: the airframe identified from a flight log
 * (ident.h) and its gyro's noise, written as a scenario file ladrc_sil
 * flies and ladrc_margins analyses (docs/flight-logs.md).
 *
 * The log gives each axis's b0 per unit of normalised command, not an
 * inertia: the scenario takes a nominal vehicle (1 kg, 0.1 m arm, thrust to
 * weight 2) whose torque authority (sim_setup_authority_Nm) is what a
 * command of 1 means, and the inertia J = authority / b0 on roll and pitch;
 * yaw's inertia is SIM_AIRFRAME_YAW_INERTIA_SHARE of their sum (at least their
 * difference: a rigid body) and its torque
 * coefficient is set to give yaw's b0: the plant's b0 is the log's on every
 * axis. Rate damping: the median over the axes
 * of a J. Motor lag: the median of the axes'. Delay: the median in ticks.
 * Gyro noise: its white floor as rate_noise_std, or, with a noise series,
 * the log's own noise (vibration lines included) replayed from that file.
 */
#ifndef LADRC_SIM_AIRFRAME_H
#define LADRC_SIM_AIRFRAME_H

#include <stdio.h>

#include "gyro_filter.h"
#include "ident.h"
#include "ladrc/gyro_filter.h"
#include "log_outlier.h"
#include "scenario/scenario.h"
#include "run/spectrum.h"

/* The nominal vehicle of an identified airframe. */
#define SIM_AIRFRAME_MASS_KG 1.0
#define SIM_AIRFRAME_ARM_M 0.1
#define SIM_AIRFRAME_THRUST_COEFF_N_S2 1e-5
/* Yaw's inertia: this share of Jx + Jy (a rigid body's Jz is at most their
 * sum; quadrotors' is 1.6-2 Jx); its torque coefficient then gives yaw's b0. */
#define SIM_AIRFRAME_YAW_INERTIA_SHARE 0.9
#define SIM_AIRFRAME_G_M_S2 9.81

typedef struct {
    double dt_s;
    double prefilter_hz; /* the identification's low-pass corner */
    sim_ident_axis_t axis[3];
    double noise_floor_rad_s_rthz[3]; /* the gyro's white floor (sqrt of its PSD) */
    int n_lines[3];
    sim_spectrum_line_t lines[3][SIM_SPECTRUM_MAX_LINES];
    int has_gyro_filter; /* the log held the gyro before and after its filters */
    sim_gyro_filter_axis_t gyro_filter[3];
    sim_log_outliers_t outliers; /* the samples replaced as outliers before the identification (log_outlier.h) */
    /* Set by the caller after the identification (zero: none): the gyro filter stage to fly
     * ([filter]), and the logged controller's command noise above 20 Hz per axis (normalised
     * command), the LADRC family's per-axis cap in N m (sim_airframe_torque_per_command_Nm). */
    int has_filter;
    ladrc_gyro_filter_config_t filter;
    double log_cmd_noise[3];
} sim_airframe_t;

/* The band of the gyro's spectrum its floor is taken over (Hz), at sample rate fs. */
void sim_airframe_floor_band(double fs_hz, double *lo_hz, double *hi_hz);

/* The inertia (kg m^2) the scenario gives roll (0) or pitch (1) for b0: the
 * axis's authority over b0 (NaN when b0 is not > 0). */
double sim_airframe_inertia(int axis, double b0);

/* The yaw torque coefficient (N m s^2) that makes yaw's authority over
 * inertia_yaw equal b0_yaw. */
double sim_airframe_yaw_coeff(double b0_yaw, double inertia_yaw);

/* Where the b0 the scenario gives an axis comes from. */
typedef enum {
    SIM_AIRFRAME_B0_IDENTIFIED = 0, /* the log's, told (sim_ident_b0_told) */
    SIM_AIRFRAME_B0_INTERVAL_HI,    /* not told: its interval's upper end, the side a tuning is gentle on */
    SIM_AIRFRAME_B0_OTHER_AXIS,     /* roll's for pitch or pitch's for roll: alike on a multirotor */
    SIM_AIRFRAME_B0_DEFAULT         /* the library's default airframe's (sim_vehicle_paper) */
} sim_airframe_b0_source_t;

/* The b0 (rad/s^2 per unit of command) the scenario gives axis `axis`: the
 * identified one when the log tells it; else its interval's upper end when
 * that is positive (the larger b0, the lower the gains: flown on the smaller
 * true b0 the loop loses gain, not margin); else (negative: the command's
 * sign does not match the gyro's) the other of roll and pitch by the same
 * rule, else the library's default airframe's. */
double sim_airframe_b0(const sim_airframe_t *a, int axis, sim_airframe_b0_source_t *source);

/* 1 and a sentence in buf saying why axis's b0 is not the log's and what the
 * scenario takes instead; 0 and "" when it is the log's. */
int sim_airframe_b0_note(const sim_airframe_t *a, int axis, char *buf, size_t len);

/* The controllers the scenario does not list: they do not start on the
 * airframe (a rate their defaults refuse), each with the reason. */
typedef struct {
    int n;
    sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
    char reason[SIM_MAX_CONTROLLERS][256];
} sim_airframe_refused_t;

/* The torque (N m) a command of 1 means on axis i of the scenario: the
 * axis's inertia times its b0 (the b0 sim_airframe_b0 gives it). */
double sim_airframe_torque_per_command_Nm(const sim_airframe_t *a, int axis);

/* Writes the scenario to f: `source` names the log in its comment (a file
 * name, no folders), `noise_series` the noise file next to it (NULL: none).
 * It lists HP-MLADRC, LP-MLADRC, LADRC, RATE-ADRC, CASCADED and INDI, each
 * tune = margins, less those that do not start at the log's rate (into
 * *refused when not NULL, and named in the file's comments). An axis whose
 * b0 is not told takes sim_airframe_b0's (said in the comments), the lag
 * and delay the median of the axes that tell them. Returns 0, or -1 (the
 * message in why) when the control period is outside a scenario's range
 * or no controller starts. */
int sim_airframe_write(FILE *f, const sim_airframe_t *a, const char *source, const char *noise_series,
                       sim_airframe_refused_t *refused, char *why, size_t why_len);

#endif
