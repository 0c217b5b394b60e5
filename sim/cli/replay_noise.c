/* SPDX-License-Identifier: BSD-3-Clause */
/* ladrc_replay's noise stage (replay_noise.h). */
#include "replay_noise.h"

#include <math.h>
#include <stdlib.h>

#include "ladrc/margins.h"
#include "log/filter_proposal.h"
#include "log/log_noise.h"

#define PI 3.14159265358979323846
#define RAD2DEG (180.0 / PI)

static const char *const AXIS[3] = {"roll", "pitch", "yaw"};

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median3(double a, double b, double c)
{
    double v[3] = {a, b, c};
    qsort(v, 3, sizeof v[0], cmp_double);
    return v[1];
}

int sim_replay_noise_stage(const sim_log_options_t *opt, sim_airframe_t *a, FILE *out, char *err, size_t err_len)
{
    sim_log_noise_t *n = malloc(sizeof *n);
    if (n == NULL) {
        snprintf(err, err_len, "%s: out of memory for the noise pass", opt->path);
        return -1;
    }
    const double wc_identified = sim_filter_crossover_estimate(
        median3(a->axis[0].lag_s, a->axis[1].lag_s, a->axis[2].lag_s),
        (int)median3(a->axis[0].delay_ticks, a->axis[1].delay_ticks, a->axis[2].delay_ticks), a->dt_s);
    const int wc_known = isfinite(wc_identified);
    const double wc = wc_known ? wc_identified : SIM_FILTER_CROSSOVER_DEFAULT_RAD_S;
    if (sim_log_noise_measure(opt, wc, n, err, err_len) != 0) {
        free(n);
        return -1;
    }
    const int raw = (n->has & SIM_LOG_HAS_GYRO_RAW) != 0;
    if (n->has & SIM_LOG_HAS_COMMAND) {
        fprintf(out, "logged command noise above %.0f Hz (of the authority; the LADRC family's cap, N m):",
                LADRC_MARGINS_NOISE_CORNER_HZ);
        for (int i = 0; i < 3; ++i) {
            a->log_cmd_noise[i] = sim_log_noise_command_above(n, i, LADRC_MARGINS_NOISE_CORNER_HZ);
            fprintf(out, " %s %.4g (%.4g)", AXIS[i], a->log_cmd_noise[i],
                    a->log_cmd_noise[i] * sim_airframe_torque_per_command_Nm(a, i));
        }
        fputc('\n', out);
    }
    static sim_filter_proposal_t p;
    char why[256];
    /* the airframe's rotors are nominal, not the log's: its stage has fixed notches only */
    if (sim_filter_propose(raw ? n->gyro_raw : n->gyro, n->dt_s, 0.0, 0, wc, &p, why, sizeof why) != 0) {
        fprintf(out, "no filter stage proposed: %s\n", why);
        free(n);
        return 0;
    }
    a->has_filter = p.cfg.lpf_order > 0 || p.cfg.n_notches > 0;
    a->filter = p.cfg;
    fprintf(out, "proposed gyro filter (from the gyro %s the log's filters): low-pass ", raw ? "before" : "after");
    if (p.cfg.lpf_order > 0) {
        fprintf(out, "order 2 at %.1f Hz", (double)p.cfg.lpf_cutoff_hz);
    } else {
        fprintf(out, "none (the notches use the phase budget)");
    }
    fprintf(out, ", %d notch(es)", p.cfg.n_notches);
    for (int k = 0; k < p.cfg.n_notches; ++k) {
        fprintf(out, "%s%.1f", k == 0 ? " at " : " ", (double)p.cfg.notch_hz[k]);
    }
    if (p.cfg.n_notches > 0) {
        fprintf(out, " Hz, Q %.3g", (double)p.cfg.notch_q);
    }
    fprintf(out, "; vibration band %.1f-%.1f Hz, crossover %.1f rad/s (%s)\n", p.band_lo_hz, p.band_hi_hz, wc,
            wc_known ? "estimated from the lag and delay" : "the default: the lag and delay are not identified");
    const double own_phase = sim_filter_phase_cost_deg(&p.cfg, 0.0, wc);
    for (int i = 0; i < 3; ++i) {
        fprintf(out, "  %-5s proposed: %5.1f dB in the band, %4.1f deg at the crossover (a delay of %.2f ms)", AXIS[i],
                sim_filter_band_attenuation_db(&p.cfg, 0.0, raw ? &n->gyro_raw[i] : &n->gyro[i], p.band_lo_hz,
                                               p.band_hi_hz),
                own_phase, 1e3 * sim_phase_delay_s(own_phase, wc));
        if (raw) {
            fprintf(out, "; the log's chain: %5.1f dB, %4.1f deg at the crossover (a delay of %.2f ms)",
                    sim_filter_measured_attenuation_db(&n->gyro_raw[i], &n->gyro[i], p.band_lo_hz, p.band_hi_hz),
                    sim_log_noise_chain_phase_deg(n, i), 1e3 * sim_log_noise_chain_delay_s(n, i));
        }
        fputc('\n', out);
    }
    free(n);
    return 0;
}

static int in_family(sim_controller_id_t id)
{
    return id == SIM_CTRL_HP_MLADRC || id == SIM_CTRL_LP_MLADRC || id == SIM_CTRL_LADRC || id == SIM_CTRL_RATE_ADRC;
}

void sim_replay_noise_report(FILE *out, const sim_scenario_t *sc, const sim_replay_t *r)
{
    fprintf(out, "command noise above %.0f Hz (of the authority): predicted by the tuning, replayed, the log's\n",
            LADRC_MARGINS_NOISE_CORNER_HZ);
    fprintf(out, "%-10s %-5s %10s %10s %10s\n", "source", "axis", "predicted", "replayed", "log");
    double quietest[3] = {INFINITY, INFINITY, INFINITY};
    int family = 0;
    for (int c = 0; c < r->n; ++c) {
        const sim_tuning_t *t = &sc->tuning[r->ids[c]];
        for (int i = 0; i < 3; ++i) {
            const double replayed =
                sim_spectrum_band_rms(&r->axis[c][i].spectrum, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY);
            const double log = sim_spectrum_band_rms(&r->log_axis[i].spectrum, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY);
            const double predicted = t->tuned ? t->cmd_noise_Nm[i] / r->authority_Nm[i] : NAN;
            fprintf(out, "%-10s %-5s %10.4g %10.4g %10.4g\n", sim_controller_name(r->ids[c]), AXIS[i], predicted,
                    replayed, log);
        }
        if (!in_family(r->ids[c])) {
            continue;
        }
        family = 1;
        for (int i = 0; i < 3; ++i) {
            quietest[i] = fmin(quietest[i],
                               sim_spectrum_band_rms(&r->axis[c][i].spectrum, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY));
        }
    }
    if (!family) {
        return;
    }
    fprintf(out, "the LADRC family's quietest against the log's:");
    for (int i = 0; i < 3; ++i) {
        const double log = sim_spectrum_band_rms(&r->log_axis[i].spectrum, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY);
        fprintf(out, " %s %.4g %s %.4g", AXIS[i], quietest[i],
                quietest[i] <= log ? "<=" : (isnan(quietest[i]) || isnan(log) ? "?" : "ABOVE"), log);
    }
    fputc('\n', out);
    for (int i = 0; i < 3; ++i) {
        const double log = sim_spectrum_band_rms(&r->log_axis[i].spectrum, LADRC_MARGINS_NOISE_CORNER_HZ, INFINITY);
        if (quietest[i] <= log) {
            continue;
        }
        if (isnan(quietest[i]) || isnan(log)) {
            fprintf(out, "  %s: no noise figure above %.0f Hz: the log is shorter than one spectrum segment\n", AXIS[i],
                    LADRC_MARGINS_NOISE_CORNER_HZ);
            continue;
        }
        /* the family's lowest prediction says which side of the tuning the excess lies on */
        double lowest = INFINITY;
        for (int c = 0; c < r->n; ++c) {
            const sim_tuning_t *t = &sc->tuning[r->ids[c]];
            if (in_family(r->ids[c]) && t->tuned) {
                lowest = fmin(lowest, t->cmd_noise_Nm[i] / r->authority_Nm[i]);
            }
        }
        if (isinf(lowest)) {
            fprintf(out,
                    "  %s: above the log's by %.3gx; no member of the family was tuned for this airframe (the "
                    "library's defaults fly): nothing predicted\n",
                    AXIS[i], quietest[i] / log);
        } else if (!(lowest <= log)) {
            fprintf(out,
                    "  %s: above the log's: no tuned gains of the family reach it even as predicted (lowest %.4g, "
                    "%.3gx the log's)\n",
                    AXIS[i], lowest, lowest / log);
        } else {
            fprintf(out,
                    "  %s: above the log's by %.3gx though predicted within it (lowest %.4g): the excess is what "
                    "the prediction does not count (the setpoint's steps through the reference shapers, the "
                    "flight's own motion above %.0f Hz)\n",
                    AXIS[i], quietest[i] / log, lowest, LADRC_MARGINS_NOISE_CORNER_HZ);
        }
    }
}
