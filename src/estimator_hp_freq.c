/* SPDX-License-Identifier: BSD-3-Clause */
/* ONLINE frequency search of the HP disturbance estimator (estimator.h,
 * "ONLINE frequencies"): a least squares on state-variable-filtered
 * derivatives of the sample, the tones it starts and stops, and the
 * tracking of a locked tone's slip. Called by estimator_hp.c on fit samples
 * only. */
#include "estimator_hp_internal.h"

#if LADRC_WITH_HP_ONLINE

/* ONLINE: a model with another number of tones replaces the tones only
 * after TONE_HOLD_S without such a change, so the fit settles in between;
 * two tones must lie more than TONE_SEPARATION (relative) apart. */
#define TONE_SEPARATION LADRC_R(0.15)
#define TONE_HOLD_S LADRC_R(0.5)
/* ONLINE: a locked tone's frequency follows its slip at this fraction of
 * the fit's forgetting rate. */
#define TRACK_FRACTION LADRC_R(0.25)
/* ONLINE: a model is clean while it leaves less than this share of the
 * highest derivative's power unexplained (1 - correlation^2 for one tone). */
#define IMPURITY_MAX LADRC_R(0.01)
/* The frequency fit's averages keep at least this much of the slowest
 * tone's phase (rad). */
#define FREQ_MEMORY_RAD LADRC_R(1.0)
/* A change's transient has passed the frequency fit's filter (wf / (s + wf))^6
 * FILTER_SETTLE_PER_WF / wf seconds after it: u^5 e^-u, the slowest term of
 * its response, is down to 3e-4 of its peak at u = 20. */
#define FILTER_SETTLE_PER_WF LADRC_R(20.0)
/* The frequency fit's model is judged every this many fit samples. */
#define SPEC_DECIDE 4u
/* The frequency fit speaks only after this much data since its (re)start (s). */
#define SPEC_MIN_S LADRC_R(0.1)
/* The frequency fit needs this much derivative power ((rad/s^3)^2). */
#define FILTER_MIN_POWER LADRC_R(1.0e-6)
/* Indices of the frequency fit's averages: x1 x1, x3 x1, x3 x3, x5 x1, x5 x3, x5 x5. */
enum { SPEC_11 = 0, SPEC_31, SPEC_33, SPEC_51, SPEC_53, SPEC_55, SPEC_COUNT };

#if LADRC_HP_MAX_TONES < 1 || LADRC_HP_MAX_TONES > 2
#error "the online frequency fit resolves one or two tones: LADRC_HP_MAX_TONES must be 1 or 2"
#endif

/* ONLINE: a locked tone's frequency follows its slip at TRACK_FRACTION of
 * the fit's forgetting rate (the loop of the slip through the fit's lag is
 * then well damped). */
static void track_slip(ladrc_hp_estimator_t *est, ladrc_hp_tone_t *tone)
{
    if (tone->locked) {
        const ladrc_real_t gain = TRACK_FRACTION * est->fit_rate_per_s * est->fit_period_s;
        hp_set_tone_freq(
            &est->basis, est->advance, tone,
            ladrc_clamp(tone->w_rad_s + gain * tone->slip_rad_s, est->freq_min_rad_s, est->freq_max_rad_s));
    }
}

/* ONLINE: the slot of the active tone within TONE_SEPARATION of w nearest
 * to it, or n_active if none. */
static unsigned nearest_tone(const ladrc_hp_estimator_t *est, ladrc_real_t w)
{
    unsigned nearest = est->n_active;
    for (unsigned j = 0u; j < est->n_active; ++j) {
        const ladrc_real_t gap = ladrc_fabs(est->tone[j].w_rad_s - w);
        if (gap < TONE_SEPARATION * w &&
            (nearest == est->n_active || gap < ladrc_fabs(est->tone[nearest].w_rad_s - w))) {
            nearest = j;
        }
    }
    return nearest;
}

/* ONLINE: the fit restarts with n tones at the frequencies found (ascending;
 * LADRC_HP_MAX_TONES <= 2): one tone becomes two, two one, or a tone that is
 * not locked jumped. A tone that is still there keeps its state and fitted
 * values (and, unless locked, takes the frequency found for it); a new one
 * starts at its frequency with zero amplitude. Called from ladrc_hp_step,
 * beside the RLS update, to keep the stack of a tick shallow. */
void hp_restart_tones(ladrc_hp_estimator_t *est, unsigned n)
{
    const ladrc_real_t *w = est->found_rad_s;
    ladrc_real_t theta[LADRC_RLS_MAX_PARAMS];
    const ladrc_real_t *old = ladrc_rls_get_theta(&est->fit);
    for (unsigned i = 0u; i < LADRC_RLS_MAX_PARAMS; ++i) {
        theta[i] = (i < theta_a(est->n_active)) ? old[i] : LADRC_R(0.0);
    }
    ladrc_real_t target[LADRC_HP_MAX_TONES];
    unsigned fresh = 0u; /* bit k: slot k starts a new tone */
    if (n < est->n_active) {
        /* two -> one: the tone nearest w[0] stays, in slot 0 */
        const unsigned kept = nearest_tone(est, w[0]);
        if (kept == 1u) {
            est->tone[0] = est->tone[1];
            theta[theta_a(0u)] = theta[theta_a(1u)];
            theta[theta_a(0u) + 1u] = theta[theta_a(1u) + 1u];
        }
        target[0] = w[0];
        fresh = (kept < est->n_active) ? 0u : 1u;
    } else if (n > est->n_active) {
        /* one -> two: tone 0 keeps the frequency it is near, slot 1 the other */
        const unsigned near_first = nearest_tone(est, w[0]) == 0u;
        const unsigned near_second = !near_first && nearest_tone(est, w[n - 1u]) == 0u;
        target[0] = near_second ? w[n - 1u] : w[0];
        target[n - 1u] = near_second ? w[0] : w[n - 1u];
        fresh = (near_first || near_second) ? 2u : 3u;
    } else {
        /* as many: a tone that is not locked and far from its frequency jumped */
        for (unsigned k = 0u; k < n; ++k) {
            target[k] = w[k];
            if (!est->tone[k].locked && ladrc_fabs(w[k] - est->tone[k].w_rad_s) > TONE_SEPARATION * w[k]) {
                fresh |= 1u << k;
            }
        }
    }
    for (unsigned k = 0u; k < n; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        if ((fresh & (1u << k)) != 0u) {
            theta[theta_a(k)] = LADRC_R(0.0);
            theta[theta_a(k) + 1u] = LADRC_R(0.0);
            hp_forget_tone(tone);
        }
        if (!tone->locked) {
            hp_set_tone_freq(&est->basis, est->advance, tone, target[k]);
        }
    }
    hp_start_fit(est, n, theta);
    est->contradicts = 0u; /* the tones now take the frequencies found */
}

/* ONLINE frequency fit (see estimator.h). One fit sample of the raw sample
 * x through (wf / (s + wf))^6, whose states are x and its first five
 * derivatives (semi-implicit Euler, the highest derivative first), and the
 * averages of the products of x1, x3 and x5.
 * Each state is the backward difference of the next lower one, so for a
 * tone x3_k = -sigma^2 x1_k-1 and x5_k = sigma^4 x1_k-2 exactly, with
 * sigma = 2 sin(w T / 2) / T: the averages pair x1_k-2, x3_k-1 and x5_k,
 * and every ratio of them is exact at every instant (no ripple from the
 * averaging). The filter does not see the bias, so it needs no fitted bias
 * (which over a short memory would also follow a slow tone and hide it). */
static void update_spectrum(ladrc_hp_estimator_t *est, ladrc_real_t x)
{
    const ladrc_real_t wf = est->filter_rad_s;
    const ladrc_real_t t = est->fit_period_s;
    ladrc_real_t *v = est->spec_x;
    /* (s + wf)^6 = s^6 + 6 wf s^5 + 15 wf^2 s^4 + 20 wf^3 s^3 + 15 wf^4 s^2 + 6 wf^5 s + wf^6 */
    const ladrc_real_t w2 = wf * wf;
    const ladrc_real_t w3 = w2 * wf;
    const ladrc_real_t d6 = w3 * w3 * (x - v[0]) - LADRC_R(6.0) * w3 * w2 * v[1] - LADRC_R(15.0) * w2 * w2 * v[2] -
                            LADRC_R(20.0) * w3 * v[3] - LADRC_R(15.0) * w2 * v[4] - LADRC_R(6.0) * wf * v[5];
    const ladrc_real_t x1_2 = est->spec_x1_prev[1];
    const ladrc_real_t x3_1 = est->spec_x3_prev;
    est->spec_x1_prev[1] = est->spec_x1_prev[0];
    est->spec_x1_prev[0] = v[1];
    est->spec_x3_prev = v[3];
    v[5] += t * d6;
    for (unsigned i = 5u; i > 0u; --i) {
        v[i - 1u] += t * v[i];
    }
    const ladrc_real_t x5 = v[5];
    /* The averages keep at least FREQ_MEMORY_RAD of the slowest locked
     * tone's phase (a tone not locked may be far off its frequency). */
    ladrc_real_t rate = est->freq_lambda0_per_s;
    for (unsigned k = 0u; k < est->n_active; ++k) {
        if (est->tone[k].locked) {
            rate = min_real(rate, est->tone[k].w_rad_s / FREQ_MEMORY_RAD);
        }
    }
    ladrc_real_t *m = est->spec_avg;
    if (est->spec_restart_left > 0u) {
        if (--est->spec_restart_left == 0u) {
            for (unsigned i = 0u; i < SPEC_COUNT; ++i) {
                m[i] = LADRC_R(0.0);
            }
            est->spec_count = 0u;
        }
        return;
    }
    if (est->spec_count < UINT16_MAX) {
        est->spec_count++;
    }
    /* Plain means of everything since the (re)start until those hold as
     * many samples as the forgetting's memory, then forgetting. */
    const ladrc_real_t alpha = ladrc_clamp(LADRC_R(1.0) / (ladrc_real_t)est->spec_count, rate * t, LADRC_R(1.0));
    m[SPEC_11] += alpha * (x1_2 * x1_2 - m[SPEC_11]);
    m[SPEC_31] += alpha * (x3_1 * x1_2 - m[SPEC_31]);
    m[SPEC_33] += alpha * (x3_1 * x3_1 - m[SPEC_33]);
    m[SPEC_51] += alpha * (x5 * x1_2 - m[SPEC_51]);
    m[SPEC_53] += alpha * (x5 * x3_1 - m[SPEC_53]);
    m[SPEC_55] += alpha * (x5 * x5 - m[SPEC_55]);
}

/* w from sigma^2 = (2 sin(w T / 2) / T)^2: w = (2 / T) asin(sigma T / 2),
 * here to the cubic term (relative error under 1e-5 for w T < 0.2); 0 when
 * sigma^2 gives no frequency in range. */
static ladrc_real_t freq_of(const ladrc_hp_estimator_t *est, ladrc_real_t sigma2)
{
    if (!(sigma2 > LADRC_R(0.0))) {
        return LADRC_R(0.0);
    }
    const ladrc_real_t s = ladrc_sqrt(sigma2);
    const ladrc_real_t t = est->fit_period_s;
    const ladrc_real_t w = s + sigma2 * s * t * t / LADRC_R(24.0);
    return (w > est->freq_min_rad_s && w < est->freq_max_rad_s) ? w : LADRC_R(0.0);
}

/* The clean model the averages show: one tone if x3 = -sigma^2 x1 explains
 * x3, else (n_tones 2) two tones if x5 + p1 x3 + p2 x1 = 0 explains x5, the
 * roots of sigma^4 - p1 sigma^2 + p2 giving the two; returns the number of
 * tones found (0: none clean) and their frequencies in w, ascending. */
static unsigned clean_tones(const ladrc_hp_estimator_t *est, ladrc_real_t w[LADRC_HP_MAX_TONES])
{
    const ladrc_real_t *m = est->spec_avg;
    if ((ladrc_real_t)est->spec_count * est->fit_period_s < SPEC_MIN_S || est->spec_restart_left > 0u ||
        !(m[SPEC_11] > FILTER_MIN_POWER && m[SPEC_33] > LADRC_R(0.0))) {
        return 0u;
    }
    /* One tone: 1 - correlation^2 of x3 and x1 is the share of x3 it leaves. */
    const ladrc_real_t det = m[SPEC_33] * m[SPEC_11] - m[SPEC_31] * m[SPEC_31];
    if (det < IMPURITY_MAX * m[SPEC_33] * m[SPEC_11]) {
        w[0] = freq_of(est, -m[SPEC_31] / m[SPEC_11]);
        return (w[0] > LADRC_R(0.0)) ? 1u : 0u;
    }
    if (est->n_tones < 2u || !(m[SPEC_55] > LADRC_R(0.0))) {
        return 0u;
    }
    /* Two tones: least squares for (p1, p2) on x5 = -p1 x3 - p2 x1. */
    const ladrc_real_t p1 = -(m[SPEC_53] * m[SPEC_11] - m[SPEC_51] * m[SPEC_31]) / det;
    const ladrc_real_t p2 = -(m[SPEC_33] * m[SPEC_51] - m[SPEC_31] * m[SPEC_53]) / det;
    const ladrc_real_t left = m[SPEC_55] + p1 * m[SPEC_53] + p2 * m[SPEC_51];
    const ladrc_real_t disc = p1 * p1 - LADRC_R(4.0) * p2;
    if (!(left < IMPURITY_MAX * m[SPEC_55]) || !(p2 > LADRC_R(0.0)) || !(disc > LADRC_R(0.0))) {
        return 0u;
    }
    const ladrc_real_t root = ladrc_sqrt(disc);
    w[0] = freq_of(est, LADRC_R(0.5) * (p1 - root));
    w[1] = freq_of(est, LADRC_R(0.5) * (p1 + root));
    const int apart = w[1] > (LADRC_R(1.0) + TONE_SEPARATION) * w[0];
    return (w[0] > LADRC_R(0.0) && w[1] > LADRC_R(0.0) && apart) ? 2u : 0u;
}

/* ONLINE: the active tones follow the frequency fit while it sees a clean
 * model with as many tones (exact for one clean tone). While it does not
 * (the loop's transients, which the derivatives weigh heavily, blur it), and
 * for a locked pair of tones (their fit uses the fifth derivative, noisier
 * than their slips), a locked tone follows its slip instead. Returns the
 * number of tones the fit must restart with (hp_restart_tones, at the
 * frequencies found), 0 if none: a clean model with another number of
 * tones (after TONE_HOLD_S without such a change), or a tone not locked
 * that jumped. */
unsigned hp_update_frequencies(ladrc_hp_estimator_t *est, ladrc_real_t sample)
{
    update_spectrum(est, sample);
    /* The model is judged every SPEC_DECIDE-th fit sample: its averages
     * change slowly, and the judgement costs divisions and roots. */
    if (++est->spec_decide < SPEC_DECIDE) {
        /* in between, the tones that follow their slips follow them */
        if (!est->clean || est->n_active > 1u) {
            for (unsigned k = 0u; k < est->n_active; ++k) {
                track_slip(est, &est->tone[k]);
            }
        }
        return 0u;
    }
    est->spec_decide = 0u;
    ladrc_real_t *w = est->found_rad_s;
    const unsigned found = clean_tones(est, w);
    est->clean = (found == est->n_active) ? 1u : 0u;
    est->contradicts = (found > 0u && found != est->n_active) ? 1u : 0u;
    for (unsigned k = 0u; k < found && k < est->n_active; ++k) {
        if (ladrc_fabs(w[k] - est->tone[k].w_rad_s) > TONE_SEPARATION * w[k]) {
            est->contradicts = 1u;
        }
    }
    if (est->hold < UINT16_MAX) {
        est->hold++;
    }
    if (found == 0u || (found != est->n_active && (ladrc_real_t)est->hold * est->fit_period_s < TONE_HOLD_S)) {
        for (unsigned k = 0u; k < est->n_active; ++k) {
            track_slip(est, &est->tone[k]);
        }
        return 0u;
    }
    if (found != est->n_active) {
        return found;
    }
    unsigned jumped = 0u;
    for (unsigned k = 0u; k < est->n_active; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        const int far = ladrc_fabs(w[k] - tone->w_rad_s) > TONE_SEPARATION * tone->w_rad_s;
        if (tone->locked && (found > 1u || far)) {
            /* Two tones come from the fifth derivative, noisier than a
             * locked pair's slips; a far frequency is another tone. */
            track_slip(est, tone);
        } else if (!tone->locked && far) {
            jumped = 1u; /* what the fit holds for it belongs to another frequency */
        } else {
            hp_set_tone_freq(&est->basis, est->advance, tone, w[k]);
        }
    }
    return jumped ? found : 0u;
}

void hp_freq_reset(ladrc_hp_estimator_t *est)
{
    for (unsigned i = 0u; i < 6u; ++i) {
        est->spec_x[i] = LADRC_R(0.0);
    }
    for (unsigned i = 0u; i < SPEC_COUNT; ++i) {
        est->spec_avg[i] = LADRC_R(0.0);
    }
    est->spec_x1_prev[0] = LADRC_R(0.0);
    est->spec_x1_prev[1] = LADRC_R(0.0);
    est->spec_x3_prev = LADRC_R(0.0);
    est->spec_count = 0u;
    est->spec_decide = 0u;
    est->found_rad_s[0] = LADRC_R(0.0);
    est->found_rad_s[LADRC_HP_MAX_TONES - 1u] = LADRC_R(0.0);
    est->clean = 0u;
    est->contradicts = 0u;
    est->spec_restart_left = 0u;
}

void hp_freq_after_change(ladrc_hp_estimator_t *est)
{
    /* One restart of the frequency fit at a time: a change seen again while
     * one is pending does not delay it further. */
    if (est->spec_restart_left == 0u) {
        est->spec_restart_left = hp_count(FILTER_SETTLE_PER_WF / (est->filter_rad_s * est->fit_period_s));
    }
}

#endif /* LADRC_WITH_HP_ONLINE */
