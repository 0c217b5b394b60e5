/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file levant.c
 * @brief Levant's 3rd-order robust exact differentiator (non-recursive form)
 *        with an implicit, an HD and an explicit Euler discretisation.
 */
#include "ladrc/levant.h"
#include "require.h"

#include <stddef.h>

/* Newton iterations on the implicit step's quartic: 3 at most (the last one
 * only confirms) from the set-valued band up to |q| = 1e30, for Levant's
 * coefficients (L = 1 to 1e6) and for the paper's gains (measured). The cap
 * only bounds the worst case (gains skewed by 1e4 need about 20); hitting it
 * leaves u above the root: a finite, slightly larger correction. */
#define LEVANT_NEWTON_MAX 16

/* Newton's error after a step of relative size t is about c t^2 with
 * c = u P''/(2 P') <= 3/2 for this quartic: stopping once t <= 2^-12
 * (2^-27 in double) leaves at most 1.5 * 2^-24 (2^-54), the last bit of u,
 * and saves the iterations that would only move rounding. */
#ifdef LADRC_REAL_DOUBLE
#define LEVANT_NEWTON_REL_STEP LADRC_R(7.450580596923828e-9)
#else
#define LEVANT_NEWTON_REL_STEP LADRC_R(2.44140625e-4)
#endif

/* u >= 0 with P(u) = u^4 + a3 u^3 + a2 u^2 + a1 u = d, for d > 0 and a1,
 * a2 > 0. Each term alone bounds u: u <= b_i with 1/b_i = c_i, here
 * c4 = d^(-1/4), c2 = (a2/d)^(1/2) and c1 = a1/d (the cubic's needs a cube
 * root). 1/max(c_i) is the smallest bound; 1/sum(c_i) is below the root
 * unless the cubic term weighs; both are the root when one term dominates.
 * The start 1/(3/4 |c|_2 + 1/4 sum(c_i)) lies between them, closest to
 * the root for balanced terms (measured). P is convex and increasing on
 * u >= 0: from above Newton descends monotonically onto the root, from
 * below one step lands above it. A NaN step (P overflowing near the top of
 * the range) ends with a NaN root, which the caller's check refuses. */
static ladrc_real_t quartic_root(ladrc_real_t d, ladrc_real_t a3, ladrc_real_t a2, ladrc_real_t a1)
{
    const ladrc_real_t inv_d = LADRC_R(1.0) / d;
    const ladrc_real_t c4_sq = ladrc_sqrt(inv_d);
    const ladrc_real_t c2_sq = a2 * inv_d;
    const ladrc_real_t c1 = a1 * inv_d;
    const ladrc_real_t sum = ladrc_sqrt(c4_sq) + ladrc_sqrt(c2_sq) + c1;
    ladrc_real_t u = LADRC_R(4.0) / (LADRC_R(3.0) * ladrc_sqrt(c4_sq + c2_sq + c1 * c1) + sum);
    int i;

    for (i = 0; i < LEVANT_NEWTON_MAX; ++i) {
        const ladrc_real_t p = (((u + a3) * u + a2) * u + a1) * u - d;
        const ladrc_real_t dp = ((LADRC_R(4.0) * u + LADRC_R(3.0) * a3) * u + LADRC_R(2.0) * a2) * u + a1;
        const ladrc_real_t step = p / dp;
        u -= step;
        if (!(ladrc_fabs(step) > LEVANT_NEWTON_REL_STEP * u)) {
            break;
        }
    }
    return u;
}

ladrc_status_t ladrc_levant_init(ladrc_levant_t *lev, const ladrc_levant_config_t *cfg)
{
    const ladrc_levant_t zero = {0};
    ladrc_real_t h;
    ladrc_real_t k3;
    ladrc_real_t k2;
    ladrc_real_t k1;
    ladrc_real_t k0;
    ladrc_real_t g[4];
    int i;

    if (lev == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    /* A rejected config leaves an all-zero instance, which every step refuses. */
    *lev = zero;
    h = cfg->dt_s;
    if (!ladrc_dt_is_valid(h)) {
        return LADRC_ERR_DT_S;
    }
    if ((unsigned)cfg->method > (unsigned)LADRC_LEVANT_EULER) {
        return LADRC_ERR_LEVANT_METHOD;
    }
    if (cfg->gains == LADRC_LEVANT_GAINS_LIPSCHITZ) {
        const ladrc_real_t lip = cfg->lipschitz_rad_s4;
        ladrc_real_t q;
        if (!ladrc_is_positive(lip)) {
            return LADRC_ERR_LEVANT_LIPSCHITZ;
        }
        q = ladrc_sqrt(ladrc_sqrt(lip)); /* L^(1/4) */
        k3 = LADRC_R(3.0) * q;
        k2 = LADRC_R(4.16) * q * q;
        k1 = LADRC_R(3.06) * q * q * q;
        k0 = LADRC_R(1.1) * lip;
    } else if (cfg->gains == LADRC_LEVANT_GAINS_EXPLICIT) {
        const ladrc_real_t l[4] = {cfg->l1, cfg->l2, cfg->l3, cfg->l4};
        ladrc_real_t c;
        for (i = 0; i < 4; ++i) {
            if (!ladrc_is_positive(l[i])) {
                /* LADRC_ERR_LEVANT_L1 .. _L4 are consecutive in types.h. */
                return (ladrc_status_t)(LADRC_ERR_LEVANT_L1 + i);
            }
        }
        /* Recursive to non-recursive form (see levant.h). */
        c = ladrc_cbrt(l[0]);
        k3 = l[0];
        k2 = l[1] * c * c;
        k1 = l[2] * ladrc_sqrt(l[1]) * c;
        k0 = l[3];
    } else {
        return LADRC_ERR_LEVANT_GAINS;
    }

    /* The step multiplies the per-sample gains by up to h^3: the same
     * products, in the same order, must stay finite and non-zero (the
     * implicit step divides by h^3 g0, h g2 and h^2 g1). */
    g[3] = h * k3;
    g[2] = h * k2;
    g[1] = h * k1;
    g[0] = h * k0;
    {
        const ladrc_real_t used[4] = {g[3], h * g[2], h * h * g[1], h * h * h * g[0]};
        for (i = 0; i < 4; ++i) {
            if (!ladrc_is_positive(used[i])) {
                return LADRC_ERR_LEVANT_RANGE;
            }
        }
    }
    lev->g3 = g[3];
    lev->g2 = g[2];
    lev->g1 = g[1];
    lev->g0 = g[0];
    lev->h_s = h;
    lev->method = (uint8_t)cfg->method;
    ladrc_levant_reset(lev, LADRC_R(0.0));
    return LADRC_OK;
}

void ladrc_levant_reset(ladrc_levant_t *lev, ladrc_real_t r_rad)
{
    LADRC_REQUIRE_VOID(lev != NULL);
    lev->faults = LADRC_FAULT_NONE;
    if (ladrc_is_finite(r_rad)) {
        lev->r_last = r_rad;
    } else {
        /* Never let a bad sample into the state: restart where we are. */
        lev->r_last += lev->w;
        lev->faults = LADRC_FAULT_INPUT;
    }
    lev->w = LADRC_R(0.0);
    lev->z1 = LADRC_R(0.0);
    lev->z2 = LADRC_R(0.0);
    lev->z3 = LADRC_R(0.0);
}

void ladrc_levant_get_ref(const ladrc_levant_t *lev, ladrc_ref_t *out)
{
    LADRC_REQUIRE_VOID(lev != NULL && out != NULL);
    out->r = lev->r_last + lev->w;
    out->dr = lev->z1;
    out->ddr = lev->z2;
}

ladrc_real_t ladrc_levant_get_dddr(const ladrc_levant_t *lev)
{
    LADRC_REQUIRE(lev != NULL, LADRC_R(0.0));
    return lev->z3;
}

/* Keeps the state and writes the held estimate: an input fault when the
 * sample was not finite, else a state fault. */
static ladrc_fault_t refuse(ladrc_levant_t *lev, ladrc_real_t r_rad, ladrc_ref_t *out)
{
    const ladrc_fault_t fault = ladrc_is_finite(r_rad) ? LADRC_FAULT_STATE : LADRC_FAULT_INPUT;
    lev->faults = fault;
    if (out != NULL) {
        ladrc_levant_get_ref(lev, out);
    }
    return fault;
}

ladrc_fault_t ladrc_levant_step(ladrc_levant_t *lev, ladrc_real_t r_rad, ladrc_ref_t *out)
{
    ladrc_real_t h;
    ladrc_real_t e_prior;
    ladrc_real_t dz0;
    ladrc_real_t u;
    ladrc_real_t u2;
    ladrc_real_t s;
    ladrc_real_t t2;
    ladrc_real_t t3;
    ladrc_real_t w;
    ladrc_real_t z1;
    ladrc_real_t z2;
    ladrc_real_t z3;
    ladrc_real_t r_est;

    LADRC_REQUIRE(lev != NULL, LADRC_FAULT_STATE);
    /* h is 0 in an instance never initialised, or rejected: its update is
     * computed (finite work, whatever it gives) and refused below. */
    h = lev->h_s;

    /* Old estimate of r minus the new sample. Consecutive samples are close,
     * so their difference is (nearly) exact and the small offset w keeps all
     * its digits: the error is not the difference of two large numbers. */
    e_prior = lev->w + (lev->r_last - r_rad);
    /* Prediction over one step: z0 moves by dz0; z1, z2 and z3 become z1..z3. */
    if (lev->method == LADRC_LEVANT_EULER) {
        dz0 = h * lev->z1;
        z1 = lev->z1 + h * lev->z2;
    } else {
        dz0 = h * (lev->z1 + h * (LADRC_R(0.5) * lev->z2 + h * (LADRC_R(1.0) / LADRC_R(6.0)) * lev->z3));
        z1 = lev->z1 + h * (lev->z2 + LADRC_R(0.5) * h * lev->z3);
    }
    z2 = lev->z2 + h * lev->z3;
    z3 = lev->z3;

    if (lev->method == LADRC_LEVANT_IMPLICIT) {
        /* Predicted error q; the new error e solves e + c(e) = q (levant.h),
         * with u = |e|^(1/4) and s the (set-valued) sign. */
        const ladrc_real_t q = e_prior + dz0;
        const ladrc_real_t a0 = h * h * h * lev->g0;
        if (ladrc_fabs(q) <= a0) {
            /* The sign term alone absorbs q: e = 0 and s in [-1, 1]. */
            u = LADRC_R(0.0);
            s = (q != LADRC_R(0.0)) ? q / a0 : LADRC_R(0.0);
        } else {
            s = q / ladrc_fabs(q); /* exactly +-1: q != 0 here */
            u = quartic_root(ladrc_fabs(q) - a0, lev->g3, h * lev->g2, h * h * lev->g1);
        }
        u2 = u * u;
        t3 = lev->g0 * s;
        t2 = lev->g1 * u * s;
        w = s * u2 * u2;
        z1 -= lev->g2 * u2 * s + h * (t2 + (LADRC_R(11.0) / LADRC_R(6.0)) * h * t3);
        z2 -= t2 + LADRC_R(2.0) * h * t3;
    } else {
        /* Explicit: corrections from the prediction error e = e_prior. */
        u2 = ladrc_sqrt(ladrc_fabs(e_prior));
        u = ladrc_sqrt(u2);
        s = ladrc_sign(e_prior);
        t3 = lev->g0 * s;
        t2 = lev->g1 * u * s;
        w = e_prior + dz0 - lev->g3 * u2 * u * s;
        z1 -= lev->g2 * u2 * s;
        z2 -= t2;
    }
    z3 -= t3;
    /* Non-finite whenever w or r_rad is: a bad sample is caught here too,
     * and refuse() tells it from an overflowing update. */
    r_est = r_rad + w;
    if (!(h > LADRC_R(0.0)) || !ladrc_all_finite4(r_est, z1, z2, z3)) {
        return refuse(lev, r_rad, out);
    }

    lev->w = w;
    lev->r_last = r_rad;
    lev->z1 = z1;
    lev->z2 = z2;
    lev->z3 = z3;
    lev->faults = LADRC_FAULT_NONE;
    if (out != NULL) {
        out->r = r_est;
        out->dr = z1;
        out->ddr = z2;
    }
    return LADRC_FAULT_NONE;
}
