/* SPDX-License-Identifier: BSD-3-Clause */
/* HP-MLADRC: the LADRC axis with the HP estimator and its shadow observer
 * (axis.h, estimator.h). */
#include "axis_internal.h"
#include "estimator_hp_internal.h"
#include "estimator_lp_internal.h"
#include "require.h"

void ladrc_axis_hp_config(const ladrc_axis_config_t *cfg, ladrc_hp_config_t *hp)
{
    LADRC_REQUIRE_VOID(cfg != NULL && hp != NULL);
    ladrc_hp_config_t c = {.dt_s = cfg->dt_s,
                           .freq_mode = cfg->hp_freq_mode,
                           .n_tones = cfg->hp_n_tones,
                           .freq_min_rad_s = cfg->hp_freq_min_rad_s,
                           .freq_max_rad_s = cfg->hp_freq_max_rad_s,
                           .lambda0_per_s = cfg->hp_lambda0_per_s,
                           .freq_lambda0_per_s = cfg->hp_freq_lambda0_per_s,
                           .freq_filter_rad_s = cfg->hp_freq_filter_rad_s,
                           .fit_decimation = cfg->hp_fit_decimation,
                           .fit_phase = 0u, /* the first tick of each block; axis_hp_stagger moves it */
                           /* the command's tones are advanced over the modelled actuator */
                           .act_tau_s = cfg->motor_tau_s,
                           .act_delay_ticks = cfg->delay_ticks};
    for (unsigned k = 0u; k < LADRC_HP_MAX_TONES; ++k) {
        c.freq_rad_s[k] = cfg->hp_freq_rad_s[k];
    }
    if (cfg->hp_sample == LADRC_HP_SAMPLE_GYRO) {
        /* LP's sample, a rate difference per tick, noisy: the fit takes
         * each block's mean, centred half a block before the fit tick (the
         * difference half a tick, the mean (n - 1) / 2 ticks). */
        c.sample_block_mean = 1u;
        c.sample_age_s = LADRC_R(0.5) * (ladrc_real_t)cfg->hp_fit_decimation * cfg->dt_s;
    } else {
        c.sample_lag_wo_rad_s = cfg->wo_rad_s; /* the sample comes through this axis's LESO */
    }
    *hp = c;
}

ladrc_status_t axis_hp_init(ladrc_axis_t *axis, const ladrc_axis_config_t *cfg)
{
    if (cfg->hp_sample != LADRC_HP_SAMPLE_OBSERVER && cfg->hp_sample != LADRC_HP_SAMPLE_GYRO) {
        return LADRC_ERR_HP_SAMPLE;
    }
    axis->part.hp.gyro = (cfg->hp_sample == LADRC_HP_SAMPLE_GYRO) ? 1u : 0u;
    if (axis->part.hp.gyro) {
        const ladrc_status_t status = axis_lp_configure(&axis->part.hp.source.lp, cfg);
        if (status != LADRC_OK) {
            return status;
        }
    } else {
        /* The shadow runs with the LESO's gains (initialised just before). */
        ladrc_leso_twin_reset(&axis->part.hp.source.shadow, LADRC_R(0.0));
    }
    ladrc_hp_config_t hp;
    ladrc_axis_hp_config(cfg, &hp);
    return ladrc_hp_init(&axis->part.hp.est, &hp);
}

void axis_hp_stagger(ladrc_axis_t *axis, unsigned phase)
{
    hp_set_fit_phase(&axis->part.hp.est, phase);
}

void axis_hp_restart(ladrc_axis_t *axis)
{
    ladrc_hp_reset(&axis->part.hp.est);
    if (axis->part.hp.gyro) {
        ladrc_lp_reset(&axis->part.hp.source.lp);
    } else {
        ladrc_leso_twin_reset(&axis->part.hp.source.shadow, LADRC_R(0.0));
    }
}

ladrc_real_t axis_hp_preset(ladrc_axis_t *axis, ladrc_real_t f_rad_s2)
{
    if (!axis->part.hp.gyro) {
        return LADRC_R(0.0); /* the fit starts idle: the LESO carries f */
    }
    ladrc_lp_hand_over(&axis->part.hp.source.lp, f_rad_s2); /* the LP beside the fit at f at once */
    return lp_estimate(&axis->part.hp.source.lp);
}

ladrc_real_t axis_hp_command(ladrc_axis_t *axis)
{
    const ladrc_real_t tones = hp_command(&axis->part.hp.est);
    if (!axis->part.hp.gyro) {
        return tones;
    }
    return lp_lead_step(&axis->part.hp.source.lp) + tones;
}
