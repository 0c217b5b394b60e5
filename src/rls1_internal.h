/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The one-parameter RLS's update (rls.h, ladrc_rls1_t) for the LP
 * estimator's tick: the settled update inline, the full one in rls.c. Not
 * installed.
 */
#ifndef LADRC_RLS1_INTERNAL_H
#define LADRC_RLS1_INTERNAL_H

#include "ladrc/rls.h"

/* rls.c: the full update (forgetting, gain, P, the bound; settles once P
 * stays as it was) on a finite y, and P's restart. */
ladrc_fault_t rls1_full_update(ladrc_rls1_t *rls, ladrc_real_t y);
void rls1_restart_p(ladrc_rls1_t *rls);

/* ladrc_rls1_update without its NULL test. */
static inline ladrc_fault_t rls1_update(ladrc_rls1_t *rls, ladrc_real_t y)
{
    if (!ladrc_is_finite(y)) {
        rls->faults = LADRC_FAULT_INPUT;
        return rls->faults;
    }
    if (!rls->settled) {
        return rls1_full_update(rls, y);
    }
    /* P at its fixed point: the full update's gain, forgetting and P again. */
    const ladrc_real_t theta = rls->theta + rls->gain * ((y - rls->theta) * rls->inv_beta);
    if (!ladrc_is_finite(theta)) {
        rls1_restart_p(rls);
        rls->faults = LADRC_FAULT_STATE;
        return rls->faults;
    }
    rls->theta = theta;
    rls->faults = LADRC_FAULT_NONE;
    return rls->faults;
}

#endif /* LADRC_RLS1_INTERNAL_H */
