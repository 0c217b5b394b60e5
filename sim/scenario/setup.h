/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The library configurations a scenario gives its controllers, the mixer and
 * the differentiators: one place for the runner, which flies them, and the
 * parser, which initialises them once to refuse a scenario they cannot fly.
 */
#ifndef LADRC_SIM_SETUP_H
#define LADRC_SIM_SETUP_H

#include "ladrc/attitude.h"
#include "ladrc/gyro_filter.h"
#include "ladrc/levant.h"
#include "ladrc/mixer.h"
#include "ladrc/td.h"
#include "plant/plant.h"
#include "plant/vibration.h"
#include "scenario.h"

/* The library's default config of controller id for the airframe as the
 * controller models it (inertia times inertia_scale, drag times
 * rot_drag_scale): no key of the file applied. */
void sim_setup_library_defaults(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg);

/* Controller id on sc: the library defaults for the control period and the
 * inertia and drag the controllers assume (the plant's times the mismatch
 * factors), then the scenario's [controller NAME] overrides, then the gains
 * tune = margins chose (sc->tuning[id], once sim_tune_controller has run). */
void sim_setup_attitude(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg);

/* One gain that tune = margins chooses: its metrics.csv key (the config
 * field's name), its short label and unit on stdout, and the field. */
typedef struct {
    const char *key;
    const char *label;
    const char *unit;
    size_t offset; /* of the ladrc_real_t field in ladrc_axis_config_t */
} sim_gain_field_t;

/* The gain fields tune = margins chooses for variant v (wc, wo for the LADRC
 * family; PID's, CASCADED's or INDI's own); *n gets their number. */
const sim_gain_field_t *sim_setup_gain_fields(ladrc_variant_t v, int *n);

/* The value of gain field f in a. */
double sim_setup_gain(const ladrc_axis_config_t *a, const sim_gain_field_t *f);

/* The gains tuning t chose for axis (0 roll, 1 pitch, 2 yaw) into a (the
 * fields sim_setup_gain_fields lists for a's variant). */
void sim_setup_tuned_gains(const sim_tuning_t *t, int axis, ladrc_axis_config_t *a);

/* "label value unit ..." of a's tuned gains into buf (snprintf's result). */
int sim_setup_format_gains(const ladrc_axis_config_t *a, char *buf, size_t size);

/* 1 when controller id's yaw wraps at +-180 deg ([controller NAME] wrap_yaw,
 * default yes): its sensor then reports yaw in (-180, 180] deg and its yaw
 * error is measured modulo 360 deg. */
int sim_setup_wraps_yaw(const sim_scenario_t *sc, sim_controller_id_t id);

/* 1 when controller id is RATE-ADRC flown by Betaflight's acro pilot
 * ([controller RATE-ADRC] pilot = acro): its flights run the axes in acro
 * (radrc_acro), their reference each tick the pilot's body-rate demand
 * (bf_pilot.h); its gains are this function's configuration's (tune =
 * margins tunes the rate loop under its own attitude loop, as without it). */
int sim_setup_piloted(const sim_scenario_t *sc, sim_controller_id_t id);

/* The vehicle's mixer; ideal rotors get limits 0 and 1e12 (the mixer wants
 * finite ones). */
void sim_setup_mixer(const sim_scenario_t *sc, ladrc_mixer_config_t *cfg);

/* Levant's differentiator and the TD of a differentiator scenario; an absent
 * key takes the value the library gives an attitude axis (ladrc_axis_config_default). */
void sim_setup_differentiators(const sim_scenario_t *sc, ladrc_levant_config_t *lev, ladrc_td_config_t *td);

/* The plant's vehicle: [vehicle] and [rotors] (drag and rotor height as
 * the parser resolved their defaults). */
sim_vehicle_t sim_setup_vehicle(const sim_scenario_t *sc);

/* The propeller vibration of [vibration] (none when it gives no orders). */
sim_vibration_config_t sim_setup_vibration(const sim_scenario_t *sc);

/* 1 when the controllers fly behind the gyro filter stage: [filter]
 * enabled and some filter set (a low-pass, a notch or RPM harmonics). */
int sim_setup_filters_gyro(const sim_scenario_t *sc);

/* The gyro filter stage of [filter] at the control period: 6 channels (the
 * rates, then the angles) with angle = yes, else 3 (the rates); the RPM
 * bank on the four rotors. */
void sim_setup_gyro_filter(const sim_scenario_t *sc, ladrc_gyro_filter_config_t *cfg);
/* Each rotor's rate at hover (Hz): where tune = margins holds the RPM notches. */
double sim_setup_hover_rotor_hz(const sim_scenario_t *sc);

/* The torque (N m) that a normalised command of 1 means on axis 0 roll, 1
 * pitch, 2 yaw: one rotor (one pair for yaw) from hover to 0 and its
 * opposite to twice hover, from the plant's own [vehicle] values (not
 * [mismatch]). With w2_hover = mass_kg g_m_s2 / (4 thrust_coeff_N_s2):
 *   roll, pitch: 2 arm_m thrust_coeff_N_s2 w2_hover (= arm_m mass_kg g / 2),
 *   yaw:         4 yaw_coeff_Nm_s2 w2_hover.
 * [excitation]'s amplitude and the flight logs' normalised commands are in
 * this unit: a log's command c is c times this, N m. */
double sim_setup_authority_Nm(const sim_scenario_t *sc, int axis);

/* A rotor's w^2 at full command (rad^2/s^2), the flight logs' full throttle
 * and motor output: w2_max_rad2_s2, or twice hover with ideal rotors (which
 * have no top). */
double sim_setup_full_w2_rad2_s2(const sim_scenario_t *sc);

#endif
