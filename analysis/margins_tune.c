/* SPDX-License-Identifier: BSD-3-Clause */
/* The margins-based tuner: the gains of a variant searched for the highest
 * bandwidth that meets phase and gain margin targets (docs/margins.md). */
#include "margins_internal.h"

#include <math.h>
#include <string.h>

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

/* The search's shapes: the first N_SHAPES for every variant; the LADRC
 * family's wide observer ratios after them, a fallback only (margins are
 * blind to noise: searched everywhere, they made plain LADRC fly up to 15
 * times worse where the usual ratios meet the targets). RATE-ADRC searches
 * its attitude gain too: shape = ratio index + N_WIDE_SHAPES * separation
 * index. */
#define N_SHAPES 3
#define N_WIDE_SHAPES 6

static int n_separations(ladrc_variant_t variant)
{
    return variant == LADRC_VARIANT_RATE_ADRC ? 3 : 1;
}

/* Sets the candidate's gains from the search parameters (w, shape index). */
static void set_gains(tuner_t *t, double w, int shape, double j_model)
{
    /* observer ratios wo / w: the usual three, then the wide fallback ones */
    static const double ratios[N_WIDE_SHAPES] = {3.0, 5.0, 8.0, 12.0, 20.0, 32.0};
    static const double integral[] = {3.0, 5.0, 10.0};
    static const double cascade_separation[] = {3.0, 4.0, 6.0};
    /* RATE-ADRC's k_w / k_att: the default's 4 first, then tighter */
    static const double rate_adrc_separation[] = {4.0, 3.0, 2.0};
    ladrc_axis_config_t *a = tuner_axis(t);
    if (a->variant == LADRC_VARIANT_INDI) {
        /* The LADRC rule with the acceleration filter in the observer's
         * place: loop (s + w)^2, w_f = r w (at most 0.9 pi / dt). */
        const double wf_max = 0.9 * PI / (double)a->dt_s;
        a->indi_att_kp_per_s = (ladrc_real_t)w;
        a->indi_rate_kp_per_s = (ladrc_real_t)w;
        a->indi_filter_rad_s = (ladrc_real_t)fmin(ratios[shape] * w, wf_max);
    } else if (a->variant == LADRC_VARIANT_RATE_ADRC) {
        /* w: the rate loop's crossover k_w; its observer r w above it, the
         * attitude gain w / n */
        a->radrc_kp_per_s = (ladrc_real_t)w;
        a->wo_rad_s = (ladrc_real_t)(ratios[shape % N_WIDE_SHAPES] * w);
        a->radrc_att_kp_per_s = (ladrc_real_t)(w / rate_adrc_separation[shape / N_WIDE_SHAPES]);
    } else if (a->variant == LADRC_VARIANT_CASCADED) {
        /* w: the rate loop's crossover; the default's rule (axis.h) with
         * the attitude gain w / n, n the cascade's separation */
        const double kp = j_model * w;
        const double tf = 1.0 / (8.0 * w);
        a->cas_rate_kp = (ladrc_real_t)kp;
        a->cas_rate_ki = (ladrc_real_t)(kp * w / 5.0);
        a->cas_rate_kd = (ladrc_real_t)(kp / (4.0 * w));
        a->cas_att_kp = (ladrc_real_t)(w / cascade_separation[shape]);
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

/* 1 when the targets cap the command noise (a finite cap > 0). */
static int caps_noise(const ladrc_margins_targets_t *tg)
{
    return tg->cmd_noise_max_Nm > 0.0 && isfinite(tg->cmd_noise_max_Nm);
}

int ladrc_margins_meets(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg)
{
    return res->stable && res->pm_deg >= tg->pm_min_deg && res->gm_db >= tg->gm_min_db &&
           res->gm_low_db <= -tg->gm_min_db && (!caps_noise(tg) || res->cmd_noise_Nm <= tg->cmd_noise_max_Nm);
}

static int meets(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg)
{
    return ladrc_margins_meets(res, tg);
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
        margins_make_loop(t->ws, &t->req->plant, &lp) != LADRC_MARGINS_OK) {
        res->stable = 0;
        return 0;
    }
    memset(res, 0, sizeof *res);
    margins_compute(&lp, t->req->plant.dt_s, res);
    if (caps_noise(t->tg))
        res->cmd_noise_Nm = margins_cmd_noise(&lp, t->req);
    return meets(res, t->tg);
}

/* A missed candidate's distance to the targets (larger: closer); the noise
 * over its cap counts in dB like the gain margin. */
static double miss_score(const ladrc_margins_result_t *res, const ladrc_margins_targets_t *tg)
{
    double score = fmin(res->pm_deg - tg->pm_min_deg, 3.0 * (res->gm_db - tg->gm_min_db));
    if (caps_noise(tg) && res->cmd_noise_Nm > 0.0)
        score = fmin(score, 3.0 * 20.0 * log10(tg->cmd_noise_max_Nm / res->cmd_noise_Nm));
    return score;
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
    out->radrc_kp_per_s = (double)a->radrc_kp_per_s;
    out->radrc_att_kp_per_s = (double)a->radrc_att_kp_per_s;
    out->cas_att_kp = (double)a->cas_att_kp;
    out->cas_rate_kp = (double)a->cas_rate_kp;
    out->cas_rate_ki = (double)a->cas_rate_ki;
    out->cas_rate_kd = (double)a->cas_rate_kd;
    out->cas_d_filter_tau_s = (double)a->cas_d_filter_tau_s;
}

/* 1 when the request asks for the step objective (else the peak |d -> e|). */
static int uses_steps(const ladrc_margins_request_t *req)
{
    return req->track_step_rad > 0.0 || req->dist_step_rad_s2 > 0.0;
}

/* The candidate's step costs (rad^2 s), each flown alone from rest: the
 * reference step, then the disturbance step (0 where the request's step is
 * 0); +INFINITY where it diverges. */
static void step_costs(tuner_t *t, double *track, double *dist)
{
    ladrc_margins_request_t r = *t->req;
    *track = *dist = 0.0;
    if (t->req->track_step_rad > 0.0) {
        r.dist_step_rad_s2 = 0.0;
        if (ladrc_margins_step_cost(t->ws, &t->ctl, &r, track) != LADRC_MARGINS_OK)
            *track = INFINITY;
    }
    if (t->req->dist_step_rad_s2 > 0.0) {
        r = *t->req;
        r.track_step_rad = 0.0;
        if (ladrc_margins_step_cost(t->ws, &t->ctl, &r, dist) != LADRC_MARGINS_OK)
            *dist = INFINITY;
    }
}

/* The chosen setting's peak |d -> e| (its margins in out) and step cost. */
static void report_objective(tuner_t *t, ladrc_margins_tuning_t *out)
{
    out->peak_dist_rad = out->margins.dist_peak_rad;
    out->cmd_noise_Nm = out->margins.cmd_noise_Nm;
    out->step_cost_rad2_s = NAN;
    if (uses_steps(t->req) &&
        ladrc_margins_step_cost(t->ws, &t->ctl, t->req, &out->step_cost_rad2_s) != LADRC_MARGINS_OK)
        out->step_cost_rad2_s = NAN;
}

/* The candidates that meet the targets, one per shape searched (and per
 * search: on the core and on the whole loop), with what ranks them. */
#define MAX_CANDIDATES (2 * N_WIDE_SHAPES * 3)
typedef struct {
    double w, track, dist, peak;
    int shape;
} candidate_t;

typedef struct {
    int n;
    candidate_t c[MAX_CANDIDATES];
} candidates_t;

static double share_of_best(double x, double best)
{
    return best > 0.0 ? x / best : 0.0;
}

/* The winner's index (-1 if none). With steps: each candidate's reference
 * and disturbance step costs, each over the smallest of all candidates,
 * summed, so the two weigh alike whatever their sizes; the smallest sum
 * wins, and one that diverges in a step loses to every one that does not.
 * Without steps, or where every candidate diverges (steps too large for an
 * airframe this slow: the steps never fail a tuning the margins allow), the
 * smallest peak |disturbance -> error| wins. */
static int pick(const candidates_t *cs, int steps)
{
    double best_track = INFINITY, best_dist = INFINITY;
    for (int i = 0; steps && i < cs->n; ++i) {
        if (cs->c[i].track < INFINITY && cs->c[i].dist < INFINITY) {
            best_track = fmin(best_track, cs->c[i].track);
            best_dist = fmin(best_dist, cs->c[i].dist);
        }
    }
    const int by_steps = best_track < INFINITY;
    int win = -1;
    double win_score = INFINITY;
    for (int i = 0; i < cs->n; ++i) {
        const candidate_t *c = &cs->c[i];
        const double score =
            by_steps ? share_of_best(c->track, best_track) + share_of_best(c->dist, best_dist) : c->peak;
        if (score < win_score) {
            win = i;
            win_score = score;
        }
    }
    return win;
}

/* One shape's candidate, searched on the LADRC core (whole 0; the adaptive
 * variants then stepped down until the whole variant meets the targets) or
 * on the whole variant's own loop (whole 1), added to *cs. */
static void try_shape(tuner_t *t, int shape, int whole, ladrc_variant_t variant, double j_model, double w_lo,
                      double w_hi, fallback_t *fb_core, fallback_t *fb_whole, candidates_t *cs)
{
    ladrc_axis_config_t *a = tuner_axis(t);
    const ladrc_variant_t searched = a->variant; /* the core (LADRC) for the adaptive variants */
    const int adaptive = variant != searched;
    double ok_w;
    if (whole) {
        a->variant = variant;
        ok_w = search_up(t, shape, j_model, w_lo, w_hi, 1, fb_whole);
        a->variant = searched;
    } else {
        ok_w = search_up(t, shape, j_model, w_lo, w_hi, 0, fb_core);
        if (!isnan(ok_w) && adaptive) {
            /* The whole variant at the core's bandwidth, and lower until it
             * meets the targets too: its estimator adds phase lag. */
            a->variant = variant;
            ok_w = search_down(t, shape, j_model, ok_w, w_lo, fb_whole);
            a->variant = searched;
        }
    }
    if (isnan(ok_w))
        return;
    a->variant = variant;
    set_gains(t, ok_w, shape, j_model);
    ladrc_margins_result_t *res = &t->ws->scratch;
    if (ladrc_margins_analyse_reported(t->ws, &t->ctl, t->req, res, NULL) == LADRC_MARGINS_OK &&
        cs->n < MAX_CANDIDATES) {
        candidate_t *c = &cs->c[cs->n++];
        c->w = ok_w;
        c->shape = shape;
        c->peak = res->dist_peak_rad;
        step_costs(t, &c->track, &c->dist);
    }
    a->variant = searched;
}

ladrc_margins_status_t ladrc_margins_tune(ladrc_margins_workspace_t *ws, const ladrc_margins_controller_t *ctl,
                                          const ladrc_margins_request_t *req, const ladrc_margins_targets_t *targets,
                                          ladrc_axis_config_t *tuned, ladrc_margins_tuning_t *out)
{
    if (ws == NULL || ctl == NULL || req == NULL || targets == NULL || tuned == NULL || out == NULL)
        return LADRC_MARGINS_ERR_NULL;
    if (!margins_ctl_names_axis(ctl))
        return LADRC_MARGINS_ERR_CONTROLLER;
    const ladrc_margins_status_t st = margins_check_request(req);
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
    /* closest misses of the searched core and of the whole adaptive variant */
    fallback_t fb_core = {.score = -INFINITY, .w = NAN, .shape = -1},
               fb_whole = {.score = -INFINITY, .w = NAN, .shape = -1};
    candidates_t cand_list = {.n = 0};
    candidates_t *cands = &cand_list;
    const int n_sep = n_separations(variant);
    for (int sep = 0; sep < n_sep; ++sep)
        for (int shape = 0; shape < N_SHAPES; ++shape)
            try_shape(&t, shape + N_WIDE_SHAPES * sep, 0, variant, j_model, w_lo, w_hi, &fb_core, &fb_whole, cands);
    /* The adaptive variants' own loops too, at the usual ratios: their core
     * must not cap them (LP's estimate adds phase where the LESO alone lacks
     * it; e.g. 30 ms behind the motors the core leaves LP 30 deg of PM
     * unused), and where nothing meets the targets on the core (a modelled
     * plant without drag: the LESO loop stays below PM 45 deg at every usual
     * ratio) the estimator may add the missing phase. */
    if (adaptive) {
        for (int shape = 0; shape < N_SHAPES; ++shape)
            try_shape(&t, shape, 1, variant, j_model, w_lo, w_hi, &fb_core, &fb_whole, cands);
    }
    /* Still nothing: the LADRC family's wide ratios. Whatever tunes with the
     * usual ratios keeps its gains. */
    if (cands->n == 0 && ladrc_variant_has_observer(variant)) {
        for (int sep = 0; sep < n_sep; ++sep) {
            for (int shape = N_SHAPES + N_WIDE_SHAPES * sep; shape < N_WIDE_SHAPES * (sep + 1); ++shape) {
                try_shape(&t, shape, 0, variant, j_model, w_lo, w_hi, &fb_core, &fb_whole, cands);
                if (adaptive)
                    try_shape(&t, shape, 1, variant, j_model, w_lo, w_hi, &fb_core, &fb_whole, cands);
            }
        }
    }
    const int win = pick(cands, uses_steps(req));
    const int found = win >= 0;
    double best_w = found ? cands->c[win].w : NAN;
    int best_shape = found ? cands->c[win].shape : -1;
    const fallback_t fb = (adaptive && fb_whole.shape >= 0) ? fb_whole : fb_core;
    if (!found) {
        if (fb.shape < 0) {
            /* Not one stable candidate: the margins of the controller as given. */
            a->variant = variant;
            *a = *margins_ctl_axis_config(ctl);
            (void)ladrc_margins_analyse_reported(ws, &t.ctl, req, &out->margins, NULL);
            out->met = 0;
            report_gains(a, out);
            report_objective(&t, out);
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
    report_objective(&t, out);
    report_gains(a, out);
    *tuned = *a;
    if (fin != LADRC_MARGINS_OK)
        return fin;
    return out->met ? LADRC_MARGINS_OK : LADRC_MARGINS_ERR_TARGETS_NOT_MET;
}
