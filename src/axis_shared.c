/* SPDX-License-Identifier: BSD-3-Clause */
/* What the axis variants share (see axis_shared.h): the reference shaper,
 * the actuator model and the command's bounds. */
#include "axis_shared.h"

/* Largest L dt^2 (rad/s^2) a Levant shaper may have on an axis: 1e7 rad/s^4
 * at 1 kHz, ten thousand times the default. */
#define AXIS_LEVANT_CHATTER_MAX_RAD_S2 LADRC_R(10.0)

ladrc_status_t axis_shaper_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    axis->shaper = cfg->shaper;
    switch (cfg->shaper) {
    case LADRC_SHAPER_NONE:
        return LADRC_OK;
    case LADRC_SHAPER_TD: {
#if LADRC_WITH_TD
        const ladrc_td_config_t td_cfg = {
            .dt_s = cfg->dt_s, .accel_rad_s2 = cfg->td_accel_rad_s2, .h0_s = cfg->td_h0_s};
        return ladrc_td_init(&axis->shaping.td, &td_cfg);
#else
        return LADRC_ERR_SHAPER_NOT_BUILT;
#endif
    }
    case LADRC_SHAPER_LEVANT: {
#if LADRC_WITH_LEVANT
        /* Levant's r'' chatters on the scale L h^2: beyond a few rad/s^2 the
         * law would pass that chatter to the actuators as torque noise. */
        if (!(cfg->levant_lipschitz_rad_s4 * cfg->dt_s * cfg->dt_s <= AXIS_LEVANT_CHATTER_MAX_RAD_S2)) {
            return LADRC_ERR_LEVANT_LIPSCHITZ;
        }
        const ladrc_levant_config_t lev_cfg = {.dt_s = cfg->dt_s,
                                               .method = cfg->levant_method,
                                               .gains = LADRC_LEVANT_GAINS_LIPSCHITZ,
                                               .lipschitz_rad_s4 = cfg->levant_lipschitz_rad_s4};
        return ladrc_levant_init(&axis->shaping.levant, &lev_cfg);
#else
        return LADRC_ERR_SHAPER_NOT_BUILT;
#endif
    }
    default:
        return LADRC_ERR_SHAPER;
    }
}

/* The share of the torque bounds' acceleration a large error is closed
 * with (axis_shared.h): the other half stays for the disturbance rejected
 * meanwhile. */
#define AXIS_APPROACH_SHARE LADRC_R(0.5)

void axis_approach_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg, ladrc_real_t k_per_s)
{
    const ladrc_real_t bound_Nm = (cfg->u_max_Nm < -cfg->u_min_Nm) ? cfg->u_max_Nm : -cfg->u_min_Nm;
    const ladrc_real_t accel = AXIS_APPROACH_SHARE * ladrc_fabs(cfg->b0) * bound_Nm;
    axis->approach_rad_s2 = LADRC_R(2.0) * accel;
    axis->linear_rad = ladrc_is_finite(accel) ? LADRC_R(2.0) * accel / (k_per_s * k_per_s) : (ladrc_real_t)INFINITY;
}

void axis_shaper_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
#if LADRC_WITH_TD
    if (axis->shaper == LADRC_SHAPER_TD) {
        ladrc_td_reset(&axis->shaping.td, angle_rad);
    }
#endif
#if LADRC_WITH_LEVANT
    if (axis->shaper == LADRC_SHAPER_LEVANT) {
        ladrc_levant_reset(&axis->shaping.levant, angle_rad);
    }
#endif
    (void)axis;
    (void)angle_rad;
}

/* Below this h / tau the mean gain g = (x - 1 + exp(-x)) / x, x = h / tau,
 * comes from its series (the direct form cancels: a relative error of
 * 2 eps / x); the series' first omitted term, x^4 / 120, is then below
 * 1e-6 of g = x / 2. */
#define AXIS_MEAN_GAIN_SERIES_MAX LADRC_R(0.1)

ladrc_status_t axis_actuator_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_real_t tau = cfg->motor_tau_s;
    if (!(ladrc_is_finite(tau) && tau >= LADRC_R(0.0) && tau <= LADRC_MOTOR_TAU_MAX_S)) {
        return LADRC_ERR_MOTOR_TAU_S;
    }
    if (cfg->delay_ticks > LADRC_MAX_DELAY_TICKS) {
        return LADRC_ERR_DELAY_TICKS;
    }
    ladrc_actuator_t *act = &axis->act;
    act->alpha = LADRC_R(1.0);
    act->mean_gain = LADRC_R(1.0);
    if (tau > LADRC_R(0.0)) {
        const ladrc_real_t x = cfg->dt_s / tau;
        act->alpha = -ladrc_expm1(-x);
        if (x < AXIS_MEAN_GAIN_SERIES_MAX) {
            act->mean_gain =
                x * (LADRC_R(0.5) - x * (LADRC_R(1.0) / LADRC_R(6.0) - x * (LADRC_R(1.0) / LADRC_R(24.0))));
        } else {
            act->mean_gain = LADRC_R(1.0) - act->alpha / x;
        }
    }
    act->delay_ticks = cfg->delay_ticks;
    act->block_ticks = axis_delay_block_ticks(cfg->delay_ticks);
    act->inv_block = LADRC_R(1.0) / (ladrc_real_t)act->block_ticks;
    act->inv_2block = LADRC_R(0.5) * act->inv_block;
    axis_delay_fill(act, LADRC_R(0.0));
    axis->model = (tau > LADRC_R(0.0) || cfg->delay_ticks > 0u) ? 1u : 0u;
    return LADRC_OK;
}

void axis_delay_fill(ladrc_actuator_t *act, ladrc_real_t torque_Nm)
{
    for (unsigned k = 0u; k < LADRC_DELAY_SLOTS; ++k) {
        act->delayed_Nm[k] = torque_Nm;
    }
    act->block_sum_Nm = LADRC_R(0.0);
    act->fill = 0u;
    act->head = 0u;
}

ladrc_real_t axis_command_min(const ladrc_axis_config_t *cfg)
{
    return (cfg->u_min_Nm > -cfg->applied_limit_Nm) ? cfg->u_min_Nm : -cfg->applied_limit_Nm;
}

ladrc_real_t axis_command_max(const ladrc_axis_config_t *cfg)
{
    return (cfg->u_max_Nm < cfg->applied_limit_Nm) ? cfg->u_max_Nm : cfg->applied_limit_Nm;
}
