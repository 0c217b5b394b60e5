/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the scenario parser (sim_scenario_parse_buffer) on
 * arbitrary bytes. Besides what the sanitizers catch, it checks that:
 * - a refused input has its error inside the text: 1 <= line <= the lines of
 *   the text, 1 <= column <= that line's length + 1, and a message;
 * - an accepted one can be flown: the run within the limits of scenario.h,
 *   each listed controller, the mixer or the differentiators start with the
 *   configuration the runner gives them (setup.h), each controller not listed
 *   either starts or has its error recorded (and sim_scenario_set_controllers
 *   agrees), the metric windows lie in the run, and every signal evaluates
 *   at a few times of the run.
 */
#include "fuzz.h"

#include <math.h>
#include <string.h>

#include "run/runner.h"
#include "scenario/excitation.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

static sim_scenario_t sc;

static void check_refused(const uint8_t *data, size_t size, const sim_parse_error_t *err)
{
    int lines;
    size_t line_len;
    if (strcmp(err->path, "fuzz.ini") != 0) {
        /* an error in a series file the scenario names: at that file's place, naming the scenario's key */
        FUZZ_CHECK(err->line >= 0 && err->column >= 0, "line %d column %d in '%s'", err->line, err->column, err->path);
        FUZZ_CHECK(strstr(err->message, "(the file of ") != NULL && strstr(err->message, "fuzz.ini line ") != NULL,
                   "series error without its key: %s", err->message);
        return;
    }
    fuzz_measure_lines(data, size, err->line, &lines, &line_len);
    FUZZ_CHECK(err->line >= 1 && err->line <= lines, "line %d of %d: %s", err->line, lines, err->message);
    FUZZ_CHECK(err->column >= 1 && (size_t)err->column <= line_len + 1, "column %d of a %zu-byte line %d: %s",
               err->column, line_len, err->line, err->message);
    FUZZ_CHECK(err->message[0] != '\0', "no message at %d:%d", err->line, err->column);
    FUZZ_CHECK(strcmp(err->path, "fuzz.ini") == 0, "path '%s'", err->path);
}

static int starts(sim_controller_id_t id)
{
    ladrc_attitude_config_t cfg;
    ladrc_attitude_t att;
    sim_setup_attitude(&sc, id, &cfg);
    /* what the library refuses, and what the simulator does (scenario.h) */
    return ladrc_attitude_init(&att, &cfg, NULL) == LADRC_OK && !(sim_controller_needs_rate(id) && !sc.use_rate);
}

static void evaluate(const sim_signal_t *sig, const double *times, int n)
{
    for (int i = 0; i < n; ++i) {
        (void)sim_signal_eval(sig, times[i]); /* any value; the sanitizers watch */
    }
}

/* [excitation]: a chirp within the run, its amplitude and frequencies in
 * range, a value within the amplitude at a few times; none without it. */
static void check_excitation(const double *times, int n)
{
    if (sc.excite_on) {
        FUZZ_CHECK(sc.excite_n_amplitudes == 1 || sc.excite_n_amplitudes == 3, "%d amplitudes", sc.excite_n_amplitudes);
        for (int a = 0; a < sc.excite_n_amplitudes; ++a) {
            FUZZ_CHECK(sc.excite_amplitude[a] > 0.0 && sc.excite_amplitude[a] <= 1.0, "amplitude %g",
                       sc.excite_amplitude[a]);
        }
        FUZZ_CHECK(sc.excite_f0_hz > 0.0 && sc.excite_f0_hz < sc.excite_f1_hz &&
                       sc.excite_f1_hz <= 0.45 / sc.control_dt_s,
                   "f0 %g, f1 %g Hz at dt %g", sc.excite_f0_hz, sc.excite_f1_hz, sc.control_dt_s);
        FUZZ_CHECK(sc.excite_start_s >= 0.0 && sim_excitation_end_s(&sc) <= sc.duration_s,
                   "the chirps from %g to %g s of %g", sc.excite_start_s, sim_excitation_end_s(&sc), sc.duration_s);
    }
    for (int i = 0; i < n; ++i) {
        double c[3];
        sim_excitation_at(&sc, times[i], c);
        for (int a = 0; a < 3; ++a) {
            const double amplitude = sc.excite_amplitude[sc.excite_n_amplitudes == 3 ? a : 0];
            FUZZ_CHECK(fabs(c[a]) <= (sc.excite_on ? amplitude : 0.0), "chirp %g at %g s", c[a], times[i]);
        }
    }
}

static void check_accepted(void)
{
    FUZZ_CHECK(sc.control_dt_s >= SIM_CONTROL_DT_MIN_S && sc.control_dt_s <= SIM_CONTROL_DT_MAX_S, "dt %g",
               sc.control_dt_s);
    FUZZ_CHECK(sc.duration_s > 0.0 && sc.duration_s <= SIM_DURATION_MAX_S, "duration %g", sc.duration_s);
    const long ticks = sim_run_ticks(&sc);
    FUZZ_CHECK(ticks >= 1 && ticks <= SIM_RUN_TICKS_MAX, "%ld control periods", ticks);
    const double windows[3][2] = {{sc.error_window_s[0], sc.error_window_s[1]},
                                  {sc.steady_window_s[0], sc.steady_window_s[1]},
                                  {sc.settle_after_s, sc.settle_until_s}};
    for (int i = 0; i < 3; ++i) {
        FUZZ_CHECK(windows[i][0] >= 0.0 && windows[i][0] < windows[i][1] && windows[i][1] <= sc.duration_s,
                   "window %d: %g %g of %g s", i, windows[i][0], windows[i][1], sc.duration_s);
    }
    const double times[] = {0.0, sc.control_dt_s, 0.5 * sc.duration_s, sc.duration_s};
    const int n_times = (int)(sizeof times / sizeof times[0]);

    if (sc.kind == SIM_KIND_DIFFERENTIATOR) {
        ladrc_levant_config_t lcfg;
        ladrc_td_config_t tcfg;
        ladrc_levant_t lev;
        ladrc_td_t td;
        sim_setup_differentiators(&sc, &lcfg, &tcfg);
        FUZZ_CHECK(ladrc_levant_init(&lev, &lcfg) == LADRC_OK, "Levant does not start");
        FUZZ_CHECK(ladrc_td_init(&td, &tcfg) == LADRC_OK, "the TD does not start");
        evaluate(&sc.diff_signal, times, n_times);
        evaluate(&sc.diff_derivative, times, n_times);
        return;
    }
    FUZZ_CHECK(sc.plant_substeps >= 1 && sc.plant_substeps <= SIM_PLANT_SUBSTEPS_MAX, "substeps %d", sc.plant_substeps);
    FUZZ_CHECK((double)ticks * sc.plant_substeps <= SIM_RUN_PLANT_STEPS_MAX, "%ld x %d plant steps", ticks,
               sc.plant_substeps);
    const double h = sc.control_dt_s / sc.plant_substeps;
    FUZZ_CHECK(!(sc.motor_tau_s > 0.0) || h <= sc.motor_tau_s, "plant step %g, motor lag %g", h, sc.motor_tau_s);
    for (int i = 0; i < 3; ++i) {
        FUZZ_CHECK(!(sc.rot_drag_Nm_s > 0.0) || h <= sc.inertia_kg_m2[i] / sc.rot_drag_Nm_s,
                   "plant step %g, drag time constant %g", h, sc.inertia_kg_m2[i] / sc.rot_drag_Nm_s);
    }
    FUZZ_CHECK(sc.n_controllers >= 1 && sc.n_controllers <= SIM_CTRL_COUNT, "%d controllers", sc.n_controllers);
    int listed[SIM_CTRL_COUNT] = {0};
    for (int i = 0; i < sc.n_controllers; ++i) {
        const sim_controller_id_t id = sc.controllers[i];
        FUZZ_CHECK((int)id >= 0 && id < SIM_CTRL_COUNT && !listed[id], "controller %d", (int)id);
        listed[id] = 1;
        FUZZ_CHECK(starts(id), "listed controller %s does not start", sim_controller_name(id));
    }
    int all_start = 1;
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
        const int ok = starts((sim_controller_id_t)id);
        const sim_parse_error_t *e = &sc.controller_error[id];
        FUZZ_CHECK(ok == (e->line == 0), "%s starts: %d, recorded error at line %d: %s",
                   sim_controller_name((sim_controller_id_t)id), ok, e->line, e->message);
        all_start &= ok;
    }
    ladrc_mixer_config_t mcfg;
    ladrc_mixer_t mixer;
    sim_setup_mixer(&sc, &mcfg);
    FUZZ_CHECK(ladrc_mixer_init(&mixer, &mcfg) == LADRC_OK, "the mixer does not start");
    for (int i = 0; i < 3; ++i) {
        evaluate(&sc.reference[i], times, n_times);
        evaluate(&sc.disturbance[i], times, n_times);
    }
    check_excitation(times, n_times);
    /* last: it changes the list */
    static const sim_controller_id_t every[] = {SIM_CTRL_PID,       SIM_CTRL_LADRC,    SIM_CTRL_LP_MLADRC,
                                                SIM_CTRL_HP_MLADRC, SIM_CTRL_CASCADED, SIM_CTRL_INDI};
    sim_parse_error_t err;
    const int rc = sim_scenario_set_controllers(&sc, every, (int)(sizeof every / sizeof every[0]), &err);
    FUZZ_CHECK((rc == 0) == all_start, "set_controllers %d while every controller starts: %d (%s)", rc, all_start,
               err.message);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sim_parse_error_t err;
    const int rc = sim_scenario_parse_buffer(&sc, (const char *)data, size, "fuzz.ini", &err);
    FUZZ_CHECK(rc == 0 || rc == -1, "rc %d", rc);
    if (rc != 0) {
        check_refused(data, size, &err);
    } else {
        check_accepted();
    }
    return 0;
}
