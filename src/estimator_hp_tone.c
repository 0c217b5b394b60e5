/* SPDX-License-Identifier: BSD-3-Clause */
/* A tone's frequency and what follows from it (estimator_hp_internal.h),
 * for the HP estimator's init and its ONLINE frequency search: below both. */
#include "estimator_hp_internal.h"

/* cos and sin of a small angle x by their series to x^8 and x^9: exact to
 * float rounding for the per-tick turns of the defaults (|x| <= 0.04 at
 * 40 rad/s and 1 kHz) and within 3e-5 at the largest init allows (pi/2: a
 * quarter turn per fit sample); the phasor is renormalised every tick. Cheap
 * enough for a frequency update on every fit sample. */
static void small_rotation(ladrc_real_t x, ladrc_real_t *c, ladrc_real_t *s)
{
    const ladrc_real_t x2 = x * x;
    *c = LADRC_R(1.0) -
         x2 / LADRC_R(2.0) *
             (LADRC_R(1.0) -
              x2 / LADRC_R(12.0) * (LADRC_R(1.0) - x2 / LADRC_R(30.0) * (LADRC_R(1.0) - x2 / LADRC_R(56.0))));
    *s = x * (LADRC_R(1.0) -
              x2 / LADRC_R(6.0) *
                  (LADRC_R(1.0) -
                   x2 / LADRC_R(20.0) * (LADRC_R(1.0) - x2 / LADRC_R(42.0) * (LADRC_R(1.0) - x2 / LADRC_R(72.0)))));
}

/* (re, im) turned n times by the unit step (c, s): the step's binary powers,
 * squared up and multiplied in as n's bits are set, so log2 n squarings and
 * at most as many turns, no trig (d up to LADRC_MAX_DELAY_TICKS at every
 * frequency update). The rounding grows as n eps, as n single turns would. */
static void turn_by_steps(ladrc_real_t *re, ladrc_real_t *im, ladrc_real_t c, ladrc_real_t s, unsigned n)
{
    while (n != 0u) {
        if ((n & 1u) != 0u) {
            const ladrc_real_t turned = *re * c - *im * s;
            *im = *im * c + *re * s;
            *re = turned;
        }
        n >>= 1u;
        if (n != 0u) {
            const ladrc_real_t c2 = c * c - s * s;
            s = LADRC_R(2.0) * c * s;
            c = c2;
        }
    }
}

void hp_set_tone_freq(const ladrc_hp_tone_basis_t *basis, unsigned advance, ladrc_hp_tone_t *tone, ladrc_real_t w_rad_s)
{
    tone->w_rad_s = w_rad_s;
    small_rotation(w_rad_s * basis->dt_s, &tone->cos_step, &tone->sin_step);
    const ladrc_real_t x = (basis->lag_wo_rad_s > LADRC_R(0.0)) ? w_rad_s / basis->lag_wo_rad_s : LADRC_R(0.0);
    ladrc_real_t re = LADRC_R(1.0) - LADRC_R(3.0) * x * x;
    ladrc_real_t im = LADRC_R(3.0) * x - x * x * x;
    if (basis->age_s > LADRC_R(0.0) || basis->block_ticks > 1u) {
        /* times e^{j w age} / G(w), G the block mean's gain at w,
         * sin(N w h / 2) / (N sin(w h / 2)): >= 0.9 where init allows it */
        ladrc_real_t c, sn, c_half, s_half, c_block, s_block;
        const ladrc_real_t age_turn = w_rad_s * basis->age_s;
        const ladrc_real_t block_turn = LADRC_R(0.5) * (ladrc_real_t)basis->block_ticks * w_rad_s * basis->dt_s;
        small_rotation(age_turn, &c, &sn);
        small_rotation(LADRC_R(0.5) * w_rad_s * basis->dt_s, &c_half, &s_half);
        if (block_turn == age_turn) {
            /* the gyro sample's age is half its block (axis_hp.c): with a
             * power-of-two block the two turns are the same number */
            s_block = sn;
        } else {
            small_rotation(block_turn, &c_block, &s_block);
        }
        const ladrc_real_t gain =
            (s_half > LADRC_R(0.0)) ? s_block / ((ladrc_real_t)basis->block_ticks * s_half) : LADRC_R(1.0);
        const ladrc_real_t turned = (re * c - im * sn) / gain;
        im = (im * c + re * sn) / gain;
        re = turned;
    }
    tone->lead_re = re;
    tone->lead_im = im;
    if (advance) {
        /* lead (1 + j w tau) e^{j w d h}, times e^{-j w h}: the command is
         * read after the tick has turned the phase by w h (estimator.h).
         * The turn by w (d - 1) h as |d - 1| turns by w h (exact to
         * rounding, no trig). */
        const ladrc_real_t wt = min_real(w_rad_s * basis->act_tau_s, HP_LEAD_RATIO_MAX);
        re = tone->lead_re - wt * tone->lead_im;
        im = tone->lead_im + wt * tone->lead_re;
        const ladrc_real_t back = (basis->act_delay_ticks == 0u) ? LADRC_R(-1.0) : LADRC_R(1.0);
        const unsigned turns = (basis->act_delay_ticks == 0u) ? 1u : basis->act_delay_ticks - 1u;
        turn_by_steps(&re, &im, tone->cos_step, back * tone->sin_step, turns);
        tone->cmd_re = re;
        tone->cmd_im = im;
    }
}
