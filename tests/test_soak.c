/* SPDX-License-Identifier: BSD-3-Clause */
/* Soak: HP-MLADRC (its fit on the observer and on the gyro) and LP-MLADRC fly the paper's vehicle for an hour of
 * simulated time (SOAK_SECONDS, or LADRC_SOAK_SECONDS from the environment)
 * at 1 kHz with the library's real type (float by default), through the
 * three-axis attitude layer with its defaults, under a steady periodic
 * disturbance, the paper's periodic references and IMU-like noise on angle
 * and rate. Checked on every tick: no fault flag, the HP fit's covariance
 * within its bound, the estimates finite. Checked per window (SOAK_WINDOW_S): the
 * RMS and peak tracking error of each axis finite and under a ceiling, and
 * the last windows no worse than the first settled ones (no drift). See
 * docs/soak.md. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "test_rigid_body.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Simulated seconds per variant; -DSOAK_SECONDS=... at build time, or the
 * environment variable LADRC_SOAK_SECONDS at run time (it wins). */
#ifndef SOAK_SECONDS
#define SOAK_SECONDS 3600.0
#endif
#define SOAK_ENV "LADRC_SOAK_SECONDS"

#define DT_S 1e-3
#define PI 3.14159265358979
#define DEG (PI / 180.0)
/* The plant's RK4 substeps per control tick (as test_hp_paper). */
#define PLANT_SUBSTEPS 2

/* Statistics per window of this length: 15 periods of the reference (4 s)
 * and 28.6 of the disturbance (2.09 s), so a window's RMS averages whole
 * cycles of both to within a few percent, and an hour gives 60 windows. */
#ifndef SOAK_WINDOW_S
#define SOAK_WINDOW_S 60.0
#endif
#define WINDOW_S ((double)(SOAK_WINDOW_S))
/* The first window holds the start-up from rest, 20 deg off the roll
 * reference (noise-free: HP's weight reaches 1 at 1.3 s and |error| stays
 * under 0.003 deg from 2.5 s; LP's under 0.3 deg from 0.63 s): windows
 * ending after this are "settled". */
#define SETTLE_S WINDOW_S
/* Drift: the mean of the last DRIFT_WINDOWS settled windows against the mean
 * of the first DRIFT_WINDOWS (fewer, half the settled windows each, in a
 * short run). */
#define DRIFT_WINDOWS 10
/* At least this many settled windows: one first and one last to compare. */
#define MIN_SETTLED_WINDOWS 2

/* Disturbance (rad/s^2), on from t = 0: the paper's steady tone (Table 2,
 * roll and yaw 20 - 120 sin(3 t), pitch 20 + 120 sin(3 t)) on roll and
 * pitch, a quarter of it on yaw (a multirotor's yaw is driven by the
 * rotors' drag torque, not by thrust on an arm, and feels smaller
 * disturbances; with Jz = 2 Jx this is half roll's torque). */
#define DIST_BIAS_RAD_S2 20.0
#define DIST_AMP_RAD_S2 120.0
#define DIST_W_RAD_S 3.0
#define DIST_YAW_SCALE 0.25

/* Measurement noise, white Gaussian, on every tick: the angle of an
 * attitude filter 0.01 deg RMS, the gyro 0.05 deg/s RMS (a MEMS gyro of
 * 0.005 deg/s/sqrt(Hz) over its 100 Hz band; the BMI088's 0.014 and the
 * ICM-42688's 0.0028 bracket that). HP reads the angle only, LP the rate
 * too (its sample is the rate's difference: 1.2 rad/s^2 of noise per tick
 * before its 75 rad/s filter). */
#define ANGLE_NOISE_RAD (0.01 * DEG)
#define RATE_NOISE_RAD_S (0.05 * DEG)

/* Ceilings on every settled window's RMS and peak error (deg), per axis
 * (roll, pitch, yaw): twice the worst window measured over the CI hour in
 * float (RMS HP 0.0021, 0.0021, 0.0023, LP 0.107, 0.096, 0.027; peak HP
 * 0.0098, 0.0095, 0.0105, LP 0.215, 0.186, 0.046), rounded up, and well
 * below plain LADRC's on the same flight (RMS 2.1, 2.1, 0.65, peak 3.2, 3.1,
 * 0.93: LP's RMS ceilings are a tenth of those, its peak ones a seventh):
 * a window where an estimator quits is caught, the scatter of the noise
 * (2% per window for the RMS, 9% for the peak) is not. The start-up window
 * (from rest, 20 deg off the roll reference) is only checked finite. */
static const double hp_rms_ceiling_deg[LADRC_AXES] = {0.005, 0.005, 0.005};
static const double hp_peak_ceiling_deg[LADRC_AXES] = {0.021, 0.021, 0.021};
/* HP on the gyro (its sample is LP's, the rate's noise in it; its gate
 * judges each tone on its band): the same rule, twice the worst window of
 * the CI hour (RMS 0.0635, 0.0424, 0.0023; peak 0.099, 0.069, 0.011),
 * rounded up; a window where the fit quits rises to LP's (0.107, 0.096). */
static const double hp_gyro_rms_ceiling_deg[LADRC_AXES] = {0.13, 0.085, 0.005};
static const double hp_gyro_peak_ceiling_deg[LADRC_AXES] = {0.2, 0.14, 0.022};
static const double lp_rms_ceiling_deg[LADRC_AXES] = {0.22, 0.20, 0.055};
static const double lp_peak_ceiling_deg[LADRC_AXES] = {0.43, 0.38, 0.095};
/* Drift: the mean RMS of the last DRIFT_WINDOWS windows at most this factor
 * of the mean of the first settled ones. A window's RMS scatters by 2% (HP,
 * noise-dominated) or 1% (LP, the disturbance's residual beating with the
 * reference), so the ratio of two means of ten by under 1%: 10% is some ten
 * of those, and a creeping error (a phase slipping, a covariance or an
 * estimate wandering) of a tenth is caught. */
#define RMS_DRIFT_FACTOR 1.10
/* A window's peak is an extreme of the noise and scatters by 9% (HP; LP 2%),
 * the ratio of two means of ten by 4%: 25% is six of those. */
#define PEAK_DRIFT_FACTOR 1.25
/* HP: after SETTLE_S the weight is 1 on every tick but this fraction (per
 * axis). The gate lets go only on a change of the disturbance or a tone it
 * does not hold; this disturbance never changes (measured 0 over the hour),
 * so 0.1% (3.6 s an hour) allows a rare false alarm of the change detector
 * on noise (each costs a second or two: from rest the weight is 1 at 1.3 s),
 * not a gate that keeps letting go. */
#define HP_DISENGAGED_MAX_FRACTION 1e-3
/* No estimate (rad/s^2) may exceed this: the disturbance's peak is 140, the
 * drag and coupling of the references add under 10, the noise a few. */
#define ESTIMATE_MAX_RAD_S2 300.0

void setUp(void)
{
}
void tearDown(void)
{
}

/* ---------------------------------------------------------------- noise */

/* xorshift64* (Vigna 2016) feeding Box-Muller; both deviates of a pair are
 * used. Deterministic: the same uniforms on every host and build, the same
 * deviates up to the last bit of the C library's log, sin and cos. */
typedef struct {
    uint64_t s;
    double spare;
    int has_spare;
} soak_rng_t;

static double uniform_open(soak_rng_t *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    const uint64_t x = r->s * UINT64_C(2685821657736338717);
    /* top 53 bits, centred in their step: in (0, 1), never 0 for the log */
    return ((double)(x >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

static double gaussian(soak_rng_t *r)
{
    if (r->has_spare) {
        r->has_spare = 0;
        return r->spare;
    }
    const double radius = sqrt(-2.0 * log(uniform_open(r)));
    const double angle = 2.0 * PI * uniform_open(r);
    r->spare = radius * sin(angle);
    r->has_spare = 1;
    return radius * cos(angle);
}

/* ------------------------------------------------------- the flight */

static double reference(int axis, double t)
{
    /* the paper's references: roll 5 + 15 cos(pi t / 2) deg, pitch
     * 10 cos(pi t / 2) deg, yaw 0 */
    if (axis == LADRC_ROLL) {
        return (5.0 + 15.0 * cos(0.5 * PI * t)) * DEG;
    }
    return axis == LADRC_PITCH ? 10.0 * cos(0.5 * PI * t) * DEG : 0.0;
}

static double disturbance(int axis, double t)
{
    const double s = DIST_AMP_RAD_S2 * sin(DIST_W_RAD_S * t);
    if (axis == LADRC_PITCH) {
        return DIST_BIAS_RAD_S2 + s;
    }
    return (axis == LADRC_YAW ? DIST_YAW_SCALE : 1.0) * (DIST_BIAS_RAD_S2 - s);
}

typedef struct {
    double sum_sq, peak;
} window_acc_t;

/* What one run saw; figures in deg unless named otherwise. */
typedef struct {
    double seconds;
    long long ticks;
    long windows, settled;
    int drift_n; /* windows in each mean of the drift test */
    double first_rms[LADRC_AXES][DRIFT_WINDOWS], last_rms[LADRC_AXES][DRIFT_WINDOWS]; /* last: a ring */
    double first_peak[LADRC_AXES][DRIFT_WINDOWS], last_peak[LADRC_AXES][DRIFT_WINDOWS];
    double worst_rms[LADRC_AXES], worst_peak[LADRC_AXES];
    long worst_rms_window[LADRC_AXES], worst_peak_window[LADRC_AXES];
    double slope_sums[LADRC_AXES][4]; /* settled RMS against its index x: n, sum x, sum RMS, sum x RMS */
    double sum_xx[LADRC_AXES];        /* sum x^2 */
    long long nonfinite_window;       /* index of the first window with a non-finite RMS, -1 */
    long long fault_ticks;            /* ticks with any fault flag */
    long long first_fault_tick;
    unsigned first_fault_flags;
    int first_fault_axis;       /* -1: the step's return value */
    long long trace_violations; /* ticks where tr(P) left (0, bound] or the fit faulted */
    long long first_trace_violation_tick;
    double max_trace_ratio;         /* max tr(P) / bound */
    double max_settled_trace_ratio; /* the same after SETTLE_S */
    double trace_bound;
    long long disengaged_ticks[LADRC_AXES]; /* HP: ticks after SETTLE_S with weight < 1 */
    long long settled_ticks;
    long long estimate_violations; /* ticks with a non-finite or too large estimate */
    double max_estimate;           /* largest |d_hat| (rad/s^2) */
    int diverged;                  /* the plant left +-90 deg or went non-finite */
    double diverged_t;
} soak_result_t;

static double soak_seconds(void)
{
    const char *text = getenv(SOAK_ENV);
    if (text == NULL || text[0] == '\0') {
        return (double)(SOAK_SECONDS);
    }
    char *end = NULL;
    const double s = strtod(text, &end);
    if (end == text || *end != '\0' || !(s > 0.0 && s < 1e7)) {
        TEST_FAIL_MESSAGE(SOAK_ENV " must be a number of seconds in (0, 1e7)");
    }
    return s;
}

static void record_window(soak_result_t *r, const window_acc_t acc[LADRC_AXES], long n_samples)
{
    const long w = r->windows++;
    const double t_end = (double)r->windows * WINDOW_S;
    for (int i = 0; i < LADRC_AXES; ++i) {
        const double rms = sqrt(acc[i].sum_sq / (double)n_samples) / DEG;
        const double peak = acc[i].peak / DEG;
        if (!isfinite(rms) && r->nonfinite_window < 0) {
            r->nonfinite_window = w;
        }
        if (t_end <= SETTLE_S + 1e-9) {
            continue;
        }
        if (!(rms <= r->worst_rms[i])) {
            r->worst_rms[i] = rms;
            r->worst_rms_window[i] = w;
        }
        if (!(peak <= r->worst_peak[i])) {
            r->worst_peak[i] = peak;
            r->worst_peak_window[i] = w;
        }
        const long s = r->settled; /* index among the settled windows */
        if (s < DRIFT_WINDOWS) {
            r->first_rms[i][s] = rms;
            r->first_peak[i][s] = peak;
        }
        r->last_rms[i][s % DRIFT_WINDOWS] = rms;
        r->last_peak[i][s % DRIFT_WINDOWS] = peak;
        r->slope_sums[i][0] += 1.0;
        r->slope_sums[i][1] += (double)s;
        r->slope_sums[i][2] += rms;
        r->slope_sums[i][3] += (double)s * rms;
        r->sum_xx[i] += (double)s * (double)s;
    }
    if (t_end > SETTLE_S + 1e-9) {
        r->settled++;
    }
}

static void fly(ladrc_variant_t variant, ladrc_hp_sample_t sample, double seconds, soak_result_t *r)
{
    static const ladrc_real_t inertia[LADRC_AXES] = {(ladrc_real_t)5.445e-3, (ladrc_real_t)5.445e-3,
                                                     (ladrc_real_t)1.089e-2};
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, variant, (ladrc_real_t)DT_S, inertia, (ladrc_real_t)0.09);
    for (int i = 0; i < LADRC_AXES; ++i) {
        cfg.axis[i].hp_sample = sample;
    }
    ladrc_attitude_t att;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    test_rigid_body_t body;
    test_rigid_body_init(&body);
    soak_rng_t rng = {.s = UINT64_C(0x9E3779B97F4A7C15), .spare = 0.0, .has_spare = 0};

    memset(r, 0, sizeof *r);
    r->seconds = seconds;
    r->nonfinite_window = -1;
    r->first_fault_tick = -1;
    r->first_fault_axis = -1;
    r->first_trace_violation_tick = -1;
    for (int i = 0; i < LADRC_AXES; ++i) {
        r->worst_rms_window[i] = r->worst_peak_window[i] = -1;
    }

    const long window_ticks = (long)(WINDOW_S / DT_S + 0.5);
    const long long total = (long long)(seconds / DT_S + 0.5);
    const long long settle_ticks = (long long)(SETTLE_S / DT_S + 0.5);
    window_acc_t acc[LADRC_AXES];
    memset(acc, 0, sizeof acc);
    long in_window = 0;

    for (long long k = 0; k < total; ++k) {
        const double t = (double)k * DT_S;
        ladrc_real_t ref[LADRC_AXES], angle[LADRC_AXES], rate[LADRC_AXES], torque[LADRC_AXES];
        double dist[LADRC_AXES], tq[LADRC_AXES];
        for (int i = 0; i < LADRC_AXES; ++i) {
            ref[i] = (ladrc_real_t)reference(i, t);
            angle[i] = (ladrc_real_t)(body.angle_rad[i] + ANGLE_NOISE_RAD * gaussian(&rng));
            rate[i] = (ladrc_real_t)(body.rate_rad_s[i] + RATE_NOISE_RAD_S * gaussian(&rng));
            /* held over the step at its midpoint value (as test_hp_paper) */
            dist[i] = disturbance(i, t + 0.5 * DT_S);
        }
        const ladrc_fault_t f = ladrc_attitude_step(&att, ref, angle, rate, torque);
        ladrc_attitude_set_applied(&att, torque);
        unsigned any = f;
        int fault_axis = -1;
        for (int i = 0; i < LADRC_AXES; ++i) {
            const ladrc_fault_t fa = ladrc_axis_get_faults(&att.axis[i]);
            if (fa != LADRC_FAULT_NONE && fault_axis < 0) {
                fault_axis = i;
            }
            any |= fa;
        }
        if (any != LADRC_FAULT_NONE) {
            if (r->fault_ticks++ == 0) {
                r->first_fault_tick = k;
                r->first_fault_flags = any;
                r->first_fault_axis = fault_axis;
            }
        }

        for (int i = 0; i < LADRC_AXES; ++i) {
            double est;
            const ladrc_hp_estimator_t *hp = ladrc_axis_get_hp(&att.axis[i]);
            if (hp != NULL) {
                const ladrc_rls_t *fit = ladrc_hp_get_fit(hp);
                const double tr = (double)ladrc_rls_get_p_norm(fit);
                const double bound = (double)ladrc_rls_get_p_bound(fit);
                r->trace_bound = bound;
                if (!(tr > 0.0 && tr <= bound) || ladrc_rls_get_faults(fit) != LADRC_FAULT_NONE) {
                    if (r->trace_violations++ == 0) {
                        r->first_trace_violation_tick = k;
                    }
                }
                if (tr / bound > r->max_trace_ratio) {
                    r->max_trace_ratio = tr / bound;
                }
                if (k >= settle_ticks && tr / bound > r->max_settled_trace_ratio) {
                    r->max_settled_trace_ratio = tr / bound;
                }
                if (k >= settle_ticks && ladrc_hp_get_weight(hp) < (ladrc_real_t)1.0) {
                    r->disengaged_ticks[i]++;
                }
                est = (double)ladrc_hp_get_estimate(hp);
            } else {
                est = (double)ladrc_lp_get_estimate(ladrc_axis_get_lp(&att.axis[i]));
            }
            if (!(fabs(est) <= ESTIMATE_MAX_RAD_S2)) {
                r->estimate_violations++;
            }
            if (fabs(est) > r->max_estimate) {
                r->max_estimate = fabs(est);
            }
        }
        if (k >= settle_ticks) {
            r->settled_ticks++;
        }

        for (int i = 0; i < LADRC_AXES; ++i) {
            tq[i] = (double)torque[i];
        }
        test_rigid_body_step(&body, tq, dist, DT_S, PLANT_SUBSTEPS);
        const double tn = (double)(k + 1) * DT_S;
        for (int i = 0; i < LADRC_AXES; ++i) {
            const double e = fabs(reference(i, tn) - body.angle_rad[i]);
            if (!(e < 90.0 * DEG)) {
                r->diverged = 1;
                r->diverged_t = tn;
                r->ticks = k + 1;
                return;
            }
            acc[i].sum_sq += e * e;
            if (e > acc[i].peak) {
                acc[i].peak = e;
            }
        }
        if (++in_window == window_ticks) {
            record_window(r, acc, in_window);
            memset(acc, 0, sizeof acc);
            in_window = 0;
        }
    }
    r->ticks = total; /* a last partial window is left out of the statistics */
    const long n = r->settled / 2 < DRIFT_WINDOWS ? r->settled / 2 : DRIFT_WINDOWS;
    r->drift_n = (int)n;
}

/* Mean of the first and the last drift_n settled windows of a series. */
static void drift_means(const soak_result_t *r, const double first[DRIFT_WINDOWS],
                        const double last_ring[DRIFT_WINDOWS], double *mean_first, double *mean_last)
{
    double a = 0.0, b = 0.0;
    for (int j = 0; j < r->drift_n; ++j) {
        a += first[j];
        b += last_ring[(r->settled - 1 - j) % DRIFT_WINDOWS];
    }
    *mean_first = a / r->drift_n;
    *mean_last = b / r->drift_n;
}

/* Trend of the settled windows' RMS: the least-squares line's change from
 * the first settled window to the last, relative to the mean. */
static double relative_trend(const soak_result_t *r, int i)
{
    const double n = r->slope_sums[i][0];
    const double sx = r->slope_sums[i][1], sy = r->slope_sums[i][2], sxy = r->slope_sums[i][3];
    const double den = n * r->sum_xx[i] - sx * sx;
    if (n < 2.0 || den <= 0.0) {
        return 0.0;
    }
    const double slope = (n * sxy - sx * sy) / den; /* deg per window */
    return slope * (n - 1.0) / (sy / n);
}

static void check(const char *name, ladrc_variant_t variant, ladrc_hp_sample_t sample,
                  const double rms_ceiling[LADRC_AXES], const double peak_ceiling[LADRC_AXES])
{
    static soak_result_t r; /* off the stack (about 1.3 kB; the board runs have little) */
    const double seconds = soak_seconds();
    fly(variant, sample, seconds, &r);

    static const char *axis_name[LADRC_AXES] = {"roll", "pitch", "yaw"};
    char msg[1024];
    int len = 0;
    double first_rms[LADRC_AXES] = {0}, last_rms[LADRC_AXES] = {0}, first_peak[LADRC_AXES] = {0},
           last_peak[LADRC_AXES] = {0};
    if (r.drift_n > 0) {
        for (int i = 0; i < LADRC_AXES; ++i) {
            drift_means(&r, r.first_rms[i], r.last_rms[i], &first_rms[i], &last_rms[i]);
            drift_means(&r, r.first_peak[i], r.last_peak[i], &first_peak[i], &last_peak[i]);
        }
    }
    double disengaged = 0.0;
    for (int i = 0; i < LADRC_AXES; ++i) {
        const double frac = r.settled_ticks > 0 ? (double)r.disengaged_ticks[i] / (double)r.settled_ticks : 0.0;
        disengaged = fmax(disengaged, frac);
    }

    /* the one-line summary */
    len += snprintf(msg + len, sizeof msg - (size_t)len,
                    "%s: %.3f h simulated, %lld ticks, %ld windows of %.0f s (%ld settled, drift over %d); RMS "
                    "first/last [deg]",
                    name, r.seconds / 3600.0, r.ticks, r.windows, WINDOW_S, r.settled, r.drift_n);
    for (int i = 0; i < LADRC_AXES; ++i) {
        len += snprintf(msg + len, sizeof msg - (size_t)len, " %s %.5f/%.5f", axis_name[i], first_rms[i], last_rms[i]);
    }
    len += snprintf(msg + len, sizeof msg - (size_t)len, "; peak first/last");
    for (int i = 0; i < LADRC_AXES; ++i) {
        len += snprintf(msg + len, sizeof msg - (size_t)len, " %.4f/%.4f", first_peak[i], last_peak[i]);
    }
    len += snprintf(msg + len, sizeof msg - (size_t)len, "; worst window RMS/peak");
    for (int i = 0; i < LADRC_AXES; ++i) {
        len += snprintf(msg + len, sizeof msg - (size_t)len, " %.5f/%.4f", r.worst_rms[i], r.worst_peak[i]);
    }
    len += snprintf(msg + len, sizeof msg - (size_t)len, "; RMS trend over the settled windows");
    for (int i = 0; i < LADRC_AXES; ++i) {
        len += snprintf(msg + len, sizeof msg - (size_t)len, " %+.2f%%", 100.0 * relative_trend(&r, i));
    }
    if (variant == LADRC_VARIANT_HP_MLADRC) {
        len += snprintf(msg + len, sizeof msg - (size_t)len,
                        "; max tr(P)/bound %.4f, after %.0f s %.3g (bound %.4g); disengaged %.4f%%", r.max_trace_ratio,
                        SETTLE_S, r.max_settled_trace_ratio, r.trace_bound, 100.0 * disengaged);
    }
    (void)snprintf(msg + len, sizeof msg - (size_t)len, "; max |d_hat| %.1f rad/s^2; faults %lld", r.max_estimate,
                   r.fault_ticks);
    TEST_MESSAGE(msg);

    /* the checks, most telling first */
    if (r.diverged) {
        snprintf(msg, sizeof msg, "%s: the loop diverged at t = %.3f s", name, r.diverged_t);
        TEST_FAIL_MESSAGE(msg);
    }
    if (r.fault_ticks > 0) {
        snprintf(msg, sizeof msg, "%s: %lld ticks with faults, the first at t = %.3f s: flags 0x%02x (%s)", name,
                 r.fault_ticks, (double)r.first_fault_tick * DT_S, r.first_fault_flags,
                 r.first_fault_axis < 0 ? "step" : axis_name[r.first_fault_axis]);
        TEST_FAIL_MESSAGE(msg);
    }
    if (r.trace_violations > 0) {
        snprintf(msg, sizeof msg,
                 "%s: tr(P) outside (0, bound] or the fit faulted on %lld ticks, the first at t = %.3f s", name,
                 r.trace_violations, (double)r.first_trace_violation_tick * DT_S);
        TEST_FAIL_MESSAGE(msg);
    }
    if (r.estimate_violations > 0) {
        snprintf(msg, sizeof msg, "%s: an estimate not finite or above %.0f rad/s^2 on %lld ticks", name,
                 ESTIMATE_MAX_RAD_S2, r.estimate_violations);
        TEST_FAIL_MESSAGE(msg);
    }
    if (r.nonfinite_window >= 0) {
        snprintf(msg, sizeof msg, "%s: window %lld has a non-finite RMS", name, r.nonfinite_window);
        TEST_FAIL_MESSAGE(msg);
    }
    if (r.settled < MIN_SETTLED_WINDOWS) {
        snprintf(msg, sizeof msg, "%s: %.0f s is too short: it needs %.0f s (%d settled windows of %.0f s)", name,
                 r.seconds, SETTLE_S + MIN_SETTLED_WINDOWS * WINDOW_S, MIN_SETTLED_WINDOWS, WINDOW_S);
        TEST_FAIL_MESSAGE(msg);
    }
    for (int i = 0; i < LADRC_AXES; ++i) {
        snprintf(msg, sizeof msg, "%s %s: window %ld has RMS %.5f deg (ceiling %.5f)", name, axis_name[i],
                 r.worst_rms_window[i], r.worst_rms[i], rms_ceiling[i]);
        TEST_ASSERT_TRUE_MESSAGE(r.worst_rms[i] < rms_ceiling[i], msg);
        snprintf(msg, sizeof msg, "%s %s: window %ld has peak %.4f deg (ceiling %.4f)", name, axis_name[i],
                 r.worst_peak_window[i], r.worst_peak[i], peak_ceiling[i]);
        TEST_ASSERT_TRUE_MESSAGE(r.worst_peak[i] < peak_ceiling[i], msg);
        snprintf(msg, sizeof msg,
                 "%s %s: RMS drifted from %.5f to %.5f deg (first/last %d settled windows, factor %.2f)", name,
                 axis_name[i], first_rms[i], last_rms[i], r.drift_n, RMS_DRIFT_FACTOR);
        TEST_ASSERT_TRUE_MESSAGE(last_rms[i] <= RMS_DRIFT_FACTOR * first_rms[i], msg);
        snprintf(msg, sizeof msg,
                 "%s %s: peak drifted from %.4f to %.4f deg (first/last %d settled windows, factor %.2f)", name,
                 axis_name[i], first_peak[i], last_peak[i], r.drift_n, PEAK_DRIFT_FACTOR);
        TEST_ASSERT_TRUE_MESSAGE(last_peak[i] <= PEAK_DRIFT_FACTOR * first_peak[i], msg);
        if (variant == LADRC_VARIANT_HP_MLADRC) {
            const double frac = (double)r.disengaged_ticks[i] / (double)r.settled_ticks;
            snprintf(msg, sizeof msg, "%s %s: the weight was below 1 on %.4f%% of the ticks after %.0f s (max %.4f%%)",
                     name, axis_name[i], 100.0 * frac, SETTLE_S, 100.0 * HP_DISENGAGED_MAX_FRACTION);
            TEST_ASSERT_TRUE_MESSAGE(frac <= HP_DISENGAGED_MAX_FRACTION, msg);
        }
    }
}

static void test_hp_mladrc_soaks_without_drift_or_fault(void)
{
    check("HP-MLADRC", LADRC_VARIANT_HP_MLADRC, LADRC_HP_SAMPLE_OBSERVER, hp_rms_ceiling_deg, hp_peak_ceiling_deg);
}

static void test_hp_mladrc_on_the_gyro_soaks_without_drift_or_fault(void)
{
    check("HP-MLADRC (gyro)", LADRC_VARIANT_HP_MLADRC, LADRC_HP_SAMPLE_GYRO, hp_gyro_rms_ceiling_deg,
          hp_gyro_peak_ceiling_deg);
}

static void test_lp_mladrc_soaks_without_drift_or_fault(void)
{
    check("LP-MLADRC", LADRC_VARIANT_LP_MLADRC, LADRC_HP_SAMPLE_OBSERVER, lp_rms_ceiling_deg, lp_peak_ceiling_deg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hp_mladrc_soaks_without_drift_or_fault);
    RUN_TEST(test_hp_mladrc_on_the_gyro_soaks_without_drift_or_fault);
    RUN_TEST(test_lp_mladrc_soaks_without_drift_or_fault);
    return UNITY_END();
}
