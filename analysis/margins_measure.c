/* SPDX-License-Identifier: BSD-3-Clause */
/* The controller in closed loop on the sampled plant and its measured
 * response: impulse differences of the real code, the integrators' tail
 * fitted, C(z) on the FFT grid (docs/margins.md). */
#include "margins_internal.h"

#include <math.h>
#include <string.h>

/* Perturbations of the measured angle (rad) and rate (rad/s): small against
 * the converged run of an adaptive variant (degrees) and large against float
 * rounding of the command (relative 6e-8), so the differential response is
 * linear and exact to about 1e-4. Linear controllers do not care. */
#define IMPULSE_ANGLE_RAD 1e-3
#define IMPULSE_RATE_RAD_S 1e-2
/* A response has settled when its last eighth stays within this share of its
 * peak around its final value: float rounding of the library leaves 1e-6. */
#define TAIL_SETTLED 1e-3
#define WARMUP_TICKS 4

int margins_ctl_names_axis(const ladrc_margins_controller_t *ctl)
{
    if (ctl == NULL || (ctl->attitude == NULL) == (ctl->axis == NULL))
        return 0;
    return ctl->attitude == NULL || (ctl->axis_index >= 0 && ctl->axis_index < LADRC_AXES);
}

const ladrc_axis_config_t *margins_ctl_axis_config(const ladrc_margins_controller_t *ctl)
{
    return ctl->attitude != NULL ? &ctl->attitude->axis[ctl->axis_index] : ctl->axis;
}

/* The controller's gyro filter on the rate (channel 0) and, with
 * filter_angle, the angle (channel 1), its RPM notches on the rotors' rates. */
static ladrc_margins_status_t filter_init(const ladrc_margins_controller_t *ctl, ladrc_gyro_filter_t *f)
{
    ladrc_gyro_filter_config_t cfg = *ctl->filter;
    cfg.channels = (uint8_t)(ctl->filter_angle ? 2 : 1);
    if (ladrc_gyro_filter_init(f, &cfg) != LADRC_OK)
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (cfg.rpm_rotors > 0u) {
        if (ctl->filter_rotor_hz == NULL || ladrc_gyro_filter_set_rotor_hz(f, ctl->filter_rotor_hz) != LADRC_FAULT_NONE)
            return LADRC_MARGINS_ERR_CONTROLLER;
    }
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t margins_ctl_init(const ladrc_margins_controller_t *ctl, ctl_state_t *s)
{
    /* INDI and RATE-ADRC hold their command without a rate: no loop to analyse. */
    const ladrc_axis_config_t *own =
        (ctl->attitude != NULL)
            ? ((ctl->axis_index >= 0 && ctl->axis_index < LADRC_AXES) ? &ctl->attitude->axis[ctl->axis_index] : NULL)
            : ctl->axis;
    if (own != NULL && (own->variant == LADRC_VARIANT_INDI || own->variant == LADRC_VARIANT_RATE_ADRC) &&
        !ctl->use_rate)
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (ctl->filter != NULL && filter_init(ctl, &s->filter) != LADRC_MARGINS_OK)
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (ctl->attitude != NULL) {
        if (ctl->axis_index < 0 || ctl->axis_index >= LADRC_AXES)
            return LADRC_MARGINS_ERR_CONTROLLER;
        return ladrc_attitude_init(&s->ctl.attitude, ctl->attitude, NULL) == LADRC_OK ? LADRC_MARGINS_OK
                                                                                      : LADRC_MARGINS_ERR_CONTROLLER;
    }
    return ladrc_axis_init(&s->ctl.axis, ctl->axis) == LADRC_OK ? LADRC_MARGINS_OK : LADRC_MARGINS_ERR_CONTROLLER;
}

/* One tick of the real code: torque command (N m). The other axes of an
 * attitude rest at 0, so the coupling products vanish and only this axis's
 * own (drag) feed remains, as in the linearised flight. */
double margins_ctl_step(const ladrc_margins_controller_t *ctl, ctl_state_t *s, double ref_rad, double angle_rad,
                        double rate_rad_s)
{
    if (ctl->filter != NULL) {
        const ladrc_real_t in[2] = {(ladrc_real_t)rate_rad_s, (ladrc_real_t)angle_rad};
        ladrc_real_t out[2] = {in[0], in[1]};
        (void)ladrc_gyro_filter_step(&s->filter, in, out);
        rate_rad_s = (double)out[0];
        if (ctl->filter_angle)
            angle_rad = (double)out[1];
    }
    if (ctl->attitude != NULL) {
        ladrc_real_t ref[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t angle[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t rate[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t torque[LADRC_AXES];
        ref[ctl->axis_index] = (ladrc_real_t)ref_rad;
        angle[ctl->axis_index] = (ladrc_real_t)angle_rad;
        rate[ctl->axis_index] = (ladrc_real_t)rate_rad_s;
        if (ctl->attitude->frame == LADRC_FRAME_QUATERNION) {
            /* the quaternion frame's own path: one axis turned from level */
            const ladrc_quat_t q_ref = ladrc_quat_from_euler(ref[0], ref[1], ref[2]);
            const ladrc_quat_t q_meas = ladrc_quat_from_euler(angle[0], angle[1], angle[2]);
            (void)ladrc_attitude_step_quat(&s->ctl.attitude, &q_ref, &q_meas, ctl->use_rate ? rate : NULL, torque);
        } else {
            (void)ladrc_attitude_step(&s->ctl.attitude, ref, angle, ctl->use_rate ? rate : NULL, torque);
        }
        return (double)torque[ctl->axis_index];
    }
    const ladrc_real_t rate = (ladrc_real_t)rate_rad_s;
    ladrc_real_t torque_Nm;
    (void)ladrc_axis_step(&s->ctl.axis, (ladrc_real_t)ref_rad, (ladrc_real_t)angle_rad, ctl->use_rate ? &rate : NULL,
                          &torque_Nm);
    return (double)torque_Nm;
}

void ladrc_margins_request_default(ladrc_margins_request_t *req, const ladrc_margins_plant_t *plant)
{
    memset(req, 0, sizeof *req);
    if (plant != NULL)
        req->plant = *plant;
    req->response_s = 4.0;
    if (plant != NULL && plant->dt_s > 0.0 && req->response_s / plant->dt_s > (double)N_FFT) {
        req->response_s = (double)N_FFT * plant->dt_s; /* at loop rates above 4 kHz: what the FFT holds */
    }
    req->tone_rad_s = 0.0;
    req->tone_rad_s2 = 20.0;
    req->converge_s = 10.0;
    req->n_starts = 4;
    req->out_min_rad_s = 0.1;
    req->n_out = 200;
    req->track_step_rad = 0.1745; /* 10 deg */
    req->dist_step_rad_s2 = 20.0;
    req->step_window_s = 2.0;
    req->angle_noise_std_rad = 0.0;
    req->rate_noise_std_rad_s = 0.0;
    req->noise_corner_hz = LADRC_MARGINS_NOISE_CORNER_HZ;
}

ladrc_margins_status_t margins_check_request(const ladrc_margins_request_t *req)
{
    const ladrc_margins_status_t st = margins_check_plant(&req->plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    const double taps = req->response_s / req->plant.dt_s;
    if (!(isfinite(req->response_s) && taps >= 16.0 && taps <= (double)N_FFT) || !(req->tone_rad_s >= 0.0) ||
        !isfinite(req->tone_rad_s) || !(req->tone_rad_s2 >= 0.0) || !isfinite(req->tone_rad_s2) ||
        !(req->converge_s >= 0.0 && req->converge_s < 1e5) || req->n_starts < 1 || req->n_starts > 64 ||
        !(req->out_min_rad_s > 0.0 && req->out_min_rad_s < PI / req->plant.dt_s) || req->n_out < 2 ||
        req->n_out > LADRC_MARGINS_MAX_OUT ||
        !(req->track_step_rad >= 0.0 && req->track_step_rad <= LADRC_MARGINS_MAX_STEP_RAD) ||
        !(req->dist_step_rad_s2 >= 0.0) || !isfinite(req->dist_step_rad_s2) ||
        !(req->step_window_s > 0.0 && req->step_window_s <= STEP_WINDOW_MAX_S) || margins_check_noise(req) != 0)
        return LADRC_MARGINS_ERR_REQUEST;
    return LADRC_MARGINS_OK;
}

/* Closed loop of copy[0] on the plant for n ticks under the tone; returns 0
 * if it diverged. */
static int run_closed(const ladrc_margins_controller_t *ctl, ctl_state_t *s, psim_t *ps, const dplant_t *dp,
                      double tone_w, double tone_a, double dt, long k0, long n)
{
    for (long k = k0; k < k0 + n; ++k) {
        double y, r;
        psim_measure(ps, dp, &y, &r);
        const double u = margins_ctl_step(ctl, s, 0.0, y, r);
        psim_step(ps, dp, u, tone_a * sin(tone_w * dt * (double)k));
        if (!(fabs(ps->x[0]) < DIVERGED_RAD))
            return 0;
    }
    return 1;
}

void margins_fft(double *re, double *im, int n)
{
    for (int i = 1, j = 0; i < n; ++i) {
        int bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j) {
            double t = re[i];
            re[i] = re[j];
            re[j] = t;
            t = im[i];
            im[i] = im[j];
            im[j] = t;
        }
    }
    for (int len = 2; len <= n; len <<= 1) {
        const double ang = -2.0 * PI / len;
        for (int i = 0; i < n; i += len) {
            for (int k = 0; k < len / 2; ++k) {
                const double c = cos(ang * k), s = sin(ang * k);
                const int a = i + k, b = i + k + len / 2;
                const double tr = re[b] * c - im[b] * s, ti = re[b] * s + im[b] * c;
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
            }
        }
    }
}

ladrc_margins_status_t ladrc_margins_measure(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                             const ladrc_margins_request_t *req)
{
    if (ws == NULL || ctl == NULL || req == NULL)
        return LADRC_MARGINS_ERR_NULL;
    ws->measured = 0;
    ladrc_margins_status_t st = margins_check_request(req);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (!margins_ctl_names_axis(ctl))
        return LADRC_MARGINS_ERR_CONTROLLER;
    const ladrc_axis_config_t *acfg = margins_ctl_axis_config(ctl);
    if (fabs((double)acfg->dt_s - req->plant.dt_s) > 1e-6 * req->plant.dt_s)
        return LADRC_MARGINS_ERR_DT_S;
    ctl_state_t *s = (ctl_state_t *)(void *)ws->copy;
    st = margins_ctl_init(ctl, &s[0]);
    if (st != LADRC_MARGINS_OK)
        return st;

    const double dt = req->plant.dt_s;
    const int n = (int)(req->response_s / dt + 0.5);
    const int adaptive = is_adaptive(acfg);
    double tone_w = 0.0, tone_a = 0.0;
    int starts = 1;
    long spacing = 0;
    if (adaptive) {
        tone_w = req->tone_rad_s > 0.0 ? req->tone_rad_s : (double)acfg->hp_freq_rad_s[0];
        tone_a = req->tone_rad_s2;
        starts = req->n_starts;
        if (tone_w > 0.0 && tone_a > 0.0) {
            spacing = (long)(2.0 * PI / tone_w / dt / starts + 0.5);
            if (spacing < 1)
                spacing = 1;
        }
    }
    dplant_t dp;
    margins_discretise(&req->plant, &dp);
    psim_t ps;
    psim_reset(&ps);
    /* A few ticks at rest first: a PID differences its angle only from its
     * second sample on, and the impulse must not land on the first. */
    const long n_conv = adaptive ? (long)(req->converge_s / dt + 0.5) + WARMUP_TICKS : WARMUP_TICKS;
    ws->linearised_nominal = 0;
    if (!run_closed(ctl, &s[0], &ps, &dp, tone_w, tone_a, dt, 0, n_conv)) {
        /* No converged state on this plant: linearise on the controller's
         * own model instead (no lag, no delay, true inertia). */
        ladrc_margins_plant_t nominal = req->plant;
        nominal.motor_tau_s = 0.0;
        nominal.delay_ticks = 0;
        margins_discretise(&nominal, &dp);
        (void)margins_ctl_init(ctl, &s[0]);
        psim_reset(&ps);
        ws->linearised_nominal = 1;
        if (!run_closed(ctl, &s[0], &ps, &dp, tone_w, tone_a, dt, 0, n_conv))
            return LADRC_MARGINS_ERR_NOT_SETTLED;
    }
    s[3] = s[0];
    const psim_t ps_saved = ps;
    ws->has_rate = ctl->use_rate;
    memset(ws->h, 0, sizeof ws->h);
    for (int st_i = 0; st_i < starts; ++st_i) {
        s[0] = s[3];
        ps = ps_saved;
        long k = n_conv;
        if (!run_closed(ctl, &s[0], &ps, &dp, tone_w, tone_a, dt, k, spacing * st_i))
            return LADRC_MARGINS_ERR_NOT_SETTLED;
        k += spacing * st_i;
        s[1] = s[0];
        s[2] = s[0];
        for (int i = 0; i < n; ++i, ++k) {
            double y, r;
            psim_measure(&ps, &dp, &y, &r);
            const double u0 = margins_ctl_step(ctl, &s[0], 0.0, y, r);
            const double ua = margins_ctl_step(ctl, &s[1], 0.0, y + (i == 0 ? IMPULSE_ANGLE_RAD : 0.0), r);
            ws->h[0][i] += (ua - u0) / IMPULSE_ANGLE_RAD / starts;
            if (ws->has_rate) {
                const double ur = margins_ctl_step(ctl, &s[2], 0.0, y, r + (i == 0 ? IMPULSE_RATE_RAD_S : 0.0));
                ws->h[1][i] += (ur - u0) / IMPULSE_RATE_RAD_S / starts;
            }
            psim_step(&ps, &dp, u0, tone_a * sin(tone_w * dt * (double)k));
        }
    }
    /* The tail c0 + c1 k (the controller's integrators: one, or two when a
     * disturbance estimate integrates the command, as LP's does on the angle
     * path) by least squares over the last eighth, and how well it fits. */
    const int tail_from = n - n / 8;
    double residue = 0.0;
    for (int p = 0; p < 2; ++p) {
        double sk = 0.0, skk = 0.0, sh = 0.0, skh = 0.0, peak = 0.0;
        const double m = (double)(n - tail_from);
        for (int i = tail_from; i < n; ++i) {
            const double k = (double)i;
            sk += k;
            skk += k * k;
            sh += ws->h[p][i];
            skh += k * ws->h[p][i];
        }
        const double c1 = (m * skh - sk * sh) / (m * skk - sk * sk);
        const double c0 = (sh - c1 * sk) / m;
        for (int i = 0; i < n; ++i)
            peak = fmax(peak, fabs(ws->h[p][i]));
        double dev = 0.0;
        for (int i = tail_from; i < n; ++i)
            dev = fmax(dev, fabs(ws->h[p][i] - c0 - c1 * (double)i));
        ws->tail[p] = c0;
        ws->ramp[p] = c1;
        if (peak > 0.0)
            residue = fmax(residue, dev / peak);
        if (!(peak < INFINITY))
            residue = INFINITY;
    }
    ws->tail_residue = residue;
    ws->n_taps = n;
    ws->dt_s = dt;
    if (!(residue <= TAIL_SETTLED))
        return LADRC_MARGINS_ERR_NOT_SETTLED;
    /* C on the uniform grid w_m = 2 pi m / N_FFT (rad per tick) by one FFT
     * of h - c per response (zero beyond n, N_FFT >= n: no aliasing). */
    for (int p = 0; p < 2; ++p) {
        for (int i = 0; i < N_FFT; ++i) {
            ws->fft_re[i] = (i < n) ? ws->h[p][i] - ws->tail[p] - ws->ramp[p] * (double)i : 0.0;
            ws->fft_im[i] = 0.0;
        }
        margins_fft(ws->fft_re, ws->fft_im, N_FFT);
        for (int m = 1; m <= N_HALF; ++m) {
            const cplx zi = cexp(-I * 2.0 * PI * m / N_FFT);
            const cplx v = ws->fft_re[m] + I * ws->fft_im[m] + tail_at(ws, p, zi);
            ws->grid_re[p][m] = creal(v);
            ws->grid_im[p][m] = cimag(v);
        }
    }
    ws->measured = 1;
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_controller_freq(const ladrc_margins_workspace_t *ws, double w_rad_s, double out[4])
{
    if (ws == NULL || out == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!ws->measured)
        return LADRC_MARGINS_ERR_NOT_MEASURED;
    const cplx z = cexp(I * w_rad_s * ws->dt_s);
    const cplx ca = ctl_at(ws, 0, z);
    const cplx cr = ws->has_rate ? ctl_at(ws, 1, z) : 0.0;
    out[0] = creal(ca);
    out[1] = cimag(ca);
    out[2] = creal(cr);
    out[3] = cimag(cr);
    return LADRC_MARGINS_OK;
}
