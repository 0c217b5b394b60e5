/* SPDX-License-Identifier: BSD-3-Clause */
/* Cascaded attitude P / rate PID controller (see cascaded.h). */
#include "ladrc/cascaded.h"
#include "require.h"

#include <stddef.h>

/* Largest size of one term of the command over the inputs' ranges: a
 * quarter of the real type's range, so that the P, D and feed-forward terms
 * together stay within three quarters of it (and an integral step within a
 * quarter). */
#define CAS_TERM_MAX (LADRC_REAL_MAX * LADRC_R(0.25))
/* att_kp dt below 1: the sampled attitude loop on an ideal rate loop (an
 * integrator held over each step) has its pole 1 - att_kp dt inside the
 * unit circle and does not ring. */
#define CAS_ATT_KP_DT_LIMIT LADRC_R(1.0)

static int is_non_negative(ladrc_real_t x)
{
    return ladrc_is_finite(x) && x >= LADRC_R(0.0);
}

/* gain * size within CAS_TERM_MAX (gain >= 0 finite, size > 0 finite). */
static int term_fits(ladrc_real_t gain, ladrc_real_t size)
{
    return gain <= CAS_TERM_MAX / size;
}

/* e_relax > 0 (INFINITY included) whose inverse is finite, so that the
 * relax factor never multiplies 0 by infinity. NaN fails. */
static int relax_is_valid(ladrc_real_t e_relax_rad_s)
{
    return e_relax_rad_s > LADRC_R(0.0) && ladrc_is_finite(LADRC_R(1.0) / e_relax_rad_s);
}

/* The relax factor g = max(0, 1 - (e / e_relax)^2) (cascaded.h); exactly 1
 * when inv_relax is 0 (no relax). */
static inline ladrc_real_t relax_factor(ladrc_real_t inv_relax_s_rad, ladrc_real_t rate_error_rad_s)
{
    const ladrc_real_t x = rate_error_rad_s * inv_relax_s_rad;
    const ladrc_real_t g = LADRC_R(1.0) - x * x;
    return (g > LADRC_R(0.0)) ? g : LADRC_R(0.0);
}

ladrc_status_t ladrc_cascaded_init(ladrc_cascaded_t *c, const ladrc_cascaded_config_t *cfg)
{
    if (c == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    const ladrc_real_t h = cfg->dt_s;
    if (!ladrc_dt_is_valid(h)) {
        return LADRC_ERR_DT_S;
    }
    if (!ladrc_is_positive(cfg->att_kp_per_s) || !(cfg->att_kp_per_s * h < CAS_ATT_KP_DT_LIMIT)) {
        return LADRC_ERR_CAS_ATT_KP;
    }
    /* A setpoint beyond the rates the axis can measure is no setpoint. */
    const ladrc_real_t range = cfg->rate_limit_rad_s;
    if (!(ladrc_is_positive(range) && ladrc_is_positive(cfg->rate_max_rad_s) && cfg->rate_max_rad_s <= range)) {
        return LADRC_ERR_CAS_RATE_MAX;
    }
    /* |e_w| <= rate_max + |m| <= 2 range; |(m_k - m_k-1) / h| <= 2 range / h. */
    const ladrc_real_t err_max = LADRC_R(2.0) * range;
    if (!(is_non_negative(cfg->rate_kp) && term_fits(cfg->rate_kp, err_max))) {
        return LADRC_ERR_CAS_RATE_KP;
    }
    if (!(is_non_negative(cfg->rate_ki) && term_fits(cfg->rate_ki * h, err_max))) {
        return LADRC_ERR_CAS_RATE_KI;
    }
    if (!(is_non_negative(cfg->rate_kd) && term_fits(cfg->rate_kd, err_max / h))) {
        return LADRC_ERR_CAS_RATE_KD;
    }
    if (!is_non_negative(cfg->d_filter_tau_s)) {
        return LADRC_ERR_CAS_D_TAU_S;
    }
    if (!is_non_negative(cfg->rate_filter_tau_s)) {
        return LADRC_ERR_CAS_RATE_TAU_S;
    }
    if (!(cfg->i_limit_Nm >= LADRC_R(0.0))) { /* INFINITY: no clamp; NaN fails */
        return LADRC_ERR_CAS_I_LIMIT_NM;
    }
    if (!relax_is_valid(cfg->i_relax_rad_s)) {
        return LADRC_ERR_CAS_I_RELAX;
    }
    /* |w_sp| <= rate_max. */
    if (!(is_non_negative(cfg->rate_ff) && term_fits(cfg->rate_ff, cfg->rate_max_rad_s))) {
        return LADRC_ERR_CAS_RATE_FF;
    }
    if (cfg->setpoint_ff > 1u) {
        return LADRC_ERR_CAS_SETPOINT_FF;
    }
    if (!(cfg->u_min_Nm < LADRC_R(0.0) && cfg->u_max_Nm > LADRC_R(0.0))) {
        return LADRC_ERR_U_LIMITS;
    }
    if (cfg->wrap_angle > 1u) {
        return LADRC_ERR_WRAP_ANGLE;
    }
    c->dt_s = h;
    c->inv_dt = LADRC_R(1.0) / h;
    c->att_kp_per_s = cfg->att_kp_per_s;
    c->rate_max_rad_s = cfg->rate_max_rad_s;
    c->rate_kp = cfg->rate_kp;
    c->rate_ki_dt = cfg->rate_ki * h;
    c->rate_kd = cfg->rate_kd;
    c->inv_relax_s_rad = LADRC_R(1.0) / cfg->i_relax_rad_s; /* INFINITY: 0, no relax */
    c->rate_ff = cfg->rate_ff;
    c->setpoint_ff = cfg->setpoint_ff;
    c->landed = 0u;
    c->d_alpha = h / (cfg->d_filter_tau_s + h);
    c->d_keep = LADRC_R(1.0) - c->d_alpha;
    c->w_alpha = h / (cfg->rate_filter_tau_s + h);
    c->w_keep = LADRC_R(1.0) - c->w_alpha;
    c->i_limit_Nm = cfg->i_limit_Nm;
    c->rate_limit_rad_s = range;
    c->u_min_Nm = cfg->u_min_Nm;
    c->u_max_Nm = cfg->u_max_Nm;
    c->wrap = cfg->wrap_angle;
    ladrc_cascaded_reset(c, LADRC_R(0.0));
    return LADRC_OK;
}

void ladrc_cascaded_reset(ladrc_cascaded_t *c, ladrc_real_t angle_rad)
{
    LADRC_REQUIRE_VOID(c != NULL);
    c->integral_Nm = LADRC_R(0.0);
    c->rate_rad_s = LADRC_R(0.0);
    c->accel_rad_s2 = LADRC_R(0.0);
    c->prev_angle_rad = angle_rad;
    c->rate_sp_rad_s = LADRC_R(0.0);
    c->unclamped_Nm = LADRC_R(0.0);
    c->output_Nm = LADRC_R(0.0);
    c->applied_Nm = LADRC_R(0.0);
    c->has_prev = 0u;
}

void ladrc_cascaded_engage(ladrc_cascaded_t *c, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s, ladrc_real_t torque_Nm)
{
    LADRC_REQUIRE_VOID(c != NULL);
    ladrc_cascaded_reset(c, angle_rad);
    c->rate_rad_s = rate_rad_s;
    c->integral_Nm = ladrc_clamp(torque_Nm, -c->i_limit_Nm, c->i_limit_Nm);
    c->unclamped_Nm = torque_Nm;
    c->output_Nm = torque_Nm;
    c->applied_Nm = torque_Nm;
}

/* m_k: the measured rate, or the filtered difference of the angle. */
static ladrc_real_t rate_of_tick(const ladrc_cascaded_t *c, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s)
{
    if (rate_rad_s != NULL) {
        return *rate_rad_s;
    }
    if (!c->has_prev) {
        return c->rate_rad_s; /* nothing to difference yet */
    }
    ladrc_real_t diff_rad = angle_rad - c->prev_angle_rad;
    if (c->wrap) {
        diff_rad = ladrc_wrap_pi(diff_rad);
    }
    const ladrc_real_t m = ladrc_lowpass_blend(c->w_keep, c->w_alpha, c->rate_rad_s, diff_rad * c->inv_dt);
    return ladrc_clamp(m, -c->rate_limit_rad_s, c->rate_limit_rad_s);
}

ladrc_fault_t ladrc_cascaded_step(ladrc_cascaded_t *c, const ladrc_ref_t *ref, ladrc_real_t angle_rad,
                                  const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm)
{
    LADRC_REQUIRE(c != NULL && ref != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    ladrc_real_t error_rad = ref->r - angle_rad;
    if (c->wrap) {
        error_rad = ladrc_wrap_pi(error_rad);
    }
    const ladrc_real_t setpoint_rate = c->setpoint_ff ? ref->dr : LADRC_R(0.0);
    const ladrc_real_t rate_sp =
        ladrc_clamp(c->att_kp_per_s * error_rad + setpoint_rate, -c->rate_max_rad_s, c->rate_max_rad_s);
    const ladrc_real_t m = rate_of_tick(c, angle_rad, rate_rad_s);
    const ladrc_real_t dm = c->has_prev ? (m - c->rate_rad_s) * c->inv_dt : LADRC_R(0.0);
    const ladrc_real_t accel = ladrc_lowpass_blend(c->d_keep, c->d_alpha, c->accel_rad_s2, dm);
    const ladrc_real_t rate_error = rate_sp - m;
    /* The command takes the integral of the errors before this tick; this
     * tick's error enters it afterwards (cascaded.h). */
    const ladrc_real_t unclamped = c->rate_kp * rate_error + c->integral_Nm - c->rate_kd * accel + c->rate_ff * rate_sp;
    ladrc_real_t integral = c->integral_Nm;
    if (!c->landed && !ladrc_integrator_frozen(rate_error, c->applied_Nm, c->unclamped_Nm)) {
        const ladrc_real_t step = relax_factor(c->inv_relax_s_rad, rate_error) * c->rate_ki_dt * rate_error;
        integral = ladrc_clamp(integral + step, -c->i_limit_Nm, c->i_limit_Nm);
    }
    if (!ladrc_all_finite4(m, accel, integral, unclamped)) {
        *torque_Nm = c->output_Nm;
        return LADRC_FAULT_STATE;
    }
    c->rate_rad_s = m;
    c->accel_rad_s2 = accel;
    c->integral_Nm = integral;
    c->prev_angle_rad = angle_rad;
    c->rate_sp_rad_s = rate_sp;
    c->unclamped_Nm = unclamped;
    c->output_Nm = ladrc_clamp(unclamped, c->u_min_Nm, c->u_max_Nm);
    c->applied_Nm = c->output_Nm;
    c->has_prev = 1u;
    *torque_Nm = c->output_Nm;
    return LADRC_FAULT_NONE;
}

void ladrc_cascaded_set_applied(ladrc_cascaded_t *c, ladrc_real_t applied_Nm)
{
    LADRC_REQUIRE_VOID(c != NULL);
    c->applied_Nm = applied_Nm;
}

void ladrc_cascaded_set_landed(ladrc_cascaded_t *c, uint8_t landed)
{
    LADRC_REQUIRE_VOID(c != NULL);
    c->landed = (landed != 0u) ? 1u : 0u;
}
