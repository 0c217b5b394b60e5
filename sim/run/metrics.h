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
double sim_stat_std(const sim_stat_t *s); /* population standard deviation */
double sim_stat_rms(const sim_stat_t *s);

/* The corner of the measured command noise (Hz), the analysis's default. */
#define SIM_CMD_NOISE_CORNER_HZ 20.0

/* settle_s of an axis whose error is outside the band at the settle window's last sample */
#define SIM_NOT_SETTLED (-1.0)

/* One attitude run's results. Angles in deg, disturbances in rad/s^2,
 * rotor speeds squared in rad^2/s^2. */
typedef struct {
    sim_stat_t error_deg[3];  /* Table 4: reference - angle over the error window */
    double max_error_deg[3];  /* Table 5: over the error window */
    double settle_s[3];       /* Table 5: from settle_after_s until |error| stays in the band;
                                   * SIM_NOT_SETTLED: still outside it at the window's last sample */
    double band_deg[3];       /* Table 5: max |error| over the steady window */
    sim_stat_t steady_deg[3]; /* Table 5: the error over the steady window (its RMS) */
    sim_stat_t dist_error[3]; /* Table 6: total-disturbance estimate - truth over the error window */
    sim_stat_t rotor_w2[4];   /* Table 7: over the whole run */
    int has_estimate;         /* 0 for PID: no disturbance estimate */
    int finite;               /* 0 if the plant's state turned non-finite */
    /* Divergence (runner.h): the run stopped at diverged_at_s, and none of the
     * statistics above is a result of the run (the tables print "diverged"). */
    int diverged;              /* 1: |error| beyond diverge_limit_deg or a non-finite state */
    double diverged_at_s;      /* the instant it was seen */
    int diverged_axis;         /* 0..2; -1: a rotor's w^2 turned non-finite */
    double diverged_error_deg; /* |error| on that axis then; NaN when non-finite */
    /* The reference outran the controller's shaper (runner.h): |error| beyond
     * diverge_limit_deg while the controller stayed near its shaped
     * reference; the run went on. First instant (NaN: never) and the largest
     * |error| (deg) per axis. */
    double reference_outran_at_s[3];
    double reference_outran_deg[3];
    /* tune = margins found no gains that fly the check flight: the
     * controller was not flown (the tables print "untunable"). */
    int untunable;
    long faults; /* controller ticks with a fault flag */
    /* Command noise: the controller's torque command (before [excitation]'s
     * chirp) through a second-order Butterworth high-pass at
     * SIM_CMD_NOISE_CORNER_HZ, run over the whole flight; its RMS over the
     * error window (N m), per axis. NaN when the corner is not below the
     * Nyquist frequency. The predicted counterpart: margins.h cmd_noise_Nm. */
    sim_stat_t cmd_hp_Nm[3];
    double cmd_noise_Nm[3];
    double wall_s; /* wall time of the run (of its lockstep group, runner.h) */
} sim_metrics_t;

/* Table 3: derivative-error statistics of the two reference shapers. */
typedef struct {
    sim_stat_t levant_error, td_error;
    double wall_s;
} sim_diff_metrics_t;

#endif
