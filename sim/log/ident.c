/* SPDX-License-Identifier: BSD-3-Clause */
/* Identification of the axes' plant from a log (ident.h): the prefilter, the
 * candidates' sums over each pass, the fits at each pass's end. */
#include "ident_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FIRST_TAU_S 0.0005 /* the coarse grid's first lag after 0 */

/* The prefilter: a band from SIM_IDENT_HIGHPASS_HZ (second-order
 * high-pass: the slow disturbances the loop cancels, wind and trim, are
 * correlated with the command and would bias the fit) to the corner
 * (fourth-order low-pass, -24 dB an octave above it, where the rotors'
 * vibration lines lie: their frequency follows the command too). */
static const double PREFILTER_Q[PREFILTER_SECTIONS] = {0.54119610014619690, 1.30656296487637653, BIQUAD_Q_BUTTERWORTH};

static double prefilter_step(const biquad_coef_t *c, prefilter_t *f, double x)
{
    for (int i = 0; i < PREFILTER_SECTIONS; ++i) {
        x = biquad_step(&c[i], &f->s[i], x);
    }
    return x;
}

/* Settled on a constant input (unit gain at 0 Hz: each section passes x). */
static void prefilter_settle(const biquad_coef_t *c, prefilter_t *f, double x)
{
    for (int i = 0; i < PREFILTER_SECTIONS; ++i) {
        biquad_settle(&c[i], &f->s[i], x);
    }
}

sim_ident_t *sim_ident_new(const sim_ident_options_t *opt)
{
    if (opt == NULL || !(opt->dt_s > 0.0) || !isfinite(opt->dt_s)) {
        return NULL;
    }
    sim_ident_t *id = calloc(1, sizeof *id);
    if (id == NULL) {
        return NULL;
    }
    id->opt = *opt;
    const double fs = 1.0 / opt->dt_s;
    if (!(id->opt.prefilter_hz > 0.0)) {
        id->opt.prefilter_hz = fmin(SIM_IDENT_PREFILTER_MAX_HZ, 0.08 * fs);
    }
    id->opt.prefilter_hz = fmin(id->opt.prefilter_hz, 0.4 * fs);
    if (!(id->opt.lag_max_s > 0.0)) {
        id->opt.lag_max_s = 0.2;
    }
    id->delay_max = opt->delay_max_ticks >= 0 ? opt->delay_max_ticks : (int)ceil(0.040 / opt->dt_s);
    if (id->delay_max > SIM_IDENT_MAX_DELAY) {
        id->delay_max = SIM_IDENT_MAX_DELAY;
    }
    for (int i = 0; i < 2; ++i) {
        id->lpf[i] = biquad_lowpass(id->opt.prefilter_hz, opt->dt_s, PREFILTER_Q[i]);
    }
    id->lpf[2] = biquad_highpass(SIM_IDENT_HIGHPASS_HZ, opt->dt_s, PREFILTER_Q[2]);
    /* the low-pass settles in some 6 / fc; the ring fills in delay_max + 1 */
    id->skip = (int)ceil(6.0 / (id->opt.prefilter_hz * opt->dt_s));
    if (id->skip < id->delay_max + 2) {
        id->skip = id->delay_max + 2;
    }
    /* residuals stay correlated over the low-pass's memory and the loop's */
    id->hac_lags = (int)ceil(8.0 / (id->opt.prefilter_hz * opt->dt_s));
    if (id->hac_lags > SIM_IDENT_MAX_HAC_LAGS) {
        id->hac_lags = SIM_IDENT_MAX_HAC_LAGS;
    }
    return id;
}

void sim_ident_free(sim_ident_t *id)
{
    free(id);
}

int sim_ident_delay_max(const sim_ident_t *id)
{
    return id->delay_max;
}

double sim_ident_prefilter_hz(const sim_ident_t *id)
{
    return id->opt.prefilter_hz;
}

static double coarse_tau(const sim_ident_t *id, int i)
{
    if (i == 0) {
        return 0.0;
    }
    const double ratio = pow(id->opt.lag_max_s / FIRST_TAU_S, 1.0 / (SIM_IDENT_COARSE_TAUS - 2));
    return FIRST_TAU_S * pow(ratio, i - 1);
}

static int channels_of_pass(const sim_ident_t *id)
{
    return id->pass == 1 ? SIM_IDENT_COARSE_TAUS : id->pass == 2 ? SIM_IDENT_FINE_TAUS : 1;
}

static double channel_tau(const sim_ident_t *id, const axis_t *a, int c)
{
    return id->pass == 1 ? a->tau_coarse[c] : id->pass == 2 ? a->tau_fine[c] : a->tau_s;
}

/* The delays a pass fits: all in pass 1, about the best in pass 2, the chosen one in pass 3. */
static void delays_of_pass(const sim_ident_t *id, const axis_t *a, int *d0, int *nd)
{
    if (id->pass == 1) {
        *d0 = 0;
        *nd = id->delay_max + 1;
    } else if (id->pass == 2) {
        *d0 = a->fine_d0;
        *nd = a->fine_nd;
    } else {
        *d0 = a->delay;
        *nd = 1;
    }
}

/* A gap: the filters start again, and no residual is paired across it. */
static void restart(axis_t *a)
{
    a->since_restart = 0;
    a->h_seg = 0;
}

int sim_ident_begin_pass(sim_ident_t *id)
{
    if (id->pass >= 3) {
        return 0;
    }
    id->pass++;
    for (int i = 0; i < 3; ++i) {
        axis_t *a = &id->axis[i];
        memset(&a->sh, 0, sizeof a->sh);
        memset(&a->cand, 0, sizeof a->cand);
        a->h_count = 0;
        a->sse3 = 0.0;
        memset(a->hac, 0, sizeof a->hac);
        memset(a->block_h, 0, sizeof a->block_h);
        memset(a->zx, 0, sizeof a->zx);
        memset(a->zy, 0, sizeof a->zy);
        memset(a->block_zx, 0, sizeof a->block_zx);
        memset(a->block_zy, 0, sizeof a->block_zy);
        a->iv_on = id->pass == 3;
        const int n = channels_of_pass(id);
        for (int c = 0; c < n; ++c) {
            if (id->pass == 1) {
                a->tau_coarse[c] = coarse_tau(id, c);
            }
            const double tau = channel_tau(id, a, c);
            a->ch[c].tau_s = tau;
            a->ch[c].alpha = tau > 0.0 ? exp(-id->opt.dt_s / tau) : 0.0;
            a->ch[c].gain = tau > 0.0 ? tau / id->opt.dt_s * (1.0 - a->ch[c].alpha) : 0.0;
        }
        a->ref_ch = a->ch[0]; /* pass 3: the chosen lag */
        restart(a);
        if (id->pass == 1) {
            sim_spectrum_init(&a->command, 1.0 / id->opt.dt_s);
        }
    }
    return id->pass;
}

/* The phi of one lag channel for input v held over the tick (ident_internal.h), filtered into its ring. */
static void lag_channel_step(const sim_ident_t *id, lag_channel_t *ch, int pos, double v)
{
    const double phi = v + (ch->x - v) * ch->gain;
    ch->x = ch->alpha * ch->x + (1.0 - ch->alpha) * v;
    ch->ring[pos] = ch->ring[pos + RING] = prefilter_step(id->lpf, &ch->filter, phi);
}

/* The running sums of phi and phi^2 through the newest tick, into their rings (slot spos of RING + 1). */
static void lag_channel_sums(lag_channel_t *ch, int pos, int spos)
{
    const double p = ch->ring[pos];
    ch->sum1 += p;
    ch->sum2 += p * p;
    ch->ring1[spos] = ch->ring1[spos + RING + 1] = ch->sum1;
    ch->ring2[spos] = ch->ring2[spos + RING + 1] = ch->sum2;
}

static void lag_channel_settle(const sim_ident_t *id, lag_channel_t *ch, double v)
{
    ch->x = v;
    prefilter_settle(id->lpf, &ch->filter, v);
    for (int k = 0; k < 2 * RING; ++k) {
        ch->ring[k] = v;
    }
    ch->sum1 = ch->sum2 = 0.0;
    for (int k = 0; k < 2 * (RING + 1); ++k) {
        ch->ring1[k] = ch->ring2[k] = 0.0;
    }
}

/* Pass 3's instrumental-variable sums of one fitted sample into block b:
 * z = (the setpoint's phi at the chosen delay, its filtered mid-point, 1),
 * x = (p, wm, 1). */
static void iv_add(axis_t *a, int d0, long long b, double rf, double p, double wm, double y)
{
    const double z[3] = {lag_channel_at(&a->ref_ch, a->pos, d0), rf, 1.0}, x[3] = {p, wm, 1.0};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a->zx[i][j] += z[i] * x[j];
            a->block_zx[b][i][j] += z[i] * x[j];
        }
        a->zy[i] += z[i] * y;
        a->block_zy[b][i] += z[i] * y;
    }
}

/* Passes 1 and 2 take the candidates' sums of phi and phi^2 from the
 * channels' running sums: sign -1 at a segment's first fitted tick (the
 * sums through the tick before it, delay d + 1), +1 after its last (the
 * sums through it, delay d). */
static void segment_sums(const sim_ident_t *id, axis_t *a, double sign, int extra)
{
    int d0, nd;
    delays_of_pass(id, a, &d0, &nd);
    for (int c = 0; c < channels_of_pass(id); ++c) {
        const lag_channel_t *ch = &a->ch[c];
        for (int j = 0; j < nd; ++j) {
            const int at = a->spos + d0 + j + extra;
            a->cand.p1[c][j] += sign * ch->ring1[at];
            a->cand.pp[c][j] += sign * ch->ring2[at];
        }
    }
}

/* A segment's end (a gap, the pass's end): its fitted ticks' sums of phi and phi^2 in. */
static void segment_close(const sim_ident_t *id, axis_t *a)
{
    if (id->pass < 3 && a->since_restart > id->skip) {
        segment_sums(id, a, 1.0, 0);
    }
}

/* One axis's sample (ref: the setpoint, NaN when none). */
static void add_axis(sim_ident_t *id, axis_t *a, double w, double u, double ref)
{
    if (!isfinite(w) || !isfinite(u)) {
        segment_close(id, a);
        restart(a);
        if (id->pass == 1) {
            sim_spectrum_break(&a->command); /* no segment across the gap */
        }
        return;
    }
    if (!isfinite(ref)) {
        a->iv_on = 0;
    }
    if (id->pass == 1) {
        sim_spectrum_push(&a->command, u);
    }
    const int n_ch = channels_of_pass(id);
    if (a->since_restart == 0) {
        /* settled on the first sample: the filters start where the signals are */
        prefilter_settle(id->lpf, &a->fy, 0.0);
        prefilter_settle(id->lpf, &a->fw, w);
        for (int c = 0; c < n_ch; ++c) {
            lag_channel_settle(id, &a->ch[c], u);
        }
        if (a->iv_on) {
            lag_channel_settle(id, &a->ref_ch, ref);
            prefilter_settle(id->lpf, &a->fr, ref);
            a->r_prev = ref;
        }
        a->w_prev = w;
        a->u_prev = u;
        a->since_restart = 1;
        return;
    }
    const double y = prefilter_step(id->lpf, &a->fy, (w - a->w_prev) / id->opt.dt_s);
    const double wm = prefilter_step(id->lpf, &a->fw, 0.5 * (w + a->w_prev));
    a->pos = (a->pos + RING - 1) % RING;
    a->spos = (a->spos + RING) % (RING + 1);
    for (int c = 0; c < n_ch; ++c) {
        lag_channel_step(id, &a->ch[c], a->pos, a->u_prev);
        lag_channel_sums(&a->ch[c], a->pos, a->spos);
    }
    double rf = 0.0;
    if (a->iv_on) {
        lag_channel_step(id, &a->ref_ch, a->pos, a->r_prev);
        rf = prefilter_step(id->lpf, &a->fr, 0.5 * (ref + a->r_prev));
        a->r_prev = ref;
    }
    a->w_prev = w;
    a->u_prev = u;
    a->since_restart++;
    if (a->since_restart <= id->skip) {
        return;
    }
    if (a->since_restart == id->skip + 1 && id->pass < 3) {
        segment_sums(id, a, -1.0, 1); /* the segment's first fitted tick */
    }
    shared_sums_t *s = &a->sh;
    s->ww += wm * wm;
    s->w1 += wm;
    s->n += 1.0;
    s->wy += wm * y;
    s->y1 += y;
    s->yy += y * y;
    int d0, nd;
    delays_of_pass(id, a, &d0, &nd);
    for (int c = 0; c < n_ch; ++c) {
        const double *restrict phi = &a->ch[c].ring[a->pos + d0]; /* delay d0 + j at phi[j] */
        double *restrict pw = a->cand.pw[c], *restrict py = a->cand.py[c];
        if (id->pass == 3) { /* one candidate: its sums of phi and phi^2 here too */
            a->cand.pp[c][0] += phi[0] * phi[0];
            a->cand.p1[c][0] += phi[0];
        }
        for (int j = 0; j < nd; ++j) { /* phi and phi^2: segment_sums */
            pw[j] += phi[j] * wm;
            py[j] += phi[j] * y;
        }
    }
    if (id->pass == 3 && a->valid) {
        const double p = lag_channel_at(&a->ch[0], a->pos, d0);
        const double r = y - (a->theta[0] * p + a->theta[1] * wm + a->theta[2]);
        const double h = (a->v[0] * p + a->v[1] * wm + a->v[2]) * r;
        a->sse3 += r * r;
        long long b = a->n_fitted > 0 ? a->h_count * SPLIT_BLOCKS / a->n_fitted : 0;
        b = b < SPLIT_BLOCKS ? b : SPLIT_BLOCKS - 1;
        a->block_h[b] += h;
        if (a->iv_on) {
            iv_add(a, d0, b, rf, p, wm, y);
        }
        const int lags = id->hac_lags, size = lags + 1;
        const long long k = a->h_seg++;
        a->h_count++;
        a->h_pos = (a->h_pos + size - 1) % size;
        a->h_ring[a->h_pos] = a->h_ring[a->h_pos + size] = h;
        const int m_max = k < lags ? (int)k : lags;
        const double *restrict past = &a->h_ring[a->h_pos]; /* lag m at past[m] */
        double *restrict hac = a->hac;
        for (int m = 0; m <= m_max; ++m) {
            hac[m] += h * past[m];
        }
    }
}

void sim_ident_add_ref(sim_ident_t *id, const double gyro_rad_s[3], const double command[3],
                       const double setpoint_rad_s[3])
{
    for (int i = 0; i < 3; ++i) {
        add_axis(id, &id->axis[i], gyro_rad_s[i], command[i], setpoint_rad_s != NULL ? setpoint_rad_s[i] : NAN);
    }
}

void sim_ident_add(sim_ident_t *id, const double gyro_rad_s[3], const double command[3])
{
    sim_ident_add_ref(id, gyro_rad_s, command, NULL);
}

/* Least squares of candidate sums: theta, the inverse of the sums matrix and
 * the residual sum of squares; 0 when the regressors are (nearly) collinear. */
static int solve(const shared_sums_t *s, const candidate_sums_t *c, double theta[3], double inv[3][3], double *sse)
{
    const double m[3][3] = {{c->pp, c->pw, c->p1}, {c->pw, s->ww, s->w1}, {c->p1, s->w1, s->n}};
    const double rhs[3] = {c->py, s->wy, s->y1};
    const double cof00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double cof01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double cof02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * cof00 + m[0][1] * cof01 + m[0][2] * cof02;
    /* collinear when the determinant is lost against the diagonal's product */
    if (!(s->n > 3.0) || !(fabs(det) > 1e-12 * fabs(m[0][0] * m[1][1] * m[2][2]))) {
        return 0;
    }
    inv[0][0] = cof00 / det;
    inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    inv[1][0] = cof01 / det;
    inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    inv[2][0] = cof02 / det;
    inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    for (int i = 0; i < 3; ++i) {
        theta[i] = inv[i][0] * rhs[0] + inv[i][1] * rhs[1] + inv[i][2] * rhs[2];
    }
    *sse = s->yy - (theta[0] * rhs[0] + theta[1] * rhs[1] + theta[2] * rhs[2]);
    if (*sse < 0.0) {
        *sse = 0.0; /* rounding on an exact fit */
    }
    return 1;
}

/* A candidate's residual sum of squares (+inf when it cannot be fitted) and b0. */
static double candidate_fit(const axis_t *a, int c, int j, double *b0)
{
    double theta[3], inv[3][3], sse;
    const candidate_sums_t cs = candidate_at(&a->cand, c, j);
    if (!solve(&a->sh, &cs, theta, inv, &sse)) {
        *b0 = NAN;
        return INFINITY;
    }
    *b0 = theta[0];
    return sse;
}

/* After pass 1: the coarse profile, the fine grid about its best. */
static void end_coarse(sim_ident_t *id, axis_t *a)
{
    int best_c = 0, best_d = 0;
    for (int c = 0; c < SIM_IDENT_COARSE_TAUS; ++c) {
        for (int d = 0; d < RING; ++d) {
            a->sse_coarse[c][d] = d <= id->delay_max ? candidate_fit(a, c, d, &a->b0_coarse[c][d]) : INFINITY;
            if (a->sse_coarse[c][d] < a->sse_coarse[best_c][best_d]) {
                best_c = c;
                best_d = d;
            }
        }
    }
    const double lo = a->tau_coarse[best_c > 0 ? best_c - 1 : 0];
    const double hi = a->tau_coarse[best_c + 1 < SIM_IDENT_COARSE_TAUS ? best_c + 1 : best_c];
    for (int c = 0; c < SIM_IDENT_FINE_TAUS; ++c) {
        a->tau_fine[c] = lo + (hi - lo) * c / (SIM_IDENT_FINE_TAUS - 1);
    }
    a->fine_d0 = best_d - SIM_IDENT_FINE_DELAYS / 2 < 0 ? 0 : best_d - SIM_IDENT_FINE_DELAYS / 2;
    a->fine_nd = SIM_IDENT_FINE_DELAYS;
    if (a->fine_d0 + a->fine_nd > id->delay_max + 1) {
        a->fine_nd = id->delay_max + 1 - a->fine_d0;
    }
}

/* The lag at the vertex of the parabola through the fine profile's best and
 * its two neighbours (at the best delay): the grid's spacing would
 * otherwise show in b0. The grid point itself at an edge or a flat profile. */
static double profile_vertex(const axis_t *a, int c, int j)
{
    if (c == 0 || c == SIM_IDENT_FINE_TAUS - 1) {
        return a->tau_fine[c];
    }
    const double y0 = a->sse_fine[c - 1][j], y1 = a->sse_fine[c][j], y2 = a->sse_fine[c + 1][j];
    const double curvature = y0 - 2.0 * y1 + y2;
    if (!(curvature > 0.0) || !isfinite(curvature)) {
        return a->tau_fine[c];
    }
    const double step = a->tau_fine[c + 1] - a->tau_fine[c];
    return a->tau_fine[c] + 0.5 * step * (y0 - y2) / curvature;
}

/* After pass 2: the choice and its fit. */
static void end_fine(axis_t *a)
{
    int best_c = -1, best_j = 0;
    double best = INFINITY;
    for (int c = 0; c < SIM_IDENT_FINE_TAUS; ++c) {
        for (int j = 0; j < SIM_IDENT_FINE_DELAYS; ++j) {
            a->sse_fine[c][j] = j < a->fine_nd ? candidate_fit(a, c, j, &a->b0_fine[c][j]) : INFINITY;
            if (a->sse_fine[c][j] < best) {
                best = a->sse_fine[c][j];
                best_c = c;
                best_j = j;
            }
        }
    }
    const candidate_sums_t best_sums = candidate_at(&a->cand, best_c >= 0 ? best_c : 0, best_j);
    a->valid = best_c >= 0 && solve(&a->sh, &best_sums, a->theta, a->m_inv, &a->sse);
    if (!a->valid) {
        return;
    }
    const candidate_sums_t *c = &best_sums;
    a->tau_grid_s = a->tau_fine[best_c];
    a->tau_s = profile_vertex(a, best_c, best_j);
    a->delay = a->fine_d0 + best_j;
    a->n = a->sh.n;
    a->n_fitted = (long long)a->sh.n;
    a->sst = a->sh.yy - a->sh.y1 * a->sh.y1 / a->sh.n;
    a->phi_mean = c->p1 / a->sh.n;
    a->phi_var = c->pp / a->sh.n - a->phi_mean * a->phi_mean;
    for (int i = 0; i < 3; ++i) {
        a->v[i] = a->m_inv[0][i];
    }
}

/* After pass 3: the fit at the refined lag when it beats the grid's best. */
static void end_refined(axis_t *a)
{
    double theta[3], inv[3][3], sse;
    const candidate_sums_t refined = candidate_at(&a->cand, 0, 0);
    if (solve(&a->sh, &refined, theta, inv, &sse) && sse <= a->sse) {
        memcpy(a->theta, theta, sizeof theta);
        memcpy(a->m_inv, inv, sizeof inv);
        a->sse = sse;
        a->phi_mean = refined.p1 / a->sh.n;
        a->phi_var = refined.pp / a->sh.n - a->phi_mean * a->phi_mean;
    } else {
        a->tau_s = a->tau_grid_s;
    }
}

void sim_ident_end_pass(sim_ident_t *id)
{
    for (int i = 0; i < 3; ++i) {
        axis_t *a = &id->axis[i];
        segment_close(id, a);
        if (id->pass == 1) {
            end_coarse(id, a);
        } else if (id->pass == 2) {
            end_fine(a);
        } else if (a->valid) {
            end_refined(a);
        }
    }
}
