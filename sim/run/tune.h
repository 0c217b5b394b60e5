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
 * (tune_step_deg, tune_disturbance_step_rad_s2) into req; the others keep
 * req's values. */
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

/* Tunes controller id of sc (tune = margins) on each axis into
 * sc->tuning[id]; ws is scratch (ladrc_margins_workspace_t is about 1 MB).
 * Pitch takes roll's result when the two axes' modelled inertias are equal
 * (the same loop). The tuned gains are then flown over the whole scenario
 * (sim_run_attitude, no time series) before they are accepted. Returns 0;
 * or -1 with *err set at the `tune` key (file:line:column) when an axis's
 * targets cannot be met (the message gives the best margins reached), its
 * analysis fails, or the check flight diverges (the message names the axis
 * and the time); sc->tuning[id] then holds what was reached, with
 * tuned = 0. Nothing to do: returns 0. */
int sim_tune_controller(sim_scenario_t *sc, sim_controller_id_t id, ladrc_margins_workspace_t *ws,
                        sim_parse_error_t *err);

#endif
