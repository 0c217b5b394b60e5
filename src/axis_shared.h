/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the axis variants share (not installed), below them: the acting
 * torque, the fed disturbance rate, the reference shaper, the actuator
 * model and the command's bounds (src/axis_shared.c). axis.c dispatches to
 * the variant files (axis_internal.h), which call down into this; nothing
 * here calls up, so the files of the axis form layers, not a circle
 * (tools/check_layers.py checks that).
 */
#ifndef LADRC_AXIS_SHARED_H
#define LADRC_AXIS_SHARED_H

#include "compiler.h"
#include "ladrc/axis.h"

/* --- the delay line (axis.h): the one place that reads and writes it ------- */

/** The torque the line gives at its next push, v = a_k-1-d (N m); `now` (the
 *  torque about to be pushed) when d = 0. Exact up to LADRC_DELAY_SLOTS
 *  ticks; beyond, the line through the two block means whose centres
 *  bracket the tick d pushes back. */
static inline ladrc_real_t axis_delay_out(const ladrc_actuator_t *act, ladrc_real_t now)
{
    if (act->delay_ticks <= LADRC_DELAY_SLOTS) {
        return (act->delay_ticks != 0u) ? act->delayed_Nm[act->head] : now;
    }
    /* The newest whole block's centre lies fill + (m + 1) / 2 ticks back of
     * the next push, the wanted tick d; the distance between them in blocks
     * is q = (2 (d - fill) - m - 1) / (2 m), >= 0 and < slots - 1 for the m
     * of init (axis_delay_block_ticks). */
    const unsigned m = act->block_ticks;
    const unsigned twice = 2u * (act->delay_ticks - act->fill) - m - 1u;
    const unsigned back = twice / (2u * m);
    const ladrc_real_t w = (ladrc_real_t)(twice - back * 2u * m) * act->inv_2block;
    const unsigned newer = (act->head + LADRC_DELAY_SLOTS - 1u - back) % LADRC_DELAY_SLOTS;
    const unsigned older = (newer + LADRC_DELAY_SLOTS - 1u) % LADRC_DELAY_SLOTS;
    return act->delayed_Nm[newer] + w * (act->delayed_Nm[older] - act->delayed_Nm[newer]);
}

/** Pushes the torque of the tick ended (N m) into the line (d > 0). */
static inline void axis_delay_push(ladrc_actuator_t *act, ladrc_real_t torque_Nm)
{
    const unsigned head = act->head;
    if (act->delay_ticks <= LADRC_DELAY_SLOTS) {
        act->delayed_Nm[head] = torque_Nm;
        act->head = (uint8_t)((head + 1u < act->delay_ticks) ? head + 1u : 0u);
        return;
    }
    act->block_sum_Nm += torque_Nm;
    if (++act->fill >= act->block_ticks) {
        act->delayed_Nm[head] = act->block_sum_Nm * act->inv_block;
        act->head = (uint8_t)((head + 1u < LADRC_DELAY_SLOTS) ? head + 1u : 0u);
        act->block_sum_Nm = LADRC_R(0.0);
        act->fill = 0u;
    }
}

/** Ticks per slot for a delay of d ticks: 1 up to the slots; beyond, the
 *  least m with 2 d <= m (2 S - 1), which keeps both blocks read within the
 *  S slots at every fill (axis_delay_out). */
static inline uint16_t axis_delay_block_ticks(unsigned d)
{
    const unsigned span = 2u * LADRC_DELAY_SLOTS - 1u;
    return (uint16_t)((d <= LADRC_DELAY_SLOTS) ? 1u : (2u * d + span - 1u) / span);
}

/** The line as if torque_Nm had been pushed for ever (reset, engage). */
void axis_delay_fill(ladrc_actuator_t *act, ladrc_real_t torque_Nm);

/** The lag's mean over the next tick of a command v that comes out of the
 *  delay line (N m): m + g (v - m). */
static inline ladrc_real_t axis_lagged_mean(const ladrc_actuator_t *act, ladrc_real_t v)
{
    return act->lag_Nm + act->mean_gain * (v - act->lag_Nm);
}

/** Torque (N m) the next tick's observer step takes as acting: the applied
 *  torque without a model, else its delayed and lagged mean (axis.h). */
static inline ladrc_real_t axis_acting_Nm(const ladrc_axis_t *axis)
{
    if (!axis->model) {
        return axis->applied_Nm;
    }
    return axis_lagged_mean(&axis->act, axis_delay_out(&axis->act, axis->applied_Nm));
}

/** The fed rate of change of f as ladrc_axis_set_disturbance_rate takes it:
 *  a non-finite rate is fed as 0. */
static inline void axis_put_disturbance_rate(ladrc_axis_t *axis, ladrc_real_t rate_rad_s3)
{
    axis->f_rate_rad_s3 = ladrc_is_finite(rate_rad_s3) ? rate_rad_s3 : LADRC_R(0.0);
}

/** The known part of f as ladrc_axis_set_known_disturbance takes it
 *  (rad/s^2): a non-finite one is taken as 0. */
static inline void axis_put_known_disturbance(ladrc_axis_t *axis, ladrc_real_t f_known_rad_s2)
{
    axis->f_known_rad_s2 = ladrc_is_finite(f_known_rad_s2) ? f_known_rad_s2 : LADRC_R(0.0);
}

/** |b0| for an inertia between 1e-7 and 1000 kg m^2 (a 10 g toy to a 500 kg
 *  airframe): outside, the law's division by b0 or the observer's b0 u
 *  leaves float for commands a real actuator gives (LADRC family, RATE-ADRC). */
static inline int axis_b0_is_valid(ladrc_real_t b0)
{
    return ladrc_fabs(b0) >= LADRC_R(1e-3) && ladrc_fabs(b0) <= LADRC_R(1e7);
}

/* --- the reference shaper, for the variants that shape ---------------------- */

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

/* --- the actuator model (axis.h), LADRC family and INDI --------------------- */

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
    ladrc_actuator_t *act = &axis->act;
    const ladrc_real_t v = axis_delay_out(act, axis->applied_Nm);
    const ladrc_real_t mean = axis_lagged_mean(act, v);
    if (act->delay_ticks != 0u) {
        axis_delay_push(act, axis->applied_Nm);
    }
    act->lag_Nm += act->alpha * (v - act->lag_Nm);
    return mean;
}

/** The command's bounds: u_min_Nm..u_max_Nm inside
 *  +-applied_limit_Nm (the command is applied by default, so it must be a
 *  plausible applied torque). */
ladrc_real_t axis_command_min(const ladrc_axis_config_t *cfg);
ladrc_real_t axis_command_max(const ladrc_axis_config_t *cfg);

/* Reference minus angle (rad); on a wrapped axis taken modulo 2 pi, and the
 * shaped reference moved by a whole turn once it leaves (-pi, pi], which the
 * error does not see. For the variants that close their own angle loop. */
static inline ladrc_real_t axis_wrapped_error(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    const ladrc_real_t r = axis->ref.r;
    if (!axis->wrap) {
        return r - angle_rad;
    }
    if (r > LADRC_PI) {
        axis_shift_reference(axis, -LADRC_TWO_PI);
    } else if (r < -LADRC_PI) {
        axis_shift_reference(axis, LADRC_TWO_PI);
    }
    return ladrc_wrap_pi(r - angle_rad);
}

/* A large error closed within the torque bounds. A P loop asks to close an
 * error e at the rate k e; beyond linear_rad that is faster than the axis
 * can brake from with half its torque bounds' acceleration a, and after any
 * saturation it would overshoot. There the rate asked is sqrt(2 a |e|) =
 * sqrt(approach_rad_s2 |e|), the fastest that still stops at the reference
 * (equal to k e at linear_rad = 2 a / k^2). Infinite bounds: linear_rad
 * infinite, the plain P loop. axis_approach_init sets both for gain k. */
void axis_approach_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg, ladrc_real_t k_per_s);

static inline ladrc_real_t axis_braking_rate(const ladrc_axis_t *axis, ladrc_real_t error_rad)
{
    const ladrc_real_t rate_rad_s = ladrc_sqrt(axis->approach_rad_s2 * ladrc_fabs(error_rad));
    return (error_rad > LADRC_R(0.0)) ? rate_rad_s : -rate_rad_s;
}

#endif /* LADRC_AXIS_SHARED_H */
