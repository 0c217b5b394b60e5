/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file margins.h
 * @brief Host-side stability analysis of one configured attitude axis: the
 *        sampled loop as it really runs (the library's own controller code on
 *        the exact ZOH discretisation of the airframe), its gain, phase and
 *        delay margins, peak sensitivity, a Nyquist stability verdict, the
 *        largest stable motor lag and delay, and a margins-based tuning.
 *
 * Not part of the firmware library (target ladrc_analysis, host builds only):
 * double precision inside, no heap (everything lives in a caller-owned
 * workspace), no stdio. Method, equations and criterion: docs/margins.md.
 *
 * Plant (one axis, true inertia J = inertia_kg_m2 * inertia_factor):
 *     tau_a' = (u - tau_a) / motor_tau_s        (tau_a = u when motor_tau_s = 0)
 *     omega' = (tau_a - drag_Nm_s * omega) / J + d,   theta' = omega
 * u held over each tick (zero-order hold), d an angular acceleration
 * (rad/s^2); the controller measures theta and omega delay_ticks ticks late.
 *
 * Controller: measured, not re-derived. With the reference at 0 the map from
 * measured angle (and rate) to torque is linear (LADRC, PID) or linearised
 * about a converged run under a tone disturbance (LP-/HP-MLADRC: the
 * difference between a perturbed and an unperturbed copy of the controller,
 * averaged over start instants). The impulse responses h_k tend to a constant
 * c (the controller's integrator); C(z) = sum_k (h_k - c) z^-k + c / (1 - z^-1).
 * Loop broken at the plant input: L = -(C_angle P_angle + C_rate P_rate).
 */
#ifndef LADRC_MARGINS_H
#define LADRC_MARGINS_H

#include "ladrc/attitude.h"
#include "ladrc/axis.h"
#include "ladrc/gyro_filter.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Longest controller impulse response (ticks); also the FFT length. */
#define LADRC_MARGINS_MAX_TAPS 16384
/** Points of the output frequency grid (plots, CSV). */
#define LADRC_MARGINS_MAX_OUT 400
/** Largest measurement delay analysed (ticks); the simulator's sensor limit. */
#define LADRC_MARGINS_MAX_DELAY 512
/** Largest reference step of the tuning objective (rad): well inside the
 *  small-angle loop, whose error beyond 1 rad counts as diverged. */
#define LADRC_MARGINS_MAX_STEP_RAD 0.5
/** Most bins of a coloured rate-noise spectrum (ladrc_margins_request_t rate_noise_psd):
 *  a 1024-point Welch spectrum's. */
#define LADRC_MARGINS_NOISE_PSD_BINS 513
/** Default corner of the predicted command noise (Hz): above an attitude
 *  loop's bandwidth, where what reaches the motors is noise, not control. */
#define LADRC_MARGINS_NOISE_CORNER_HZ 20.0
/** Crossovers of each kind kept in a result. */
#define LADRC_MARGINS_MAX_CROSS 8

/** Result of a margins function; each error names what is wrong. */
typedef enum {
    LADRC_MARGINS_OK = 0,             /**< success */
    LADRC_MARGINS_ERR_NULL,           /**< a required pointer is NULL */
    LADRC_MARGINS_ERR_DT_S,           /**< plant dt_s not > 0 or not the controller's */
    LADRC_MARGINS_ERR_INERTIA,        /**< inertia_kg_m2 or inertia_factor not finite and > 0 */
    LADRC_MARGINS_ERR_DRAG,           /**< drag_Nm_s not finite and >= 0 */
    LADRC_MARGINS_ERR_MOTOR_TAU,      /**< motor_tau_s not finite and >= 0 */
    LADRC_MARGINS_ERR_DELAY,          /**< delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY */
    LADRC_MARGINS_ERR_CONTROLLER,     /**< the controller config is refused by its init */
    LADRC_MARGINS_ERR_REQUEST,        /**< a request field (tone, response length, grid) is invalid */
    LADRC_MARGINS_ERR_NOT_SETTLED,    /**< the controller's response did not settle to a constant
                                            within response_s (an unstable or undamped controller) */
    LADRC_MARGINS_ERR_NOT_MEASURED,   /**< the workspace holds no measured controller */
    LADRC_MARGINS_ERR_TARGETS_NOT_MET /**< tuning: no setting meets the targets (best one reported) */
} ladrc_margins_status_t;

/** Text of a status.
 *  @param status  any value
 *  @return "LADRC_MARGINS_ERR_...: explanation" (a text for a value outside
 *          the enum too); never NULL */
const char *ladrc_margins_status_str(ladrc_margins_status_t status);

/** The airframe as it really is. */
typedef struct {
    double dt_s;           /**< control period (s), the controller's dt_s */
    double inertia_kg_m2;  /**< modelled axis inertia J (kg m^2) */
    double inertia_factor; /**< true J / modelled J (1: exact) */
    double drag_Nm_s;      /**< rotational drag kt (N m s), >= 0 */
    double motor_tau_s;    /**< first-order lag of the torque (s), 0 = none */
    int delay_ticks;       /**< measurement delay (ticks), 0..LADRC_MARGINS_MAX_DELAY */
} ladrc_margins_plant_t;

/** The controller analysed: one axis of an attitude controller (what the
 *  simulator and firmware fly: the coupling feed's drag term included), or a
 *  bare axis. Exactly one of attitude and axis is non-NULL. With a filter,
 *  the measured rate (and the angle, with filter_angle) reaches the
 *  controller through the gyro filter stage, its RPM notches held at
 *  filter_rotor_hz: the margins, steps and tuning are those of the filtered
 *  loop. Zero-initialised fields: no filter. */
typedef struct {
    const ladrc_attitude_config_t *attitude;  /**< with axis_index */
    int axis_index;                           /**< LADRC_ROLL, LADRC_PITCH or LADRC_YAW */
    const ladrc_axis_config_t *axis;          /**< a bare axis */
    int use_rate;                             /**< the controller gets the measured rate */
    const ladrc_gyro_filter_config_t *filter; /**< the gyro filter before it; NULL: none (its channels are
                                                    ignored: one, or two with filter_angle) */
    const ladrc_real_t *filter_rotor_hz;      /**< the rotors' rates its RPM notches sit on (Hz), rpm_rotors
                                                    of them; may be NULL without an RPM bank */
    int filter_angle;                         /**< 1: the angle goes through the filter too */
} ladrc_margins_controller_t;

/** How to measure. ladrc_margins_request_default fills every field. */
typedef struct {
    ladrc_margins_plant_t plant; /**< the plant of the adaptive variants' converged run and of the loop */
    double response_s;           /**< length of the impulse responses (s); default 4, or
                                  LADRC_MARGINS_MAX_TAPS periods where that is shorter */
    double tone_rad_s;           /**< adaptive variants: disturbance tone they converge on;
                                  0: the axis's hp_freq_rad_s[0] (default) */
    double tone_rad_s2;          /**< its amplitude (rad/s^2); default 20 */
    double converge_s;           /**< adaptive variants: closed-loop run before the
                                  linearisation (s); default 10 */
    int n_starts;                /**< adaptive variants: start instants averaged over a
                                  tone period; default 4 */
    double out_min_rad_s;        /**< output grid: lowest frequency (rad/s); default 0.1 */
    int n_out;                   /**< output grid points, 2..LADRC_MARGINS_MAX_OUT; default 200 */
    double track_step_rad;       /**< tuning objective: reference step (rad),
                                  0..LADRC_MARGINS_MAX_STEP_RAD; default
                                  0.1745 (10 deg) */
    double dist_step_rad_s2;     /**< tuning objective: then a disturbance step (rad/s^2), >= 0;
                                  default 20. Both 0: the peak |d -> error| is the objective */
    double step_window_s;        /**< how long each step is flown (s), > 0 and <= 60; default 2 */
    double angle_noise_std_rad;  /**< command noise: white noise on the measured angle, standard
                                  deviation per sample (rad), finite and >= 0; default 0 */
    double rate_noise_std_rad_s; /**< white noise on the measured rate (gyro), standard deviation
                                  per sample (rad/s), finite and >= 0; default 0 */
    double noise_corner_hz;      /**< the command noise is its RMS from this frequency (Hz) up to
                                  the Nyquist frequency; > 0 and below it when a noise is
                                  non-zero; default LADRC_MARGINS_NOISE_CORNER_HZ */
    int rate_noise_psd_bins;     /**< coloured rate noise added to the white: 0 (default) none, else
                                  the bins of rate_noise_psd, 2..LADRC_MARGINS_NOISE_PSD_BINS */
    double rate_noise_bin_hz;    /**< the bins' spacing (Hz), > 0: bin k is at k times it */
    /** one-sided PSD of the coloured rate noise ((rad/s)^2/Hz), finite and >= 0, linear between
     *  the bins and 0 beyond the last (e.g. a flight log's gyro noise, its Welch spectrum) */
    double rate_noise_psd[LADRC_MARGINS_NOISE_PSD_BINS];
} ladrc_margins_request_t;

/** Margins and verdict of one loop. Margins that do not exist are +INFINITY
 *  (no phase crossover: gain margin; no gain crossover: phase margin, delay
 *  margin), their frequencies NaN. */
typedef struct {
    int stable;                            /**< 1: every closed-loop pole inside the unit circle (Nyquist) */
    int encirclements;                     /**< closed-loop poles outside the unit circle (Nyquist count) */
    double gm_db;                          /**< gain margin (dB): smallest over phase crossovers with |L| < 1 */
    double gm_rad_s;                       /**< its frequency */
    double gm_low_db;                      /**< lower gain margin (dB, <= 0): gain reduction the loop
                                  tolerates (phase crossovers with |L| > 1); -INFINITY if none */
    double pm_deg;                         /**< phase margin (deg): smallest over gain crossovers */
    double wc_rad_s;                       /**< its crossover frequency */
    double dm_s;                           /**< delay margin (s): smallest PM / w over gain crossovers; 0 if
                                  a crossover has PM <= 0 */
    double dm_ticks;                       /**< the same in control periods */
    double ms;                             /**< peak sensitivity max |1 / (1 + L)| */
    double ms_db;                          /**< the same in dB */
    double dist_peak_rad;                  /**< peak |angle error / acceleration disturbance| (rad per rad/s^2) */
    double dist_peak_rad_s;                /**< its frequency */
    double tail_residue;                   /**< largest |h_k - c| / max |h_k| over the last eighth of the
                                  responses (how well they settled) */
    int linearised_nominal;                /**< adaptive: the run on the requested plant diverged, so the
                                  controller was linearised on the plant without lag and delay */
    double cmd_noise_Nm;                   /**< predicted RMS of the torque command (N m) from
                                  noise_corner_hz to the Nyquist frequency caused by the request's
                                  white angle and rate noise through the closed loop:
                                  u = S (C_angle n_angle + C_rate n_rate); 0 when both noises are 0
                                  (docs/margins.md, "Command noise") */
    int n_out;                             /**< output grid */
    double w_rad_s[LADRC_MARGINS_MAX_OUT]; /**< the grid's frequencies (rad/s), n_out of them */
    /** @{ */
    double l_re[LADRC_MARGINS_MAX_OUT], l_im[LADRC_MARGINS_MAX_OUT]; /**< L(e^jwT) */
    /** @} */
    /** @{ */
    double s_re[LADRC_MARGINS_MAX_OUT], s_im[LADRC_MARGINS_MAX_OUT]; /**< 1 / (1 + L) */
    /** @} */
    /** @{ */
    double de_re[LADRC_MARGINS_MAX_OUT], de_im[LADRC_MARGINS_MAX_OUT]; /**< angle error per
                                  acceleration disturbance at the plant input (rad per rad/s^2) */
    /** @} */
} ladrc_margins_result_t;

/** The measured controller and scratch space; large (about 1 MB): give it
 *  static storage. Opaque: read it through the functions below. */
typedef struct {
    int measured;                                      /**< 1 once a controller was measured */
    int has_rate;                                      /**< the controller gets the measured rate */
    double dt_s;                                       /**< its control period (s) */
    int n_taps;                                        /**< length of the responses (ticks) */
    double tail[2];                                    /**< c0 of the angle and rate responses' tails */
    double ramp[2];                                    /**< c1: h_k -> c0 + c1 k */
    double tail_residue;                               /**< as in ladrc_margins_result_t */
    int linearised_nominal;                            /**< as in ladrc_margins_result_t */
    double h[2][LADRC_MARGINS_MAX_TAPS];               /**< angle (N m/rad), rate (N m s/rad) */
    double grid_re[2][LADRC_MARGINS_MAX_TAPS / 2 + 1]; /**< C on w_m = 2 pi m / MAX_TAPS */
    double grid_im[2][LADRC_MARGINS_MAX_TAPS / 2 + 1]; /**< its imaginary part */
    /** @{ */
    double fft_re[LADRC_MARGINS_MAX_TAPS], fft_im[LADRC_MARGINS_MAX_TAPS]; /**< FFT scratch */
    /** @} */
    struct {
        union {
            ladrc_axis_t axis;         /**< a bare axis */
            ladrc_attitude_t attitude; /**< an attitude controller */
        } ctl;                         /**< the controller */
        ladrc_gyro_filter_t filter;    /**< the gyro filter before it, if any */
    } copy[4];                         /**< base, angle-, rate-perturbed, saved */
    ladrc_margins_result_t scratch;    /**< the tuning's candidates */
} ladrc_margins_workspace_t;

/** Defaults for the given plant (see the fields).
 *  @param req    out: the request; must not be NULL (not checked)
 *  @param plant  copied into req->plant; NULL: the plant is zeroed (set it) */
void ladrc_margins_request_default(ladrc_margins_request_t *req, const ladrc_margins_plant_t *plant);

/** Measures the controller's frequency response into ws (the plant of req
 *  is used only for the adaptive variants' converged run).
 *  @param ws   the workspace
 *  @param ctl  the controller
 *  @param req  the request
 *  @retval LADRC_MARGINS_OK              measured
 *  @retval LADRC_MARGINS_ERR_NULL        ws, ctl or req is NULL
  *  @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0, or not the controller's
  *  @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY
 *  @retval LADRC_MARGINS_ERR_REQUEST     a request field outside its range
 *  @retval LADRC_MARGINS_ERR_CONTROLLER  not exactly one of attitude and axis, a bad
 *                                        axis_index, INDI or RATE-ADRC without use_rate, or its init refuses it
 *  @retval LADRC_MARGINS_ERR_NOT_SETTLED the response did not settle within response_s */
ladrc_margins_status_t ladrc_margins_measure(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                             const ladrc_margins_request_t *req);

/** Margins, verdict and output grid of the measured controller (ws) on
 *  req->plant (which may differ from the one it was measured with).
 *  @param ws   the measured workspace
 *  @param req  the request (plant and output grid)
 *  @param res  out: the result
 *  @retval LADRC_MARGINS_OK               computed
 *  @retval LADRC_MARGINS_ERR_NULL         ws, req or res is NULL
 *  @retval LADRC_MARGINS_ERR_NOT_MEASURED ws holds no measured controller
  *  @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0, or not the measured one's
  *  @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY
 *  @retval LADRC_MARGINS_ERR_REQUEST      a request field outside its range */
ladrc_margins_status_t ladrc_margins_loop(ladrc_margins_workspace_t *ws, const ladrc_margins_request_t *req,
                                          ladrc_margins_result_t *res);

/** ladrc_margins_measure then ladrc_margins_loop.
 *  @param ws   the workspace
 *  @param ctl  the controller
 *  @param req  the request
 *  @param res  out: the result
 *  @return the first status that is not LADRC_MARGINS_OK of the two, else LADRC_MARGINS_OK */
ladrc_margins_status_t ladrc_margins_analyse(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                             const ladrc_margins_request_t *req, ladrc_margins_result_t *res);

/** ladrc_margins_analyse as ladrc_margins reports it: HP-MLADRC whose
 *  converged tone model has no settled linear response
 *  (LADRC_MARGINS_ERR_NOT_SETTLED under the tone) is analysed in its idle
 *  state (req's tone amplitude 0, estimator weight 0), and *idle (may be
 *  NULL) is set to 1, else 0. HP-MLADRC on the gyro (hp_sample GYRO) is
 *  analysed as the LP-MLADRC it is with its gate shut, *idle 1.
 *  @param ws    the workspace
 *  @param ctl   the controller
 *  @param req   the request
 *  @param res   out: the result
 *  @param idle  out: 1 analysed idle, 0 not; may be NULL
 *  @return as ladrc_margins_analyse (of the idle analysis when it ran) */
ladrc_margins_status_t ladrc_margins_analyse_reported(ladrc_margins_workspace_t *ws,
                                                      const ladrc_margins_controller_t *ctl,
                                                      const ladrc_margins_request_t *req, ladrc_margins_result_t *res,
                                                      int *idle);

/** Nyquist verdict only (fast).
 *  @param ws     the measured workspace
 *  @param plant  the plant
 *  @return 1 stable; 0 unstable, or ws or plant NULL, unmeasured or invalid */
int ladrc_margins_is_stable(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant);

/** Largest motor lag (s) for which the measured controller's loop on plant
 *  (motor_tau_s replaced) stays stable, by bisection on the Nyquist verdict
 *  to a relative 1e-3; searched up to tau_max_s (returned if still stable).
 *  0 if the loop is unstable without lag.
 *  @param ws         the measured workspace
 *  @param plant      the plant
 *  @param tau_max_s  the search's top (s), finite, > 0
 *  @param tau_s      out: the largest stable lag (s)
 *  @retval LADRC_MARGINS_OK               found
 *  @retval LADRC_MARGINS_ERR_NULL         ws, plant or tau_s is NULL
 *  @retval LADRC_MARGINS_ERR_NOT_MEASURED ws holds no measured controller
  *  @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0, or not the measured one's
  *  @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0, or tau_max_s not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY */
ladrc_margins_status_t ladrc_margins_max_motor_tau(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                                   double tau_max_s, double *tau_s);

/** Largest stable measurement delay (whole ticks, delay_ticks replaced),
 *  -1 if unstable at 0, LADRC_MARGINS_MAX_DELAY if stable throughout. Every
 *  delay up to 64 ticks is tried in turn (the first unstable one ends the
 *  search); past 64, doubling and bisection (about 2 log2 d verdicts), which
 *  takes the loop as stable below one delay and unstable above it.
 *  @param ws     the measured workspace
 *  @param plant  the plant
 *  @param ticks  out: the largest stable delay (ticks)
 *  @retval LADRC_MARGINS_OK               found
 *  @retval LADRC_MARGINS_ERR_NULL         ws, plant or ticks is NULL
 *  @retval LADRC_MARGINS_ERR_NOT_MEASURED ws holds no measured controller
  *  @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0, or not the measured one's
  *  @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY */
ladrc_margins_status_t ladrc_margins_max_delay(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                               int *ticks);

/** Frequency responses at w (rad/s): plant from torque to measured angle and
 *  rate (delay included).
 *  @param plant    the plant
 *  @param w_rad_s  the frequency (rad/s)
 *  @param out      out: angle re, im (rad per N m), rate re, im (rad/s per N m)
 *  @retval LADRC_MARGINS_OK        computed
 *  @retval LADRC_MARGINS_ERR_NULL  plant or out is NULL
  *  @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0
  *  @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
  *  @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0
  *  @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY */
ladrc_margins_status_t ladrc_margins_plant_freq(const ladrc_margins_plant_t *plant, double w_rad_s, double out[4]);

/** The measured controller at w (rad/s): out[0..3] = angle re, im, rate re, im
 *  (torque per measured angle and per measured rate).
 *  @param ws       the measured workspace
 *  @param w_rad_s  the frequency (rad/s)
 *  @param out      out: angle re, im (N m/rad), rate re, im (N m s/rad)
 *  @retval LADRC_MARGINS_OK               computed
 *  @retval LADRC_MARGINS_ERR_NULL         ws or out is NULL
 *  @retval LADRC_MARGINS_ERR_NOT_MEASURED ws holds no measured controller */
ladrc_margins_status_t ladrc_margins_controller_freq(const ladrc_margins_workspace_t *ws, double w_rad_s,
                                                     double out[4]);

/** Loop given as a function of complex z (re, im) -> L, with n_unit_poles
 *  poles at z = 1 and every other pole strictly inside the unit circle:
 *  margins and verdict by the same code (for textbook loops). The output
 *  grid is left empty. */
typedef void (*ladrc_margins_loop_fn)(void *ctx, double z_re, double z_im, double *l_re, double *l_im);
/** Margins and verdict of a loop given as a ladrc_margins_loop_fn.
 *  @param fn    the loop L(z); must not be NULL (not checked)
 *  @param ctx   passed to fn
 *  @param dt_s  the sample period (s) the frequencies are scaled by
 *  @param res   out: the result (grid empty); must not be NULL (not checked) */
void ladrc_margins_of_loop(ladrc_margins_loop_fn fn, void *ctx, double dt_s, ladrc_margins_result_t *res);

/**
 * Independent check: the same controller code and exact discrete plant flown
 * in closed loop for n_ticks after an acceleration-disturbance pulse.
 * *growth = max |angle| over the last quarter / max |angle| over the
 * quarter before (0 once the angle has decayed below 1e-6 of its peak, the
 * float controller's rounding); a stable loop's error decays (growth < 1).
 * Linear controllers only need this; adaptive ones are flown as they are.
 * @param ws       the workspace (its controller copies are used)
 * @param ctl      the controller
 * @param plant    the plant
 * @param n_ticks  the run's length (ticks), >= 64
 * @param growth   out: the growth ratio
 * @retval LADRC_MARGINS_OK              flown
 * @retval LADRC_MARGINS_ERR_NULL        ws, ctl, plant or growth is NULL
 * @retval LADRC_MARGINS_ERR_DT_S       plant dt_s not finite and > 0
 * @retval LADRC_MARGINS_ERR_INERTIA    plant inertia_kg_m2 or inertia_factor not finite and > 0
 * @retval LADRC_MARGINS_ERR_DRAG       plant drag_Nm_s not finite and >= 0
 * @retval LADRC_MARGINS_ERR_MOTOR_TAU  plant motor_tau_s not finite and >= 0
 * @retval LADRC_MARGINS_ERR_DELAY      plant delay_ticks outside 0..LADRC_MARGINS_MAX_DELAY
 * @retval LADRC_MARGINS_ERR_REQUEST     not exactly one of attitude and axis, or n_ticks < 64
 * @retval LADRC_MARGINS_ERR_CONTROLLER  a bad axis_index, INDI or RATE-ADRC without use_rate, or its init refuses it
 */
ladrc_margins_status_t ladrc_margins_simulate(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                              const ladrc_margins_plant_t *plant, long n_ticks, double *growth);

/**
 * The tuning's time-domain objective: the controller as it flies (its
 * shaper, estimators and limits), from rest on the exact discrete plant
 * req->plant (lag and delay included), given a reference step of
 * req->track_step_rad for req->step_window_s, then, the reference held, an
 * acceleration-disturbance step of req->dist_step_rad_s2 for as long again.
 * *cost = sum over both windows of (reference - angle)^2 dt (rad^2 s): the
 * square of the RMS error the simulator reports, times the time flown.
 * +INFINITY when |reference - angle| reaches 1 rad (diverged).
 * @param ws    the workspace (its controller copies are used)
 * @param ctl   the controller
 * @param req   the request (plant and steps)
 * @param cost  out: the integral of the squared error (rad^2 s)
 * @retval LADRC_MARGINS_OK          flown
 * @retval LADRC_MARGINS_ERR_NULL    ws, ctl, req or cost is NULL
 * @retval LADRC_MARGINS_ERR_DT_S    plant dt_s not finite and > 0, or not the controller's
 * @retval LADRC_MARGINS_ERR_INERTIA, LADRC_MARGINS_ERR_DRAG, LADRC_MARGINS_ERR_MOTOR_TAU,
 *         LADRC_MARGINS_ERR_DELAY   the plant field named is out of range
 * @retval LADRC_MARGINS_ERR_REQUEST    a request field outside its range
 * @retval LADRC_MARGINS_ERR_CONTROLLER not exactly one of attitude and axis, a bad
 *                                      axis_index, INDI or RATE-ADRC without use_rate, or its init refuses it
 */
ladrc_margins_status_t ladrc_margins_step_cost(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                               const ladrc_margins_request_t *req, double *cost);

/** Targets and search of the margins-based tuning. */
typedef struct {
    double pm_min_deg;       /**< least phase margin (deg), finite; default 45 */
    double gm_min_db;        /**< least gain margins (dB), finite; default 6 */
    double cmd_noise_max_Nm; /**< largest predicted command noise (ladrc_margins_result_t
                                  cmd_noise_Nm, N m) of the request's noise; 0, negative or
                                  not finite: no cap */
} ladrc_margins_targets_t;

/** 1 when a result meets the targets: stable, phase margin and both gain
 *  margins, and its command noise within the cap when the targets cap it
 *  (the result must then carry cmd_noise_Nm: a request with noise).
 *  @param res  the result; must not be NULL (not checked)
 *  @param tg   the targets; must not be NULL (not checked)
 *  @return 1 when it meets them, else 0 */
int ladrc_margins_meets(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg);

/** The tuning's outcome: the gains chosen (those of the variant) and their margins. */
typedef struct {
    int met; /**< 1 when the chosen setting meets the targets */
    /** @{ */
    double wc_rad_s, wo_rad_s; /**< LADRC family */
    /** @} */
    /** @{ */
    double kp, ki, kd, d_filter_tau_s; /**< PID */
    /** @} */
    /** @{ */
    double indi_att_kp_per_s, indi_rate_kp_per_s, indi_filter_rad_s; /**< INDI */
    /** @} */
    /** @{ */
    double radrc_kp_per_s, radrc_att_kp_per_s; /**< RATE-ADRC (its observer's bandwidth: wo_rad_s) */
    /** @} */
    /** @{ */
    double cas_att_kp, cas_rate_kp, cas_rate_ki, cas_rate_kd, cas_d_filter_tau_s; /**< CASCADED */
    /** @} */
    double peak_dist_rad;           /**< peak |d -> error| of the chosen setting (rad per rad/s^2) */
    double step_cost_rad2_s;        /**< its ladrc_margins_step_cost (rad^2 s); NAN when the
                                  request's steps are both 0 */
    double cmd_noise_Nm;            /**< its predicted command noise (N m; margins.cmd_noise_Nm) */
    ladrc_margins_result_t margins; /**< of the chosen setting */
} ladrc_margins_tuning_t;

/**
 * Tunes ctl's axis (its config is copied into *tuned, the axis_index-th axis
 * for an attitude, and the gains written there) for req->plant. A setting
 * meets the targets when its loop is stable with PM >= pm_min_deg and both
 * gain margins >= gm_min_db and, with a noise cap (targets->cmd_noise_max_Nm
 * finite and > 0), its predicted command noise (cmd_noise_Nm of req's angle
 * and rate noise above req->noise_corner_hz) is at most the cap: the cap
 * lowers the bandwidth found below until the noise fits. Searched:
 * LADRC family: wo = r wc, r in {3, 5, 8}; for each r the largest
 * wc whose loop is stable with PM >= pm_min_deg and both gain margins
 * >= gm_min_db (geometric scan by 1.5 from 0.5 rad/s to 0.95 / dt, then
 * bisection to 1 %);
 * PID: kp = J w^2, kd = 2 J w, ki = kp w / m, m in {3, 5, 10}, derivative
 * filter 1 / (10 w) (none if below dt); the largest such w for each m;
 * CASCADED: rate-loop crossover w (cas_rate_kp = J w, ki = kp w / 5,
 * kd = kp / (4 w) through a low pass 1 / (8 w), none if below dt, the
 * default's rule) and cas_att_kp = w / n, n in {3, 4, 6}; the largest such
 * w for each n;
 * INDI: k_att = k_rate = w (the loop (s + w)^2 of LADRC's rule), filter
 * w_f = r w, r in {3, 5, 8} (at most 0.9 pi / dt), the largest such w for
 * each r; INDI needs use_rate (else LADRC_MARGINS_ERR_CONTROLLER);
 * RATE-ADRC: rate-loop crossover radrc_kp_per_s = w, its observer
 * wo = r w, r in {3, 5, 8}, radrc_att_kp_per_s = w / n, n in {4, 3, 2}
 * (4 the default's separation), the largest such w for each (r, n); it
 * needs use_rate too.
 * The adaptive variants' estimator settings are kept; their wc and wo are
 * searched on the plain LADRC loop (estimator off), then lowered (by 1.1,
 * then bisection to 1 %) until the whole variant, as
 * ladrc_margins_analyse_reported analyses it, meets the targets too; and
 * on the whole variant's own loop, searched like LADRC's, r in {3, 5, 8}.
 * Of these candidates, each flown as ladrc_margins_step_cost flies it
 * through req's reference step alone and through its disturbance step
 * alone, the one with the smallest sum of the two costs, each over the
 * smallest among the candidates, wins; one that diverges in a step loses to
 * every one that does not (and if all diverge, the smallest peak
 * |disturbance -> error| wins: steps too large for the airframe never fail
 * a tuning). With both steps 0 the smallest peak wins. out->margins are the
 * winner's margins.
 * Only when none meets the targets does the search widen (what tunes above
 * keeps its gains): the LADRC family at r in {12, 20, 32} (on the core and
 * stepped down, and on the whole loop), ranked the same way.
 * Returns LADRC_MARGINS_ERR_TARGETS_NOT_MET when none meets them, with the
 * closest stable miss (smallest shortfall, gain margin and noise over the
 * cap weighted 3 per dB against 1 per degree) in *tuned and its margins in out->margins (the
 * controller as given when not one candidate was stable).
 * @param ws       the workspace
 * @param ctl      the controller to tune
 * @param req      the request (plant, grid)
 * @param targets  the targets
 * @param tuned    out: the tuned axis config
 * @param out      out: the chosen gains and margins
 * @retval LADRC_MARGINS_OK                setting found that meets the targets
 * @retval LADRC_MARGINS_ERR_NULL          a pointer is NULL
 * @retval LADRC_MARGINS_ERR_CONTROLLER    not exactly one of attitude and axis, or a bad axis_index
 * @retval LADRC_MARGINS_ERR_REQUEST       a request field outside its range, or a margin target not finite
 * @retval LADRC_MARGINS_ERR_TARGETS_NOT_MET no setting meets the targets (closest miss reported)
 * @return otherwise the status of ladrc_margins_analyse_reported on the chosen setting
 *         (the plant statuses, LADRC_MARGINS_ERR_NOT_SETTLED, ...)
 */
ladrc_margins_status_t ladrc_margins_tune(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                          const ladrc_margins_request_t *req, const ladrc_margins_targets_t *targets,
                                          ladrc_axis_config_t *tuned, ladrc_margins_tuning_t *out);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_MARGINS_H */
