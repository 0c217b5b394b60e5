/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file td.c
 * @brief Han's tracking differentiator (fhan), written from the discrete
 *        synthesis function of Han 2009, "From PID to Active Disturbance
 *        Rejection Control".
 */
#include "ladrc/td.h"
#include "require.h"

#include <stddef.h>

/* fhan on validated accel > 0 and h0_s > 0, with d = accel h0 and d0 = h0 d. */
static ladrc_real_t fhan(ladrc_real_t x1, ladrc_real_t x2, ladrc_real_t accel, ladrc_real_t h0_s, ladrc_real_t d,
                         ladrc_real_t d0)
{
    const ladrc_real_t y = x1 + h0_s * x2; /* position error predicted one h0 ahead */
    ladrc_real_t a;
    ladrc_real_t u;

    /* d: speed change over one h0 at full acceleration; d0: half-width of the
     * linear zone around the switching curve. */
    if (ladrc_fabs(y) > d0) {
        /* Follow the switching curve. Here 8 accel |y| > 8 d^2, so a0 > 3 d and
         * a0 - d does not cancel. An overflow makes a0 and a infinite, which
         * saturates below: full acceleration is the right answer that far out. */
        const ladrc_real_t a0 = ladrc_sqrt(d * d + LADRC_R(8.0) * accel * ladrc_fabs(y));
        a = x2 + LADRC_R(0.5) * (a0 - d) * ladrc_sign(y);
    } else {
        a = x2 + y / h0_s;
    }

    if (ladrc_fabs(a) > d) {
        u = -accel * ladrc_sign(a);
    } else {
        /* -accel a / d equals -a / h0 (d = accel h0): no division by d, which
         * underflows to 0 when accel h0 is tiny. The clamp keeps rounding from
         * lifting |u| above accel. */
        u = -ladrc_clamp(a / h0_s, -accel, accel);
    }

    /* NaN only comes from non-finite inputs (inf - inf), or from the all-zero
     * instance a rejected init leaves (0 / 0); push nothing then. */
    return ladrc_is_finite(u) ? u : LADRC_R(0.0);
}

ladrc_real_t ladrc_fhan(ladrc_real_t x1, ladrc_real_t x2, ladrc_real_t accel, ladrc_real_t h0_s)
{
    /* No meaningful bound to respect: the safe acceleration is none. */
    if (!ladrc_is_positive(accel) || !ladrc_is_positive(h0_s)) {
        return LADRC_R(0.0);
    }
    return fhan(x1, x2, accel, h0_s, accel * h0_s, h0_s * (accel * h0_s));
}

static void write_held(const ladrc_td_t *td, ladrc_ref_t *out)
{
    if (out != NULL) {
        out->r = td->x1;
        out->dr = td->x2;
        out->ddr = LADRC_R(0.0);
    }
}

ladrc_status_t ladrc_td_init(ladrc_td_t *td, const ladrc_td_config_t *cfg)
{
    const ladrc_td_t zero = {0};

    if (td == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    /* A rejected config leaves an all-zero instance: its steps output 0 and never move. */
    *td = zero;
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (!ladrc_is_positive(cfg->accel_rad_s2)) {
        return LADRC_ERR_TD_ACCEL_RAD_S2;
    }
    /* The comparison is false for NaN, so NaN is rejected too. */
    if (!ladrc_is_finite(cfg->h0_s) || !(cfg->h0_s >= cfg->dt_s)) {
        return LADRC_ERR_TD_H0_S;
    }
    td->dt_s = cfg->dt_s;
    td->accel_rad_s2 = cfg->accel_rad_s2;
    td->h0_s = cfg->h0_s;
    td->d = cfg->accel_rad_s2 * cfg->h0_s;
    td->d0 = cfg->h0_s * td->d;
    return LADRC_OK;
}

void ladrc_td_reset(ladrc_td_t *td, ladrc_real_t r_rad)
{
    LADRC_REQUIRE_VOID(td != NULL);
    td->faults = LADRC_FAULT_NONE;
    if (ladrc_is_finite(r_rad)) {
        td->x1 = r_rad;
    } else {
        /* Never let a bad sample into the state: restart where we are. */
        td->faults = LADRC_FAULT_INPUT;
    }
    td->x2 = LADRC_R(0.0);
    td->a = LADRC_R(0.0);
}

ladrc_fault_t ladrc_td_step(ladrc_td_t *td, ladrc_real_t r_rad, ladrc_ref_t *out)
{
    ladrc_real_t a;
    ladrc_real_t x1_next;
    ladrc_real_t x2_next;

    LADRC_REQUIRE(td != NULL, LADRC_FAULT_STATE);
    if (!ladrc_is_finite(r_rad)) {
        td->faults = LADRC_FAULT_INPUT;
        write_held(td, out);
        return td->faults;
    }

    /* x1 - r may overflow to +-inf for huge finite inputs; fhan saturates then. */
    a = fhan(td->x1 - r_rad, td->x2, td->accel_rad_s2, td->h0_s, td->d, td->d0);
    x1_next = td->x1 + td->dt_s * td->x2;
    x2_next = td->x2 + td->dt_s * a;
    if (!ladrc_all_finite2(x1_next, x2_next)) {
        td->faults = LADRC_FAULT_STATE;
        write_held(td, out);
        return td->faults;
    }

    td->x1 = x1_next;
    td->x2 = x2_next;
    td->a = a;
    td->faults = LADRC_FAULT_NONE;
    if (out != NULL) {
        out->r = x1_next;
        out->dr = x2_next;
        out->ddr = a;
    }
    return td->faults;
}
