/* SPDX-License-Identifier: BSD-3-Clause */
/* HP disturbance estimator: a bias and up to LADRC_HP_MAX_TONES tones fitted
 * by one RLS at known or online-estimated frequencies, behind a gate that
 * checks the frequencies themselves (see estimator.h). */
#include "require.h"

#include "compiler.h"
#include "estimator_hp_internal.h"

#define HP_PI LADRC_R(3.14159265358979)
/* Largest sample the fit takes (rad/s^2): a hundred times the largest
 * angular acceleration a multirotor reaches, so squares and fifth
 * derivatives of it stay far inside float. A larger one is a bad input. */
#define HP_SAMPLE_LIMIT_RAD_S2 LADRC_R(1e6)
/* Initial P of the RLS per sample (P h, rls.h keeps P in continuous units):
 * large against the gains it settles to, small enough that the first updates
 * do not amplify float rounding; the bound leaves room for 1 + 2 K of them. */
#define HP_P_INITIAL_PER_SAMPLE LADRC_R(1.0e3)
#define HP_P_BOUND_PER_SAMPLE LADRC_R(1.0e4)
/* The fit keeps at least this much of a significant tone's phase in memory
 * (rad), enough to tell the bias and the tone apart... */
#define FIT_MEMORY_RAD LADRC_R(0.5)
/* ...and this much of the relative phase of two significant tones. */
#define SEPARATION_MEMORY_RAD LADRC_R(1.0)
/* Slip (turn rate of a fitted phasor) averaged at this rate (1/s): a few
 * fit memories, so one noisy fit sample does not move a tone's frequency
 * far (the ONLINE search follows the slip). */
#define SLIP_AVERAGE_PER_S LADRC_R(10.0)
/* To lock, a tone's slip must stay below SLIP_TOL_FRACTION of the fit's rate
 * (the fit then follows the turning phasor with a phase error of about
 * slip / lambda) plus SLIP_NOISE_SIGMAS times the slip the phasor's noise
 * gives; to stay locked, below SLIP_UNLOCK_FACTOR times that. */
#define SLIP_TOL_FRACTION LADRC_R(0.1)
#define SLIP_NOISE_SIGMAS LADRC_R(3.0)
#define SLIP_UNLOCK_FACTOR LADRC_R(3.0)
/* A change of size counts at this weight beside the turn: a third, so a fit
 * whose amplitude still settles after a restart may lock, the tail of a
 * transient (decaying at several times lambda) may not. */
#define DRIFT_WEIGHT LADRC_R(0.33)
/* The gate judges each tone on its band (estimator.h "Gate"): the fitted
 * phasor's mean over a window of at least GATE_WINDOW_RAD of the tone's
 * phase and GATE_WINDOW_MEMORIES of the fit's memories... */
#define GATE_WINDOW_RAD LADRC_R(6.28318530717959)
#define GATE_WINDOW_MEMORIES LADRC_R(3.0)
/* ...must stand GATE_EVIDENCE_ON times above the power white noise alone
 * would give it to lock, GATE_EVIDENCE_OFF to stay locked (turbulence, whose
 * phasor wanders more slowly, crossed 64 times it 18 s per simulated hour,
 * 256 never: estimator.h)... */
#define GATE_EVIDENCE_ON LADRC_R(256.0)
#define GATE_EVIDENCE_OFF LADRC_R(64.0)
/* ...and hold at least GATE_COHERENCE_ON of the phasor's power less its
 * noise (a tone off its frequency by dw turns its phasor at dw: the mean
 * keeps 1 / (1 + (dw W)^2) of it), GATE_COHERENCE_OFF to stay locked. */
#define GATE_COHERENCE_ON LADRC_R(0.5)
#define GATE_COHERENCE_OFF LADRC_R(0.25)
/* The phasor's noise power is averaged over this many fit memories. */
#define NOISE_MEMORIES LADRC_R(2.0)
/* A tone is significant while its power a^2/2 is at least this share of the
 * sample's power around its mean and its amplitude above AMP_FLOOR. */
#define AMP_SHARE LADRC_R(0.01)
#define AMP_FLOOR_RAD_S2 LADRC_R(0.05)
/* The fit has settled while its recent prior error power is below this
 * share of the sample's power. */
#define SETTLED_SHARE LADRC_R(0.01)
#define NOISY_EXPLAINED_SHARE LADRC_R(0.5)
/* The fit's forgetting rate, times this once the weight has been 1 for
 * ENGAGED_SETTLE_S. */
#define ENGAGED_RATE_FRACTION LADRC_R(0.5)
#define ENGAGED_SETTLE_S LADRC_R(1.0)
/* The weight moves at most this much per second. */
#define GATE_RATE_PER_S LADRC_R(5.0)
/* The sample's mean and its power around it are averaged at these rates (1/s). */
#define MEAN_AVERAGE_PER_S LADRC_R(1.0)
#define POWER_AVERAGE_PER_S LADRC_R(3.0)
/* Change detection: fast and slow averages of the prior error power (1/s);
 * a change is a fast average CHANGE_RATIO times the slow one and at least
 * CHANGE_SHARE of the sample's power; no tone locks for CHANGE_HOLD_S after. */
#define CHANGE_FAST_PER_S LADRC_R(20.0)
#define CHANGE_SLOW_PER_S LADRC_R(1.0)
#define CHANGE_RATIO LADRC_R(10.0)
#define CHANGE_SHARE LADRC_R(0.01)
#define CHANGE_HOLD_S LADRC_R(0.1)
enum { CHANGE_HOLD = 1, CHANGE_NEW = 2 };

/* The rarely taken paths below (LADRC_NOINLINE) are kept out of line so
 * that their locals are not on the stack of the path through the RLS
 * update, the deepest of a tick. */

static ladrc_status_t check_config(const ladrc_hp_config_t *cfg)
{
    if (!ladrc_dt_is_valid(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (cfg->freq_mode != LADRC_HP_FREQ_KNOWN && cfg->freq_mode != LADRC_HP_FREQ_ONLINE) {
        return LADRC_ERR_HP_FREQ_MODE;
    }
#if !LADRC_WITH_HP_ONLINE
    if (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) {
        return LADRC_ERR_FEATURE_NOT_BUILT;
    }
#endif
    if (cfg->n_tones < 1u || cfg->n_tones > LADRC_HP_MAX_TONES) {
        return LADRC_ERR_HP_N_TONES;
    }
    /* The fastest tone the estimator may model: KNOWN the fastest given,
     * ONLINE the top of the search range. */
    ladrc_real_t fastest_rad_s = LADRC_R(0.0);
    for (unsigned k = 0u; k < cfg->n_tones; ++k) {
        const ladrc_real_t w = cfg->freq_rad_s[k];
        /* The phasor must turn by less than half a turn per tick. */
        if (!ladrc_is_positive(w) || w * cfg->dt_s >= HP_PI) {
            return LADRC_ERR_HP_FREQ_RAD_S;
        }
        if (w > fastest_rad_s) {
            fastest_rad_s = w;
        }
    }
#if LADRC_WITH_HP_ONLINE
    if (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) {
        if (!(ladrc_is_positive(cfg->freq_min_rad_s) && ladrc_is_finite(cfg->freq_max_rad_s) &&
              cfg->freq_min_rad_s < cfg->freq_max_rad_s && cfg->freq_max_rad_s * cfg->dt_s < HP_PI)) {
            return LADRC_ERR_HP_FREQ_RANGE;
        }
        fastest_rad_s = cfg->freq_max_rad_s;
    }
#endif
    const ladrc_real_t fit_period_s = (ladrc_real_t)cfg->fit_decimation * cfg->dt_s;
    if (!ladrc_is_positive(cfg->lambda0_per_s) || cfg->lambda0_per_s * fit_period_s > LADRC_R(1.0)) {
        return LADRC_ERR_EST_LAMBDA0;
    }
    /* A fit sample must see every tone turn by less than a quarter turn. */
    if (cfg->fit_decimation < 1u || cfg->fit_phase >= cfg->fit_decimation ||
        !(fastest_rad_s * fit_period_s < LADRC_R(0.5) * HP_PI)) {
        return LADRC_ERR_HP_FIT_DECIMATION;
    }
    if (!(ladrc_is_finite(cfg->act_tau_s) && cfg->act_tau_s >= LADRC_R(0.0) &&
          cfg->act_tau_s <= LADRC_MOTOR_TAU_MAX_S)) {
        return LADRC_ERR_MOTOR_TAU_S;
    }
    if (cfg->act_delay_ticks > LADRC_MAX_DELAY_TICKS) {
        return LADRC_ERR_DELAY_TICKS;
    }
    const ladrc_real_t lag_wo = cfg->sample_lag_wo_rad_s;
    if (!ladrc_is_finite(lag_wo) || lag_wo < LADRC_R(0.0) ||
        (lag_wo > LADRC_R(0.0) && !(fastest_rad_s <= HP_LEAD_RATIO_MAX * lag_wo))) {
        return LADRC_ERR_HP_SAMPLE_LAG;
    }
    const ladrc_real_t age_s = cfg->sample_age_s;
    if (!ladrc_is_finite(age_s) || age_s < LADRC_R(0.0) || !(fastest_rad_s * age_s <= LADRC_R(0.5) * HP_PI) ||
        cfg->sample_block_mean > 1u) {
        return LADRC_ERR_HP_SAMPLE_LAG;
    }
#if LADRC_WITH_HP_ONLINE
    if (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) {
        if (!(ladrc_is_positive(cfg->freq_lambda0_per_s) && cfg->freq_lambda0_per_s * fit_period_s <= LADRC_R(1.0))) {
            return LADRC_ERR_HP_FREQ_LAMBDA0;
        }
        /* The derivative filter is integrated once per fit sample. */
        if (!(ladrc_is_positive(cfg->freq_filter_rad_s) && cfg->freq_filter_rad_s * fit_period_s < LADRC_R(0.2))) {
            return LADRC_ERR_HP_FREQ_FILTER;
        }
    }
#endif
    return LADRC_OK;
}

ladrc_status_t ladrc_hp_init(ladrc_hp_estimator_t *est, const ladrc_hp_config_t *cfg)
{
    if (est == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    ladrc_status_t status = check_config(cfg);
    if (status != LADRC_OK) {
        return status;
    }
    const ladrc_real_t fit_period_s = (ladrc_real_t)cfg->fit_decimation * cfg->dt_s;
    /* The largest fit, checked once: every later start_fit is smaller or equal. */
    const ladrc_rls_config_t fit = {.n_params = (uint8_t)(1u + 2u * cfg->n_tones),
                                    .dt_s = fit_period_s,
                                    .lambda0_per_s = cfg->lambda0_per_s,
                                    .p_bound = HP_P_BOUND_PER_SAMPLE / fit_period_s,
                                    .p_initial = HP_P_INITIAL_PER_SAMPLE / fit_period_s};
    status = ladrc_rls_init(&est->fit, &fit);
    if (status != LADRC_OK) {
        return status;
    }
    const ladrc_hp_tone_basis_t basis = {.dt_s = cfg->dt_s,
                                         .lag_wo_rad_s = cfg->sample_lag_wo_rad_s,
                                         .age_s = cfg->sample_age_s,
                                         .act_tau_s = cfg->act_tau_s,
                                         .block_ticks = cfg->sample_block_mean ? cfg->fit_decimation : 1u,
                                         .act_delay_ticks = cfg->act_delay_ticks};
    est->fit_period_s = fit_period_s;
    est->block_mean = cfg->sample_block_mean;
    est->advance = (cfg->act_tau_s > LADRC_R(0.0) || cfg->act_delay_ticks > 0u) ? 1u : 0u;
#if LADRC_WITH_HP_ONLINE
    est->basis = basis;
    est->online = (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) ? 1u : 0u;
    est->freq_min_rad_s = cfg->freq_min_rad_s;
    est->freq_max_rad_s = cfg->freq_max_rad_s;
    est->freq_lambda0_per_s = cfg->freq_lambda0_per_s;
    est->filter_rad_s = cfg->freq_filter_rad_s;
#endif
    est->lambda0_max = cfg->lambda0_per_s;
    est->fit_decimation = cfg->fit_decimation;
    est->fit_phase = cfg->fit_phase;
    est->n_tones = cfg->n_tones;
    for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
        hp_set_tone_freq(&basis, est->advance, &est->tone[k], (k < cfg->n_tones) ? cfg->freq_rad_s[k] : LADRC_R(0.0));
    }
    ladrc_hp_reset(est);
    return LADRC_OK;
}

void ladrc_hp_reset(ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE_VOID(est != NULL);
    est->fit_rate_per_s = est->lambda0_max;
    (void)ladrc_rls_set_lambda0(&est->fit, est->fit_rate_per_s);
    hp_start_fit(est, hp_online(est) ? 1u : est->n_tones, NULL);
    for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        tone->cos_psi = LADRC_R(1.0);
        tone->sin_psi = LADRC_R(0.0);
        hp_forget_tone(tone);
    }
    est->sample_mean = LADRC_R(0.0);
    est->sig_power = LADRC_R(0.0);
#if LADRC_WITH_HP_ONLINE
    hp_freq_reset(est);
#endif
    est->err_fast = LADRC_R(0.0);
    est->err_slow = LADRC_R(0.0);
    est->weight = LADRC_R(0.0);
    est->engaged = 0u;
    est->estimate = LADRC_R(0.0);
    est->command = LADRC_R(0.0);
    est->handover = LADRC_R(0.0);
    est->fit_count = 0u;
    est->block_sum = LADRC_R(0.0);
    est->block_n = 0u;
    est->change_left = 0u;
    est->faults = LADRC_FAULT_NONE;
}

/* The fitted phasor (a - j b) of a tone turned and scaled by (re + j im),
 * real part at the tone's current phase psi. Inlined into both readers: a
 * call per tone and tick would cost more than the product. */
static LADRC_FORCE_INLINE ladrc_real_t tone_turned(const ladrc_hp_tone_t *tone, ladrc_real_t a, ladrc_real_t b,
                                                   ladrc_real_t re, ladrc_real_t im)
{
    const ladrc_real_t x = a * re + b * im;
    const ladrc_real_t y = a * im - b * re;
    return x * tone->cos_psi - y * tone->sin_psi;
}

/* Turn of a tone's fitted phasor since the previous fit sample, as a rate
 * (rad/s), averaged into its slip (what the ONLINE search follows), and the
 * relative change of its size, as a rate (1/s), averaged into its drift;
 * returns |slip| + DRIFT_WEIGHT |drift|, how far the phasor is from
 * standing still (a tone that decays or grows, e.g. the tail of a
 * transient, does not stand still either). Reads the previous phasor
 * (update_evidence moves it on). */
static ladrc_real_t update_slip(const ladrc_hp_estimator_t *est, ladrc_hp_tone_t *tone, ladrc_real_t a, ladrc_real_t b)
{
    /* (a - j b) conj(prev_a - j prev_b) = |prev|^2 P / P_prev: its angle is
     * the turn, its real part over |prev|^2 the change of size plus 1. */
    const ladrc_real_t re = a * tone->prev_a + b * tone->prev_b;
    const ladrc_real_t im = a * tone->prev_b - b * tone->prev_a;
    const ladrc_real_t prev2 = tone->prev_a * tone->prev_a + tone->prev_b * tone->prev_b;
    if (!(prev2 > LADRC_R(0.0))) {
        /* a (re)started fit: nothing to compare yet */
        return ladrc_fabs(tone->slip_rad_s) + DRIFT_WEIGHT * ladrc_fabs(tone->drift_per_s);
    }
    /* tan of the turn for turns under an eighth; a larger turn (or a
     * vanished phasor) counts as a quarter turn. */
    ladrc_real_t turn = LADRC_R(0.5) * HP_PI;
    if (re > LADRC_R(0.0) && ladrc_fabs(im) < re) {
        turn = im / re;
    } else if (im < LADRC_R(0.0)) {
        turn = -turn;
    }
    const ladrc_real_t grow = ladrc_clamp(re / prev2 - LADRC_R(1.0), LADRC_R(-1.0), LADRC_R(1.0));
    const ladrc_real_t alpha = SLIP_AVERAGE_PER_S * est->fit_period_s;
    tone->slip_rad_s += alpha * (turn / est->fit_period_s - tone->slip_rad_s);
    tone->drift_per_s += alpha * (grow / est->fit_period_s - tone->drift_per_s);
    return ladrc_fabs(tone->slip_rad_s) + DRIFT_WEIGHT * ladrc_fabs(tone->drift_per_s);
}

/* The slip a tone of power a^2 / 2 may show and still lock (rad/s): the
 * fit's share and the noise's, whose per-sample turn has a variance of
 * lambda T s2 / |P|^2 (the increments' power across the phasor), averaged
 * at SLIP_AVERAGE_PER_S. */
static ladrc_real_t slip_allowed(const ladrc_hp_estimator_t *est, const ladrc_hp_tone_t *tone, ladrc_real_t power)
{
    const ladrc_real_t lambda = est->fit_rate_per_s;
    const ladrc_real_t noise2 =
        lambda * SLIP_AVERAGE_PER_S * tone->noise_power / (LADRC_R(4.0) * power + LADRC_R(1e-30));
    return SLIP_TOL_FRACTION * lambda + SLIP_NOISE_SIGMAS * ladrc_sqrt(noise2);
}

/* The gate's band evidence for a tone (estimator.h "Gate"), from its fitted
 * phasor P = (a, b) at this fit sample; updates the means and returns 1
 * once they span a whole window. Under noise alone P wanders as a
 * first-order process of the fit's rate lambda and variance s2, whose
 * increments are uncorrelated with mean power 2 lambda T s2 (their changes:
 * 4 lambda T s2); its mean over a window of rate
 * beta then has power s2 beta / (beta + lambda). */
static int update_evidence(const ladrc_hp_estimator_t *est, ladrc_hp_tone_t *tone, ladrc_real_t a, ladrc_real_t b)
{
    const ladrc_real_t t = est->fit_period_s;
    const ladrc_real_t lambda = est->fit_rate_per_s;
    const ladrc_real_t da = a - tone->prev_a;
    const ladrc_real_t db = b - tone->prev_b;
    /* the change of the increment: noise's increments are uncorrelated, a
     * smooth motion (the fit converging, a slow turn) nearly cancels */
    const ladrc_real_t dda = da - tone->prev_da;
    const ladrc_real_t ddb = db - tone->prev_db;
    const int fresh = (tone->prev_a == LADRC_R(0.0) && tone->prev_b == LADRC_R(0.0));
    const int second = (tone->prev_da != LADRC_R(0.0) || tone->prev_db != LADRC_R(0.0));
    tone->prev_a = a;
    tone->prev_b = b;
    tone->prev_da = fresh ? LADRC_R(0.0) : da;
    tone->prev_db = fresh ? LADRC_R(0.0) : db;
    if (fresh || !second) {
        return 0; /* a (re)started fit: no change of increment yet */
    }
    if (tone->gate_samples < UINT16_MAX) {
        tone->gate_samples++;
    }
    const ladrc_real_t n = (ladrc_real_t)tone->gate_samples;
    const ladrc_real_t window_s = max_real(GATE_WINDOW_RAD / tone->w_rad_s, GATE_WINDOW_MEMORIES / lambda);
    /* plain means until the window is full, then forgetting at its rate */
    const ladrc_real_t alpha = max_real(LADRC_R(1.0) / n, t / window_s);
    const ladrc_real_t alpha_noise = max_real(LADRC_R(1.0) / n, lambda * t / NOISE_MEMORIES);
    tone->mean_a += alpha * (a - tone->mean_a);
    tone->mean_b += alpha * (b - tone->mean_b);
    tone->mean_power += alpha * (a * a + b * b - tone->mean_power);
    tone->noise_power += alpha_noise * ((dda * dda + ddb * ddb) / (LADRC_R(4.0) * lambda * t) - tone->noise_power);
    const ladrc_real_t beta = alpha / t;
    const ladrc_real_t mean2 = tone->mean_a * tone->mean_a + tone->mean_b * tone->mean_b;
    const ladrc_real_t mean_noise = tone->noise_power * beta / (beta + lambda);
    tone->evidence = mean2 / (GATE_EVIDENCE_ON * mean_noise + LADRC_R(1e-30));
    tone->coherence = mean2 / max_real(tone->mean_power - tone->noise_power, mean2 + LADRC_R(1e-30));
    return n * t >= window_s;
}

/* Change detection on the fit's prior error (see estimator.h). A change
 * restarts the fit on fresh data at once (its old values would hold it back
 * for a memory, and a slow tone's would swing with the new data), discards
 * the compensation (weight 0, not handed over: the model no longer describes
 * the disturbance) and unlocks every tone; the frequency fit restarts once
 * the change has passed its filter. Returns CHANGE_NEW on the fit sample of
 * a change, CHANGE_HOLD for CHANGE_HOLD_S after it (no tone may lock), 0
 * otherwise. */
static int detect_change(ladrc_hp_estimator_t *est, ladrc_real_t err)
{
    const ladrc_real_t t = est->fit_period_s;
    const ladrc_real_t e2 = err * err;
    est->err_fast += CHANGE_FAST_PER_S * t * (e2 - est->err_fast);
    est->err_slow += CHANGE_SLOW_PER_S * t * (e2 - est->err_slow);
    if (est->change_left > 0u) {
        est->change_left--;
        return CHANGE_HOLD;
    }
    if (!(est->err_fast > CHANGE_RATIO * est->err_slow && est->err_fast > CHANGE_SHARE * est->sig_power)) {
        return 0;
    }
    est->change_left = hp_count(CHANGE_HOLD_S / t);
#if LADRC_WITH_HP_ONLINE
    hp_freq_after_change(est);
#endif
    ladrc_rls_reset(&est->fit, NULL);
    est->weight = LADRC_R(0.0);
    for (unsigned k = 0u; k < est->n_active; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        tone->prev_a = LADRC_R(0.0);
        tone->prev_b = LADRC_R(0.0);
        tone->slip_rad_s = LADRC_R(0.0);
        tone->drift_per_s = LADRC_R(0.0);
        hp_forget_evidence(tone);
    }
    return CHANGE_NEW;
}

/* 1 once the fit predicts the sample. A clean sample: its prior error power
 * below SETTLED_SHARE of the sample's. A block mean (the gyro's sample, whose
 * noise the fit cannot predict): the fit removes at least
 * NOISY_EXPLAINED_SHARE of the power its tones claim. */
/* The power a^2 / 2 of tone k's fitted phasor (rad^2/s^4). */
static inline ladrc_real_t fit_tone_power(const ladrc_real_t *theta, unsigned k)
{
    const ladrc_real_t a = theta[theta_a(k)];
    const ladrc_real_t b = theta[theta_a(k) + 1u];
    return LADRC_R(0.5) * (a * a + b * b);
}

static int fit_settled(const ladrc_hp_estimator_t *est, const ladrc_real_t *theta)
{
    if (!est->block_mean) {
        return est->err_fast < SETTLED_SHARE * est->sig_power;
    }
    ladrc_real_t claimed = LADRC_R(0.0);
    for (unsigned k = 0u; k < est->n_active; ++k) {
        claimed += fit_tone_power(theta, k);
    }
    return est->sig_power - est->err_slow >= NOISY_EXPLAINED_SHARE * claimed;
}

/* After the RLS took a fit sample: per tone its slip and lock, the gate and
 * the fit's memory (the ONLINE frequencies follow). */
LADRC_NOINLINE static void after_fit(ladrc_hp_estimator_t *est, ladrc_real_t sample, int changing)
{
    const ladrc_real_t *theta = ladrc_rls_get_theta(&est->fit);
    const ladrc_real_t t = est->fit_period_s;
    /* The sample's power around its own mean: a measure of scale that does
     * not depend on the fit. */
    est->sample_mean += MEAN_AVERAGE_PER_S * t * (sample - est->sample_mean);
    const ladrc_real_t centred = sample - est->sample_mean;
    est->sig_power += POWER_AVERAGE_PER_S * t * (centred * centred - est->sig_power);
    const ladrc_real_t power_floor = LADRC_R(0.5) * AMP_FLOOR_RAD_S2 * AMP_FLOOR_RAD_S2;
    const int settled = !changing && fit_settled(est, theta);
    ladrc_real_t rate = est->lambda0_max;
    int any_locked = 0;
    int all_locked = 1;
    for (unsigned k = 0u; k < est->n_active; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        const ladrc_real_t a = theta[theta_a(k)];
        const ladrc_real_t b = theta[theta_a(k) + 1u];
        const ladrc_real_t motion = update_slip(est, tone, a, b);
        const int window_full = update_evidence(est, tone, a, b);
        const ladrc_real_t power = fit_tone_power(theta, k);
        const uint8_t was_significant = tone->significant;
        tone->significant = (power >= AMP_SHARE * est->sig_power && power >= power_floor) ? 1u : 0u;
        if (tone->significant && !was_significant) {
            /* a tone that just rose out of the sample: its window starts now */
            hp_restart_window(tone);
        }
        if (!tone->significant) {
            tone->locked = 0u;
            continue;
        }
        /* A tone locks once the fit predicts the sample (its phasor also
         * moves while the fit converges) and its phasor stands still. A
         * clean sample (the observer's): while an ONLINE search sees a
         * clean model of the active tones. A noisy one (the gyro's): while
         * no clean model contradicts the tones and the band evidence and
         * coherence pass over a whole window. It stays locked while the
         * phasor does not turn and, noisy, the evidence and coherence pass
         * their lower bars. */
        int stays, locks;
        if (!est->block_mean) {
            const ladrc_real_t tol = SLIP_TOL_FRACTION * est->fit_rate_per_s;
            stays = tone->locked && ladrc_fabs(tone->slip_rad_s) < SLIP_UNLOCK_FACTOR * tol;
            locks = settled && hp_search_agrees(est) && motion < tol;
        } else {
            const ladrc_real_t slip_bar = slip_allowed(est, tone, power);
            const int agrees = !hp_search_contradicts(est);
            stays = tone->locked && agrees && ladrc_fabs(tone->slip_rad_s) < SLIP_UNLOCK_FACTOR * slip_bar &&
                    tone->evidence * GATE_EVIDENCE_ON >= GATE_EVIDENCE_OFF && tone->coherence >= GATE_COHERENCE_OFF;
            locks = settled && agrees && motion < slip_bar && window_full && tone->evidence >= LADRC_R(1.0) &&
                    tone->coherence >= GATE_COHERENCE_ON;
        }
        tone->locked = (stays || locks) ? 1u : 0u;
        any_locked |= tone->locked;
        all_locked &= tone->locked;
        rate = min_real(rate, tone->w_rad_s / FIT_MEMORY_RAD);
        for (unsigned j = 0u; j < k; ++j) {
            if (est->tone[j].significant) {
                rate = min_real(rate, ladrc_fabs(tone->w_rad_s - est->tone[j].w_rad_s) / SEPARATION_MEMORY_RAD);
            }
        }
    }
    const ladrc_real_t max_move = GATE_RATE_PER_S * t;
    const ladrc_real_t target = (any_locked && all_locked && !changing) ? LADRC_R(1.0) : LADRC_R(0.0);
    est->weight += ladrc_clamp(target - est->weight, -max_move, max_move);
    /* Engaged for a while (the fit has converged), the fit keeps a longer
     * memory: less noise in the compensation; a change restarts it anyway. */
    est->engaged =
        (est->weight >= LADRC_R(1.0)) ? (uint16_t)(est->engaged < UINT16_MAX ? est->engaged + 1u : est->engaged) : 0u;
    if ((ladrc_real_t)est->engaged * t >= ENGAGED_SETTLE_S) {
        rate *= ENGAGED_RATE_FRACTION;
    }
    if (rate != est->fit_rate_per_s) {
        est->fit_rate_per_s = rate;
        (void)ladrc_rls_set_lambda0(&est->fit, rate);
    }
}

/* Rotates a tone's phasor by w h, renormalising to first order so it stays
 * unit. Inlined into both model passes: a call per tone and tick would
 * cost more than the rotation. */
static LADRC_FORCE_INLINE void advance_phase(ladrc_hp_tone_t *tone)
{
    const ladrc_real_t c = tone->cos_psi * tone->cos_step - tone->sin_psi * tone->sin_step;
    const ladrc_real_t s = tone->sin_psi * tone->cos_step + tone->cos_psi * tone->sin_step;
    const ladrc_real_t norm = LADRC_R(1.5) - LADRC_R(0.5) * (c * c + s * s);
    tone->cos_psi = c * norm;
    tone->sin_psi = s * norm;
}

/* The model at this tick's phases (returned), each tone's phase moved on by
 * w h, and the command: the tones turned by cmd at the moved phase, which
 * cmd takes back (estimator.h), times the weight: one pass over the tones
 * for an estimator with an actuator to advance over; the plain one's tick
 * keeps its own loop (ladrc_hp_step). */
static LADRC_FORCE_INLINE ladrc_real_t model_and_command(ladrc_hp_estimator_t *est, const ladrc_real_t *theta)
{
    ladrc_real_t model = theta[0];
    ladrc_real_t command = theta[0];
    for (unsigned k = 0u; k < est->n_active; ++k) {
        ladrc_hp_tone_t *tone = &est->tone[k];
        const ladrc_real_t a = theta[theta_a(k)];
        const ladrc_real_t b = theta[theta_a(k) + 1u];
        model += tone_turned(tone, a, b, tone->lead_re, tone->lead_im);
        advance_phase(tone);
        command += tone_turned(tone, a, b, tone->cmd_re, tone->cmd_im);
    }
    est->command = est->weight * command;
    return model;
}

ladrc_fault_t ladrc_hp_step(ladrc_hp_estimator_t *est, ladrc_real_t sample_rad_s2)
{
    LADRC_REQUIRE(est != NULL, LADRC_FAULT_STATE);
    est->faults = LADRC_FAULT_NONE;
    ladrc_real_t weight_before = est->weight;
    int usable = ladrc_within(sample_rad_s2, HP_SAMPLE_LIMIT_RAD_S2);
    const int fit_tick = est->fit_count == est->fit_phase;
    if (!usable) {
        est->faults = LADRC_FAULT_INPUT;
    }
    if (est->block_mean) {
        /* the fit takes the block's mean: what a gap left of it */
        if (usable) {
            est->block_sum += sample_rad_s2;
            est->block_n++;
        }
        if (fit_tick) {
            usable = est->block_n > 0u;
            sample_rad_s2 = usable ? est->block_sum / (ladrc_real_t)est->block_n : LADRC_R(0.0);
            est->block_sum = LADRC_R(0.0);
            est->block_n = 0u;
        }
    }
    if (usable && fit_tick) {
        /* One fit sample: the change detection on the prior error, the RLS
         * (called from here: the deepest path of a tick), the gate, the
         * ONLINE frequencies. */
        ladrc_real_t *phi = est->phi; /* in the state: off the deepest stack of a tick */
        phi[0] = LADRC_R(1.0);
        for (unsigned k = 0u; k < est->n_active; ++k) {
            phi[theta_a(k)] = est->tone[k].cos_psi;
            phi[theta_a(k) + 1u] = est->tone[k].sin_psi;
        }
        const int changing = detect_change(est, sample_rad_s2 - ladrc_rls_predict(&est->fit, phi));
        if (changing == CHANGE_NEW) {
            weight_before = LADRC_R(0.0); /* discarded, not handed over */
        }
        est->faults = ladrc_rls_update(&est->fit, phi, sample_rad_s2);
        after_fit(est, sample_rad_s2, changing);
#if LADRC_WITH_HP_ONLINE
        const unsigned restart = est->online ? hp_update_frequencies(est, sample_rad_s2) : 0u;
        if (restart > 0u) {
            hp_restart_tones(est, restart);
        }
#endif
    }
    /* The fit's clock runs on every tick, fitted or not, so it stays in step. */
    if (++est->fit_count >= est->fit_decimation) {
        est->fit_count = 0u;
    }
    /* The model at this tick's phases with the sample's lag undone per tone
     * (lead: (1 + j w / wo)^3), and with an actuator to advance over the
     * command in the same pass; theta read from the fit the estimator owns
     * (the getter is a call). */
    const ladrc_real_t *theta = est->fit.theta;
    ladrc_real_t model;
    if (est->advance) {
        model = model_and_command(est, theta);
    } else {
        model = theta[0];
        for (unsigned k = 0u; k < est->n_active; ++k) {
            ladrc_hp_tone_t *tone = &est->tone[k];
            model += tone_turned(tone, theta[theta_a(k)], theta[theta_a(k) + 1u], tone->lead_re, tone->lead_im);
            advance_phase(tone);
        }
    }
    est->estimate = est->weight * model;
    est->handover = (est->weight - weight_before) * model;
    if (!ladrc_all_finite2(est->estimate, est->handover)) {
        /* Nothing inside the sample's range gets here; should it, the fit
         * starts over rather than hold a state it cannot leave. */
        ladrc_hp_reset(est);
        est->faults = LADRC_FAULT_STATE;
    }
    return est->faults;
}

ladrc_real_t ladrc_hp_get_estimate(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return hp_estimate(est);
}

ladrc_real_t ladrc_hp_get_command(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return hp_command(est);
}

ladrc_real_t ladrc_hp_get_handover(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return hp_handover(est);
}

unsigned ladrc_hp_get_active_tones(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, 0u);
    return est->n_active;
}

ladrc_real_t ladrc_hp_get_freq(const ladrc_hp_estimator_t *est, unsigned k)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return (k < est->n_active) ? est->tone[k].w_rad_s : LADRC_R(0.0);
}

ladrc_real_t ladrc_hp_get_amplitude(const ladrc_hp_estimator_t *est, unsigned k)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    if (k >= est->n_active) {
        return LADRC_R(0.0);
    }
    const ladrc_real_t *theta = ladrc_rls_get_theta(&est->fit);
    const ladrc_real_t a = theta[theta_a(k)];
    const ladrc_real_t b = theta[theta_a(k) + 1u];
    return ladrc_sqrt(a * a + b * b);
}

int ladrc_hp_tone_locked(const ladrc_hp_estimator_t *est, unsigned k)
{
    LADRC_REQUIRE(est != NULL, 0);
    return (k < est->n_active) ? (int)est->tone[k].locked : 0;
}

ladrc_real_t ladrc_hp_get_evidence(const ladrc_hp_estimator_t *est, unsigned k)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return (k < est->n_active) ? est->tone[k].evidence : LADRC_R(0.0);
}

ladrc_real_t ladrc_hp_get_coherence(const ladrc_hp_estimator_t *est, unsigned k)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return (k < est->n_active) ? est->tone[k].coherence : LADRC_R(0.0);
}

ladrc_real_t ladrc_hp_get_weight(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return est->weight;
}

ladrc_real_t ladrc_hp_get_bias(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, LADRC_R(0.0));
    return ladrc_rls_get_theta(&est->fit)[0];
}

const ladrc_rls_t *ladrc_hp_get_fit(const ladrc_hp_estimator_t *est)
{
    LADRC_REQUIRE(est != NULL, NULL);
    return &est->fit;
}
