/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * The scenario's checks once every line is read (parser.h): the keys
 * against the kind, the run's size and limits, rotors, differentiator and
 * tuning keys against each other; then what the library accepts. Each
 * error is at the key responsible; the earliest in the file is kept.
 */
#include "parser.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "plant/plant.h"
#include "plant/turbulence.h"
#include "excitation.h"
#include "series.h"
#include "setup.h"

/* A consistency error: kept if it is the earliest in the file so far. */
static void PRINTF_LIKE(4, 5) check_fail(parser_t *p, int line, int col, const char *format, ...)
{
    if (p->checked && (line > p->place.err->line || (line == p->place.err->line && col >= p->place.err->column))) {
        return;
    }
    p->checked = 1;
    va_list ap;
    va_start(ap, format);
    ini_vset_error(p->place.err, line, col, format, ap);
    va_end(ap);
}

const loc_t *checks_seen(const parser_t *p, int sec, const char *name)
{
    const int k = schema_find_key(SCHEMA_TABLE(sec), name);
    return &p->seen[sec][k];
}

static void check_kind(parser_t *p)
{
    const int kind = p->sc->kind == SIM_KIND_DIFFERENTIATOR ? FOR_DIFFERENTIATOR : FOR_ATTITUDE;
    const char *kind_name = kind == FOR_DIFFERENTIATOR ? "differentiator" : "attitude";
    char title[48];
    for (int sec = 0; sec < SEC_COUNT; ++sec) {
        const int sec_kind = schema_section_kind(sec);
        if (p->section_line[sec] != 0 && sec_kind != FOR_BOTH && sec_kind != kind) {
            check_fail(p, p->section_line[sec], 1, "%s does not apply to kind = %s",
                       schema_section_title(sec, title, sizeof title), kind_name);
        }
        for (int k = 0; k < SCHEMA_N_KEYS; ++k) {
            const loc_t *at = &p->seen[sec][k];
            const int key_kind = schema_key_kind(sec, &SCHEMA_KEYS[k]);
            /* a key of a section that does not apply is reported with its section */
            if (at->line != 0 && SCHEMA_KEYS[k].kind != FOR_BOTH && SCHEMA_KEYS[k].kind != kind) {
                check_fail(p, at->line, at->key_col, "'%s' does not apply to kind = %s", SCHEMA_KEYS[k].name,
                           kind_name);
            }
            if (SCHEMA_KEYS[k].required && SCHEMA_KEYS[k].section == sec && at->line == 0 &&
                (key_kind == FOR_BOTH || key_kind == kind)) {
                const int line = p->section_line[sec] != 0 ? p->section_line[sec] : 1;
                check_fail(p, line, 1, "missing required key '%s' in %s", SCHEMA_KEYS[k].name,
                           schema_section_title(sec, title, sizeof title));
            }
        }
    }
}

/* The first of the keys of a section that the file gives, or NULL. */
static const loc_t *first_given(const parser_t *p, int sec, const char *const *names, int n)
{
    for (int i = 0; i < n; ++i) {
        const loc_t *at = checks_seen(p, sec, names[i]);
        if (at->line != 0) {
            return at;
        }
    }
    return NULL;
}

/* Where a limit on the run's steps is reported: the first key given of
 * plant_substeps (when it takes part), control_dt_s, duration_s. */
static const loc_t *steps_key(const parser_t *p, int with_substeps)
{
    static const char *const keys[] = {"plant_substeps", "control_dt_s", "duration_s"};
    return with_substeps ? first_given(p, SEC_RUN, keys, 3) : first_given(p, SEC_RUN, keys + 1, 2);
}

/* The run's size (control periods and plant steps) and the plant step
 * against the plant's time constants; limits in scenario.h. */
static void check_run_size(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const double ticks = floor(sc->duration_s / sc->control_dt_s + 0.5); /* sim_run_ticks */
    if (ticks > (double)SIM_RUN_TICKS_MAX) {
        const loc_t *at = steps_key(p, 0);
        check_fail(p, at->line, at->value_col,
                   "the run takes %g control periods (duration_s / control_dt_s), more than %g", ticks,
                   (double)SIM_RUN_TICKS_MAX);
        return;
    }
    if (sc->kind != SIM_KIND_ATTITUDE) {
        return;
    }
    const double steps = ticks * sc->plant_substeps;
    if (steps > SIM_RUN_PLANT_STEPS_MAX) {
        const loc_t *at = steps_key(p, 1);
        check_fail(p, at->line, at->value_col,
                   "the run takes %g plant steps (duration_s / control_dt_s x plant_substeps), more than %g", steps,
                   SIM_RUN_PLANT_STEPS_MAX);
        return;
    }
    /* RK4 is stable on a decay up to 2.8 time constants per step and loses
     * its accuracy well before: the plant's truth resolves its fastest part. */
    const double h = sc->control_dt_s / sc->plant_substeps;
    double tau = INFINITY;
    const char *what = NULL;
    const loc_t *cause = NULL; /* the key that sets the time constant */
    if (sc->motor_tau_s > 0.0) {
        tau = sc->motor_tau_s;
        what = "motor_tau_s";
        cause = checks_seen(p, SEC_ROTORS, "motor_tau_s");
    }
    for (int i = 0; i < 3; ++i) {
        if (sc->rot_drag_Nm_s > 0.0 && sc->inertia_kg_m2[i] / sc->rot_drag_Nm_s < tau) {
            tau = sc->inertia_kg_m2[i] / sc->rot_drag_Nm_s;
            what = "the drag time constant J / rot_drag_Nm_s";
            static const char *const vehicle[] = {"inertia_kg_m2", "rot_drag_Nm_s"};
            cause = first_given(p, SEC_VEHICLE, vehicle, 2);
        }
    }
    if (h > tau) {
        static const char *const run[] = {"plant_substeps", "control_dt_s"};
        const loc_t *at = first_given(p, SEC_RUN, run, 2);
        if (at == NULL) {
            at = cause != NULL ? cause : checks_seen(p, SEC_RUN, "duration_s");
        }
        const double needed = ceil(sc->control_dt_s / tau);
        char fix[64];
        if (needed <= SIM_PLANT_SUBSTEPS_MAX) {
            snprintf(fix, sizeof fix, "plant_substeps must be at least %.0f", needed);
        } else {
            snprintf(fix, sizeof fix, "more than %d plant_substeps would be needed", SIM_PLANT_SUBSTEPS_MAX);
        }
        check_fail(p, at->line, at->value_col,
                   "the plant step control_dt_s / plant_substeps (%g s) is longer than %s (%g s): %s", h, what, tau,
                   fix);
    }
}

static void check_run(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    if (isnan(sc->duration_s)) {
        return; /* missing, reported by check_kind */
    }
    if (!(sc->control_dt_s <= sc->duration_s)) {
        const loc_t *dt = checks_seen(p, SEC_RUN, "control_dt_s");
        const loc_t *at = dt->line != 0 ? dt : checks_seen(p, SEC_RUN, "duration_s");
        if (at->line != 0) {
            check_fail(p, at->line, at->value_col, "control_dt_s (%g) must not exceed duration_s (%g)",
                       sc->control_dt_s, sc->duration_s);
        }
    }
    check_run_size(p);
    /* [metrics] windows, and the error window of [differentiator] */
    static const int sections[] = {SEC_METRICS, SEC_METRICS, SEC_METRICS, SEC_DIFFERENTIATOR};
    static const char *const windows[] = {"error_window_s", "steady_window_s", "settle_window_s", "error_window_s"};
    const double ends[] = {sc->error_window_s[1], sc->steady_window_s[1], sc->settle_until_s, sc->error_window_s[1]};
    for (int i = 0; i < 4; ++i) {
        const loc_t *at = checks_seen(p, sections[i], windows[i]);
        if (at->line != 0 && ends[i] > sc->duration_s) {
            check_fail(p, at->line, at->value_col, "%s ends after the run (duration_s = %g)", windows[i],
                       sc->duration_s);
        }
    }
}

static void check_rotors(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *max = checks_seen(p, SEC_ROTORS, "w2_max_rad2_s2");
    if (sc->rotors_ideal) {
        /* the limits, and what needs a full thrust or an ESC command */
        const char *name[4] = {"w2_min_rad2_s2", "w2_max_rad2_s2", "thrust_curve", "mixer_thrust_curve"};
        for (int i = 0; i < 4; ++i) {
            const loc_t *at = checks_seen(p, SEC_ROTORS, name[i]);
            if (at->line != 0) {
                check_fail(p, at->line, at->key_col, "'%s' does not apply with ideal = yes", name[i]);
            }
        }
        const loc_t *throttle = checks_seen(p, SEC_REFERENCE, "throttle");
        if (throttle->line != 0) {
            check_fail(p, throttle->line, throttle->key_col, "'throttle' needs [rotors] ideal = no (a full thrust)");
        }
        return;
    }
    if (max->line == 0) {
        const loc_t *ideal = checks_seen(p, SEC_ROTORS, "ideal");
        check_fail(p, ideal->line, ideal->value_col, "ideal = no needs w2_max_rad2_s2");
    } else if (!(sc->w2_max_rad2_s2 > sc->w2_min_rad2_s2)) {
        check_fail(p, max->line, max->value_col, "w2_max_rad2_s2 must be > w2_min_rad2_s2 (%g)", sc->w2_min_rad2_s2);
    }
}

/* A list key's count against the orders it goes with: equal, or not given. */
static void check_list_length(parser_t *p, int sec, const char *name, int n, const char *of, int n_of)
{
    const loc_t *at = checks_seen(p, sec, name);
    if (at->line != 0 && n != n_of) {
        check_fail(p, at->line, at->value_col, "%s gives %d numbers; %s gives %d (one per order)", name, n, of, n_of);
    }
}

/* What the library's gyro filter still refuses once the ranges hold (a Q so
 * high that a notch rounds to an unstable section, a cut-off at the very
 * edge), at the key responsible. */
static void check_filter_init(parser_t *p)
{
    static const struct {
        ladrc_status_t status;
        const char *key;
    } keys[] = {{LADRC_ERR_GYRO_LPF_CUTOFF_HZ, "lpf_hz"},    {LADRC_ERR_GYRO_NOTCH_HZ, "notch_hz"},
                {LADRC_ERR_GYRO_NOTCH_Q, "notch_q"},         {LADRC_ERR_GYRO_RPM_MIN_HZ, "rpm_min_hz"},
                {LADRC_ERR_GYRO_RPM_FADE_HZ, "rpm_fade_hz"}, {LADRC_ERR_GYRO_RPM_Q, "rpm_q"}};
    const sim_scenario_t *sc = p->sc;
    if (!sim_setup_filters_gyro(sc)) {
        return;
    }
    ladrc_gyro_filter_config_t cfg;
    ladrc_gyro_filter_t f;
    sim_setup_gyro_filter(sc, &cfg);
    const ladrc_status_t st = ladrc_gyro_filter_init(&f, &cfg);
    if (st == LADRC_OK) {
        return;
    }
    const char *key = "rpm_harmonics";
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; ++i) {
        if (keys[i].status == st) {
            key = keys[i].key;
        }
    }
    const loc_t *at = checks_seen(p, SEC_FILTER, key);
    if (at->line == 0) { /* a default the file left: at the [filter] header */
        const int line = p->section_line[SEC_FILTER] != 0 ? p->section_line[SEC_FILTER] : 1;
        check_fail(p, line, 1, "the gyro filter refuses %s's default: %s", key, ladrc_status_str(st));
        return;
    }
    check_fail(p, at->line, at->value_col, "the gyro filter refuses it: %s", ladrc_status_str(st));
}

/* [wind], [vibration] and [filter] keys against each other and the run. */
static void check_environment(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *sigma = checks_seen(p, SEC_WIND, "sigma_m_s");
    if (sc->turbulence == SIM_TURB_SIGMA && !(sc->turb_sigma_m_s > 0.0)) {
        const loc_t *turb = checks_seen(p, SEC_WIND, "turbulence");
        check_fail(p, turb->line, turb->value_col, "turbulence = sigma needs sigma_m_s > 0");
    } else if (sc->turbulence != SIM_TURB_SIGMA && sigma->line != 0) {
        check_fail(p, sigma->line, sigma->key_col, "'sigma_m_s' applies only with turbulence = sigma");
    }
    const loc_t *orders = checks_seen(p, SEC_VIBRATION, "orders");
    if (orders->line == 0) {
        static const char *const amplitudes[] = {"gyro_deg_s", "accel_m_s2", "axis_gain"};
        const loc_t *at = first_given(p, SEC_VIBRATION, amplitudes, 3);
        if (at != NULL) {
            check_fail(p, at->line, at->key_col, "the vibration's amplitudes need its orders (orders = 1 2 3 ...)");
        }
    } else {
        check_list_length(p, SEC_VIBRATION, "gyro_deg_s", sc->vib_n_gyro, "orders", sc->vib_n_orders);
        check_list_length(p, SEC_VIBRATION, "accel_m_s2", sc->vib_n_accel, "orders", sc->vib_n_orders);
    }
    const double nyquist_hz = 0.5 / sc->control_dt_s;
    const loc_t *lpf = checks_seen(p, SEC_FILTER, "lpf_hz");
    if (sc->filter_lpf_order > 0 && !(sc->filter_lpf_hz < nyquist_hz)) {
        const loc_t *at = lpf->line != 0 ? lpf : checks_seen(p, SEC_FILTER, "lpf_order");
        check_fail(p, at->line, at->value_col, "lpf_hz must be below the Nyquist frequency 0.5 / control_dt_s (%g Hz)",
                   nyquist_hz);
    }
    /* A bilinear notch stops being one near Nyquist: the library's guard. */
    const double guard_hz = (double)LADRC_GYRO_FILTER_CENTRE_MAX_NYQUIST * nyquist_hz;
    for (int i = 0; i < sc->filter_n_notches; ++i) {
        if (!(sc->filter_notch_hz[i] < guard_hz)) {
            const loc_t *at = checks_seen(p, SEC_FILTER, "notch_hz");
            check_fail(p, at->line, at->value_col, "notch_hz %g must be below %g Hz (0.9 of the Nyquist frequency)",
                       sc->filter_notch_hz[i], guard_hz);
            break;
        }
    }
    const loc_t *rpm_min = checks_seen(p, SEC_FILTER, "rpm_min_hz");
    if (sc->filter_rpm_harmonics > 0 && !(sc->filter_rpm_min_hz < guard_hz)) {
        const loc_t *at = rpm_min->line != 0 ? rpm_min : checks_seen(p, SEC_FILTER, "rpm_harmonics");
        check_fail(p, at->line, at->value_col, "rpm_min_hz must be below %g Hz (0.9 of the Nyquist frequency)",
                   guard_hz);
    }
    check_filter_init(p);
}

/* The quaternion frame's keys against the others. */
static void check_frame(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *weight = checks_seen(p, SEC_REFERENCE, "yaw_weight");
    if (sc->frame != LADRC_FRAME_QUATERNION) {
        if (weight->line != 0) {
            check_fail(p, weight->line, weight->key_col, "'yaw_weight' applies only with frame = quaternion");
        }
        return;
    }
    const loc_t *angle = checks_seen(p, SEC_FILTER, "angle");
    if (sc->filter_angle && angle->line != 0) {
        check_fail(p, angle->line, angle->value_col,
                   "angle = yes needs [reference] frame = euler (the quaternion frame takes the attitude unfiltered)");
    }
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const loc_t *wrap = checks_seen(p, SEC_CONTROLLER + id, "wrap_yaw");
        if (sc->overrides[id].wrap_yaw == 0 && wrap->line != 0) {
            check_fail(p, wrap->line, wrap->value_col,
                       "wrap_yaw = no needs [reference] frame = euler (the quaternion frame wraps every axis)");
        }
    }
}

/* One list of [phases]: strictly increasing, before the run's end. */
static int check_event_list(parser_t *p, const char *key, const double *t_s, int n)
{
    const loc_t *at = checks_seen(p, SEC_PHASES, key);
    for (int i = 0; i < n; ++i) {
        if (i > 0 && !(t_s[i] > t_s[i - 1])) {
            check_fail(p, at->line, at->value_col, "%s must increase", key);
            return -1;
        }
        if (!(t_s[i] < p->sc->duration_s)) {
            check_fail(p, at->line, at->value_col, "%s %g is not before the run's end (duration_s %g)", key, t_s[i],
                       p->sc->duration_s);
            return -1;
        }
    }
    return 0;
}

/* The [phases] timeline: the four lists merged in time order into sc's
 * events, each event possible where it stands (arm and disarm on the
 * ground, take-off armed, land in the air). */
static void check_phases(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    static const char *const keys[4] = {"arm_s", "takeoff_s", "land_s", "disarm_s"}; /* by sim_event_t */
    const double *lists[4] = {sc->phase_arm_s, sc->phase_takeoff_s, sc->phase_land_s, sc->phase_disarm_s};
    const int counts[4] = {sc->phase_n_arm, sc->phase_n_takeoff, sc->phase_n_land, sc->phase_n_disarm};
    sc->n_events = 0;
    for (int k = 0; k < 4; ++k) {
        if (check_event_list(p, keys[k], lists[k], counts[k]) != 0) {
            return;
        }
    }
    if (sc->phase_n_takeoff == 0) {
        static const char *const ground_keys[] = {"arm_s",      "disarm_s",      "land_s",
                                                  "ground_deg", "ground_thrust", "landed_input"};
        const loc_t *at = first_given(p, SEC_PHASES, ground_keys, 6);
        if (at != NULL) {
            check_fail(p, at->line, at->key_col, "the ground phases need takeoff_s (the vehicle starts on the ground)");
        }
        return;
    }
    int next[4] = {0, 0, 0, 0};
    int armed = sc->phase_n_arm == 0, on_ground = 1;
    for (int e = 0; e < sc->phase_n_arm + sc->phase_n_takeoff + sc->phase_n_land + sc->phase_n_disarm; ++e) {
        int kind = -1;
        for (int k = 0; k < 4; ++k) { /* the earliest event left; a tie is an error below */
            if (next[k] < counts[k] && (kind < 0 || lists[k][next[k]] < lists[kind][next[kind]])) {
                kind = k;
            }
        }
        const double t = lists[kind][next[kind]];
        const loc_t *at = checks_seen(p, SEC_PHASES, keys[kind]);
        for (int k = 0; k < 4; ++k) {
            if (k != kind && next[k] < counts[k] && lists[k][next[k]] == t) {
                check_fail(p, at->line, at->value_col, "%s and %s both at %g s", keys[kind], keys[k], t);
                return;
            }
        }
        const char *why = NULL;
        switch (kind) {
        case SIM_EVENT_ARM:
            why = armed ? "while armed" : NULL;
            armed = 1;
            break;
        case SIM_EVENT_TAKEOFF:
            why = !armed ? "while disarmed" : (!on_ground ? "in the air" : NULL);
            on_ground = 0;
            break;
        case SIM_EVENT_LAND:
            why = on_ground ? "on the ground" : NULL;
            on_ground = 1;
            break;
        default:
            why = !armed ? "while disarmed" : (!on_ground ? "in the air (land first)" : NULL);
            armed = 0;
            break;
        }
        if (why != NULL) {
            check_fail(p, at->line, at->value_col, "%s %g %s", keys[kind], t, why);
            return;
        }
        sc->event_s[sc->n_events] = t;
        sc->event_kind[sc->n_events] = kind;
        ++sc->n_events;
        ++next[kind];
    }
}

/* [excitation]: f1 capped at 0.45 / control_dt_s unless given (then beyond
 * it is an error), f0 below f1, and the chirps within the run. */
static void check_excitation(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    sc->excite_on = p->section_line[SEC_EXCITATION] != 0;
    if (!sc->excite_on) {
        return;
    }
    const loc_t *amplitude = checks_seen(p, SEC_EXCITATION, "amplitude");
    if (amplitude->line != 0 && sc->excite_n_amplitudes != 1 && sc->excite_n_amplitudes != 3) {
        check_fail(p, amplitude->line, amplitude->value_col,
                   "amplitude gives %d numbers: one for every axis, or three (roll, pitch, yaw)",
                   sc->excite_n_amplitudes);
    }
    const double f_max_hz = 0.45 / sc->control_dt_s;
    const loc_t *f0 = checks_seen(p, SEC_EXCITATION, "f0_hz");
    const loc_t *f1 = checks_seen(p, SEC_EXCITATION, "f1_hz");
    if (f1->line == 0 && sc->excite_f1_hz > f_max_hz) {
        sc->excite_f1_hz = f_max_hz;
    }
    if (f1->line != 0 && sc->excite_f1_hz > f_max_hz) {
        check_fail(p, f1->line, f1->value_col, "f1_hz must be at most 0.45 / control_dt_s (%g Hz)", f_max_hz);
    } else if (!(sc->excite_f0_hz < sc->excite_f1_hz)) {
        const loc_t *at = f0->line != 0 ? f0 : f1;
        check_fail(p, at->line, at->value_col, "f0_hz (%g) must be below f1_hz (%g)", sc->excite_f0_hz,
                   sc->excite_f1_hz);
    }
    const double end_s = sim_excitation_end_s(sc);
    if (!isnan(sc->duration_s) && end_s > sc->duration_s) {
        static const char *const keys[] = {"duration_s", "start_s", "axis"};
        const loc_t *at = first_given(p, SEC_EXCITATION, keys, sim_excitation_axes(sc) > 1 ? 3 : 2);
        const int line = at != NULL ? at->line : p->section_line[SEC_EXCITATION];
        const int col = at != NULL ? at->value_col : 1;
        check_fail(p, line, col, "the %s at %g s, after the run's end (duration_s = %g)",
                   sim_excitation_axes(sc) > 1 ? "three chirps end" : "chirp ends", end_s, sc->duration_s);
    }
}

static void check_differentiator(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    const loc_t *h0 = checks_seen(p, SEC_DIFFERENTIATOR, "td_h0_s");
    if (h0->line != 0 && sc->diff_td_h0_s < sc->control_dt_s) {
        check_fail(p, h0->line, h0->value_col, "td_h0_s must be >= control_dt_s (%g)", sc->control_dt_s);
    }
}

/* The noise cap of controller id (tune = margins): an absolute cap or
 * another controller's noise, not both; the ratio only with the other
 * controller, which the scenario flies with tune = margins, is not id and
 * takes no other's noise itself (no chains, no cycles). */
static void check_noise_cap(parser_t *p, int id)
{
    const sim_scenario_t *sc = p->sc;
    const int sec = SEC_CONTROLLER + id;
    const loc_t *max = checks_seen(p, sec, "tune_noise_max_Nm");
    const loc_t *ref = checks_seen(p, sec, "tune_noise_ref");
    const loc_t *ratio = checks_seen(p, sec, "tune_noise_ratio");
    const loc_t *axis = checks_seen(p, sec, "tune_noise_axis_max_Nm");
    if (axis->line != 0 && (max->line != 0 || ref->line != 0)) {
        check_fail(p, axis->line, axis->key_col,
                   "'tune_noise_axis_max_Nm' conflicts with %s (line %d): give one of them",
                   max->line != 0 ? "tune_noise_max_Nm" : "tune_noise_ref", max->line != 0 ? max->line : ref->line);
        return;
    }
    if (ratio->line != 0 && ref->line == 0) {
        check_fail(p, ratio->line, ratio->key_col, "'tune_noise_ratio' applies only with tune_noise_ref");
    }
    if (ref->line == 0) {
        return;
    }
    if (max->line != 0) {
        check_fail(p, ref->line, ref->key_col,
                   "'tune_noise_ref' conflicts with tune_noise_max_Nm (line %d): give one of them", max->line);
        return;
    }
    const int other = sc->overrides[id].tune_noise_ref;
    const char *name = sim_controller_name((sim_controller_id_t)other);
    int listed = 0;
    for (int i = 0; i < sc->n_controllers; ++i) {
        listed |= (int)sc->controllers[i] == other;
    }
    if (other == id) {
        check_fail(p, ref->line, ref->value_col, "tune_noise_ref must name another controller, not %s itself", name);
    } else if (!listed) {
        check_fail(p, ref->line, ref->value_col, "tune_noise_ref: the scenario does not fly %s ([run] controllers)",
                   name);
    } else if (sc->overrides[other].tune != SIM_TUNE_MARGINS) {
        check_fail(p, ref->line, ref->value_col, "tune_noise_ref: %s is not tuned (its tune = margins is missing)",
                   name);
    } else if (sc->overrides[other].tune_noise_ref >= 0) {
        check_fail(p, ref->line, ref->value_col,
                   "tune_noise_ref: %s takes its own cap from another controller's noise; name one that does not",
                   name);
    }
}

/* The targets, objective steps and noise caps of tune = margins without it
 * are an error. Gains given beside tune = margins are not: they are one of
 * the tuning's candidates (tune.h). */
static void check_tuning(parser_t *p)
{
    static const char *const tune_only[] = {
        "tune_phase_margin_deg", "tune_gain_margin_db", "tune_step_deg",    "tune_disturbance_step_rad_s2",
        "tune_noise_max_Nm",     "tune_noise_ref",      "tune_noise_ratio", "tune_noise_axis_max_Nm"};
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const int sec = SEC_CONTROLLER + id;
        if (p->sc->overrides[id].tune == SIM_TUNE_MARGINS) {
            check_noise_cap(p, id);
            continue;
        }
        for (int g = 0; g < (int)(sizeof tune_only / sizeof tune_only[0]); ++g) {
            const loc_t *at = checks_seen(p, sec, tune_only[g]);
            if (at->line != 0) {
                check_fail(p, at->line, at->key_col, "'%s' applies only with tune = margins", tune_only[g]);
            }
        }
    }
}

/* RATE-ADRC's pilot keys without pilot = acro are an error: its own
 * attitude loop flies then, and nothing would read them. */
static void check_pilot(parser_t *p)
{
    static const char *const pilot_only[] = {"pilot_pulse", "pilot_att_kp_per_s", "pilot_rate_max_deg_s"};
    const int sec = SEC_CONTROLLER + SIM_CTRL_RATE_ADRC;
    if (p->sc->overrides[SIM_CTRL_RATE_ADRC].radrc_pilot == 1) {
        return;
    }
    for (int k = 0; k < (int)(sizeof pilot_only / sizeof pilot_only[0]); ++k) {
        const loc_t *at = checks_seen(p, sec, pilot_only[k]);
        if (at->line != 0) {
            check_fail(p, at->line, at->key_col, "'%s' applies only with pilot = acro", pilot_only[k]);
        }
    }
}

/* ---- what the library accepts ------------------------------------------------
 *
 * The controllers, the mixer and the differentiators are initialised once
 * here with the configurations the runner gives them (setup.h), so that a
 * scenario the library refuses is an error of the file, at the key that sets
 * the refused value, and not a failed run. */

typedef struct {
    int sec; /* SEC_*; -1: the controller's own [controller NAME] */
    const char *name;
} key_ref_t;

#define CTRL_SEC (-1)
/* clang-format off */
#define END_KEYS {.sec = 0, .name = NULL}
/* clang-format on */

/* The keys behind a refused value, most likely first (the first one the
 * file gives is reported). */
static const key_ref_t *keys_of_status(ladrc_status_t st, int known_freqs)
{
    static const key_ref_t dt[] = {{.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t inertia[] = {
        {.sec = SEC_VEHICLE, .name = "inertia_kg_m2"}, {.sec = SEC_MISMATCH, .name = "inertia_scale"}, END_KEYS};
    static const key_ref_t drag[] = {
        {.sec = SEC_VEHICLE, .name = "rot_drag_Nm_s"}, {.sec = SEC_MISMATCH, .name = "rot_drag_scale"}, END_KEYS};
    static const key_ref_t wc[] = {{.sec = CTRL_SEC, .name = "wc_rad_s"}, END_KEYS};
    static const key_ref_t wo[] = {{.sec = CTRL_SEC, .name = "wo_rad_s"}, END_KEYS};
    static const key_ref_t euler[] = {{.sec = CTRL_SEC, .name = "wo_rad_s"},
                                      {.sec = SEC_RUN, .name = "control_dt_s"},
                                      {.sec = CTRL_SEC, .name = "leso_method"},
                                      END_KEYS};
    static const key_ref_t td_accel[] = {{.sec = CTRL_SEC, .name = "td_accel_rad_s2"}, END_KEYS};
    static const key_ref_t levant[] = {
        {.sec = CTRL_SEC, .name = "levant_lipschitz_rad_s4"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t kp[] = {{.sec = CTRL_SEC, .name = "pid_kp"}, END_KEYS};
    static const key_ref_t ki[] = {{.sec = CTRL_SEC, .name = "pid_ki"}, END_KEYS};
    static const key_ref_t kd[] = {{.sec = CTRL_SEC, .name = "pid_kd"}, END_KEYS};
    static const key_ref_t indi_att[] = {
        {.sec = CTRL_SEC, .name = "indi_att_kp_per_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t indi_rate[] = {
        {.sec = CTRL_SEC, .name = "indi_rate_kp_per_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t indi_filter[] = {
        {.sec = CTRL_SEC, .name = "indi_filter_rad_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t radrc_kp[] = {
        {.sec = CTRL_SEC, .name = "radrc_kp_per_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t radrc_att[] = {
        {.sec = CTRL_SEC, .name = "radrc_att_kp_per_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t radrc_max[] = {{.sec = CTRL_SEC, .name = "radrc_rate_max_deg_s"}, END_KEYS};
    static const key_ref_t cas_att[] = {
        {.sec = CTRL_SEC, .name = "cas_att_kp"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    static const key_ref_t cas_max[] = {{.sec = CTRL_SEC, .name = "cas_rate_max_deg_s"}, END_KEYS};
    static const key_ref_t cas_kp[] = {{.sec = CTRL_SEC, .name = "cas_rate_kp"}, END_KEYS};
    static const key_ref_t cas_ki[] = {{.sec = CTRL_SEC, .name = "cas_rate_ki"}, END_KEYS};
    static const key_ref_t cas_kd[] = {{.sec = CTRL_SEC, .name = "cas_rate_kd"}, END_KEYS};
    static const key_ref_t cas_tau[] = {{.sec = CTRL_SEC, .name = "cas_d_filter_tau_s"}, END_KEYS};
    static const key_ref_t cas_i[] = {{.sec = CTRL_SEC, .name = "cas_i_limit_Nm"}, END_KEYS};
    static const key_ref_t freqs[] = {{.sec = CTRL_SEC, .name = "hp_freq_rad_s"},
                                      {.sec = CTRL_SEC, .name = "hp_freq2_rad_s"},
                                      {.sec = SEC_RUN, .name = "control_dt_s"},
                                      END_KEYS};
    static const key_ref_t range[] = {{.sec = CTRL_SEC, .name = "hp_freq_min_rad_s"},
                                      {.sec = CTRL_SEC, .name = "hp_freq_max_rad_s"},
                                      {.sec = SEC_RUN, .name = "control_dt_s"},
                                      END_KEYS};
    static const key_ref_t tones[] = {{.sec = CTRL_SEC, .name = "hp_tones"},
                                      {.sec = CTRL_SEC, .name = "hp_freq2_rad_s"},
                                      {.sec = CTRL_SEC, .name = "hp_freq_mode"},
                                      END_KEYS};
    static const key_ref_t mixer_kl[] = {{.sec = SEC_VEHICLE, .name = "thrust_coeff_N_s2"}, END_KEYS};
    static const key_ref_t mixer_arm[] = {{.sec = SEC_VEHICLE, .name = "arm_m"}, END_KEYS};
    static const key_ref_t mixer_b[] = {{.sec = SEC_VEHICLE, .name = "yaw_coeff_Nm_s2"}, END_KEYS};
    static const key_ref_t mixer_mass[] = {{.sec = SEC_VEHICLE, .name = "mass_kg"}, END_KEYS};
    static const key_ref_t mixer_g[] = {{.sec = SEC_VEHICLE, .name = "g_m_s2"}, END_KEYS};
    static const key_ref_t w2_min[] = {{.sec = SEC_ROTORS, .name = "w2_min_rad2_s2"}, END_KEYS};
    static const key_ref_t w2_max[] = {
        {.sec = SEC_ROTORS, .name = "w2_max_rad2_s2"}, {.sec = SEC_ROTORS, .name = "w2_min_rad2_s2"}, END_KEYS};
    static const key_ref_t tilt[] = {{.sec = SEC_ROTORS, .name = "tilt_max_deg"}, END_KEYS};
    static const key_ref_t motor_tau[] = {
        {.sec = CTRL_SEC, .name = "model_motor_tau_s"}, {.sec = SEC_ROTORS, .name = "motor_tau_s"}, END_KEYS};
    static const key_ref_t delay[] = {
        {.sec = CTRL_SEC, .name = "model_delay_ticks"}, {.sec = SEC_SENSORS, .name = "delay_ticks"}, END_KEYS};
    switch (st) {
    case LADRC_ERR_INERTIA_KG_M2:
    case LADRC_ERR_B0:
        return inertia;
    case LADRC_ERR_DRAG_NMS:
        return drag;
    case LADRC_ERR_WC_RAD_S:
        return wc;
    case LADRC_ERR_WO_RAD_S:
    case LADRC_ERR_HP_SAMPLE_LAG:
        return wo;
    case LADRC_ERR_LESO_EULER_UNSTABLE:
        return euler;
    case LADRC_ERR_TD_ACCEL_RAD_S2:
        return td_accel;
    case LADRC_ERR_LEVANT_LIPSCHITZ:
    case LADRC_ERR_LEVANT_RANGE:
        return levant;
    case LADRC_ERR_PID_KP:
        return kp;
    case LADRC_ERR_PID_KI:
        return ki;
    case LADRC_ERR_PID_KD:
        return kd;
    case LADRC_ERR_INDI_ATT_KP:
        return indi_att;
    case LADRC_ERR_INDI_RATE_KP:
        return indi_rate;
    case LADRC_ERR_INDI_FILTER:
        return indi_filter;
    case LADRC_ERR_RADRC_KP:
        return radrc_kp;
    case LADRC_ERR_RADRC_ATT_KP:
        return radrc_att;
    case LADRC_ERR_RADRC_RATE_MAX:
        return radrc_max;
    case LADRC_ERR_CAS_ATT_KP:
        return cas_att;
    case LADRC_ERR_CAS_RATE_MAX:
        return cas_max;
    case LADRC_ERR_CAS_RATE_KP:
        return cas_kp;
    case LADRC_ERR_CAS_RATE_KI:
        return cas_ki;
    case LADRC_ERR_CAS_RATE_KD:
        return cas_kd;
    case LADRC_ERR_CAS_D_TAU_S:
    case LADRC_ERR_CAS_RATE_TAU_S:
        return cas_tau;
    case LADRC_ERR_CAS_I_LIMIT_NM:
        return cas_i;
    case LADRC_ERR_HP_FREQ_RAD_S:
        return freqs;
    case LADRC_ERR_HP_FREQ_RANGE:
        return range;
    /* the fastest tone is a known frequency, or else the search range's top */
    case LADRC_ERR_HP_FIT_DECIMATION:
        return known_freqs ? freqs : range;
    case LADRC_ERR_HP_N_TONES:
        return tones;
    case LADRC_ERR_MIXER_KL_N_S2:
        return mixer_kl;
    case LADRC_ERR_MIXER_ARM_M:
        return mixer_arm;
    case LADRC_ERR_MIXER_B_NM_S2:
        return mixer_b;
    case LADRC_ERR_MIXER_MASS_KG:
        return mixer_mass;
    case LADRC_ERR_MIXER_G_M_S2:
        return mixer_g;
    case LADRC_ERR_MIXER_W2_MIN:
        return w2_min;
    case LADRC_ERR_MIXER_W2_MAX:
        return w2_max;
    case LADRC_ERR_MIXER_TILT_MAX_RAD:
        return tilt;
    case LADRC_ERR_MOTOR_TAU_S:
        return motor_tau;
    case LADRC_ERR_DELAY_TICKS:
        return delay;
    default:
        return dt; /* the rest depend on the period alone (and library constants) */
    }
}

static const key_ref_t *keys_of_differentiator_status(ladrc_status_t st)
{
    static const key_ref_t levant[] = {{.sec = SEC_DIFFERENTIATOR, .name = "levant_lipschitz_rad_s4"},
                                       {.sec = SEC_RUN, .name = "control_dt_s"},
                                       END_KEYS};
    static const key_ref_t td_accel[] = {{.sec = SEC_DIFFERENTIATOR, .name = "td_accel_rad_s2"}, END_KEYS};
    static const key_ref_t td_h0[] = {
        {.sec = SEC_DIFFERENTIATOR, .name = "td_h0_s"}, {.sec = SEC_RUN, .name = "control_dt_s"}, END_KEYS};
    switch (st) {
    case LADRC_ERR_LEVANT_LIPSCHITZ:
    case LADRC_ERR_LEVANT_RANGE:
        return levant;
    case LADRC_ERR_TD_ACCEL_RAD_S2:
        return td_accel;
    case LADRC_ERR_TD_H0_S:
        return td_h0;
    default:
        return keys_of_status(st, 0);
    }
}

/* The first key of keys the file gives (errors point at its value); else
 * the controller's section header (ctrl_sec >= 0), else line 1. */
static loc_t locate(const parser_t *p, const key_ref_t *keys, int ctrl_sec)
{
    for (const key_ref_t *k = keys; k->name != NULL; ++k) {
        const int sec = k->sec == CTRL_SEC ? ctrl_sec : k->sec;
        if (sec < 0) {
            continue;
        }
        const loc_t *at = checks_seen(p, sec, k->name);
        if (at->line != 0) {
            return *at;
        }
    }
    const loc_t header = {.line = ctrl_sec >= 0 && p->section_line[ctrl_sec] != 0 ? p->section_line[ctrl_sec] : 1,
                          .key_col = 1,
                          .value_col = 1};
    return header;
}

static void PRINTF_LIKE(4, 5) set_error(sim_parse_error_t *err, const char *path, loc_t at, const char *format, ...)
{
    memset(err, 0, sizeof *err);
    snprintf(err->path, sizeof err->path, "%s", path);
    va_list ap;
    va_start(ap, format);
    ini_vset_error(err, at.line, at.value_col, format, ap);
    va_end(ap);
}

/* Each controller on the scenario: an error for a listed one, kept in
 * controller_error for the others (sim_scenario_set_controllers). */
static void check_controllers(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        if (id == SIM_CTRL_BETAFLIGHT) {
            continue; /* not the library's: its SITL answers for itself when it flies */
        }
        ladrc_attitude_config_t cfg;
        ladrc_attitude_t att;
        sim_setup_attitude(sc, (sim_controller_id_t)id, &cfg);
        const ladrc_status_t st = ladrc_attitude_init(&att, &cfg, NULL);
        int listed = 0;
        for (int i = 0; i < sc->n_controllers; ++i) {
            listed |= (int)sc->controllers[i] == id;
        }
        /* HP-MLADRC on the gyro flies as LADRC without a rate: refused as the others */
        const int needs_rate = sim_controller_needs_rate((sim_controller_id_t)id) ||
                               (id == SIM_CTRL_HP_MLADRC && cfg.axis[0].hp_sample == LADRC_HP_SAMPLE_GYRO);
        if (st == LADRC_OK && needs_rate && !sc->use_rate) {
            static const key_ref_t use_rate[] = {{.sec = SEC_SENSORS, .name = "use_rate"}, END_KEYS};
            const loc_t at = locate(p, use_rate, -1);
            const char *needs = sim_controller_name((sim_controller_id_t)id);
            if (listed) {
                check_fail(p, at.line, at.value_col, "%s needs the measured rate ([sensors] use_rate = yes)", needs);
            } else {
                set_error(&sc->controller_error[id], sc->path, at,
                          "%s needs the measured rate ([sensors] use_rate = yes)", needs);
            }
            continue;
        }
        if (st == LADRC_OK) {
            continue;
        }
        const int known = cfg.axis[0].hp_freq_mode == LADRC_HP_FREQ_KNOWN;
        const char *name = sim_controller_name((sim_controller_id_t)id);
        const loc_t at = locate(p, keys_of_status(st, known), SEC_CONTROLLER + id);
        if (listed) {
            check_fail(p, at.line, at.value_col, "%s does not start: %s", name, ladrc_status_str(st));
        } else {
            set_error(&sc->controller_error[id], sc->path, at, "%s does not start: %s", name, ladrc_status_str(st));
        }
    }
    ladrc_mixer_config_t mix;
    ladrc_mixer_t mixer;
    sim_setup_mixer(sc, &mix);
    const ladrc_status_t st = ladrc_mixer_init(&mixer, &mix);
    if (st != LADRC_OK) {
        const loc_t at = locate(p, keys_of_status(st, 0), -1);
        check_fail(p, at.line, at.value_col, "the mixer does not start: %s", ladrc_status_str(st));
    }
}

static void check_differentiators(parser_t *p)
{
    ladrc_levant_config_t lcfg;
    ladrc_td_config_t tcfg;
    ladrc_levant_t lev;
    ladrc_td_t td;
    sim_setup_differentiators(p->sc, &lcfg, &tcfg);
    ladrc_status_t st = ladrc_levant_init(&lev, &lcfg);
    const char *which = "Levant's differentiator";
    if (st == LADRC_OK) {
        st = ladrc_td_init(&td, &tcfg);
        which = "the tracking differentiator";
    }
    if (st != LADRC_OK) {
        const loc_t at = locate(p, keys_of_differentiator_status(st), -1);
        check_fail(p, at.line, at.value_col, "%s does not start: %s", which, ladrc_status_str(st));
    }
}

void checks_finish(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    if (checks_seen(p, SEC_METRICS, "error_window_s")->line == 0 &&
        checks_seen(p, SEC_DIFFERENTIATOR, "error_window_s")->line == 0) {
        sc->error_window_s[0] = 0.0;
        sc->error_window_s[1] = sc->duration_s;
    }
    if (checks_seen(p, SEC_METRICS, "steady_window_s")->line == 0) {
        sc->steady_window_s[0] = 0.0;
        sc->steady_window_s[1] = sc->duration_s;
    }
    if (checks_seen(p, SEC_METRICS, "settle_window_s")->line == 0) {
        sc->settle_after_s = 0.0;
        sc->settle_until_s = sc->duration_s;
    }
    if (isnan(sc->rotor_drag_N_s_m)) { /* k_d w_hover 4 = m d: the drag d per kg at hover */
        const double w_hover = sqrt(sim_hover_w2_rad2_s2(sc->mass_kg, sc->g_m_s2, sc->thrust_coeff_N_s2));
        sc->rotor_drag_N_s_m = sc->mass_kg * sc->rotor_drag_per_s / (4.0 * w_hover);
    }
    if (isnan(sc->rotor_height_m)) {
        sc->rotor_height_m = SIM_ROTOR_HEIGHT_ARMS * sc->arm_m;
    }
    if (sc->kind == SIM_KIND_DIFFERENTIATOR) {
        sc->n_controllers = 0; /* it runs the two differentiators, no controller */
    }
    if (sc->output_dir[0] == '\0') {
        snprintf(sc->output_dir, sizeof sc->output_dir, "out/%s", sc->name);
    }
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const loc_t *tune = checks_seen(p, SEC_CONTROLLER + id, "tune");
        sc->tune_line[id] = tune->line;
        sc->tune_column[id] = tune->value_col;
    }
}

/* A series key's file: `given` as written, resolved against the scenario's
 * folder when relative, into out; 0, or -1 when it is too long. */
static int series_path(const sim_scenario_t *sc, const char *given, char *out, size_t len)
{
    size_t dir = 0;
    for (size_t i = 0; sc->path[i] != '\0'; ++i) {
        if (sc->path[i] == '/') {
            dir = i + 1;
        }
    }
    const int n =
        given[0] == '/' ? snprintf(out, len, "%s", given) : snprintf(out, len, "%.*s%s", (int)dir, sc->path, given);
    return (n >= 0 && (size_t)n < len) ? 0 : -1;
}

/* One series key: its file read as the runs will read it (errors at the
 * file's line and column), and long enough for the run when it refuses to
 * repeat or hold. The resolved path replaces the given one. */
static void check_one_series(parser_t *p, int sec, const char *name, char *path, sim_dim_t dim, int interp, int end)
{
    const loc_t *at = checks_seen(p, sec, name);
    if (at->line == 0 || p->checked) {
        return;
    }
    char resolved[SIM_PATH_LEN];
    if (series_path(p->sc, path, resolved, sizeof resolved) != 0) {
        check_fail(p, at->line, at->value_col, "%s: the path is longer than %d characters", name, SIM_PATH_LEN - 1);
        return;
    }
    const sim_series_spec_t spec = {
        .dim = dim, .key = name, .interp = (sim_series_interp_t)interp, .end = (sim_series_end_t)end};
    sim_series_t s;
    sim_series_error_t serr;
    if (sim_series_load(&s, resolved, &spec, &serr) != 0) {
        sim_parse_error_t *err = p->place.err;
        snprintf(err->path, sizeof err->path, "%s", serr.path);
        err->line = serr.line;
        err->column = serr.column;
        char msg[sizeof serr.message + SIM_PATH_LEN + 64];
        snprintf(msg, sizeof msg, "%s (the file of %s, %s line %d)", serr.message, name, p->sc->path, at->line);
        /* a long one is cut: its start says what is wrong */
        const size_t n = strlen(msg) < sizeof err->message ? strlen(msg) : sizeof err->message - 1;
        memcpy(err->message, msg, n);
        err->message[n] = '\0';
        p->checked = 1;
        return;
    }
    char why[256];
    if (!sim_series_covers(&s, p->sc->duration_s, resolved, why, sizeof why)) {
        check_fail(p, at->line, at->value_col, "%s; set series_end = repeat or hold to fly past it", why);
    }
    sim_series_free(&s);
    memcpy(path, resolved, sizeof resolved);
}

/* series_interp and series_end of a section that names no series. */
static void check_series_options(parser_t *p, int sec, const char *const *series, int n_series)
{
    static const char *const options[] = {"series_interp", "series_end"};
    const loc_t *opt = first_given(p, sec, options, 2);
    if (opt != NULL && first_given(p, sec, series, n_series) == NULL) {
        check_fail(p, opt->line, opt->key_col, "'%s' applies only with a series file",
                   checks_seen(p, sec, options[0])->line == opt->line ? options[0] : options[1]);
    }
}

/* The recorded series: read last, once the rest of the file is consistent. */
static void check_series(parser_t *p)
{
    sim_scenario_t *sc = p->sc;
    static const char *const dist[] = {"series"};
    static const char *const noise[] = {"rate_noise_series", "angle_noise_series"};
    check_series_options(p, SEC_DISTURBANCE, dist, 1);
    check_series_options(p, SEC_REFERENCE, dist, 1);
    check_series_options(p, SEC_SENSORS, noise, 2);
    check_one_series(p, SEC_DISTURBANCE, "series", sc->dist_series, SIM_DIM_ANG_ACCEL, sc->dist_series_interp,
                     sc->dist_series_end);
    check_one_series(p, SEC_REFERENCE, "series", sc->ref_series, SIM_DIM_ANGLE, sc->ref_series_interp,
                     sc->ref_series_end);
    check_one_series(p, SEC_SENSORS, "rate_noise_series", sc->rate_noise_series, SIM_DIM_ANG_RATE,
                     sc->noise_series_interp, sc->noise_series_end);
    check_one_series(p, SEC_SENSORS, "angle_noise_series", sc->angle_noise_series, SIM_DIM_ANGLE,
                     sc->noise_series_interp, sc->noise_series_end);
}

void checks_run(parser_t *p)
{
    const sim_scenario_t *sc = p->sc;
    check_kind(p);
    check_run(p);
    if (sc->kind == SIM_KIND_ATTITUDE) {
        check_rotors(p);
        check_environment(p);
        check_frame(p);
        check_phases(p);
        check_excitation(p);
        check_tuning(p);
        check_pilot(p);
    } else {
        check_differentiator(p);
    }
    /* the library's own checks, once the file is consistent */
    if (!p->checked) {
        if (sc->kind == SIM_KIND_ATTITUDE) {
            check_series(p);
            check_controllers(p);
        } else {
            check_differentiators(p);
        }
    }
}
