/* SPDX-License-Identifier: BSD-3-Clause */
/* The LADRC family's axis (axis.h): LESO, shaped reference and control law;
 * the estimator of LP-MLADRC (axis_lp.c) or HP-MLADRC (axis_hp.c) plugs in
 * through the four hooks below, the family's one dispatch point. */
#include "axis_internal.h"
#if LADRC_WITH_LP_MLADRC
#include "axis_lp.h"
#endif
#if LADRC_WITH_HP_MLADRC
#include "axis_hp.h"
#endif

/* The Euler observer (poles at 1 - wo h) closes a stable loop with the law
 * only for wo h below a bound that shrinks as wc h grows: 0.90 at wc h -> 0,
 * 0.63 at 0.2, 0.38 at 0.5, 0.20 at 0.99 (eigenvalues of the sampled loop on
 * its matched model). 0.88 / (1 + 3.6 wc h) stays below it throughout. */
#define AXIS_EULER_WOH_AT_0 LADRC_R(0.88)
#define AXIS_EULER_WOH_SLOPE LADRC_R(3.6)
/* wc dt below 1: the sampled loop (s + wc)^2 on a double integrator held over
 * each step has its poles inside the unit circle (Jury: 4 - 4 wc dt > 0). */
#define AXIS_WC_DT_LIMIT LADRC_R(1.0)

/* --- the estimator's hooks: none for plain LADRC ----------------------------- */

static ladrc_status_t estimator_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
#if LADRC_WITH_LP_MLADRC
    if (cfg->variant == LADRC_VARIANT_LP_MLADRC) {
        return axis_lp_init(axis, cfg);
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (cfg->variant == LADRC_VARIANT_HP_MLADRC) {
        return axis_hp_init(axis, cfg);
    }
#endif
    (void)axis;
    (void)cfg;
    return LADRC_OK;
}

static void estimator_restart(ladrc_axis_t *axis)
{
#if LADRC_WITH_LP_MLADRC
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        axis_lp_restart(axis);
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        axis_hp_restart(axis);
    }
#endif
    (void)axis;
}

static inline ladrc_real_t estimator_sample(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t acting_Nm)
{
#if LADRC_WITH_LP_MLADRC
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        return axis_lp_sample(axis, rate_rad_s, acting_Nm);
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        return axis_hp_sample(axis, rate_rad_s, acting_Nm);
    }
#endif
    (void)axis;
    (void)rate_rad_s;
    (void)acting_Nm;
    return LADRC_R(0.0);
}

/* The part of f (rad/s^2) the estimator takes over after a restart: plain
 * LADRC none, its LESO carries it all. */
static ladrc_real_t estimator_preset(ladrc_axis_t *axis, ladrc_real_t f_rad_s2)
{
#if LADRC_WITH_LP_MLADRC
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        return axis_lp_preset(axis, f_rad_s2);
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        return axis_hp_preset(axis, f_rad_s2);
    }
#endif
    (void)axis;
    (void)f_rad_s2;
    return LADRC_R(0.0);
}

/* plain LADRC: d_hat itself */
static inline ladrc_real_t estimator_command(ladrc_axis_t *axis, ladrc_real_t d_hat)
{
#if LADRC_WITH_LP_MLADRC
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        return axis_lp_command(axis);
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        return axis_hp_command(axis);
    }
#endif
    (void)axis;
    return d_hat;
}

ladrc_status_t axis_adrc_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (!ladrc_is_positive(cfg->wc_rad_s) || !(cfg->wc_rad_s * cfg->dt_s < AXIS_WC_DT_LIMIT)) {
        return LADRC_ERR_WC_RAD_S;
    }
    if (!axis_b0_is_valid(cfg->b0)) {
        return LADRC_ERR_B0;
    }
    const ladrc_real_t wch = cfg->wc_rad_s * cfg->dt_s;
    if (cfg->leso_method == LADRC_LESO_EULER && ladrc_is_positive(cfg->wo_rad_s) &&
        !(cfg->wo_rad_s * cfg->dt_s * (LADRC_R(1.0) + AXIS_EULER_WOH_SLOPE * wch) <= AXIS_EULER_WOH_AT_0)) {
        return LADRC_ERR_LESO_EULER_UNSTABLE;
    }
    ladrc_status_t status = axis_actuator_init(axis, cfg);
    if (status != LADRC_OK) {
        return status;
    }
    const ladrc_leso_config_t leso_cfg = {
        .dt_s = cfg->dt_s, .wo_rad_s = cfg->wo_rad_s, .b0 = cfg->b0, .method = cfg->leso_method};
    status = ladrc_leso_init(&axis->leso, &leso_cfg);
    if (status == LADRC_OK) {
        status = axis_shaper_init(axis, cfg);
    }
    if (status == LADRC_OK) {
        status = estimator_init(axis, cfg);
    }
    if (status != LADRC_OK) {
        return status;
    }
    axis->kp = cfg->wc_rad_s * cfg->wc_rad_s;
    axis->kd = LADRC_R(2.0) * cfg->wc_rad_s;
    axis_approach_init(axis, cfg, LADRC_R(0.5) * cfg->wc_rad_s); /* the law's closing rate is (wc / 2) e */
    axis->b0 = cfg->b0;
    return LADRC_OK;
}

/* The law's u0 = wc^2 e + 2 wc (r' - z2) + r'' (axis.h), on the axis's
 * shaped reference and observer: the one formula of the step and of engage.
 * It is 2 wc ((wc / 2) e + r' - z2) + r'': it asks to close the error at the
 * rate (wc / 2) e, and beyond linear_rad at the braking rate instead
 * (axis_shared.h), so that a large error is not overshot. */
static inline ladrc_real_t law_u0(const ladrc_axis_t *axis, ladrc_real_t error_rad)
{
    if (ladrc_fabs(error_rad) > axis->linear_rad) {
        return axis->kd * (axis_braking_rate(axis, error_rad) + axis->ref.dr - axis->leso.z2) + axis->ref.ddr;
    }
    return axis->kp * error_rad + axis->kd * (axis->ref.dr - axis->leso.z2) + axis->ref.ddr;
}

void axis_adrc_engage(ladrc_axis_t *axis, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm)
{
    axis->leso.z2 = rate_rad_s;
    /* u = (u0 - z3 - d_hat) / b0 = torque at zero error: the disturbance
     * f = u0 - b0 torque, shared between the estimator and z3 */
    const ladrc_real_t f = law_u0(axis, LADRC_R(0.0)) - axis->b0 * torque_Nm;
    axis->d_hat_rad_s2 = estimator_preset(axis, f);
    axis->leso.z3 = f - axis->d_hat_rad_s2;
}

/* The observer at rest on angle_rad and the estimator from scratch. */
static void restart_estimates(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_leso_reset(&axis->leso, angle_rad);
    estimator_restart(axis);
    axis->d_hat_rad_s2 = LADRC_R(0.0);
}

void axis_adrc_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    restart_estimates(axis, angle_rad);
    axis_shaper_reset(axis, angle_rad);
}

/* A wrapped axis: z1 and r both beyond +pi (or -pi) move one turn back,
 * with the shaper's state. Both lie within 4 pi of 0 (pi past the bound at
 * most, plus the |r - z1| < 2 pi the wrapped law allows), so each shift by
 * LADRC_TWO_PI is exact (Sterbenz) and r - z1 keeps every bit: the law sees
 * no change. Without it z1 and r would grow with every turn and lose a bit
 * of resolution at each doubling (a float at 1000 rad resolves 6e-5 rad). */
static void recentre(ladrc_axis_t *axis)
{
    const ladrc_real_t z1 = axis->leso.z1;
    const ladrc_real_t r = axis->ref.r;
    ladrc_real_t turn;
    if (z1 > LADRC_PI && r > LADRC_PI) {
        turn = -LADRC_TWO_PI;
    } else if (z1 < -LADRC_PI && r < -LADRC_PI) {
        turn = LADRC_TWO_PI;
    } else {
        return;
    }
    axis->leso.z1 = z1 + turn;
    axis_shift_reference(axis, turn);
}

/* The tick on finite ref and angle; returns the state fault, if any. The
 * estimators' own faults (e.g. a missing rate) only hold their estimate, so
 * they are not reported as axis faults beyond LADRC_FAULT_RATE. */
ladrc_fault_t axis_adrc_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s,
                             int has_rate)
{
    const ladrc_leso_t *leso = &axis->leso;
    ladrc_ref_t *ref = &axis->ref;
    if (axis->wrap) {
        /* Whole turns off the measurement and the reference (axis.h). */
        angle_rad = ladrc_unwrap_near(angle_rad, leso->z1);
        ref_rad = ladrc_unwrap_near(ref_rad, ref->r);
    }
    /* The LESO must see what really acted: the acting torque and the estimate. */
    const ladrc_real_t acting_Nm = axis_advance_actuator(axis);
    ladrc_fault_t faults = ladrc_leso_step(&axis->leso, angle_rad, acting_Nm, axis->d_hat_rad_s2, axis->f_rate_rad_s3);
    faults |= axis_shape_reference(axis, ref_rad);
    /* A tick without a rate gives the estimator NaN: a gap. */
    const ladrc_real_t d_hat = estimator_sample(axis, has_rate ? rate_rad_s : (ladrc_real_t)NAN, acting_Nm);
    ladrc_real_t error_rad = ref->r - leso->z1;
    if (axis->wrap) {
        error_rad = ladrc_wrap_pi(error_rad);
        recentre(axis);
    }
    const ladrc_real_t u0 = law_u0(axis, error_rad);
    /* With an actuator model the command carries d_hat advanced over it
     * (estimator.h); d_hat stays the observer's known input. */
    const ladrc_real_t compensation = axis->model ? estimator_command(axis, d_hat) : d_hat;
    const ladrc_real_t u = (u0 - leso->z3 - compensation) / axis->b0;
    if (!ladrc_is_finite(u)) {
        /* The command is held; what made it non-finite must not outlive the
         * tick, so the estimates restart from the measurement. */
        restart_estimates(axis, angle_rad);
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->d_hat_rad_s2 = d_hat;
    axis->output_Nm = ladrc_clamp(u, axis->u_min_Nm, axis->u_max_Nm);
    return faults;
}

ladrc_real_t axis_adrc_accel(const ladrc_axis_t *axis)
{
    return axis_observer_accel(axis);
}

void axis_adrc_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                        ladrc_real_t *disturbance_rad_s2)
{
    *angle_rad = axis->leso.z1;
    *rate_rad_s = axis->leso.z2;
    *disturbance_rad_s2 = axis->leso.z3 + axis->d_hat_rad_s2;
}
