/* SPDX-License-Identifier: BSD-3-Clause */
/* The Nyquist contour and the margins of a loop: a measured controller on a
 * plant, or a user function; the analysis entry points and the output grid. */
#include "margins_internal.h"

#include <math.h>
#include <string.h>

/* Radius of the indentation around z = 1 (and lowest frequency of the
 * contour, rad per tick): far below every other pole's distance from z = 1
 * (a drag pole kt T / J is 3e-3 for J = 0.03 kg m^2 at 1 kHz, and a slower
 * one would be a time constant above 1000 s), far above double rounding at
 * |L| ~ eps^-3. */
#define INDENT_EPS 1e-6
/* Points of the indentation quarter-circle and of the log-spaced band from
 * INDENT_EPS to the first FFT bin; the phase of 1 + L is refined wherever
 * two neighbours differ by more than MAX_PHASE_STEP. */
#define INDENT_POINTS 16
#define LOW_POINTS 160
#define MAX_PHASE_STEP (PI / 4.0)
#define MAX_REFINE_DEPTH 24

static cplx loop_with(const loop_t *lp, cplx z, cplx ca, cplx cr)
{
    cplx gu[NX_MAX], gd[NX_MAX];
    margins_plant_solve(&lp->dp, z, gu, gd);
    const cplx late = 1.0 / cpow_int(z, lp->dp.delay);
    return -(ca * gu[0] + cr * gu[1]) * late;
}

static cplx loop_at(const loop_t *lp, cplx z)
{
    if (lp->fn != NULL) {
        double re, im;
        lp->fn(lp->ctx, creal(z), cimag(z), &re, &im);
        return re + I * im;
    }
    const cplx ca = ctl_at(lp->ws, 0, z);
    const cplx cr = lp->ws->has_rate ? ctl_at(lp->ws, 1, z) : 0.0;
    return loop_with(lp, z, ca, cr);
}

/* L at grid bin m (w = 2 pi m / N_FFT per tick), from the cached C. */
static cplx loop_bin(const loop_t *lp, int m)
{
    const cplx z = cexp(I * 2.0 * PI * m / N_FFT);
    if (lp->fn != NULL)
        return loop_at(lp, z);
    const cplx ca = lp->ws->grid_re[0][m] + I * lp->ws->grid_im[0][m];
    const cplx cr = lp->ws->has_rate ? lp->ws->grid_re[1][m] + I * lp->ws->grid_im[1][m] : 0.0;
    return loop_with(lp, z, ca, cr);
}

/* The upper half of the Nyquist contour by a parameter t in [0, 3]:
 * [0, 1] the quarter circle z = 1 + eps e^{j t pi/2} (outside the unit
 * circle, so the poles at z = 1 count as enclosed), [1, 2] the unit circle
 * from w = eps to the first FFT bin (log-spaced), [2, 3] on to w = pi. */
static double bin1(void)
{
    return 2.0 * PI / N_FFT;
}

static cplx contour_z(double t)
{
    if (t <= 1.0)
        return 1.0 + INDENT_EPS * cexp(I * t * PI / 2.0);
    if (t <= 2.0)
        return cexp(I * INDENT_EPS * pow(bin1() / INDENT_EPS, t - 1.0));
    return cexp(I * (bin1() + (PI - bin1()) * (t - 2.0)));
}

/* Phase change of 1 + L from t0 to t1 (values f0, f1), refined by bisection
 * while the step exceeds MAX_PHASE_STEP. */
static double phase_change(const loop_t *lp, double t0, cplx f0, double t1, cplx f1, int depth)
{
    const double d = carg(f1 / f0);
    if (fabs(d) <= MAX_PHASE_STEP || depth >= MAX_REFINE_DEPTH)
        return d;
    const double tm = 0.5 * (t0 + t1);
    const cplx fm = 1.0 + loop_at(lp, contour_z(tm));
    return phase_change(lp, t0, f0, tm, fm, depth + 1) + phase_change(lp, tm, fm, t1, f1, depth + 1);
}

/* Nyquist count: closed-loop poles outside the unit circle (see docs/margins.md). */
static int nyquist(const loop_t *lp)
{
    double total = 0.0;
    double t_prev = 0.0;
    cplx f_prev = 1.0 + loop_at(lp, contour_z(0.0));
    for (int i = 1; i <= INDENT_POINTS + LOW_POINTS; ++i) {
        const double t =
            (i <= INDENT_POINTS) ? (double)i / INDENT_POINTS : 1.0 + (double)(i - INDENT_POINTS) / LOW_POINTS;
        const cplx f = 1.0 + loop_at(lp, contour_z(t));
        total += phase_change(lp, t_prev, f_prev, t, f, 0);
        t_prev = t;
        f_prev = f;
    }
    for (int m = 2; m <= N_HALF; ++m) {
        const double t = 2.0 + (double)(m - 1) / (N_HALF - 1);
        const cplx f = 1.0 + loop_bin(lp, m);
        total += phase_change(lp, t_prev, f_prev, t, f, 0);
        t_prev = t;
        f_prev = f;
    }
    /* Upper half turns by k pi, the whole contour by 2 k pi: k = -Z_out. */
    const long k = lround(total / PI);
    return (int)(k < 0 ? -k : k);
}

/* L at w (rad per tick) on the unit circle. */
static cplx loop_w(const loop_t *lp, double w)
{
    return loop_at(lp, cexp(I * w));
}

/* Bisection on w in [a, b] for g(w) = 0 with a sign change; kind 0: |L| - 1,
 * kind 1: Im L. */
static double cross(const loop_t *lp, double a, double b, int kind)
{
    cplx la = loop_w(lp, a);
    double ga = kind == 0 ? cabs(la) - 1.0 : cimag(la);
    for (int it = 0; it < 50 && b - a > 1e-12 * b; ++it) {
        const double m = 0.5 * (a + b);
        const cplx lm = loop_w(lp, m);
        const double gm = kind == 0 ? cabs(lm) - 1.0 : cimag(lm);
        if ((gm < 0.0) == (ga < 0.0)) {
            a = m;
            ga = gm;
        } else {
            b = m;
        }
    }
    return 0.5 * (a + b);
}

void margins_compute(const loop_t *lp, double dt, ladrc_margins_result_t *res)
{
    res->gm_db = INFINITY;
    res->gm_rad_s = NAN;
    res->gm_low_db = -INFINITY;
    res->pm_deg = INFINITY;
    res->wc_rad_s = NAN;
    res->dm_s = INFINITY;
    res->ms = 0.0;
    const int zout = nyquist(lp);
    res->encirclements = zout;
    res->stable = zout == 0;
    double w_prev = INDENT_EPS;
    cplx l_prev = loop_w(lp, w_prev);
    const int total = LOW_POINTS + N_HALF - 1;
    for (int i = 1; i <= total; ++i) {
        double w;
        cplx l;
        if (i <= LOW_POINTS) {
            w = INDENT_EPS * pow(bin1() / INDENT_EPS, (double)i / LOW_POINTS);
            l = loop_w(lp, w);
        } else {
            const int m = i - LOW_POINTS + 1;
            w = 2.0 * PI * m / N_FFT;
            l = loop_bin(lp, m);
        }
        res->ms = fmax(res->ms, 1.0 / cabs(1.0 + l));
        if ((cabs(l) - 1.0 < 0.0) != (cabs(l_prev) - 1.0 < 0.0)) {
            const double wc = cross(lp, w_prev, w, 0);
            const cplx lc = loop_w(lp, wc);
            const double pm = carg(-lc) * 180.0 / PI;
            if (pm < res->pm_deg) {
                res->pm_deg = pm;
                res->wc_rad_s = wc / dt;
            }
            const double dm = pm > 0.0 ? (pm * PI / 180.0) / (wc / dt) : 0.0;
            res->dm_s = fmin(res->dm_s, dm);
        }
        if ((cimag(l) < 0.0) != (cimag(l_prev) < 0.0) && creal(l) < 0.0 && creal(l_prev) < 0.0) {
            const double wp = cross(lp, w_prev, w, 1);
            const cplx lpc = loop_w(lp, wp);
            if (creal(lpc) < 0.0) {
                const double g = -20.0 * log10(cabs(lpc));
                if (g >= 0.0 && g < res->gm_db) {
                    res->gm_db = g;
                    res->gm_rad_s = wp / dt;
                } else if (g < 0.0 && g > res->gm_low_db) {
                    res->gm_low_db = g;
                }
            }
        }
        w_prev = w;
        l_prev = l;
    }
    res->dm_ticks = res->dm_s / dt;
    res->ms_db = 20.0 * log10(res->ms);
}

void ladrc_margins_of_loop(ladrc_margins_loop_fn fn, void *ctx, double dt_s, ladrc_margins_result_t *res)
{
    loop_t lp;
    memset(&lp, 0, sizeof lp);
    lp.fn = fn;
    lp.ctx = ctx;
    memset(res, 0, sizeof *res);
    margins_compute(&lp, dt_s, res);
    res->dist_peak_rad = NAN;
    res->dist_peak_rad_s = NAN;
}

ladrc_margins_status_t margins_make_loop(const ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                         loop_t *lp)
{
    if (ws == NULL || plant == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!ws->measured)
        return LADRC_MARGINS_ERR_NOT_MEASURED;
    const ladrc_margins_status_t st = margins_check_plant(plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (fabs(plant->dt_s - ws->dt_s) > 1e-9 * ws->dt_s)
        return LADRC_MARGINS_ERR_DT_S;
    memset(lp, 0, sizeof *lp);
    lp->ws = ws;
    margins_discretise(plant, &lp->dp);
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_loop(ladrc_margins_workspace_t *ws, const ladrc_margins_request_t *req,
                                          ladrc_margins_result_t *res)
{
    if (req == NULL || res == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    ladrc_margins_status_t st = margins_make_loop(ws, &req->plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (margins_check_request(req) != LADRC_MARGINS_OK)
        return LADRC_MARGINS_ERR_REQUEST;
    memset(res, 0, sizeof *res);
    const double dt = req->plant.dt_s;
    margins_compute(&lp, dt, res);
    res->tail_residue = ws->tail_residue;
    res->linearised_nominal = ws->linearised_nominal;
    res->cmd_noise_Nm = margins_cmd_noise(&lp, req);
    /* Output grid, log-spaced up to the Nyquist frequency. */
    const double w_hi = PI / dt;
    res->n_out = req->n_out;
    res->dist_peak_rad = 0.0;
    res->dist_peak_rad_s = NAN;
    for (int i = 0; i < req->n_out; ++i) {
        const double w = req->out_min_rad_s * pow(w_hi / req->out_min_rad_s, (double)i / (req->n_out - 1));
        const cplx z = cexp(I * w * dt);
        const cplx ca = ctl_at(ws, 0, z);
        const cplx cr = ws->has_rate ? ctl_at(ws, 1, z) : 0.0;
        cplx gu[NX_MAX], gd[NX_MAX];
        margins_plant_solve(&lp.dp, z, gu, gd);
        const cplx late = 1.0 / cpow_int(z, lp.dp.delay);
        const cplx l = -(ca * gu[0] + cr * gu[1]) * late;
        const cplx sens = 1.0 / (1.0 + l);
        /* angle = Gd d + Gu u, u = late (Ca angle + Cr rate): error = -angle */
        const cplx u_per_d = late * (ca * gd[0] + cr * gd[1]) * sens;
        const cplx err = -(gd[0] + gu[0] * u_per_d);
        res->w_rad_s[i] = w;
        res->l_re[i] = creal(l);
        res->l_im[i] = cimag(l);
        res->s_re[i] = creal(sens);
        res->s_im[i] = cimag(sens);
        res->de_re[i] = creal(err);
        res->de_im[i] = cimag(err);
        if (cabs(err) > res->dist_peak_rad) {
            res->dist_peak_rad = cabs(err);
            res->dist_peak_rad_s = w;
        }
    }
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_analyse(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                             const ladrc_margins_request_t *req, ladrc_margins_result_t *res)
{
    const ladrc_margins_status_t st = ladrc_margins_measure(ws, ctl, req);
    return st != LADRC_MARGINS_OK ? st : ladrc_margins_loop(ws, req, res);
}

int ladrc_margins_is_stable(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant)
{
    loop_t lp;
    if (margins_make_loop(ws, plant, &lp) != LADRC_MARGINS_OK)
        return 0;
    return nyquist(&lp) == 0;
}

ladrc_margins_status_t ladrc_margins_analyse_reported(ladrc_margins_workspace_t *ws,
                                                      const ladrc_margins_controller_t *ctl,
                                                      const ladrc_margins_request_t *req, ladrc_margins_result_t *res,
                                                      int *idle)
{
    if (idle != NULL)
        *idle = 0;
    if (margins_ctl_names_axis(ctl)) {
        const ladrc_axis_config_t *a = margins_ctl_axis_config(ctl);
        if (a->variant == LADRC_VARIANT_HP_MLADRC && a->hp_sample == LADRC_HP_SAMPLE_GYRO) {
            /* HP-MLADRC on the gyro is LP-MLADRC until its gate engages on a
             * steady tone, and lets go at any change: its margins are that
             * LP-MLADRC's, its estimator idle. */
            ladrc_attitude_config_t att;
            ladrc_axis_config_t axis;
            ladrc_margins_controller_t as_lp = *ctl;
            if (ctl->attitude != NULL) {
                att = *ctl->attitude;
                att.axis[ctl->axis_index].variant = LADRC_VARIANT_LP_MLADRC;
                as_lp.attitude = &att;
            } else {
                axis = *ctl->axis;
                axis.variant = LADRC_VARIANT_LP_MLADRC;
                as_lp.axis = &axis;
            }
            if (idle != NULL)
                *idle = 1;
            return ladrc_margins_analyse(ws, &as_lp, req, res);
        }
    }
    ladrc_margins_status_t st = ladrc_margins_analyse(ws, ctl, req, res);
    if (st == LADRC_MARGINS_ERR_NOT_SETTLED && req != NULL && margins_ctl_names_axis(ctl) &&
        margins_ctl_axis_config(ctl)->variant == LADRC_VARIANT_HP_MLADRC) {
        ladrc_margins_request_t quiet = *req;
        quiet.tone_rad_s2 = 0.0;
        st = ladrc_margins_analyse(ws, ctl, &quiet, res);
        if (idle != NULL)
            *idle = st == LADRC_MARGINS_OK;
    }
    return st;
}
