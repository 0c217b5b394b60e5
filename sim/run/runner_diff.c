/* SPDX-License-Identifier: BSD-3-Clause */
/* The differentiator run (runner.h): Levant and the TD on a noisy signal. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ladrc/levant.h"
#include "ladrc/td.h"
#include "plant/rng.h"
#include "runner_parts.h"
#include "scenario/setup.h"

/* Levant and the TD configured as the parser checked them, at the signal's
 * value at t = 0; 0, or -1 with the message. */
static int diff_open(const sim_scenario_t *sc, ladrc_levant_t *lev, ladrc_td_t *td, char *err, size_t err_len)
{
    ladrc_levant_config_t lcfg;
    ladrc_td_config_t tcfg;
    sim_setup_differentiators(sc, &lcfg, &tcfg);
    ladrc_status_t st = ladrc_levant_init(lev, &lcfg);
    if (st == LADRC_OK) {
        st = ladrc_td_init(td, &tcfg);
    }
    if (st != LADRC_OK) {
        snprintf(err, err_len, "%s: differentiator: %s", sc->path, ladrc_status_str(st));
        return -1;
    }
    const double r0 = sim_signal_eval(&sc->diff_signal, 0.0);
    ladrc_levant_reset(lev, (ladrc_real_t)r0);
    ladrc_td_reset(td, (ladrc_real_t)r0);
    return 0;
}

/* A line of the time series: "%.4f,%.7g,%.7g,%.7g,%.7g\n" of t, the noisy
 * signal, the true derivative, Levant's and the TD's. */
static void diff_csv_line(csv_line_t *line, FILE *csv, double t, double r, double dr, double dr_levant, double dr_td)
{
    runner_line_f4(line, t);
    runner_line_g(line, r, 7);
    runner_line_g(line, dr, 7);
    runner_line_g(line, dr_levant, 7);
    runner_line_g(line, dr_td, 7);
    runner_line_end(line, csv);
}

int sim_run_differentiator(const sim_scenario_t *sc, const char *csv_path, const sim_progress_t *progress,
                           sim_diff_metrics_t *m, char *err, size_t err_len)
{
    memset(m, 0, sizeof *m);
    ladrc_levant_t lev;
    ladrc_td_t td;
    if (diff_open(sc, &lev, &td, err, err_len) != 0) {
        return -1;
    }
    sim_rng_t rng;
    sim_rng_seed(&rng, sc->seed);
    FILE *csv = runner_open_csv(csv_path, "t_s,r_noisy,dr_true,dr_levant,dr_td\n", err, err_len);
    if (csv_path != NULL && csv == NULL) {
        return -1;
    }
    csv_line_t line;
    line.len = 0;
    const double start = runner_wall_now_s();
    const long n = sim_run_ticks(sc);
    const double noise_std = sqrt(sc->diff_noise_var);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * sc->control_dt_s;
        const double r = sim_signal_eval(&sc->diff_signal, t) + noise_std * sim_rng_gauss(&rng);
        const double dr = sim_signal_eval(&sc->diff_derivative, t);
        /* the TD's output belongs to the next instant (td.h), Levant's to this one */
        const double dr_next = sim_signal_eval(&sc->diff_derivative, t + sc->control_dt_s);
        ladrc_ref_t lev_out, td_out;
        ladrc_levant_step(&lev, (ladrc_real_t)r, &lev_out);
        ladrc_td_step(&td, (ladrc_real_t)r, &td_out);
        if (in_window(sc->error_window_s, t)) {
            sim_stat_add(&m->levant_error, (double)lev_out.dr - dr);
            sim_stat_add(&m->td_error, (double)td_out.dr - dr_next);
        }
        if (csv != NULL) {
            diff_csv_line(&line, csv, t, r, dr, (double)lev_out.dr, (double)td_out.dr);
        }
        if (progress != NULL && progress->ticks_done != NULL && (k & 1023) == 1023) {
            *progress->ticks_done += 1024;
        }
    }
    m->wall_s = runner_wall_now_s() - start;
    if (csv != NULL && fclose(csv) != 0) {
        snprintf(err, err_len, "%s: write failed", csv_path);
        return -1;
    }
    return 0;
}
