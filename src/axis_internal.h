/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Inside the axis (not installed): what src/axis.c and the per-variant files
 * share. Each variant lives in its own file (axis_adrc.c for the LADRC
 * family with axis_lp.c and axis_hp.c as its estimators, axis_pid.c,
 * axis_cascaded.c, axis_indi.c); axis.c is the one place that dispatches to
 * them. A variant left out of the build (LADRC_VARIANTS, axis.h) has no
 * code: its file is not compiled and its cases are not in the switches.
 */
#ifndef LADRC_AXIS_INTERNAL_H
#define LADRC_AXIS_INTERNAL_H

#include "compiler.h"
#include "ladrc/axis.h"

/* Each variant file defines the functions below for its variant; axis.c
 * dispatches to them with one switch per operation, direct calls (which the
 * tick's static stack analysis, tools/bench/stack.py, follows):
 *   init        validates the variant's fields (the common ones are checked
 *               before) and fills its part of the state
 *   reset       restarts at rest on a plausible angle (shaper included)
 *   step        one tick on a plausible reference and angle (the rate read
 *               only when has_rate); sets output_Nm unless held; returns the
 *               tick's faults
 *   set_applied passes a plausible applied torque on (PID, CASCADED)
 *   estimate    ladrc_axis_get_estimate
 *   accel       ladrc_axis_get_accel (LADRC family, INDI; the others: 0)
 * The LADRC family (axis_adrc.c) shares one set for its three variants and
 * calls its estimator (axis_lp.c, axis_hp.c) through the axis_<est>_* hooks. */
#define LADRC_WITH_ADRC_FAMILY (LADRC_WITH_LADRC || LADRC_WITH_LP_MLADRC || LADRC_WITH_HP_MLADRC)

#define AXIS_VARIANT_FUNCTIONS(v)                                                                                      \
    ladrc_status_t axis_##v##_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);                                \
    void axis_##v##_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad);                                                 \
    ladrc_fault_t axis_##v##_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,                    \
                                  ladrc_real_t rate_rad_s, int has_rate);                                              \
    void axis_##v##_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,              \
                             ladrc_real_t *disturbance_rad_s2);

#if LADRC_WITH_ADRC_FAMILY
AXIS_VARIANT_FUNCTIONS(adrc)
ladrc_real_t axis_adrc_accel(const ladrc_axis_t *axis);
#endif
#if LADRC_WITH_PID
AXIS_VARIANT_FUNCTIONS(pid)
void axis_pid_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm);
#endif
#if LADRC_WITH_CASCADED
AXIS_VARIANT_FUNCTIONS(cascaded)
void axis_cascaded_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm);
#endif
#if LADRC_WITH_HP_MLADRC
/** Moves an initialised HP-MLADRC axis's fit to tick phase (modulo the
 *  block) of each fit block: the attitude layer gives axis i phase i, so
 *  that one tick carries at most one fit. */
void axis_hp_stagger(ladrc_axis_t *axis, unsigned phase);
#endif
#if LADRC_WITH_INDI
AXIS_VARIANT_FUNCTIONS(indi)
ladrc_real_t axis_indi_accel(const ladrc_axis_t *axis);
#endif

/* The estimator of LP-MLADRC and HP-MLADRC, for axis_adrc.c:
 *   init     validates and starts it (the LESO is initialised before)
 *   restart  restarts it from scratch
 *   command  the compensation the command carries with an actuator model
 * and, inline in src/axis_lp.h and src/axis_hp.h (the tick's deepest path
 * keeps no frame of its own for it),
 *   sample   this tick's d_hat from the rate (NaN: none) and the acting torque */
#define AXIS_ESTIMATOR_FUNCTIONS(e)                                                                                    \
    ladrc_status_t axis_##e##_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);                                \
    void axis_##e##_restart(ladrc_axis_t *axis);                                                                       \
    ladrc_real_t axis_##e##_command(ladrc_axis_t *axis);

#if LADRC_WITH_LP_MLADRC
AXIS_ESTIMATOR_FUNCTIONS(lp)
#endif
#if LADRC_WITH_HP_MLADRC
AXIS_ESTIMATOR_FUNCTIONS(hp)
#endif

/** Torque (N m) the next tick's observer step takes as acting: the applied
 *  torque without a model, else its delayed and lagged mean (axis.h). */
static inline ladrc_real_t axis_acting_Nm(const ladrc_axis_t *axis)
{
    if (!axis->model) {
        return axis->applied_Nm;
    }
    const ladrc_actuator_t *act = &axis->act;
    const ladrc_real_t v = (act->delay_ticks != 0u) ? act->delayed_Nm[act->head] : axis->applied_Nm;
    return act->lag_Nm + act->mean_gain * (v - act->lag_Nm);
}

/** Angular acceleration a LADRC-family axis expects over its observer's
 *  next step (rad/s^2): b0 * acting torque + z3 + d_hat (axis.h). */
static inline ladrc_real_t axis_observer_accel(const ladrc_axis_t *axis)
{
    return axis->b0 * axis_acting_Nm(axis) + axis->leso.z3 + axis->d_hat_rad_s2;
}

/** The fed rate of change of f as ladrc_axis_set_disturbance_rate takes it:
 *  a non-finite rate is fed as 0. */
static inline void axis_put_disturbance_rate(ladrc_axis_t *axis, ladrc_real_t rate_rad_s3)
{
    axis->f_rate_rad_s3 = ladrc_is_finite(rate_rad_s3) ? rate_rad_s3 : LADRC_R(0.0);
}

/* --- the reference shaper (axis.c), for the variants that shape ------------ */

/** Validates the shaper fields and starts the shaper (axis->shaper set). */
ladrc_status_t axis_shaper_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);

/** Restarts the shaper and the shaped reference at rest on angle_rad. */
void axis_shaper_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad);

/** The shaper's tick on the raw reference: r, r', r'' into axis->ref (the
 *  shapers write straight into the axis: no copy on the stack). */
static inline ladrc_fault_t axis_shape_reference(ladrc_axis_t *axis, ladrc_real_t ref_rad)
{
    ladrc_ref_t *ref = &axis->ref;
#if LADRC_WITH_TD
    if (axis->shaper == LADRC_SHAPER_TD) {
        return ladrc_td_step(&axis->shaping.td, ref_rad, ref);
    }
#endif
#if LADRC_WITH_LEVANT
    if (axis->shaper == LADRC_SHAPER_LEVANT) {
        return ladrc_levant_step(&axis->shaping.levant, ref_rad, ref);
    }
#endif
    ref->r = ref_rad;
    ref->dr = LADRC_R(0.0);
    ref->ddr = LADRC_R(0.0);
    return LADRC_FAULT_NONE;
}

/** The shaped reference and the shaper's state moved by a turn (a wrapped
 *  axis; axis.h). */
static inline void axis_shift_reference(ladrc_axis_t *axis, ladrc_real_t turn)
{
    axis->ref.r += turn;
#if LADRC_WITH_TD
    if (axis->shaper == LADRC_SHAPER_TD) {
        axis->shaping.td.x1 += turn;
    }
#endif
#if LADRC_WITH_LEVANT
    if (axis->shaper == LADRC_SHAPER_LEVANT) {
        axis->shaping.levant.r_last += turn; /* z0 = r_last + w moves with it */
    }
#endif
}

/* --- the actuator model (axis.c; axis.h), LADRC family and INDI ------------ */

/** Validates motor_tau_s and delay_ticks and derives the model's constants
 *  (axis->model set). */
ladrc_status_t axis_actuator_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);

/** Torque the observer step of this tick takes (axis.h): the model's mean
 *  over the step, which also advances the model by the step; without a
 *  model the applied torque. */
static inline ladrc_real_t axis_advance_actuator(ladrc_axis_t *axis)
{
    if (!axis->model) {
        return axis->applied_Nm;
    }
    const ladrc_real_t mean = axis_acting_Nm(axis);
    ladrc_actuator_t *act = &axis->act;
    ladrc_real_t v = axis->applied_Nm;
    if (act->delay_ticks != 0u) {
        const uint8_t head = act->head;
        v = act->delayed_Nm[head];
        act->delayed_Nm[head] = axis->applied_Nm;
        act->head = (uint8_t)((head + 1u < act->delay_ticks) ? head + 1u : 0u);
    }
    act->lag_Nm += act->alpha * (v - act->lag_Nm);
    return mean;
}

/** The command's bounds (axis.c): u_min_Nm..u_max_Nm inside
 *  +-applied_limit_Nm (the command is applied by default, so it must be a
 *  plausible applied torque). */
ladrc_real_t axis_command_min(const ladrc_axis_config_t *cfg);
ladrc_real_t axis_command_max(const ladrc_axis_config_t *cfg);

#endif /* LADRC_AXIS_INTERNAL_H */
