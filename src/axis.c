/* SPDX-License-Identifier: BSD-3-Clause */
/* One attitude axis: LADRC, its modified variants or PID behind one API (see axis.h). */
#include "ladrc/axis.h"

/* Paper settings (Section 5) used by ladrc_axis_config_default. */
#define AXIS_DEFAULT_WC_RAD_S LADRC_R(15.0)
#define AXIS_DEFAULT_WO_RAD_S LADRC_R(75.0)
/* At most the initial acceleration the ideal loop (s + wc)^2 asks for a 10 deg
 * step (wc^2 * 0.17 rad = 39 rad/s^2), so shaping lowers the torque peak;
 * the shaped 10 deg step still takes only 2 sqrt(0.17 / 20) = 0.19 s. */
#define AXIS_DEFAULT_TD_ACCEL_RAD_S2 LADRC_R(20.0)
/* Levant for the modified variants: L bounds |r''''|. 1000 rad/s^4 converges on
 * the paper's 20 deg initial reference step within 1 s and then tracks its
 * 15 deg swing to 0.1 deg (LP) / 0.02 deg (HP) on the coupled test body;
 * 100 leaves 0.18 deg, 10 leaves 4.8 deg (too slow for the start), and
 * 10000 lets the step's transient into HP (0.8 deg). */
#define AXIS_DEFAULT_LEVANT_LIPSCHITZ_RAD_S4 LADRC_R(1000.0)
/* INDI (axis.h): the LADRC default's closed loop (s + wc)^2 and its
 * observer's bandwidth for the acceleration filter. */
#define AXIS_DEFAULT_INDI_ATT_KP_PER_S AXIS_DEFAULT_WC_RAD_S
#define AXIS_DEFAULT_INDI_RATE_KP_PER_S AXIS_DEFAULT_WC_RAD_S
#define AXIS_DEFAULT_INDI_FILTER_RAD_S AXIS_DEFAULT_WO_RAD_S
#define AXIS_DEFAULT_PID_KP LADRC_R(20.0)
#define AXIS_DEFAULT_PID_KI LADRC_R(20.0)
#define AXIS_DEFAULT_PID_KD LADRC_R(0.05)
/* CASCADED (axis.h): the rate loop crosses over at the paper's observer
 * bandwidth wo (where LADRC's disturbance rejection acts), the attitude
 * gain a quarter of that (the P parts then put a critically damped double
 * pole at wr / 2); the integral corner a fifth below wr, the derivative a
 * quarter of the P torque in quadrature at wr, filtered at 8 wr.
 * 220 deg/s: PX4's default maximum roll and pitch rate (MC_ROLLRATE_MAX). */
#define AXIS_DEFAULT_CAS_RATE_BW_RAD_S AXIS_DEFAULT_WO_RAD_S
#define AXIS_DEFAULT_CAS_ATT_PER_BW LADRC_R(0.25)
#define AXIS_DEFAULT_CAS_I_CORNER LADRC_R(5.0)
#define AXIS_DEFAULT_CAS_D_QUADRATURE LADRC_R(4.0)
#define AXIS_DEFAULT_CAS_D_FILTER LADRC_R(8.0)
#define AXIS_DEFAULT_CAS_RATE_MAX_RAD_S LADRC_R(3.8397243543875251) /* 220 deg/s */
#define AXIS_DEFAULT_LP_LAMBDA0_PER_S LADRC_R(100.0)
#define AXIS_DEFAULT_LP_K0_PER_S LADRC_R(300.0)
/* HP: the search range covers 0.5..30 rad/s with margin. The fit forgets at
 * most 5 /s: a change is followed within 0.2 s, and (estimator.h) slower
 * locked tones lengthen the memory to a radian of their phase. Tracking at a
 * quarter of that rate is critically damped (estimator.h). The acquisition
 * filter at 10 rad/s passes the range's middle with little lag and still
 * weights 40 rad/s by (10/40)^4 (only the ratio of its two averages counts,
 * so a lone tone gives its exact frequency at any wf). First guesses 3 and
 * 8 rad/s: mid-range and apart. */
#define AXIS_DEFAULT_HP_N_TONES 2u
#define AXIS_DEFAULT_HP_FREQ_RAD_S LADRC_R(3.0)
#define AXIS_DEFAULT_HP_FREQ2_RAD_S LADRC_R(8.0)
#define AXIS_DEFAULT_HP_FREQ_MIN_RAD_S LADRC_R(0.3)
#define AXIS_DEFAULT_HP_FREQ_MAX_RAD_S LADRC_R(40.0)
#define AXIS_DEFAULT_HP_LAMBDA0_PER_S LADRC_R(8.0)
#define AXIS_DEFAULT_HP_FREQ_LAMBDA0_PER_S LADRC_R(2.0)
#define AXIS_DEFAULT_HP_FREQ_FILTER_RAD_S LADRC_R(20.0)
/* The fit samples the observer's output (bandwidth 75 rad/s, a time constant
 * of 13 ms) every 4 ms: a quarter of the work of fitting every tick at 1 kHz,
 * and 40 rad/s turns by only 0.16 rad between fit samples. */
#define AXIS_DEFAULT_HP_FIT_SAMPLE_S LADRC_R(0.004)

/* Plausible ranges: beyond any real flight, far inside float. An unwrapped
 * yaw reaches 1000 rad after 160 turns (float still resolves 6e-5 rad there);
 * gyros saturate at 35-70 rad/s; 1e4 rad/s^2 is ten times a racing quad's
 * angular acceleration. */
#define AXIS_DEFAULT_ANGLE_LIMIT_RAD LADRC_R(1000.0)
#define AXIS_DEFAULT_RATE_LIMIT_RAD_S LADRC_R(100.0)
#define AXIS_DEFAULT_ACCEL_LIMIT_RAD_S2 LADRC_R(1e4)
/* The smallest angle and rate range accepted: a milliradian (per second),
 * the resolution of a good IMU; below, float rounding alone leaves it. */
#define AXIS_RANGE_MIN LADRC_R(1e-3)
/* |b0| for an inertia between 1e-7 and 1000 kg m^2 (a 10 g toy to a 500 kg
 * airframe): outside, the law's division by b0 or the observer's b0 u leaves
 * float for commands a real actuator gives. */
#define AXIS_B0_MIN LADRC_R(1e-3)
#define AXIS_B0_MAX LADRC_R(1e7)
/* The Euler observer (poles at 1 - wo h) closes a stable loop with the law
 * only for wo h below a bound that shrinks as wc h grows: 0.90 at wc h -> 0,
 * 0.63 at 0.2, 0.38 at 0.5, 0.20 at 0.99 (eigenvalues of the sampled loop on
 * its matched model). 0.88 / (1 + 3.6 wc h) stays below it throughout. */
#define AXIS_EULER_WOH_AT_0 LADRC_R(0.88)
#define AXIS_EULER_WOH_SLOPE LADRC_R(3.6)
/* Largest L dt^2 (rad/s^2) a Levant shaper may have on an axis: 1e7 rad/s^4
 * at 1 kHz, ten thousand times the default. */
#define AXIS_LEVANT_CHATTER_MAX_RAD_S2 LADRC_R(10.0)
/* wc dt below 1: the sampled loop (s + wc)^2 on a double integrator held over
 * each step has its poles inside the unit circle (Jury: 4 - 4 wc dt > 0). */
#define AXIS_WC_DT_LIMIT LADRC_R(1.0)

/* Ticks of dt_s in period_s, at least 1 (a period shorter than a tick: every tick). */
static uint16_t ticks_in(ladrc_real_t period_s, ladrc_real_t dt_s)
{
    const ladrc_real_t ticks = period_s / dt_s;
    return (ticks >= LADRC_R(1.0) && ticks < LADRC_R(65535.0)) ? (uint16_t)(ticks + LADRC_R(0.5)) : 1u;
}

void ladrc_axis_config_default(ladrc_axis_config_t *cfg, ladrc_variant_t variant,
                               ladrc_real_t dt_s, ladrc_real_t inertia_kg_m2)
{
    LADRC_ASSERT(cfg != NULL);
    const ladrc_real_t unlimited = (ladrc_real_t)INFINITY;
    cfg->variant = variant;
    cfg->dt_s = dt_s;
    cfg->u_min_Nm = -unlimited;
    cfg->u_max_Nm = unlimited;
    cfg->angle_limit_rad = AXIS_DEFAULT_ANGLE_LIMIT_RAD;
    cfg->rate_limit_rad_s = AXIS_DEFAULT_RATE_LIMIT_RAD_S;
    cfg->applied_limit_Nm = AXIS_DEFAULT_ACCEL_LIMIT_RAD_S2 * inertia_kg_m2;
    cfg->wc_rad_s = AXIS_DEFAULT_WC_RAD_S;
    cfg->wo_rad_s = AXIS_DEFAULT_WO_RAD_S;
    cfg->b0 = LADRC_R(1.0) / inertia_kg_m2;
    cfg->leso_method = LADRC_LESO_ZOH;
    cfg->shaper = LADRC_SHAPER_TD;
    cfg->td_accel_rad_s2 = AXIS_DEFAULT_TD_ACCEL_RAD_S2;
    cfg->td_h0_s = dt_s;
    cfg->levant_method = LADRC_LEVANT_IMPLICIT;
    cfg->levant_lipschitz_rad_s4 = AXIS_DEFAULT_LEVANT_LIPSCHITZ_RAD_S4;
    if (variant == LADRC_VARIANT_LP_MLADRC || variant == LADRC_VARIANT_HP_MLADRC) {
        cfg->shaper = LADRC_SHAPER_LEVANT; /* the modified scheme's shaper */
    }
    cfg->pid_kp = AXIS_DEFAULT_PID_KP;
    cfg->pid_ki = AXIS_DEFAULT_PID_KI;
    cfg->pid_kd = AXIS_DEFAULT_PID_KD;
    cfg->pid_d_filter_tau_s = LADRC_R(0.0);
    cfg->pid_i_limit_Nm = unlimited;
    cfg->lp_lambda0_per_s = AXIS_DEFAULT_LP_LAMBDA0_PER_S;
    cfg->lp_k0_per_s = AXIS_DEFAULT_LP_K0_PER_S;
    cfg->hp_freq_mode = LADRC_HP_FREQ_ONLINE;
    cfg->hp_n_tones = (uint8_t)(AXIS_DEFAULT_HP_N_TONES < LADRC_HP_MAX_TONES ? AXIS_DEFAULT_HP_N_TONES
                                                                            : LADRC_HP_MAX_TONES);
    for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
        cfg->hp_freq_rad_s[k] = (k == 0u) ? AXIS_DEFAULT_HP_FREQ_RAD_S
                                          : AXIS_DEFAULT_HP_FREQ2_RAD_S * (ladrc_real_t)k;
    }
    cfg->hp_freq_min_rad_s = AXIS_DEFAULT_HP_FREQ_MIN_RAD_S;
    cfg->hp_freq_max_rad_s = AXIS_DEFAULT_HP_FREQ_MAX_RAD_S;
    cfg->hp_lambda0_per_s = AXIS_DEFAULT_HP_LAMBDA0_PER_S;
    cfg->hp_freq_lambda0_per_s = AXIS_DEFAULT_HP_FREQ_LAMBDA0_PER_S;
    cfg->hp_freq_filter_rad_s = AXIS_DEFAULT_HP_FREQ_FILTER_RAD_S;
    cfg->hp_fit_decimation = ticks_in(AXIS_DEFAULT_HP_FIT_SAMPLE_S, dt_s);
    cfg->hp_fit_phase = 0u;
    cfg->motor_tau_s = LADRC_R(0.0);
    cfg->delay_ticks = 0u;
    cfg->wrap_angle = 0u;
    cfg->indi_att_kp_per_s = AXIS_DEFAULT_INDI_ATT_KP_PER_S;
    cfg->indi_rate_kp_per_s = AXIS_DEFAULT_INDI_RATE_KP_PER_S;
    cfg->indi_filter_rad_s = AXIS_DEFAULT_INDI_FILTER_RAD_S;
    const ladrc_real_t wr = AXIS_DEFAULT_CAS_RATE_BW_RAD_S;
    cfg->cas_att_kp = AXIS_DEFAULT_CAS_ATT_PER_BW * wr;
    cfg->cas_rate_max_rad_s = AXIS_DEFAULT_CAS_RATE_MAX_RAD_S;
    cfg->cas_rate_kp = inertia_kg_m2 * wr;
    cfg->cas_rate_ki = cfg->cas_rate_kp * wr / AXIS_DEFAULT_CAS_I_CORNER;
    cfg->cas_rate_kd = cfg->cas_rate_kp / (AXIS_DEFAULT_CAS_D_QUADRATURE * wr);
    cfg->cas_d_filter_tau_s = LADRC_R(1.0) / (AXIS_DEFAULT_CAS_D_FILTER * wr);
    cfg->cas_i_limit_Nm = unlimited;
    cfg->cas_rate_filter_tau_s = cfg->cas_d_filter_tau_s;
}

static ladrc_status_t init_shaper(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (cfg->shaper == LADRC_SHAPER_TD) {
        const ladrc_td_config_t td_cfg = {cfg->dt_s, cfg->td_accel_rad_s2, cfg->td_h0_s};
        return ladrc_td_init(&axis->shaping.td, &td_cfg);
    }
    if (cfg->shaper == LADRC_SHAPER_LEVANT) {
        /* Levant's r'' chatters on the scale L h^2: beyond a few rad/s^2 the
         * law would pass that chatter to the actuators as torque noise. */
        if (!(cfg->levant_lipschitz_rad_s4 * cfg->dt_s * cfg->dt_s <= AXIS_LEVANT_CHATTER_MAX_RAD_S2)) {
            return LADRC_ERR_LEVANT_LIPSCHITZ;
        }
        const ladrc_levant_config_t lev_cfg = {cfg->dt_s,
                                               cfg->levant_method,
                                               LADRC_LEVANT_GAINS_LIPSCHITZ,
                                               cfg->levant_lipschitz_rad_s4,
                                               LADRC_R(0.0),
                                               LADRC_R(0.0),
                                               LADRC_R(0.0),
                                               LADRC_R(0.0)};
        return ladrc_levant_init(&axis->shaping.levant, &lev_cfg);
    }
    return (cfg->shaper == LADRC_SHAPER_NONE) ? LADRC_OK : LADRC_ERR_SHAPER;
}

static ladrc_status_t init_estimator(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (cfg->variant == LADRC_VARIANT_LP_MLADRC) {
        const ladrc_lp_config_t lp = {cfg->dt_s, cfg->lp_lambda0_per_s, cfg->lp_k0_per_s,
                                      cfg->motor_tau_s, cfg->delay_ticks};
        return ladrc_lp_init(&axis->part.lp, &lp);
    }
    if (cfg->variant == LADRC_VARIANT_HP_MLADRC) {
        ladrc_hp_config_t hp = {
            .dt_s = cfg->dt_s,
            .freq_mode = cfg->hp_freq_mode,
            .n_tones = cfg->hp_n_tones,
            .freq_min_rad_s = cfg->hp_freq_min_rad_s,
            .freq_max_rad_s = cfg->hp_freq_max_rad_s,
            .lambda0_per_s = cfg->hp_lambda0_per_s,
            .freq_lambda0_per_s = cfg->hp_freq_lambda0_per_s,
            .freq_filter_rad_s = cfg->hp_freq_filter_rad_s,
            .sample_lag_wo_rad_s = cfg->wo_rad_s, /* the sample comes through this axis's LESO */
            .fit_decimation = cfg->hp_fit_decimation,
            .fit_phase = cfg->hp_fit_phase,
            /* the command's tones are advanced over the modelled actuator */
            .act_tau_s = cfg->motor_tau_s,
            .act_delay_ticks = cfg->delay_ticks};
        for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
            hp.freq_rad_s[k] = cfg->hp_freq_rad_s[k];
        }
        /* The shadow runs with the LESO's gains (initialised just before). */
        ladrc_leso_twin_reset(&axis->part.hp.shadow, LADRC_R(0.0));
        return ladrc_hp_init(&axis->part.hp.est, &hp);
    }
    return LADRC_OK;
}

/* Below this h / tau the mean gain g = (x - 1 + exp(-x)) / x, x = h / tau,
 * comes from its series (the direct form cancels: a relative error of
 * 2 eps / x); the series' first omitted term, x^4 / 120, is then below
 * 1e-6 of g = x / 2. */
#define AXIS_MEAN_GAIN_SERIES_MAX LADRC_R(0.1)

/* The actuator model's constants (axis.h), validated; the state starts at rest. */
static ladrc_status_t init_actuator(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_real_t tau = cfg->motor_tau_s;
    if (!(ladrc_is_finite(tau) && tau >= LADRC_R(0.0) && tau <= LADRC_MOTOR_TAU_MAX_S)) {
        return LADRC_ERR_MOTOR_TAU_S;
    }
    if (cfg->delay_ticks > LADRC_MAX_DELAY_TICKS) {
        return LADRC_ERR_DELAY_TICKS;
    }
    ladrc_actuator_t *act = &axis->act;
    act->alpha = LADRC_R(1.0);
    act->mean_gain = LADRC_R(1.0);
    if (tau > LADRC_R(0.0)) {
        const ladrc_real_t x = cfg->dt_s / tau;
        act->alpha = -ladrc_expm1(-x);
        if (x < AXIS_MEAN_GAIN_SERIES_MAX) {
            act->mean_gain = x * (LADRC_R(0.5) - x * (LADRC_R(1.0) / LADRC_R(6.0) -
                                                      x * (LADRC_R(1.0) / LADRC_R(24.0))));
        } else {
            act->mean_gain = LADRC_R(1.0) - act->alpha / x;
        }
    }
    act->delay_ticks = cfg->delay_ticks;
    axis->model = (tau > LADRC_R(0.0) || cfg->delay_ticks > 0u) ? 1u : 0u;
    return LADRC_OK;
}

/* Torque the observer step of this tick takes (axis.h): the model's mean
 * over the step, which also advances the model by the step. */
static ladrc_real_t advance_actuator(ladrc_axis_t *axis)
{
    const ladrc_real_t mean = ladrc_axis_acting_Nm(axis);
    ladrc_actuator_t *act = &axis->act;
    ladrc_real_t v = axis->applied_Nm;
    if (act->delay_ticks != 0u) {
        const uint8_t head = act->head;
        v = act->delayed_Nm[head];
        act->delayed_Nm[head] = axis->applied_Nm;
        act->head = (uint8_t)((head + 1u < act->delay_ticks) ? head + 1u : 0u);
    }
    act->lag_Nm += act->alpha * (v - act->lag_Nm);
    return mean;
}

static ladrc_status_t init_adrc(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (!ladrc_is_positive(cfg->wc_rad_s) || !(cfg->wc_rad_s * cfg->dt_s < AXIS_WC_DT_LIMIT)) {
        return LADRC_ERR_WC_RAD_S;
    }
    if (!(ladrc_fabs(cfg->b0) >= AXIS_B0_MIN && ladrc_fabs(cfg->b0) <= AXIS_B0_MAX)) {
        return LADRC_ERR_B0;
    }
    const ladrc_real_t wch = cfg->wc_rad_s * cfg->dt_s;
    if (cfg->leso_method == LADRC_LESO_EULER && ladrc_is_positive(cfg->wo_rad_s) &&
        !(cfg->wo_rad_s * cfg->dt_s * (LADRC_R(1.0) + AXIS_EULER_WOH_SLOPE * wch) <= AXIS_EULER_WOH_AT_0)) {
        return LADRC_ERR_LESO_EULER_UNSTABLE;
    }
    ladrc_status_t status = init_actuator(axis, cfg);
    if (status != LADRC_OK) {
        return status;
    }
    const ladrc_leso_config_t leso_cfg = {cfg->dt_s, cfg->wo_rad_s, cfg->b0, cfg->leso_method};
    status = ladrc_leso_init(&axis->leso, &leso_cfg);
    if (status == LADRC_OK) {
        status = init_shaper(axis, cfg);
    }
    if (status == LADRC_OK) {
        status = init_estimator(axis, cfg);
    }
    if (status != LADRC_OK) {
        return status;
    }
    axis->shaper = cfg->shaper;
    axis->kp = cfg->wc_rad_s * cfg->wc_rad_s;
    axis->kd = LADRC_R(2.0) * cfg->wc_rad_s;
    axis->b0 = cfg->b0;
    return LADRC_OK;
}

/* The command's bounds: u_min_Nm..u_max_Nm inside +-applied_limit_Nm (the
 * command is applied by default, so it must be a plausible applied torque). */
static ladrc_real_t command_min(const ladrc_axis_config_t *cfg)
{
    return (cfg->u_min_Nm > -cfg->applied_limit_Nm) ? cfg->u_min_Nm : -cfg->applied_limit_Nm;
}

static ladrc_real_t command_max(const ladrc_axis_config_t *cfg)
{
    return (cfg->u_max_Nm < cfg->applied_limit_Nm) ? cfg->u_max_Nm : cfg->applied_limit_Nm;
}

static ladrc_status_t init_pid(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_pid_config_t pid_cfg = {cfg->dt_s,           cfg->pid_kp,
                                        cfg->pid_ki,         cfg->pid_kd,
                                        cfg->pid_d_filter_tau_s, cfg->pid_i_limit_Nm,
                                        command_min(cfg),    command_max(cfg),
                                        cfg->wrap_angle};
    axis->model = 0u; /* no observer to tell (axis.h) */
    return ladrc_pid_init(&axis->part.pid, &pid_cfg);
}

static ladrc_status_t init_indi(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_indi_config_t indi_cfg = {cfg->dt_s, cfg->b0, cfg->indi_att_kp_per_s, cfg->indi_rate_kp_per_s,
                                          cfg->indi_filter_rad_s};
    ladrc_status_t status = ladrc_indi_init(&axis->part.indi, &indi_cfg);
    if (status == LADRC_OK) {
        status = init_actuator(axis, cfg);
    }
    if (status == LADRC_OK) {
        status = init_shaper(axis, cfg);
    }
    if (status == LADRC_OK) {
        axis->shaper = cfg->shaper;
        axis->b0 = cfg->b0;
        axis->kp = LADRC_R(0.0);
        axis->kd = LADRC_R(0.0);
    }
    return status;
}

static ladrc_status_t init_cascaded(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    const ladrc_cascaded_config_t cas_cfg = {cfg->dt_s,
                                             cfg->cas_att_kp,
                                             cfg->cas_rate_max_rad_s,
                                             cfg->cas_rate_kp,
                                             cfg->cas_rate_ki,
                                             cfg->cas_rate_kd,
                                             cfg->cas_d_filter_tau_s,
                                             cfg->cas_rate_filter_tau_s,
                                             cfg->cas_i_limit_Nm,
                                             cfg->rate_limit_rad_s,
                                             command_min(cfg),
                                             command_max(cfg),
                                             cfg->wrap_angle};
    axis->model = 0u; /* no observer to tell (axis.h) */
    ladrc_status_t status = ladrc_cascaded_init(&axis->part.cas, &cas_cfg);
    if (status == LADRC_OK) {
        status = init_shaper(axis, cfg);
    }
    axis->shaper = cfg->shaper;
    return status;
}

ladrc_status_t ladrc_axis_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (axis == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    /* Holding an attitude takes no torque: the bounds must bracket 0. */
    if (!(cfg->u_min_Nm < LADRC_R(0.0) && cfg->u_max_Nm > LADRC_R(0.0))) {
        return LADRC_ERR_U_LIMITS;
    }
    if (!(ladrc_is_finite(cfg->angle_limit_rad) && cfg->angle_limit_rad >= AXIS_RANGE_MIN &&
          ladrc_is_finite(cfg->rate_limit_rad_s) && cfg->rate_limit_rad_s >= AXIS_RANGE_MIN &&
          ladrc_is_positive(cfg->applied_limit_Nm))) {
        return LADRC_ERR_INPUT_LIMITS;
    }
    if (cfg->wrap_angle > 1u) {
        return LADRC_ERR_WRAP_ANGLE;
    }
    ladrc_status_t status;
    switch (cfg->variant) {
    case LADRC_VARIANT_LADRC:
    case LADRC_VARIANT_LP_MLADRC:
    case LADRC_VARIANT_HP_MLADRC:
        status = init_adrc(axis, cfg);
        break;
    case LADRC_VARIANT_PID:
        status = init_pid(axis, cfg);
        break;
    case LADRC_VARIANT_INDI:
        status = init_indi(axis, cfg);
        break;
    case LADRC_VARIANT_CASCADED:
        status = init_cascaded(axis, cfg);
        break;
    default:
        status = LADRC_ERR_VARIANT;
        break;
    }
    if (status != LADRC_OK) {
        return status;
    }
    axis->variant = cfg->variant;
    axis->u_min_Nm = command_min(cfg);
    axis->u_max_Nm = command_max(cfg);
    axis->angle_limit_rad = cfg->angle_limit_rad;
    axis->rate_limit_rad_s = cfg->rate_limit_rad_s;
    axis->applied_limit_Nm = cfg->applied_limit_Nm;
    axis->wrap = cfg->wrap_angle;
    axis->f_rate_rad_s3 = LADRC_R(0.0);
    axis->f_known_rad_s2 = LADRC_R(0.0);
    ladrc_axis_reset(axis, LADRC_R(0.0));
    return LADRC_OK;
}

/* The observer at rest on angle_rad and the estimator from scratch (an ADRC axis). */
static void restart_estimates(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    ladrc_leso_reset(&axis->leso, angle_rad);
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        ladrc_lp_reset(&axis->part.lp);
    } else if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        ladrc_hp_reset(&axis->part.hp.est);
        ladrc_leso_twin_reset(&axis->part.hp.shadow, LADRC_R(0.0));
    }
    axis->d_hat_rad_s2 = LADRC_R(0.0);
}

void ladrc_axis_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    LADRC_ASSERT(axis != NULL);
    const ladrc_real_t angle = ladrc_within(angle_rad, axis->angle_limit_rad) ? angle_rad : LADRC_R(0.0);
    if (axis->variant == LADRC_VARIANT_PID) {
        ladrc_pid_reset(&axis->part.pid, angle);
    } else {
        if (axis->variant == LADRC_VARIANT_INDI) {
            ladrc_indi_reset(&axis->part.indi);
            axis->part.indi.angle_rad = angle;
        } else if (axis->variant == LADRC_VARIANT_CASCADED) {
            ladrc_cascaded_reset(&axis->part.cas, angle);
        } else {
            restart_estimates(axis, angle);
        }
        if (axis->shaper == LADRC_SHAPER_TD) {
            ladrc_td_reset(&axis->shaping.td, angle);
        } else if (axis->shaper == LADRC_SHAPER_LEVANT) {
            ladrc_levant_reset(&axis->shaping.levant, angle);
        }
    }
    axis->ref.r = angle;
    axis->ref.dr = LADRC_R(0.0);
    axis->ref.ddr = LADRC_R(0.0);
    axis->output_Nm = LADRC_R(0.0);
    axis->applied_Nm = LADRC_R(0.0);
    /* At rest: no torque acting, none on its way. */
    for (unsigned k = 0u; k < LADRC_MAX_DELAY_TICKS; ++k) {
        axis->act.delayed_Nm[k] = LADRC_R(0.0);
    }
    axis->act.lag_Nm = LADRC_R(0.0);
    axis->act.head = 0u;
    axis->consecutive_faults = 0u;
    axis->faults = LADRC_FAULT_NONE;
}

/* The estimators' view of this tick; returns the new d_hat. Their own faults
 * (e.g. a missing rate) only hold their estimate, so they are not reported
 * as axis faults beyond LADRC_FAULT_RATE. */
static ladrc_real_t estimate_disturbance(ladrc_axis_t *axis, ladrc_real_t rate_rad_s,
                                         ladrc_real_t acting_Nm)
{
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        /* A tick without a rate (NaN) is a gap: LP holds and restarts its
         * difference. The rate is as old as the angle: the torque that acted
         * over its difference is the observer's. */
        (void)ladrc_lp_step(&axis->part.lp, rate_rad_s, axis->b0 * acting_Nm);
        return ladrc_lp_get_estimate(&axis->part.lp);
    }
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        /* z3 holds f - d_hat seen through the observer's lag, plus what the
         * fed rate h put in; the shadow, a twin of the observer on a still
         * plant told d_hat - f_known and the same h, holds exactly the parts
         * of z3 that d_hat, h and the known f_known put there (the observer
         * is linear), so the difference is the observer's view of the
         * unknown f alone and the fit does not chase its own output. */
        ladrc_leso_twin_t *shadow = &axis->part.hp.shadow;
        (void)ladrc_leso_step_twin(&axis->leso, shadow, LADRC_R(0.0), LADRC_R(0.0),
                                   axis->d_hat_rad_s2 - axis->f_known_rad_s2, axis->f_rate_rad_s3);
        (void)ladrc_hp_step(&axis->part.hp.est, axis->leso.z3 - shadow->z3);
        /* What the weight moved in or out of d_hat leaves or enters z3 at
         * once, in both observers (the sample stays as it was). */
        const ladrc_real_t handover = ladrc_hp_get_handover(&axis->part.hp.est);
        if (handover != LADRC_R(0.0)) { /* only while the weight moves */
            ladrc_leso_hand_over(&axis->leso, handover);
            ladrc_leso_twin_hand_over(shadow, handover);
        }
        return ladrc_hp_get_estimate(&axis->part.hp.est);
    }
    return LADRC_R(0.0);
}

/* With an actuator model: the compensation the command carries, d_hat
 * advanced over the modelled actuator (estimator.h); d_hat stays the
 * observer's known input. */
static ladrc_real_t advanced_compensation(ladrc_axis_t *axis, ladrc_real_t d_hat)
{
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        return ladrc_lp_step_lead(&axis->part.lp);
    }
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        return ladrc_hp_get_command(&axis->part.hp.est);
    }
    return d_hat;
}

/* A wrapped axis: z1 and r both beyond +pi (or -pi) move one turn back,
 * with the shaper's state. Both lie within 4 pi of 0 (pi past the bound at
 * most, plus the |r - z1| < 2 pi the wrapped law allows), so each shift by
 * LADRC_TWO_PI is exact (Sterbenz) and r - z1 keeps every bit: the law sees
 * no change. Without it z1 and r would grow with every turn and lose a bit
 * of resolution at each doubling (a float at 1000 rad resolves 6e-5 rad). */
/* The shaped reference and the shaper's state moved by a turn. */
static void shift_reference(ladrc_axis_t *axis, ladrc_real_t turn)
{
    axis->ref.r += turn;
    if (axis->shaper == LADRC_SHAPER_TD) {
        axis->shaping.td.x1 += turn;
    } else if (axis->shaper == LADRC_SHAPER_LEVANT) {
        axis->shaping.levant.r_last += turn; /* z0 = r_last + w moves with it */
    }
}

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
    shift_reference(axis, turn);
}

/* The shaper's tick on the raw reference: r, r', r'' into axis->ref (the
 * shapers write straight into the axis: no copy on the stack). Inlined into
 * both ticks: the call would cost the LADRC family's hot path. */
#if defined(__GNUC__)
__attribute__((always_inline))
#endif
static inline ladrc_fault_t shape_reference(ladrc_axis_t *axis, ladrc_real_t ref_rad)
{
    ladrc_ref_t *ref = &axis->ref;
    if (axis->shaper == LADRC_SHAPER_TD) {
        return ladrc_td_step(&axis->shaping.td, ref_rad, ref);
    }
    if (axis->shaper == LADRC_SHAPER_LEVANT) {
        return ladrc_levant_step(&axis->shaping.levant, ref_rad, ref);
    }
    ref->r = ref_rad;
    ref->dr = LADRC_R(0.0);
    ref->ddr = LADRC_R(0.0);
    return LADRC_FAULT_NONE;
}

/* ADRC tick on finite ref and angle; returns the state fault, if any. */
static ladrc_fault_t step_adrc(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                               ladrc_real_t rate_rad_s)
{
    const ladrc_leso_t *leso = &axis->leso;
    ladrc_ref_t *ref = &axis->ref;
    if (axis->wrap) {
        /* Whole turns off the measurement and the reference (axis.h). */
        angle_rad = ladrc_unwrap_near(angle_rad, leso->z1);
        ref_rad = ladrc_unwrap_near(ref_rad, ref->r);
    }
    /* The LESO must see what really acted: the acting torque and the estimate. */
    const ladrc_real_t acting_Nm = axis->model ? advance_actuator(axis) : axis->applied_Nm;
    ladrc_fault_t faults = ladrc_leso_step(&axis->leso, angle_rad, acting_Nm,
                                           axis->d_hat_rad_s2, axis->f_rate_rad_s3);
    faults |= shape_reference(axis, ref_rad);
    const ladrc_real_t d_hat = estimate_disturbance(axis, rate_rad_s, acting_Nm);
    ladrc_real_t error_rad = ref->r - leso->z1;
    if (axis->wrap) {
        error_rad = ladrc_wrap_pi(error_rad);
        recentre(axis);
    }
    const ladrc_real_t u0 = axis->kp * error_rad + axis->kd * (ref->dr - leso->z2) + ref->ddr;
    ladrc_real_t u = (u0 - leso->z3 - d_hat) / axis->b0;
    if (axis->model) {
        /* the command carries d_hat advanced over the modelled actuator */
        u = (u0 - leso->z3 - advanced_compensation(axis, d_hat)) / axis->b0;
    }
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

/* INDI tick on finite ref and angle (indi.h); without a rate the command is
 * held and LADRC_FAULT_RATE raised, while the reference, the actuator model
 * and the filters' gap move on with time. Returns the tick's faults. */
static ladrc_fault_t step_indi(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                               ladrc_real_t rate_rad_s, int has_rate)
{
    ladrc_indi_t *indi = &axis->part.indi;
    ladrc_ref_t *ref = &axis->ref;
    if (axis->wrap) {
        ref_rad = ladrc_unwrap_near(ref_rad, ref->r);
    }
    const ladrc_real_t acting_Nm = axis->model ? advance_actuator(axis) : axis->applied_Nm;
    ladrc_fault_t faults = shape_reference(axis, ref_rad);
    if (!ladrc_indi_measure(indi, acting_Nm, rate_rad_s, has_rate)) {
        return (ladrc_fault_t)(faults | LADRC_FAULT_RATE);
    }
    indi->angle_rad = angle_rad;
    ladrc_real_t error_rad = ref->r - angle_rad;
    if (axis->wrap) {
        error_rad = ladrc_wrap_pi(error_rad);
        /* r alone decides: the error is taken modulo 2 pi anyway. */
        if (ref->r > LADRC_PI) {
            shift_reference(axis, -LADRC_TWO_PI);
        } else if (ref->r < -LADRC_PI) {
            shift_reference(axis, LADRC_TWO_PI);
        }
    }
    const ladrc_real_t u = ladrc_indi_command(indi, error_rad, ref->dr, ref->ddr, rate_rad_s);
    if (!ladrc_is_finite(u)) { /* u sums both filters: they are finite when it is */
        /* Held; the filters restart at rest (the next rate seeds again). */
        ladrc_indi_reset(indi);
        indi->angle_rad = angle_rad;
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->output_Nm = ladrc_clamp(u, axis->u_min_Nm, axis->u_max_Nm);
    return faults;
}

/* CASCADED tick on finite ref and angle; returns the state fault, if any.
 * A wrapped axis unwraps the raw reference near r for the shaper, and moves
 * r back by a turn once it lies beyond +-pi (exact: r is within 3 pi, the
 * shift is Sterbenz-exact); the error and the angle difference are wrapped
 * by the cascaded module itself. */
static ladrc_fault_t step_cascaded(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                                   const ladrc_real_t *rate_rad_s)
{
    if (axis->wrap) {
        ref_rad = ladrc_unwrap_near(ref_rad, axis->ref.r);
    }
    ladrc_fault_t faults = shape_reference(axis, ref_rad);
    if (axis->wrap && !ladrc_in_half_turn(axis->ref.r)) {
        shift_reference(axis, (axis->ref.r > LADRC_R(0.0)) ? -LADRC_TWO_PI : LADRC_TWO_PI);
    }
    ladrc_cascaded_t *cas = &axis->part.cas;
    if (ladrc_cascaded_step(cas, &axis->ref, angle_rad, rate_rad_s) != LADRC_FAULT_NONE) {
        /* The command is held; the loops restart from the measurement. */
        ladrc_cascaded_reset(cas, angle_rad);
        return (ladrc_fault_t)(faults | LADRC_FAULT_STATE);
    }
    axis->output_Nm = cas->output_Nm;
    return faults;
}

/* rate_rad_s is read only when has_rate; the rate goes by value so the
 * deepest path (HP) keeps no copy of it on the stack. */
static ladrc_real_t step_axis(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                              ladrc_real_t rate_rad_s, int has_rate)
{
    LADRC_ASSERT(axis != NULL);
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    if (has_rate && !ladrc_within(rate_rad_s, axis->rate_limit_rad_s)) {
        faults |= LADRC_FAULT_RATE;
        has_rate = 0; /* the tick runs without it */
    }
    if (!(ladrc_within(ref_rad, axis->angle_limit_rad) && ladrc_within(angle_rad, axis->angle_limit_rad))) {
        faults |= LADRC_FAULT_INPUT;
    } else if (ladrc_variant_has_observer(axis->variant)) {
        faults |= step_adrc(axis, ref_rad, angle_rad, has_rate ? rate_rad_s : (ladrc_real_t)NAN);
    } else if (axis->variant == LADRC_VARIANT_PID) {
        axis->output_Nm = ladrc_pid_step(&axis->part.pid, ref_rad, angle_rad, has_rate ? &rate_rad_s : NULL);
        faults |= ladrc_pid_get_faults(&axis->part.pid);
        axis->ref.r = ref_rad;
    } else if (axis->variant == LADRC_VARIANT_INDI) {
        faults |= step_indi(axis, ref_rad, angle_rad, rate_rad_s, has_rate);
    } else {
        faults |= step_cascaded(axis, ref_rad, angle_rad, has_rate ? &rate_rad_s : NULL);
    }
    axis->applied_Nm = axis->output_Nm;
    axis->faults = faults;
    if ((faults & (LADRC_FAULT_INPUT | LADRC_FAULT_STATE)) != 0u) {
        axis->consecutive_faults++;
    } else {
        axis->consecutive_faults = 0u;
    }
    return axis->output_Nm;
}

ladrc_real_t ladrc_axis_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad)
{
    return step_axis(axis, ref_rad, angle_rad, LADRC_R(0.0), 0);
}

ladrc_real_t ladrc_axis_step_with_rate(ladrc_axis_t *axis, ladrc_real_t ref_rad,
                                       ladrc_real_t angle_rad, ladrc_real_t rate_rad_s)
{
    return step_axis(axis, ref_rad, angle_rad, rate_rad_s, 1);
}

void ladrc_axis_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm)
{
    LADRC_ASSERT(axis != NULL);
    if (!ladrc_within(torque_Nm, axis->applied_limit_Nm)) {
        axis->faults |= LADRC_FAULT_APPLIED;
        axis->applied_Nm = axis->output_Nm;
        return;
    }
    axis->applied_Nm = torque_Nm;
    if (axis->variant == LADRC_VARIANT_PID) {
        ladrc_pid_set_applied(&axis->part.pid, torque_Nm);
    } else if (axis->variant == LADRC_VARIANT_CASCADED) {
        ladrc_cascaded_set_applied(&axis->part.cas, torque_Nm);
    }
}

void ladrc_axis_set_disturbance_rate(ladrc_axis_t *axis, ladrc_real_t rate_rad_s3)
{
    LADRC_ASSERT(axis != NULL);
    axis->f_rate_rad_s3 = ladrc_is_finite(rate_rad_s3) ? rate_rad_s3 : LADRC_R(0.0);
}

void ladrc_axis_set_known_disturbance(ladrc_axis_t *axis, ladrc_real_t f_known_rad_s2)
{
    LADRC_ASSERT(axis != NULL);
    axis->f_known_rad_s2 = ladrc_is_finite(f_known_rad_s2) ? f_known_rad_s2 : LADRC_R(0.0);
}

ladrc_real_t ladrc_axis_get_accel(const ladrc_axis_t *axis)
{
    if (axis->variant == LADRC_VARIANT_INDI) {
        return axis->b0 * ladrc_axis_acting_Nm(axis) + ladrc_indi_disturbance(&axis->part.indi);
    }
    if (!ladrc_variant_has_observer(axis->variant)) {
        return LADRC_R(0.0);
    }
    return axis->b0 * ladrc_axis_acting_Nm(axis) + axis->leso.z3 + axis->d_hat_rad_s2;
}

ladrc_fault_t ladrc_axis_get_faults(const ladrc_axis_t *axis) { return axis->faults; }

uint32_t ladrc_axis_get_consecutive_faults(const ladrc_axis_t *axis)
{
    return axis->consecutive_faults;
}

void ladrc_axis_get_reference(const ladrc_axis_t *axis, ladrc_ref_t *ref) { *ref = axis->ref; }

void ladrc_axis_get_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad,
                             ladrc_real_t *rate_rad_s, ladrc_real_t *disturbance_rad_s2)
{
    if (axis->variant == LADRC_VARIANT_PID) {
        *angle_rad = axis->part.pid.prev_meas_rad;
        *rate_rad_s = axis->part.pid.d_filtered_rad_s;
        *disturbance_rad_s2 = LADRC_R(0.0);
    } else if (axis->variant == LADRC_VARIANT_INDI) {
        *angle_rad = axis->part.indi.angle_rad;
        *rate_rad_s = axis->part.indi.rate_last_rad_s;
        *disturbance_rad_s2 = ladrc_indi_disturbance(&axis->part.indi);
    } else if (axis->variant == LADRC_VARIANT_CASCADED) {
        *angle_rad = axis->part.cas.prev_angle_rad;
        *rate_rad_s = axis->part.cas.rate_rad_s;
        *disturbance_rad_s2 = LADRC_R(0.0);
    } else {
        *angle_rad = axis->leso.z1;
        *rate_rad_s = axis->leso.z2;
        *disturbance_rad_s2 = axis->leso.z3 + axis->d_hat_rad_s2;
    }
}

const ladrc_hp_estimator_t *ladrc_axis_get_hp(const ladrc_axis_t *axis)
{
    return (axis->variant == LADRC_VARIANT_HP_MLADRC) ? &axis->part.hp.est : NULL;
}

const ladrc_lp_estimator_t *ladrc_axis_get_lp(const ladrc_axis_t *axis)
{
    return (axis->variant == LADRC_VARIANT_LP_MLADRC) ? &axis->part.lp : NULL;
}
