/* SPDX-License-Identifier: BSD-3-Clause */
/* Tables 3-7 on stdout and the metrics summary (see report.h). */
#include "report.h"

static const char *const AXES[3] = {"roll", "pitch", "yaw"};

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
            "within %g deg up to %g s (-1: never) / steady band (+-deg) over (%g, %g] s\n",
            sc->error_window_s[0], sc->error_window_s[1], sc->settle_after_s, sc->settle_band_deg,
            sc->settle_until_s, sc->steady_window_s[0], sc->steady_window_s[1]);
    column_titles(out, sc, "axis", 28);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "%-6s", AXES[i]);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_metrics_t *m = &r->attitude[c];
            fprintf(out, " | %8.4f / %8.3f / %8.4f", m->max_error_deg[i], m->settle_s[i], m->band_deg[i]);
        }
        fputc('\n', out);
    }
}

static void table6(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out, "\nTable 6. Disturbance estimate error (z3 + d_hat - true total disturbance), rad/s^2: "
                 "mean / std / RMS over (%g, %g] s\n",
            sc->error_window_s[0], sc->error_window_s[1]);
    column_titles(out, sc, "axis", 28);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "%-6s", AXES[i]);
        for (int c = 0; c < sc->n_controllers; ++c) {
            const sim_metrics_t *m = &r->attitude[c];
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
            const double sd = sim_stat_std(s);
            fprintf(out, " | %9.0f / %9.0f / %10.4g", s->mean, sd, sd * sd);
        }
        fputc('\n', out);
    }
}

static void table3(FILE *out, const sim_scenario_result_t *r)
{
    const sim_scenario_t *sc = r->sc;
    fprintf(out, "\nTable 3. Derivative of the noisy signal (noise variance %g), error over (%g, %g] s: "
                 "mean / std / RMS\n",
            sc->diff_noise_var, sc->error_window_s[0], sc->error_window_s[1]);
    const sim_stat_t *s[2] = {&r->diff->td_error, &r->diff->levant_error};
    const char *names[2] = {"TD", "Levant"};
    for (int k = 0; k < 2; ++k) {
        fprintf(out, "%-8s %10.5f / %10.5f / %10.5f\n", names[k], s[k]->mean, sim_stat_std(s[k]),
                sim_stat_rms(s[k]));
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
    for (int c = 0; c < sc->n_controllers; ++c) {
        const sim_metrics_t *m = &r->attitude[c];
        if (!m->finite) {
            fprintf(out, "%s: the run diverged (non-finite angle)\n", sim_controller_name(sc->controllers[c]));
        }
    }
    table4(out, r);
    table5(out, r);
    table6(out, r);
    table7(out, r);
}

static void row(FILE *out, const sim_scenario_t *sc, const char *ctrl, const char *table, const char *quantity,
                const char *axis, double value)
{
    fprintf(out, "%s,%s,%s,%s,%s,%.9g\n", sc->name, ctrl, table, quantity, axis, value);
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
            row(out, sc, name, "4", "error_mean_deg", AXES[i], m->error_deg[i].mean);
            row(out, sc, name, "4", "error_std_deg", AXES[i], sim_stat_std(&m->error_deg[i]));
            row(out, sc, name, "4", "error_rms_deg", AXES[i], sim_stat_rms(&m->error_deg[i]));
            row(out, sc, name, "5", "max_error_deg", AXES[i], m->max_error_deg[i]);
            row(out, sc, name, "5", "settling_s", AXES[i], m->settle_s[i]);
            row(out, sc, name, "5", "steady_band_deg", AXES[i], m->band_deg[i]);
            if (m->has_estimate) {
                row(out, sc, name, "6", "dist_error_mean", AXES[i], m->dist_error[i].mean);
                row(out, sc, name, "6", "dist_error_std", AXES[i], sim_stat_std(&m->dist_error[i]));
                row(out, sc, name, "6", "dist_error_rms", AXES[i], sim_stat_rms(&m->dist_error[i]));
            }
        }
        for (int k = 0; k < 4; ++k) {
            const double sd = sim_stat_std(&m->rotor_w2[k]);
            row(out, sc, name, "7", "w2_mean", ROTORS[k], m->rotor_w2[k].mean);
            row(out, sc, name, "7", "w2_std", ROTORS[k], sd);
            row(out, sc, name, "7", "w2_var", ROTORS[k], sd * sd);
        }
        row(out, sc, name, "-", "finite", "-", m->finite);
        row(out, sc, name, "-", "fault_ticks", "-", (double)m->faults);
    }
    return ferror(out) ? -1 : 0;
}
