/* SPDX-License-Identifier: BSD-3-Clause */
/* The library's rate loop as a flight stack's rate controller (ladrc_rate.h). */
#include "ladrc_rate.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* A loop period that differs by more than this fraction is a new loop time
 * (Betaflight's pidRuntime.dT is one constant per configuration; float
 * rounding of the same period stays far below). */
#define LOOP_TIME_CHANGE 1e-4f

static int axis_in_range(int axis)
{
    return axis >= 0 && axis < LADRC_BF_AXES;
}

/* The library's RATE-ADRC defaults for an axis of b0 (rad/s^2 per pidSum
 * unit, the "inertia" 1 / b0 in pidSum units), then the airframe's gains:
 * acro (the reference is the rate setpoint), Betaflight's pidSum bound as
 * the command bound, no rate bound of its own beyond the plausible range
 * (Betaflight bounds its setpoint). */
static void axis_config(ladrc_axis_config_t *cfg, const ladrc_bf_rate_params_t *p, int i, float dt_s)
{
    const ladrc_real_t b0 = (ladrc_real_t)p->b0_rad_s2_per_pidsum[i];
    ladrc_axis_config_default(cfg, LADRC_VARIANT_RATE_ADRC, (ladrc_real_t)dt_s, LADRC_R(1.0) / b0);
    cfg->b0 = b0; /* exactly, not 1 / (1 / b0) */
    cfg->radrc_acro = 1u;
    cfg->radrc_kp_per_s = (ladrc_real_t)p->k_w_per_s[i];
    cfg->wo_rad_s = (ladrc_real_t)p->wo_rad_s[i];
    cfg->radrc_rate_max_rad_s = cfg->rate_limit_rad_s;
    cfg->u_min_Nm = -(ladrc_real_t)p->pidsum_limit[i];
    cfg->u_max_Nm = (ladrc_real_t)p->pidsum_limit[i];
    cfg->motor_tau_s = (ladrc_real_t)p->motor_tau_s;
    cfg->delay_ticks = p->delay_ticks;
}

ladrc_status_t ladrc_bf_rate_init(ladrc_bf_rate_t *rc, const ladrc_bf_rate_params_t *params, float dt_s)
{
    if (rc == NULL || params == NULL) {
        return LADRC_ERR_NULL;
    }
    memset(rc, 0, sizeof *rc);
    rc->params = *params;
    rc->dt_s = dt_s;
    for (int i = 0; i < LADRC_BF_AXES; ++i) {
        rc->faults[i] = LADRC_FAULT_STATE; /* until ready */
        /* a positive pidSum accelerates Betaflight's gyro positively (its
         * PID's own sign), so b0 > 0; checked before the defaults divide by it */
        const float b0 = params->b0_rad_s2_per_pidsum[i];
        if (!(b0 > 0.0f && ladrc_is_finite((ladrc_real_t)b0))) {
            return LADRC_ERR_B0;
        }
        /* an infinite pidSum bound would pass the axis's check as "no
         * bound"; the mixer has one: refused with the command-bound status */
        if (!(params->pidsum_limit[i] > 0.0f && ladrc_is_finite((ladrc_real_t)params->pidsum_limit[i]))) {
            return LADRC_ERR_U_LIMITS;
        }
        ladrc_axis_config_t cfg;
        axis_config(&cfg, params, i, dt_s);
        const ladrc_status_t status = ladrc_axis_init(&rc->axis[i], &cfg);
        if (status != LADRC_OK) {
            return status;
        }
    }
    for (int i = 0; i < LADRC_BF_AXES; ++i) {
        rc->faults[i] = LADRC_FAULT_NONE;
    }
    rc->ready = 1u;
    return LADRC_OK;
}

void ladrc_bf_rate_reset(ladrc_bf_rate_t *rc)
{
    if (rc == NULL || !rc->ready) {
        return;
    }
    for (int i = 0; i < LADRC_BF_AXES; ++i) {
        ladrc_axis_reset(&rc->axis[i], LADRC_R(0.0));
        rc->pidsum[i] = 0.0f;
        rc->faults[i] = LADRC_FAULT_NONE;
    }
}

float ladrc_bf_rate_step(ladrc_bf_rate_t *rc, int axis, float setpoint_deg_s, float gyro_deg_s, float dt_s)
{
    if (rc == NULL || !axis_in_range(axis)) {
        return 0.0f;
    }
    if (rc->ready && !(fabsf(dt_s - rc->dt_s) <= LOOP_TIME_CHANGE * rc->dt_s)) {
        const ladrc_bf_rate_params_t params = rc->params;
        (void)ladrc_bf_rate_init(rc, &params, dt_s); /* not ready on a refusal: held below */
    }
    if (!rc->ready) {
        rc->faults[axis] = LADRC_FAULT_STATE;
        return rc->pidsum[axis];
    }
    const ladrc_real_t rate_rad_s = ladrc_bf_rad_s(gyro_deg_s);
    ladrc_real_t command = LADRC_R(0.0);
    rc->faults[axis] =
        ladrc_axis_step(&rc->axis[axis], ladrc_bf_rad_s(setpoint_deg_s), LADRC_R(0.0), &rate_rad_s, &command);
    /* The axis holds its command on a bad input (axis.h); a finite command is
     * the only one that leaves here. */
    if (ladrc_is_finite(command)) {
        rc->pidsum[axis] = (float)command;
    }
    return rc->pidsum[axis];
}

ladrc_fault_t ladrc_bf_rate_faults(const ladrc_bf_rate_t *rc, int axis)
{
    return (rc == NULL || !axis_in_range(axis)) ? LADRC_FAULT_STATE : rc->faults[axis];
}
