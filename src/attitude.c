/* SPDX-License-Identifier: BSD-3-Clause */
/* Three axes with the decoupling-free coupling feed (see attitude.h). */
#include "ladrc/attitude.h"
#include "require.h"

#include "axis_internal.h"

/* Relative rounding allowed on the inertia triangle (a few float ulps). */
#define ATTITUDE_TRIANGLE_SLACK LADRC_R(1.00001)
/* Largest drag / J * dt_s. */
#define ATTITUDE_DRAG_DT_MAX LADRC_R(2.0)

void ladrc_attitude_config_default(ladrc_attitude_config_t *cfg, ladrc_variant_t variant, ladrc_real_t dt_s,
                                   const ladrc_real_t inertia_kg_m2[LADRC_AXES], ladrc_real_t drag_Nms)
{
    LADRC_REQUIRE_VOID(cfg != NULL && inertia_kg_m2 != NULL);
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_config_default(&cfg->axis[i], variant, dt_s, inertia_kg_m2[i]);
        cfg->inertia_kg_m2[i] = inertia_kg_m2[i];
    }
    cfg->axis[LADRC_YAW].wrap_angle = 1u; /* yaw lives on a circle, roll and pitch do not */
    /* CASCADED as PX4: only the yaw setpoint's rate is fed forward. */
    cfg->axis[LADRC_ROLL].cas_setpoint_ff = 0u;
    cfg->axis[LADRC_PITCH].cas_setpoint_ff = 0u;
    cfg->drag_Nms = drag_Nms;
    cfg->coupling_feed = 1u;
    cfg->frame = LADRC_FRAME_EULER;
    cfg->yaw_weight = LADRC_YAW_WEIGHT_DEFAULT;
    cfg->spool_up_s = LADRC_SPOOL_UP_DEFAULT_S;
    cfg->gain_thrust_curve = LADRC_R(0.0);
    cfg->gain_full_thrust_N = LADRC_R(0.0);
    cfg->gain_ref_thrust_N = LADRC_R(0.0);
    cfg->gain_ref_voltage_V = LADRC_R(0.0);
}

void ladrc_attitude_config_quaternion(ladrc_attitude_config_t *cfg)
{
    LADRC_REQUIRE_VOID(cfg != NULL);
    cfg->frame = LADRC_FRAME_QUATERNION;
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        cfg->axis[i].wrap_angle = 1u; /* body angles are kept within a turn */
    }
}

/* The frame's own fields: the frame, and in the quaternion frame the yaw
 * weight and a wrapped angle on every axis (failed_axis for the last). */
static ladrc_status_t check_frame(const ladrc_attitude_config_t *cfg, int *failed_axis)
{
    if (cfg->frame == LADRC_FRAME_EULER) {
        return LADRC_OK;
    }
    if (cfg->frame != LADRC_FRAME_QUATERNION) {
        return LADRC_ERR_ATTITUDE_FRAME;
    }
    if (!ladrc_is_finite(cfg->yaw_weight) || !(cfg->yaw_weight > LADRC_R(0.0)) || cfg->yaw_weight > LADRC_R(1.0)) {
        return LADRC_ERR_YAW_WEIGHT;
    }
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        if (cfg->axis[i].wrap_angle != 1u) {
            if (failed_axis != NULL) {
                *failed_axis = (int)i;
            }
            return LADRC_ERR_WRAP_ANGLE;
        }
    }
    return LADRC_OK;
}

/* The thrust curve's slope at the command a thrust asked gives, (1 - k) +
 * 2 k T / T_full: the torque per command there, up to a constant (1
 * without a curve). */
static ladrc_real_t thrust_slope(const ladrc_attitude_t *att, ladrc_real_t thrust_N)
{
    return LADRC_R(1.0) - att->gain_curve + att->gain_per_full_N * thrust_N;
}

ladrc_status_t ladrc_attitude_init(ladrc_attitude_t *att, const ladrc_attitude_config_t *cfg, int *failed_axis)
{
    if (failed_axis != NULL) {
        *failed_axis = -1;
    }
    if (att == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    const ladrc_real_t *j = cfg->inertia_kg_m2;
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        if (!ladrc_is_positive(j[i])) {
            return LADRC_ERR_INERTIA_KG_M2;
        }
    }
    /* A rigid body's principal inertias obey the triangle inequality; the
     * coupling coefficients (J_next - J_after) / J_i then lie in [-1, 1]. A
     * flat body sits on the edge (Jz = Jx + Jy), so rounding is allowed for. */
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        if (j[i] > (j[(i + 1u) % LADRC_AXES] + j[(i + 2u) % LADRC_AXES]) * ATTITUDE_TRIANGLE_SLACK) {
            return LADRC_ERR_INERTIA_TRIANGLE;
        }
    }
    if (!ladrc_is_finite(cfg->drag_Nms) || cfg->drag_Nms < LADRC_R(0.0)) {
        return LADRC_ERR_DRAG_NMS;
    }
    /* The drag's decay rate drag / J, fed to the observers one step at a
     * time, is a stable explicit step only below 2 / dt_s. */
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        if (cfg->drag_Nms * cfg->axis[0].dt_s > ATTITUDE_DRAG_DT_MAX * j[i]) {
            return LADRC_ERR_DRAG_NMS;
        }
    }
    if (cfg->coupling_feed > 1u) {
        return LADRC_ERR_COUPLING_FEED;
    }
    const ladrc_status_t frame_status = check_frame(cfg, failed_axis);
    if (frame_status != LADRC_OK) {
        return frame_status;
    }
    if (!ladrc_is_finite(cfg->spool_up_s) || cfg->spool_up_s < LADRC_R(0.0) || cfg->spool_up_s > LADRC_SPOOL_UP_MAX_S) {
        return LADRC_ERR_SPOOL_UP_S;
    }
    const ladrc_real_t k = cfg->gain_thrust_curve;
    if (!ladrc_is_finite(k) || k < LADRC_R(0.0) || k > LADRC_R(1.0) ||
        (k > LADRC_R(0.0) &&
         !(ladrc_is_positive(cfg->gain_full_thrust_N) && ladrc_is_positive(cfg->gain_ref_thrust_N))) ||
        !ladrc_is_finite(cfg->gain_ref_voltage_V) || cfg->gain_ref_voltage_V < LADRC_R(0.0)) {
        return LADRC_ERR_GAIN_SCHEDULE;
    }
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        /* The feed mixes the axes' states tick by tick: one clock for all. */
        ladrc_status_t status = (cfg->axis[i].dt_s == cfg->axis[0].dt_s) ? LADRC_OK : LADRC_ERR_DT_S;
        if (status == LADRC_OK) {
            status = ladrc_axis_init(&att->axis[i], &cfg->axis[i]);
        }
        if (status != LADRC_OK) {
            if (failed_axis != NULL) {
                *failed_axis = (int)i;
            }
            return status;
        }
#if LADRC_WITH_HP_MLADRC
        if (cfg->axis[i].variant == LADRC_VARIANT_HP_MLADRC) {
            /* HP axes fit on different ticks, so one tick carries at most one fit. */
            axis_hp_stagger(&att->axis[i], i);
        }
#endif
        /* (J of the next axis - J of the one after) / J, roll -> pitch -> yaw -> roll */
        const unsigned next = (i == LADRC_YAW) ? 0u : i + 1u;
        const unsigned after = (next == LADRC_YAW) ? 0u : next + 1u;
        att->coupling[i] = (j[next] - j[after]) / j[i];
        att->drag_per_s[i] = cfg->drag_Nms / j[i];
        att->feed_rad_s3[i] = LADRC_R(0.0);
        att->body_angle_rad[i] = LADRC_R(0.0);
    }
    att->coupling_feed = cfg->coupling_feed;
    att->frame = (uint8_t)cfg->frame;
    att->yaw_weight = cfg->yaw_weight;
    att->has_attitude = 0u;
    /* whole ticks, rounded up: a spool-up never ends early */
    const ladrc_real_t spool_ticks = cfg->spool_up_s / cfg->axis[0].dt_s;
    att->spool_up_ticks = (uint32_t)spool_ticks;
    if ((ladrc_real_t)att->spool_up_ticks < spool_ticks) {
        ++att->spool_up_ticks;
    }
    att->spool_ticks = 0u;
    att->gain_curve = k;
    att->gain_per_full_N = (k > LADRC_R(0.0)) ? LADRC_R(2.0) * k / cfg->gain_full_thrust_N : LADRC_R(0.0);
    att->gain_ref_inv = LADRC_R(1.0) / thrust_slope(att, cfg->gain_ref_thrust_N);
    att->gain_ref_voltage_V = cfg->gain_ref_voltage_V;
    att->phase = LADRC_PHASE_FLYING; /* as it always flew */
    att->landed = 0u;
    att->restart = 0u;
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        att->engage_Nm[i] = LADRC_R(0.0);
    }
    return LADRC_OK;
}

/* No coupling feed on axis i until the next one is worked out. */
static void clear_feed(ladrc_attitude_t *att, unsigned i)
{
    att->feed_rad_s3[i] = LADRC_R(0.0);
    ladrc_axis_set_disturbance_rate(&att->axis[i], LADRC_R(0.0));
    ladrc_axis_set_known_disturbance(&att->axis[i], LADRC_R(0.0));
}

void ladrc_attitude_reset(ladrc_attitude_t *att, const ladrc_real_t angle_rad[LADRC_AXES])
{
    LADRC_REQUIRE_VOID(att != NULL && angle_rad != NULL);
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_reset(&att->axis[i], angle_rad[i]);
        ladrc_real_t rate_rad_s, disturbance_rad_s2; /* the axis's start, for the quaternion frame */
        ladrc_axis_get_estimate(&att->axis[i], &att->body_angle_rad[i], &rate_rad_s, &disturbance_rad_s2);
        clear_feed(att, i);
    }
    att->has_attitude = 0u;
}

/* h of one axis from the other two axes' rates and accelerations (a, b in
 * roll -> pitch -> yaw -> roll order after the axis). */
static ladrc_real_t feed(const ladrc_attitude_t *att, unsigned i, ladrc_real_t rate_a, ladrc_real_t accel_a,
                         ladrc_real_t rate_b, ladrc_real_t accel_b, ladrc_real_t accel_i)
{
    return att->coupling[i] * (accel_a * rate_b + rate_a * accel_b) - att->drag_per_s[i] * accel_i;
}

/* Rate and acceleration of one axis (axis_observer_rate and
 * axis_observer_accel, the formula of ladrc_axis_get_accel). A PID, CASCADED
 * or INDI axis has no observer: 0 and 0 (INDI measures the coupling in its
 * acceleration and needs no feed). Forced inline: 28 instructions of the 3-axis HP-MLADRC tick
 * (2,805.5 with it, 2,833.5 without). */
static LADRC_FORCE_INLINE void observed(const ladrc_axis_t *ax, ladrc_real_t *rate, ladrc_real_t *accel)
{
    *rate = LADRC_R(0.0);
    *accel = LADRC_R(0.0);
    if (axis_has_observer(ax)) {
        *rate = axis_observer_rate(ax);
        *accel = axis_observer_accel(ax);
    }
}

/* Feeds h to axis i; a PID, CASCADED or INDI axis gets none, and a non-finite
 * h is fed as 0 (as ladrc_axis_set_disturbance_rate does). */
static inline void put_feed(ladrc_attitude_t *att, unsigned i, ladrc_real_t h)
{
    ladrc_axis_t *ax = &att->axis[i];
    if (!axis_has_observer(ax)) {
        h = LADRC_R(0.0);
    }
    att->feed_rad_s3[i] = h;
    axis_put_disturbance_rate(ax, h);
}

/* The known part of axis i's f from the rates (same order as feed): the
 * coupling product and the drag, whose derivative feed() gives. */
static ladrc_real_t known_part(const ladrc_attitude_t *att, unsigned i, ladrc_real_t rate_a, ladrc_real_t rate_b,
                               ladrc_real_t rate_i)
{
    return att->coupling[i] * rate_a * rate_b - att->drag_per_s[i] * rate_i;
}

/* Sets h and the known part of f on each axis from the other axes' rate and
 * acceleration estimates. Kept out of line so that its locals are not on the
 * stack of the axis steps. */
LADRC_NOINLINE static void update_feed(ladrc_attitude_t *att)
{
    ladrc_real_t w0, w1, w2, a0, a1, a2;
    observed(&att->axis[0], &w0, &a0);
    observed(&att->axis[1], &w1, &a1);
    observed(&att->axis[2], &w2, &a2);
    put_feed(att, LADRC_ROLL, feed(att, LADRC_ROLL, w1, a1, w2, a2, a0));
    put_feed(att, LADRC_PITCH, feed(att, LADRC_PITCH, w2, a2, w0, a0, a1));
    put_feed(att, LADRC_YAW, feed(att, LADRC_YAW, w0, a0, w1, a1, a2));
    axis_put_known_disturbance(&att->axis[LADRC_ROLL], known_part(att, LADRC_ROLL, w1, w2, w0));
    axis_put_known_disturbance(&att->axis[LADRC_PITCH], known_part(att, LADRC_PITCH, w2, w0, w1));
    axis_put_known_disturbance(&att->axis[LADRC_YAW], known_part(att, LADRC_YAW, w0, w1, w2));
}

/* The tick of both frames: the feed, then each axis (inlined in both: the
 * Euler tick pays nothing for the quaternion frame). */
static LADRC_FORCE_INLINE ladrc_fault_t step_axes(ladrc_attitude_t *att, const ladrc_real_t ref_rad[LADRC_AXES],
                                                  const ladrc_real_t angle_rad[LADRC_AXES],
                                                  const ladrc_real_t *rate_rad_s, ladrc_real_t torque_Nm[LADRC_AXES])
{
    if (att->coupling_feed && !att->restart) { /* no feed from states waiting to restart */
        update_feed(att);
    }
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    for (unsigned i = 0u; i < LADRC_AXES; ++i) {
        faults |= ladrc_axis_step(&att->axis[i], ref_rad[i], angle_rad[i], (rate_rad_s != NULL) ? &rate_rad_s[i] : NULL,
                                  &torque_Nm[i]);
    }
    return faults;
}

/* Every axis landed or not. */
static void set_axes_landed(ladrc_attitude_t *att, uint8_t landed)
{
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_set_landed(&att->axis[i], landed);
    }
}

/* Landed or flying, as the landed input says, every axis told. */
static void follow_landed_input(ladrc_attitude_t *att)
{
    att->phase = att->landed ? LADRC_PHASE_LANDED : LADRC_PHASE_FLYING;
    set_axes_landed(att, att->landed);
}

/* Arming or engaging: every axis restarts on its next good measurement
 * (axis_request_restart), the feed off until then. */
static void request_restart(ladrc_attitude_t *att, int engage)
{
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        axis_request_restart(&att->axis[i], engage, att->engage_Nm[i]);
        clear_feed(att, i);
    }
    att->restart = 1u;
}

/* The restarts asked for, before the axes step (off the flying tick's path
 * and out of its stack); the flag stays up while an angle waits. */
LADRC_NOINLINE static void restart_pass(ladrc_attitude_t *att, const ladrc_real_t ref_rad[LADRC_AXES],
                                        const ladrc_real_t angle_rad[LADRC_AXES], const ladrc_real_t *rate_rad_s)
{
    uint8_t pending = 0u;
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_t *ax = &att->axis[i];
        axis_restart_now(ax, ref_rad[i], angle_rad[i], (rate_rad_s != NULL) ? &rate_rad_s[i] : NULL);
        pending |= ax->restart;
    }
    att->restart = pending ? 1u : 0u;
}

/* After the axes stepped while spooling up: the torque held at 0, the
 * spool-up counted down, then landed or flying as the input says. */
LADRC_NOINLINE static void spool_up_after(ladrc_attitude_t *att, ladrc_real_t torque_Nm[LADRC_AXES])
{
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        torque_Nm[i] = LADRC_R(0.0);
    }
    if (att->spool_ticks > 0u) {
        --att->spool_ticks;
    }
    if (att->spool_ticks == 0u) {
        follow_landed_input(att);
    }
}

/* The tick of both frames with the phases: disarmed, torque 0 and the
 * axes left; spooling up, torque 0 after they step. */
static LADRC_FORCE_INLINE ladrc_fault_t tick(ladrc_attitude_t *att, const ladrc_real_t ref_rad[LADRC_AXES],
                                             const ladrc_real_t angle_rad[LADRC_AXES], const ladrc_real_t *rate_rad_s,
                                             ladrc_real_t torque_Nm[LADRC_AXES])
{
    if (att->phase == LADRC_PHASE_DISARMED) {
        torque_Nm[0] = torque_Nm[1] = torque_Nm[2] = LADRC_R(0.0);
        return LADRC_FAULT_NONE;
    }
    if (att->restart) {
        restart_pass(att, ref_rad, angle_rad, rate_rad_s);
    }
    const ladrc_fault_t faults = step_axes(att, ref_rad, angle_rad, rate_rad_s, torque_Nm);
    if (att->phase == LADRC_PHASE_SPOOL_UP) {
        spool_up_after(att, torque_Nm);
    }
    return faults;
}

ladrc_fault_t ladrc_attitude_step(ladrc_attitude_t *att, const ladrc_real_t ref_rad[LADRC_AXES],
                                  const ladrc_real_t angle_rad[LADRC_AXES], const ladrc_real_t *rate_rad_s,
                                  ladrc_real_t torque_Nm[LADRC_AXES])
{
    LADRC_REQUIRE(att != NULL && ref_rad != NULL && angle_rad != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    if (att->frame != LADRC_FRAME_EULER) {
        return LADRC_FAULT_STATE;
    }
    return tick(att, ref_rad, angle_rad, rate_rad_s, torque_Nm);
}

void ladrc_attitude_arm(ladrc_attitude_t *att)
{
    LADRC_REQUIRE_VOID(att != NULL);
    if (att->phase != LADRC_PHASE_DISARMED) {
        return;
    }
    request_restart(att, 0);
    att->spool_ticks = att->spool_up_ticks;
    if (att->spool_ticks > 0u) {
        att->phase = LADRC_PHASE_SPOOL_UP;
        set_axes_landed(att, 1u);
    } else {
        follow_landed_input(att);
    }
}

void ladrc_attitude_disarm(ladrc_attitude_t *att)
{
    LADRC_REQUIRE_VOID(att != NULL);
    att->phase = LADRC_PHASE_DISARMED;
}

void ladrc_attitude_set_landed(ladrc_attitude_t *att, uint8_t landed)
{
    LADRC_REQUIRE_VOID(att != NULL);
    att->landed = landed ? 1u : 0u;
    if (att->phase == LADRC_PHASE_LANDED || att->phase == LADRC_PHASE_FLYING) {
        follow_landed_input(att);
    }
}

ladrc_phase_t ladrc_attitude_get_phase(const ladrc_attitude_t *att)
{
    LADRC_REQUIRE(att != NULL, LADRC_PHASE_DISARMED);
    return (ladrc_phase_t)att->phase;
}

void ladrc_attitude_engage(ladrc_attitude_t *att, const ladrc_real_t torque_Nm[LADRC_AXES])
{
    LADRC_REQUIRE_VOID(att != NULL && torque_Nm != NULL);
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        att->engage_Nm[i] = ladrc_is_finite(torque_Nm[i]) ? torque_Nm[i] : LADRC_R(0.0);
    }
    request_restart(att, 1);
}

/* Moves the body angles by the rotation from the previous good attitude to
 * q (none for the first one). */
static void advance_body_angles(ladrc_attitude_t *att, ladrc_quat_t q)
{
    if (att->has_attitude) {
        ladrc_real_t step_rad[LADRC_AXES];
        ladrc_quat_rotvec(ladrc_quat_mul(ladrc_quat_conj(att->attitude), q), step_rad);
        for (unsigned i = 0; i < LADRC_AXES; ++i) {
            att->body_angle_rad[i] = ladrc_wrap_pi(att->body_angle_rad[i] + step_rad[i]);
        }
    }
    att->attitude = q;
    att->has_attitude = 1u;
}

ladrc_fault_t ladrc_attitude_step_quat(ladrc_attitude_t *att, const ladrc_quat_t *q_ref, const ladrc_quat_t *q_meas,
                                       const ladrc_real_t *rate_rad_s, ladrc_real_t torque_Nm[LADRC_AXES])
{
    LADRC_REQUIRE(att != NULL && q_ref != NULL && q_meas != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    if (att->frame != LADRC_FRAME_QUATERNION) {
        return LADRC_FAULT_STATE;
    }
    ladrc_real_t angle[LADRC_AXES], ref[LADRC_AXES];
    ladrc_quat_t q, qr;
    const int measured = ladrc_quat_normalise(*q_meas, &q);
    const int referenced = ladrc_quat_normalise(*q_ref, &qr);
    if (measured) {
        advance_body_angles(att, q);
    }
    ladrc_real_t error_rad[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    if (measured && referenced) {
        ladrc_quat_tilt_error(q, qr, att->yaw_weight, error_rad);
    }
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        /* a bad attitude or reference reaches each axis beyond any angle
         * limit: it holds and raises LADRC_FAULT_INPUT */
        angle[i] = measured ? att->body_angle_rad[i] : LADRC_REAL_MAX;
        ref[i] = (measured && referenced) ? ladrc_wrap_pi(att->body_angle_rad[i] + error_rad[i]) : LADRC_REAL_MAX;
    }
    return tick(att, ref, angle, rate_rad_s, torque_Nm);
}

void ladrc_attitude_set_operating_point(ladrc_attitude_t *att, ladrc_real_t thrust_N, ladrc_real_t voltage_V)
{
    LADRC_REQUIRE_VOID(att != NULL);
    if (att->gain_curve == LADRC_R(0.0) && att->gain_ref_voltage_V == LADRC_R(0.0)) {
        return; /* no schedule */
    }
    ladrc_real_t scale = LADRC_R(1.0);
    if (att->gain_curve > LADRC_R(0.0)) {
        if (!ladrc_is_finite(thrust_N) || thrust_N < LADRC_R(0.0)) {
            return; /* the last good scale kept */
        }
        scale = thrust_slope(att, thrust_N) * att->gain_ref_inv;
    }
    if (att->gain_ref_voltage_V > LADRC_R(0.0) && ladrc_is_positive(voltage_V)) {
        const ladrc_real_t v = voltage_V / att->gain_ref_voltage_V;
        scale *= v * v;
    }
    scale = ladrc_clamp(scale, LADRC_GAIN_SCALE_MIN, LADRC_GAIN_SCALE_MAX);
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_set_gain_scale(&att->axis[i], scale);
    }
}

void ladrc_attitude_set_applied(ladrc_attitude_t *att, const ladrc_real_t torque_Nm[LADRC_AXES])
{
    LADRC_REQUIRE_VOID(att != NULL && torque_Nm != NULL);
    for (unsigned i = 0; i < LADRC_AXES; ++i) {
        ladrc_axis_set_applied(&att->axis[i], torque_Nm[i]);
    }
}
