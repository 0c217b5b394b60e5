/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * What the HP estimator (estimator_hp.c) and its ONLINE frequency search
 * (estimator_hp_freq.c) share; not installed. A tone's frequency is set
 * below both (estimator_hp_tone.c), so neither calls the other back. The
 * search's functions run on fit samples only, out of line, so that their
 * locals are not on the stack of the path through the RLS update, the
 * deepest of a tick.
 */
#ifndef LADRC_ESTIMATOR_HP_INTERNAL_H
#define LADRC_ESTIMATOR_HP_INTERNAL_H

#include "ladrc/estimator.h"

/* What ladrc_hp_get_estimate, ladrc_hp_get_command and ladrc_hp_get_handover read, for the HP
 * axis's tick too (axis_hp.h): no call and no NULL test for an estimator
 * the axis owns. */
static inline ladrc_real_t hp_estimate(const ladrc_hp_estimator_t *est)
{
    return est->estimate;
}

static inline ladrc_real_t hp_command(const ladrc_hp_estimator_t *est)
{
    return est->advance ? est->command : est->estimate;
}

static inline ladrc_real_t hp_handover(const ladrc_hp_estimator_t *est)
{
    return est->handover;
}

/* Which tick of each block of fit_decimation ticks fits (the attitude layer
 * staggers its axes so that a tick carries at most one fit). */
static inline void hp_set_fit_phase(ladrc_hp_estimator_t *est, unsigned phase)
{
    est->fit_phase = (uint16_t)(phase % est->fit_decimation); /* fit_decimation >= 1 (init) */
}

/* Index of tone k's a in the fit's theta = (c, a_1, b_1, ..., a_n, b_n). */
static inline unsigned theta_a(unsigned k)
{
    return 1u + 2u * k;
}

static inline ladrc_real_t min_real(ladrc_real_t a, ladrc_real_t b)
{
    return (b < a) ? b : a;
}

static inline ladrc_real_t max_real(ladrc_real_t a, ladrc_real_t b)
{
    return (b > a) ? b : a;
}

/* A count of fit samples, x rounded, held within 0..UINT16_MAX (an x out
 * of that range or not a number, from a fit period near its bounds,
 * converts to no integer; NaN: the most). */
static inline uint16_t hp_count(ladrc_real_t x)
{
    if (x < LADRC_R(0.0)) {
        return 0u;
    }
    if (x < LADRC_R(65534.5)) {
        return (uint16_t)(x + LADRC_R(0.5));
    }
    return UINT16_MAX;
}

/* 1: the frequencies are searched online (never without the search built). */
static inline int hp_online(const ladrc_hp_estimator_t *est)
{
#if LADRC_WITH_HP_ONLINE
    return est->online;
#else
    (void)est;
    return 0;
#endif
}

/* 1 while an ONLINE search sees a clean model whose tones are not the
 * active ones (another number, or a frequency far from a tone's): no tone
 * may lock then. Under noise the search sees no clean model and leaves the
 * judgement to the band evidence. */
static inline int hp_search_contradicts(const ladrc_hp_estimator_t *est)
{
#if LADRC_WITH_HP_ONLINE
    return est->online && est->contradicts;
#else
    (void)est;
    return 0;
#endif
}

/* 1 unless an ONLINE search sees another number of clean tones than are
 * active (on a clean sample a tone may lock only while it agrees). */
static inline int hp_search_agrees(const ladrc_hp_estimator_t *est)
{
#if LADRC_WITH_HP_ONLINE
    return !est->online || est->clean;
#else
    (void)est;
    return 1;
#endif
}

/* The lead that undoes the observer's lag, (1 + j w / wo)^3, grows as
 * (w / wo)^3: beyond w = 10 wo it would amplify the sample a thousandfold. */
#define HP_LEAD_RATIO_MAX LADRC_R(10.0)

/* estimator_hp_tone.c */

/* A tone's frequency and what follows from it (its turn per tick, the
 * leads of the estimate and, with advance, of the command). */
void hp_set_tone_freq(const ladrc_hp_tone_basis_t *basis, unsigned advance, ladrc_hp_tone_t *tone,
                      ladrc_real_t w_rad_s);

/* The gate's window starts over: the phasor's means restart from the next
 * fit sample (its noise power and increments stay). */
static inline void hp_restart_window(ladrc_hp_tone_t *tone)
{
    tone->mean_a = LADRC_R(0.0);
    tone->mean_b = LADRC_R(0.0);
    tone->mean_power = LADRC_R(0.0);
    tone->gate_samples = 0u;
}

/* A tone whose phasor starts over: the gate's means restart (not locked). */
static inline void hp_forget_evidence(ladrc_hp_tone_t *tone)
{
    hp_restart_window(tone);
    tone->prev_da = LADRC_R(0.0);
    tone->prev_db = LADRC_R(0.0);
    tone->noise_power = LADRC_R(0.0);
    tone->evidence = LADRC_R(0.0);
    tone->coherence = LADRC_R(0.0);
    tone->locked = 0u;
}

/* A tone whose fit starts over: no phasor history, not significant, not locked. */
static inline void hp_forget_tone(ladrc_hp_tone_t *tone)
{
    tone->prev_a = LADRC_R(0.0);
    tone->prev_b = LADRC_R(0.0);
    tone->slip_rad_s = LADRC_R(0.0);
    tone->drift_per_s = LADRC_R(0.0);
    hp_forget_evidence(tone);
    tone->significant = 0u;
    tone->locked = 0u;
}

/* (Re)starts the fit with n tones and the given estimate (NULL: 0). */
static inline void hp_start_fit(ladrc_hp_estimator_t *est, unsigned n, const ladrc_real_t *theta0)
{
    /* Valid: init checked the largest n. */
    (void)ladrc_rls_restart(&est->fit, (uint8_t)(1u + 2u * n), theta0);
    est->n_active = (uint8_t)n;
#if LADRC_WITH_HP_ONLINE
    est->hold = 0u;
#endif
}

#if LADRC_WITH_HP_ONLINE
/* estimator_hp_freq.c: the ONLINE frequency search */

/* Forgets the search's filter, averages and findings. */
void hp_freq_reset(ladrc_hp_estimator_t *est);
/* A change was detected: the search restarts its averages once the change
 * has passed its filter. */
void hp_freq_after_change(ladrc_hp_estimator_t *est);
/* One fit sample of the search; returns the number of tones the fit must
 * restart with (hp_restart_tones), 0 if none. */
unsigned hp_update_frequencies(ladrc_hp_estimator_t *est, ladrc_real_t sample);
/* Restarts the fit with n tones at the frequencies found. */
void hp_restart_tones(ladrc_hp_estimator_t *est, unsigned n);
#endif

#endif /* LADRC_ESTIMATOR_HP_INTERNAL_H */
