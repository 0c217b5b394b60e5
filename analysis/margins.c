/* SPDX-License-Identifier: BSD-3-Clause */
/* Stability margins of a configured axis on a sampled airframe (margins.h,
 * docs/margins.md). Double precision; no heap, no stdio. */
#include "ladrc/margins.h"

#include <complex.h>
#include <math.h>
#include <string.h>

typedef double complex cplx;

#define PI 3.14159265358979323846
#define N_FFT LADRC_MARGINS_MAX_TAPS
#define N_HALF (LADRC_MARGINS_MAX_TAPS / 2)

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
/* Perturbations of the measured angle (rad) and rate (rad/s): small against
 * the converged run of an adaptive variant (degrees) and large against float
 * rounding of the command (relative 6e-8), so the differential response is
 * linear and exact to about 1e-4. Linear controllers do not care. */
#define IMPULSE_ANGLE_RAD 1e-3
#define IMPULSE_RATE_RAD_S 1e-2
/* A response has settled when its last eighth stays within this share of its
 * peak around its final value: float rounding of the library leaves 1e-6. */
#define TAIL_SETTLED 1e-3
/* Divergence of a converged run: beyond a radian the small-angle loop is
 * meaningless. */
#define DIVERGED_RAD 1.0
#define WARMUP_TICKS 4
/* Simulated check: an angle below this share of its peak has decayed to
 * the float controller's rounding. */
#define SIM_DECAYED 1e-6

const char *ladrc_margins_status_str(ladrc_margins_status_t status)
{
    switch (status) {
    case LADRC_MARGINS_OK:
        return "LADRC_MARGINS_OK: success";
    case LADRC_MARGINS_ERR_NULL:
        return "LADRC_MARGINS_ERR_NULL: a required pointer is NULL";
    case LADRC_MARGINS_ERR_DT_S:
        return "LADRC_MARGINS_ERR_DT_S: plant dt_s not > 0 or not the controller's";
    case LADRC_MARGINS_ERR_INERTIA:
        return "LADRC_MARGINS_ERR_INERTIA: inertia or inertia factor not finite and > 0";
    case LADRC_MARGINS_ERR_DRAG:
        return "LADRC_MARGINS_ERR_DRAG: drag_Nm_s not finite and >= 0";
    case LADRC_MARGINS_ERR_MOTOR_TAU:
        return "LADRC_MARGINS_ERR_MOTOR_TAU: motor_tau_s not finite and >= 0";
    case LADRC_MARGINS_ERR_DELAY:
        return "LADRC_MARGINS_ERR_DELAY: delay_ticks outside 0..64";
    case LADRC_MARGINS_ERR_CONTROLLER:
        return "LADRC_MARGINS_ERR_CONTROLLER: the controller config is refused";
    case LADRC_MARGINS_ERR_REQUEST:
        return "LADRC_MARGINS_ERR_REQUEST: invalid tone, response length or grid";
    case LADRC_MARGINS_ERR_NOT_SETTLED:
        return "LADRC_MARGINS_ERR_NOT_SETTLED: the controller's response did not settle within response_s";
    case LADRC_MARGINS_ERR_NOT_MEASURED:
        return "LADRC_MARGINS_ERR_NOT_MEASURED: no controller measured";
    case LADRC_MARGINS_ERR_TARGETS_NOT_MET:
        return "LADRC_MARGINS_ERR_TARGETS_NOT_MET: no setting meets the targets";
    }
    return "LADRC_MARGINS_ERR_?: unknown status";
}

/* ---------------------------------------------------------------- plant */

#define NX_MAX 3 /* angle, rate, lagged torque */

typedef struct {
    int n;                                          /* 2 without lag, 3 with */
    int delay;                                      /* ticks */
    double j_kg_m2;                                 /* true inertia */
    double a[NX_MAX][NX_MAX], b[NX_MAX], e[NX_MAX]; /* x+ = A x + B u + E d */
} dplant_t;

static ladrc_margins_status_t check_plant(const ladrc_margins_plant_t *p)
{
    if (p == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!(isfinite(p->dt_s) && p->dt_s > 0.0))
        return LADRC_MARGINS_ERR_DT_S;
    if (!(isfinite(p->inertia_kg_m2) && p->inertia_kg_m2 > 0.0 && isfinite(p->inertia_factor) &&
          p->inertia_factor > 0.0))
        return LADRC_MARGINS_ERR_INERTIA;
    if (!(isfinite(p->drag_Nm_s) && p->drag_Nm_s >= 0.0))
        return LADRC_MARGINS_ERR_DRAG;
    if (!(isfinite(p->motor_tau_s) && p->motor_tau_s >= 0.0))
        return LADRC_MARGINS_ERR_MOTOR_TAU;
    if (p->delay_ticks < 0 || p->delay_ticks > LADRC_MARGINS_MAX_DELAY)
        return LADRC_MARGINS_ERR_DELAY;
    return LADRC_MARGINS_OK;
}

#define NM (NX_MAX + 2)

static void mat_mul(int n, double x[NM][NM], double y[NM][NM], double out[NM][NM])
{
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            double s = 0.0;
            for (int k = 0; k < n; ++k)
                s += x[i][k] * y[k][j];
            out[i][j] = s;
        }
    }
}

/* exp(m) by scaling and squaring of a Taylor series (n <= NM; the norm is
 * scaled below 0.5, where 20 terms leave 1e-26). */
static void mat_exp(int n, double m[NM][NM], double out[NM][NM])
{
    double norm = 0.0;
    for (int j = 0; j < n; ++j) {
        double col = 0.0;
        for (int i = 0; i < n; ++i)
            col += fabs(m[i][j]);
        if (col > norm)
            norm = col;
    }
    int squarings = 0;
    double scale = 1.0;
    while (norm * scale > 0.5 && squarings < 60) {
        scale *= 0.5;
        ++squarings;
    }
    double x[NM][NM], term[NM][NM], tmp[NM][NM];
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            x[i][j] = m[i][j] * scale;
            out[i][j] = (i == j) ? 1.0 : 0.0;
            term[i][j] = (i == j) ? 1.0 : 0.0;
        }
    }
    for (int k = 1; k <= 20; ++k) {
        mat_mul(n, term, x, tmp);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
                term[i][j] = tmp[i][j] / k;
                out[i][j] += term[i][j];
            }
        }
    }
    for (int s = 0; s < squarings; ++s) {
        mat_mul(n, out, out, tmp);
        memcpy(out, tmp, sizeof tmp);
    }
}

/* Exact ZOH discretisation of [A B E] (u and d held over the tick). */
static void discretise(const ladrc_margins_plant_t *p, dplant_t *dp)
{
    const double j = p->inertia_kg_m2 * p->inertia_factor;
    const int lag = p->motor_tau_s > 0.0;
    const int n = lag ? 3 : 2;
    double m[NM][NM];
    memset(m, 0, sizeof m);
    /* states: 0 angle, 1 rate, 2 lagged torque; inputs n: u, n + 1: d */
    m[0][1] = 1.0;
    m[1][1] = -p->drag_Nm_s / j;
    m[1][n + 1] = 1.0;
    if (lag) {
        m[1][2] = 1.0 / j;
        m[2][2] = -1.0 / p->motor_tau_s;
        m[2][n] = 1.0 / p->motor_tau_s;
    } else {
        m[1][n] = 1.0 / j;
    }
    for (int r = 0; r < n + 2; ++r) {
        for (int c = 0; c < n + 2; ++c)
            m[r][c] *= p->dt_s;
    }
    double ex[NM][NM];
    mat_exp(n + 2, m, ex);
    memset(dp, 0, sizeof *dp);
    dp->n = n;
    dp->delay = p->delay_ticks;
    dp->j_kg_m2 = j;
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c)
            dp->a[r][c] = ex[r][c];
        dp->b[r] = ex[r][n];
        dp->e[r] = ex[r][n + 1];
    }
}

/* (zI - A)^-1 [B E]: g[0..n-1] the state response to u, g[NX_MAX..] to d
 * (Gaussian elimination with partial pivoting). */
static void plant_solve(const dplant_t *dp, cplx z, cplx gu[NX_MAX], cplx gd[NX_MAX])
{
    const int n = dp->n;
    cplx m[NX_MAX][NX_MAX + 2];
    for (int r = 0; r < n; ++r) {
        for (int c = 0; c < n; ++c)
            m[r][c] = ((r == c) ? z : 0.0) - dp->a[r][c];
        m[r][n] = dp->b[r];
        m[r][n + 1] = dp->e[r];
    }
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r) {
            if (cabs(m[r][c]) > cabs(m[piv][c]))
                piv = r;
        }
        if (piv != c) {
            for (int k = 0; k < n + 2; ++k) {
                const cplx t = m[c][k];
                m[c][k] = m[piv][k];
                m[piv][k] = t;
            }
        }
        for (int r = c + 1; r < n; ++r) {
            const cplx f = m[r][c] / m[c][c];
            for (int k = c; k < n + 2; ++k)
                m[r][k] -= f * m[c][k];
        }
    }
    for (int r = n - 1; r >= 0; --r) {
        cplx su = m[r][n], sd = m[r][n + 1];
        for (int k = r + 1; k < n; ++k) {
            su -= m[r][k] * gu[k];
            sd -= m[r][k] * gd[k];
        }
        gu[r] = su / m[r][r];
        gd[r] = sd / m[r][r];
    }
}

static cplx cpow_int(cplx z, int k)
{
    cplx r = 1.0;
    for (int i = 0; i < k; ++i)
        r *= z;
    return r;
}

ladrc_margins_status_t ladrc_margins_plant_freq(const ladrc_margins_plant_t *plant, double w_rad_s, double out[4])
{
    const ladrc_margins_status_t st = check_plant(plant);
    if (st != LADRC_MARGINS_OK || out == NULL)
        return st != LADRC_MARGINS_OK ? st : LADRC_MARGINS_ERR_NULL;
    dplant_t dp;
    discretise(plant, &dp);
    const cplx z = cexp(I * w_rad_s * plant->dt_s);
    cplx gu[NX_MAX], gd[NX_MAX];
    plant_solve(&dp, z, gu, gd);
    const cplx late = 1.0 / cpow_int(z, dp.delay);
    out[0] = creal(gu[0] * late);
    out[1] = cimag(gu[0] * late);
    out[2] = creal(gu[1] * late);
    out[3] = cimag(gu[1] * late);
    return LADRC_MARGINS_OK;
}

/* ----------------------------------------------------------- controller */

typedef union {
    ladrc_axis_t axis;
    ladrc_attitude_t attitude;
} ctl_state_t;

static const ladrc_axis_config_t *ctl_axis_config(const ladrc_margins_controller_t *ctl)
{
    return ctl->attitude != NULL ? &ctl->attitude->axis[ctl->axis_index] : ctl->axis;
}

static ladrc_margins_status_t ctl_init(const ladrc_margins_controller_t *ctl, ctl_state_t *s)
{
    /* INDI holds its command without a rate: no loop to analyse. */
    const ladrc_axis_config_t *own =
        (ctl->attitude != NULL)
            ? ((ctl->axis_index >= 0 && ctl->axis_index < LADRC_AXES) ? &ctl->attitude->axis[ctl->axis_index] : NULL)
            : ctl->axis;
    if (own != NULL && own->variant == LADRC_VARIANT_INDI && !ctl->use_rate)
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (ctl->attitude != NULL) {
        if (ctl->axis_index < 0 || ctl->axis_index >= LADRC_AXES)
            return LADRC_MARGINS_ERR_CONTROLLER;
        return ladrc_attitude_init(&s->attitude, ctl->attitude, NULL) == LADRC_OK ? LADRC_MARGINS_OK
                                                                                  : LADRC_MARGINS_ERR_CONTROLLER;
    }
    return ladrc_axis_init(&s->axis, ctl->axis) == LADRC_OK ? LADRC_MARGINS_OK : LADRC_MARGINS_ERR_CONTROLLER;
}

/* One tick of the real code at reference 0: torque command (N m). The other
 * axes of an attitude rest at 0, so the coupling products vanish and only
 * this axis's own (drag) feed remains, as in the linearised flight. */
static double ctl_step(const ladrc_margins_controller_t *ctl, ctl_state_t *s, double angle_rad, double rate_rad_s)
{
    if (ctl->attitude != NULL) {
        const ladrc_real_t ref[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t angle[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t rate[LADRC_AXES] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
        ladrc_real_t torque[LADRC_AXES];
        angle[ctl->axis_index] = (ladrc_real_t)angle_rad;
        rate[ctl->axis_index] = (ladrc_real_t)rate_rad_s;
        (void)ladrc_attitude_step(&s->attitude, ref, angle, ctl->use_rate ? rate : NULL, torque);
        return (double)torque[ctl->axis_index];
    }
    const ladrc_real_t rate = (ladrc_real_t)rate_rad_s;
    ladrc_real_t torque_Nm;
    (void)ladrc_axis_step(&s->axis, LADRC_R(0.0), (ladrc_real_t)angle_rad, ctl->use_rate ? &rate : NULL, &torque_Nm);
    return (double)torque_Nm;
}

/* The discrete plant in the time domain with its measurement delay line. */
typedef struct {
    double x[NX_MAX];
    double hist[LADRC_MARGINS_MAX_DELAY + 1][2];
    int head;
} psim_t;

static void psim_reset(psim_t *ps)
{
    memset(ps, 0, sizeof *ps);
}

/* Measurement of this tick: the state delay ticks ago. */
static void psim_measure(psim_t *ps, const dplant_t *dp, double *angle, double *rate)
{
    const int len = LADRC_MARGINS_MAX_DELAY + 1;
    ps->hist[ps->head][0] = ps->x[0];
    ps->hist[ps->head][1] = ps->x[1];
    const int idx = (ps->head - dp->delay + len) % len;
    *angle = ps->hist[idx][0];
    *rate = ps->hist[idx][1];
    ps->head = (ps->head + 1) % len;
}

static void psim_step(psim_t *ps, const dplant_t *dp, double u, double d)
{
    double nx[NX_MAX];
    for (int r = 0; r < dp->n; ++r) {
        double s = dp->b[r] * u + dp->e[r] * d;
        for (int c = 0; c < dp->n; ++c)
            s += dp->a[r][c] * ps->x[c];
        nx[r] = s;
    }
    memcpy(ps->x, nx, sizeof nx);
}

static int is_adaptive(const ladrc_axis_config_t *a)
{
    return a->variant == LADRC_VARIANT_LP_MLADRC || a->variant == LADRC_VARIANT_HP_MLADRC;
}

void ladrc_margins_request_default(ladrc_margins_request_t *req, const ladrc_margins_plant_t *plant)
{
    memset(req, 0, sizeof *req);
    if (plant != NULL)
        req->plant = *plant;
    req->response_s = 4.0;
    req->tone_rad_s = 0.0;
    req->tone_rad_s2 = 20.0;
    req->converge_s = 10.0;
    req->n_starts = 4;
    req->out_min_rad_s = 0.1;
    req->n_out = 200;
}

static ladrc_margins_status_t check_request(const ladrc_margins_request_t *req)
{
    const ladrc_margins_status_t st = check_plant(&req->plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    const double taps = req->response_s / req->plant.dt_s;
    if (!(isfinite(req->response_s) && taps >= 16.0 && taps <= (double)N_FFT) || !(req->tone_rad_s >= 0.0) ||
        !isfinite(req->tone_rad_s) || !(req->tone_rad_s2 >= 0.0) || !isfinite(req->tone_rad_s2) ||
        !(req->converge_s >= 0.0 && req->converge_s < 1e5) || req->n_starts < 1 || req->n_starts > 64 ||
        !(req->out_min_rad_s > 0.0 && req->out_min_rad_s < PI / req->plant.dt_s) || req->n_out < 2 ||
        req->n_out > LADRC_MARGINS_MAX_OUT)
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
        const double u = ctl_step(ctl, s, y, r);
        psim_step(ps, dp, u, tone_a * sin(tone_w * dt * (double)k));
        if (!(fabs(ps->x[0]) < DIVERGED_RAD))
            return 0;
    }
    return 1;
}

/* Radix-2 FFT in place (n a power of 2), forward: X_m = sum x_k e^{-j 2 pi m k / n}. */
static void fft(double *re, double *im, int n)
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

/* The tail's transform: sum_k (c0 + c1 k) z^-k = c0 / (1 - z^-1) + c1 z^-1 / (1 - z^-1)^2. */
static cplx tail_at(const ladrc_margins_workspace_t *ws, int p, cplx zi)
{
    const cplx one_minus = 1.0 - zi;
    return ws->tail[p] / one_minus + ws->ramp[p] * zi / (one_minus * one_minus);
}

/* C(z) of response p: sum (h_k - c0 - c1 k) z^-k (Horner in z^-1) + the tail's. */
static cplx ctl_at(const ladrc_margins_workspace_t *ws, int p, cplx z)
{
    const cplx zi = 1.0 / z;
    cplx acc = 0.0;
    for (int k = ws->n_taps - 1; k >= 0; --k)
        acc = acc * zi + (ws->h[p][k] - ws->tail[p] - ws->ramp[p] * (double)k);
    return acc + tail_at(ws, p, zi);
}

ladrc_margins_status_t ladrc_margins_measure(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                             const ladrc_margins_request_t *req)
{
    if (ws == NULL || ctl == NULL || req == NULL)
        return LADRC_MARGINS_ERR_NULL;
    ws->measured = 0;
    ladrc_margins_status_t st = check_request(req);
    if (st != LADRC_MARGINS_OK)
        return st;
    if ((ctl->attitude == NULL) == (ctl->axis == NULL))
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (ctl->attitude != NULL && (ctl->axis_index < 0 || ctl->axis_index >= LADRC_AXES))
        return LADRC_MARGINS_ERR_CONTROLLER;
    const ladrc_axis_config_t *acfg = ctl_axis_config(ctl);
    if (fabs((double)acfg->dt_s - req->plant.dt_s) > 1e-6 * req->plant.dt_s)
        return LADRC_MARGINS_ERR_DT_S;
    ctl_state_t *s = (ctl_state_t *)(void *)ws->copy;
    st = ctl_init(ctl, &s[0]);
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
    discretise(&req->plant, &dp);
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
        discretise(&nominal, &dp);
        (void)ctl_init(ctl, &s[0]);
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
            const double u0 = ctl_step(ctl, &s[0], y, r);
            const double ua = ctl_step(ctl, &s[1], y + (i == 0 ? IMPULSE_ANGLE_RAD : 0.0), r);
            ws->h[0][i] += (ua - u0) / IMPULSE_ANGLE_RAD / starts;
            if (ws->has_rate) {
                const double ur = ctl_step(ctl, &s[2], y, r + (i == 0 ? IMPULSE_RATE_RAD_S : 0.0));
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
        fft(ws->fft_re, ws->fft_im, N_FFT);
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

/* ----------------------------------------------------------------- loop */

/* Anything that gives L at a complex z, with a fast path on the FFT grid. */
typedef struct {
    /* measured controller on a plant */
    const ladrc_margins_workspace_t *ws;
    dplant_t dp;
    /* or a user function */
    ladrc_margins_loop_fn fn;
    void *ctx;
} loop_t;

static cplx loop_with(const loop_t *lp, cplx z, cplx ca, cplx cr)
{
    cplx gu[NX_MAX], gd[NX_MAX];
    plant_solve(&lp->dp, z, gu, gd);
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

static void margins(const loop_t *lp, double dt, ladrc_margins_result_t *res)
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
    margins(&lp, dt_s, res);
    res->dist_peak_rad = NAN;
    res->dist_peak_rad_s = NAN;
}

static ladrc_margins_status_t make_loop(const ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                        loop_t *lp)
{
    if (ws == NULL || plant == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!ws->measured)
        return LADRC_MARGINS_ERR_NOT_MEASURED;
    const ladrc_margins_status_t st = check_plant(plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (fabs(plant->dt_s - ws->dt_s) > 1e-9 * ws->dt_s)
        return LADRC_MARGINS_ERR_DT_S;
    memset(lp, 0, sizeof *lp);
    lp->ws = ws;
    discretise(plant, &lp->dp);
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_loop(ladrc_margins_workspace_t *ws, const ladrc_margins_request_t *req,
                                          ladrc_margins_result_t *res)
{
    if (req == NULL || res == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    ladrc_margins_status_t st = make_loop(ws, &req->plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (check_request(req) != LADRC_MARGINS_OK)
        return LADRC_MARGINS_ERR_REQUEST;
    memset(res, 0, sizeof *res);
    const double dt = req->plant.dt_s;
    margins(&lp, dt, res);
    res->tail_residue = ws->tail_residue;
    res->linearised_nominal = ws->linearised_nominal;
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
        plant_solve(&lp.dp, z, gu, gd);
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
    if (make_loop(ws, plant, &lp) != LADRC_MARGINS_OK)
        return 0;
    return nyquist(&lp) == 0;
}

ladrc_margins_status_t ladrc_margins_max_motor_tau(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                                   double tau_max_s, double *tau_s)
{
    if (tau_s == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    const ladrc_margins_status_t st = make_loop(ws, plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (!(tau_max_s > 0.0 && isfinite(tau_max_s)))
        return LADRC_MARGINS_ERR_MOTOR_TAU;
    ladrc_margins_plant_t p = *plant;
    p.motor_tau_s = 0.0;
    if (!ladrc_margins_is_stable(ws, &p)) {
        *tau_s = 0.0;
        return LADRC_MARGINS_OK;
    }
    /* The first unstable lag by doubling from a tenth of a tick, then bisection. */
    double lo = 0.0, hi = 0.1 * plant->dt_s;
    for (;;) {
        p.motor_tau_s = hi;
        if (!ladrc_margins_is_stable(ws, &p))
            break;
        lo = hi;
        if (hi >= tau_max_s) {
            *tau_s = tau_max_s;
            return LADRC_MARGINS_OK;
        }
        hi = fmin(2.0 * hi, tau_max_s);
    }
    while (hi - lo > 1e-3 * hi) {
        p.motor_tau_s = 0.5 * (lo + hi);
        if (ladrc_margins_is_stable(ws, &p)) {
            lo = p.motor_tau_s;
        } else {
            hi = p.motor_tau_s;
        }
    }
    *tau_s = lo;
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_max_delay(ladrc_margins_workspace_t *ws, const ladrc_margins_plant_t *plant,
                                               int *ticks)
{
    if (ticks == NULL)
        return LADRC_MARGINS_ERR_NULL;
    loop_t lp;
    const ladrc_margins_status_t st = make_loop(ws, plant, &lp);
    if (st != LADRC_MARGINS_OK)
        return st;
    ladrc_margins_plant_t p = *plant;
    *ticks = -1;
    for (int d = 0; d <= LADRC_MARGINS_MAX_DELAY; ++d) {
        p.delay_ticks = d;
        if (!ladrc_margins_is_stable(ws, &p))
            return LADRC_MARGINS_OK;
        *ticks = d;
    }
    return LADRC_MARGINS_OK;
}

ladrc_margins_status_t ladrc_margins_simulate(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                              const ladrc_margins_plant_t *plant, long n_ticks, double *growth)
{
    if (ws == NULL || ctl == NULL || plant == NULL || growth == NULL)
        return LADRC_MARGINS_ERR_NULL;
    ladrc_margins_status_t st = check_plant(plant);
    if (st != LADRC_MARGINS_OK)
        return st;
    if ((ctl->attitude == NULL) == (ctl->axis == NULL) || n_ticks < 64)
        return LADRC_MARGINS_ERR_REQUEST;
    ctl_state_t *s = (ctl_state_t *)(void *)ws->copy;
    st = ctl_init(ctl, &s[0]);
    if (st != LADRC_MARGINS_OK)
        return st;
    dplant_t dp;
    discretise(plant, &dp);
    psim_t ps;
    psim_reset(&ps);
    /* A 10 ms pulse of 1 rad/s^2: a small step of the rate, all frequencies excited. */
    const long pulse = (long)(0.01 / plant->dt_s + 0.5) + 1;
    double third = 0.0, last = 0.0, peak = 0.0;
    for (long k = 0; k < n_ticks; ++k) {
        double y, r;
        psim_measure(&ps, &dp, &y, &r);
        const double u = ctl_step(ctl, &s[0], y, r);
        psim_step(&ps, &dp, u, k < pulse ? 1.0 : 0.0);
        const double a = fabs(ps.x[0]);
        if (!(a < DIVERGED_RAD)) {
            /* From a 1e-5 rad pulse response: diverged (beyond, the torque
             * limits would turn the growth into a bounded limit cycle). */
            last = INFINITY;
            break;
        }
        peak = fmax(peak, a);
        if (k >= n_ticks / 2 && k < n_ticks - n_ticks / 4)
            third = fmax(third, a);
        if (k >= n_ticks - n_ticks / 4)
            last = fmax(last, a);
    }
    /* Consecutive quarters: in the end the slowest mode dominates, growing
     * (> 1) or decaying (< 1); a response decayed to the float controller's
     * rounding (1e-7 of its peak) counts as decayed whatever its ratio. */
    const double floor_level = SIM_DECAYED * peak;
    *growth = (last <= floor_level) ? 0.0 : last / fmax(third, floor_level);
    return LADRC_MARGINS_OK;
}

/* --------------------------------------------------------------- tuning */

typedef struct {
    ladrc_margins_workspace_t *ws;
    ladrc_margins_controller_t ctl;
    ladrc_attitude_config_t att;
    ladrc_axis_config_t axis;
    const ladrc_margins_request_t *req;
    const ladrc_margins_targets_t *tg;
} tuner_t;

static ladrc_axis_config_t *tuner_axis(tuner_t *t)
{
    return t->ctl.attitude != NULL ? &t->att.axis[t->ctl.axis_index] : &t->axis;
}

/* Sets the candidate's gains from the search parameters (w, shape index). */
static void set_gains(tuner_t *t, double w, int shape, double j_model)
{
    static const double ratios[] = {3.0, 5.0, 8.0};
    static const double integral[] = {3.0, 5.0, 10.0};
    static const double separation[] = {3.0, 4.0, 6.0};
    ladrc_axis_config_t *a = tuner_axis(t);
    if (a->variant == LADRC_VARIANT_INDI) {
        /* The LADRC rule with the acceleration filter in the observer's
         * place: loop (s + w)^2, w_f = r w (at most 0.9 pi / dt). */
        const double wf_max = 0.9 * PI / (double)a->dt_s;
        a->indi_att_kp_per_s = (ladrc_real_t)w;
        a->indi_rate_kp_per_s = (ladrc_real_t)w;
        a->indi_filter_rad_s = (ladrc_real_t)fmin(ratios[shape] * w, wf_max);
    } else if (a->variant == LADRC_VARIANT_CASCADED) {
        /* w: the rate loop's crossover; the default's rule (axis.h) with
         * the attitude gain w / n, n the cascade's separation */
        const double kp = j_model * w;
        const double tf = 1.0 / (8.0 * w);
        a->cas_rate_kp = (ladrc_real_t)kp;
        a->cas_rate_ki = (ladrc_real_t)(kp * w / 5.0);
        a->cas_rate_kd = (ladrc_real_t)(kp / (4.0 * w));
        a->cas_att_kp = (ladrc_real_t)(w / separation[shape]);
        a->cas_d_filter_tau_s = (ladrc_real_t)(tf >= (double)a->dt_s ? tf : 0.0);
        a->cas_rate_filter_tau_s = a->cas_d_filter_tau_s;
    } else if (a->variant == LADRC_VARIANT_PID) {
        a->pid_kp = (ladrc_real_t)(j_model * w * w);
        a->pid_kd = (ladrc_real_t)(2.0 * j_model * w);
        a->pid_ki = (ladrc_real_t)(j_model * w * w * w / integral[shape]);
        const double tf = 1.0 / (10.0 * w);
        a->pid_d_filter_tau_s = (ladrc_real_t)(tf >= (double)a->dt_s ? tf : 0.0);
    } else {
        a->wc_rad_s = (ladrc_real_t)w;
        a->wo_rad_s = (ladrc_real_t)(ratios[shape] * w);
    }
}

static int n_shapes(void)
{
    return 3;
}

/* 1 when a result meets the targets: stable, PM and both gain margins. */
static int meets(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg)
{
    return res->stable && res->pm_deg >= tg->pm_min_deg && res->gm_db >= tg->gm_min_db &&
           res->gm_low_db <= -tg->gm_min_db;
}

ladrc_margins_status_t ladrc_margins_analyse_reported(ladrc_margins_workspace_t *ws,
                                                      const ladrc_margins_controller_t *ctl,
                                                      const ladrc_margins_request_t *req, ladrc_margins_result_t *res,
                                                      int *idle)
{
    if (idle != NULL)
        *idle = 0;
    ladrc_margins_status_t st = ladrc_margins_analyse(ws, ctl, req, res);
    if (st == LADRC_MARGINS_ERR_NOT_SETTLED && ctl != NULL && req != NULL &&
        (ctl->attitude != NULL || ctl->axis != NULL) &&
        (ctl->attitude == NULL || (ctl->axis_index >= 0 && ctl->axis_index < LADRC_AXES)) &&
        ctl_axis_config(ctl)->variant == LADRC_VARIANT_HP_MLADRC) {
        ladrc_margins_request_t quiet = *req;
        quiet.tone_rad_s2 = 0.0;
        st = ladrc_margins_analyse(ws, ctl, &quiet, res);
        if (idle != NULL)
            *idle = st == LADRC_MARGINS_OK;
    }
    return st;
}

/* Margins of the candidate (whole: as ladrc_margins reports the variant;
 * otherwise the search's LADRC core, margins only, no output grid); 1 when
 * it meets the targets. */
static int evaluate(tuner_t *t, ladrc_margins_result_t *res, int whole)
{
    if (whole) {
        if (ladrc_margins_analyse_reported(t->ws, &t->ctl, t->req, res, NULL) != LADRC_MARGINS_OK) {
            res->stable = 0; /* not analysable: no fallback either */
            return 0;
        }
        return meets(res, t->tg);
    }
    loop_t lp;
    if (ladrc_margins_measure(t->ws, &t->ctl, t->req) != LADRC_MARGINS_OK ||
        make_loop(t->ws, &t->req->plant, &lp) != LADRC_MARGINS_OK) {
        res->stable = 0;
        return 0;
    }
    memset(res, 0, sizeof *res);
    margins(&lp, t->req->plant.dt_s, res);
    return meets(res, t->tg);
}

/* A missed candidate's distance to the targets (larger: closer). */
static double miss_score(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg)
{
    return fmin(res->pm_deg - tg->pm_min_deg, 3.0 * (res->gm_db - tg->gm_min_db));
}

/* The closest stable miss so far (the report when nothing meets the targets). */
typedef struct {
    double score, w;
    int shape;
} fallback_t;

static void note_miss(fallback_t *f, const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg, double w,
                      int shape)
{
    const double score = miss_score(res, tg);
    if (res->stable && score > f->score) {
        f->score = score;
        f->w = w;
        f->shape = shape;
    }
}

/* Largest w on the geometric scan from w_lo (factor 1.5, up to w_hi) whose
 * candidate meets the targets, refined by bisection to 1 % against the next
 * scan point; NAN if none. */
static double search_up(tuner_t *t, int shape, double j_model, double w_lo, double w_hi, int whole, fallback_t *fb)
{
    ladrc_margins_result_t *res = &t->ws->scratch;
    double ok_w = NAN, bad_w = NAN;
    for (double w = w_lo; w <= w_hi; w *= 1.5) {
        set_gains(t, w, shape, j_model);
        if (evaluate(t, res, whole)) {
            ok_w = w;
        } else {
            note_miss(fb, res, t->tg, w, shape);
            if (!isnan(ok_w)) {
                bad_w = w;
                break;
            }
        }
    }
    if (isnan(ok_w) || isnan(bad_w))
        return ok_w;
    double lo = ok_w, hi = bad_w;
    while (hi - lo > 0.01 * lo) {
        const double m = sqrt(lo * hi);
        set_gains(t, m, shape, j_model);
        if (evaluate(t, res, whole))
            lo = m;
        else
            hi = m;
    }
    return lo;
}

/* Adaptive variants: from the core's w down (factor 1.1, to w_lo) to the
 * first w at which the whole variant meets the targets, refined by bisection
 * to 1 % against the scan point above it; NAN if none. The step is finer
 * than the core's scan: the variant's margins need not fall monotonically
 * with w (LP's gain bound adapts to what it sees), and a coarse step can
 * jump over the highest band that meets them. */
static double search_down(tuner_t *t, int shape, double j_model, double w_top, double w_lo, fallback_t *fb)
{
    ladrc_margins_result_t *res = &t->ws->scratch;
    double bad_w = NAN;
    for (double w = w_top; w >= w_lo; w /= 1.1) {
        set_gains(t, w, shape, j_model);
        if (evaluate(t, res, 1)) {
            if (isnan(bad_w))
                return w;
            double lo = w, hi = bad_w;
            while (hi - lo > 0.01 * lo) {
                const double m = sqrt(lo * hi);
                set_gains(t, m, shape, j_model);
                if (evaluate(t, res, 1))
                    lo = m;
                else
                    hi = m;
            }
            return lo;
        }
        note_miss(fb, res, t->tg, w, shape);
        bad_w = w;
    }
    return NAN;
}

/* The gains of every variant as the tuning reports them (its result struct). */
static void report_gains(const ladrc_axis_config_t *a, ladrc_margins_tuning_t *out)
{
    out->wc_rad_s = (double)a->wc_rad_s;
    out->wo_rad_s = (double)a->wo_rad_s;
    out->kp = (double)a->pid_kp;
    out->ki = (double)a->pid_ki;
    out->kd = (double)a->pid_kd;
    out->d_filter_tau_s = (double)a->pid_d_filter_tau_s;
    out->indi_att_kp_per_s = (double)a->indi_att_kp_per_s;
    out->indi_rate_kp_per_s = (double)a->indi_rate_kp_per_s;
    out->indi_filter_rad_s = (double)a->indi_filter_rad_s;
    out->cas_att_kp = (double)a->cas_att_kp;
    out->cas_rate_kp = (double)a->cas_rate_kp;
    out->cas_rate_ki = (double)a->cas_rate_ki;
    out->cas_rate_kd = (double)a->cas_rate_kd;
    out->cas_d_filter_tau_s = (double)a->cas_d_filter_tau_s;
}

ladrc_margins_status_t ladrc_margins_tune(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                          const ladrc_margins_request_t *req, const ladrc_margins_targets_t *targets,
                                          ladrc_axis_config_t *tuned, ladrc_margins_tuning_t *out)
{
    if (ws == NULL || ctl == NULL || req == NULL || targets == NULL || tuned == NULL || out == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if ((ctl->attitude == NULL) == (ctl->axis == NULL))
        return LADRC_MARGINS_ERR_CONTROLLER;
    if (ctl->attitude != NULL && (ctl->axis_index < 0 || ctl->axis_index >= LADRC_AXES))
        return LADRC_MARGINS_ERR_CONTROLLER;
    const ladrc_margins_status_t st = check_request(req);
    if (st != LADRC_MARGINS_OK)
        return st;
    if (!(isfinite(targets->pm_min_deg) && isfinite(targets->gm_min_db)))
        return LADRC_MARGINS_ERR_REQUEST;
    tuner_t t;
    memset(&t, 0, sizeof t);
    t.ws = ws;
    t.ctl = *ctl;
    t.req = req;
    t.tg = targets;
    if (ctl->attitude != NULL) {
        t.att = *ctl->attitude;
        t.ctl.attitude = &t.att;
    } else {
        t.axis = *ctl->axis;
        t.ctl.axis = &t.axis;
    }
    ladrc_axis_config_t *a = tuner_axis(&t);
    const ladrc_variant_t variant = a->variant;
    /* The adaptive variants are tuned on their LADRC core. */
    if (is_adaptive(a))
        a->variant = LADRC_VARIANT_LADRC;
    const double dt = req->plant.dt_s;
    const double j_model = req->plant.inertia_kg_m2;
    /* w from 0.5 rad/s up to the sampled loop's limit (wc dt < 1 for LADRC;
     * the same bound keeps PID's w below the Nyquist frequency). */
    const double w_lo = 0.5, w_hi = 0.95 / dt;
    const int adaptive = variant != a->variant;
    memset(out, 0, sizeof *out);
    out->peak_dist_rad = INFINITY;
    /* closest misses of the searched core and of the whole adaptive variant */
    fallback_t fb_core = {.score = -INFINITY, .w = NAN, .shape = -1},
               fb_whole = {.score = -INFINITY, .w = NAN, .shape = -1};
    double best_w = NAN;
    int best_shape = -1;
    for (int shape = 0; shape < n_shapes(); ++shape) {
        double ok_w = search_up(&t, shape, j_model, w_lo, w_hi, 0, &fb_core);
        if (isnan(ok_w))
            continue;
        if (adaptive) {
            /* The whole variant at the core's bandwidth, and lower until it
             * meets the targets too: its estimator adds phase lag. */
            a->variant = variant;
            ok_w = search_down(&t, shape, j_model, ok_w, w_lo, &fb_whole);
            a->variant = LADRC_VARIANT_LADRC;
            if (isnan(ok_w))
                continue;
        }
        a->variant = variant;
        set_gains(&t, ok_w, shape, j_model);
        ladrc_margins_result_t *res = &ws->scratch;
        const ladrc_margins_status_t st_c = ladrc_margins_analyse_reported(ws, &t.ctl, req, res, NULL);
        a->variant = adaptive ? LADRC_VARIANT_LADRC : variant;
        if (st_c != LADRC_MARGINS_OK)
            continue;
        if (best_shape < 0 || res->dist_peak_rad < out->peak_dist_rad) {
            best_w = ok_w;
            best_shape = shape;
            out->peak_dist_rad = res->dist_peak_rad;
        }
    }
    const int found = best_shape >= 0;
    const fallback_t fb = (adaptive && fb_whole.shape >= 0) ? fb_whole : fb_core;
    if (!found) {
        if (fb.shape < 0) {
            /* Not one stable candidate: the margins of the controller as given. */
            a->variant = variant;
            *a = *ctl_axis_config(ctl);
            (void)ladrc_margins_analyse_reported(ws, &t.ctl, req, &out->margins, NULL);
            out->met = 0;
            report_gains(a, out);
            out->peak_dist_rad = out->margins.dist_peak_rad;
            *tuned = *a;
            return LADRC_MARGINS_ERR_TARGETS_NOT_MET;
        }
        best_w = fb.w;
        best_shape = fb.shape;
    }
    set_gains(&t, best_w, best_shape, j_model);
    a->variant = variant;
    /* Margins of the variant as it will fly (and as ladrc_margins reports them). */
    const ladrc_margins_status_t fin = ladrc_margins_analyse_reported(ws, &t.ctl, req, &out->margins, NULL);
    out->met = found && fin == LADRC_MARGINS_OK && meets(&out->margins, targets);
    out->peak_dist_rad = out->margins.dist_peak_rad;
    report_gains(a, out);
    *tuned = *a;
    if (fin != LADRC_MARGINS_OK)
        return fin;
    return out->met ? LADRC_MARGINS_OK : LADRC_MARGINS_ERR_TARGETS_NOT_MET;
}
