/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * One attitude run of a lockstep group (runner_parts.h): its controller,
 * plant and sensor set up, each control tick (measure, check, control, mix,
 * the truth, metrics, the time series' line), divergence, and the close.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant/rotation.h"
#include "runner_parts.h"
#include "scenario/excitation.h"
#include "scenario/setup.h"

/* The vibration's phases: another stream than the sensor noise's. */
#define VIBRATION_SEED_SALT 0x56494252ULL /* "VIBR" */

/* The controller and mixer of the run, configured as the parser checked them. */
static int configure(const sim_scenario_t *sc, sim_controller_id_t id, ladrc_attitude_t *att, ladrc_mixer_t *mixer,
                     char *err, size_t err_len)
{
    ladrc_attitude_config_t cfg;
    int bad_axis = -1;
    ladrc_status_t st = LADRC_OK;
    if (id == SIM_CTRL_BETAFLIGHT) {
        memset(att, 0, sizeof *att); /* not flown: the SITL controls (the mixer gives the thrust asked) */
    } else {
        sim_setup_attitude(sc, id, &cfg);
        st = ladrc_attitude_init(att, &cfg, &bad_axis);
    }
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: controller %s, axis %d: %s", sc->path, sim_controller_name(id), bad_axis,
                 ladrc_status_str(st));
        return -1;
    }
    ladrc_mixer_config_t mix;
    sim_setup_mixer(sc, &mix);
    st = ladrc_mixer_init(mixer, &mix);
    if (st == LADRC_OK) {
        st = ladrc_mixer_set_thrust_curve(mixer, (ladrc_real_t)sc->mixer_thrust_curve);
    }
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: mixer: %s", sc->path, ladrc_status_str(st));
        return -1;
    }
    return 0;
}

/* ref - angle (rad); on a wrapped axis taken into (-pi, pi]: 359 deg of error is 1 deg. */
static double tracking_error_rad(double ref_rad, double angle_rad, int wrapped)
{
    const double e = ref_rad - angle_rad;
    return wrapped ? sim_wrap_pi(e) : e;
}

/* The tracking error of every axis (rad): ref - angle per axis in the Euler
 * frame (yaw's wrapped when the controller wraps it), the body-axis
 * rotation vector from the attitude to the reference's (ZYX) in the
 * quaternion frame. */
void runner_attitude_error_rad(const sim_scenario_t *sc, const sim_plant_t *p, const double ref_rad[3], int wrap_yaw,
                               double error_rad[3])
{
    if (sc->frame == LADRC_FRAME_QUATERNION) {
        double q[4], q_ref[4];
        sim_plant_attitude(p, q);
        sim_quat_from_euler(ref_rad, q_ref);
        sim_quat_error(q, q_ref, error_rad);
        return;
    }
    for (int i = 0; i < 3; ++i) {
        error_rad[i] = tracking_error_rad(ref_rad[i], p->angle_rad[i], i == 2 && wrap_yaw);
    }
}

/* How far the controller is from the reference it tracks on axis i (deg):
 * its shaped reference less its angle. */
static double shaped_error_deg(const ladrc_attitude_t *att, int i)
{
    ladrc_ref_t ref;
    ladrc_real_t angle = LADRC_R(0.0), rate, disturbance;
    ladrc_axis_get_reference(&att->axis[i], &ref);
    ladrc_axis_get_estimate(&att->axis[i], &angle, &rate, &disturbance);
    return fabs(sim_wrap_pi((double)ref.r - (double)angle)) * RAD2DEG;
}

/* Divergence at t (runner.h): the plant's state non-finite, or the tracking
 * error ref - angle beyond the scenario's limit on an axis while the
 * controller is as far from its own shaped reference (att; NULL: not
 * asked). An error beyond the limit with the controller near its shaped
 * reference is the reference outrunning the shaper, not a divergence: it
 * is recorded (reference_outran_*) and the run goes on. Records the first
 * cause found in m and returns 1; 0 while the run is healthy. */
int runner_diverged(const sim_scenario_t *sc, const sim_plant_t *p, const double ref_rad[3], int wrap_yaw, double t_s,
                    const ladrc_attitude_t *att, sim_metrics_t *m)
{
    int axis = -2;
    double error_deg = NAN, error_rad[3];
    runner_attitude_error_rad(sc, p, ref_rad, wrap_yaw, error_rad);
    for (int i = 0; i < 3 && axis == -2; ++i) {
        const double e_deg = error_rad[i] * RAD2DEG;
        if (!isfinite(e_deg) || !isfinite(p->rate_rad_s[i])) {
            axis = i;
            m->finite = 0;
        } else if (fabs(e_deg) > sc->diverge_limit_deg) {
            if (att != NULL && shaped_error_deg(att, i) <= SIM_SHAPED_TRACKING_SHARE * sc->diverge_limit_deg) {
                if (isnan(m->reference_outran_at_s[i])) {
                    m->reference_outran_at_s[i] = t_s;
                }
                m->reference_outran_deg[i] = fmax(m->reference_outran_deg[i], fabs(e_deg));
                continue;
            }
            axis = i;
            error_deg = fabs(e_deg);
        }
    }
    for (int r = 0; r < 4 && axis == -2; ++r) {
        if (!isfinite(p->w2_rad2_s2[r])) {
            axis = -1;
            m->finite = 0;
        }
    }
    if (axis == -2) {
        return 0;
    }
    m->diverged = 1;
    m->diverged_at_s = t_s;
    m->diverged_axis = axis;
    m->diverged_error_deg = error_deg;
    return 1;
}

/* Sets a run up; 0, or -1 with the message in its spec (then it does not fly). */
int runner_run_open(const sim_scenario_t *sc, attitude_run_t *r, sim_run_spec_t *spec)
{
    sim_metrics_t *m = spec->metrics;
    r->spec = spec;
    r->flying = 0;
    r->csv = NULL;
    memset(&r->log, 0, sizeof r->log); /* no flight log open */
    r->rec = NULL;                     /* no series unless the group gives its own */
    r->bf = NULL;
    r->failed = 0;
    memset(m, 0, sizeof *m);
    if (configure(sc, spec->ctrl, &r->att, &r->mixer, spec->err, spec->err_len) != 0) {
        return -1;
    }
    const sim_vehicle_t vehicle = sim_setup_vehicle(sc);
    sim_plant_init(&r->plant, &vehicle);
    if (sim_sensor_init(&r->sensor, sc->angle_noise_std_rad, sc->rate_noise_std_rad_s, sc->delay_ticks, sc->seed) !=
        0) {
        snprintf(spec->err, spec->err_len, "%s: bad sensor settings", sc->path);
        return -1;
    }
    const sim_vibration_config_t vib = sim_setup_vibration(sc);
    if (sim_vibration_init(&r->vibration, &vib, sc->seed ^ VIBRATION_SEED_SALT) != 0) {
        snprintf(spec->err, spec->err_len, "%s: bad vibration settings", sc->path);
        return -1;
    }
    r->filtered = sim_setup_filters_gyro(sc);
    if (r->filtered) {
        ladrc_gyro_filter_config_t fc;
        sim_setup_gyro_filter(sc, &fc);
        const ladrc_status_t st = ladrc_gyro_filter_init(&r->filter, &fc);
        if (st != LADRC_OK) {
            snprintf(spec->err, spec->err_len, "%s: [filter]: %s", sc->path, ladrc_status_str(st));
            return -1;
        }
    }
    if (spec->csv_path != NULL) {
        char header[RUNNER_CSV_HEADER_MAX];
        runner_attitude_csv_header(header, sizeof header);
        r->csv = runner_open_csv(spec->csv_path, header, spec->err, spec->err_len);
        if (r->csv == NULL) {
            return -1;
        }
    }
    if (runner_log_open(&r->log, sc, spec->csv_path, spec->err, spec->err_len) != 0) {
        if (r->csv != NULL) {
            fclose(r->csv);
            r->csv = NULL;
        }
        return -1;
    }
    r->excited = sc->excite_on;
    for (int i = 0; i < 3; ++i) {
        r->authority_Nm[i] = sim_setup_authority_Nm(sc, i);
    }
    r->line.len = 0;
    for (int i = 0; i < 3; ++i) {
        r->last_out_s[i] = sc->settle_after_s;
        r->out_at_last[i] = 0;
        m->settle_s[i] = SIM_NOT_SETTLED;
    }
    /* The command noise's high-pass, from rest (a corner at or above 0.45 of
     * the sampling rate leaves no band: NaN) */
    r->cmd_hp_on = SIM_CMD_NOISE_CORNER_HZ < 0.45 / sc->control_dt_s;
    r->cmd_hp = biquad_highpass(SIM_CMD_NOISE_CORNER_HZ, sc->control_dt_s, BIQUAD_Q_BUTTERWORTH);
    for (int i = 0; i < 3; ++i) {
        r->cmd_hp_state[i].z1 = r->cmd_hp_state[i].z2 = 0.0;
        memset(&m->cmd_hp_Nm[i], 0, sizeof m->cmd_hp_Nm[i]);
        m->cmd_noise_Nm[i] = r->cmd_hp_on ? 0.0 : NAN;
    }
    /* A wrapping controller is told yaw as an attitude estimator gives it,
     * in (-pi, pi]; the plant's own yaw is continuous (not wrapped). */
    r->wrap_yaw = sc->frame == LADRC_FRAME_EULER && sim_setup_wraps_yaw(sc, spec->ctrl);
    /* [phases]: disarmed until the first arm_s when one is given, on the
     * ground until the first takeoff_s when one is given */
    r->next_event = 0;
    r->armed = sc->phase_n_arm == 0;
    r->on_ground = sc->phase_n_takeoff > 0;
    r->ground_angle_rad[0] = sc->ground_rad[0];
    r->ground_angle_rad[1] = sc->ground_rad[1];
    r->ground_angle_rad[2] = 0.0;
    const int library = spec->ctrl != SIM_CTRL_BETAFLIGHT;
    if (r->on_ground) {
        sim_plant_hold(&r->plant, r->ground_angle_rad);
        if (library) {
            ladrc_attitude_set_landed(&r->att, (uint8_t)sc->landed_input);
        }
    }
    if (!r->armed && library) {
        ladrc_attitude_disarm(&r->att);
    }
    m->has_estimate = library && spec->ctrl != SIM_CTRL_PID && spec->ctrl != SIM_CTRL_CASCADED;
    m->finite = 1;
    m->diverged_axis = -1;
    m->diverged_at_s = m->diverged_error_deg = NAN;
    for (int i = 0; i < 3; ++i) {
        m->reference_outran_at_s[i] = NAN;
        m->reference_outran_deg[i] = 0.0;
    }
    if (!library && runner_bf_open(sc, r, spec->err, spec->err_len) != 0) {
        runner_bf_close(r);
        if (r->csv != NULL) {
            fclose(r->csv);
            r->csv = NULL;
        }
        char ignored[8];
        (void)runner_log_close(&r->log, ignored, sizeof ignored);
        return -1;
    }
    r->flying = 1;
    return 0;
}

/* The thrust asked of the mixer (N): none while disarmed, the ground's share
 * of the weight while armed on the ground, else what holds altitude at the
 * measured tilt. */
ladrc_real_t runner_thrust_N(const sim_scenario_t *sc, const attitude_run_t *r, const ladrc_real_t angle[3], double t_s)
{
    if (!r->armed) {
        return LADRC_R(0.0);
    }
    if (r->on_ground) {
        return (ladrc_real_t)(sc->ground_thrust * sc->mass_kg * sc->g_m_s2);
    }
    if (sc->throttle.n_pieces > 0) { /* a fraction of the full thrust */
        return (ladrc_real_t)(sim_signal_eval(&sc->throttle, t_s) * 4.0 * sc->thrust_coeff_N_s2 * sc->w2_max_rad2_s2);
    }
    return ladrc_mixer_thrust_from_tilt(&r->mixer, angle[0], angle[1]);
}

/* The pack's voltage at t_s (V): full, less what the battery law takes off. */
static ladrc_real_t run_voltage_V(const sim_scenario_t *sc, const attitude_run_t *r, double t_s)
{
    return (ladrc_real_t)(sc->battery_full_V * sqrt(sim_plant_battery_factor(&r->plant.v, t_s)));
}

/* The w^2 a rotor gives for the mix's w2: itself, or with [rotors]
 * thrust_curve through the ESC command the mixer gives (ladrc_mixer_command)
 * and the rotors' own curve. */
static double rotor_w2(const sim_scenario_t *sc, const attitude_run_t *r, ladrc_real_t w2)
{
    if (!isfinite(sc->thrust_curve)) {
        return (double)w2;
    }
    return runner_command_w2(sc, (double)ladrc_mixer_command(&r->mixer, w2));
}

double runner_command_w2(const sim_scenario_t *sc, double c)
{
    const double k = isfinite(sc->thrust_curve) ? sc->thrust_curve : 0.0;
    return sc->w2_max_rad2_s2 * ((1.0 - k) * c + k * c * c);
}

/* The torque asked of the mixer: the controller's, plus [excitation]'s
 * chirp (its normalised value times the axis's authority) when excited. */
static const ladrc_real_t *run_excite(const sim_scenario_t *sc, attitude_run_t *r, const tick_t *tk)
{
    if (!r->excited) {
        return tk->torque;
    }
    double command[3];
    sim_excitation_at(sc, tk->t, command);
    for (int i = 0; i < 3; ++i) {
        r->asked_Nm[i] = (ladrc_real_t)((double)tk->torque[i] + command[i] * r->authority_Nm[i]);
    }
    return r->asked_Nm;
}

/* Measure, check, control and mix at tk->t; 0 when the run diverged (nothing
 * of this instant or later is recorded), -1 when its SITL failed (the message
 * in the spec), else 1 with the rotors' command. */
static int run_control(const sim_scenario_t *sc, attitude_run_t *r, tick_t *tk, double w2_cmd[4])
{
    const sim_plant_t *plant = &r->plant;
    const int quat_frame = sc->frame == LADRC_FRAME_QUATERNION;
    double q_sensed[4], angle_sensed[3];
    if (quat_frame) {
        double q_true[4];
        sim_plant_attitude(plant, q_true);
        sim_sensor_measure_quat(&r->sensor, plant->angle_rad, q_true, plant->rate_rad_s, tk->meas_angle, tk->meas_rate,
                                q_sensed);
        memcpy(angle_sensed, tk->meas_angle, sizeof angle_sensed);
    } else {
        sim_sensor_measure(&r->sensor, plant->angle_rad, plant->rate_rad_s, tk->meas_angle, tk->meas_rate);
    }
    if (r->rec != NULL && r->rec->has_rate) {
        runner_recorded_add(&r->rec->rate, &r->rate_cur, tk->t, tk->meas_rate);
    }
    if (r->rec != NULL && r->rec->has_angle) {
        runner_recorded_add(&r->rec->angle, &r->angle_cur, tk->t, tk->meas_angle);
    }
    const double gravity[3] = {0.0, 0.0, -plant->v.g_m_s2}; /* what a level, hovering IMU reads */
    sim_plant_wind_to_body(plant->angle_rad, gravity, tk->accel_m_s2);
    sim_vibration_tick(&r->vibration, plant->w2_rad2_s2, sc->control_dt_s, tk->meas_rate, tk->meas_angle,
                       tk->accel_m_s2);
    if (runner_diverged(sc, plant, tk->ref_rad, r->wrap_yaw, tk->t, r->bf != NULL ? NULL : &r->att, r->spec->metrics)) {
        return 0;
    }
    if (r->bf != NULL) {
        return runner_bf_control(sc, r, tk, w2_cmd);
    }
    /* the filter stage sees the rates and the unwrapped angles, as the
     * attitude estimator integrating the filtered gyro would give them;
     * a wrapping controller gets yaw in (-pi, pi] after it */
    const double yaw_rad = tk->meas_angle[2];
    if (r->wrap_yaw) {
        tk->meas_angle[2] = sim_wrap_pi(yaw_rad);
    }
    ladrc_real_t signal[6];
    for (int i = 0; i < 3; ++i) {
        signal[i] = (ladrc_real_t)tk->meas_rate[i];
        signal[3 + i] = (ladrc_real_t)tk->meas_angle[i];
    }
    if (r->filtered) {
        signal[5] = (ladrc_real_t)yaw_rad;
        ladrc_real_t rotor_hz[4];
        for (int q = 0; q < 4; ++q) {
            rotor_hz[q] = (ladrc_real_t)sim_vibration_rotor_hz(&r->vibration, q);
        }
        ladrc_fault_t f = ladrc_gyro_filter_set_rotor_hz(&r->filter, rotor_hz);
        f |= ladrc_gyro_filter_step(&r->filter, signal, signal);
        if (f != LADRC_FAULT_NONE) {
            r->spec->metrics->faults++;
        }
        if (r->wrap_yaw) {
            signal[5] = (ladrc_real_t)sim_wrap_pi((double)signal[5]);
        }
    }
    ladrc_real_t angle[3], rate[3], thrust_N;
    for (int i = 0; i < 3; ++i) {
        rate[i] = signal[i];
        angle[i] = signal[3 + i];
        tk->ctrl_rate[i] = (double)rate[i];
        tk->ctrl_angle[i] = (double)angle[i];
    }
    ladrc_quat_t meas = {LADRC_R(1.0), 0, 0, 0}, ref = {LADRC_R(1.0), 0, 0, 0};
    if (quat_frame) {
        /* what series and vibration added to the angles turns the sensed
         * attitude as a small rotation in body axes */
        double turn_rad[3], turn[4], q_meas[4], q_ref[4], tilt_rad[3];
        for (int i = 0; i < 3; ++i) {
            turn_rad[i] = tk->meas_angle[i] - angle_sensed[i];
        }
        sim_quat_from_rotvec(turn_rad, turn);
        sim_quat_mul(q_sensed, turn, q_meas);
        sim_quat_from_euler(tk->ref_rad, q_ref);
        meas = (ladrc_quat_t){(ladrc_real_t)q_meas[0], (ladrc_real_t)q_meas[1], (ladrc_real_t)q_meas[2],
                              (ladrc_real_t)q_meas[3]};
        ref = (ladrc_quat_t){(ladrc_real_t)q_ref[0], (ladrc_real_t)q_ref[1], (ladrc_real_t)q_ref[2],
                             (ladrc_real_t)q_ref[3]};
        sim_quat_to_euler(q_meas, NULL, tilt_rad); /* the mixer's tilt: cos(roll) cos(pitch) is R33 */
        angle[0] = (ladrc_real_t)tilt_rad[0];
        angle[1] = (ladrc_real_t)tilt_rad[1];
        tk->ctrl_quat[0] = (double)meas.w;
        tk->ctrl_quat[1] = (double)meas.x;
        tk->ctrl_quat[2] = (double)meas.y;
        tk->ctrl_quat[3] = (double)meas.z;
        memcpy(tk->ctrl_angle, tilt_rad, sizeof tilt_rad);
    }
    thrust_N = runner_thrust_N(sc, r, angle, tk->t);
    tk->thrust_N = thrust_N;
    ladrc_attitude_set_operating_point(&r->att, thrust_N, run_voltage_V(sc, r, tk->t));
    const ladrc_fault_t faults =
        quat_frame ? ladrc_attitude_step_quat(&r->att, &ref, &meas, sc->use_rate ? rate : NULL, tk->torque)
                   : ladrc_attitude_step(&r->att, tk->ref, angle, sc->use_rate ? rate : NULL, tk->torque);
    if (faults != LADRC_FAULT_NONE) {
        r->spec->metrics->faults++;
    }
    ladrc_mixer_step(&r->mixer, thrust_N, run_excite(sc, r, tk), &tk->out);
    ladrc_attitude_set_applied(&r->att, tk->out.torque_Nm); /* the chirp included */
    for (int q = 0; q < 4; ++q) {
        w2_cmd[q] = rotor_w2(sc, r, tk->out.w2_rad2_s2[q]);
    }
    return 1;
}

/* The truth of the tick and the controller's estimates (tick_t). */
static void run_truth(const sim_scenario_t *sc, const attitude_run_t *r, tick_t *tk)
{
    const sim_plant_t *plant = &r->plant;
    double accel[3], thrust_actual, torque_actual[3];
    for (int i = 0; i < 3; ++i) {
        tk->applied[i] = tk->out.torque_Nm[i];
    }
    sim_plant_forces(&plant->v, plant->w2_rad2_s2, &thrust_actual, torque_actual);
    sim_plant_accel(plant, torque_actual, tk->dist, accel);
    runner_attitude_error_rad(sc, plant, tk->ref_rad, r->wrap_yaw, tk->err_rad);
    for (int i = 0; i < 3; ++i) {
        tk->f_true[i] = accel[i] - tk->applied[i] / (sc->inertia_kg_m2[i] * sc->inertia_scale[i]);
        if (r->bf != NULL) { /* the SITL's estimates are its own */
            tk->f_est[i] = tk->z1[i] = tk->z2[i] = NAN;
            continue;
        }
        ladrc_real_t a_est, r_est, d_est;
        ladrc_axis_get_estimate(&r->att.axis[i], &a_est, &r_est, &d_est);
        tk->f_est[i] = d_est;
        tk->z1[i] = a_est;
        tk->z2[i] = r_est;
    }
}

/* The tick into the run's statistics (metrics.h) and settling. */
static void run_metrics(const sim_scenario_t *sc, attitude_run_t *r, const tick_t *tk)
{
    sim_metrics_t *m = r->spec->metrics;
    const double t = tk->t;
    const double band_rad = sc->settle_band_deg / RAD2DEG;
    for (int i = 0; i < 3; ++i) {
        const double e_deg = tk->err_rad[i] * RAD2DEG;
        if (r->cmd_hp_on) {
            const double hp = biquad_step(&r->cmd_hp, &r->cmd_hp_state[i], (double)tk->torque[i]);
            if (in_window(sc->error_window_s, t))
                sim_stat_add(&m->cmd_hp_Nm[i], hp);
        }
        if (in_window(sc->error_window_s, t)) {
            sim_stat_add(&m->error_deg[i], e_deg);
            if (fabs(e_deg) > m->max_error_deg[i])
                m->max_error_deg[i] = fabs(e_deg);
            if (m->has_estimate)
                sim_stat_add(&m->dist_error[i], tk->f_est[i] - tk->f_true[i]);
        }
        if (in_window(sc->steady_window_s, t)) {
            sim_stat_add(&m->steady_deg[i], e_deg);
            if (fabs(e_deg) > m->band_deg[i])
                m->band_deg[i] = fabs(e_deg);
        }
        if (t >= sc->settle_after_s && t <= sc->settle_until_s) {
            r->out_at_last[i] = fabs(tk->err_rad[i]) > band_rad;
            if (r->out_at_last[i]) {
                r->last_out_s[i] = t + sc->control_dt_s;
            }
        }
    }
    for (int q = 0; q < 4; ++q) {
        sim_stat_add(&m->rotor_w2[q], r->plant.w2_rad2_s2[q]);
    }
}

/* The [phases] events due by t, in order, and the ground's hold. */
static void run_phases(const sim_scenario_t *sc, attitude_run_t *r, double t)
{
    for (; r->next_event < sc->n_events && sc->event_s[r->next_event] <= t; ++r->next_event) {
        if (r->bf != NULL) { /* the SITL gets the switches and the throttle from its pilot */
            const int kind = sc->event_kind[r->next_event];
            r->armed = kind == SIM_EVENT_ARM ? 1 : kind == SIM_EVENT_DISARM ? 0 : r->armed;
            r->on_ground = kind == SIM_EVENT_TAKEOFF ? 0 : kind == SIM_EVENT_LAND ? 1 : r->on_ground;
            if (kind == SIM_EVENT_LAND) {
                r->ground_angle_rad[2] = r->plant.angle_rad[2];
            }
            continue;
        }
        switch (sc->event_kind[r->next_event]) {
        case SIM_EVENT_ARM:
            r->armed = 1;
            ladrc_attitude_arm(&r->att);
            break;
        case SIM_EVENT_TAKEOFF:
            r->on_ground = 0;
            ladrc_attitude_set_landed(&r->att, 0u);
            break;
        case SIM_EVENT_LAND: /* touch down level on the ground, heading kept */
            r->on_ground = 1;
            r->ground_angle_rad[2] = r->plant.angle_rad[2];
            ladrc_attitude_set_landed(&r->att, (uint8_t)sc->landed_input);
            break;
        default:
            r->armed = 0;
            ladrc_attitude_disarm(&r->att);
            break;
        }
    }
    if (r->on_ground) {
        sim_plant_hold(&r->plant, r->ground_angle_rad);
    }
}

/* The controller's part of a tick at t: measure, check, control, record.
 * ref and dist are the references and disturbances at t. Returns 0 when the
 * run diverged (nothing of this instant or later is recorded), else 1. */
int runner_run_tick(const sim_scenario_t *sc, attitude_run_t *r, double t, const ladrc_real_t ref[3],
                    const double ref_rad[3], const double dist[3], double w2_cmd[4])
{
    tick_t tk;
    if (sc->n_events > 0 || r->on_ground) {
        run_phases(sc, r, t);
    }
    tk.t = t;
    tk.ref = ref;
    tk.ref_rad = ref_rad;
    tk.dist = dist;
    const int controlled = run_control(sc, r, &tk, w2_cmd);
    if (controlled <= 0) {
        r->failed = controlled < 0;
        return 0;
    }
    run_truth(sc, r, &tk);
    run_metrics(sc, r, &tk);
    if (r->csv != NULL) {
        runner_csv_line(r, &tk);
    }
    if (r->log.forms != 0) {
        runner_log_tick(&r->log, sc, &r->plant, &tk, w2_cmd);
    }
    return 1;
}

/* Settling times and the time series' end; 0, or -1 with the message. */
int runner_run_close(const sim_scenario_t *sc, attitude_run_t *r)
{
    sim_metrics_t *m = r->spec->metrics;
    runner_bf_close(r);
    for (int i = 0; i < 3; ++i) {
        m->settle_s[i] = r->out_at_last[i] ? SIM_NOT_SETTLED : r->last_out_s[i] - sc->settle_after_s;
        if (r->cmd_hp_on)
            m->cmd_noise_Nm[i] = sim_stat_rms(&m->cmd_hp_Nm[i]);
    }
    char log_err[SIM_PATH_LEN + 64];
    const int log_rc = runner_log_close(&r->log, log_err, sizeof log_err);
    const int csv_rc = r->csv != NULL && fclose(r->csv) != 0 ? -1 : 0;
    r->csv = NULL;
    if (r->failed) {
        return -1; /* its message is the failure's */
    }
    if (csv_rc != 0) {
        snprintf(r->spec->err, r->spec->err_len, "%s: write failed", r->spec->csv_path);
        return -1;
    }
    if (log_rc != 0) {
        snprintf(r->spec->err, r->spec->err_len, "%s", log_err);
    }
    return log_rc;
}
