/* SPDX-License-Identifier: BSD-3-Clause */
/* One attitude axis behind one API (see axis.h): the config defaults, the
 * checks every variant shares and the dispatch to the variant files
 * (axis_internal.h); the shaper and the actuator model are below those
 * (axis_shared.c). */
#include "axis_internal.h"
#include "require.h"

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
/* PX4's rate controller: the integrator relaxes to 0 at a rate error of
 * 400 deg/s; the rate feed-forward gains (MC_ROLLRATE_FF, ...) default to 0. */
#define AXIS_DEFAULT_CAS_I_RELAX_RAD_S LADRC_R(6.9813170079773183) /* 400 deg/s */
/* INDI adaptation (off by default; these apply when turned on): a step of
 * 0.005 follows a change over 200 excited ticks (0.2 s at 1 kHz of
 * continuous excitation), slow enough to average the gyro noise that
 * reaches domegadot_f; 50 rad/s^3 of expected jerk is a 0.05 rad/s^2 change
 * of the commanded acceleration per millisecond, above that noise and far
 * below a manoeuvre's; the bounds allow a factor 4 either way. */
#define AXIS_DEFAULT_INDI_ADAPT_MU LADRC_R(0.005)
#define AXIS_DEFAULT_INDI_ADAPT_JERK_MIN_RAD_S3 LADRC_R(50.0)
#define AXIS_DEFAULT_INDI_ADAPT_MIN_RATIO LADRC_R(0.25)
#define AXIS_DEFAULT_INDI_ADAPT_MAX_RATIO LADRC_R(4.0)
/* RATE-ADRC (axis.h): CASCADED's rate crossover and attitude separation,
 * the rate observer's double pole four times above the crossover. */
#define AXIS_DEFAULT_RADRC_RATE_BW_RAD_S AXIS_DEFAULT_CAS_RATE_BW_RAD_S
#define AXIS_DEFAULT_RADRC_WO_PER_BW LADRC_R(4.0)
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
/* The largest angle_limit_rad init takes: a million radians, far beyond any
 * attitude, wrapped or not, and low enough that the reference shapers'
 * states on an angle within it stay far inside the real type (a limit near
 * its maximum let a reset leave them where every later tick overflowed). */
#define AXIS_ANGLE_LIMIT_MAX_RAD LADRC_R(1e6)
/* Ticks of dt_s in period_s, at least 1 (a period shorter than a tick: every tick). */
static uint16_t ticks_in(ladrc_real_t period_s, ladrc_real_t dt_s)
{
    const ladrc_real_t ticks = period_s / dt_s;
    if (ticks >= LADRC_R(1.0) && ticks < LADRC_R(65535.0)) {
        return (uint16_t)(ticks + LADRC_R(0.5));
    }
    return 1u;
}

void ladrc_axis_config_default(ladrc_axis_config_t *cfg, ladrc_variant_t variant, ladrc_real_t dt_s,
                               ladrc_real_t inertia_kg_m2)
{
    LADRC_REQUIRE_VOID(cfg != NULL);
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
    cfg->hp_n_tones =
        (uint8_t)(AXIS_DEFAULT_HP_N_TONES < LADRC_HP_MAX_TONES ? AXIS_DEFAULT_HP_N_TONES : LADRC_HP_MAX_TONES);
    for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
        cfg->hp_freq_rad_s[k] = (k == 0u) ? AXIS_DEFAULT_HP_FREQ_RAD_S : AXIS_DEFAULT_HP_FREQ2_RAD_S * (ladrc_real_t)k;
    }
    cfg->hp_freq_min_rad_s = AXIS_DEFAULT_HP_FREQ_MIN_RAD_S;
    cfg->hp_freq_max_rad_s = AXIS_DEFAULT_HP_FREQ_MAX_RAD_S;
    cfg->hp_lambda0_per_s = AXIS_DEFAULT_HP_LAMBDA0_PER_S;
    cfg->hp_freq_lambda0_per_s = AXIS_DEFAULT_HP_FREQ_LAMBDA0_PER_S;
    cfg->hp_freq_filter_rad_s = AXIS_DEFAULT_HP_FREQ_FILTER_RAD_S;
    cfg->hp_fit_decimation = ticks_in(AXIS_DEFAULT_HP_FIT_SAMPLE_S, dt_s);
    cfg->hp_sample = LADRC_HP_SAMPLE_OBSERVER;
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
    cfg->cas_i_relax_rad_s = AXIS_DEFAULT_CAS_I_RELAX_RAD_S;
    cfg->cas_rate_ff = LADRC_R(0.0);
    cfg->cas_setpoint_ff = 1u; /* the axis is unknown here: ladrc_attitude_config_default sets roll and pitch */
    cfg->indi_adapt = 0u;
    cfg->indi_adapt_mu = AXIS_DEFAULT_INDI_ADAPT_MU;
    cfg->indi_adapt_jerk_min_rad_s3 = AXIS_DEFAULT_INDI_ADAPT_JERK_MIN_RAD_S3;
    cfg->indi_adapt_min_ratio = AXIS_DEFAULT_INDI_ADAPT_MIN_RATIO;
    cfg->indi_adapt_max_ratio = AXIS_DEFAULT_INDI_ADAPT_MAX_RATIO;
    const ladrc_real_t wr_adrc = AXIS_DEFAULT_RADRC_RATE_BW_RAD_S;
    cfg->radrc_kp_per_s = wr_adrc;
    cfg->radrc_att_kp_per_s = AXIS_DEFAULT_CAS_ATT_PER_BW * wr_adrc;
    cfg->radrc_rate_max_rad_s = AXIS_DEFAULT_CAS_RATE_MAX_RAD_S;
    cfg->radrc_acro = 0u;
    if (variant == LADRC_VARIANT_RATE_ADRC) {
        cfg->wo_rad_s = AXIS_DEFAULT_RADRC_WO_PER_BW * wr_adrc; /* its rate observer */
    }
}

/* 1 for each variant built (LADRC_VARIANTS, axis.h). */
static const uint8_t variant_built[LADRC_VARIANT_COUNT] = {
    [LADRC_VARIANT_LADRC] = LADRC_WITH_LADRC,         [LADRC_VARIANT_LP_MLADRC] = LADRC_WITH_LP_MLADRC,
    [LADRC_VARIANT_HP_MLADRC] = LADRC_WITH_HP_MLADRC, [LADRC_VARIANT_PID] = LADRC_WITH_PID,
    [LADRC_VARIANT_CASCADED] = LADRC_WITH_CASCADED,   [LADRC_VARIANT_INDI] = LADRC_WITH_INDI,
    [LADRC_VARIANT_RATE_ADRC] = LADRC_WITH_RATE_ADRC};

/* The dispatch to the variant files (axis_internal.h): one switch per
 * operation, a case per variant built, for an axis whose variant init
 * accepted (a variant left out never gets that far). */
#if LADRC_WITH_ADRC_FAMILY
#define CASE_ADRC(call)                                                                                                \
    case LADRC_VARIANT_LADRC:                                                                                          \
    case LADRC_VARIANT_LP_MLADRC:                                                                                      \
    case LADRC_VARIANT_HP_MLADRC:                                                                                      \
        call;                                                                                                          \
        break;
#else
#define CASE_ADRC(call)
#endif
#if LADRC_WITH_PID
#define CASE_PID(call)                                                                                                 \
    case LADRC_VARIANT_PID:                                                                                            \
        call;                                                                                                          \
        break;
#else
#define CASE_PID(call)
#endif
#if LADRC_WITH_CASCADED
#define CASE_CASCADED(call)                                                                                            \
    case LADRC_VARIANT_CASCADED:                                                                                       \
        call;                                                                                                          \
        break;
#else
#define CASE_CASCADED(call)
#endif
#if LADRC_WITH_INDI
#define CASE_INDI(call)                                                                                                \
    case LADRC_VARIANT_INDI:                                                                                           \
        call;                                                                                                          \
        break;
#else
#define CASE_INDI(call)
#endif
#if LADRC_WITH_RATE_ADRC
#define CASE_RATE_ADRC(call)                                                                                           \
    case LADRC_VARIANT_RATE_ADRC:                                                                                      \
        call;                                                                                                          \
        break;
#else
#define CASE_RATE_ADRC(call)
#endif

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
    if (!(cfg->angle_limit_rad >= AXIS_RANGE_MIN && cfg->angle_limit_rad <= AXIS_ANGLE_LIMIT_MAX_RAD &&
          ladrc_is_finite(cfg->rate_limit_rad_s) && cfg->rate_limit_rad_s >= AXIS_RANGE_MIN &&
          ladrc_is_positive(cfg->applied_limit_Nm))) {
        return LADRC_ERR_INPUT_LIMITS;
    }
    if (cfg->wrap_angle > 1u) {
        return LADRC_ERR_WRAP_ANGLE;
    }
    if ((unsigned)cfg->variant >= (unsigned)LADRC_VARIANT_COUNT) {
        return LADRC_ERR_VARIANT;
    }
    if (!variant_built[cfg->variant]) {
        return LADRC_ERR_VARIANT_NOT_BUILT;
    }
    ladrc_status_t status = LADRC_ERR_VARIANT;
    switch (cfg->variant) {
        CASE_ADRC(status = axis_adrc_init(axis, cfg))
        CASE_PID(status = axis_pid_init(axis, cfg))
        CASE_CASCADED(status = axis_cascaded_init(axis, cfg))
        CASE_INDI(status = axis_indi_init(axis, cfg))
        CASE_RATE_ADRC(status = axis_rate_adrc_init(axis, cfg))
    default:
        break;
    }
    if (status != LADRC_OK) {
        return status;
    }
    axis->variant = cfg->variant;
    axis->u_min_Nm = axis_command_min(cfg);
    axis->u_max_Nm = axis_command_max(cfg);
    axis->angle_limit_rad = cfg->angle_limit_rad;
    axis->rate_limit_rad_s = cfg->rate_limit_rad_s;
    axis->applied_limit_Nm = cfg->applied_limit_Nm;
    axis->wrap = cfg->wrap_angle;
    axis->f_rate_rad_s3 = LADRC_R(0.0);
    axis->f_known_rad_s2 = LADRC_R(0.0);
    axis->landed = 0u;
    axis->gain_scale = LADRC_R(1.0);
    axis->adjusted = 0u;
    axis->restart = 0u;
    axis->engage_Nm = LADRC_R(0.0);
    ladrc_axis_reset(axis, LADRC_R(0.0));
    return LADRC_OK;
}

void ladrc_axis_reset(ladrc_axis_t *axis, ladrc_real_t angle_rad)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    const ladrc_real_t angle = ladrc_within(angle_rad, axis->angle_limit_rad) ? angle_rad : LADRC_R(0.0);
    switch (axis->variant) {
        CASE_ADRC(axis_adrc_reset(axis, angle))
        CASE_PID(axis_pid_reset(axis, angle))
        CASE_CASCADED(axis_cascaded_reset(axis, angle))
        CASE_INDI(axis_indi_reset(axis, angle))
        CASE_RATE_ADRC(axis_rate_adrc_reset(axis, angle))
    default:
        break;
    }
    axis->ref.r = angle;
    axis->ref.dr = LADRC_R(0.0);
    axis->ref.ddr = LADRC_R(0.0);
    axis->output_Nm = LADRC_R(0.0);
    axis->applied_Nm = LADRC_R(0.0);
    axis->command_Nm = LADRC_R(0.0);
    /* At rest: no torque acting, none on its way. */
    axis_delay_fill(&axis->act, LADRC_R(0.0));
    axis->act.lag_Nm = LADRC_R(0.0);
    axis->consecutive_faults = 0u;
    axis->faults = LADRC_FAULT_NONE;
}

/* The tick's end for an axis landed or gain-scaled (its adjusted flag),
 * off the common path: the command for the plant's gain, within the bounds
 * (what acts is kept in b0's units), and the torque taken as acting, 0 on
 * the ground. Returns the command. */
LADRC_NOINLINE static ladrc_real_t adjusted_command(ladrc_axis_t *axis)
{
    ladrc_real_t command_Nm = axis->output_Nm;
    if (axis->gain_scale != LADRC_R(1.0)) {
        const ladrc_real_t scaled_Nm = axis->output_Nm / axis->gain_scale;
        command_Nm = ladrc_clamp(scaled_Nm, axis->u_min_Nm, axis->u_max_Nm);
        if (command_Nm != scaled_Nm) {
            axis->output_Nm = command_Nm * axis->gain_scale; /* bounded: what acts */
        }
    }
    axis->command_Nm = command_Nm;
    axis->applied_Nm = axis->landed ? LADRC_R(0.0) : axis->output_Nm; /* landed: the ground takes it */
    return command_Nm;
}

/* The applied torque of an adjusted axis in b0's units: the command itself
 * as it was, not a rounded product (the integrators' saturation test is
 * exact, pid.h); the torque taken as acting, 0 on the ground. */
static ladrc_real_t adjusted_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm)
{
    const ladrc_real_t acted_Nm = (torque_Nm == axis->command_Nm) ? axis->output_Nm : torque_Nm * axis->gain_scale;
    axis->applied_Nm = axis->landed ? LADRC_R(0.0) : acted_Nm;
    return acted_Nm;
}

/* Whether the tick's end takes the adjusted path. */
static void update_adjusted(ladrc_axis_t *axis)
{
    axis->adjusted = (axis->landed || axis->gain_scale != LADRC_R(1.0)) ? 1u : 0u;
}

void axis_request_restart(ladrc_axis_t *axis, int engage, ladrc_real_t torque_Nm)
{
    axis->restart = engage ? 2u : 1u;
    axis->engage_Nm = torque_Nm;
}

void axis_restart_now(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s)
{
    if (!axis->restart || !ladrc_within(angle_rad, axis->angle_limit_rad)) {
        return; /* none asked, or it waits for a good measurement */
    }
    if (axis->restart == 2u) {
        ladrc_axis_engage(axis, ref_rad, angle_rad, rate_rad_s, axis->engage_Nm);
    } else {
        ladrc_axis_reset(axis, angle_rad);
    }
    axis->restart = 0u;
}

/* rate_rad_s is read only when has_rate; the rate goes by value so the
 * deepest path (HP) keeps no copy of it on the stack. */
static ladrc_real_t step_axis(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, ladrc_real_t rate_rad_s,
                              int has_rate)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    if (has_rate && !ladrc_within(rate_rad_s, axis->rate_limit_rad_s)) {
        faults |= LADRC_FAULT_RATE;
        has_rate = 0; /* the tick runs without it */
    }
    if (!(ladrc_within(ref_rad, axis->angle_limit_rad) && ladrc_within(angle_rad, axis->angle_limit_rad))) {
        faults |= LADRC_FAULT_INPUT;
    } else {
        switch (axis->variant) {
            CASE_ADRC(faults |= axis_adrc_step(axis, ref_rad, angle_rad, rate_rad_s, has_rate))
            CASE_PID(faults |= axis_pid_step(axis, ref_rad, angle_rad, rate_rad_s, has_rate))
            CASE_CASCADED(faults |= axis_cascaded_step(axis, ref_rad, angle_rad, rate_rad_s, has_rate))
            CASE_INDI(faults |= axis_indi_step(axis, ref_rad, angle_rad, rate_rad_s, has_rate))
            CASE_RATE_ADRC(faults |= axis_rate_adrc_step(axis, ref_rad, angle_rad, rate_rad_s, has_rate))
        default:
            break;
        }
    }
    ladrc_real_t command_Nm = axis->output_Nm;
    axis->applied_Nm = axis->output_Nm;
    if (axis->adjusted) {
        command_Nm = adjusted_command(axis);
    }
    axis->faults = faults;
    if ((faults & (LADRC_FAULT_INPUT | LADRC_FAULT_STATE)) != 0u) {
        axis->consecutive_faults++;
    } else {
        axis->consecutive_faults = 0u;
    }
    return command_Nm;
}

ladrc_fault_t ladrc_axis_step(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad,
                              const ladrc_real_t *rate_rad_s, ladrc_real_t *torque_Nm)
{
    LADRC_REQUIRE(axis != NULL && torque_Nm != NULL, LADRC_FAULT_STATE);
    const int has_rate = (rate_rad_s != NULL);
    *torque_Nm = step_axis(axis, ref_rad, angle_rad, has_rate ? *rate_rad_s : LADRC_R(0.0), has_rate);
    return axis->faults;
}

void ladrc_axis_set_applied(ladrc_axis_t *axis, ladrc_real_t torque_Nm)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    if (!ladrc_within(torque_Nm, axis->applied_limit_Nm)) {
        axis->faults |= LADRC_FAULT_APPLIED;
        axis->applied_Nm = axis->output_Nm;
        return;
    }
    ladrc_real_t acted_Nm = torque_Nm;
    axis->applied_Nm = torque_Nm;
    if (axis->adjusted) {
        acted_Nm = adjusted_applied(axis, torque_Nm);
    }
    (void)acted_Nm; /* read by PID and CASCADED, which a build may leave out */
    switch (axis->variant) {
        CASE_PID(axis_pid_set_applied(axis, acted_Nm))
        CASE_CASCADED(axis_cascaded_set_applied(axis, acted_Nm))
    default:
        break; /* the others read applied_Nm */
    }
}

void ladrc_axis_set_landed(ladrc_axis_t *axis, uint8_t landed)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    axis->landed = (landed != 0u) ? 1u : 0u;
    update_adjusted(axis);
    if (axis->landed) {
        axis->applied_Nm = LADRC_R(0.0);
    }
    switch (axis->variant) {
        CASE_PID(ladrc_pid_set_landed(&axis->part.pid, axis->landed))
        CASE_CASCADED(axis_cascaded_set_landed(axis, axis->landed))
    default:
        break; /* the others read applied_Nm */
    }
}

void ladrc_axis_set_gain_scale(ladrc_axis_t *axis, ladrc_real_t scale)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    if (ladrc_is_finite(scale) && scale >= LADRC_GAIN_SCALE_MIN && scale <= LADRC_GAIN_SCALE_MAX) {
        axis->gain_scale = scale;
        update_adjusted(axis);
    }
}

void ladrc_axis_engage(ladrc_axis_t *axis, ladrc_real_t ref_rad, ladrc_real_t angle_rad, const ladrc_real_t *rate_rad_s,
                       ladrc_real_t torque_Nm)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    ladrc_axis_reset(axis, angle_rad);
    const ladrc_real_t angle = axis->ref.r; /* the angle reset took */
    if (ladrc_within(ref_rad, axis->angle_limit_rad) && axis->variant != LADRC_VARIANT_PID) {
        /* the shaper at rest on the reference (a wrapped one within a turn of the angle) */
        const ladrc_real_t r = axis->wrap ? ladrc_unwrap_near(ref_rad, angle) : ref_rad;
        axis_shaper_reset(axis, r);
        axis->ref.r = r;
    }
    const int has_rate = rate_rad_s != NULL && ladrc_within(*rate_rad_s, axis->rate_limit_rad_s);
    const ladrc_real_t rate = has_rate ? *rate_rad_s : LADRC_R(0.0);
    const ladrc_real_t u = ladrc_within(torque_Nm, axis->applied_limit_Nm)
                               ? ladrc_clamp(torque_Nm, axis->u_min_Nm, axis->u_max_Nm) * axis->gain_scale
                               : LADRC_R(0.0); /* in b0's units */
    /* the torque has been acting, and is on its way */
    axis_delay_fill(&axis->act, u);
    axis->act.lag_Nm = u;
    axis->output_Nm = u;
    axis->applied_Nm = axis->landed ? LADRC_R(0.0) : u;
    axis->command_Nm = u / axis->gain_scale;
    (void)angle; /* not every build has the variants that read them */
    (void)has_rate;
    switch (axis->variant) {
        CASE_ADRC(axis_adrc_engage(axis, rate, u))
        CASE_PID(ladrc_pid_engage(&axis->part.pid, angle, rate, u))
        CASE_CASCADED(ladrc_cascaded_engage(&axis->part.cas, angle, rate, u))
        CASE_INDI(ladrc_indi_engage(&axis->part.indi, angle, has_rate ? &rate : NULL, u))
        CASE_RATE_ADRC(axis_rate_adrc_engage(axis, rate, u))
    default:
        break;
    }
}

void ladrc_axis_set_disturbance_rate(ladrc_axis_t *axis, ladrc_real_t rate_rad_s3)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    axis_put_disturbance_rate(axis, rate_rad_s3);
}

void ladrc_axis_set_known_disturbance(ladrc_axis_t *axis, ladrc_real_t f_known_rad_s2)
{
    LADRC_REQUIRE_VOID(axis != NULL);
    axis_put_known_disturbance(axis, f_known_rad_s2);
}

ladrc_real_t ladrc_axis_get_accel(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, LADRC_R(0.0));
    ladrc_real_t accel = LADRC_R(0.0); /* PID, CASCADED: no model */
    switch (axis->variant) {
        CASE_ADRC(accel = axis_adrc_accel(axis))
        CASE_INDI(accel = axis_indi_accel(axis))
        CASE_RATE_ADRC(accel = axis_rate_adrc_accel(axis))
    default:
        break;
    }
    return accel;
}

ladrc_real_t ladrc_axis_get_effectiveness(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, LADRC_R(0.0));
    ladrc_real_t g = LADRC_R(0.0); /* PID, CASCADED: no model */
    switch (axis->variant) {
        CASE_ADRC(g = axis->b0)
        CASE_INDI(g = axis_indi_effectiveness(axis))
        CASE_RATE_ADRC(g = axis->b0)
    default:
        break;
    }
    return g;
}

ladrc_real_t ladrc_axis_get_acting_Nm(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, LADRC_R(0.0));
    return axis_acting_Nm(axis);
}

ladrc_fault_t ladrc_axis_get_faults(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, LADRC_FAULT_STATE);
    return axis->faults;
}

uint32_t ladrc_axis_get_consecutive_faults(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, 0u);
    return axis->consecutive_faults;
}

void ladrc_axis_get_reference(const ladrc_axis_t *axis, ladrc_ref_t *ref)
{
    LADRC_REQUIRE_VOID(axis != NULL && ref != NULL);
    *ref = axis->ref;
}

void ladrc_axis_get_estimate(const ladrc_axis_t *axis, ladrc_real_t *angle_rad, ladrc_real_t *rate_rad_s,
                             ladrc_real_t *disturbance_rad_s2)
{
    LADRC_REQUIRE_VOID(axis != NULL && angle_rad != NULL && rate_rad_s != NULL && disturbance_rad_s2 != NULL);
    switch (axis->variant) {
        CASE_ADRC(axis_adrc_estimate(axis, angle_rad, rate_rad_s, disturbance_rad_s2))
        CASE_PID(axis_pid_estimate(axis, angle_rad, rate_rad_s, disturbance_rad_s2))
        CASE_CASCADED(axis_cascaded_estimate(axis, angle_rad, rate_rad_s, disturbance_rad_s2))
        CASE_INDI(axis_indi_estimate(axis, angle_rad, rate_rad_s, disturbance_rad_s2))
        CASE_RATE_ADRC(axis_rate_adrc_estimate(axis, angle_rad, rate_rad_s, disturbance_rad_s2))
    default:
        break;
    }
}

const ladrc_hp_estimator_t *ladrc_axis_get_hp(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, NULL);
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC) {
        return &axis->part.hp.est;
    }
#endif
    (void)axis;
    return NULL;
}

const ladrc_lp_estimator_t *ladrc_axis_get_lp(const ladrc_axis_t *axis)
{
    LADRC_REQUIRE(axis != NULL, NULL);
#if LADRC_WITH_LP_MLADRC
    if (axis->variant == LADRC_VARIANT_LP_MLADRC) {
        return &axis->part.lp;
    }
#endif
#if LADRC_WITH_HP_MLADRC
    if (axis->variant == LADRC_VARIANT_HP_MLADRC && axis->part.hp.gyro) {
        return &axis->part.hp.source.lp;
    }
#endif
    (void)axis;
    return NULL;
}
