/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * Dryden turbulence, MIL-F-8785C low-altitude model (below 1000 ft).
 *
 * Three gust components: u along the mean wind, v across it, w down. At the
 * altitude h (ft, clamped to the standard's 10..1000 ft):
 *   scale lengths  L_w = h,  L_u = L_v = h / (0.177 + 0.000823 h)^1.2   (ft)
 *   intensities    sigma_w = 0.1 W20,  sigma_u = sigma_v = sigma_w / (0.177 + 0.000823 h)^0.4
 * with W20, the wind speed at 20 ft, 15 kt (light), 30 kt (moderate) or
 * 45 kt (severe); SIM_TURB_SIGMA gives sigma_w directly and keeps the
 * ratios. The one-sided PSDs over the temporal frequency omega (rad/s),
 * frozen field swept past at the speed V:
 *   Phi_u = sigma_u^2 (2 L_u / (pi V)) / (1 + (L_u omega / V)^2)
 *   Phi_v = sigma_v^2 (L_v / (pi V)) (1 + 3 (L_v omega / V)^2) / (1 + (L_v omega / V)^2)^2
 *   Phi_w as Phi_v with L_w, sigma_w
 * each integrating to its sigma^2 over omega in [0, inf).
 *
 * Hover rule: the frozen-field (Taylor) assumption needs the air to sweep
 * past faster than the eddies change; near hover it does not. The model
 * sweeps at V = max(|mean wind|, sigma_u): with little mean wind the eddies
 * carry themselves past at about their own gust speed, so the correlation
 * time stays L_u / sigma_u instead of growing without bound.
 *
 * Exact discretisation: the shaping filters (1 / (1 + tau s) for u,
 * (1 + sqrt3 tau s) / (1 + tau s)^2 for v and w, tau = L / V) are sampled
 * at sample_dt_s with their transition matrices and the discrete noise
 * covariance Q = P - Phi P Phi^T of the stationary covariance P, and start
 * from a draw of P: the samples have the continuous process's statistics
 * exactly, from the first. Between samples the gusts are linear in time.
 * Seeded: one seed gives the same air on every host.
 *
 * No heap, no stdio, no globals.
 */
#ifndef LADRC_SIM_TURBULENCE_H
#define LADRC_SIM_TURBULENCE_H

#include <stdint.h>

#include "rng.h"

/* The standard's low-altitude model ends at 1000 ft. */
#define SIM_TURB_ALTITUDE_MAX_M 304.8
/* and starts at 10 ft: below, the 10 ft values. */
#define SIM_TURB_ALTITUDE_MIN_M 3.048

typedef enum { SIM_TURB_OFF, SIM_TURB_LIGHT, SIM_TURB_MODERATE, SIM_TURB_SEVERE, SIM_TURB_SIGMA } sim_turb_level_t;

typedef struct {
    sim_turb_level_t level;
    double sigma_m_s;     /* SIM_TURB_SIGMA: the vertical intensity sigma_w (m/s), > 0 */
    double altitude_m;    /* > 0, <= SIM_TURB_ALTITUDE_MAX_M */
    double mean_wind_m_s; /* steady wind speed, >= 0: sets V with the hover rule */
    double sample_dt_s;   /* spacing of the samples (s), > 0 */
} sim_turb_config_t;

typedef struct {
    sim_rng_t rng;
    double dt_s;
    double sigma_m_s[3];  /* u, v, w */
    double scale_m[3];    /* L_u, L_v, L_w */
    double speed_m_s;     /* V */
    double phi[3][2][2];  /* transition per sample (u uses [0][0][0]) */
    double chol[3][2][2]; /* lower Cholesky factor of the noise covariance per sample */
    double x[3][2];       /* shaping-filter states */
    double sample[2][3];  /* the gusts at samples k and k + 1 */
    uint64_t k;           /* index of sample[0] */
} sim_turb_t;

/* Returns 0, or -1 (t untouched) when a setting is out of its range or
 * level is SIM_TURB_OFF. */
int sim_turb_init(sim_turb_t *t, const sim_turb_config_t *cfg, uint64_t seed);

/* The gusts (m/s) at time t_s: along the mean wind, across it (to its
 * right), down. Times must not decrease from call to call; a time before the
 * latest sample interval gives that interval's start. */
void sim_turb_gust_at(sim_turb_t *t, double t_s, double gust_m_s[3]);

/* The analytic one-sided PSD of component axis (0 u, 1 v, 2 w) at omega
 * (rad/s), in (m/s)^2 per rad/s. */
double sim_turb_psd(const sim_turb_t *t, int axis, double omega_rad_s);

#endif
