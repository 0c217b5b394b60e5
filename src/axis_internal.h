/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Inside the axis (not installed): the interface between src/axis.c and the
 * per-variant files. Each variant lives in its own file (axis_adrc.c for the
 * LADRC family with axis_lp.c and axis_hp.c as its estimators, axis_pid.c,
 * axis_cascaded.c, axis_indi.c, axis_rate_adrc.c); axis.c is the one place that dispatches to
 * them, and what they share sits below them (axis_shared.h). A variant left
 * out of the build (LADRC_VARIANTS, axis.h) has no code: its file is not
 * compiled and its cases are not in the switches.
 */
#ifndef LADRC_AXIS_INTERNAL_H
#define LADRC_AXIS_INTERNAL_H

#include "axis_shared.h"
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
 *   set_landed  passes the landed flag on (CASCADED; PID's is its module's)
 *   engage      presets what stands for the disturbance after a reset
 *               (LADRC family, RATE-ADRC; the baselines' modules do their own)
 *   estimate    ladrc_axis_get_estimate
 *   accel       ladrc_axis_get_accel (LADRC family, INDI, RATE-ADRC; the others: 0)
 *   effectiveness ladrc_axis_get_effectiveness (INDI; the others read axis->b0)
 * The LADRC family (axis_adrc.c) shares one set for its three variants and
 * calls its estimator (axis_lp.c, axis_hp.c) through the axis_<est>_* hooks. */
/* The attitude layer's restart of an axis on its next good measurement:
 * engage 0 afresh (ladrc_axis_reset), 1 from torque_Nm (ladrc_axis_engage). */
void axis_request_restart(ladrc_axis_t *axis, int engage, ladrc_real_t torque_Nm);
/* Does a requested restart on this measurement (the rate may be NULL) once
 * the angle is plausible; nothing when none is pending. */
void axis_restart_now(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s);

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
/** Presets the observer after a reset (ladrc_axis_engage): z2 at the rate,
 *  z3 so that the next command is torque_Nm. */
void axis_adrc_engage(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm);
#endif
#if LADRC_WITH_PID
AXIS_VARIANT_FUNCTIONS(pid)
void axis_pid_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm);
#endif
#if LADRC_WITH_CASCADED
AXIS_VARIANT_FUNCTIONS(cascaded)
void axis_cascaded_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm);
void axis_cascaded_set_landed(ladrc_axis_t *axis, uint8_t landed);
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
ladrc_real_t axis_indi_effectiveness(const ladrc_axis_t *axis);
#endif
#if LADRC_WITH_RATE_ADRC
AXIS_VARIANT_FUNCTIONS(rate_adrc)
ladrc_real_t axis_rate_adrc_accel(const ladrc_axis_t *axis);
/** Presets the rate observer after a reset (ladrc_axis_engage): (rate, -b0 torque_Nm). */
void axis_rate_adrc_engage(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm);
#endif

/* The estimator of LP-MLADRC and HP-MLADRC, for axis_adrc.c:
 *   init     validates and starts it (the LESO is initialised before)
 *   restart  restarts it from scratch
 *   preset   after a restart, takes over what it can of a known disturbance
 *            (rad/s^2; ladrc_axis_engage) and returns that part
 *   command  the compensation the command carries with an actuator model
 * and, inline in src/axis_lp.h and src/axis_hp.h (the tick's deepest path
 * keeps no frame of its own for it),
 *   sample   this tick's d_hat from the rate (NaN: none) and the acting torque */
#define AXIS_ESTIMATOR_FUNCTIONS(e)                                                                                    \
    ladrc_status_t axis_##e##_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg);                                \
    void axis_##e##_restart(ladrc_axis_t *axis);                                                                       \
    ladrc_real_t axis_##e##_preset(ladrc_axis_t *axis, ladrc_real_t f_rad_s2);                                         \
    ladrc_real_t axis_##e##_command(ladrc_axis_t *axis);

#if LADRC_WITH_LP_MLADRC
AXIS_ESTIMATOR_FUNCTIONS(lp)
#endif
#if LADRC_WITH_LP_MLADRC || LADRC_WITH_HP_MLADRC
/* An LP estimator from the axis's lp_ fields and actuator model (LP-MLADRC's,
 * and HP-MLADRC's on the gyro). */
static inline ladrc_status_t axis_lp_configure(ladrc_lp_estimator_t *lp, const ladrc_axis_config_t *cfg)
{
    const ladrc_lp_config_t c = {.dt_s = cfg->dt_s,
                                 .lambda0_per_s = cfg->lp_lambda0_per_s,
                                 .k0_per_s = cfg->lp_k0_per_s,
                                 .act_tau_s = cfg->motor_tau_s,
                                 .act_delay_ticks = cfg->delay_ticks};
    return ladrc_lp_init(lp, &c);
}
#endif
#if LADRC_WITH_HP_MLADRC
AXIS_ESTIMATOR_FUNCTIONS(hp)
#endif

/** Whether the axis runs an observer (the LADRC family), whose rate and
 *  acceleration estimates the attitude layer's coupling feed reads. */
static inline int axis_has_observer(const ladrc_axis_t *axis)
{
    return ladrc_variant_has_observer(axis->variant);
}

/** A LADRC-family axis's rate estimate (rad/s): the observer's z2. */
static inline ladrc_real_t axis_observer_rate(const ladrc_axis_t *axis)
{
    return axis->leso.z2;
}

/** Angular acceleration a LADRC-family axis expects over its observer's
 *  next step (rad/s^2): b0 * acting torque + z3 + d_hat (axis.h). */
static inline ladrc_real_t axis_observer_accel(const ladrc_axis_t *axis)
{
    return axis->b0 * axis_acting_Nm(axis) + axis->leso.z3 + axis->d_hat_rad_s2;
}

#endif /* LADRC_AXIS_INTERNAL_H */
