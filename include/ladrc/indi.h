/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file indi.h
 * @brief Incremental nonlinear dynamic inversion (INDI) on one attitude axis:
 *        the baseline that, like LP-MLADRC, works on the measured angular
 *        acceleration. Used through axis.h (LADRC_VARIANT_INDI).
 *
 * Structure (Smeur, Chu and de Croon, "Adaptive Incremental Nonlinear Dynamic
 * Inversion for Attitude Control of Micro Air Vehicles", JGCD 2016; the
 * attitude INDI of Paparazzi): the axis obeys omega' = G u + d with G = b0
 * (rad/s^2 per N m) and an unknown d. Measuring omega' and knowing the torque
 * that produced it, the increment that turns the present acceleration into
 * the wanted one nu is (nu - omega') / G, added to that torque:
 *
 *     u_k = u_f,k + J (nu_k - omegadot_f,k),        J = 1 / b0
 *
 * where omegadot_f and u_f are the measured acceleration and the torque that
 * produced it, both through the SAME low-pass filter F (below): then
 * omegadot_f - b0 u_f = F d exactly, and u_k = J (nu_k - (F d)_k), the
 * dynamic inversion with the disturbance estimated as F d. With G exact the
 * loop sees omega' = nu + (1 - z^-1 F) d: a constant d is rejected
 * completely (F(1) = 1), with no integrator to wind up.
 *
 * Outer loops (the P-on-attitude, P-on-rate cascade of PX4 and ArduPilot,
 * with the reference's derivatives fed forward): r, r', r'' from the axis's
 * shaper, theta and omega measured,
 *
 *     omega_ref  = k_att (r - theta) + r'                 (error mod 2 pi on a wrapped axis)
 *     nu         = k_rate (omega_ref - omega) + omega_ref'
 *     omega_ref' = k_att (r' - omega) + r''
 *
 * so that with omega' = nu the error obeys e'' + (k_att + k_rate) e' +
 * k_att k_rate e = 0: poles at -k_att and -k_rate (gains in 1/s).
 *
 * Acceleration and torque (tick k, h = dt_s). The measured rate is
 * differenced, omegadot_k = (omega_k - omega_k-1) / h, and the torque that
 * acted over that same step is the axis's acting torque ubar_k
 * (ladrc_axis_get_acting_Nm: the applied torque of tick k-1, or, with the
 * actuator model, the applied torque delayed by delay_ticks and lagged by
 * motor_tau_s, averaged over the step). For the rigid body with the torque
 * held over the step, omegadot_k = b0 ubar_k + (mean d over the step)
 * holds exactly, so the pair is synchronised before filtering, and stays so
 * after it because both go through the same filter, one formula
 * (one filter step, twice):
 *
 *     F(z) = (alpha / (1 - (1 - alpha) z^-1))^2,   alpha = 1 - exp(-w_f h)
 *
 * two cascaded first-order stages s += alpha (x - s): the critically damped
 * low-pass w_f^2 / (s + w_f)^2, each stage discretised exactly (step
 * invariant) so the poles sit at exp(-w_f h) for any w_f h (Tustin would warp
 * them near Nyquist). Critically damped rather than Butterworth: no overshoot,
 * so a torque step does not return as a filtered overshoot in u_f; the blend
 * form keeps F(1) = 1 to the last bit, which the rejection of a constant d
 * rests on. The filter's lag does not enter the loop from nu (it cancels
 * between u_f and omegadot_f); it only sets how fast d is followed, and how
 * much gyro noise reaches the torque: white gyro noise of std sigma per
 * sample leaves omegadot_f with a std of about sigma sqrt(h w_f^3) / 2
 * (10 sigma at h = 1 ms, w_f = 75 rad/s), times J in the command.
 *
 * Without a measured rate INDI has no acceleration: a tick without one (or
 * with a rate outside its plausible range) holds the previous command and
 * raises LADRC_FAULT_RATE. The angle is not differentiated twice instead: at
 * 1 kHz an angle noise of 5e-4 rad (the paper's noisy case) becomes 1.4
 * rad/s of rate noise and 1000 rad/s^2 of acceleration noise before the
 * filter. The filters wait over such a gap; the next tick with a rate feeds
 * them one step with the mean acceleration over the gap,
 * (omega_k - omega_last) / (n h), and the mean acting torque over the same
 * n steps, which still satisfy the identity above, so they stay
 * synchronised. After a reset the first rate only seeds omega_last.
 *
 * Saturation: u_f is the filtered torque that ACTED (what set_applied
 * reported), not the command, so a saturated actuator leaves nothing to wind
 * up: the next increment starts from what the actuator delivered.
 *
 * Adaptive effectiveness (adapt = 1; the "adaptive" of Smeur et al. 2016,
 * who estimate G online by least mean squares on the filtered increments).
 * The identity above holds for the TRUE effectiveness G: omegadot_f = G u_f
 * + F d, so between two filter steps
 *
 *     domegadot_f = G du_f + d(F d),   du_f = u_f,k - u_f,k-1,
 *                                      domegadot_f = omegadot_f,k - omegadot_f,k-1
 *
 * (the same filter F, so no extra lag enters). Each filter step whose
 * increment is large enough, |du_f| >= du_min, moves the estimate by the
 * normalised LMS step
 *
 *     G <- clamp(G - mu (G du_f - domegadot_f) du_f / (du_f^2 + du_min^2), G_lo, G_hi)
 *
 * then J = 1 / G serves the command and G the disturbance (omegadot_f - G
 * u_f). Dividing by du_f^2 makes mu dimensionless and the step the same for
 * any torque scale: one step moves G a fraction of about mu toward the
 * sample's ratio domegadot_f / du_f, so G follows a change with a time
 * constant of about dt_s / mu seconds of excitation (the du_min^2 term
 * halves the weight of increments at the threshold and keeps the step
 * finite). The threshold is an expected jerk: du_min = jerk_min dt_s / |b0|,
 * so slow, noise-sized increments (hover) leave G alone. Bounds: G stays
 * between min_ratio b0 and max_ratio b0 (its sign is b0's: a G through zero
 * would invert the loop). No step is taken on a non-finite sample or one
 * whose result is not finite (the estimate keeps its last good value). The
 * estimate is unbiased while the disturbance is steady over the increments
 * (d(F d) = 0); a disturbance that changes with the command biases it, as
 * any closed-loop identification. adapt = 0: G = b0 always, the arithmetic
 * of the fixed law bit for bit. A reset restarts G at b0.
 */
#ifndef LADRC_INDI_H
#define LADRC_INDI_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest w_f dt_s: the filter's corner at the Nyquist frequency. */
#define LADRC_INDI_FILTER_WH_MAX LADRC_PI

/** INDI configuration (ladrc_indi_init validates it). */
typedef struct {
    ladrc_real_t dt_s;          /**< fixed step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    ladrc_real_t b0;            /**< control effectiveness G (rad/s^2 per N m), |b0| in [1e-3, 1e7] */
    ladrc_real_t att_kp_per_s;  /**< k_att (1/s), > 0, k_att dt_s < 1 */
    ladrc_real_t rate_kp_per_s; /**< k_rate (1/s), > 0, k_rate dt_s < 1 */
    ladrc_real_t filter_rad_s;  /**< w_f (rad/s), > 0, w_f dt_s <= pi */
    uint8_t adapt;              /**< 1: G adapted online (see above), 0: G = b0 */
    /* Read only when adapt is 1: */
    ladrc_real_t adapt_mu;              /**< normalised LMS step mu (dimensionless), in (0, 1] */
    ladrc_real_t adapt_jerk_min_rad_s3; /**< excitation threshold: least |b0 du_f| / dt_s
                                             (rad/s^3) for a step, finite, > 0 */
    ladrc_real_t adapt_min_ratio;       /**< G_lo / b0, in (0, 1], |b0| min_ratio >= 1e-3 */
    ladrc_real_t adapt_max_ratio;       /**< G_hi / b0, >= 1, finite, |b0| max_ratio <= 1e7 */
} ladrc_indi_config_t;

/** Two first-order stages of the filter F (see above). */
typedef struct {
    /** @{ */
    ladrc_real_t s1, s2; /**< outputs of the first and second stage */
    /** @} */
} ladrc_indi_lowpass_t;

/** INDI state; owned by the axis. */
typedef struct {
    ladrc_real_t inv_dt; /**< 1 / h */
    ladrc_real_t j;      /**< J = 1 / G (N m per rad/s^2) */
    ladrc_real_t b0;     /**< G of the config (rad/s^2 per N m) */
    ladrc_real_t g;      /**< G in use (rad/s^2 per N m): b0, or its online estimate */
    /** @{ */
    ladrc_real_t g_lo, g_hi; /**< bounds of the estimate (rad/s^2 per N m), g_lo < g_hi */
    /** @} */
    ladrc_real_t mu;        /**< adapt_mu */
    ladrc_real_t du_min_Nm; /**< excitation threshold on |du_f| (N m) */
    ladrc_real_t du_min_sq; /**< du_min^2 (N^2 m^2) */
    /** @{ */
    ladrc_real_t k_att, k_rate; /**< k_att and k_rate of the config (1/s) */
    /** @} */
    ladrc_real_t alpha;           /**< 1 - exp(-w_f h) */
    ladrc_indi_lowpass_t accel;   /**< F of the differenced rate: omegadot_f (rad/s^2) */
    ladrc_indi_lowpass_t torque;  /**< F of the acting torque: u_f (N m) */
    ladrc_real_t rate_last_rad_s; /**< rate of the last tick that had one */
    ladrc_real_t gap_torque_Nm;   /**< sum of the acting torques since then */
    ladrc_real_t angle_rad;       /**< measured angle of the last tick with a rate */
    uint32_t gap_ticks;           /**< steps since then */
    uint8_t has_rate_last;        /**< 0 after a reset until a first rate */
    uint8_t adapt;                /**< of the config */
} ladrc_indi_t;

/**
 * Validates cfg in the order below and resets (ladrc_indi_reset).
 * @param[out] indi  the controller to set up
 * @param[in]  cfg   its configuration
 * @retval LADRC_OK               set up
 * @retval LADRC_ERR_NULL         indi or cfg is NULL
 * @retval LADRC_ERR_DT_S         dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_B0           |b0| not in [1e-3, 1e7] (or NaN)
 * @retval LADRC_ERR_INDI_ATT_KP  att_kp_per_s not finite, not > 0, or times dt_s >= 1
 * @retval LADRC_ERR_INDI_RATE_KP rate_kp_per_s not finite, not > 0, or times dt_s >= 1
 * @retval LADRC_ERR_INDI_FILTER  filter_rad_s not finite, not > 0, or times dt_s > LADRC_INDI_FILTER_WH_MAX
 * @retval LADRC_ERR_INDI_ADAPT   adapt not 0 or 1
 * @retval LADRC_ERR_INDI_ADAPT_MU         adapt: adapt_mu not finite or not in (0, 1]
 * @retval LADRC_ERR_INDI_ADAPT_EXCITATION adapt: adapt_jerk_min_rad_s3 not finite, not > 0, or
 *                                         its du_min = jerk_min dt_s / |b0| (or du_min^2) not > 0
 * @retval LADRC_ERR_INDI_ADAPT_MIN        adapt: adapt_min_ratio not finite, not in (0, 1], or
 *                                         |b0| min_ratio below 1e-3
 * @retval LADRC_ERR_INDI_ADAPT_MAX        adapt: adapt_max_ratio not finite, below 1, or |b0|
 *                                         max_ratio above 1e7
 */
ladrc_status_t ladrc_indi_init(ladrc_indi_t *indi, const ladrc_indi_config_t *cfg);

/** At rest: filters at 0, no previous rate, no gap, G = b0.
 *  @param indi  the controller; NULL: nothing happens */
void ladrc_indi_reset(ladrc_indi_t *indi);

/** Takes over from another controller: restarts as ladrc_indi_reset, as if
 *  torque_Nm had been acting steadily at the measured rate (the torque
 *  filter at it, the acceleration filter at rest), so that a first tick
 *  asking for no acceleration continues torque_Nm.
 *  @param indi        the controller; NULL: nothing happens
 *  @param angle_rad   the measured angle (rad)
 *  @param rate_rad_s  the measured rate (rad/s), or NULL without one
 *  @param torque_Nm   the other controller's last command (N m) */
void ladrc_indi_engage(ladrc_indi_t *indi, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s,
                       ladrc_real_t torque_Nm);

/**
 * The measurement half of a tick: acting_Nm is the torque that acted over the
 * step just ended (ladrc_axis_get_acting_Nm). With a rate (rate_rad_s not NULL)
 * the filters take the step (or the gap's mean) and 1 is returned; without
 * one the step joins the gap and 0 is returned (hold the command). The first
 * rate after a reset only seeds: 1, filters unchanged. With adapt, each
 * filter step also takes the LMS step on G (see above). The inputs are not
 * checked for finiteness (the axis checks them first).
 * @param indi        the controller; NULL: 0, nothing changes
 * @param acting_Nm   the torque that acted over the step (N m)
 * @param rate_rad_s  the measured rate (rad/s), or NULL without one
 * @return 1 with a rate, 0 without one
 */
int ladrc_indi_measure(ladrc_indi_t *indi, ladrc_real_t acting_Nm, const ladrc_real_t *rate_rad_s);

/** The command u = u_f + J (nu - omegadot_f) for the attitude error
 *  (r - theta, already wrapped), the shaped reference's r' and r'' and the
 *  measured rate. Not checked for finiteness (the axis clamps and checks).
 *  @param indi              the controller; NULL: 0
 *  @param error_rad         r - theta (rad), wrapped for a wrapped angle
 *  @param ref_rate_rad_s    r' (rad/s)
 *  @param ref_accel_rad_s2  r'' (rad/s^2)
 *  @param rate_rad_s        the measured rate (rad/s)
 *  @return the command (N m), unclamped; non-finite for absurd inputs */
ladrc_real_t ladrc_indi_command(const ladrc_indi_t *indi, ladrc_real_t error_rad, ladrc_real_t ref_rate_rad_s,
                                ladrc_real_t ref_accel_rad_s2, ladrc_real_t rate_rad_s);

/** The disturbance INDI acts on, omegadot_f - G u_f = (F d).
 *  @param indi  the controller; NULL: 0
 *  @return the filtered disturbance (rad/s^2) */
ladrc_real_t ladrc_indi_get_disturbance(const ladrc_indi_t *indi);

/** The control effectiveness G in use: b0 without adaptation, else the
 *  online estimate, always within [G_lo, G_hi].
 *  @param indi  the controller; NULL: 0
 *  @return G (rad/s^2 per N m) */
ladrc_real_t ladrc_indi_get_effectiveness(const ladrc_indi_t *indi);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_INDI_H */
