/* SPDX-License-Identifier: BSD-3-Clause */
/* Library configurations of a scenario (see setup.h). */
#include "setup.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "ladrc/axis.h"

static ladrc_variant_t variant_of(sim_controller_id_t id)
{
    switch (id) {
    case SIM_CTRL_HP_MLADRC:
        return LADRC_VARIANT_HP_MLADRC;
    case SIM_CTRL_LP_MLADRC:
        return LADRC_VARIANT_LP_MLADRC;
    case SIM_CTRL_LADRC:
        return LADRC_VARIANT_LADRC;
    case SIM_CTRL_CASCADED:
        return LADRC_VARIANT_CASCADED;
    case SIM_CTRL_INDI:
        return LADRC_VARIANT_INDI;
    case SIM_CTRL_RATE_ADRC:
        return LADRC_VARIANT_RATE_ADRC;
    default:
        return LADRC_VARIANT_PID;
    }
}

/* The scenario's overrides on top of the library defaults, for one axis. */
static void apply_overrides(ladrc_axis_config_t *a, const sim_overrides_t *o)
{
    if (!isnan(o->wc_rad_s))
        a->wc_rad_s = (ladrc_real_t)o->wc_rad_s;
    if (!isnan(o->wo_rad_s))
        a->wo_rad_s = (ladrc_real_t)o->wo_rad_s;
    if (o->leso_method >= 0)
        a->leso_method = (ladrc_leso_method_t)o->leso_method;
    if (o->hp_freq_mode >= 0)
        a->hp_freq_mode = (ladrc_hp_freq_mode_t)o->hp_freq_mode;
    if (o->hp_sample >= 0)
        a->hp_sample = (ladrc_hp_sample_t)o->hp_sample;
    if (!isnan(o->hp_freq_rad_s))
        a->hp_freq_rad_s[0] = (ladrc_real_t)o->hp_freq_rad_s;
#if LADRC_HP_MAX_TONES > 1
    if (!isnan(o->hp_freq2_rad_s))
        a->hp_freq_rad_s[1] = (ladrc_real_t)o->hp_freq2_rad_s;
#endif
    if (!isnan(o->hp_freq_min_rad_s))
        a->hp_freq_min_rad_s = (ladrc_real_t)o->hp_freq_min_rad_s;
    if (!isnan(o->hp_freq_max_rad_s))
        a->hp_freq_max_rad_s = (ladrc_real_t)o->hp_freq_max_rad_s;
    /* Known frequencies: as many tones as frequencies given, unless said. */
    if (a->hp_freq_mode == LADRC_HP_FREQ_KNOWN)
        a->hp_n_tones = isnan(o->hp_freq2_rad_s) ? 1u : 2u;
    if (o->hp_tones > 0)
        a->hp_n_tones = (uint8_t)o->hp_tones;
    if (!isnan(o->levant_lipschitz_rad_s4))
        a->levant_lipschitz_rad_s4 = (ladrc_real_t)o->levant_lipschitz_rad_s4;
    if (!isnan(o->td_accel_rad_s2))
        a->td_accel_rad_s2 = (ladrc_real_t)o->td_accel_rad_s2;
    if (!isnan(o->pid_kp))
        a->pid_kp = (ladrc_real_t)o->pid_kp;
    if (!isnan(o->pid_ki))
        a->pid_ki = (ladrc_real_t)o->pid_ki;
    if (!isnan(o->pid_kd))
        a->pid_kd = (ladrc_real_t)o->pid_kd;
    if (!isnan(o->indi_att_kp_per_s))
        a->indi_att_kp_per_s = (ladrc_real_t)o->indi_att_kp_per_s;
    if (!isnan(o->indi_rate_kp_per_s))
        a->indi_rate_kp_per_s = (ladrc_real_t)o->indi_rate_kp_per_s;
    if (!isnan(o->indi_filter_rad_s))
        a->indi_filter_rad_s = (ladrc_real_t)o->indi_filter_rad_s;
    if (!isnan(o->radrc_kp_per_s))
        a->radrc_kp_per_s = (ladrc_real_t)o->radrc_kp_per_s;
    if (!isnan(o->radrc_att_kp_per_s))
        a->radrc_att_kp_per_s = (ladrc_real_t)o->radrc_att_kp_per_s;
    if (!isnan(o->radrc_rate_max_deg_s))
        a->radrc_rate_max_rad_s = (ladrc_real_t)(o->radrc_rate_max_deg_s * (3.14159265358979323846 / 180.0));
    if (!isnan(o->cas_att_kp))
        a->cas_att_kp = (ladrc_real_t)o->cas_att_kp;
    if (!isnan(o->cas_rate_max_deg_s))
        a->cas_rate_max_rad_s = (ladrc_real_t)(o->cas_rate_max_deg_s * (3.14159265358979323846 / 180.0));
    if (!isnan(o->cas_rate_kp))
        a->cas_rate_kp = (ladrc_real_t)o->cas_rate_kp;
    if (!isnan(o->cas_rate_ki))
        a->cas_rate_ki = (ladrc_real_t)o->cas_rate_ki;
    if (!isnan(o->cas_rate_kd))
        a->cas_rate_kd = (ladrc_real_t)o->cas_rate_kd;
    if (!isnan(o->cas_d_filter_tau_s))
        a->cas_d_filter_tau_s = (ladrc_real_t)o->cas_d_filter_tau_s;
    if (!isnan(o->cas_i_limit_Nm))
        a->cas_i_limit_Nm = (ladrc_real_t)o->cas_i_limit_Nm;
    if (o->cas_setpoint_ff >= 0)
        a->cas_setpoint_ff = (uint8_t)o->cas_setpoint_ff;
    if (!isnan(o->cas_rate_ff))
        a->cas_rate_ff = (ladrc_real_t)o->cas_rate_ff;
    if (!isnan(o->cas_i_relax_deg_s))
        a->cas_i_relax_rad_s = (ladrc_real_t)(o->cas_i_relax_deg_s * (3.14159265358979323846 / 180.0));
    if (o->indi_adapt >= 0)
        a->indi_adapt = (uint8_t)o->indi_adapt;
    if (!isnan(o->indi_adapt_mu))
        a->indi_adapt_mu = (ladrc_real_t)o->indi_adapt_mu;
    if (!isnan(o->model_motor_tau_s))
        a->motor_tau_s = (ladrc_real_t)o->model_motor_tau_s;
    if (o->model_delay_ticks >= 0)
        a->delay_ticks = (uint16_t)o->model_delay_ticks;
}

#define GAIN(field, text, units)                                                                                       \
    {                                                                                                                  \
        .key = #field, .label = (text), .unit = (units), .offset = offsetof(ladrc_axis_config_t, field)                \
    }
static const sim_gain_field_t LADRC_GAINS[] = {GAIN(wc_rad_s, "wc", "rad/s"), GAIN(wo_rad_s, "wo", "rad/s")};
static const sim_gain_field_t PID_GAINS[] = {GAIN(pid_kp, "kp", ""), GAIN(pid_ki, "ki", ""), GAIN(pid_kd, "kd", ""),
                                             GAIN(pid_d_filter_tau_s, "d_filter", "s")};
static const sim_gain_field_t CASCADED_GAINS[] = {GAIN(cas_att_kp, "att_kp", "1/s"),
                                                  GAIN(cas_rate_kp, "rate kp", ""),
                                                  GAIN(cas_rate_ki, "ki", ""),
                                                  GAIN(cas_rate_kd, "kd", ""),
                                                  GAIN(cas_d_filter_tau_s, "d_filter", "s"),
                                                  GAIN(cas_rate_filter_tau_s, "rate_filter", "s")};
static const sim_gain_field_t INDI_GAINS[] = {GAIN(indi_att_kp_per_s, "k_att", "1/s"),
                                              GAIN(indi_rate_kp_per_s, "k_rate", "1/s"),
                                              GAIN(indi_filter_rad_s, "w_f", "rad/s")};
static const sim_gain_field_t RATE_ADRC_GAINS[] = {GAIN(radrc_att_kp_per_s, "k_att", "1/s"),
                                                   GAIN(radrc_kp_per_s, "k_w", "1/s"), GAIN(wo_rad_s, "wo", "rad/s")};
#undef GAIN
#define N_OF(a) ((int)(sizeof(a) / sizeof((a)[0])))

const sim_gain_field_t *sim_setup_gain_fields(ladrc_variant_t v, int *n)
{
    switch (v) {
    case LADRC_VARIANT_PID:
        *n = N_OF(PID_GAINS);
        return PID_GAINS;
    case LADRC_VARIANT_CASCADED:
        *n = N_OF(CASCADED_GAINS);
        return CASCADED_GAINS;
    case LADRC_VARIANT_INDI:
        *n = N_OF(INDI_GAINS);
        return INDI_GAINS;
    case LADRC_VARIANT_RATE_ADRC:
        *n = N_OF(RATE_ADRC_GAINS);
        return RATE_ADRC_GAINS;
    default:
        *n = N_OF(LADRC_GAINS);
        return LADRC_GAINS;
    }
}

static ladrc_real_t *gain_at(ladrc_axis_config_t *a, const sim_gain_field_t *f)
{
    return (ladrc_real_t *)(void *)((char *)a + f->offset);
}

double sim_setup_gain(const ladrc_axis_config_t *a, const sim_gain_field_t *f)
{
    return (double)*(const ladrc_real_t *)(const void *)((const char *)a + f->offset);
}

void sim_setup_tuned_gains(const sim_tuning_t *t, int axis, ladrc_axis_config_t *a)
{
    int n;
    const sim_gain_field_t *f = sim_setup_gain_fields(a->variant, &n);
    for (int k = 0; k < n; ++k) {
        *gain_at(a, &f[k]) = (ladrc_real_t)sim_setup_gain(&t->gains[axis], &f[k]);
    }
}

int sim_setup_format_gains(const ladrc_axis_config_t *a, char *buf, size_t size)
{
    int n, used = 0;
    const sim_gain_field_t *f = sim_setup_gain_fields(a->variant, &n);
    if (size > 0)
        buf[0] = '\0';
    for (int k = 0; k < n; ++k) {
        const size_t at = (size_t)used < size ? (size_t)used : size;
        const int w = snprintf(buf + at, size - at, "%s%s %.5g%s%s", k ? " " : "", f[k].label, sim_setup_gain(a, &f[k]),
                               f[k].unit[0] ? " " : "", f[k].unit);
        if (w < 0)
            return w;
        used += w;
    }
    return used;
}

int sim_setup_piloted(const sim_scenario_t *sc, sim_controller_id_t id)
{
    return id == SIM_CTRL_RATE_ADRC && sc->overrides[id].radrc_pilot == 1;
}

int sim_setup_wraps_yaw(const sim_scenario_t *sc, sim_controller_id_t id)
{
    return sc->overrides[id].wrap_yaw != 0;
}

void sim_setup_library_defaults(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg)
{
    ladrc_real_t inertia[3];
    for (int i = 0; i < 3; ++i) {
        inertia[i] = (ladrc_real_t)(sc->inertia_kg_m2[i] * sc->inertia_scale[i]);
    }
    ladrc_attitude_config_default(cfg, variant_of(id), (ladrc_real_t)sc->control_dt_s, inertia,
                                  (ladrc_real_t)(sc->rot_drag_Nm_s * sc->rot_drag_scale));
}

void sim_setup_attitude(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_config_t *cfg)
{
    sim_setup_library_defaults(sc, id, cfg);
    const sim_overrides_t *o = &sc->overrides[id];
    for (int i = 0; i < 3; ++i) {
        /* The controllers model the airframe they fly, as they are given its
         * inertia: its motors' lag and its sensors' delay (0 and 0: none,
         * and the library's arithmetic is the unmodelled one bit for bit). */
        cfg->axis[i].motor_tau_s = (ladrc_real_t)sc->motor_tau_s;
        cfg->axis[i].delay_ticks = (uint16_t)sc->delay_ticks; /* 0..SIM_SENSOR_MAX_DELAY (schema.c) */
        apply_overrides(&cfg->axis[i], o);
        if (sc->tuning[id].tuned) { /* tune = margins: the file gives no gains */
            sim_setup_tuned_gains(&sc->tuning[id], i, &cfg->axis[i]);
        }
    }
    cfg->axis[2].wrap_angle = (uint8_t)sim_setup_wraps_yaw(sc, id);
    if (o->coupling_feed >= 0) {
        cfg->coupling_feed = (uint8_t)o->coupling_feed;
    }
    if (sc->frame == LADRC_FRAME_QUATERNION) {
        ladrc_attitude_config_quaternion(cfg);
        cfg->yaw_weight = (ladrc_real_t)sc->yaw_weight;
    }
    if (o->gain_schedule == 1) {
        /* the rotors' own curve (the mixer's is then 0: checks), full thrust,
         * b0 at hover; the voltage with a battery that sags */
        cfg->gain_thrust_curve = (ladrc_real_t)(isfinite(sc->thrust_curve) ? sc->thrust_curve : 0.0);
        cfg->gain_full_thrust_N = (ladrc_real_t)(4.0 * sc->thrust_coeff_N_s2 * sc->w2_max_rad2_s2);
        cfg->gain_ref_thrust_N = (ladrc_real_t)(sc->mass_kg * sc->g_m_s2);
        cfg->gain_ref_voltage_V = (ladrc_real_t)(sc->battery_life_s > 0.0 ? sc->battery_full_V : 0.0);
    }
}

void sim_setup_mixer(const sim_scenario_t *sc, ladrc_mixer_config_t *cfg)
{
    const double w2_min = sc->rotors_ideal ? 0.0 : sc->w2_min_rad2_s2;
    const double w2_max = sc->rotors_ideal ? 1e12 : sc->w2_max_rad2_s2;
    cfg->kL_N_s2 = (ladrc_real_t)sc->thrust_coeff_N_s2;
    cfg->arm_m = (ladrc_real_t)sc->arm_m;
    cfg->b_Nm_s2 = (ladrc_real_t)sc->yaw_coeff_Nm_s2;
    cfg->mass_kg = (ladrc_real_t)sc->mass_kg;
    cfg->g_m_s2 = (ladrc_real_t)sc->g_m_s2;
    cfg->w2_min_rad2_s2 = (ladrc_real_t)w2_min;
    cfg->w2_max_rad2_s2 = (ladrc_real_t)w2_max;
    cfg->tilt_max_rad = (ladrc_real_t)sc->tilt_max_rad;
    cfg->mode = sc->rotors_ideal ? LADRC_MIXER_IDEAL : LADRC_MIXER_SATURATE;
}

void sim_setup_differentiators(const sim_scenario_t *sc, ladrc_levant_config_t *lev, ladrc_td_config_t *td)
{
    const ladrc_real_t dt = (ladrc_real_t)sc->control_dt_s;
    ladrc_axis_config_t axis; /* the library's defaults for the shapers */
    ladrc_axis_config_default(&axis, LADRC_VARIANT_LADRC, dt, (ladrc_real_t)1.0);
    memset(lev, 0, sizeof *lev);
    lev->dt_s = dt;
    lev->method = LADRC_LEVANT_IMPLICIT;
    lev->gains = LADRC_LEVANT_GAINS_LIPSCHITZ;
    lev->lipschitz_rad_s4 =
        isnan(sc->diff_levant_lipschitz) ? axis.levant_lipschitz_rad_s4 : (ladrc_real_t)sc->diff_levant_lipschitz;
    td->dt_s = dt;
    td->accel_rad_s2 = isnan(sc->diff_td_accel) ? axis.td_accel_rad_s2 : (ladrc_real_t)sc->diff_td_accel;
    td->h0_s = isnan(sc->diff_td_h0_s) ? axis.td_h0_s : (ladrc_real_t)sc->diff_td_h0_s;
}

sim_vehicle_t sim_setup_vehicle(const sim_scenario_t *sc)
{
    const sim_vehicle_t v = {.mass_kg = sc->mass_kg,
                             .inertia_kg_m2 = {sc->inertia_kg_m2[0], sc->inertia_kg_m2[1], sc->inertia_kg_m2[2]},
                             .arm_m = sc->arm_m,
                             .thrust_coeff_N_s2 = sc->thrust_coeff_N_s2,
                             .yaw_coeff_Nm_s2 = sc->yaw_coeff_Nm_s2,
                             .rot_drag_Nm_s = sc->rot_drag_Nm_s,
                             .g_m_s2 = sc->g_m_s2,
                             .rotors_ideal = sc->rotors_ideal,
                             .w2_min_rad2_s2 = sc->w2_min_rad2_s2,
                             .w2_max_rad2_s2 = sc->w2_max_rad2_s2,
                             .motor_tau_s = sc->motor_tau_s,
                             .motor_tau_down_s = sc->motor_tau_down_s,
                             .battery_life_s = sc->battery_life_s,
                             .battery_drop = sc->battery_drop,
                             .rotor_drag_N_s_m = sc->rotor_drag_N_s_m,
                             .rotor_height_m = sc->rotor_height_m,
                             .rigid_body = sc->rigid_body};
    return v;
}

sim_vibration_config_t sim_setup_vibration(const sim_scenario_t *sc)
{
    sim_vibration_config_t c;
    memset(&c, 0, sizeof c);
    c.n_orders = sc->vib_n_orders;
    for (int k = 0; k < sc->vib_n_orders && k < SIM_VIB_MAX_ORDERS; ++k) {
        c.order[k] = sc->vib_order[k];
        c.gyro_rad_s[k] = k < sc->vib_n_gyro ? sc->vib_gyro_rad_s[k] : 0.0;
        c.accel_m_s2[k] = k < sc->vib_n_accel ? sc->vib_accel_m_s2[k] : 0.0;
    }
    for (int a = 0; a < 3; ++a) {
        c.axis_gain[a] = sc->vib_axis_gain[a];
    }
    return c;
}

int sim_setup_filters_gyro(const sim_scenario_t *sc)
{
    return sc->filter_enabled && (sc->filter_lpf_order > 0 || sc->filter_n_notches > 0 || sc->filter_rpm_harmonics > 0);
}

void sim_setup_gyro_filter(const sim_scenario_t *sc, ladrc_gyro_filter_config_t *cfg)
{
    ladrc_gyro_filter_config_default(cfg, (ladrc_real_t)sc->control_dt_s, (uint8_t)(sc->filter_angle ? 6 : 3));
    cfg->lpf_order = (uint8_t)sc->filter_lpf_order;
    cfg->lpf_cutoff_hz = (ladrc_real_t)sc->filter_lpf_hz;
    cfg->n_notches = (uint8_t)sc->filter_n_notches;
    for (int i = 0; i < sc->filter_n_notches; ++i) {
        cfg->notch_hz[i] = (ladrc_real_t)sc->filter_notch_hz[i];
    }
    cfg->notch_q = (ladrc_real_t)sc->filter_notch_q;
    cfg->rpm_rotors = (uint8_t)(sc->filter_rpm_harmonics > 0 ? 4 : 0);
    cfg->rpm_harmonics = (uint8_t)(sc->filter_rpm_harmonics > 0 ? sc->filter_rpm_harmonics : 1);
    cfg->rpm_q = (ladrc_real_t)sc->filter_rpm_q;
    cfg->rpm_min_hz = (ladrc_real_t)sc->filter_rpm_min_hz;
    cfg->rpm_fade_hz = (ladrc_real_t)sc->filter_rpm_fade_hz;
}

double sim_setup_hover_rotor_hz(const sim_scenario_t *sc)
{
    return sqrt(sim_hover_w2_rad2_s2(sc->mass_kg, sc->g_m_s2, sc->thrust_coeff_N_s2)) / 6.283185307179586; /* 2 pi */
}

double sim_setup_authority_Nm(const sim_scenario_t *sc, int axis)
{
    const double w2_hover = sim_hover_w2_rad2_s2(sc->mass_kg, sc->g_m_s2, sc->thrust_coeff_N_s2);
    return axis == 2 ? 4.0 * sc->yaw_coeff_Nm_s2 * w2_hover : 2.0 * sc->arm_m * sc->thrust_coeff_N_s2 * w2_hover;
}

double sim_setup_full_w2_rad2_s2(const sim_scenario_t *sc)
{
    return sc->rotors_ideal ? 2.0 * sim_hover_w2_rad2_s2(sc->mass_kg, sc->g_m_s2, sc->thrust_coeff_N_s2)
                            : sc->w2_max_rad2_s2;
}
