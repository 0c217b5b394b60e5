/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Scenario files: a small INI-like text format (documented in
 * docs/scenario-format.md) describing one simulation: vehicle, run length and
 * steps, references and disturbances as expressions of t over time windows,
 * sensors, rotor limits, controllers to compare and metric windows. Angles are
 * degrees in files and radians here; everything else is SI.
 */
#ifndef LADRC_SIM_SCENARIO_H
#define LADRC_SIM_SCENARIO_H

#include <stddef.h>
#include <stdint.h>

#include "ladrc/axis.h"
#include "signals.h"

#define SIM_MAX_CONTROLLERS 8
#define SIM_NAME_LEN 64
#define SIM_PATH_LEN 512

/* Limits of a run (docs/scenario-format.md, "Limits"): the parser refuses
 * a scenario outside them, at the key responsible. */
#define SIM_CONTROL_DT_MIN_S 1e-5    /* control period: 100 kHz ... */
#define SIM_CONTROL_DT_MAX_S 0.1     /* ... to 10 Hz */
#define SIM_PLANT_SUBSTEPS_MAX 1000  /* plant RK4 steps per control period */
#define SIM_DURATION_MAX_S 1e5       /* run length: 27.8 h */
#define SIM_RUN_TICKS_MAX 100000000L /* control periods per run: 1e8 */
#define SIM_RUN_PLANT_STEPS_MAX 1e9  /* plant RK4 steps per run */
/* and the plant step control_dt_s / plant_substeps at most the plant's
 * shortest time constant: motor_tau_s (when > 0) and each J / kt (when kt > 0) */

typedef enum { SIM_KIND_ATTITUDE = 0, SIM_KIND_DIFFERENTIATOR = 1 } sim_kind_t;

/* [excitation] axis: one axis, or all three one chirp after another. */
typedef enum { SIM_EXCITE_ROLL = 0, SIM_EXCITE_PITCH = 1, SIM_EXCITE_YAW = 2, SIM_EXCITE_ALL = 3 } sim_excite_axis_t;

/* [run] log: the flight-log forms a run writes beside its time series, as bits. */
enum { SIM_RUN_LOG_BETAFLIGHT = 1 << 0, SIM_RUN_LOG_PX4 = 1 << 1, SIM_RUN_LOG_GENERIC = 1 << 2 };

/* The events of [phases], in the timeline sim_scenario_t holds. */
typedef enum { SIM_EVENT_ARM = 0, SIM_EVENT_TAKEOFF = 1, SIM_EVENT_LAND = 2, SIM_EVENT_DISARM = 3 } sim_event_t;

typedef enum {
    SIM_CTRL_HP_MLADRC = 0,
    SIM_CTRL_LP_MLADRC,
    SIM_CTRL_LADRC,
    SIM_CTRL_PID,
    SIM_CTRL_CASCADED = 4,
    SIM_CTRL_INDI = 5,
    SIM_CTRL_RATE_ADRC = 6,
    SIM_CTRL_BETAFLIGHT = 7, /* Betaflight's own firmware (its SITL build) over UDP (docs/betaflight.md) */
    SIM_CTRL_COUNT = 8,
    SIM_CTRL_LIBRARY_COUNT = 7 /* the library's controllers: the ids below it */
} sim_controller_id_t;

/* [controller NAME] tune: how the controller's gains are chosen. */
typedef enum { SIM_TUNE_NONE = 0, SIM_TUNE_MARGINS = 1 } sim_tune_t;

/* Targets of tune = margins when the file gives none. */
#define SIM_TUNE_PM_DEG_DEFAULT 45.0
#define SIM_TUNE_GM_DB_DEFAULT 6.0

/* The controllers a scenario flies unless it names them: the first four
 * (the paper's), so that the outputs of files without a list stay as they
 * were (a scenario lists the baselines to fly them). */
#define SIM_CTRL_DEFAULT_COUNT 4
/* rotor_height_m when not given, in arms: hubs some 4 cm above the centre
 * of mass on the paper's 0.165 m arm */
#define SIM_ROTOR_HEIGHT_ARMS 0.25

/* Optional per-controller overrides; NaN (or -1 for enums) = library default. */
typedef struct {
    double wc_rad_s, wo_rad_s;
    int leso_method;                             /* -1, or ladrc_leso_method_t */
    int hp_freq_mode;                            /* -1, or ladrc_hp_freq_mode_t */
    int hp_sample;                               /* -1, or ladrc_hp_sample_t */
    double hp_freq_rad_s;                        /* known frequency or first guess of the first tone */
    double hp_freq2_rad_s;                       /* the same for the second tone */
    double hp_freq_min_rad_s, hp_freq_max_rad_s; /* ONLINE search range */
    int hp_tones;                                /* -1, or the number of tones (1..LADRC_HP_MAX_TONES) */
    double levant_lipschitz_rad_s4;
    double td_accel_rad_s2;
    double pid_kp, pid_ki, pid_kd;
    double indi_att_kp_per_s, indi_rate_kp_per_s, indi_filter_rad_s;
    double radrc_kp_per_s, radrc_att_kp_per_s, radrc_rate_max_deg_s; /* RATE-ADRC; rate max in deg/s */
    double cas_att_kp, cas_rate_max_deg_s, cas_rate_kp, cas_rate_ki, cas_rate_kd, cas_d_filter_tau_s,
        cas_i_limit_Nm;                    /* CASCADED; cas_rate_max in deg/s as in the file */
    int coupling_feed;                     /* -1, 0 or 1 */
    int cas_setpoint_ff;                   /* -1 (the library's: yaw only), 0 or 1 on every axis */
    double cas_rate_ff, cas_i_relax_deg_s; /* CASCADED's rate feed-forward gain, integrator relax (deg/s) */
    int indi_adapt;                        /* -1 (no), 0 or 1: INDI adapts its effectiveness */
    double indi_adapt_mu;                  /* its LMS step */
    int gain_schedule;                     /* -1 (no), 0 or 1: b0 follows the thrust and the battery's voltage */
    double model_motor_tau_s;              /* NaN: [rotors] motor_tau_s; 0: no lag modelled (LADRC family) */
    int model_delay_ticks;                 /* -1: [sensors] delay_ticks (LADRC family) */
    int wrap_yaw;                          /* -1 (yes), 0 or 1: the controller's yaw wraps at +-180 deg */
    int tune;                              /* -1 (none) or sim_tune_t */
    int bf_mode;                           /* BETAFLIGHT: -1 (acro) or bf_mode_t */
    double bf_att_kp_per_s;                /* BETAFLIGHT: the pilot's angle loop in acro (NaN: default) */
    double bf_rate_max_deg_s;              /* BETAFLIGHT: full stick in acro, as the SITL's rates say */
    double bf_angle_limit_deg;             /* BETAFLIGHT: full stick in angle mode, the SITL's angle_limit */
    double bf_warmup_s;                    /* BETAFLIGHT: the SITL's time still and disarmed before arming */
    int bf_timeout_ms;                     /* BETAFLIGHT: -1 (default) or an exchange's timeout */
    double tune_pm_deg;                    /* tune = margins: phase margin target (deg); NaN: SIM_TUNE_PM_DEG_DEFAULT */
    double tune_gm_db;                     /* gain margin target (dB); NaN: SIM_TUNE_GM_DB_DEFAULT */
    double tune_step_rad;                  /* objective's reference step (rad); NaN: the analysis's default */
    double tune_dist_rad_s2;               /* its disturbance step (rad/s^2); NaN: the analysis's default */
    double tune_noise_max_Nm;              /* cap on the predicted command noise above 20 Hz (N m, margins.h
                                 cmd_noise_max_Nm); NaN: none */
    int tune_noise_ref;                    /* -1, or a sim_controller_id_t: the cap is that controller's tuned
                                 command noise on the same axis times tune_noise_ratio */
    double tune_noise_ratio;               /* > 0; default 1 */
    double tune_noise_axis_max_Nm[3];      /* per axis (roll, pitch, yaw) cap as tune_noise_max_Nm; NaN: none */
} sim_overrides_t;

/* Gains chosen by tune = margins (sim_tune_controller, tune.h) for each axis
 * (roll, pitch, yaw), and the margins ladrc_analysis computes for them on
 * the scenario's airframe as the controller models it. */
/* What tune = margins gave a controller (sim_tune_controller, tune.h): the
 * candidate that flew the check flight best, or none. */
typedef enum {
    SIM_TUNED_NONE = 0,  /* not tuned (tune = none, or not yet) */
    SIM_TUNED_MARGINS,   /* the tuner's gains */
    SIM_TUNED_DEFAULTS,  /* the library's default gains */
    SIM_TUNED_SCENARIO,  /* the gains the file gives */
    SIM_TUNED_UNTUNABLE, /* no candidate flew the check flight: not flown */
} sim_tuned_by_t;

/* The candidates of tune = margins, in sim_tuning_t.check_cost_deg's order. */
enum { SIM_CANDIDATE_MARGINS = 0, SIM_CANDIDATE_DEFAULTS = 1, SIM_CANDIDATE_SCENARIO = 2, SIM_N_CANDIDATES = 3 };

typedef struct {
    int tuned; /* 1: these gains replace the file's (sim_setup_attitude) */
    sim_tuned_by_t by;
    int targets_met;  /* 1: the gains flown meet the margin targets on every axis */
    char reason[512]; /* why the tuner's gains are not flown, or where they miss; "" if nothing to say */
    double check_cost_deg[SIM_N_CANDIDATES]; /* each candidate's check flight: the sum over the axes of the
                                                RMS error (deg); INFINITY: diverged; NaN: not a candidate */
    int candidate_met[SIM_N_CANDIDATES];     /* 1: that candidate meets the targets on every axis */
    double pm_target_deg, gm_target_db;
    ladrc_axis_config_t gains[3]; /* the tuned config of each axis: its variant's gain fields
                                     (sim_setup_gain_fields) are the tuned gains */
    double pm_deg[3], gm_db[3], gm_low_db[3], crossover_rad_s[3], ms[3];
    double step_cost_rad2_s[3]; /* the objective of the chosen gains (margins.h); NaN: steps off */
    double cmd_noise_Nm[3];     /* their predicted command noise above 20 Hz from [sensors]' noise (margins.h) */
    double cmd_noise_cap_Nm[3]; /* the cap it was held to; 0: none */
    int idle[3];                /* HP-MLADRC margins of its idle estimator (margins.h) */
    int shared[3];              /* 1: this axis took another's result (same airframe and controller) */
    double wall_s;              /* time the tuning took, the candidates included */
    double tuner_s;             /* of which the tuner and its own check flight (the tuning without candidates) */
} sim_tuning_t;

/* Where a parse failed, as file:line:column: message (line and column are
 * 1-based; both are 0 when the file could not be read at all). */
typedef struct {
    char path[SIM_PATH_LEN];
    int line;
    int column;
    char message[768];
    int first_set_line; /* > 0: lines from this one on are the command line's --set items
                            (line first_set_line + k is item k, column is into its text) */
} sim_parse_error_t;

typedef struct {
    char name[SIM_NAME_LEN]; /* from the file name without extension */
    char path[SIM_PATH_LEN];
    sim_kind_t kind; /* [run] kind = attitude | differentiator */

    /* [run] */
    double duration_s;
    double control_dt_s;
    int plant_substeps; /* plant RK4 steps per control step, >= 1 */
    uint64_t seed;
    char output_dir[SIM_PATH_LEN];      /* relative paths are relative to the current directory */
    char betaflight_sitl[SIM_PATH_LEN]; /* BETAFLIGHT: the SITL's folder (ladrc_sil --betaflight); "" none */
    int n_controllers;
    sim_controller_id_t controllers[SIM_MAX_CONTROLLERS];
    int log_forms; /* SIM_RUN_LOG_* bits; 0: no flight log */

    /* [vehicle] (the plant) */
    double mass_kg, inertia_kg_m2[3], arm_m, thrust_coeff_N_s2, yaw_coeff_Nm_s2, rot_drag_Nm_s, g_m_s2;
    int rigid_body; /* kinematics: 0 paper (angle rates = body rates), 1 rigid (quaternion) */

    /* [rotors] */
    int rotors_ideal; /* 1: no limits (paper); 0: limited */
    double w2_min_rad2_s2, w2_max_rad2_s2, motor_tau_s, tilt_max_rad;
    double motor_tau_down_s;             /* 0: motor_tau_s */
    double battery_life_s, battery_drop; /* battery sag (plant.h); life 0: none */
    double rotor_drag_N_s_m;             /* NaN: derived from rotor_drag_per_s */
    double rotor_drag_per_s;             /* the vehicle's drag per unit mass at hover (1/s) */
    double rotor_height_m;               /* NaN: 0.25 arm_m */
    double thrust_curve;                 /* the rotors' k in (1 - k) c + k c^2 of the ESC command c; NaN: none */
    double mixer_thrust_curve;           /* the k the controllers' mixer inverts (ladrc_mixer_command) */
    double battery_full_V;               /* the pack's voltage when full, for the controllers' schedule */

    /* [wind] */
    int turbulence;                           /* SIM_TURB_* (plant/turbulence.h) */
    double turb_sigma_m_s;                    /* turbulence = sigma */
    double altitude_m;                        /* for the scale lengths and intensities */
    double mean_wind_m_s, mean_wind_from_rad; /* steady wind, from this heading (0: north) */

    /* [vibration] (plant/vibration.h); n_orders 0: none */
    int vib_n_orders, vib_n_gyro, vib_n_accel;
    double vib_order[4], vib_gyro_rad_s[4], vib_accel_m_s2[4], vib_axis_gain[3];

    /* [filter]: the library's gyro filter stage before every controller */
    int filter_enabled, filter_angle; /* yes/no; filter_angle: the angles too */
    int filter_lpf_order;             /* 0, 1, 2 */
    double filter_lpf_hz;
    int filter_n_notches;
    double filter_notch_hz[4], filter_notch_q;
    int filter_rpm_harmonics; /* 0: no RPM notch bank */
    double filter_rpm_q, filter_rpm_min_hz, filter_rpm_fade_hz;

    /* [phases]: arming, the ground and take-off (docs/scenario-format.md); no arm_s:
     * armed from the start; no takeoff_s: in the air from the start */
    int phase_n_arm, phase_n_disarm, phase_n_takeoff, phase_n_land;
    double phase_arm_s[4], phase_disarm_s[4], phase_takeoff_s[4], phase_land_s[4];
    double ground_rad[2]; /* the ground's roll and pitch: the attitude the vehicle stands at */
    double ground_thrust; /* thrust while armed on the ground, as a fraction of the weight */
    int landed_input;     /* 1: the controllers are told landed on the ground; 0: never (no land detector) */
    int n_events;         /* the timeline the checks build from the four lists, in time order */
    double event_s[16];
    int event_kind[16]; /* SIM_EVENT_* */

    /* [sensors] */
    double angle_noise_std_rad; /* file gives angle_noise_var_deg2 or angle_noise_std_deg */
    double rate_noise_std_rad_s;
    int delay_ticks;
    int use_rate; /* controllers get the measured rate */

    /* Recorded series (series.h): a file added to the disturbance, to the
     * references or to the measured rate or angle. Paths are relative to the scenario's folder
     * as given, resolved by the parser ("" : none). */
    char dist_series[SIM_PATH_LEN];
    int dist_series_interp, dist_series_end; /* SIM_SERIES_LINEAR/HOLD; SIM_SERIES_REPEAT/HOLD_END/REFUSE */
    char rate_noise_series[SIM_PATH_LEN], angle_noise_series[SIM_PATH_LEN];
    int noise_series_interp, noise_series_end;
    char ref_series[SIM_PATH_LEN]; /* [reference] series: angles added to the references */
    int ref_series_interp, ref_series_end;

    /* [mismatch]: what the controllers assume, as factors of the plant's values */
    double inertia_scale[3], rot_drag_scale;

    /* [reference] roll, pitch, yaw (deg in the file, rad here) and
     * [disturbance] roll, pitch, yaw (rad/s^2) */
    sim_signal_t reference[3];
    sim_signal_t disturbance[3];
    sim_signal_t throttle; /* [reference] throttle: fraction of the full thrust 4 kL w2_max; no pieces: hold
                              altitude (the weight over the tilt) */
    int frame;             /* [reference] frame: ladrc_attitude_frame_t; QUATERNION: the references are
                          ZYX angles composed into an attitude, errors are body-axis rotation vectors */
    double yaw_weight;     /* [reference] yaw_weight: the quaternion frame's weight of yaw against tilt */

    /* [excitation]: a logarithmic chirp added to the controller's torque
     * (sim/scenario/excitation.h); absent: none */
    int excite_on;              /* 1: the section is given */
    int excite_axis;            /* sim_excite_axis_t */
    double excite_amplitude[4]; /* normalised command: a fraction of sim_setup_authority_Nm; one for every
                                   axis, or roll, pitch, yaw */
    int excite_n_amplitudes;    /* 1 or 3 (checks.c) */
    double excite_f0_hz, excite_f1_hz;
    double excite_start_s, excite_duration_s; /* each axis's chirp lasts duration_s */

    /* [controller NAME] sections */
    sim_overrides_t overrides[SIM_CTRL_COUNT];

    /* [metrics] */
    double error_window_s[2];  /* Table 4 statistics over this window */
    double steady_window_s[2]; /* Table 5 steady band over this window */
    double settle_band_deg;    /* Table 5 settling: |error| stays within this ... */
    double settle_after_s;     /* ... measured from this instant ... */
    double settle_until_s;     /* ... up to this one ([metrics] settle_window_s) */
    double diverge_limit_deg;  /* a run diverges when |error| on an axis exceeds this */

    /* [differentiator] (kind = differentiator): signal r(t) with noise, and
     * its exact derivative for the error */
    sim_signal_t diff_signal, diff_derivative;
    double diff_noise_var;                                     /* variance of the noise added per sample */
    double diff_levant_lipschitz, diff_td_accel, diff_td_h0_s; /* NaN: the library's default */

    /* Why a controller that is not in `controllers` could not fly this
     * scenario, where the parser would have reported it (line 0: it can);
     * sim_scenario_set_controllers reports it when one is chosen. */
    sim_parse_error_t controller_error[SIM_CTRL_COUNT];

    /* Where each controller's `tune` key is (line 0: not given), for the
     * errors of the tuning, and what the tuning chose (zero until it runs). */
    int tune_line[SIM_CTRL_COUNT], tune_column[SIM_CTRL_COUNT];
    sim_tuning_t tuning[SIM_CTRL_COUNT];

    /* > 0: lines from this one on are --set items (sim_parse_error_t) */
    int first_set_line;
} sim_scenario_t;

/* Fills sc with the defaults of every key, then reads the file. Returns 0, or
 * -1 with *err set (the first error); sc is then unusable. */
int sim_scenario_load(sim_scenario_t *sc, const char *path, sim_parse_error_t *err);

/* The same from text in memory (path is only used in messages). */
int sim_scenario_parse(sim_scenario_t *sc, const char *text, const char *path, sim_parse_error_t *err);

/* The same from len bytes that need not end with a NUL (a NUL byte among
 * them is an error at its place): what sim_scenario_load does with the file. */
int sim_scenario_parse_buffer(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                              sim_parse_error_t *err);

/* The same, then the command line's settings sets[0..n_sets-1], each
 * "SECTION.KEY=VALUE" (SECTION: a section's name, or "controller NAME" or
 * "controller:NAME"), read as a line KEY = VALUE of that section after the
 * file: same parsing, same errors. A setting replaces the file's value of
 * its key (every piece of a signal key; further settings of that signal add
 * pieces); a key set twice on the command line is a duplicate. Errors in a
 * setting have line first_set_line + its index and a column into its text. */
int sim_scenario_load_with(sim_scenario_t *sc, const char *path, const char *const *sets, int n_sets,
                           sim_parse_error_t *err);
int sim_scenario_parse_buffer_with(sim_scenario_t *sc, const char *data, size_t len, const char *path,
                                   const char *const *sets, int n_sets, sim_parse_error_t *err);

/* A list of controller names, the one rule of the file's `controllers` and
 * of --controllers: names separated by commas, whitespace or both (an empty
 * name, as in "A,,B" or a trailing comma, is an error). Returns 0 with
 * ids[0..*n-1], or -1 with the message in msg and the offset of the
 * offending text in *err_at. */
int sim_controller_list_parse(const char *text, sim_controller_id_t ids[SIM_MAX_CONTROLLERS], int *n, size_t *err_at,
                              char *msg, size_t msg_len);

/* Replaces an attitude scenario's controllers with ids[0..n-1] (the command
 * line's --controllers; 1 <= n <= SIM_MAX_CONTROLLERS). Returns 0, or -1 with
 * *err set, the list unchanged, when one of them cannot fly the scenario (the
 * error the parser gives when it is listed in the file) or n is out of range. */
int sim_scenario_set_controllers(sim_scenario_t *sc, const sim_controller_id_t *ids, int n, sim_parse_error_t *err);

/* "HP-MLADRC", "LP-MLADRC", "LADRC", "PID", "CASCADED", "INDI", "RATE-ADRC"; "?" for anything else */
const char *sim_controller_name(sim_controller_id_t id);

/* 1 for a controller that cannot fly without the measured rate ([sensors]
 * use_rate = yes): INDI and RATE-ADRC hold their command without one (axis.h). */
int sim_controller_needs_rate(sim_controller_id_t id);

#endif
