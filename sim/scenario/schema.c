/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario schema (schema.h): sections, the key table, the per-key
 * checks and the defaults. docs/scenario-format.md documents every key.
 */
#include "schema.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "bridge/bf_pilot.h"
#include "ladrc/attitude.h"
#include "ladrc/estimator.h"
#include "ini.h"
#include "ladrc/leso.h"
#include "ladrc/margins.h"
#include "plant/plant.h"
#include "plant/sensor.h"
#include "plant/turbulence.h"
#include "plant/vibration.h"
#include "series.h"

/* Defaults that are not the paper vehicle's (documented in docs/scenario-format.md). */
#define DEFAULT_CONTROL_DT_S 0.001
#define DEFAULT_PLANT_SUBSTEPS 10
#define DEFAULT_SEED 1u
#define DEFAULT_TILT_MAX_DEG 40.0
#define DEFAULT_SETTLE_BAND_DEG 0.5
#define DEFAULT_DIVERGE_LIMIT_DEG 90.0
/* Rotor drag: a quadrotor of 0.5-1 kg drags about 0.2-0.4 N per m/s of air
 * per kg at hover (published fits of its linear drag); 0.3 1/s is taken. */
#define DEFAULT_ROTOR_DRAG_PER_S 0.3
#define DEFAULT_ALTITUDE_M 10.0 /* a low hover, within the standard's low-altitude model */
#define DEFAULT_FILTER_LPF_HZ 100.0
#define DEFAULT_FILTER_Q 5.0 /* the RPM filters' usual notch Q */
#define DEFAULT_FILTER_RPM_MIN_HZ 20.0
#define DEFAULT_FILTER_RPM_FADE_HZ 10.0
/* Armed on the ground, a flight stack idles its motors at a low throttle. */
#define DEFAULT_GROUND_THRUST 0.2
#define DEFAULT_BATTERY_FULL_V 16.8 /* a charged 4S pack */
/* [excitation]: a fifth of the authority, 1 to 40 Hz over 10 s from 1 s:
 * the span of an attitude loop's crossover and the rotors' lag at 1 kHz */
#define DEFAULT_EXCITE_AMPLITUDE 0.2
#define DEFAULT_EXCITE_F0_HZ 1.0
#define DEFAULT_EXCITE_F1_HZ 40.0 /* or 0.45 / control_dt_s when lower (checks.c) */
#define DEFAULT_EXCITE_START_S 1.0
#define DEFAULT_EXCITE_DURATION_S 10.0

/* ---- controllers ------------------------------------------------------------ */

static const char *const CONTROLLER_NAMES[SIM_CTRL_COUNT] = {"HP-MLADRC", "LP-MLADRC", "LADRC",     "PID",
                                                             "CASCADED",  "INDI",      "RATE-ADRC", "BETAFLIGHT"};

int sim_controller_needs_rate(sim_controller_id_t id)
{
    return id == SIM_CTRL_INDI || id == SIM_CTRL_RATE_ADRC;
}

const char *sim_controller_name(sim_controller_id_t id)
{
    return ((int)id >= 0 && id < SIM_CTRL_COUNT) ? CONTROLLER_NAMES[id] : "?";
}

int schema_controller_id(const char *name, size_t len)
{
    for (int i = 0; i < SIM_CTRL_COUNT; ++i) {
        if (strlen(CONTROLLER_NAMES[i]) == len && strncmp(CONTROLLER_NAMES[i], name, len) == 0) {
            return i;
        }
    }
    return -1;
}

/* ---- sections ----------------------------------------------------------------- */

static const char *const SECTION_NAMES[SEC_CONTROLLER + 1] = {
    "run",  "vehicle",   "rotors", "sensors", "mismatch",   "reference", "disturbance", "metrics", "differentiator",
    "wind", "vibration", "filter", "phases",  "excitation", "controller"};

static const int SECTION_KIND[SEC_CONTROLLER + 1] = {FOR_BOTH,           FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE,
                                                     FOR_ATTITUDE,       FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE,
                                                     FOR_DIFFERENTIATOR, FOR_ATTITUDE, FOR_ATTITUDE, FOR_ATTITUDE,
                                                     FOR_ATTITUDE,       FOR_ATTITUDE, FOR_ATTITUDE};

int schema_find_section(const char *name, size_t len)
{
    for (int i = 0; i <= SEC_CONTROLLER; ++i) {
        if (strlen(SECTION_NAMES[i]) == len && strncmp(SECTION_NAMES[i], name, len) == 0) {
            return i;
        }
    }
    return -1;
}

const char *schema_section_title(int sec, char *buf, size_t n)
{
    if (sec >= SEC_CONTROLLER) {
        snprintf(buf, n, "[controller %s]", CONTROLLER_NAMES[sec - SEC_CONTROLLER]);
    } else {
        snprintf(buf, n, "[%s]", SECTION_NAMES[sec]);
    }
    return buf;
}

int schema_section_kind(int sec)
{
    return SECTION_KIND[SCHEMA_TABLE(sec)];
}

int schema_key_kind(int sec, const key_def_t *def)
{
    return def->kind != FOR_BOTH ? def->kind : schema_section_kind(sec);
}

/* ---- keys --------------------------------------------------------------------- */

static const choice_t YES_NO[] = {{.name = "yes", .value = 1}, {.name = "no", .value = 0}, {.name = NULL, .value = 0}};
static const choice_t KINDS[] = {{.name = "attitude", .value = SIM_KIND_ATTITUDE},
                                 {.name = "differentiator", .value = SIM_KIND_DIFFERENTIATOR},
                                 {.name = NULL, .value = 0}};
static const choice_t LESO_METHODS[] = {
    {.name = "zoh", .value = LADRC_LESO_ZOH}, {.name = "euler", .value = LADRC_LESO_EULER}, {.name = NULL, .value = 0}};
static const choice_t SERIES_INTERP[] = {{.name = "linear", .value = SIM_SERIES_LINEAR},
                                         {.name = "hold", .value = SIM_SERIES_HOLD},
                                         {.name = NULL, .value = 0}};
static const choice_t SERIES_END[] = {{.name = "repeat", .value = SIM_SERIES_REPEAT},
                                      {.name = "hold", .value = SIM_SERIES_HOLD_END},
                                      {.name = "refuse", .value = SIM_SERIES_REFUSE},
                                      {.name = NULL, .value = 0}};
static const choice_t TURBULENCE[] = {
    {.name = "off", .value = SIM_TURB_OFF},           {.name = "light", .value = SIM_TURB_LIGHT},
    {.name = "moderate", .value = SIM_TURB_MODERATE}, {.name = "severe", .value = SIM_TURB_SEVERE},
    {.name = "sigma", .value = SIM_TURB_SIGMA},       {.name = NULL, .value = 0}};
static const choice_t TUNE_MODES[] = {{.name = "none", .value = SIM_TUNE_NONE},
                                      {.name = "margins", .value = SIM_TUNE_MARGINS},
                                      {.name = NULL, .value = 0}};
/* tune_noise_ref: a controller's name, its sim_controller_id_t */
static const choice_t CONTROLLER_CHOICES[] = {
    {.name = "HP-MLADRC", .value = SIM_CTRL_HP_MLADRC}, {.name = "LP-MLADRC", .value = SIM_CTRL_LP_MLADRC},
    {.name = "LADRC", .value = SIM_CTRL_LADRC},         {.name = "PID", .value = SIM_CTRL_PID},
    {.name = "CASCADED", .value = SIM_CTRL_CASCADED},   {.name = "INDI", .value = SIM_CTRL_INDI},
    {.name = "RATE-ADRC", .value = SIM_CTRL_RATE_ADRC}, {.name = NULL, .value = 0}};
static const choice_t BF_MODES[] = {
    {.name = "acro", .value = BF_MODE_ACRO}, {.name = "angle", .value = BF_MODE_ANGLE}, {.name = NULL, .value = 0}};
static const choice_t HP_FREQ_MODES[] = {{.name = "known", .value = LADRC_HP_FREQ_KNOWN},
                                         {.name = "online", .value = LADRC_HP_FREQ_ONLINE},
                                         {.name = NULL, .value = 0}};
static const choice_t KINEMATICS[] = {
    {.name = "paper", .value = 0}, {.name = "rigid", .value = 1}, {.name = NULL, .value = 0}};
static const choice_t FRAMES[] = {{.name = "euler", .value = LADRC_FRAME_EULER},
                                  {.name = "quaternion", .value = LADRC_FRAME_QUATERNION},
                                  {.name = NULL, .value = 0}};
static const choice_t EXCITE_AXES[] = {{.name = "roll", .value = SIM_EXCITE_ROLL},
                                       {.name = "pitch", .value = SIM_EXCITE_PITCH},
                                       {.name = "yaw", .value = SIM_EXCITE_YAW},
                                       {.name = "all", .value = SIM_EXCITE_ALL},
                                       {.name = NULL, .value = 0}};
static const choice_t LOG_FORMS[] = {{.name = "betaflight", .value = SIM_RUN_LOG_BETAFLIGHT},
                                     {.name = "px4", .value = SIM_RUN_LOG_PX4},
                                     {.name = "generic", .value = SIM_RUN_LOG_GENERIC},
                                     {.name = NULL, .value = 0}};
static const choice_t HP_SAMPLES[] = {{.name = "observer", .value = LADRC_HP_SAMPLE_OBSERVER},
                                      {.name = "gyro", .value = LADRC_HP_SAMPLE_GYRO},
                                      {.name = NULL, .value = 0}};

#define CTRL_BIT(id) (1u << (id))
#define C_HP CTRL_BIT(SIM_CTRL_HP_MLADRC)
#define C_LP CTRL_BIT(SIM_CTRL_LP_MLADRC)
#define C_LADRC CTRL_BIT(SIM_CTRL_LADRC)
#define C_PID CTRL_BIT(SIM_CTRL_PID)
#define C_CAS CTRL_BIT(SIM_CTRL_CASCADED)
#define C_INDI CTRL_BIT(SIM_CTRL_INDI)
#define C_RADRC CTRL_BIT(SIM_CTRL_RATE_ADRC)
#define LADRC_FAMILY (C_HP | C_LP | C_LADRC)
#define C_BF CTRL_BIT(SIM_CTRL_BETAFLIGHT)
/* the library's controllers: Betaflight brings its own gains and tuning */
#define ALL_CONTROLLERS (((1u << SIM_CTRL_COUNT) - 1u) & ~C_BF)

#define SC(field) offsetof(sim_scenario_t, field)
#define OV(field) offsetof(sim_overrides_t, field)

/* A row names its section, key, type and field; the other members are
 * given by name where they differ from their zero: no range (R_ANY), unit
 * factor 1, the section's kind, optional, no twin. */
#define KEY(sec, key, typ, field) .section = (sec), .name = (key), .type = (typ), .offset = (field)
/* A [controller NAME] key: its field in sim_overrides_t and the controllers it applies to. */
#define CTRL_KEY(key, typ, field, ctrls) KEY(SEC_CONTROLLER, key, typ, OV(field)), .controllers = (ctrls)

const key_def_t SCHEMA_KEYS[] = {
    {KEY(SEC_RUN, "kind", V_KIND, SC(kind)), .choices = KINDS},
    {KEY(SEC_RUN, "duration_s", V_REAL, SC(duration_s)), .range = R_DURATION, .required = 1},
    {KEY(SEC_RUN, "control_dt_s", V_REAL, SC(control_dt_s)), .range = R_CONTROL_DT},
    {KEY(SEC_RUN, "plant_substeps", V_INT, SC(plant_substeps)), .range = R_SUBSTEPS, .kind = FOR_ATTITUDE},
    {KEY(SEC_RUN, "seed", V_SEED, SC(seed))},
    {KEY(SEC_RUN, "output_dir", V_TEXT, SC(output_dir))},
    {KEY(SEC_RUN, "controllers", V_CONTROLLERS, SC(controllers)), .kind = FOR_ATTITUDE},
    {KEY(SEC_RUN, "log", V_FLAGS, SC(log_forms)), .choices = LOG_FORMS, .kind = FOR_ATTITUDE},

    {KEY(SEC_VEHICLE, "mass_kg", V_REAL, SC(mass_kg)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "inertia_kg_m2", V_VEC3, SC(inertia_kg_m2)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "arm_m", V_REAL, SC(arm_m)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "thrust_coeff_N_s2", V_REAL, SC(thrust_coeff_N_s2)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "yaw_coeff_Nm_s2", V_REAL, SC(yaw_coeff_Nm_s2)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "rot_drag_Nm_s", V_REAL, SC(rot_drag_Nm_s)), .range = R_NONNEGATIVE},
    {KEY(SEC_VEHICLE, "g_m_s2", V_REAL, SC(g_m_s2)), .range = R_POSITIVE},
    {KEY(SEC_VEHICLE, "kinematics", V_CHOICE, SC(rigid_body)), .choices = KINEMATICS},

    {KEY(SEC_ROTORS, "ideal", V_CHOICE, SC(rotors_ideal)), .choices = YES_NO},
    {KEY(SEC_ROTORS, "w2_min_rad2_s2", V_REAL, SC(w2_min_rad2_s2)), .range = R_NONNEGATIVE},
    {KEY(SEC_ROTORS, "w2_max_rad2_s2", V_REAL, SC(w2_max_rad2_s2)), .range = R_POSITIVE},
    {KEY(SEC_ROTORS, "motor_tau_s", V_REAL, SC(motor_tau_s)), .range = R_NONNEGATIVE},
    {KEY(SEC_ROTORS, "tilt_max_deg", V_REAL, SC(tilt_max_rad)), .range = R_TILT, .scale = DEG_TO_RAD},
    {KEY(SEC_ROTORS, "motor_tau_down_s", V_REAL, SC(motor_tau_down_s)), .range = R_NONNEGATIVE},
    {KEY(SEC_ROTORS, "battery_life_s", V_REAL, SC(battery_life_s)), .range = R_NONNEGATIVE},
    {KEY(SEC_ROTORS, "battery_drop", V_REAL, SC(battery_drop)), .range = R_FRACTION},
    {KEY(SEC_ROTORS, "rotor_drag_N_s_m", V_REAL, SC(rotor_drag_N_s_m)), .range = R_NONNEGATIVE,
     .twin = "rotor_drag_per_s"},
    {KEY(SEC_ROTORS, "rotor_drag_per_s", V_REAL, SC(rotor_drag_per_s)), .range = R_NONNEGATIVE,
     .twin = "rotor_drag_N_s_m"},
    {KEY(SEC_ROTORS, "rotor_height_m", V_REAL, SC(rotor_height_m)), .range = R_NONNEGATIVE},
    {KEY(SEC_ROTORS, "thrust_curve", V_REAL, SC(thrust_curve)), .range = R_UNIT},
    {KEY(SEC_ROTORS, "mixer_thrust_curve", V_REAL, SC(mixer_thrust_curve)), .range = R_UNIT},
    {KEY(SEC_ROTORS, "battery_full_V", V_REAL, SC(battery_full_V)), .range = R_POSITIVE},

    {KEY(SEC_SENSORS, "angle_noise_std_deg", V_REAL, SC(angle_noise_std_rad)), .range = R_NONNEGATIVE,
     .scale = DEG_TO_RAD, .twin = "angle_noise_var_deg2"},
    {KEY(SEC_SENSORS, "angle_noise_var_deg2", V_REAL, SC(angle_noise_std_rad)), .range = R_NONNEGATIVE,
     .scale = DEG_TO_RAD, .variance = 1, .twin = "angle_noise_std_deg"},
    {KEY(SEC_SENSORS, "rate_noise_std_deg_s", V_REAL, SC(rate_noise_std_rad_s)), .range = R_NONNEGATIVE,
     .scale = DEG_TO_RAD, .twin = "rate_noise_var_deg2_s2"},
    {KEY(SEC_SENSORS, "rate_noise_var_deg2_s2", V_REAL, SC(rate_noise_std_rad_s)), .range = R_NONNEGATIVE,
     .scale = DEG_TO_RAD, .variance = 1, .twin = "rate_noise_std_deg_s"},
    {KEY(SEC_SENSORS, "delay_ticks", V_INT, SC(delay_ticks)), .range = R_DELAY},
    {KEY(SEC_SENSORS, "use_rate", V_CHOICE, SC(use_rate)), .choices = YES_NO},
    {KEY(SEC_SENSORS, "rate_noise_series", V_TEXT, SC(rate_noise_series))},
    {KEY(SEC_SENSORS, "angle_noise_series", V_TEXT, SC(angle_noise_series))},
    {KEY(SEC_SENSORS, "series_interp", V_CHOICE, SC(noise_series_interp)), .choices = SERIES_INTERP},
    {KEY(SEC_SENSORS, "series_end", V_CHOICE, SC(noise_series_end)), .choices = SERIES_END},

    {KEY(SEC_MISMATCH, "inertia_scale", V_VEC3, SC(inertia_scale)), .range = R_POSITIVE},
    {KEY(SEC_MISMATCH, "rot_drag_scale", V_REAL, SC(rot_drag_scale)), .range = R_NONNEGATIVE},

    {KEY(SEC_REFERENCE, "roll", V_SIGNAL, SC(reference[0]))},
    {KEY(SEC_REFERENCE, "pitch", V_SIGNAL, SC(reference[1]))},
    {KEY(SEC_REFERENCE, "yaw", V_SIGNAL, SC(reference[2]))},
    {KEY(SEC_REFERENCE, "throttle", V_SIGNAL, SC(throttle))},
    {KEY(SEC_REFERENCE, "frame", V_CHOICE, SC(frame)), .choices = FRAMES},
    {KEY(SEC_REFERENCE, "yaw_weight", V_REAL, SC(yaw_weight)), .range = R_WEIGHT},
    {KEY(SEC_REFERENCE, "series", V_TEXT, SC(ref_series))},
    {KEY(SEC_REFERENCE, "series_interp", V_CHOICE, SC(ref_series_interp)), .choices = SERIES_INTERP},
    {KEY(SEC_REFERENCE, "series_end", V_CHOICE, SC(ref_series_end)), .choices = SERIES_END},

    {KEY(SEC_DISTURBANCE, "roll", V_SIGNAL, SC(disturbance[0]))},
    {KEY(SEC_DISTURBANCE, "pitch", V_SIGNAL, SC(disturbance[1]))},
    {KEY(SEC_DISTURBANCE, "yaw", V_SIGNAL, SC(disturbance[2]))},
    {KEY(SEC_DISTURBANCE, "series", V_TEXT, SC(dist_series))},
    {KEY(SEC_DISTURBANCE, "series_interp", V_CHOICE, SC(dist_series_interp)), .choices = SERIES_INTERP},
    {KEY(SEC_DISTURBANCE, "series_end", V_CHOICE, SC(dist_series_end)), .choices = SERIES_END},

    {KEY(SEC_METRICS, "error_window_s", V_WINDOW, SC(error_window_s[0])), .offset2 = SC(error_window_s[1])},
    {KEY(SEC_METRICS, "steady_window_s", V_WINDOW, SC(steady_window_s[0])), .offset2 = SC(steady_window_s[1])},
    {KEY(SEC_METRICS, "settle_band_deg", V_REAL, SC(settle_band_deg)), .range = R_POSITIVE},
    {KEY(SEC_METRICS, "settle_window_s", V_WINDOW, SC(settle_after_s)), .offset2 = SC(settle_until_s)},
    {KEY(SEC_METRICS, "diverge_limit_deg", V_REAL, SC(diverge_limit_deg)), .range = R_POSITIVE},

    {KEY(SEC_WIND, "turbulence", V_CHOICE, SC(turbulence)), .choices = TURBULENCE},
    {KEY(SEC_WIND, "sigma_m_s", V_REAL, SC(turb_sigma_m_s)), .range = R_SIGMA},
    {KEY(SEC_WIND, "altitude_m", V_REAL, SC(altitude_m)), .range = R_ALTITUDE},
    {KEY(SEC_WIND, "mean_m_s", V_REAL, SC(mean_wind_m_s)), .range = R_WIND},
    {KEY(SEC_WIND, "from_deg", V_REAL, SC(mean_wind_from_rad)), .range = R_HEADING, .scale = DEG_TO_RAD},

    {KEY(SEC_VIBRATION, "orders", V_LIST, SC(vib_order)), .offset2 = SC(vib_n_orders), .range = R_ORDER},
    {KEY(SEC_VIBRATION, "gyro_deg_s", V_LIST, SC(vib_gyro_rad_s)), .offset2 = SC(vib_n_gyro), .range = R_VIB_GYRO,
     .scale = DEG_TO_RAD},
    {KEY(SEC_VIBRATION, "accel_m_s2", V_LIST, SC(vib_accel_m_s2)), .offset2 = SC(vib_n_accel), .range = R_VIB_ACCEL},
    {KEY(SEC_VIBRATION, "axis_gain", V_VEC3, SC(vib_axis_gain)), .range = R_VIB_GAIN},

    {KEY(SEC_FILTER, "enabled", V_CHOICE, SC(filter_enabled)), .choices = YES_NO},
    {KEY(SEC_FILTER, "angle", V_CHOICE, SC(filter_angle)), .choices = YES_NO},
    {KEY(SEC_FILTER, "lpf_order", V_INT, SC(filter_lpf_order)), .range = R_LPF_ORDER},
    {KEY(SEC_FILTER, "lpf_hz", V_REAL, SC(filter_lpf_hz)), .range = R_POSITIVE},
    {KEY(SEC_FILTER, "notch_hz", V_LIST, SC(filter_notch_hz)), .offset2 = SC(filter_n_notches), .range = R_POSITIVE},
    {KEY(SEC_FILTER, "notch_q", V_REAL, SC(filter_notch_q)), .range = R_Q},
    {KEY(SEC_FILTER, "rpm_harmonics", V_INT, SC(filter_rpm_harmonics)), .range = R_HARMONICS},
    {KEY(SEC_FILTER, "rpm_q", V_REAL, SC(filter_rpm_q)), .range = R_Q},
    {KEY(SEC_FILTER, "rpm_min_hz", V_REAL, SC(filter_rpm_min_hz)), .range = R_POSITIVE},
    {KEY(SEC_FILTER, "rpm_fade_hz", V_REAL, SC(filter_rpm_fade_hz)), .range = R_NONNEGATIVE},

    {KEY(SEC_PHASES, "arm_s", V_LIST, SC(phase_arm_s)), .offset2 = SC(phase_n_arm), .range = R_NONNEGATIVE},
    {KEY(SEC_PHASES, "disarm_s", V_LIST, SC(phase_disarm_s)), .offset2 = SC(phase_n_disarm), .range = R_NONNEGATIVE},
    {KEY(SEC_PHASES, "takeoff_s", V_LIST, SC(phase_takeoff_s)), .offset2 = SC(phase_n_takeoff), .range = R_NONNEGATIVE},
    {KEY(SEC_PHASES, "land_s", V_LIST, SC(phase_land_s)), .offset2 = SC(phase_n_land), .range = R_NONNEGATIVE},
    {KEY(SEC_PHASES, "ground_deg", V_VEC2, SC(ground_rad)), .range = R_SLOPE, .scale = DEG_TO_RAD},
    {KEY(SEC_PHASES, "ground_thrust", V_REAL, SC(ground_thrust)), .range = R_FRACTION},
    {KEY(SEC_PHASES, "landed_input", V_CHOICE, SC(landed_input)), .choices = YES_NO},

    {KEY(SEC_EXCITATION, "axis", V_CHOICE, SC(excite_axis)), .choices = EXCITE_AXES},
    {KEY(SEC_EXCITATION, "amplitude", V_LIST, SC(excite_amplitude)), .offset2 = SC(excite_n_amplitudes),
     .range = R_WEIGHT},
    {KEY(SEC_EXCITATION, "f0_hz", V_REAL, SC(excite_f0_hz)), .range = R_POSITIVE},
    {KEY(SEC_EXCITATION, "f1_hz", V_REAL, SC(excite_f1_hz)), .range = R_POSITIVE},
    {KEY(SEC_EXCITATION, "start_s", V_REAL, SC(excite_start_s)), .range = R_NONNEGATIVE},
    {KEY(SEC_EXCITATION, "duration_s", V_REAL, SC(excite_duration_s)), .range = R_POSITIVE},

    {KEY(SEC_DIFFERENTIATOR, "signal", V_SIGNAL, SC(diff_signal)), .required = 1},
    {KEY(SEC_DIFFERENTIATOR, "derivative", V_SIGNAL, SC(diff_derivative)), .required = 1},
    {KEY(SEC_DIFFERENTIATOR, "noise_var", V_REAL, SC(diff_noise_var)), .range = R_NONNEGATIVE},
    {KEY(SEC_DIFFERENTIATOR, "levant_lipschitz_rad_s4", V_REAL, SC(diff_levant_lipschitz)), .range = R_POSITIVE},
    {KEY(SEC_DIFFERENTIATOR, "td_accel_rad_s2", V_REAL, SC(diff_td_accel)), .range = R_POSITIVE},
    {KEY(SEC_DIFFERENTIATOR, "td_h0_s", V_REAL, SC(diff_td_h0_s)), .range = R_POSITIVE},
    {KEY(SEC_DIFFERENTIATOR, "error_window_s", V_WINDOW, SC(error_window_s[0])), .offset2 = SC(error_window_s[1])},

    {CTRL_KEY("wc_rad_s", V_REAL, wc_rad_s, LADRC_FAMILY), .range = R_POSITIVE},
    {CTRL_KEY("wo_rad_s", V_REAL, wo_rad_s, LADRC_FAMILY | C_RADRC), .range = R_POSITIVE},
    {CTRL_KEY("leso_method", V_CHOICE, leso_method, LADRC_FAMILY), .choices = LESO_METHODS},
    {CTRL_KEY("hp_freq_mode", V_CHOICE, hp_freq_mode, C_HP), .choices = HP_FREQ_MODES},
    {CTRL_KEY("hp_sample", V_CHOICE, hp_sample, C_HP), .choices = HP_SAMPLES},
    {CTRL_KEY("hp_freq_rad_s", V_REAL, hp_freq_rad_s, C_HP), .range = R_POSITIVE},
    {CTRL_KEY("hp_freq2_rad_s", V_REAL, hp_freq2_rad_s, C_HP), .range = R_POSITIVE},
    {CTRL_KEY("hp_freq_min_rad_s", V_REAL, hp_freq_min_rad_s, C_HP), .range = R_POSITIVE},
    {CTRL_KEY("hp_freq_max_rad_s", V_REAL, hp_freq_max_rad_s, C_HP), .range = R_POSITIVE},
    {CTRL_KEY("hp_tones", V_INT, hp_tones, C_HP), .range = R_HP_TONES},
    {CTRL_KEY("levant_lipschitz_rad_s4", V_REAL, levant_lipschitz_rad_s4, C_HP | C_LP), .range = R_POSITIVE},
    {CTRL_KEY("td_accel_rad_s2", V_REAL, td_accel_rad_s2, C_LADRC | C_CAS | C_INDI | C_RADRC), .range = R_POSITIVE},
    {CTRL_KEY("pid_kp", V_REAL, pid_kp, C_PID), .range = R_NONNEGATIVE},
    {CTRL_KEY("pid_ki", V_REAL, pid_ki, C_PID), .range = R_NONNEGATIVE},
    {CTRL_KEY("pid_kd", V_REAL, pid_kd, C_PID), .range = R_NONNEGATIVE},
    {CTRL_KEY("indi_att_kp_per_s", V_REAL, indi_att_kp_per_s, C_INDI), .range = R_POSITIVE},
    {CTRL_KEY("indi_rate_kp_per_s", V_REAL, indi_rate_kp_per_s, C_INDI), .range = R_POSITIVE},
    {CTRL_KEY("indi_filter_rad_s", V_REAL, indi_filter_rad_s, C_INDI), .range = R_POSITIVE},
    {CTRL_KEY("radrc_kp_per_s", V_REAL, radrc_kp_per_s, C_RADRC), .range = R_POSITIVE},
    {CTRL_KEY("radrc_att_kp_per_s", V_REAL, radrc_att_kp_per_s, C_RADRC), .range = R_POSITIVE},
    {CTRL_KEY("radrc_rate_max_deg_s", V_REAL, radrc_rate_max_deg_s, C_RADRC), .range = R_POSITIVE},
    {CTRL_KEY("cas_att_kp", V_REAL, cas_att_kp, C_CAS), .range = R_POSITIVE},
    {CTRL_KEY("cas_rate_max_deg_s", V_REAL, cas_rate_max_deg_s, C_CAS), .range = R_POSITIVE},
    {CTRL_KEY("cas_rate_kp", V_REAL, cas_rate_kp, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("cas_rate_ki", V_REAL, cas_rate_ki, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("cas_rate_kd", V_REAL, cas_rate_kd, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("cas_d_filter_tau_s", V_REAL, cas_d_filter_tau_s, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("cas_i_limit_Nm", V_REAL, cas_i_limit_Nm, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("coupling_feed", V_CHOICE, coupling_feed, LADRC_FAMILY), .choices = YES_NO},
    {CTRL_KEY("cas_setpoint_ff", V_CHOICE, cas_setpoint_ff, C_CAS), .choices = YES_NO},
    {CTRL_KEY("cas_rate_ff", V_REAL, cas_rate_ff, C_CAS), .range = R_NONNEGATIVE},
    {CTRL_KEY("cas_i_relax_deg_s", V_REAL, cas_i_relax_deg_s, C_CAS), .range = R_POSITIVE},
    {CTRL_KEY("indi_adapt", V_CHOICE, indi_adapt, C_INDI), .choices = YES_NO},
    {CTRL_KEY("indi_adapt_mu", V_REAL, indi_adapt_mu, C_INDI), .range = R_POSITIVE},
    {CTRL_KEY("gain_schedule", V_CHOICE, gain_schedule, ALL_CONTROLLERS), .choices = YES_NO},
    {CTRL_KEY("model_motor_tau_s", V_REAL, model_motor_tau_s, LADRC_FAMILY | C_INDI | C_RADRC), .range = R_NONNEGATIVE},
    {CTRL_KEY("model_delay_ticks", V_INT, model_delay_ticks, LADRC_FAMILY | C_INDI | C_RADRC), .range = R_DELAY},
    {CTRL_KEY("wrap_yaw", V_CHOICE, wrap_yaw, LADRC_FAMILY | C_PID | C_CAS | C_INDI | C_RADRC), .choices = YES_NO},
    {CTRL_KEY("tune", V_CHOICE, tune, ALL_CONTROLLERS), .choices = TUNE_MODES},
    {CTRL_KEY("mode", V_CHOICE, bf_mode, C_BF), .choices = BF_MODES},
    {CTRL_KEY("pilot_att_kp_per_s", V_REAL, bf_att_kp_per_s, C_BF), .range = R_POSITIVE},
    {CTRL_KEY("rate_max_deg_s", V_REAL, bf_rate_max_deg_s, C_BF), .range = R_POSITIVE},
    {CTRL_KEY("angle_limit_deg", V_REAL, bf_angle_limit_deg, C_BF), .range = R_POSITIVE},
    {CTRL_KEY("warmup_s", V_REAL, bf_warmup_s, C_BF), .range = R_NONNEGATIVE},
    {CTRL_KEY("timeout_ms", V_INT, bf_timeout_ms, C_BF), .range = R_POSITIVE},
    {CTRL_KEY("tune_phase_margin_deg", V_REAL, tune_pm_deg, ALL_CONTROLLERS), .range = R_PHASE_MARGIN},
    {CTRL_KEY("tune_gain_margin_db", V_REAL, tune_gm_db, ALL_CONTROLLERS), .range = R_POSITIVE},
    {CTRL_KEY("tune_step_deg", V_REAL, tune_step_rad, ALL_CONTROLLERS), .range = R_TUNE_STEP, .scale = DEG_TO_RAD},
    {CTRL_KEY("tune_disturbance_step_rad_s2", V_REAL, tune_dist_rad_s2, ALL_CONTROLLERS), .range = R_NONNEGATIVE},
    {CTRL_KEY("tune_noise_max_Nm", V_REAL, tune_noise_max_Nm, ALL_CONTROLLERS), .range = R_POSITIVE},
    {CTRL_KEY("tune_noise_ref", V_CHOICE, tune_noise_ref, ALL_CONTROLLERS), .choices = CONTROLLER_CHOICES},
    {CTRL_KEY("tune_noise_ratio", V_REAL, tune_noise_ratio, ALL_CONTROLLERS), .range = R_POSITIVE},
    {CTRL_KEY("tune_noise_axis_max_Nm", V_VEC3, tune_noise_axis_max_Nm, ALL_CONTROLLERS), .range = R_POSITIVE},
};

#define N_KEYS ((int)(sizeof SCHEMA_KEYS / sizeof SCHEMA_KEYS[0]))
const int SCHEMA_N_KEYS = N_KEYS;

/* The reader's arrays hold SCHEMA_MAX_KEYS keys. */
typedef char schema_keys_fit[(N_KEYS <= SCHEMA_MAX_KEYS) ? 1 : -1];

int schema_find_key(int table, const char *name)
{
    for (int i = 0; i < N_KEYS; ++i) {
        if (SCHEMA_KEYS[i].section == table && strcmp(SCHEMA_KEYS[i].name, name) == 0) {
            return i;
        }
    }
    return -1;
}

int schema_applies_to(const key_def_t *def, int id)
{
    return (def->controllers & CTRL_BIT(id)) != 0;
}

/* ---- per-key checks ----------------------------------------------------------- */

static int PRINTF_LIKE(3, 4) refuse(char *msg, size_t msg_len, const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    vsnprintf(msg, msg_len, format, ap);
    va_end(ap);
    return -1;
}

int schema_check_range(const key_def_t *def, double v, char *msg, size_t msg_len)
{
    switch (def->range) {
    case R_POSITIVE:
        return v > 0.0 ? 0 : refuse(msg, msg_len, "%s must be > 0", def->name);
    case R_NONNEGATIVE:
        return v >= 0.0 ? 0 : refuse(msg, msg_len, "%s must be >= 0", def->name);
    case R_TILT:
        return (v > 0.0 && v < 90.0) ? 0 : refuse(msg, msg_len, "%s must be > 0 and < 90", def->name);
    case R_DELAY:
        return (v >= 0.0 && v <= SIM_SENSOR_MAX_DELAY)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 0 and %d", def->name, SIM_SENSOR_MAX_DELAY);
    case R_HP_TONES:
        return (v >= 1.0 && v <= LADRC_HP_MAX_TONES)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 1 and %d", def->name, LADRC_HP_MAX_TONES);
    case R_PHASE_MARGIN:
        return (v > 0.0 && v < 90.0) ? 0 : refuse(msg, msg_len, "%s must be > 0 and < 90", def->name);
    case R_TUNE_STEP:
        return (v >= 0.0 && v <= LADRC_MARGINS_MAX_STEP_RAD / DEG_TO_RAD)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 0 and %.1f", def->name,
                            LADRC_MARGINS_MAX_STEP_RAD / DEG_TO_RAD);
    case R_DURATION:
        return (v > 0.0 && v <= SIM_DURATION_MAX_S)
                   ? 0
                   : refuse(msg, msg_len, "%s must be > 0 and at most %g", def->name, SIM_DURATION_MAX_S);
    case R_CONTROL_DT:
        return (v >= SIM_CONTROL_DT_MIN_S && v <= SIM_CONTROL_DT_MAX_S)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between %g and %g", def->name, SIM_CONTROL_DT_MIN_S,
                            SIM_CONTROL_DT_MAX_S);
    case R_SUBSTEPS:
        return (v >= 1.0 && v <= SIM_PLANT_SUBSTEPS_MAX)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 1 and %d", def->name, SIM_PLANT_SUBSTEPS_MAX);
    case R_FRACTION:
        return (v >= 0.0 && v < 1.0) ? 0 : refuse(msg, msg_len, "%s must be >= 0 and < 1", def->name);
    case R_LPF_ORDER:
        return (v == 0.0 || v == 1.0 || v == 2.0) ? 0 : refuse(msg, msg_len, "%s must be 0, 1 or 2", def->name);
    case R_HARMONICS:
        return (v >= 0.0 && v <= 4.0) ? 0 : refuse(msg, msg_len, "%s must be between 0 and 4", def->name);
    case R_ALTITUDE:
        return (v > 0.0 && v <= SIM_TURB_ALTITUDE_MAX_M)
                   ? 0
                   : refuse(msg, msg_len, "%s must be > 0 and at most %g (1000 ft)", def->name,
                            SIM_TURB_ALTITUDE_MAX_M);
    case R_SIGMA:
        return (v >= 0.0 && v <= 30.0) ? 0 : refuse(msg, msg_len, "%s must be between 0 and 30", def->name);
    case R_WIND:
        return (v >= 0.0 && v <= 50.0) ? 0 : refuse(msg, msg_len, "%s must be between 0 and 50", def->name);
    case R_ORDER:
        return (v >= SIM_VIB_ORDER_MIN && v <= SIM_VIB_ORDER_MAX)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between %g and %g", def->name, SIM_VIB_ORDER_MIN,
                            SIM_VIB_ORDER_MAX);
    case R_VIB_GYRO:
        /* whole deg/s: the bound's conversion to rad/s cannot round past the plant's */
        return (v >= 0.0 && v <= floor(SIM_VIB_GYRO_MAX_RAD_S / DEG_TO_RAD))
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 0 and %.0f (%g rad/s)", def->name,
                            floor(SIM_VIB_GYRO_MAX_RAD_S / DEG_TO_RAD), SIM_VIB_GYRO_MAX_RAD_S);
    case R_VIB_ACCEL:
        return (v >= 0.0 && v <= SIM_VIB_ACCEL_MAX_M_S2)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 0 and %g", def->name, SIM_VIB_ACCEL_MAX_M_S2);
    case R_VIB_GAIN:
        return (v >= 0.0 && v <= SIM_VIB_AXIS_GAIN_MAX)
                   ? 0
                   : refuse(msg, msg_len, "%s must be between 0 and %g", def->name, SIM_VIB_AXIS_GAIN_MAX);
    case R_Q:
        return (v >= 0.1 && v <= 100.0) ? 0 : refuse(msg, msg_len, "%s must be between 0.1 and 100", def->name);
    case R_WEIGHT:
        return (v > 0.0 && v <= 1.0) ? 0 : refuse(msg, msg_len, "%s must be > 0 and at most 1", def->name);
    case R_HEADING:
        return (v >= 0.0 && v < 360.0) ? 0 : refuse(msg, msg_len, "%s must be >= 0 and below 360", def->name);
    case R_UNIT:
        return (v >= 0.0 && v <= 1.0) ? 0 : refuse(msg, msg_len, "%s must be between 0 and 1", def->name);
    case R_SLOPE:
        return (v > -30.0 && v < 30.0) ? 0 : refuse(msg, msg_len, "%s must be within (-30, 30)", def->name);
    default:
        return 0;
    }
}

/* ---- defaults ------------------------------------------------------------------ */

void schema_set_defaults(sim_scenario_t *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->kind = SIM_KIND_ATTITUDE;
    sc->duration_s = NAN; /* required */
    sc->control_dt_s = DEFAULT_CONTROL_DT_S;
    sc->plant_substeps = DEFAULT_PLANT_SUBSTEPS;
    sc->seed = DEFAULT_SEED;
    sc->n_controllers = SIM_CTRL_DEFAULT_COUNT;
    for (int i = 0; i < SIM_CTRL_DEFAULT_COUNT; ++i) {
        sc->controllers[i] = (sim_controller_id_t)i;
    }

    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    sc->mass_kg = v.mass_kg;
    memcpy(sc->inertia_kg_m2, v.inertia_kg_m2, sizeof sc->inertia_kg_m2);
    sc->arm_m = v.arm_m;
    sc->thrust_coeff_N_s2 = v.thrust_coeff_N_s2;
    sc->yaw_coeff_Nm_s2 = v.yaw_coeff_Nm_s2;
    sc->rot_drag_Nm_s = v.rot_drag_Nm_s;
    sc->g_m_s2 = v.g_m_s2;
    sc->rotors_ideal = v.rotors_ideal;
    sc->w2_min_rad2_s2 = v.w2_min_rad2_s2;
    sc->w2_max_rad2_s2 = v.w2_max_rad2_s2;
    sc->motor_tau_s = v.motor_tau_s;
    sc->tilt_max_rad = DEFAULT_TILT_MAX_DEG * DEG_TO_RAD;
    sc->rotor_drag_N_s_m = NAN; /* derived from rotor_drag_per_s */
    sc->rotor_drag_per_s = DEFAULT_ROTOR_DRAG_PER_S;
    sc->rotor_height_m = NAN; /* SIM_ROTOR_HEIGHT_ARMS arms */

    sc->dist_series_end = SIM_SERIES_REFUSE; /* a run past the recording is an error unless asked */
    sc->noise_series_end = SIM_SERIES_REFUSE;
    sc->ref_series_end = SIM_SERIES_REFUSE;
    sc->turbulence = SIM_TURB_OFF;
    sc->turb_sigma_m_s = 0.0;
    sc->altitude_m = DEFAULT_ALTITUDE_M;
    for (int i = 0; i < 3; ++i) {
        sc->vib_axis_gain[i] = 1.0;
    }
    sc->filter_enabled = 1;
    sc->filter_angle = 0; /* the rate loop's gyro only, as flight stacks do */
    sc->filter_lpf_hz = DEFAULT_FILTER_LPF_HZ;
    sc->filter_notch_q = DEFAULT_FILTER_Q;
    sc->filter_rpm_q = DEFAULT_FILTER_Q;
    sc->filter_rpm_min_hz = DEFAULT_FILTER_RPM_MIN_HZ;
    sc->filter_rpm_fade_hz = DEFAULT_FILTER_RPM_FADE_HZ;

    sc->use_rate = 1;
    for (int i = 0; i < 3; ++i) {
        sc->inertia_scale[i] = 1.0;
        sc->reference[i].scale = DEG_TO_RAD;
        sc->disturbance[i].scale = 1.0;
    }
    sc->rot_drag_scale = 1.0;
    sc->ground_thrust = DEFAULT_GROUND_THRUST;
    sc->landed_input = 1;
    sc->throttle.scale = 1.0;
    sc->thrust_curve = NAN; /* none: the rotors give the w^2 the mixer asks */
    sc->battery_full_V = DEFAULT_BATTERY_FULL_V;
    sc->excite_axis = SIM_EXCITE_ROLL;
    sc->excite_amplitude[0] = DEFAULT_EXCITE_AMPLITUDE;
    sc->excite_n_amplitudes = 1;
    sc->excite_f0_hz = DEFAULT_EXCITE_F0_HZ;
    sc->excite_f1_hz = DEFAULT_EXCITE_F1_HZ;
    sc->excite_start_s = DEFAULT_EXCITE_START_S;
    sc->excite_duration_s = DEFAULT_EXCITE_DURATION_S;
    sc->frame = LADRC_FRAME_EULER;
    sc->yaw_weight = (double)LADRC_YAW_WEIGHT_DEFAULT;

    for (int i = 0; i < SIM_CTRL_COUNT; ++i) {
        sim_overrides_t *o = &sc->overrides[i];
        o->wc_rad_s = o->wo_rad_s = NAN;
        o->leso_method = o->hp_freq_mode = o->hp_sample = o->coupling_feed = -1;
        o->hp_freq_rad_s = o->hp_freq2_rad_s = o->hp_freq_min_rad_s = o->hp_freq_max_rad_s =
            o->levant_lipschitz_rad_s4 = o->td_accel_rad_s2 = NAN;
        o->hp_tones = -1;
        o->model_motor_tau_s = NAN;
        o->model_delay_ticks = o->wrap_yaw = -1;
        o->pid_kp = o->pid_ki = o->pid_kd = NAN;
        o->tune = -1;
        o->bf_mode = o->bf_timeout_ms = -1;
        o->bf_att_kp_per_s = o->bf_rate_max_deg_s = o->bf_angle_limit_deg = o->bf_warmup_s = NAN;
        o->tune_pm_deg = o->tune_gm_db = NAN;
        o->tune_step_rad = o->tune_dist_rad_s2 = NAN;
        o->tune_noise_max_Nm = NAN;
        o->tune_noise_ref = -1;
        o->tune_noise_ratio = 1.0;
        o->tune_noise_axis_max_Nm[0] = o->tune_noise_axis_max_Nm[1] = o->tune_noise_axis_max_Nm[2] = NAN;
        o->indi_att_kp_per_s = o->indi_rate_kp_per_s = o->indi_filter_rad_s = NAN;
        o->radrc_kp_per_s = o->radrc_att_kp_per_s = o->radrc_rate_max_deg_s = NAN;
        o->cas_att_kp = o->cas_rate_max_deg_s = o->cas_rate_kp = o->cas_rate_ki = o->cas_rate_kd = NAN;
        o->cas_d_filter_tau_s = o->cas_i_limit_Nm = NAN;
        o->cas_setpoint_ff = o->indi_adapt = o->gain_schedule = -1;
        o->cas_rate_ff = o->cas_i_relax_deg_s = o->indi_adapt_mu = NAN;
    }

    sc->settle_band_deg = DEFAULT_SETTLE_BAND_DEG;
    sc->diverge_limit_deg = DEFAULT_DIVERGE_LIMIT_DEG;
    /* the metric windows default to the whole run, set once duration_s is known */

    sc->diff_signal.scale = 1.0;
    sc->diff_derivative.scale = 1.0;
    sc->diff_levant_lipschitz = sc->diff_td_accel = sc->diff_td_h0_s = NAN;
}
