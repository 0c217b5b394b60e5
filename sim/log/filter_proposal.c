/* SPDX-License-Identifier: BSD-3-Clause */
/* The gyro filter stage from a log's spectrum (filter_proposal.h). */
#include "filter_proposal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "airframe.h"

#define PI 3.14159265358979323846
#define RAD2DEG (180.0 / PI)

/* A section's response at e^{jw}: (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2),
 * blended with its input by its weight. */
static void section_response(const ladrc_gyro_filter_section_t *s, double w, double *re, double *im)
{
    const double c1 = cos(w), s1 = -sin(w), c2 = cos(2.0 * w), s2 = -sin(2.0 * w);
    const double nr = s->b0 + s->b1 * c1 + s->b2 * c2, ni = s->b1 * s1 + s->b2 * s2;
    const double dr = 1.0 + s->a1 * c1 + s->a2 * c2, di = s->a1 * s1 + s->a2 * s2;
    const double d2 = dr * dr + di * di;
    const double hr = (nr * dr + ni * di) / d2, hi = (ni * dr - nr * di) / d2;
    *re = 1.0 + s->weight * (hr - 1.0);
    *im = s->weight * hi;
}

int sim_filter_response(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, double hz, double *gain,
                        double *phase_rad)
{
    static ladrc_gyro_filter_t f; /* the library's derived sections (host tools: one thread) */
    if (ladrc_gyro_filter_init(&f, cfg) != LADRC_OK) {
        return -1;
    }
    if (cfg->rpm_rotors > 0) {
        ladrc_real_t speeds[LADRC_GYRO_FILTER_MAX_ROTORS];
        for (unsigned r = 0; r < LADRC_GYRO_FILTER_MAX_ROTORS; ++r) {
            speeds[r] = (ladrc_real_t)rotor_hz;
        }
        ladrc_gyro_filter_set_rotor_hz(&f, speeds);
    }
    const double w = 2.0 * PI * hz * (double)cfg->dt_s;
    double g = 1.0, ph = 0.0;
    for (int k = 0; k < f.n_sections; ++k) {
        double re, im;
        section_response(&f.section[k], w, &re, &im);
        g *= hypot(re, im);
        ph += atan2(im, re);
    }
    *gain = g;
    *phase_rad = ph;
    return 0;
}

double sim_filter_band_attenuation_db(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, const sim_spectrum_t *in,
                                      double lo_hz, double hi_hz)
{
    double before = 0.0, after = 0.0;
    for (int k = 1; k < SIM_SPECTRUM_BINS; ++k) {
        const double hz = sim_spectrum_hz(in, k);
        double g, ph;
        if (hz < lo_hz || hz >= hi_hz || sim_filter_response(cfg, rotor_hz, hz, &g, &ph) != 0) {
            continue;
        }
        before += sim_spectrum_psd(in, k);
        after += g * g * sim_spectrum_psd(in, k);
    }
    return after > 0.0 ? 10.0 * log10(before / after) : NAN;
}

double sim_filter_measured_attenuation_db(const sim_spectrum_t *in, const sim_spectrum_t *out, double lo_hz,
                                          double hi_hz)
{
    const double a = sim_spectrum_band_rms(in, lo_hz, hi_hz), b = sim_spectrum_band_rms(out, lo_hz, hi_hz);
    return b > 0.0 ? 20.0 * log10(a / b) : NAN;
}

double sim_filter_crossover_estimate(double lag_s, int delay_ticks, double dt_s)
{
    if (!(lag_s >= 0.0 && isfinite(lag_s)) || delay_ticks < 0 || !(dt_s > 0.0)) {
        return NAN;
    }
    return 1.0 / (lag_s + ((double)delay_ticks + 0.5) * dt_s);
}

/* The line's width (Hz) at k: the bins about it whose PSD above the floor
 * stays above SIM_FILTER_WIDTH_SHARE of the peak's while it falls, one bin at least. */
static double line_width_hz(const sim_spectrum_t *s, int k, double floor_psd)
{
    const double peak = sim_spectrum_psd(s, k) - floor_psd, cut = floor_psd + SIM_FILTER_WIDTH_SHARE * peak;
    int lo = k, hi = k;
    /* down the peak's flanks only: a rise is the next line or the flight's own motion */
    while (lo > 1 && sim_spectrum_psd(s, lo - 1) > cut && sim_spectrum_psd(s, lo - 1) < sim_spectrum_psd(s, lo)) {
        --lo;
    }
    while (hi + 1 < SIM_SPECTRUM_BINS && sim_spectrum_psd(s, hi + 1) > cut &&
           sim_spectrum_psd(s, hi + 1) < sim_spectrum_psd(s, hi)) {
        ++hi;
    }
    const double bin_hz = sim_spectrum_hz(s, 1);
    return (double)(hi - lo + 1) * bin_hz;
}

static int by_hz(const void *a, const void *b)
{
    const double x = ((const sim_filter_line_t *)a)->hz, y = ((const sim_filter_line_t *)b)->hz;
    return (x > y) - (x < y);
}

static int by_power_desc(const void *a, const void *b)
{
    const double x = ((const sim_filter_line_t *)a)->power, y = ((const sim_filter_line_t *)b)->power;
    return (x < y) - (x > y);
}

/* Every axis's lines, one entry per line: those of different axes that
 * overlap (centres within half their wider width) merged, power summed. */
static int gather_lines(const sim_spectrum_t raw[3], double fs_hz, sim_filter_line_t *out)
{
    int n = 0;
    double flo, fhi;
    sim_airframe_floor_band(fs_hz, &flo, &fhi);
    for (int i = 0; i < 3; ++i) {
        const double floor_psd = sim_spectrum_floor(&raw[i], flo, fhi);
        sim_spectrum_line_t lines[SIM_SPECTRUM_MAX_LINES];
        const int m = sim_spectrum_lines(&raw[i], SIM_FILTER_LINE_MIN_HZ, floor_psd, SIM_FILTER_LINE_RATIO, lines,
                                         SIM_SPECTRUM_MAX_LINES);
        const double bin_hz = sim_spectrum_hz(&raw[i], 1);
        for (int j = 0; j < m; ++j) {
            const int k = (int)lround(lines[j].hz / bin_hz);
            out[n].hz = lines[j].hz;
            out[n].width_hz = line_width_hz(&raw[i], k, floor_psd);
            out[n].power = lines[j].rms * lines[j].rms;
            out[n].harmonic = 0;
            ++n;
        }
    }
    qsort(out, (size_t)n, sizeof out[0], by_hz);
    int kept = 0;
    for (int j = 0; j < n; ++j) {
        sim_filter_line_t *last = kept > 0 ? &out[kept - 1] : NULL;
        if (last != NULL && out[j].hz - last->hz <= 0.5 * fmax(out[j].width_hz, last->width_hz)) {
            /* the same line on another axis: the centre weighted by power, the span of both */
            const double lo = fmin(last->hz - 0.5 * last->width_hz, out[j].hz - 0.5 * out[j].width_hz);
            const double hi = fmax(last->hz + 0.5 * last->width_hz, out[j].hz + 0.5 * out[j].width_hz);
            last->hz = (last->hz * last->power + out[j].hz * out[j].power) / (last->power + out[j].power);
            last->power += out[j].power;
            last->width_hz = fmax(hi - last->hz, last->hz - lo) * 2.0;
        } else {
            out[kept++] = out[j];
        }
    }
    return kept;
}

static double clamp_q(double q)
{
    return fmin(fmax(q, SIM_FILTER_Q_MIN), SIM_FILTER_Q_MAX);
}

double sim_filter_phase_cost_deg(const ladrc_gyro_filter_config_t *cfg, double rotor_hz, double w_rad_s)
{
    double g, ph;
    if (sim_filter_response(cfg, rotor_hz, w_rad_s / (2.0 * PI), &g, &ph) != 0) {
        return INFINITY;
    }
    return -ph * RAD2DEG;
}

/* The lowest low-pass corner (Hz) whose stage costs at most the budget at the
 * crossover, by bisection (the cost falls as the corner rises); 0 when even
 * the highest corner costs more. */
static double lowpass_corner_hz(ladrc_gyro_filter_config_t *cfg, double rotor_hz, double w_rad_s)
{
    const double top = 0.45 / (double)cfg->dt_s;
    double lo = w_rad_s / (2.0 * PI), hi = top;
    if (!(w_rad_s > 0.0 && isfinite(w_rad_s))) {
        cfg->lpf_order = 0; /* no crossover to hold the phase at (a log that tells no lag) */
        return 0.0;
    }
    cfg->lpf_order = 2;
    cfg->lpf_cutoff_hz = (ladrc_real_t)hi;
    if (sim_filter_phase_cost_deg(cfg, rotor_hz, w_rad_s) > SIM_FILTER_PHASE_BUDGET_DEG) {
        cfg->lpf_order = 0;
        return 0.0;
    }
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        cfg->lpf_cutoff_hz = (ladrc_real_t)mid;
        if (sim_filter_phase_cost_deg(cfg, rotor_hz, w_rad_s) > SIM_FILTER_PHASE_BUDGET_DEG) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    cfg->lpf_cutoff_hz = (ladrc_real_t)hi;
    return hi;
}

/* The RPM bank: the lines within SIM_FILTER_RPM_MATCH of a harmonic of
 * rotor_hz are its; its harmonics reach the highest such, its Q the
 * lowest of theirs. */
static void assign_rpm(sim_filter_proposal_t *p, double rotor_hz, int rotors)
{
    int top = 0;
    double q = SIM_FILTER_Q_MAX;
    for (int j = 0; j < p->n_lines && rotor_hz > 0.0 && rotors > 0; ++j) {
        sim_filter_line_t *l = &p->lines[j];
        const int h = (int)lround(l->hz / rotor_hz);
        if (h >= 1 && h <= (int)LADRC_GYRO_FILTER_MAX_HARMONICS &&
            fabs(l->hz - h * rotor_hz) <= SIM_FILTER_RPM_MATCH * h * rotor_hz) {
            l->harmonic = h;
            top = h > top ? h : top;
            q = fmin(q, l->hz / l->width_hz);
        }
    }
    if (top == 0) {
        return;
    }
    p->cfg.rpm_rotors =
        (uint8_t)(rotors < (int)LADRC_GYRO_FILTER_MAX_ROTORS ? rotors : (int)LADRC_GYRO_FILTER_MAX_ROTORS);
    p->cfg.rpm_harmonics = (uint8_t)top;
    p->cfg.rpm_q = (ladrc_real_t)clamp_q(q);
    p->cfg.rpm_min_hz = (ladrc_real_t)(0.5 * rotor_hz);
    p->cfg.rpm_fade_hz = (ladrc_real_t)(0.25 * rotor_hz);
    p->rotor_hz = rotor_hz;
}

int sim_filter_propose(const sim_spectrum_t raw[3], double dt_s, double rotor_hz, int rotors, double crossover_rad_s,
                       sim_filter_proposal_t *p, char *why, size_t why_len)
{
    memset(p, 0, sizeof *p);
    if (sim_spectrum_segments(&raw[0]) <= 0) {
        snprintf(why, why_len,
                 "the log is shorter than one spectrum segment (%d ticks): no spectrum to propose a "
                 "filter from",
                 SIM_SPECTRUM_N);
        return -1;
    }
    const double fs = 1.0 / dt_s;
    ladrc_gyro_filter_config_default(&p->cfg, (ladrc_real_t)dt_s, 3);
    p->crossover_rad_s = crossover_rad_s;
    p->n_lines = gather_lines(raw, fs, p->lines);
    const double centre_max = 0.45 * fs; /* gyro_filter.h: notches from here on are off */
    for (int j = 0; j < p->n_lines; ++j) {
        if (p->lines[j].hz >= centre_max) {
            p->lines[j].harmonic = -1;
        }
    }
    assign_rpm(p, rotor_hz, rotors);
    /* the fixed notches: the strongest lines the RPM bank leaves, each kept
     * when the stage with it (no low-pass yet) stays within the phase budget */
    qsort(p->lines, (size_t)p->n_lines, sizeof p->lines[0], by_power_desc);
    double q = SIM_FILTER_Q_MAX;
    for (int j = 0; j < p->n_lines; ++j) {
        sim_filter_line_t *l = &p->lines[j];
        const double line_q = l->hz / l->width_hz;
        if (l->harmonic != 0) {
            continue;
        }
        if (p->cfg.n_notches >= LADRC_GYRO_FILTER_MAX_NOTCHES || line_q < SIM_FILTER_Q_MIN) {
            l->harmonic = -1; /* no room, or a hump too wide for a notch: the low-pass's */
            continue;
        }
        ladrc_gyro_filter_config_t with = p->cfg;
        with.notch_hz[with.n_notches++] = (ladrc_real_t)l->hz;
        with.notch_q = (ladrc_real_t)fmin(clamp_q(line_q), q);
        if (sim_filter_phase_cost_deg(&with, p->rotor_hz, crossover_rad_s) > SIM_FILTER_PHASE_BUDGET_DEG) {
            l->harmonic = -1;
            continue;
        }
        p->cfg = with;
        q = (double)with.notch_q;
    }
    qsort(p->lines, (size_t)p->n_lines, sizeof p->lines[0], by_hz);
    /* the vibration band: the lines' span (their widths included), else the floor band */
    if (p->n_lines > 0) {
        p->band_lo_hz = fmax(p->lines[0].hz - 0.5 * p->lines[0].width_hz, SIM_FILTER_LINE_MIN_HZ);
        p->band_hi_hz = fmin(p->lines[p->n_lines - 1].hz + 0.5 * p->lines[p->n_lines - 1].width_hz, 0.5 * fs);
    } else {
        sim_airframe_floor_band(fs, &p->band_lo_hz, &p->band_hi_hz);
    }
    lowpass_corner_hz(&p->cfg, p->rotor_hz, crossover_rad_s);
    return 0;
}

void sim_filter_write_ini(FILE *f, const ladrc_gyro_filter_config_t *cfg)
{
    fprintf(f, "[filter]\nlpf_order = %u\n", (unsigned)cfg->lpf_order);
    if (cfg->lpf_order > 0) {
        fprintf(f, "lpf_hz = %.6g\n", (double)cfg->lpf_cutoff_hz);
    }
    if (cfg->n_notches > 0) {
        fprintf(f, "notch_hz =");
        for (int k = 0; k < cfg->n_notches; ++k) {
            fprintf(f, " %.6g", (double)cfg->notch_hz[k]);
        }
        fprintf(f, "\nnotch_q = %.4g\n", (double)cfg->notch_q);
    }
    if (cfg->rpm_rotors > 0) {
        fprintf(f, "rpm_harmonics = %u\nrpm_q = %.4g\nrpm_min_hz = %.6g\nrpm_fade_hz = %.6g\n",
                (unsigned)cfg->rpm_harmonics, (double)cfg->rpm_q, (double)cfg->rpm_min_hz, (double)cfg->rpm_fade_hz);
    }
    fputc('\n', f);
}
