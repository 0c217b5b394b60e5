/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The plant of each axis identified from a flight log's gyro and command:
 *
 *   (w[k] - w[k-1]) / dt = b0 phi(k - 1 - d) - a (w[k] + w[k-1]) / 2 + c
 *
 * w the gyro (rad/s), u the log's normalised command, phi(j) the mean over
 * tick j's hold of u through a first-order lag of time constant tau (the
 * motors), d whole ticks of delay between a command and the first gyro
 * sample it moves beyond the hold itself; a the rate damping (1/s), c the
 * fit's intercept (rad/s^2; the band-pass leaves no constant disturbance).
 * Both sides go through the same band-pass (which keeps the relation, cuts
 * the gyro's differentiated noise and the rotors' vibration lines above, and
 * the disturbances the loop cancels below), then least squares for (b0, a,
 * c) at every (tau, d) of a grid: a coarse pass, a fine pass about its best,
 * and a pass at the profile's vertex for the lag, which also gives the
 * residuals.
 *
 * Intervals (95 %): every candidate (tau, d) whose residual sum of squares
 * lies within the larger of the chi-square(1) threshold, scaled by the
 * sandwich (Newey-West, Bartlett) variance ratio and by PROFILE_SAFETY, and
 * PROFILE_BIAS_SHARE of the best's (ident_result.c) is consistent with the
 * log: the lag's and delay's intervals span that set, b0's spans its b0s
 * widened by the larger of b0's sandwich and split-window (8 blocks)
 * half-widths, and spans the instrumental-variable b0's interval too (the
 * setpoint as the instrument: b0_iv). Warnings flag what the log cannot
 * tell (SIM_IDENT_WARN_*), "b0 not told" among them
 * (sim_ident_b0_told).
 *
 * Memory is fixed (grid sums and short rings): a log of any length is
 * streamed through each pass.
 */
#ifndef LADRC_SIM_IDENT_H
#define LADRC_SIM_IDENT_H

#include "run/spectrum.h"

#define SIM_IDENT_COARSE_TAUS 40 /* 0, then geometric from 0.5 ms to lag_max_s */
#define SIM_IDENT_FINE_TAUS 33   /* between the coarse best's neighbours */
#define SIM_IDENT_MAX_DELAY 40   /* ticks */
#define SIM_IDENT_FINE_DELAYS 7  /* the coarse best's delay +- 3 */
#define SIM_IDENT_MAX_HAC_LAGS 256

/* What the log cannot tell (bits of sim_ident_axis_t.warnings). */
enum {
    SIM_IDENT_WARN_FEW = 1u << 0,        /* fewer than SIM_IDENT_MIN_SAMPLES samples fitted */
    SIM_IDENT_WARN_SIGN = 1u << 1,       /* b0 <= 0: command and gyro disagree in sign */
    SIM_IDENT_WARN_B0_WIDE = 1u << 2,    /* b0's interval wider than +-SIM_IDENT_B0_REL_MAX */
    SIM_IDENT_WARN_LAG_WIDE = 1u << 3,   /* the lag's interval wider than SIM_IDENT_LAG_REL_MAX or 4 ms */
    SIM_IDENT_WARN_DELAY_WIDE = 1u << 4, /* the delay not told to the tick */
    SIM_IDENT_WARN_LOW_FIT = 1u << 5,    /* R^2 below SIM_IDENT_R2_MIN */
    SIM_IDENT_WARN_EDGE = 1u << 6,       /* the best fit at the edge of the grid */
    SIM_IDENT_WARN_NARROW = 1u << 7, /* the command's share above the motors' corner under SIM_IDENT_BAND_SHARE_MIN */
    SIM_IDENT_WARN_B0_NOT_TOLD = 1u << 8 /* sim_ident_b0_told() is 0: the log cannot tell b0 */
};
#define SIM_IDENT_WARN_LAST SIM_IDENT_WARN_B0_NOT_TOLD
#define SIM_IDENT_MIN_SAMPLES 2000
#define SIM_IDENT_PREFILTER_MAX_HZ 40.0 /* the default corner: a chirp's top */
#define SIM_IDENT_PREFILTER_MIN_HZ 10.0 /* the lowest a vibration line may push it */
/* The band's low edge: on a chirp flight in turbulence (scenarios/logs), b0
 * of roll came out 25 % low without it (the loop's answer to the gusts taken
 * for the plant's), 4 % low with it; 2 and 4 Hz gave no better. */
#define SIM_IDENT_HIGHPASS_HZ 1.0
#define SIM_IDENT_B0_REL_MAX 0.10
/* b0 is not told when its interval's upper end is more than this times its
 * lower end (or the lower end is not > 0): a tuning for one end would then
 * put the loop's gain off by more than half its margin of 6 dB at the other. */
#define SIM_IDENT_B0_TOLD_RATIO 2.0
#define SIM_IDENT_LAG_REL_MAX 0.5
#define SIM_IDENT_R2_MIN 0.5
/* Lag and delay part only where the lag's phase differs from a delay's:
 * above the motors' corner 1 / (2 pi tau), which must lie in the band
 * fitted (below the prefilter's corner). The command's rms share there (up
 * to the prefilter's corner) was 0.75-0.91 for 1-40 Hz chirps and 0.06-0.41
 * for pilots' steps and sweeps on the same airframes. */
#define SIM_IDENT_BAND_SHARE_MIN 0.5

typedef struct {
    double dt_s; /* the samples' period */
    double
        prefilter_hz; /* the low-pass of both sides (fourth order); 0: min(SIM_IDENT_PREFILTER_MAX_HZ, 0.08 / dt_s) */
    double lag_max_s; /* largest motor lag searched; 0: 0.2 s */
    int delay_max_ticks; /* largest delay searched; < 0: the ticks of 40 ms, at most SIM_IDENT_MAX_DELAY */
} sim_ident_options_t;

typedef struct {
    long long samples;                /* fitted (after the low-pass's settling) */
    double b0, b0_lo, b0_hi;          /* rad/s^2 per unit of command; 95 % interval */
    double lag_s, lag_lo_s, lag_hi_s; /* motor lag tau */
    int delay_ticks, delay_lo_ticks, delay_hi_ticks;
    double damping_per_s;  /* a */
    double r2;             /* of the filtered fit */
    double command_rms;    /* the filtered command's rms about its mean: the excitation */
    double variance_ratio; /* sandwich over ordinary variance of b0 (>= 1 with coloured residuals) */
    double band_share;     /* the command's rms share above the motors' corner (SIM_IDENT_WARN_NARROW) */
    /* b0 by instrumental variables (the logged rate setpoint, exogenous in
     * closed loop, through the same lag and delay as the instrument of the
     * command): free of the bias the gyro's noise brings into the command;
     * its 95 % interval from the split-window variance. NaN without a
     * setpoint in the log. b0_lo and b0_hi span this interval too. */
    double b0_iv, b0_iv_lo, b0_iv_hi;
    unsigned warnings; /* SIM_IDENT_WARN_* */
} sim_ident_axis_t;

typedef struct sim_ident sim_ident_t;

/* A new identification (heap); NULL when out of memory or dt_s is not > 0. */
sim_ident_t *sim_ident_new(const sim_ident_options_t *opt);
void sim_ident_free(sim_ident_t *id);

/* Starts the next pass over the log: returns its number (1, 2, 3), or 0
 * when all are done. Each pass must see the same samples in the same order. */
int sim_ident_begin_pass(sim_ident_t *id);

/* One sample: the gyro (rad/s) and the normalised command of each axis. A
 * sample with a non-finite value restarts the fit's filters and the
 * command's spectrum's segment (a gap). */
void sim_ident_add(sim_ident_t *id, const double gyro_rad_s[3], const double command[3]);

/* The same with the rate setpoint (rad/s; NULL: none), the instrument of
 * b0_iv. A non-finite setpoint turns the axis's b0_iv off. Every sample of
 * a pass must come the same way. */
void sim_ident_add_ref(sim_ident_t *id, const double gyro_rad_s[3], const double command[3],
                       const double setpoint_rad_s[3]);

void sim_ident_end_pass(sim_ident_t *id);

/* The result of axis 0 roll, 1 pitch, 2 yaw (after the last pass). */
void sim_ident_result(const sim_ident_t *id, int axis, sim_ident_axis_t *out);

/* The delay grid's last value and the prefilter's corner actually used. */
int sim_ident_delay_max(const sim_ident_t *id);
double sim_ident_prefilter_hz(const sim_ident_t *id);

/* 1 when the log tells b0: enough samples; a signal of the log's own, not
 * the loop's answer to its gyro (in closed loop without one any plant fits:
 * the gyro's noise and the gusts the controller answers look like a plant,
 * and in hover b0 came out 1.5-8 times the truth with R^2 up to 0.98):
 * a setpoint that moves (b0_iv is had) or a command with content above the
 * motors' corner (SIM_IDENT_BAND_SHARE_MIN, a chirp); R^2 at least
 * SIM_IDENT_R2_MIN; b0 and its interval's lower end > 0; the upper end
 * within SIM_IDENT_B0_TOLD_RATIO of the lower. */
int sim_ident_b0_told(const sim_ident_axis_t *x);

/* One sentence per warning bit; "" for 0. */
const char *sim_ident_warning_text(unsigned bit);

#endif
