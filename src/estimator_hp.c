/* SPDX-License-Identifier: BSD-3-Clause */
/* HP disturbance estimator: bias + sinusoid fitted by RLS at a known or
 * online-estimated frequency, behind a confidence gate (see estimator.h). */
#include "ladrc/estimator.h"

#define HP_PI LADRC_R(3.14159265358979)
/* Initial P of the RLS per sample (P h, rls.h keeps P in continuous units):
 * large against the gains it settles to, small enough that the first updates
 * do not amplify float rounding. */
#define HP_P_INITIAL_PER_SAMPLE LADRC_R(1.0e3)
#define HP_P_BOUND_PER_SAMPLE LADRC_R(1.0e4)
/* Confidence gate: the weight aims at 0 below GATE_Q_OFF of explained power,
 * at 1 above GATE_Q_ON, and moves at most GATE_RATE_PER_S per second so a
 * wrong model cannot kick the loop. A second tone with 2% of the power of the
 * modelled one is enough to hold the compensation back partly. */
#define GATE_Q_OFF LADRC_R(0.97)
#define GATE_Q_ON LADRC_R(0.995)
#define GATE_RATE_PER_S LADRC_R(1.0)
/* Below this sample power (rad/s^2)^2 there is nothing worth compensating. */
#define GATE_MIN_POWER LADRC_R(1.0e-6)

/* Which memory the RLS were last given (set_memory). */
#define HP_MEMORY_SHORT 0u
#define HP_MEMORY_PERIOD 1u
#define HP_MEMORY_STALE 2u /* the frequency moved: set them again */

static ladrc_status_t init_rls(ladrc_rls_t *rls, uint8_t n, ladrc_real_t h, ladrc_real_t lambda0)
{
    const ladrc_rls_config_t cfg = {n, h, lambda0, HP_P_BOUND_PER_SAMPLE / h,
                                    HP_P_INITIAL_PER_SAMPLE / h};
    return ladrc_rls_init(rls, &cfg);
}

/* Forgetting rate that keeps one period of a tone at w, at most cap. */
static ladrc_real_t one_period_rate(ladrc_real_t w_rad_s, ladrc_real_t cap)
{
    const ladrc_real_t rate = w_rad_s / (LADRC_R(2.0) * HP_PI);
    return rate < cap ? rate : cap;
}

/* The frequency and what follows from it; the RLS memories follow at the
 * next set_memory. */
static void set_freq(ladrc_hp_estimator_t *est, ladrc_real_t w_rad_s)
{
    est->w_rad_s = w_rad_s;
    est->period_rate_per_s = one_period_rate(w_rad_s, est->lambda0_max);
    est->freq_period_rate_per_s = one_period_rate(w_rad_s, est->freq_lambda0_max);
    est->memory = HP_MEMORY_STALE;
    est->cos_step = ladrc_cos(w_rad_s * est->dt_s);
    est->sin_step = ladrc_sin(w_rad_s * est->dt_s);
    const ladrc_real_t x = (est->lag_wo_rad_s > LADRC_R(0.0)) ? w_rad_s / est->lag_wo_rad_s : LADRC_R(0.0);
    est->lead_re = LADRC_R(1.0) - LADRC_R(3.0) * x * x;
    est->lead_im = LADRC_R(3.0) * x - x * x * x;
}

/* Memory of the fits and the gate. A fit that explains the signal keeps about
 * one period of data, which it needs to tell the bias, the sinusoid and a
 * neighbouring tone apart; a fit that does not (start, frequency jump) forgets
 * at the configured maximum rate so it can find the new signal quickly. */
static void set_memory(ladrc_hp_estimator_t *est, ladrc_real_t explained)
{
    const uint8_t memory = (explained >= GATE_Q_OFF) ? HP_MEMORY_PERIOD : HP_MEMORY_SHORT;
    if (memory == est->memory) {
        return; /* the RLS already have these rates */
    }
    est->memory = memory;
    const int fits = memory == HP_MEMORY_PERIOD;
    (void)ladrc_rls_set_lambda0(&est->amp, fits ? est->period_rate_per_s : est->lambda0_max);
    (void)ladrc_rls_set_lambda0(&est->freq, fits ? est->freq_period_rate_per_s : est->freq_lambda0_max);
}

ladrc_status_t ladrc_hp_init(ladrc_hp_estimator_t *est, const ladrc_hp_config_t *cfg)
{
    if (est == NULL || cfg == NULL) {
        return LADRC_ERR_NULL;
    }
    if (!ladrc_is_positive(cfg->dt_s)) {
        return LADRC_ERR_DT_S;
    }
    if (cfg->freq_mode != LADRC_HP_FREQ_KNOWN && cfg->freq_mode != LADRC_HP_FREQ_ONLINE) {
        return LADRC_ERR_HP_FREQ_MODE;
    }
    /* The phasor must turn by less than half a turn per tick. */
    if (!ladrc_is_positive(cfg->freq_rad_s) || cfg->freq_rad_s * cfg->dt_s >= HP_PI) {
        return LADRC_ERR_HP_FREQ_RAD_S;
    }
    if (cfg->decimation < 1u) {
        return LADRC_ERR_HP_DECIMATION;
    }
    /* A fit sample must see the tone turn by less than a quarter turn. */
    const ladrc_real_t fit_period_s = (ladrc_real_t)cfg->fit_decimation * cfg->dt_s;
    const ladrc_real_t fastest_rad_s =
        (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) ? cfg->freq_max_rad_s : cfg->freq_rad_s;
    const ladrc_real_t period_s = (ladrc_real_t)cfg->decimation * cfg->dt_s;
    if (cfg->freq_mode == LADRC_HP_FREQ_ONLINE &&
        !(ladrc_is_positive(cfg->freq_min_rad_s) && ladrc_is_finite(cfg->freq_max_rad_s) &&
          cfg->freq_min_rad_s < cfg->freq_max_rad_s &&
          cfg->freq_max_rad_s * period_s < LADRC_R(0.5) * HP_PI)) {
        return LADRC_ERR_HP_FREQ_RANGE;
    }
    if (!ladrc_is_positive(cfg->lambda0_per_s) || !ladrc_is_positive(cfg->freq_lambda0_per_s)) {
        return LADRC_ERR_EST_LAMBDA0;
    }
    if (cfg->fit_decimation < 1u || cfg->fit_phase >= cfg->fit_decimation ||
        !(fastest_rad_s * fit_period_s < LADRC_R(0.5) * HP_PI)) {
        return LADRC_ERR_HP_FIT_DECIMATION;
    }
    if (!ladrc_is_finite(cfg->sample_lag_wo_rad_s) || cfg->sample_lag_wo_rad_s < LADRC_R(0.0)) {
        return LADRC_ERR_HP_SAMPLE_LAG;
    }
    est->lambda0_max = cfg->lambda0_per_s;
    est->freq_lambda0_max = cfg->freq_lambda0_per_s;
    ladrc_status_t status = init_rls(&est->amp, 3u, fit_period_s, cfg->lambda0_per_s);
    if (status == LADRC_OK) {
        status = init_rls(&est->freq, 2u, period_s, cfg->freq_lambda0_per_s);
    }
    if (status != LADRC_OK) {
        return status;
    }
    est->dt_s = cfg->dt_s;
    est->lag_wo_rad_s = cfg->sample_lag_wo_rad_s;
    est->freq_min_rad_s = cfg->freq_min_rad_s;
    est->freq_max_rad_s = cfg->freq_max_rad_s;
    est->decimation = cfg->decimation;
    est->fit_decimation = cfg->fit_decimation;
    est->fit_phase = cfg->fit_phase;
    est->online = (cfg->freq_mode == LADRC_HP_FREQ_ONLINE) ? 1u : 0u;
    ladrc_hp_reset(est, cfg->freq_rad_s);
    return LADRC_OK;
}

void ladrc_hp_reset(ladrc_hp_estimator_t *est, ladrc_real_t freq_rad_s)
{
    LADRC_ASSERT(est != NULL);
    ladrc_rls_reset(&est->amp, NULL);
    ladrc_rls_reset(&est->freq, NULL);
    set_freq(est, freq_rad_s);
    set_memory(est, LADRC_R(0.0));
    est->cos_psi = LADRC_R(1.0);
    est->sin_psi = LADRC_R(0.0);
    est->dec_sum = LADRC_R(0.0);
    est->dec_count = 0u;
    est->dec_delay = est->fit_phase;
    est->fit_count = 0u;
    est->x1 = LADRC_R(0.0);
    est->x2 = LADRC_R(0.0);
    est->n_dec_samples = 0u;
    est->sig_power = LADRC_R(0.0);
    est->err_power = LADRC_R(0.0);
    est->weight = LADRC_R(0.0);
    est->estimate = LADRC_R(0.0);
    est->faults = LADRC_FAULT_NONE;
}

/* A frequency estimate that moves by more than this fraction restarts the fit. */
#define HP_REFIT_FREQ_STEP LADRC_R(0.03)

/* Frequency from one decimated sample x: second-difference regression. */
static void update_freq(ladrc_hp_estimator_t *est, ladrc_real_t x)
{
    if (est->n_dec_samples >= 2u) {
        const ladrc_real_t phi[2] = {-est->x1, LADRC_R(1.0)};
        const ladrc_real_t d2x = x - LADRC_R(2.0) * est->x1 + est->x2;
        (void)ladrc_rls_update(&est->freq, phi, d2x);
        const ladrc_real_t kappa = ladrc_rls_get_theta(&est->freq)[0];
        if (kappa > LADRC_R(0.0) && kappa < LADRC_R(2.0)) {
            const ladrc_real_t period_s = (ladrc_real_t)est->decimation * est->dt_s;
            const ladrc_real_t w = LADRC_R(2.0) * ladrc_asin(LADRC_R(0.5) * ladrc_sqrt(kappa)) / period_s;
            const ladrc_real_t w_new = ladrc_clamp(w, est->freq_min_rad_s, est->freq_max_rad_s);
            if (est->weight <= LADRC_R(0.0) &&
                ladrc_fabs(w_new - est->w_rad_s) > HP_REFIT_FREQ_STEP * est->w_rad_s) {
                /* Data fitted at another frequency would hold the fit back for a
                 * whole window: start the fit afresh from its current values.
                 * Only while nothing is compensated, so a restart cannot kick. */
                ladrc_rls_reset(&est->amp, ladrc_rls_get_theta(&est->amp));
            }
            set_freq(est, w_new);
        }
    } else {
        est->n_dec_samples++;
    }
    est->x2 = est->x1;
    est->x1 = x;
}

/* Moves the weight towards what the explained power says, at a bounded rate;
 * returns the explained fraction. Powers are averaged over a period of the
 * modelled tone, so a short-memory fit that follows a mixture of tones
 * locally does not look like a good model. */
static ladrc_real_t update_gate(ladrc_hp_estimator_t *est, ladrc_real_t centred, ladrc_real_t err)
{
    const ladrc_real_t fit_period_s = (ladrc_real_t)est->fit_decimation * est->dt_s;
    const ladrc_real_t alpha = est->period_rate_per_s * fit_period_s;
    est->sig_power += alpha * (centred * centred - est->sig_power);
    est->err_power += alpha * (err * err - est->err_power);
    const ladrc_real_t explained = (est->sig_power > GATE_MIN_POWER)
                                       ? LADRC_R(1.0) - est->err_power / est->sig_power
                                       : LADRC_R(0.0);
    const ladrc_real_t target = ladrc_clamp((explained - GATE_Q_OFF) / (GATE_Q_ON - GATE_Q_OFF),
                                            LADRC_R(0.0), LADRC_R(1.0));
    const ladrc_real_t max_move = GATE_RATE_PER_S * fit_period_s;
    est->weight += ladrc_clamp(target - est->weight, -max_move, max_move);
    return explained;
}

/* Rotates the phasor by w h, renormalising to first order so it stays unit. */
static void advance_phase(ladrc_hp_estimator_t *est)
{
    const ladrc_real_t c = est->cos_psi * est->cos_step - est->sin_psi * est->sin_step;
    const ladrc_real_t s = est->sin_psi * est->cos_step + est->cos_psi * est->sin_step;
    const ladrc_real_t norm = LADRC_R(1.5) - LADRC_R(0.5) * (c * c + s * s);
    est->cos_psi = c * norm;
    est->sin_psi = s * norm;
}

/* The model at the current phase with the sample's lag undone: the phasor
 * (a - j b) turned and scaled by (1 + j w / wo)^3; the bias has no lag. */
static ladrc_real_t model_ahead_of_lag(const ladrc_hp_estimator_t *est)
{
    const ladrc_real_t *theta = ladrc_rls_get_theta(&est->amp);
    const ladrc_real_t x = theta[1] * est->lead_re + theta[2] * est->lead_im;
    const ladrc_real_t y = theta[1] * est->lead_im - theta[2] * est->lead_re;
    return theta[0] + x * est->cos_psi - y * est->sin_psi;
}

ladrc_fault_t ladrc_hp_step(ladrc_hp_estimator_t *est, ladrc_real_t sample_rad_s2)
{
    LADRC_ASSERT(est != NULL);
    est->faults = LADRC_FAULT_NONE;
    if (!ladrc_is_finite(sample_rad_s2)) {
        est->faults = LADRC_FAULT_INPUT;
    } else {
        if (est->fit_count == est->fit_phase) {
            const ladrc_real_t phi[3] = {LADRC_R(1.0), est->cos_psi, est->sin_psi};
            const ladrc_real_t err = sample_rad_s2 - ladrc_rls_predict(&est->amp, phi);
            est->faults = ladrc_rls_update(&est->amp, phi, sample_rad_s2);
            set_memory(est, update_gate(est, sample_rad_s2 - ladrc_rls_get_theta(&est->amp)[0], err));
        }
        if (est->dec_delay > 0u) {
            /* Frequency blocks start fit_phase ticks late, so estimators on
             * different phases do not update their frequency on one tick. */
            est->dec_delay--;
        } else if (est->online) {
            est->dec_sum += sample_rad_s2;
            if (++est->dec_count >= est->decimation) {
                update_freq(est, est->dec_sum / (ladrc_real_t)est->decimation);
                est->dec_sum = LADRC_R(0.0);
                est->dec_count = 0u;
            }
        }
    }
    /* The fit's clock runs on every tick, fitted or not, so it stays in step. */
    if (++est->fit_count >= est->fit_decimation) {
        est->fit_count = 0u;
    }
    est->estimate = est->weight * model_ahead_of_lag(est);
    advance_phase(est);
    return est->faults;
}

ladrc_real_t ladrc_hp_get_estimate(const ladrc_hp_estimator_t *est) { return est->estimate; }

ladrc_real_t ladrc_hp_get_freq(const ladrc_hp_estimator_t *est) { return est->w_rad_s; }

ladrc_real_t ladrc_hp_get_amplitude(const ladrc_hp_estimator_t *est)
{
    const ladrc_real_t *theta = ladrc_rls_get_theta(&est->amp);
    return ladrc_sqrt(theta[1] * theta[1] + theta[2] * theta[2]);
}

ladrc_real_t ladrc_hp_get_weight(const ladrc_hp_estimator_t *est) { return est->weight; }
