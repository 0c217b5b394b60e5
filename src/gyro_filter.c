/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file gyro_filter.c
 * @brief Fixed notches, RPM notches and a low-pass on shared coefficients,
 *        in direct form I (gyro_filter.h; docs/method.md section 7).
 */
#include "ladrc/gyro_filter.h"
#include "compiler.h"
#include "require.h"

#include <stddef.h>

#define SQRT2 LADRC_R(1.41421356237309504880)

/* A sample the chain may take: finite (by bits under fast-math) and within
 * the bound that keeps the history 2^64 below overflow. */
static inline int sample_is_good(ladrc_real_t x)
{
    return ladrc_is_finite(x) && ladrc_fabs(x) <= LADRC_GYRO_FILTER_INPUT_MAX;
}

/*
 * The one section formula. Direct form I because the RPM notches get new
 * coefficients every tick: its history is the section's own past inputs and
 * outputs, which mean the same under any coefficients, so a change acts like
 * a change of the filter from now on. Direct form II keeps internal states
 * weighted by the old coefficients, which new ones misread into a transient.
 */
static LADRC_FORCE_INLINE ladrc_real_t section_output(const ladrc_gyro_filter_section_t *c,
                                                      const ladrc_gyro_filter_history_t *h, ladrc_real_t x)
{
    return c->b0 * x + c->b1 * h->x1 + c->b2 * h->x2 - c->a1 * h->y1 - c->a2 * h->y2;
}

/* The section's history moved on by one tick of input x and output y. */
static LADRC_FORCE_INLINE void section_push(ladrc_gyro_filter_history_t *h, ladrc_real_t x, ladrc_real_t y)
{
    h->x2 = h->x1;
    h->x1 = x;
    h->y2 = h->y1;
    h->y1 = y;
}

/* An off section passes its input and records it as its output, so that its
 * history is what a notch with nothing to remove would have: it comes back
 * without a step. */
static inline void section_pass(ladrc_gyro_filter_history_t *h, ladrc_real_t x)
{
    section_push(h, x, x);
}

/* A channel's envelope after a sample of magnitude m: the larger of m and the
 * decayed envelope. */
static inline ladrc_real_t envelope_next(ladrc_real_t m, ladrc_real_t decayed)
{
    return (m > decayed) ? m : decayed;
}

/* LADRC_FORCE_INLINE below: -Os keeps these helpers out of line in
 * ladrc_gyro_filter_set_rotor_hz; inlined, moving 12 RPM centres takes 902
 * instructions instead of 1,061 on the Cortex-M4F (tools/bench). */

/* Terms of the sine's Taylor series: the first one left out, x^(2n+1)/(2n+1)!
 * at the largest x (below), is under half an ulp of the type. */
#ifdef LADRC_REAL_DOUBLE
#define SIN_TERMS 10u /* x^21/21! = 3e-17 at x = 1.414 */
#else
#define SIN_TERMS 6u /* x^13/13! = 1.5e-8 at x = 1.414 */
#endif

/* sin x for x in [0, 0.45 pi], half of any centre's angle below the Nyquist
 * guard: the Taylor series by Horner, x (1 - x^2/(2 3) (1 - x^2/(4 5) (...))).
 * A handful of multiplications, where the C library's sinf and cosf cost the
 * RPM bank most of its update on a Cortex-M4F. */
static LADRC_FORCE_INLINE ladrc_real_t sin_to_half_guard(ladrc_real_t x)
{
    static const ladrc_real_t inv[SIN_TERMS] = {
        LADRC_R(0.0), /* unused: the leading 1 */
        LADRC_R(1.0) / LADRC_R(6.0),
        LADRC_R(1.0) / LADRC_R(20.0),
        LADRC_R(1.0) / LADRC_R(42.0),
        LADRC_R(1.0) / LADRC_R(72.0),
        LADRC_R(1.0) / LADRC_R(110.0),
#ifdef LADRC_REAL_DOUBLE
        LADRC_R(1.0) / LADRC_R(156.0),
        LADRC_R(1.0) / LADRC_R(210.0),
        LADRC_R(1.0) / LADRC_R(272.0),
        LADRC_R(1.0) / LADRC_R(342.0),
#endif
    };
    const ladrc_real_t x2 = x * x;
    ladrc_real_t p = LADRC_R(1.0);
    for (unsigned k = SIN_TERMS - 1u; k >= 1u; --k) {
        p = LADRC_R(1.0) - x2 * inv[k] * p;
    }
    return x * p;
}

/* cos and sin of a centre's angle w0 in [0, 0.9 pi] from its half angle:
 * cos = 1 - 2 sin^2(w0/2) keeps the small 1 - cos of low centres exact to
 * the ulp, sin = 2 sin(w0/2) cos(w0/2) with cos(w0/2) >= 0.156 there. */
static LADRC_FORCE_INLINE void centre_cos_sin(ladrc_real_t w0_rad, ladrc_real_t *c, ladrc_real_t *s)
{
    const ladrc_real_t sh = sin_to_half_guard(LADRC_R(0.5) * w0_rad);
    *c = LADRC_R(1.0) - LADRC_R(2.0) * sh * sh;
    *s = LADRC_R(2.0) * sh * LADRC_SQRT(LADRC_R(1.0) - sh * sh);
}

/* The notch at cos(w0) = c with alpha = sin(w0) / (2 Q), divided through by
 * 1 + alpha: its only division. */
static LADRC_FORCE_INLINE void set_notch(ladrc_gyro_filter_section_t *s, ladrc_real_t c, ladrc_real_t alpha)
{
    const ladrc_real_t g = LADRC_R(1.0) / (LADRC_R(1.0) + alpha);
    s->b0 = g;
    s->b1 = LADRC_R(-2.0) * c * g;
    s->b2 = g;
    s->a1 = s->b1;
    s->a2 = (LADRC_R(1.0) - alpha) * g;
}

/* The low-pass of order 1 or 2 at K = tan(pi fc dt). The numerator comes from
 * the rounded denominator, b0 + b1 + b2 = 1 + a1 + a2, so the DC gain is 1
 * to the last bit however close to 1 the poles are. */
static void set_lowpass(ladrc_gyro_filter_section_t *s, uint8_t order, ladrc_real_t k)
{
    if (order == 1u) {
        s->a1 = (k - LADRC_R(1.0)) / (k + LADRC_R(1.0));
        s->a2 = LADRC_R(0.0);
        s->b0 = LADRC_R(0.5) * (LADRC_R(1.0) + s->a1);
        s->b1 = s->b0;
        s->b2 = LADRC_R(0.0);
    } else {
        const ladrc_real_t norm = LADRC_R(1.0) / (LADRC_R(1.0) + SQRT2 * k + k * k);
        s->a1 = LADRC_R(2.0) * (k * k - LADRC_R(1.0)) * norm;
        s->a2 = (LADRC_R(1.0) - SQRT2 * k + k * k) * norm;
        s->b0 = LADRC_R(0.25) * (LADRC_R(1.0) + s->a1 + s->a2);
        s->b1 = LADRC_R(2.0) * s->b0;
        s->b2 = s->b0;
    }
    s->weight = LADRC_R(1.0);
}

/* Finite, b0 > 0 and both poles strictly inside the unit circle as rounded
 * (|a2| < 1, |a1| < 1 + a2): a section init may hand to the step. */
static int section_is_stable(const ladrc_gyro_filter_section_t *s)
{
    return ladrc_all_finite4(s->b0, s->b1, s->b2, s->a1) && ladrc_is_finite(s->a2) && s->b0 > LADRC_R(0.0) &&
           ladrc_fabs(s->a2) < LADRC_R(1.0) && ladrc_fabs(s->a1) < LADRC_R(1.0) + s->a2;
}

/* Rounding margin of an RPM notch's stability (in eps; below). */
#define RPM_STABILITY_MARGIN_EPS LADRC_R(16.0)

/*
 * Whether the RPM notch at w0_rad (radians per tick) with 1 / (2 Q) = inv_2q
 * rounds to a stable section, with a margin that holds it stable at every
 * centre between two ends that pass. The notch's stability margin,
 * 1 + a2 - |a1| = 2 g (1 - |cos w0|) with g = 1 / (1 + alpha), rises from
 * either end of (0, pi) towards pi / 2 for any Q (its derivative is
 * sin w + (1 - cos w) / (2 Q) > 0 below pi / 2, mirrored above), and the
 * rounding of a1 and a2 moves it by up to some 1.5 eps: 16 eps at the ends
 * keeps every centre between them stable as rounded. A Q so low that the
 * notch is wider than float can place its poles (a2 rounding to -1 near
 * pi / 2: the fuzz target found Q 1.4e-8) and a Q so high that alpha vanishes
 * both fail it.
 */
static int rpm_notch_is_stable(ladrc_real_t w0_rad, ladrc_real_t inv_2q)
{
    ladrc_gyro_filter_section_t s;
    ladrc_real_t c, sn;
    centre_cos_sin(w0_rad, &c, &sn);
    set_notch(&s, c, sn * inv_2q);
    return section_is_stable(&s) &&
           (s.b0 + s.b0) * (LADRC_R(1.0) - ladrc_fabs(c)) >= RPM_STABILITY_MARGIN_EPS * LADRC_REAL_EPS;
}

/* A centre that can carry a notch: finite, > 0 and below centre_max_hz. */
static int centre_is_valid(const ladrc_gyro_filter_t *f, ladrc_real_t hz)
{
    return ladrc_is_positive(hz) && hz < f->centre_max_hz;
}

static ladrc_status_t setup_lowpass(const ladrc_gyro_filter_config_t *cfg, ladrc_gyro_filter_section_t *s)
{
    const ladrc_real_t cycles = cfg->lpf_cutoff_hz * cfg->dt_s;
    if (!ladrc_is_positive(cfg->lpf_cutoff_hz) || !(cycles < LADRC_R(0.5))) {
        return LADRC_ERR_GYRO_LPF_CUTOFF_HZ;
    }
    /* tan from sin / cos: init only. Near Nyquist cos may round to 0 or below. */
    set_lowpass(s, cfg->lpf_order, LADRC_SIN(LADRC_PI * cycles) / LADRC_COS(LADRC_PI * cycles));
    return section_is_stable(s) ? LADRC_OK : LADRC_ERR_GYRO_LPF_CUTOFF_HZ;
}

static ladrc_status_t setup_notches(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg)
{
    ladrc_real_t inv_2q;
    unsigned i;
    if (cfg->n_notches > LADRC_GYRO_FILTER_MAX_NOTCHES) {
        return LADRC_ERR_GYRO_N_NOTCHES;
    }
    for (i = 0u; i < cfg->n_notches; ++i) {
        if (!centre_is_valid(f, cfg->notch_hz[i])) {
            return LADRC_ERR_GYRO_NOTCH_HZ;
        }
    }
    if (cfg->n_notches == 0u) {
        return LADRC_OK;
    }
    if (!ladrc_is_positive(cfg->notch_q)) {
        return LADRC_ERR_GYRO_NOTCH_Q;
    }
    inv_2q = LADRC_R(0.5) / cfg->notch_q;
    for (i = 0u; i < cfg->n_notches; ++i) {
        ladrc_gyro_filter_section_t *s = &f->section[i];
        ladrc_real_t c, sn;
        centre_cos_sin(f->rad_per_hz * cfg->notch_hz[i], &c, &sn);
        set_notch(s, c, sn * inv_2q);
        s->weight = LADRC_R(1.0);
        if (!section_is_stable(s)) {
            return LADRC_ERR_GYRO_NOTCH_Q;
        }
    }
    return LADRC_OK;
}

static ladrc_status_t setup_rpm(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg)
{
    if (cfg->rpm_rotors > LADRC_GYRO_FILTER_MAX_ROTORS) {
        return LADRC_ERR_GYRO_RPM_ROTORS;
    }
    if (cfg->rpm_rotors == 0u) {
        return LADRC_OK;
    }
    if (cfg->rpm_harmonics < 1u || cfg->rpm_harmonics > LADRC_GYRO_FILTER_MAX_HARMONICS) {
        return LADRC_ERR_GYRO_RPM_HARMONICS;
    }
    if (!centre_is_valid(f, cfg->rpm_min_hz)) {
        return LADRC_ERR_GYRO_RPM_MIN_HZ;
    }
    /* The comparison is false for NaN, so NaN is rejected too. */
    if (!ladrc_is_finite(cfg->rpm_fade_hz) || !(cfg->rpm_fade_hz >= LADRC_R(0.0))) {
        return LADRC_ERR_GYRO_RPM_FADE_HZ;
    }
    f->rpm_inv_fade_per_hz = LADRC_R(0.0);
    if (cfg->rpm_fade_hz > LADRC_R(0.0)) {
        f->rpm_inv_fade_per_hz = LADRC_R(1.0) / cfg->rpm_fade_hz;
        if (!ladrc_is_finite(f->rpm_inv_fade_per_hz)) {
            return LADRC_ERR_GYRO_RPM_FADE_HZ;
        }
    }
    if (!ladrc_is_positive(cfg->rpm_q)) {
        return LADRC_ERR_GYRO_RPM_Q;
    }
    f->rpm_inv_2q = LADRC_R(0.5) / cfg->rpm_q;
    /* The ends of the range an RPM notch can be on in: the least stable
     * notches (rpm_notch_is_stable). */
    if (!rpm_notch_is_stable(f->rad_per_hz * cfg->rpm_min_hz, f->rpm_inv_2q) ||
        !rpm_notch_is_stable(LADRC_GYRO_FILTER_CENTRE_MAX_NYQUIST * LADRC_PI, f->rpm_inv_2q)) {
        return LADRC_ERR_GYRO_RPM_Q;
    }
    f->rpm_min_hz = cfg->rpm_min_hz;
    f->rpm_full_hz = cfg->rpm_min_hz + cfg->rpm_fade_hz;
    f->rpm_rotors = cfg->rpm_rotors;
    f->rpm_harmonics = cfg->rpm_harmonics;
    /* Weight 0 (zeroed by init): off until the first set_rotor_hz. */
    return LADRC_OK;
}

static ladrc_status_t setup(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg)
{
    ladrc_status_t st;
    unsigned n;
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (cfg->channels < 1u || cfg->channels > LADRC_GYRO_FILTER_MAX_CHANNELS) {
        return LADRC_ERR_GYRO_CHANNELS;
    }
    if (cfg->lpf_order > 2u) {
        return LADRC_ERR_GYRO_LPF_ORDER;
    }
    f->rad_per_hz = LADRC_TWO_PI * cfg->dt_s;
    f->centre_max_hz = LADRC_GYRO_FILTER_CENTRE_MAX_NYQUIST * LADRC_R(0.5) / cfg->dt_s;
    /* The low-pass is the chain's last section: its index is known after the
     * notches, its cutoff is checked before them (the documented order). */
    ladrc_gyro_filter_section_t lpf = {0};
    if (cfg->lpf_order > 0u) {
        st = setup_lowpass(cfg, &lpf);
        if (st != LADRC_OK) {
            return st;
        }
    }
    st = setup_notches(f, cfg);
    if (st != LADRC_OK) {
        return st;
    }
    st = setup_rpm(f, cfg);
    if (st != LADRC_OK) {
        return st;
    }
    f->rpm_first = cfg->n_notches;
    n = (unsigned)cfg->n_notches + (unsigned)f->rpm_rotors * f->rpm_harmonics;
    if (cfg->lpf_order > 0u) {
        f->section[n] = lpf;
        ++n;
    }
    f->n_sections = (uint8_t)n;
    f->channels = cfg->channels;
    f->envelope_decay = ladrc_exp(-cfg->dt_s / LADRC_GYRO_FILTER_ENVELOPE_TAU_S);
    return LADRC_OK;
}

void ladrc_gyro_filter_config_default(ladrc_gyro_filter_config_t *cfg, ladrc_real_t dt_s, uint8_t channels)
{
    const ladrc_real_t fifth_nyquist_hz = LADRC_R(0.1) / dt_s;
    /* 100 Hz, or a fifth of Nyquist on slower loops (NaN from a bad dt_s: 100, which init refuses anyway) */
    const ladrc_real_t hz = (fifth_nyquist_hz < LADRC_R(100.0)) ? fifth_nyquist_hz : LADRC_R(100.0);
    const ladrc_gyro_filter_config_t zero = {0};
    LADRC_REQUIRE_VOID(cfg != NULL);
    *cfg = zero;
    cfg->dt_s = dt_s;
    cfg->channels = channels;
    cfg->lpf_cutoff_hz = hz;
    cfg->notch_q = LADRC_R(5.0);
    cfg->rpm_harmonics = 3u;
    cfg->rpm_q = LADRC_R(5.0);
    cfg->rpm_min_hz = hz;
    cfg->rpm_fade_hz = LADRC_R(0.5) * hz;
}

ladrc_status_t ladrc_gyro_filter_init(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg)
{
    ladrc_status_t st;
    if (f == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    /* A rejected config leaves an all-zero instance: no channels, its steps refused. */
    (void)memset(f, 0, sizeof *f);
    st = setup(f, cfg);
    if (st != LADRC_OK) {
        (void)memset(f, 0, sizeof *f);
    }
    return st;
}

void ladrc_gyro_filter_reset(ladrc_gyro_filter_t *f, const ladrc_real_t *value)
{
    LADRC_REQUIRE_VOID(f != NULL && value != NULL);
    f->faults = LADRC_FAULT_NONE;
    for (unsigned ch = 0u; ch < f->channels; ++ch) {
        ladrc_real_t v = value[ch];
        if (!sample_is_good(v)) {
            /* Never let a bad sample into the state: rest where we are. */
            v = f->out[ch];
            f->faults = LADRC_FAULT_INPUT;
        }
        for (unsigned s = 0u; s < f->n_sections; ++s) {
            ladrc_gyro_filter_history_t *h = &f->hist[ch][s];
            h->x1 = v;
            h->x2 = v;
            h->y1 = v;
            h->y2 = v;
        }
        f->out[ch] = v;
        f->envelope[ch] = ladrc_fabs(v);
    }
}

/* An RPM notch's weight at centre_hz: off below rpm_min_hz and from
 * centre_max_hz on, 1 from rpm_full_hz, linear in between. */
static LADRC_FORCE_INLINE ladrc_real_t rpm_weight(const ladrc_gyro_filter_t *f, ladrc_real_t centre_hz)
{
    if (!(centre_hz >= f->rpm_min_hz) || !(centre_hz < f->centre_max_hz)) {
        return LADRC_R(0.0);
    }
    if (centre_hz >= f->rpm_full_hz) {
        return LADRC_R(1.0);
    }
    /* The clamp catches a rounding above 1 just below rpm_full_hz. */
    return ladrc_clamp((centre_hz - f->rpm_min_hz) * f->rpm_inv_fade_per_hz, LADRC_R(0.0), LADRC_R(1.0));
}

ladrc_fault_t ladrc_gyro_filter_set_rotor_hz(ladrc_gyro_filter_t *f, const ladrc_real_t *rotor_hz)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    LADRC_REQUIRE(f != NULL && rotor_hz != NULL, LADRC_FAULT_STATE);
    for (unsigned r = 0u; r < f->rpm_rotors; ++r) {
        const ladrc_real_t hz = rotor_hz[r];
        ladrc_gyro_filter_section_t *s = &f->section[f->rpm_first + r * f->rpm_harmonics];
        ladrc_real_t c1, c, s1, sn, c_prev, s_prev, centre_hz;
        if (!ladrc_is_finite(hz) || !(hz >= LADRC_R(0.0))) {
            faults = LADRC_FAULT_INPUT; /* this rotor's notches stay where they were */
            continue;
        }
        if (!(hz * (ladrc_real_t)f->rpm_harmonics >= f->rpm_min_hz) || !(hz < f->centre_max_hz)) {
            /* Every harmonic below the minimum or the first past the guard: all
             * off, no trigonometry (and none of a huge hz's overflow). */
            for (unsigned h = 0u; h < f->rpm_harmonics; ++h) {
                s[h].weight = LADRC_R(0.0);
            }
            continue;
        }
        centre_cos_sin(f->rad_per_hz * hz, &c1, &s1);
        c = c1;
        sn = s1;
        c_prev = LADRC_R(1.0);
        s_prev = LADRC_R(0.0);
        centre_hz = hz;
        for (unsigned h = 0u; h < f->rpm_harmonics; ++h, centre_hz += hz) {
            ladrc_real_t next;
            s[h].weight = rpm_weight(f, centre_hz);
            if (s[h].weight > LADRC_R(0.0)) {
                set_notch(&s[h], c, sn * f->rpm_inv_2q);
            }
            /* harmonic h + 2 from h + 1 and h: cos(kw) = 2 cos(w) cos((k-1)w) - cos((k-2)w) */
            next = LADRC_R(2.0) * c1 * c - c_prev;
            c_prev = c;
            c = next;
            next = LADRC_R(2.0) * c1 * sn - s_prev;
            s_prev = sn;
            sn = next;
        }
    }
    return faults;
}

/* One channel through its chain, history moved on; the oldest history of each
 * section is kept in undo first. The RPM notches' outputs (and so their
 * histories) are held within +-bound (LADRC_GYRO_FILTER_RPM_GAIN_BOUND; the
 * branch almost never taken); the fixed sections are left to the state
 * guard (a history corrupted from outside is a state fault, not hidden). */
static ladrc_real_t chain_step(ladrc_gyro_filter_t *f, ladrc_gyro_filter_history_t *hist, ladrc_real_t x,
                               ladrc_real_t bound)
{
    const unsigned rpm_end = (unsigned)f->rpm_first + (unsigned)f->rpm_rotors * f->rpm_harmonics;
    for (unsigned i = 0u; i < f->n_sections; ++i) {
        const ladrc_gyro_filter_section_t *s = &f->section[i];
        ladrc_gyro_filter_history_t *h = &hist[i];
        f->undo[i][0] = h->x2;
        f->undo[i][1] = h->y2;
        if (s->weight > LADRC_R(0.0)) {
            ladrc_real_t y = section_output(s, h, x);
            if (ladrc_fabs(y) > bound && i >= f->rpm_first && i < rpm_end) {
                y = (y > LADRC_R(0.0)) ? bound : -bound;
            }
            section_push(h, x, y);
            x = x + s->weight * (y - x); /* one path: no branch on the weight (within an ulp of y at 1) */
        } else {
            section_pass(h, x);
        }
    }
    return x;
}

/* Puts a channel's history back as it was before chain_step. */
static void chain_undo(const ladrc_gyro_filter_t *f, ladrc_gyro_filter_history_t *hist)
{
    for (unsigned i = 0u; i < f->n_sections; ++i) {
        ladrc_gyro_filter_history_t *h = &hist[i];
        h->x1 = h->x2;
        h->x2 = f->undo[i][0];
        h->y1 = h->y2;
        h->y2 = f->undo[i][1];
    }
}

ladrc_fault_t ladrc_gyro_filter_step(ladrc_gyro_filter_t *f, const ladrc_real_t *in, ladrc_real_t *out)
{
    ladrc_fault_t faults = LADRC_FAULT_NONE;
    LADRC_REQUIRE(f != NULL && in != NULL && out != NULL, LADRC_FAULT_STATE);
    if (f->channels == 0u) {
        /* init refused this instance: nothing to filter with */
        f->faults = LADRC_FAULT_STATE;
        return f->faults;
    }
    for (unsigned ch = 0u; ch < f->channels; ++ch) {
        const ladrc_real_t x = in[ch];
        ladrc_real_t y;
        if (!sample_is_good(x)) {
            faults |= LADRC_FAULT_INPUT;
            out[ch] = f->out[ch];
            continue;
        }
        f->envelope[ch] = envelope_next(ladrc_fabs(x), f->envelope[ch] * f->envelope_decay);
        /* A non-finite value anywhere in the chain reaches its output (every
         * section passes its input with a non-zero gain), so one test suffices. */
        y = chain_step(f, f->hist[ch], x, LADRC_GYRO_FILTER_RPM_GAIN_BOUND * f->envelope[ch]);
        if (!ladrc_is_finite(y)) {
            chain_undo(f, f->hist[ch]);
            faults |= LADRC_FAULT_STATE;
            out[ch] = f->out[ch];
            continue;
        }
        f->out[ch] = y;
        out[ch] = y;
    }
    f->faults = faults;
    return faults;
}

ladrc_real_t ladrc_gyro_filter_get_rpm_weight(const ladrc_gyro_filter_t *f, uint8_t rotor, uint8_t harmonic)
{
    LADRC_REQUIRE(f != NULL, LADRC_R(0.0));
    if (rotor >= f->rpm_rotors || harmonic < 1u || harmonic > f->rpm_harmonics) {
        return LADRC_R(0.0);
    }
    return f->section[f->rpm_first + (unsigned)rotor * f->rpm_harmonics + harmonic - 1u].weight;
}
