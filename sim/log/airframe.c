/* SPDX-License-Identifier: BSD-3-Clause */
/* The scenario of an identified airframe (airframe.h). */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include "airframe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "filter_proposal.h"
#include "plant/plant.h"
#include "scenario/setup.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)
#define SUBSTEPS_MIN 4

static const char *const AXIS[3] = {"roll", "pitch", "yaw"};

/* The controllers an identified airframe's scenario tunes and flies. */
static const sim_controller_id_t CONTROLLERS[] = {SIM_CTRL_HP_MLADRC, SIM_CTRL_LP_MLADRC, SIM_CTRL_LADRC,
                                                  SIM_CTRL_RATE_ADRC, SIM_CTRL_CASCADED,  SIM_CTRL_INDI};
#define N_CONTROLLERS ((int)(sizeof CONTROLLERS / sizeof CONTROLLERS[0]))

void sim_airframe_floor_band(double fs_hz, double *lo_hz, double *hi_hz)
{
    /* above the flight's own motion, below the anti-alias roll-off */
    *lo_hz = 0.2 * fs_hz / 2.0;
    *hi_hz = 0.9 * fs_hz / 2.0;
}

/* The nominal vehicle as a scenario, for the authority's one formula. */
static void nominal(sim_scenario_t *sc)
{
    memset(sc, 0, sizeof *sc);
    sc->mass_kg = SIM_AIRFRAME_MASS_KG;
    sc->arm_m = SIM_AIRFRAME_ARM_M;
    sc->thrust_coeff_N_s2 = SIM_AIRFRAME_THRUST_COEFF_N_S2;
    sc->yaw_coeff_Nm_s2 = 1.0; /* yaw's authority is linear in it: sim_airframe_yaw_coeff scales it */
    sc->g_m_s2 = SIM_AIRFRAME_G_M_S2;
}

double sim_airframe_inertia(int axis, double b0)
{
    static sim_scenario_t sc; /* large; only its vehicle fields are read */
    nominal(&sc);
    return b0 > 0.0 ? sim_setup_authority_Nm(&sc, axis) / b0 : NAN;
}

double sim_airframe_yaw_coeff(double b0_yaw, double inertia_yaw)
{
    static sim_scenario_t sc; /* large; only its vehicle fields are read */
    nominal(&sc);
    return b0_yaw * inertia_yaw / sim_setup_authority_Nm(&sc, 2);
}

/* The axis's own b0 for the scenario: told, else the interval's upper end. */
static double own_b0(const sim_ident_axis_t *x)
{
    if (sim_ident_b0_told(x)) {
        return x->b0;
    }
    return isfinite(x->b0_hi) && x->b0_hi > 0.0 ? fmax(x->b0_hi, x->b0) : NAN;
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The median of the axes' values that are told (finite and >= 0), or
 * `otherwise` when none is: an axis with too few samples has none. */
static double median_told(const double v[3], double otherwise)
{
    double told[3];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        if (isfinite(v[i]) && v[i] >= 0.0) {
            told[n++] = v[i];
        }
    }
    qsort(told, (size_t)n, sizeof told[0], cmp_double);
    return n == 0 ? otherwise : n == 2 ? 0.5 * (told[0] + told[1]) : told[n / 2];
}

/* The paper's vehicle's b0 on an axis (sim_vehicle_paper): the library's default airframe. */
static double paper_b0(int axis)
{
    static sim_scenario_t sc; /* large; only its vehicle fields are read */
    sim_vehicle_t v;
    sim_vehicle_paper(&v);
    memset(&sc, 0, sizeof sc);
    sc.mass_kg = v.mass_kg;
    sc.arm_m = v.arm_m;
    sc.thrust_coeff_N_s2 = v.thrust_coeff_N_s2;
    sc.yaw_coeff_Nm_s2 = v.yaw_coeff_Nm_s2;
    sc.g_m_s2 = v.g_m_s2;
    return sim_setup_authority_Nm(&sc, axis) / v.inertia_kg_m2[axis];
}

double sim_airframe_b0(const sim_airframe_t *a, int axis, sim_airframe_b0_source_t *source)
{
    const int partner = axis == 0 ? 1 : axis == 1 ? 0 : -1; /* roll and pitch: alike on a multirotor */
    const double own = own_b0(&a->axis[axis]);
    if (isfinite(own)) {
        *source = sim_ident_b0_told(&a->axis[axis]) ? SIM_AIRFRAME_B0_IDENTIFIED : SIM_AIRFRAME_B0_INTERVAL_HI;
        return own;
    }
    if (partner >= 0 && isfinite(own_b0(&a->axis[partner]))) {
        *source = SIM_AIRFRAME_B0_OTHER_AXIS;
        return own_b0(&a->axis[partner]);
    }
    *source = SIM_AIRFRAME_B0_DEFAULT;
    return paper_b0(axis);
}

int sim_airframe_b0_note(const sim_airframe_t *a, int axis, char *buf, size_t len)
{
    sim_airframe_b0_source_t source;
    const double b0 = sim_airframe_b0(a, axis, &source);
    const char *why = a->axis[axis].b0 < 0.0       ? "came out negative (check the axis's sign: --map ...*-1)"
                      : isfinite(a->axis[axis].b0) ? "is not told (see the identification's warnings)"
                                                   : "is not told (too few samples: a short log, or no excitation)";
    switch (source) {
    case SIM_AIRFRAME_B0_IDENTIFIED:
        buf[0] = '\0';
        return 0;
    case SIM_AIRFRAME_B0_INTERVAL_HI:
        snprintf(buf, len,
                 "%s: b0 %s: the scenario takes its interval's upper end, %.4g rad/s^2 (the larger b0, the gentler "
                 "the gains)",
                 AXIS[axis], why, b0);
        break;
    case SIM_AIRFRAME_B0_OTHER_AXIS:
        snprintf(buf, len, "%s: b0 %s: the scenario takes %s's, %.4g rad/s^2", AXIS[axis], why, AXIS[axis ^ 1], b0);
        break;
    default:
        snprintf(buf, len, "%s: b0 %s: the scenario takes the library's default airframe's, %.4g rad/s^2", AXIS[axis],
                 why, b0);
        break;
    }
    return 1;
}

/* The scenario's inertias: roll's and pitch's their authority over b0, yaw's a share of their sum. */
static void inertias(const sim_airframe_t *a, double J[3])
{
    for (int i = 0; i < 3; ++i) {
        sim_airframe_b0_source_t from;
        const double b0 = sim_airframe_b0(a, i, &from);
        J[i] = i < 2 ? sim_airframe_inertia(i, b0) : SIM_AIRFRAME_YAW_INERTIA_SHARE * (J[0] + J[1]);
    }
    /* a rigid body: each inertia at most the sum of the other two. Roll's and
     * pitch's b0 far apart (a weakly told axis) would break it; yaw's
     * inertia then grows to their difference, its b0 kept through its torque
     * coefficient (sim_airframe_yaw_coeff) */
    J[2] = fmax(J[2], fabs(J[0] - J[1]));
}

double sim_airframe_torque_per_command_Nm(const sim_airframe_t *a, int axis)
{
    double J[3];
    inertias(a, J);
    sim_airframe_b0_source_t from;
    return J[axis] * sim_airframe_b0(a, axis, &from);
}

/* One controller's section; the LADRC family's carries the logged controller's noise as its cap. */
static void write_controller(FILE *f, const sim_airframe_t *a, const char *name, int family, const char *extra)
{
    fprintf(f, "[controller %s]\ntune = margins\n%s", name, extra);
    if (family && a->log_cmd_noise[0] > 0.0 && a->log_cmd_noise[1] > 0.0 && a->log_cmd_noise[2] > 0.0) {
        fprintf(f, "tune_noise_axis_max_Nm =");
        for (int i = 0; i < 3; ++i) {
            fprintf(f, " %.6g", a->log_cmd_noise[i] * sim_airframe_torque_per_command_Nm(a, i));
        }
        fputc('\n', f);
    }
    fputc('\n', f);
}

/* The scenario's text, flying the listed controllers. */
static void write_text(FILE *f, const sim_airframe_t *a, const char *source, const char *noise_series,
                       const sim_controller_id_t *ids, int n_ids, const sim_airframe_refused_t *refused)
{
    double J[3], drag[3], b0[3], lag[3], delays[3];
    inertias(a, J);
    for (int i = 0; i < 3; ++i) {
        sim_airframe_b0_source_t from;
        b0[i] = sim_airframe_b0(a, i, &from);
        drag[i] = isfinite(a->axis[i].damping_per_s) ? fmax(a->axis[i].damping_per_s, 0.0) * J[i] : NAN;
        lag[i] = a->axis[i].lag_s;
        delays[i] = a->axis[i].delay_ticks;
    }
    const double kt = median_told(drag, 0.0);
    const double tau = median_told(lag, 0.0);
    const int delay = (int)median_told(delays, 0.0);
    const double fs = 1.0 / a->dt_s;
    const double w2_hover = SIM_AIRFRAME_MASS_KG * SIM_AIRFRAME_G_M_S2 / (4.0 * SIM_AIRFRAME_THRUST_COEFF_N_S2);
    /* the plant step within the shortest time constant: the lag, and each J / kt */
    double shortest = tau > 0.0 ? tau : a->dt_s;
    for (int i = 0; i < 3 && kt > 0.0; ++i) {
        shortest = fmin(shortest, J[i] / kt);
    }
    int substeps = (int)ceil(2.0 * a->dt_s / shortest);
    substeps = substeps < SUBSTEPS_MIN ? SUBSTEPS_MIN : substeps;
    double white_deg_s = 0.0;
    for (int i = 0; i < 3; ++i) {
        white_deg_s = fmax(white_deg_s, a->noise_floor_rad_s_rthz[i] * sqrt(fs / 2.0) * RAD2DEG);
    }

    fprintf(f, "# Airframe identified from the flight log %s (docs/flight-logs.md).\n", source);
    fprintf(f, "# Per axis: b0 per unit of normalised command [95 %% interval], motor lag, delay, R^2.\n");
    for (int i = 0; i < 3; ++i) {
        const sim_ident_axis_t *x = &a->axis[i];
        fprintf(
            f, "#   %-5s b0 %.4g [%.4g, %.4g] rad/s^2, lag %.1f [%.1f, %.1f] ms, delay %d [%d, %d] ticks, R^2 %.3f%s\n",
            AXIS[i], x->b0, x->b0_lo, x->b0_hi, 1e3 * x->lag_s, 1e3 * x->lag_lo_s, 1e3 * x->lag_hi_s, x->delay_ticks,
            x->delay_lo_ticks, x->delay_hi_ticks, x->r2,
            x->warnings ? "  (weak: see the identification's warnings)" : "");
        char note[256];
        if (sim_airframe_b0_note(a, i, note, sizeof note)) {
            fprintf(f, "#   %s\n", note);
        }
    }
    static const char *const FROM[] = {"identified", "not told: its interval's upper end",
                                       "not told: the other tilt axis's", "not told: the default airframe's"};
    for (int i = 0; i < 3; ++i) {
        sim_airframe_b0_source_t from;
        (void)sim_airframe_b0(a, i, &from);
        fprintf(f, "#   %-5s b0 flown %.4g rad/s^2 (%s)\n", AXIS[i], b0[i], FROM[from]);
    }
    fprintf(f,
            "# The vehicle is nominal (%.3g kg, arm %.3g m, thrust to weight 2): a command of 1 is its\n"
            "# torque authority; roll's and pitch's inertia are that authority over their b0, yaw's\n"
            "# inertia is 0.9 (Jx + Jy) and its torque coefficient gives it yaw's b0.\n\n",
            SIM_AIRFRAME_MASS_KG, SIM_AIRFRAME_ARM_M);
    fprintf(f, "[run]\nduration_s = 30\ncontrol_dt_s = %.9g\nplant_substeps = %d\nseed = 1\n", a->dt_s, substeps);
    fprintf(f, "controllers =");
    for (int c = 0; c < n_ids; ++c) {
        fprintf(f, " %s", sim_controller_name(ids[c]));
    }
    fputs("\n", f);
    for (int c = 0; refused != NULL && c < refused->n; ++c) {
        fprintf(f, "# not listed: %s\n", refused->reason[c]);
    }
    fputs("\n", f);
    fprintf(f, "[vehicle]\nmass_kg = %.9g\ninertia_kg_m2 = %.9g %.9g %.9g\narm_m = %.9g\n", SIM_AIRFRAME_MASS_KG, J[0],
            J[1], J[2], SIM_AIRFRAME_ARM_M);
    fprintf(f, "thrust_coeff_N_s2 = %.9g\nyaw_coeff_Nm_s2 = %.9g\nrot_drag_Nm_s = %.9g\ng_m_s2 = %.9g\n\n",
            SIM_AIRFRAME_THRUST_COEFF_N_S2, sim_airframe_yaw_coeff(b0[2], J[2]), kt, SIM_AIRFRAME_G_M_S2);
    fprintf(f, "[rotors]\nideal = no\nw2_min_rad2_s2 = %.9g\nw2_max_rad2_s2 = %.9g\nmotor_tau_s = %.9g\n\n",
            0.05 * w2_hover, 2.0 * w2_hover, tau);
    fprintf(f, "[sensors]\nangle_noise_std_deg = 0.05\ndelay_ticks = %d\nuse_rate = yes\n", delay);
    if (noise_series != NULL) {
        double corner_hz, top_hz;
        sim_airframe_floor_band(fs, &corner_hz, &top_hz);
        double below_deg_s = 0.0; /* the white floor below the series' high-pass corner */
        for (int i = 0; i < 3; ++i) {
            below_deg_s = fmax(below_deg_s, a->noise_floor_rad_s_rthz[i] * sqrt(corner_hz) * RAD2DEG);
        }
        fprintf(f,
                "# the log's own gyro noise above %.4g Hz, vibration lines included, looped; below it\n"
                "# the white floor\n",
                corner_hz);
        fprintf(f, "rate_noise_std_deg_s = %.6g\nrate_noise_series = %s\nseries_end = repeat\n\n", below_deg_s,
                noise_series);
    } else {
        fprintf(f, "# the log's white floor over the band it was measured in\n");
        fprintf(f, "rate_noise_std_deg_s = %.6g\n\n", white_deg_s);
    }
    if (a->has_filter) {
        fprintf(f,
                "# the gyro filter stage proposed from the log's spectrum before its filters: notches at\n"
                "# its vibration lines, a low-pass within %.0f deg of phase at the crossover\n",
                SIM_FILTER_PHASE_BUDGET_DEG);
        sim_filter_write_ini(f, &a->filter);
    }
    fprintf(f, "[reference]                     # degrees: steps both ways on each axis\n");
    fprintf(f, "roll = 1 .. 7 : 10\nroll = 13 .. 19 : -10\npitch = 7 .. 13 : 10\npitch = 19 .. 25 : -10\n");
    fprintf(f, "yaw = 4 .. 16 : 20\n\n");
    fprintf(f, "[disturbance]                   # rad/s^2: a step, then a 3 rad/s tone, at 15 %% of b0\n");
    for (int i = 0; i < 3; ++i) {
        const double d = 0.15 * b0[i];
        fprintf(f, "%s = 2 .. 8 : %.6g\n%s = 14 .. 26 : %.6g*sin(3*t)\n", AXIS[i], d, AXIS[i], d);
    }
    if (a->log_cmd_noise[0] > 0.0) {
        fprintf(f,
                "\n# the LADRC family's command noise above 20 Hz capped at the logged controller's: %.4g %.4g %.4g\n"
                "# of the authority (roll pitch yaw), in N m\n",
                a->log_cmd_noise[0], a->log_cmd_noise[1], a->log_cmd_noise[2]);
    }
    fputc('\n', f);
    write_controller(f, a, "HP-MLADRC", 1, "hp_sample = gyro\n");
    write_controller(f, a, "LP-MLADRC", 1, "");
    write_controller(f, a, "LADRC", 1, "");
    write_controller(f, a, "RATE-ADRC", 1, "");
    write_controller(f, a, "CASCADED", 0, "");
    write_controller(f, a, "INDI", 0, "");
    fprintf(f, "[metrics]\nerror_window_s = 0 30\nsteady_window_s = 20 25\nsettle_band_deg = 0.5\nsettle_window_s = 1 "
               "3\n");
}

/* 0 when controller id starts on the airframe (its scenario, without the
 * noise file, parses with it listed), else -1 with the parser's reason. */
static int controller_starts(const sim_airframe_t *a, sim_controller_id_t id, char *why, size_t why_len)
{
    static sim_scenario_t probe; /* large */
    char *text = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&text, &len);
    if (mem == NULL) {
        snprintf(why, why_len, "%s: out of memory", sim_controller_name(id));
        return -1;
    }
    write_text(mem, a, "probe", NULL, &id, 1, NULL);
    const int written = fclose(mem) == 0;
    sim_parse_error_t err;
    const int rc = written && sim_scenario_parse(&probe, text, "airframe.ini", &err) == 0 ? 0 : -1;
    free(text);
    if (rc != 0) {
        char rate[48];
        snprintf(rate, sizeof rate, " (at the log's %.4g Hz)", 1.0 / a->dt_s);
        const char *msg = written ? err.message : "out of memory";
        const size_t room = why_len > strlen(rate) ? why_len - strlen(rate) - 1 : 0;
        const size_t n = strlen(msg) < room ? strlen(msg) : room; /* cut so that the rate is always said */
        memcpy(why, msg, n);
        why[n] = '\0';
        strncat(why, rate, why_len - n - 1);
    }
    return rc;
}

int sim_airframe_write(FILE *f, const sim_airframe_t *a, const char *source, const char *noise_series,
                       sim_airframe_refused_t *refused, char *why, size_t why_len)
{
    if (!(a->dt_s >= SIM_CONTROL_DT_MIN_S && a->dt_s <= SIM_CONTROL_DT_MAX_S)) {
        snprintf(why, why_len, "a control period of %g s: a scenario's is %g to %g s (--dt resamples the log)", a->dt_s,
                 SIM_CONTROL_DT_MIN_S, SIM_CONTROL_DT_MAX_S);
        return -1;
    }
    sim_controller_id_t ids[N_CONTROLLERS];
    int n = 0;
    sim_airframe_refused_t none;
    refused = refused != NULL ? refused : &none;
    refused->n = 0;
    for (int c = 0; c < N_CONTROLLERS; ++c) {
        if (controller_starts(a, CONTROLLERS[c], refused->reason[refused->n], sizeof refused->reason[0]) == 0) {
            ids[n++] = CONTROLLERS[c];
        } else {
            refused->ids[refused->n++] = CONTROLLERS[c];
        }
    }
    if (n == 0) {
        snprintf(why, why_len, "no controller starts on it: %s", refused->reason[0]);
        return -1;
    }
    write_text(f, a, source, noise_series, ids, n, refused);
    if (ferror(f)) {
        snprintf(why, why_len, "write failed");
        return -1;
    }
    return 0;
}
