/* SPDX-License-Identifier: BSD-3-Clause */
/* A flight log's noise in one pass (log_noise.h). */
#include "log_noise.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static void start(sim_log_noise_t *n, double dt_s, unsigned has, double probe_rad_s)
{
    memset(n, 0, sizeof *n);
    n->dt_s = dt_s;
    n->has = has;
    n->probe_rad_s = probe_rad_s;
    for (int i = 0; i < 3; ++i) {
        sim_phase_probe_init(&n->chain[i], probe_rad_s, dt_s);
        sim_spectrum_init(&n->command[i], 1.0 / dt_s);
        sim_spectrum_init(&n->gyro[i], 1.0 / dt_s);
        sim_spectrum_init(&n->gyro_raw[i], 1.0 / dt_s);
    }
}

#define PI 3.14159265358979323846
#define RAD2DEG (180.0 / PI)

void sim_phase_probe_init(sim_phase_probe_t *p, double w_rad_s, double dt_s)
{
    memset(p, 0, sizeof *p);
    p->w_rad_per_tick = w_rad_s * dt_s;
}

void sim_phase_probe_push(sim_phase_probe_t *p, double x, double y)
{
    const double window = 0.5 * (1.0 - cos(2.0 * PI * p->fill / SIM_PHASE_PROBE_N));
    const double c = window * cos(p->w_rad_per_tick * p->fill), s = -window * sin(p->w_rad_per_tick * p->fill);
    p->xr += x * c;
    p->xi += x * s;
    p->yr += y * c;
    p->yi += y * s;
    if (++p->fill < SIM_PHASE_PROBE_N) {
        return;
    }
    /* Y X*: the block's cross-power */
    p->sxy_re += p->yr * p->xr + p->yi * p->xi;
    p->sxy_im += p->yi * p->xr - p->yr * p->xi;
    p->sxx += p->xr * p->xr + p->xi * p->xi;
    p->blocks++;
    p->xr = p->xi = p->yr = p->yi = 0.0;
    p->fill = 0;
}

double sim_phase_probe_rad(const sim_phase_probe_t *p)
{
    return p->blocks > 0 && p->sxx > 0.0 ? atan2(p->sxy_im, p->sxy_re) : NAN;
}

static void add(sim_log_noise_t *n, const sim_log_sample_t *s)
{
    for (int i = 0; i < 3; ++i) {
        sim_spectrum_push(&n->command[i], s->command[i]);
        sim_spectrum_push(&n->gyro[i], s->gyro_rad_s[i]);
        if (n->has & SIM_LOG_HAS_GYRO_RAW) {
            sim_spectrum_push(&n->gyro_raw[i], s->gyro_raw_rad_s[i]);
            sim_phase_probe_push(&n->chain[i], s->gyro_raw_rad_s[i], s->gyro_rad_s[i]);
        }
    }
    for (int m = 0; m < s->n_motors && (n->has & SIM_LOG_HAS_ROTOR_HZ); ++m) {
        if (isfinite(s->rotor_hz[m]) && s->rotor_hz[m] > 0.0) {
            n->rotor_hz_sum += s->rotor_hz[m];
            n->rotor_samples++;
            n->rotors = m + 1 > n->rotors ? m + 1 : n->rotors;
        }
    }
    n->ticks++;
}

int sim_log_noise_measure(const sim_log_options_t *opt, double probe_rad_s, sim_log_noise_t *n, char *err,
                          size_t err_len)
{
    sim_log_error_t lerr;
    sim_log_t *log = sim_log_open(opt, &lerr);
    if (log == NULL) {
        sim_log_error_format(&lerr, err, err_len);
        return -1;
    }
    start(n, sim_log_dt_s(log), sim_log_has(log), probe_rad_s);
    /* a damaged frame's spike would carry the whole spectrum's floor: repaired first */
    sim_log_despike_t *despike = sim_log_despike_new(n->has);
    if (despike == NULL) {
        snprintf(err, err_len, "%s: noise: out of memory", opt->path);
        sim_log_close(log);
        return -1;
    }
    sim_log_sample_t s;
    int rc;
    while ((rc = sim_log_next_repaired(log, despike, &s, &lerr)) == 1) {
        add(n, &s);
    }
    if (rc < 0) {
        sim_log_error_format(&lerr, err, err_len);
    } else {
        sim_log_despike_outliers(despike, &n->outliers);
    }
    sim_log_despike_free(despike);
    sim_log_close(log);
    return rc < 0 ? -1 : 0;
}

double sim_log_noise_command_above(const sim_log_noise_t *n, int axis, double f_lo_hz)
{
    return sim_spectrum_band_rms(&n->command[axis], f_lo_hz, INFINITY);
}

double sim_log_noise_chain_phase_deg(const sim_log_noise_t *n, int axis)
{
    return (n->has & SIM_LOG_HAS_GYRO_RAW) ? -sim_phase_probe_rad(&n->chain[axis]) * RAD2DEG : NAN;
}

double sim_log_noise_chain_delay_s(const sim_log_noise_t *n, int axis)
{
    return sim_phase_delay_s(sim_log_noise_chain_phase_deg(n, axis), n->probe_rad_s);
}

double sim_log_noise_rotor_hz(const sim_log_noise_t *n)
{
    return n->rotor_samples > 0 ? n->rotor_hz_sum / (double)n->rotor_samples : 0.0;
}
