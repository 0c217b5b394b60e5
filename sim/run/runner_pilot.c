/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * RATE-ADRC flown by Betaflight's acro pilot ([controller RATE-ADRC]
 * pilot = acro): the native twin of the library inside Betaflight. The
 * same pilot as the BETAFLIGHT run's (bridge/bf_pilot.h) turns the
 * references into body-rate demands; they are the rate setpoints of the
 * library's RATE-ADRC axes in acro, held within full stick and, with
 * pilot_pulse = yes, quantized to the RC pulse the SITL's link carries.
 */
#include <math.h>

#include "runner_parts.h"
#include "scenario/setup.h"

void runner_pilot_configure(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg)
{
    if (!sim_setup_piloted(sc, id)) {
        return;
    }
    cfg->frame = LADRC_FRAME_EULER; /* ladrc_attitude_step passes each axis its rate setpoint as it is */
    for (int i = 0; i < 3; ++i) {
        cfg->axis[i].radrc_acro = 1u;
        /* the sticks' full deflection bounds the setpoint, as in the
         * Betaflight adapter (integrations/betaflight/ladrc_rate.c) */
        cfg->axis[i].radrc_rate_max_rad_s = cfg->axis[i].rate_limit_rad_s;
    }
}

void runner_pilot_open(const sim_scenario_t *sc, sim_controller_id_t id, attitude_run_t *r)
{
    const sim_overrides_t *o = &sc->overrides[id];
    r->piloted = sim_setup_piloted(sc, id);
    r->pilot_pulse = o->radrc_pilot_pulse == 1;
    bf_pilot_config_t pc;
    runner_pilot_config(sc, o, BF_MODE_ACRO, &pc);
    bf_pilot_init(&r->pilot, &pc);
}

static double or_default(double v, double d)
{
    return isnan(v) ? d : v;
}

void runner_pilot_config(const sim_scenario_t *sc, const sim_overrides_t *o, bf_mode_t mode, bf_pilot_config_t *pc)
{
    pc->mode = mode;
    pc->rate_max_rad_s = or_default(o->bf_rate_max_deg_s, BF_RATE_MAX_DEG_S_DEFAULT) / RAD2DEG;
    pc->angle_limit_rad = or_default(o->bf_angle_limit_deg, BF_ANGLE_LIMIT_DEG_DEFAULT) / RAD2DEG;
    pc->att_kp_per_s = or_default(o->bf_att_kp_per_s, BF_PILOT_ATT_KP_DEFAULT);
    pc->dt_s = sc->control_dt_s;
}

void runner_pilot_rates(const sim_scenario_t *sc, attitude_run_t *r, const tick_t *tk, ladrc_real_t rate_sp[3])
{
    double error_rad[3], demand[3]; /* the pilot sees the vehicle, not its sensors (as runner_bf.c's) */
    runner_attitude_error_rad(sc, &r->plant, tk->ref_rad, r->wrap_yaw, error_rad);
    bf_pilot_rate_demand(&r->pilot, tk->ref_rad, error_rad, demand);
    bf_pilot_advance(&r->pilot, tk->ref_rad);
    for (int i = 0; i < 3; ++i) {
        rate_sp[i] = (ladrc_real_t)bf_pilot_stick_rate(&r->pilot, i, demand[i], r->pilot_pulse);
    }
}
