/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * [controller NAME] tune = margins: the gains ladrc_margins_tune (ladrc_analysis,
 * docs/margins.md) chooses for the controller on each axis of the scenario's
 * airframe as the controller models it (its inertia, inertia_kg_m2 times
 * inertia_scale, and drag, rot_drag_Nm_s times rot_drag_scale) with the
 * scenario's motor lag, sensor delay and control period. The parser only
 * reads the keys; ladrc_sil and ladrc_margins tune after loading, before
 * anything runs.
 */
#ifndef LADRC_SIM_TUNE_H
#define LADRC_SIM_TUNE_H

#include "ladrc/margins.h"
#include "scenario/scenario.h"

/* 1 when controller id of sc has tune = margins. */
int sim_tune_wanted(const sim_scenario_t *sc, sim_controller_id_t id);

/* The plant the tuning of axis i designs for (above). */
void sim_tune_plant(const sim_scenario_t *sc, int axis, ladrc_margins_plant_t *plant);
/* The tuning objective's steps the file gives controller id
 * (tune_step_deg, tune_disturbance_step_rad_s2) into req, the others keeping
 * req's values, and the scenario's sensor noise (sim_tune_noise_request) for
 * the predicted command noise. */
void sim_tune_objective(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_request_t *req);

/* The scenario's gyro filter ([filter]) as the tuning and the margins see it:
 * before every controller, the RPM notches held on the rotors' rate at hover. */
typedef struct {
    ladrc_gyro_filter_config_t cfg;
    ladrc_real_t rotor_hz[4];
    int on; /* 0: no filter stage on */
} sim_tune_filter_t;

void sim_tune_filter(const sim_scenario_t *sc, sim_tune_filter_t *f);

/* Axis `axis` of acfg as the tuning and the margins analyse it: the
 * scenario's use of the rate and its filter (f, which must outlive it). */
ladrc_margins_controller_t sim_tune_controller_of(const sim_scenario_t *sc, const sim_tune_filter_t *f,
                                                  const ladrc_attitude_config_t *acfg, int axis);

/* What sim_tune_controller returns. */
enum {
    SIM_TUNE_OK = 0,        /* the tuner met the targets and its gains fly the check flight */
    SIM_TUNE_MISSED = 1,    /* the tuner missed a target, its analysis failed or its gains do not fly the check
                               flight; another candidate flies (the reason at the key) */
    SIM_TUNE_UNTUNABLE = 2, /* no candidate flies the check flight: the controller is not flown */
};

/* Tunes controller id of sc (tune = margins) into sc->tuning[id]; ws is
 * scratch (ladrc_margins_workspace_t is about 1 MB).
 * The tuner (ladrc_margins_tune) runs on each axis; pitch takes roll's
 * result when the two axes' modelled inertias are equal (the same loop).
 * Then every candidate flies the whole scenario (the check flight, no
 * time series): the tuner's gains (its closest miss where it misses the
 * targets), the library's defaults and the gains the file gives beside
 * tune = margins (when it gives any). The candidate with the smallest sum
 * over the axes of the RMS error flies (ties: the tuner's first); one that
 * does not start, fails or diverges never does. sc->tuning[id].by says
 * which candidate won, check_cost_deg what each flew, reason why the
 * tuner's gains are not flown or where they miss; the margins reported are
 * those of the gains flown.
 * Returns SIM_TUNE_OK, SIM_TUNE_MISSED or SIM_TUNE_UNTUNABLE; with the
 * last two *err holds the reason at the `tune` key (file:line:column).
 * Nothing to do: SIM_TUNE_OK. */
int sim_tune_controller(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                        sim_parse_error_t *err);

/* The token of metrics.csv's tune status: tuned, defaults, scenario,
 * untunable or none. */
const char *sim_tuned_by_name(sim_tuned_by_t by);

#endif
