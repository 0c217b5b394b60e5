/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The paper's metrics (Tables 3-7), accumulated tick by tick.
 */
#ifndef LADRC_SIM_METRICS_H
#define LADRC_SIM_METRICS_H

/* Running mean and variance (Welford), plus the largest |x|. */
typedef struct {
    long n;
    double mean, m2, max_abs;
} sim_stat_t;

void sim_stat_add(sim_stat_t *s, double x);
double sim_stat_std(const sim_stat_t *s);  /* population standard deviation */
double sim_stat_rms(const sim_stat_t *s);

/* One attitude run's results. Angles in deg, disturbances in rad/s^2,
 * rotor speeds squared in rad^2/s^2. */
typedef struct {
    sim_stat_t error_deg[3];      /* Table 4: reference - angle over the error window */
    double max_error_deg[3];      /* Table 5: over the error window */
    double settle_s[3];           /* Table 5: from settle_after_s until |error| stays in the band; -1 never */
    double band_deg[3];           /* Table 5: max |error| over the steady window */
    sim_stat_t dist_error[3];     /* Table 6: total-disturbance estimate - truth over the error window */
    sim_stat_t rotor_w2[4];       /* Table 7: over the whole run */
    int has_estimate;             /* 0 for PID: no disturbance estimate */
    int finite;                   /* 0 if the run produced a non-finite angle */
    long faults;                  /* controller ticks with a fault flag */
    double wall_s;                /* CPU-independent wall time of the run */
} sim_metrics_t;

/* Table 3: derivative-error statistics of the two reference shapers. */
typedef struct {
    sim_stat_t levant_error, td_error;
    double wall_s;
} sim_diff_metrics_t;

#endif
