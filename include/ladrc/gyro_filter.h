/* SPDX-License-Identifier: BSD-3-Clause */
/**
 * @file gyro_filter.h
 * @brief Gyro filter stage run before the rate loop: per channel a bank of
 *        fixed notches, a bank of notches that follow the rotors' speeds
 *        (RPM notches) and a low-pass, all channels on shared coefficients.
 *
 * Every section is a second-order biquad with a0 = 1, run in direct form I
 * on each channel (x input, y output, k the tick):
 *
 *     y_k = b0 x_k + b1 x_k-1 + b2 x_k-2 - a1 y_k-1 - a2 y_k-2
 *
 * Low-pass (bilinear transform, prewarped so that the -3 dB point is exactly
 * at fc; K = tan(pi fc dt)): first order H = K (1 + z^-1) / ((1 + K) + (K - 1)
 * z^-1); second order Butterworth H = K^2 (1 + z^-1)^2 / ((1 + sqrt2 K + K^2)
 * + 2 (K^2 - 1) z^-1 + (1 - sqrt2 K + K^2) z^-2). Notch at f0 with quality Q
 * (bilinear, prewarped: the zeros sit exactly at f0; w0 = 2 pi f0 dt,
 * alpha = sin(w0) / (2 Q)):
 *
 *     H = (1 - 2 cos(w0) z^-1 + z^-2) / ((1 + alpha) - 2 cos(w0) z^-1 + (1 - alpha) z^-2)
 *
 * whose -3 dB points are where |cos w - cos w0| = alpha sin w (about
 * f0 +- f0 / (2 Q) for a notch well below Nyquist). The RPM notch of rotor r
 * and harmonic h sits at h * rotor_hz[r]; set_rotor_hz takes one sine and
 * one cosine per rotor (from a Taylor series of the half angle, to the
 * type's precision) and the harmonics by cos(h w) = 2 cos(w) cos((h-1) w)
 * - cos((h-2) w) (the same for sin). A notch's weight blends it with its
 * input, out = x + weight (y - x): 0 below rpm_min_hz, rising linearly to 1
 * at rpm_min_hz + rpm_fade_hz, and 0 at or above
 * LADRC_GYRO_FILTER_CENTRE_MAX_NYQUIST of Nyquist (0.45 / dt_s). A notch at
 * weight 0 is off: its output is its input, and its history records the
 * input as its output, so that it comes back without a step. Method:
 * docs/method.md section 7.
 *
 * Under hostile telemetry (speeds drawn anew every tick, alternating, sweeping
 * the range, at its ends) and any samples, every output stays finite and
 * within the chain's bound: each RPM notch within LADRC_GYRO_FILTER_RPM_GAIN_BOUND
 * times the input envelope, times the gains of the fixed notches and the
 * low-pass. Once the speeds hold still, the output is back within 1e-3 (plus
 * 1e-4 of the input and float's deadband) of a filter that never saw them: on
 * 3 channels with 4 fixed notches (60-270 Hz, Q 5), 4 rotors x 3 harmonics
 * and a 150 Hz low-pass, at most 185, 679 and 1,345 ticks at 1, 4 and 8 kHz
 * (0.17-0.19 s) after samples on a gyro's scale, and 1,383, 5,399 and 10,667
 * ticks (1.33-1.38 s) after samples of LADRC_GYRO_FILTER_INPUT_MAX: some 7 and
 * 53 time constants of the slowest section (tests/test_gyro_filter_recovery.c,
 * the fuzz target tests/fuzz/fuzz_gyro_filter.c; docs/vibration.md).
 */
#ifndef LADRC_GYRO_FILTER_H
#define LADRC_GYRO_FILTER_H

#include "ladrc/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most channels one filter runs (e.g. 3 body rates and 3 angles). */
#define LADRC_GYRO_FILTER_MAX_CHANNELS 6u
/** Most fixed notches. */
#define LADRC_GYRO_FILTER_MAX_NOTCHES 4u
/** Most rotors the RPM bank follows. */
#define LADRC_GYRO_FILTER_MAX_ROTORS 8u
/** Most harmonics per rotor (1 = the rotation frequency itself). */
#define LADRC_GYRO_FILTER_MAX_HARMONICS 4u
/** Most sections of one channel's chain: the fixed notches, the RPM notches, the low-pass. */
#define LADRC_GYRO_FILTER_MAX_STAGES                                                                                   \
    (LADRC_GYRO_FILTER_MAX_NOTCHES + LADRC_GYRO_FILTER_MAX_ROTORS * LADRC_GYRO_FILTER_MAX_HARMONICS + 1u)
/** Fraction of Nyquist at and above which a notch is off (0.9: centres from 0.45 / dt_s on).
 *  There a Q = 5 notch's upper -3 dB edge, f0 (1 + 1 / (2 Q)), reaches Nyquist, the notch
 *  narrows as sin(w0) falls, and a line a few per cent above its estimate already aliases
 *  to another frequency: the notch would be placed wrong. */
#define LADRC_GYRO_FILTER_CENTRE_MAX_NYQUIST LADRC_R(0.9)

/** Largest magnitude of a sample the filter takes (the channels' units): LADRC_REAL_MAX / 2^64,
 *  1.8e19 in float. Beyond any sensor, and 2^64 below overflow, so that no sample the step takes
 *  can overflow the chain's history; a larger one counts as non-finite. */
#define LADRC_GYRO_FILTER_INPUT_MAX (LADRC_REAL_MAX * LADRC_R(5.42101086242752217e-20))

/** An RPM notch's output never exceeds this many times its channel's input envelope (below):
 *  its coefficients change every tick, and direct form I under centres that jump at random can
 *  ring up without bound; a notch whose centre stays put never comes near it (its gain is at
 *  most 1, its ring-down at most about twice its input). With its history so bounded, the bank
 *  stays bounded for any sequence of centres and, once they settle, is a stable filter again:
 *  it recovers by itself. */
#define LADRC_GYRO_FILTER_RPM_GAIN_BOUND LADRC_R(8.0)
/** Time constant of the input envelope (s): slower than the ring-down of any notch the bank can
 *  hold (Q 5 at 20 Hz rings down in 80 ms), so the bound never cuts a legitimate output. */
#define LADRC_GYRO_FILTER_ENVELOPE_TAU_S LADRC_R(1.0)

/** Gyro filter configuration (ladrc_gyro_filter_init validates it); can live in flash.
 *  The fields of a stage that is off are not read (lpf_cutoff_hz with lpf_order 0, notch_q
 *  with n_notches 0, the rpm_ fields with rpm_rotors 0). */
typedef struct {
    ladrc_real_t dt_s;          /**< fixed step (s), in [LADRC_DT_MIN_S, LADRC_DT_MAX_S] */
    uint8_t channels;           /**< channels filtered, 1..LADRC_GYRO_FILTER_MAX_CHANNELS */
    uint8_t lpf_order;          /**< low-pass: 0 off, 1 first order, 2 second-order Butterworth */
    ladrc_real_t lpf_cutoff_hz; /**< low-pass -3 dB frequency (Hz), in (0, 0.5 / dt_s) */
    uint8_t n_notches;          /**< fixed notches, 0..LADRC_GYRO_FILTER_MAX_NOTCHES */
    /** centres of the fixed notches (Hz), each in (0, 0.45 / dt_s); the first n_notches are read */
    ladrc_real_t notch_hz[LADRC_GYRO_FILTER_MAX_NOTCHES];
    ladrc_real_t notch_q;     /**< quality of the fixed notches (centre / -3 dB width), > 0 */
    uint8_t rpm_rotors;       /**< rotors the RPM bank follows: 0 no bank, else 1..LADRC_GYRO_FILTER_MAX_ROTORS */
    uint8_t rpm_harmonics;    /**< notches per rotor, 1..LADRC_GYRO_FILTER_MAX_HARMONICS (1: the rotation itself) */
    ladrc_real_t rpm_q;       /**< quality of the RPM notches, > 0 */
    ladrc_real_t rpm_min_hz;  /**< an RPM notch centred below it is off (Hz), in (0, 0.45 / dt_s) */
    ladrc_real_t rpm_fade_hz; /**< weight from 0 at rpm_min_hz to 1 at rpm_min_hz + rpm_fade_hz (Hz), >= 0 */
} ladrc_gyro_filter_config_t;

/** One section's coefficients (a0 = 1) and its weight, shared by every channel. */
typedef struct {
    /** @{ */
    ladrc_real_t b0, b1, b2; /**< numerator */
    ladrc_real_t a1, a2;     /**< denominator after its leading 1 */
    /** @} */
    ladrc_real_t weight; /**< 0 off (output = input), 1 on, between: out = x + weight (y - x) */
} ladrc_gyro_filter_section_t;

/** One section's direct-form-I history on one channel. */
typedef struct {
    /** @{ */
    ladrc_real_t x1, x2; /**< its inputs one and two ticks back */
    ladrc_real_t y1, y2; /**< its outputs one and two ticks back (its input while off) */
    /** @} */
} ladrc_gyro_filter_history_t;

/** Gyro filter state; owned by the caller. Read it, never write it: use the functions. */
typedef struct {
    /** the chain: fixed notches, then the RPM notches rotor by rotor (harmonic 1 first), then the low-pass */
    ladrc_gyro_filter_section_t section[LADRC_GYRO_FILTER_MAX_STAGES];
    /** each channel's history of each section */
    ladrc_gyro_filter_history_t hist[LADRC_GYRO_FILTER_MAX_CHANNELS][LADRC_GYRO_FILTER_MAX_STAGES];
    /** scratch of the step: the oldest history (x2, y2) of each section before it moved, to
     *  put a channel back when its new state is not finite */
    ladrc_real_t undo[LADRC_GYRO_FILTER_MAX_STAGES][2];
    ladrc_real_t out[LADRC_GYRO_FILTER_MAX_CHANNELS]; /**< each channel's latest output (held on a fault) */
    /** each channel's input envelope: its largest |input|, decaying by envelope_decay per tick;
     *  an RPM notch's output is bounded by LADRC_GYRO_FILTER_RPM_GAIN_BOUND times it */
    ladrc_real_t envelope[LADRC_GYRO_FILTER_MAX_CHANNELS];
    ladrc_real_t envelope_decay;      /**< exp(-dt_s / LADRC_GYRO_FILTER_ENVELOPE_TAU_S) */
    ladrc_real_t rad_per_hz;          /**< 2 pi dt_s: a centre (Hz) as radians per tick */
    ladrc_real_t rpm_inv_2q;          /**< 1 / (2 rpm_q) */
    ladrc_real_t rpm_min_hz;          /**< of the config (Hz) */
    ladrc_real_t rpm_full_hz;         /**< rpm_min_hz + rpm_fade_hz: weight 1 from here (Hz) */
    ladrc_real_t rpm_inv_fade_per_hz; /**< 1 / rpm_fade_hz (1/Hz), 0 without a fade */
    ladrc_real_t centre_max_hz;       /**< 0.45 / dt_s: notches from here on are off (Hz) */
    uint8_t channels;                 /**< of the config; 0 after a rejected init */
    uint8_t n_sections;               /**< sections in the chain */
    uint8_t rpm_first;                /**< index of the first RPM notch (= n_notches) */
    uint8_t rpm_rotors;               /**< of the config */
    uint8_t rpm_harmonics;            /**< of the config */
    ladrc_fault_t faults;             /**< flags of the latest step */
} ladrc_gyro_filter_t;

/**
 * Fills cfg with dt_s and channels and every stage off: lpf_order 0,
 * n_notches 0, rpm_rotors 0. The parameters of the stages are set so that
 * switching a stage on alone gives a valid config: lpf_cutoff_hz 100 Hz,
 * notch_hz 0 Hz (set the centres), notch_q and rpm_q 5, rpm_harmonics 3,
 * rpm_min_hz 100 Hz, rpm_fade_hz 50 Hz; the three frequencies lowered to
 * 0.1 / dt_s (a fifth of Nyquist) on loops slower than 1 kHz.
 * @param cfg       the config to fill; NULL: nothing happens
 * @param dt_s      fixed step (s)
 * @param channels  channels filtered
 */
void ladrc_gyro_filter_config_default(ladrc_gyro_filter_config_t *cfg, ladrc_real_t dt_s, uint8_t channels);

/**
 * Validates cfg in the order below, derives the fixed sections and puts every
 * channel at rest on 0. The RPM notches are off until the first
 * ladrc_gyro_filter_set_rotor_hz. On a config error (not LADRC_ERR_NULL) *f is
 * zeroed: it has no channels, and a step on it writes nothing and returns
 * LADRC_FAULT_STATE.
 * @param[out] f    the filter to set up
 * @param[in]  cfg  its configuration
 * @retval LADRC_OK                     set up
 * @retval LADRC_ERR_NULL               f or cfg is NULL
 * @retval LADRC_ERR_DT_S               dt_s not finite or outside [LADRC_DT_MIN_S, LADRC_DT_MAX_S]
 * @retval LADRC_ERR_GYRO_CHANNELS      channels outside 1..LADRC_GYRO_FILTER_MAX_CHANNELS
 * @retval LADRC_ERR_GYRO_LPF_ORDER     lpf_order not 0, 1 or 2
 * @retval LADRC_ERR_GYRO_LPF_CUTOFF_HZ low-pass on: lpf_cutoff_hz not finite, not in (0, 0.5 / dt_s), or
 *                                      so near either end that its section rounds to an unstable one
 * @retval LADRC_ERR_GYRO_N_NOTCHES     n_notches above LADRC_GYRO_FILTER_MAX_NOTCHES
 * @retval LADRC_ERR_GYRO_NOTCH_HZ      one of the first n_notches notch_hz not finite or not in (0, 0.45 / dt_s)
 * @retval LADRC_ERR_GYRO_NOTCH_Q       n_notches > 0: notch_q not finite, not > 0, or so high or so low that a
 *                                      fixed notch rounds to an unstable section
 * @retval LADRC_ERR_GYRO_RPM_ROTORS    rpm_rotors above LADRC_GYRO_FILTER_MAX_ROTORS
 * @retval LADRC_ERR_GYRO_RPM_HARMONICS rpm_rotors > 0: rpm_harmonics outside 1..LADRC_GYRO_FILTER_MAX_HARMONICS
 * @retval LADRC_ERR_GYRO_RPM_MIN_HZ    rpm_rotors > 0: rpm_min_hz not finite or not in (0, 0.45 / dt_s)
 * @retval LADRC_ERR_GYRO_RPM_FADE_HZ   rpm_rotors > 0: rpm_fade_hz not finite, < 0, or > 0 with 1 / rpm_fade_hz
 *                                      not finite
 * @retval LADRC_ERR_GYRO_RPM_Q         rpm_rotors > 0: rpm_q not finite, not > 0, or so high or so low that an
 *                                      RPM notch at either end of the range (rpm_min_hz, 0.45 / dt_s) is within
 *                                      16 eps of instability as rounded (then a notch between could round
 *                                      unstable); a tiny rpm_min_hz fails it too
 */
ladrc_status_t ladrc_gyro_filter_init(ladrc_gyro_filter_t *f, const ladrc_gyro_filter_config_t *cfg);

/**
 * Puts channel ch at rest on value[ch] (every history, and the held output, at
 * value[ch]) and clears the faults; the RPM centres stay as the latest
 * ladrc_gyro_filter_set_rotor_hz left them. A value[ch] not finite or beyond
 * +-LADRC_GYRO_FILTER_INPUT_MAX puts that channel at rest on its latest output
 * instead and raises LADRC_FAULT_INPUT (in f->faults).
 * @param f      the filter; NULL: nothing happens
 * @param value  one value per channel (the channels' units); NULL: nothing happens
 */
void ladrc_gyro_filter_reset(ladrc_gyro_filter_t *f, const ladrc_real_t *value);

/**
 * Moves the RPM notches to the harmonics of the rotors' rotation frequencies,
 * once per tick before ladrc_gyro_filter_step (one sine, one cosine and
 * rpm_harmonics divisions per rotor; a rotor whose notches are all off takes
 * none). A non-finite or negative rotor_hz[r] keeps rotor r's notches as they
 * were and raises LADRC_FAULT_INPUT; the other rotors move. Without an RPM
 * bank it does nothing. Centres that move a few Hz per tick, and a speed that
 * glitches for a tick now and then, keep the outputs on the scale of the
 * input; speeds that jump at random every tick can make direct form I ring
 * up, but never beyond LADRC_GYRO_FILTER_RPM_GAIN_BOUND times the input's
 * envelope, and the bank recovers by itself once the centres settle.
 * @param f         the filter; NULL: LADRC_FAULT_STATE, nothing changes
 * @param rotor_hz  rotation frequency of each of the rpm_rotors rotors (Hz, revolutions per second,
 *                  e.g. eRPM / 60 / pole pairs); NULL: LADRC_FAULT_STATE, nothing changes
 * @return LADRC_FAULT_INPUT if a rotor was kept, else LADRC_FAULT_NONE
 */
ladrc_fault_t ladrc_gyro_filter_set_rotor_hz(ladrc_gyro_filter_t *f, const ladrc_real_t *rotor_hz);

/**
 * One tick of every channel through its chain: out[ch] = the filtered in[ch].
 * An in[ch] not finite or beyond +-LADRC_GYRO_FILTER_INPUT_MAX leaves that
 * channel's state unchanged, writes its latest output and raises
 * LADRC_FAULT_INPUT; a channel whose new state would not be finite is held
 * the same way with LADRC_FAULT_STATE (the input bound leaves that to a state
 * corrupted from outside). Other channels run on; the next good samples
 * continue as if the bad ones had been skipped.
 * @param f    the filter; NULL: LADRC_FAULT_STATE, nothing written
 * @param in   one sample per channel (e.g. rad/s); NULL: LADRC_FAULT_STATE, nothing written
 * @param out  one output per channel, may be in itself; NULL: LADRC_FAULT_STATE, nothing written
 * @return the fault flags of this step (also kept in f->faults); LADRC_FAULT_STATE, nothing written,
 *         on an instance init refused
 */
ladrc_fault_t ladrc_gyro_filter_step(ladrc_gyro_filter_t *f, const ladrc_real_t *in, ladrc_real_t *out);

/**
 * The weight of one RPM notch, as the latest ladrc_gyro_filter_set_rotor_hz set it.
 * @param f         the filter; NULL: 0
 * @param rotor     the rotor, 0..rpm_rotors - 1; beyond: 0
 * @param harmonic  the harmonic, 1..rpm_harmonics (1: the rotation frequency); beyond: 0
 * @return the weight in [0, 1]: 0 off, 1 the full notch
 */
ladrc_real_t ladrc_gyro_filter_get_rpm_weight(const ladrc_gyro_filter_t *f, uint8_t rotor, uint8_t harmonic);

#ifdef __cplusplus
}
#endif

#endif /* LADRC_GYRO_FILTER_H */
