/* SPDX-License-Identifier: BSD-3-Clause */
/* Tables 3-7 on stdout and the metrics summary (see report.h). */
#include "report.h"

#include <math.h>

#include "run/runner.h"
#include "run/tune.h"
#include "scenario/signals.h"
#include "scenario/setup.h"

static const char *const AXES[3] = {"roll", "pitch", "yaw"};

/* The axis a divergence was seen on: an attitude axis, or "-" (a rotor). */
static const char *diverged_axis_name(const sim_metrics_t *m)
{
    return (m->diverged_axis >= 0 && m->diverged_axis < 3) ? AXES[m->diverged_axis] : "-";
}

void sim_report_divergence_text(char *buf, size_t len, const sim_scenario_t *sc, const sim_metrics_t *m)
{
    if (!m->diverged) {
        snprintf(buf, len, "did not diverge");
    } else if (isnan(m->diverged_error_deg)) {
        snprintf(buf, len, "diverged at t = %.4f s: the state turned non-finite (%s%s)", m->diverged_at_s,
                 m->diverged_axis >= 0 ? diverged_axis_name(m) : "a rotor's w^2",
                 m->diverged_axis >= 0 ? " angle or rate" : "");
    } else {
        snprintf(buf, len, "diverged at t = %.4f s on %s: |tracking error| %.6g deg exceeds diverge_limit_deg = %g",
                 m->diverged_at_s, diverged_axis_name(m), m->diverged_error_deg, sc->diverge_limit_deg);
    }
}

double sim_report_reference_accel(const sim_scenario_t *sc, int axis, double until_s)
{
    const double h = SIM_REFERENCE_ACCEL_STEP_S;
    double peak = 0.0;
    double r0 = sim_signal_eval(&sc->reference[axis], 0.0);
    double r1 = sim_signal_eval(&sc->reference[axis], h);
    for (double t = 2.0 * h; t <= until_s + h; t += h) {
        const double r2 = sim_signal_eval(&sc->reference[axis], t);
        peak = fmax(peak, fabs(r2 - 2.0 * r1 + r0) / (h * h)); /* the signals are in rad */
        r0 = r1;
        r1 = r2;
    }
    return peak;
}

void sim_report_outran_text(char *buf, size_t len, const sim_scenario_t *sc, const sim_metrics_t *m, int axis)
{
    const double asked = sim_report_reference_accel(sc, axis, m->reference_outran_at_s[axis]);
    const double given = sim_setup_authority_Nm(sc, axis) / sc->inertia_kg_m2[axis];
    snprintf(buf, len,
             "the reference outran the controller's shaper on %s from t = %.4f s (|tracking error| up to %.4g deg, "
             "the controller within %g deg of its shaped reference): it asks up to %.4g rad/s^2 where the rotors "
             "give %.4g about hover: %s",
             AXES[axis], m->reference_outran_at_s[axis], m->reference_outran_deg[axis],
             SIM_SHAPED_TRACKING_SHARE * sc->diverge_limit_deg, asked, given,
             asked > given ? "reference beyond authority"
                           : "the shaper's bound holds it back (td_accel_rad_s2, levant_lipschitz_rad_s4)");
}

/* What a table prints in place of a run's statistics: "diverged",
 * "untunable", or NULL when they are the run's. */
static const char *withheld(const sim_metrics_t *m)
{
    return m->untunable ? SIM_TEXT_UNTUNABLE : m->diverged ? SIM_TEXT_DIVERGED : NULL;
}

/* The first column's title, then one column per controller. */
static void column_titles(FILE *out, const sim_scenario_t *sc, const char *first, int width)
{
    fprintf(out, "%-6s", first);
    for (int c = 0; c < sc->n_controllers; ++c) {
        fprintf(out, " | %-*s", width, sim_controller_name(sc->controllers[c]));
    }
    fputc('\n', out);
}

static void table4(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out, "\nTable 4. Tracking error, deg: mean / std / RMS over (%g, %g] s\n", sc->error_window_s[0],
            sc->error_window_s[1]);
    column_titles(out, sc, "axis", 28);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "%-6s", AXES[i]);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_stat_t *s = &r->attitude[c].error_deg[i];
            if (withheld(&r->attitude[c]) != NULL) {
                fprintf(out, " | %-28s", withheld(&r->attitude[c]));
                continue;
            }
            fprintf(out, " | %8.4f / %8.4f / %8.4f", s->mean, sim_stat_std(s), sim_stat_rms(s));
        }
        fputc('\n', out);
    }
}

static void table5(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out,
            "\nTable 5. Max error (deg) over (%g, %g] s / settling time (s): from %g s until |error| stays "
            "within %g deg up to %g s (" SIM_TEXT_NOT_SETTLED ": outside it at %g s) / steady band (+-deg) over "
            "(%g, %g] s\n",
            sc->error_window_s[0], sc->error_window_s[1], sc->settle_after_s, sc->settle_band_deg, sc->settle_until_s,
            sc->settle_until_s, sc->steady_window_s[0], sc->steady_window_s[1]);
    column_titles(out, sc, "axis", 33);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "%-6s", AXES[i]);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_metrics_t *m = &r->attitude[c];
            if (withheld(m) != NULL) {
                fprintf(out, " | %-33s", withheld(m));
                continue;
            }
            char settle[32];
            if (m->settle_s[i] == SIM_NOT_SETTLED) {
                snprintf(settle, sizeof settle, "%s", SIM_TEXT_NOT_SETTLED);
            } else {
                snprintf(settle, sizeof settle, "%11.3f", m->settle_s[i]);
            }
            fprintf(out, " | %8.4f / %11s / %8.4f", m->max_error_deg[i], settle, m->band_deg[i]);
        }
        fputc('\n', out);
    }
}

static void table6(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out,
            "\nTable 6. Disturbance estimate error (z3 + d_hat - true total disturbance), rad/s^2: "
            "mean / std / RMS over (%g, %g] s\n",
            sc->error_window_s[0], sc->error_window_s[1]);
    column_titles(out, sc, "axis", 28);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "%-6s", AXES[i]);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_metrics_t *m = &r->attitude[c];
            if (withheld(m) != NULL) {
                fprintf(out, " | %-28s", withheld(m));
                continue;
            }
            if (!m->has_estimate) {
                fprintf(out, " | %-28s", "(no estimate)");
                continue;
            }
            const sim_stat_t *s = &m->dist_error[i];
            fprintf(out, " | %8.3f / %8.3f / %8.3f", s->mean, sim_stat_std(s), sim_stat_rms(s));
        }
        fputc('\n', out);
    }
}

static void table7(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out, "\nTable 7. Rotor speed squared, rad^2/s^2: mean / std / variance over the run\n");
    column_titles(out, sc, "rotor", 32);
    for (int k = 0; k < 4; ++k) {
        fprintf(out, "%-6d", k + 1);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_stat_t *s = &r->attitude[c].rotor_w2[k];
            if (withheld(&r->attitude[c]) != NULL) {
                fprintf(out, " | %-32s", withheld(&r->attitude[c]));
                continue;
            }
            const double sd = sim_stat_std(s);
            fprintf(out, " | %9.0f / %9.0f / %10.4g", s->mean, sd, sd * sd);
        }
        fputc('\n', out);
    }
}

static void table3(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out,
            "\nTable 3. Derivative of the noisy signal (noise variance %g), error over (%g, %g] s: "
            "mean / std / RMS\n",
            sc->diff_noise_var, sc->error_window_s[0], sc->error_window_s[1]);
    const sim_stat_t *s[2] = {&r->diff->td_error, &r->diff->levant_error};
    const char *names[2] = {"TD", "Levant"};
    for (int k = 0; k < 2; ++k) {
        fprintf(out, "%-8s %10.5f / %10.5f / %10.5f\n", names[k], s[k]->mean, sim_stat_std(s[k]), sim_stat_rms(s[k]));
    }
}

void sim_report_tuning(FILE *out, const sim_scenario_t *sc)
{
    static const char *const FROM[] = {[SIM_TUNED_MARGINS] = "",
                                       [SIM_TUNED_DEFAULTS] = " (the library's defaults)",
                                       [SIM_TUNED_SCENARIO] = " (the file's gains)"};
    for (int c = 0; c < sc->n_controllers; ++c) {
        const sim_controller_id_t id = sc->controllers[c];
        const sim_tuning_t *t = &sc->tuning[id];
        if (t->by == SIM_TUNED_UNTUNABLE) {
            fprintf(out, "untunable %s: not flown: %s\n", sim_controller_name(id), t->reason);
            continue;
        }
        if (!t->tuned) {
            continue;
        }
        for (int i = 0; i < 3; ++i) {
            char gains[256];
            (void)sim_setup_format_gains(&t->gains[i], gains, sizeof gains);
            fprintf(out, "tuned %s %s: %s%s", sim_controller_name(id), AXES[i], gains, FROM[t->by]);
            char cap[48] = "";
            if (t->cmd_noise_cap_Nm[i] > 0.0) {
                snprintf(cap, sizeof cap, " (<= %.3g)", t->cmd_noise_cap_Nm[i]);
            }
            fprintf(out,
                    " -> PM %.1f deg (>= %g), GM %.1f dB / %.1f dB (>= %g), crossover %.1f rad/s, Ms %.2f,"
                    " step cost %.3g rad^2 s, command noise %.3g N m%s above 20 Hz%s%s\n",
                    t->pm_deg[i], t->pm_target_deg, t->gm_db[i], t->gm_low_db[i], t->gm_target_db,
                    t->crossover_rad_s[i], t->ms[i], t->step_cost_rad2_s[i], t->cmd_noise_Nm[i], cap,
                    t->idle[i] ? " (estimator idle)" : "", t->shared[i] ? " (= roll)" : "");
        }
        if (t->reason[0] != '\0') {
            fprintf(out, "tuning of %s: %s\n", sim_controller_name(id), t->reason);
        }
    }
}

/* The gains a CASCADED run flies, per axis (defaults and overrides). */
static void cascaded_gains(FILE *out, const sim_scenario_t *sc)
{
    ladrc_attitude_config_t cfg;
    sim_setup_attitude(sc, SIM_CTRL_CASCADED, &cfg);
    fprintf(out, "CASCADED gains: att_kp 1/s, rate max deg/s, rate kp N m s/rad, ki N m/rad, kd N m s^2/rad, "
                 "D filter s, i_limit N m\n");
    for (int i = 0; i < 3; ++i) {
        const ladrc_axis_config_t *a = &cfg.axis[i];
        fprintf(out, "  %-5s att_kp %.4g  rate_max %.4g  kp %.4g  ki %.4g  kd %.4g  tau_d %.4g  i_limit %.4g\n",
                AXES[i], (double)a->cas_att_kp, (double)a->cas_rate_max_rad_s * (180.0 / 3.14159265358979323846),
                (double)a->cas_rate_kp, (double)a->cas_rate_ki, (double)a->cas_rate_kd, (double)a->cas_d_filter_tau_s,
                (double)a->cas_i_limit_Nm);
    }
}

void sim_report_tables(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    if (r->diff != NULL) {
        fprintf(out, "\n== %s (%s): %g s, step %g ms\n", sc->name, sc->path, sc->duration_s, sc->control_dt_s * 1e3);
        table3(out, r);
        return;
    }
    fprintf(out, "\n== %s (%s): %g s, control step %g ms, %d plant steps per control step\n", sc->name, sc->path,
            sc->duration_s, sc->control_dt_s * 1e3, sc->plant_substeps);
    sim_report_tuning(out, sc);
    for (int c = 0; c < sc->n_controllers; ++c) {
        if (sc->controllers[c] != SIM_CTRL_INDI) {
            continue; /* the paper's four keep their header as it was */
        }
        ladrc_attitude_config_t cfg;
        sim_setup_attitude(sc, sc->controllers[c], &cfg);
        fprintf(out, "%s gains (roll / pitch / yaw): k_att", sim_controller_name(sc->controllers[c]));
        for (int i = 0; i < 3; ++i)
            fprintf(out, "%s%.4g", i ? " / " : " ", (double)cfg.axis[i].indi_att_kp_per_s);
        fprintf(out, " 1/s, k_rate");
        for (int i = 0; i < 3; ++i)
            fprintf(out, "%s%.4g", i ? " / " : " ", (double)cfg.axis[i].indi_rate_kp_per_s);
        fprintf(out, " 1/s, w_f");
        for (int i = 0; i < 3; ++i)
            fprintf(out, "%s%.4g", i ? " / " : " ", (double)cfg.axis[i].indi_filter_rad_s);
        fprintf(out, " rad/s\n");
    }
    for (int c = 0; c < sc->n_controllers; ++c) {
        if (sc->controllers[c] == SIM_CTRL_CASCADED) {
            cascaded_gains(out, sc);
        }
    }
    for (int c = 0; c < sc->n_controllers; ++c) {
        const sim_metrics_t *m = &r->attitude[c];
        if (m->diverged) {
            char why[160];
            sim_report_divergence_text(why, sizeof why, sc, m);
            fprintf(out, "%s: DIVERGED: %s; the run stopped there and its statistics are withheld\n",
                    sim_controller_name(sc->controllers[c]), why);
        }
        for (int i = 0; i < 3 && !m->untunable; ++i) {
            if (!isnan(m->reference_outran_at_s[i])) {
                char why[400];
                sim_report_outran_text(why, sizeof why, sc, m, i);
                fprintf(out, "%s: %s; the run went on\n", sim_controller_name(sc->controllers[c]), why);
            }
        }
    }
    table4(out, r);
    table5(out, r);
    table6(out, r);
    table7(out, r);
}

static void row_text(FILE *out, const sim_scenario_t *sc, const char *ctrl, const char *table, const char *quantity,
                     const char *axis, const char *value)
{
    fprintf(out, "%s,%s,%s,%s,%s,%s\n", sc->name, ctrl, table, quantity, axis, value);
}

static void row(FILE *out, const sim_scenario_t *sc, const char *ctrl, const char *table, const char *quantity,
                const char *axis, double value)
{
    char text[32];
    snprintf(text, sizeof text, "%.9g", value);
    row_text(out, sc, ctrl, table, quantity, axis, text);
}

/* A statistic of an attitude run: its value, or "diverged" when the run diverged. */
static void stat_row(FILE *out, const sim_scenario_t *sc, const sim_metrics_t *m, const char *ctrl, const char *table,
                     const char *quantity, const char *axis, double value)
{
    if (m->untunable) {
        row_text(out, sc, ctrl, table, quantity, axis, SIM_TOKEN_UNTUNABLE);
    } else if (m->diverged) {
        row_text(out, sc, ctrl, table, quantity, axis, SIM_TOKEN_DIVERGED);
    } else {
        row(out, sc, ctrl, table, quantity, axis, value);
    }
}

int sim_report_metrics_csv(FILE *out, const sim_scenario_result_t *r, int header)
{
    static const char *const ROTORS[4] = {"1", "2", "3", "4"};
    const sim_scenario_t *sc = r->sc;
    if (header) {
        fputs("scenario,controller,table,quantity,axis,value\n", out);
    }
    if (r->diff != NULL) {
        const sim_stat_t *s[2] = {&r->diff->td_error, &r->diff->levant_error};
        const char *names[2] = {"TD", "Levant"};
        for (int k = 0; k < 2; ++k) {
            row(out, sc, names[k], "3", "derivative_error_mean", "-", s[k]->mean);
            row(out, sc, names[k], "3", "derivative_error_std", "-", sim_stat_std(s[k]));
            row(out, sc, names[k], "3", "derivative_error_rms", "-", sim_stat_rms(s[k]));
        }
        return ferror(out) ? -1 : 0;
    }
    for (int c = 0; c < sc->n_controllers; ++c) {
        const char *name = sim_controller_name(sc->controllers[c]);
        const sim_metrics_t *m = &r->attitude[c];
        for (int i = 0; i < 3; ++i) {
            stat_row(out, sc, m, name, "4", "error_mean_deg", AXES[i], m->error_deg[i].mean);
            stat_row(out, sc, m, name, "4", "error_std_deg", AXES[i], sim_stat_std(&m->error_deg[i]));
            stat_row(out, sc, m, name, "4", "error_rms_deg", AXES[i], sim_stat_rms(&m->error_deg[i]));
            stat_row(out, sc, m, name, "5", "max_error_deg", AXES[i], m->max_error_deg[i]);
            if (withheld(m) == NULL && m->settle_s[i] == SIM_NOT_SETTLED) {
                row_text(out, sc, name, "5", "settling_s", AXES[i], SIM_TOKEN_NOT_SETTLED);
            } else {
                stat_row(out, sc, m, name, "5", "settling_s", AXES[i], m->settle_s[i]);
            }
            stat_row(out, sc, m, name, "5", "steady_band_deg", AXES[i], m->band_deg[i]);
            stat_row(out, sc, m, name, "5", "steady_rms_deg", AXES[i], sim_stat_rms(&m->steady_deg[i]));
            stat_row(out, sc, m, name, "-", "cmd_noise_Nm", AXES[i], m->cmd_noise_Nm[i]);
            if (m->has_estimate) {
                stat_row(out, sc, m, name, "6", "dist_error_mean", AXES[i], m->dist_error[i].mean);
                stat_row(out, sc, m, name, "6", "dist_error_std", AXES[i], sim_stat_std(&m->dist_error[i]));
                stat_row(out, sc, m, name, "6", "dist_error_rms", AXES[i], sim_stat_rms(&m->dist_error[i]));
            }
        }
        for (int k = 0; k < 4; ++k) {
            const double sd = sim_stat_std(&m->rotor_w2[k]);
            stat_row(out, sc, m, name, "7", "w2_mean", ROTORS[k], m->rotor_w2[k].mean);
            stat_row(out, sc, m, name, "7", "w2_std", ROTORS[k], sd);
            stat_row(out, sc, m, name, "7", "w2_var", ROTORS[k], sd * sd);
        }
        const sim_tuning_t *t = &sc->tuning[sc->controllers[c]];
        if (t->by != SIM_TUNED_NONE) {
            row_text(out, sc, name, "tune", "status", "-", sim_tuned_by_name(t->by));
            row(out, sc, name, "tune", "targets_met", "-", t->targets_met);
            static const char *const CANDIDATES[SIM_N_CANDIDATES] = {"check_rms_tuned_deg", "check_rms_defaults_deg",
                                                                     "check_rms_scenario_deg"};
            for (int k = 0; k < SIM_N_CANDIDATES; ++k) {
                if (isnan(t->check_cost_deg[k])) {
                    row_text(out, sc, name, "tune", CANDIDATES[k], "-", SIM_TOKEN_NONE);
                } else if (isinf(t->check_cost_deg[k])) {
                    row_text(out, sc, name, "tune", CANDIDATES[k], "-", SIM_TOKEN_DIVERGED);
                } else {
                    row(out, sc, name, "tune", CANDIDATES[k], "-", t->check_cost_deg[k]);
                }
            }
        }
        for (int i = 0; t->tuned && i < 3; ++i) {
            int n_gains;
            const sim_gain_field_t *g = sim_setup_gain_fields(t->gains[i].variant, &n_gains);
            for (int k = 0; k < n_gains; ++k) {
                row(out, sc, name, "tune", g[k].key, AXES[i], sim_setup_gain(&t->gains[i], &g[k]));
            }
            row(out, sc, name, "tune", "pm_deg", AXES[i], t->pm_deg[i]);
            row(out, sc, name, "tune", "gm_db", AXES[i], t->gm_db[i]);
            row(out, sc, name, "tune", "gm_low_db", AXES[i], t->gm_low_db[i]);
            row(out, sc, name, "tune", "crossover_rad_s", AXES[i], t->crossover_rad_s[i]);
            row(out, sc, name, "tune", "ms", AXES[i], t->ms[i]);
            row(out, sc, name, "tune", "step_cost_rad2_s", AXES[i], t->step_cost_rad2_s[i]);
            row(out, sc, name, "tune", "cmd_noise_Nm", AXES[i], t->cmd_noise_Nm[i]);
            row(out, sc, name, "tune", "cmd_noise_cap_Nm", AXES[i], t->cmd_noise_cap_Nm[i]);
        }
        if (m->untunable) { /* not flown */
            row_text(out, sc, name, "-", "finite", "-", SIM_TOKEN_UNTUNABLE);
            row_text(out, sc, name, "-", "fault_ticks", "-", SIM_TOKEN_UNTUNABLE);
        } else {
            row(out, sc, name, "-", "finite", "-", m->finite);
            row(out, sc, name, "-", "fault_ticks", "-", (double)m->faults);
        }
        for (int i = 0; i < 3 && !m->untunable; ++i) {
            if (!isnan(m->reference_outran_at_s[i])) {
                row(out, sc, name, "-", "reference_outran_at_s", AXES[i], m->reference_outran_at_s[i]);
                row(out, sc, name, "-", "reference_outran_deg", AXES[i], m->reference_outran_deg[i]);
                row(out, sc, name, "-", "reference_accel_rad_s2", AXES[i],
                    sim_report_reference_accel(sc, i, m->reference_outran_at_s[i]));
            }
        }
        row(out, sc, name, "-", "diverged", "-", m->diverged);
        if (m->diverged) { /* the error is nan when the state turned non-finite */
            row(out, sc, name, "-", "diverged_at_s", diverged_axis_name(m), m->diverged_at_s);
            row(out, sc, name, "-", "diverged_error_deg", diverged_axis_name(m), m->diverged_error_deg);
        } else {
            row_text(out, sc, name, "-", "diverged_at_s", "-", SIM_TOKEN_NONE);
            row_text(out, sc, name, "-", "diverged_error_deg", "-", SIM_TOKEN_NONE);
        }
    }
    return ferror(out) ? -1 : 0;
}
