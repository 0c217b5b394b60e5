/* SPDX-License-Identifier: BSD-3-Clause */
/*
 * libFuzzer target: the library's gyro filter (src/gyro_filter.c) alone.
 * The bytes give a config (loop rate, channels, low-pass, fixed notches, RPM
 * bank; a refused one ends the input, an accepted one flies), then a
 * sequence of ticks: rotor speeds (in range mostly, jumping, alternating,
 * ramping, and NaN, infinite, negative and huge ones) and samples (on a
 * gyro's scale mostly, up to the largest the filter takes, and NaN,
 * infinite and beyond it), resets now and then; then a steady tail.
 * Besides what the sanitizers catch, it checks that:
 * - every output is finite and within gfr_output_gain times the largest
 *   sample the filter took (tests/support/gyro_filter_recovery.h: the RPM
 *   notches' bound times the gains of the fixed sections);
 * - a sample that is not finite or beyond LADRC_GYRO_FILTER_INPUT_MAX raises
 *   LADRC_FAULT_INPUT, writes the channel's latest output and leaves its
 *   history and envelope as they were; a rotor speed that is not finite or
 *   negative raises LADRC_FAULT_INPUT and leaves that rotor's notches as
 *   they were; nothing else faults (no LADRC_FAULT_STATE from any input);
 * - after the sequence, the rotors held still and a steady input bring the
 *   output within gfr_tolerance of a freshly initialised twin put at rest on
 *   that input and fed the same tail (the filter's normal output) within
 *   gfr_recovery_ticks_max ticks.
 * A config with a fixed section too slow to have its gain summed (a time
 * constant over 2000 ticks: a raw float's Q or centre) is flown without the
 * output bound and the tail, and one whose recovery bound passes
 * TAIL_TICKS_MAX without the tail: such inputs would cost seconds each.
 */
#include "fuzz.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "gyro_filter_recovery.h"
#include "ladrc/gyro_filter.h"

/* Most ticks of one input's sequence: two seconds at 1 kHz, a quarter of one at 8 kHz. */
#define SEQUENCE_TICKS_MAX 2048L
/* Most ticks of a run drawn from one op (random, alternating or ramping speeds). */
#define RUN_TICKS_MAX 1024u
/* Most ticks of the tail: the recovery bound of the configs the bytes
 * decode to without a raw float (time constants up to some 350 ticks) stays
 * below it for errors up to the largest sample's (2 x 350 x ln(1e23) + the
 * sections' sum, some 6e4); a slower config is flown without the tail. */
#define TAIL_TICKS_MAX 100000L
/* Ticks within tolerance in a row that end the tail early: more than half
 * the period of the slowest ring the decoded centres hold (2 % of Nyquist:
 * 100 ticks a period), so that a ringing gap's zero crossing does not end it. */
#define QUIET_TICKS 64L
/* Float's rounding of the output bound: a few eps per section on the way. */
#define BOUND_SLACK 1.001

typedef struct {
    const uint8_t *data;
    size_t size, at;
} bytes_t;

static uint8_t next_byte(bytes_t *b)
{
    return (b->at < b->size) ? b->data[b->at++] : 0u;
}

static float next_raw_float(bytes_t *b)
{
    uint8_t raw[4];
    float v;
    for (int i = 0; i < 4; ++i) {
        raw[i] = next_byte(b);
    }
    memcpy(&v, raw, sizeof v);
    return v;
}

/* A value between lo and hi spaced by ratio (log), or at 255 any float of
 * the next 4 bytes (NaN, negative, huge: what init must refuse). */
static ladrc_real_t log_between(bytes_t *b, double lo, double hi)
{
    const uint8_t u = next_byte(b);
    if (u == 255u) {
        return (ladrc_real_t)next_raw_float(b);
    }
    return (ladrc_real_t)(lo * pow(hi / lo, (double)u / 254.0));
}

static const double LOOP_HZ[] = {1000.0, 2000.0, 4000.0, 8000.0, 500.0, 3200.0, 8000.0};

static void decode_config(bytes_t *b, ladrc_gyro_filter_config_t *cfg)
{
    const uint8_t rate = next_byte(b) % 8u;
    const ladrc_real_t dt_s = (rate < 7u) ? (ladrc_real_t)(1.0 / LOOP_HZ[rate]) : (ladrc_real_t)next_raw_float(b);
    const double nyquist_hz = 0.5 / (double)dt_s;
    uint8_t u = next_byte(b);
    /* 254 and 255: 0 and 7 channels, refused */
    ladrc_gyro_filter_config_default(cfg, dt_s, (uint8_t)(u == 254u ? 0u : u == 255u ? 7u : 1u + u % 6u));
    u = next_byte(b);
    cfg->lpf_order = (uint8_t)(u == 255u ? 3u : u % 3u);
    cfg->lpf_cutoff_hz = (ladrc_real_t)nyquist_hz * log_between(b, 0.02, 1.0);
    u = next_byte(b);
    cfg->n_notches = (uint8_t)(u == 255u ? 5u : u % 5u);
    for (unsigned i = 0u; i < LADRC_GYRO_FILTER_MAX_NOTCHES; ++i) {
        cfg->notch_hz[i] = (ladrc_real_t)nyquist_hz * log_between(b, 0.02, 0.95);
    }
    cfg->notch_q = log_between(b, 0.5, 10.0);
    u = next_byte(b);
    cfg->rpm_rotors = (uint8_t)(u == 255u ? 9u : u % 9u);
    u = next_byte(b);
    cfg->rpm_harmonics = (uint8_t)(u == 254u ? 0u : u == 255u ? 5u : 1u + u % 4u); /* 0 and 5 refused */
    cfg->rpm_q = log_between(b, 0.5, 10.0);
    cfg->rpm_min_hz = (ladrc_real_t)nyquist_hz * log_between(b, 0.02, 0.95);
    u = next_byte(b);
    cfg->rpm_fade_hz = (u == 0u) ? LADRC_R(0.0) : (ladrc_real_t)nyquist_hz * log_between(b, 0.001, 0.5);
}

/* Values the filter must refuse or take at its edges: the first 8 are bad. */
static const double EDGE_SAMPLES[] = {NAN,
                                      INFINITY,
                                      -INFINITY,
                                      1e30,
                                      -(double)LADRC_REAL_MAX,
                                      (double)LADRC_GYRO_FILTER_INPUT_MAX * 1.001,
                                      -(double)LADRC_GYRO_FILTER_INPUT_MAX * 1.001,
                                      -NAN,
                                      (double)LADRC_GYRO_FILTER_INPUT_MAX,
                                      -(double)LADRC_GYRO_FILTER_INPUT_MAX,
                                      -0.0,
                                      1e-40,
                                      0.0,
                                      35.0,
                                      -35.0,
                                      1e15};

/* Scales of a sample: 1 rad/s, a fast flip (35 rad/s, 2000 deg/s), beyond
 * any gyro, the largest the filter takes. */
static const double SAMPLE_SCALE[] = {1.0, 35.0, 1e4, (double)LADRC_GYRO_FILTER_INPUT_MAX};

/* One sample from one byte at scale (255: an edge or, at 0, any float). */
static ladrc_real_t decode_sample(bytes_t *b, double scale)
{
    const uint8_t u = next_byte(b);
    if (u == 255u) {
        const uint8_t e = next_byte(b) % 17u;
        return (e == 16u) ? (ladrc_real_t)next_raw_float(b) : (ladrc_real_t)EDGE_SAMPLES[e];
    }
    return (ladrc_real_t)(scale * ((double)u - 127.0) / 127.0);
}

/* Rotor speeds the filter must keep or take at their edges: the first 5 are bad. */
static const double EDGE_SPEEDS[] = {NAN, INFINITY, -INFINITY, -1.0, -1e-30, -0.0, 0.0, 1e30, (double)FLT_MAX, 1e-40};

/* One speed from one byte over [0, 1.1 x the highest centre] (255: an edge or any float). */
static ladrc_real_t decode_speed(bytes_t *b, double top_hz)
{
    const uint8_t u = next_byte(b);
    if (u == 255u) {
        const uint8_t e = next_byte(b) % 11u;
        return (e == 10u) ? (ladrc_real_t)next_raw_float(b) : (ladrc_real_t)EDGE_SPEEDS[e];
    }
    return (ladrc_real_t)(1.1 * top_hz * (double)u / 254.0);
}

/* xorshift32: the speeds and samples of a run, from a seed of the input. */
static double uniform(uint32_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (double)*s / 4294967296.0;
}

static int sample_ok(ladrc_real_t x)
{
    return isfinite((double)x) && fabs((double)x) <= (double)LADRC_GYRO_FILTER_INPUT_MAX;
}

static int speed_ok(ladrc_real_t hz)
{
    return isfinite((double)hz) && hz >= LADRC_R(0.0);
}

typedef struct {
    ladrc_gyro_filter_t f, twin;
    ladrc_gyro_filter_config_t cfg;
    double gain;    /* gfr_output_gain, -1 when not summed */
    double largest; /* largest |sample| taken */
    double top_hz;  /* the highest centre: 0.45 / dt_s */
    ladrc_real_t hz[LADRC_GYRO_FILTER_MAX_ROTORS];
    ladrc_real_t tail_hz[LADRC_GYRO_FILTER_MAX_ROTORS];
    ladrc_real_t tail_in[LADRC_GYRO_FILTER_MAX_CHANNELS];
    double tail_abs; /* largest |tail_in| */
    long ticks;
} run_t;

/* ladrc_gyro_filter_set_rotor_hz, checked: a bad speed keeps its rotor's notches, the rest move. */
static void set_speeds(run_t *r)
{
    ladrc_gyro_filter_section_t before[LADRC_GYRO_FILTER_MAX_STAGES];
    const unsigned h = r->f.rpm_harmonics;
    int any_bad = 0;
    memcpy(before, r->f.section, sizeof before);
    const ladrc_fault_t fault = ladrc_gyro_filter_set_rotor_hz(&r->f, r->hz);
    for (unsigned rotor = 0u; rotor < r->cfg.rpm_rotors; ++rotor) {
        const unsigned first = r->f.rpm_first + rotor * h;
        if (!speed_ok(r->hz[rotor])) {
            any_bad = 1;
            FUZZ_CHECK(memcmp(&before[first], &r->f.section[first], h * sizeof before[0]) == 0,
                       "rotor %u at %g Hz: its notches moved", rotor, (double)r->hz[rotor]);
        }
        for (unsigned k = 0u; k < h; ++k) {
            const double w = (double)r->f.section[first + k].weight;
            FUZZ_CHECK(w >= 0.0 && w <= 1.0, "rotor %u harmonic %u: weight %g", rotor, k + 1u, w);
        }
    }
    FUZZ_CHECK(fault == (any_bad ? LADRC_FAULT_INPUT : LADRC_FAULT_NONE), "speeds: fault %u, a bad speed: %d",
               (unsigned)fault, any_bad);
}

/* ladrc_gyro_filter_step, checked: bad samples hold their channel, every output finite and bounded. */
static void step(run_t *r, const ladrc_real_t *in)
{
    ladrc_gyro_filter_history_t hist[LADRC_GYRO_FILTER_MAX_CHANNELS][LADRC_GYRO_FILTER_MAX_STAGES];
    ladrc_real_t env[LADRC_GYRO_FILTER_MAX_CHANNELS], held[LADRC_GYRO_FILTER_MAX_CHANNELS];
    ladrc_real_t out[LADRC_GYRO_FILTER_MAX_CHANNELS];
    const unsigned n = r->f.n_sections;
    int any_bad = 0;
    for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
        any_bad |= !sample_ok(in[ch]);
    }
    if (any_bad) { /* the state the bad samples must leave as it is */
        memcpy(hist, r->f.hist, sizeof hist);
        memcpy(env, r->f.envelope, sizeof env);
        memcpy(held, r->f.out, sizeof held);
    }
    const ladrc_fault_t fault = ladrc_gyro_filter_step(&r->f, in, out);
    for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
        if (!sample_ok(in[ch])) {
            FUZZ_CHECK(memcmp(&out[ch], &held[ch], sizeof out[ch]) == 0 &&
                           memcmp(hist[ch], r->f.hist[ch], n * sizeof hist[0][0]) == 0 &&
                           memcmp(&env[ch], &r->f.envelope[ch], sizeof env[ch]) == 0,
                       "tick %ld channel %u: the bad sample %g changed the state", r->ticks, ch, (double)in[ch]);
            continue;
        }
        r->largest = fmax(r->largest, fabs((double)in[ch]));
        FUZZ_CHECK(isfinite((double)out[ch]), "tick %ld channel %u: output %g", r->ticks, ch, (double)out[ch]);
        FUZZ_CHECK(r->gain < 0.0 || fabs((double)out[ch]) <= BOUND_SLACK * r->gain * r->largest + 1e-30,
                   "tick %ld channel %u: |output| %g beyond %g x the largest sample %g", r->ticks, ch, (double)out[ch],
                   r->gain, r->largest);
    }
    FUZZ_CHECK(fault == (any_bad ? LADRC_FAULT_INPUT : LADRC_FAULT_NONE), "tick %ld: fault %u, a bad sample: %d",
               r->ticks, (unsigned)fault, any_bad);
    ++r->ticks;
}

/* ladrc_gyro_filter_reset, checked: a bad value rests the channel on its latest output. */
static void reset(run_t *r, const ladrc_real_t *value)
{
    ladrc_real_t held[LADRC_GYRO_FILTER_MAX_CHANNELS];
    int any_bad = 0;
    memcpy(held, r->f.out, sizeof held);
    ladrc_gyro_filter_reset(&r->f, value);
    for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
        const ladrc_real_t rest = sample_ok(value[ch]) ? value[ch] : held[ch];
        any_bad |= !sample_ok(value[ch]);
        FUZZ_CHECK(memcmp(&r->f.out[ch], &rest, sizeof rest) == 0, "reset channel %u on %g: rests on %g", ch,
                   (double)value[ch], (double)r->f.out[ch]);
        r->largest = fmax(r->largest, fabs((double)rest)); /* a value it took */
    }
    FUZZ_CHECK(r->f.faults == (any_bad ? LADRC_FAULT_INPUT : LADRC_FAULT_NONE), "reset: faults %u, a bad value: %d",
               (unsigned)r->f.faults, any_bad);
}

/* A run of ticks whose speeds come from a generator: 0 random over the
 * range every tick, 1 alternating between two speeds, 2 a sawtooth over the
 * whole range every few ticks. Samples: a sine at scale with noise. */
static void fly_run(run_t *r, bytes_t *b, unsigned kind, double scale)
{
    const unsigned ticks = 1u + (unsigned)next_byte(b) * 4u;
    uint32_t seed = 1u + ((uint32_t)next_byte(b) << 8) + next_byte(b);
    const double lo = 1.1 * r->top_hz * next_byte(b) / 255.0, hi = 1.1 * r->top_hz * next_byte(b) / 255.0;
    const unsigned period = 2u + next_byte(b) % 16u;
    for (unsigned k = 0u; k < ticks && k < RUN_TICKS_MAX && r->ticks < SEQUENCE_TICKS_MAX; ++k) {
        ladrc_real_t in[LADRC_GYRO_FILTER_MAX_CHANNELS];
        for (unsigned rotor = 0u; rotor < r->cfg.rpm_rotors; ++rotor) {
            double hz;
            if (kind == 0u) {
                hz = 1.1 * r->top_hz * uniform(&seed);
            } else if (kind == 1u) {
                hz = (k % 2u == 0u) ? lo : hi;
            } else {
                hz = 1.1 * r->top_hz * (double)((k + rotor) % period) / (double)(period - 1u);
            }
            r->hz[rotor] = (ladrc_real_t)hz;
        }
        for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
            in[ch] =
                (ladrc_real_t)(scale * (0.8 * sin(0.37 * (double)(k + 7u * ch)) + 0.2 * (2.0 * uniform(&seed) - 1.0)));
        }
        if (r->cfg.rpm_rotors > 0u) {
            set_speeds(r);
        }
        step(r, in);
    }
}

static void fly_sequence(run_t *r, bytes_t *b)
{
    while (b->at < b->size && r->ticks < SEQUENCE_TICKS_MAX) {
        const uint8_t op = next_byte(b);
        const double scale = SAMPLE_SCALE[(op >> 4) & 3u];
        ladrc_real_t in[LADRC_GYRO_FILTER_MAX_CHANNELS];
        switch (op & 7u) {
        case 0u: /* samples only, the speeds as they were */
            break;
        case 1u: /* new speeds, then samples */
            for (unsigned rotor = 0u; rotor < r->cfg.rpm_rotors; ++rotor) {
                r->hz[rotor] = decode_speed(b, r->top_hz);
            }
            set_speeds(r);
            break;
        case 2u:
        case 3u:
        case 4u:
            fly_run(r, b, (op & 7u) - 2u, scale);
            continue;
        case 5u: /* a reset */
            for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
                in[ch] = decode_sample(b, scale);
            }
            reset(r, in);
            continue;
        default: /* the same speeds again */
            set_speeds(r);
            break;
        }
        for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
            in[ch] = decode_sample(b, scale);
        }
        step(r, in);
    }
}

/* The steady tail, decoded before the sequence (right after the config):
 * one speed per rotor over [0, 1.1 x the highest centre] and one sample per
 * channel at one of the scales, all in range. */
static void decode_tail(run_t *r, bytes_t *b)
{
    const double scale = SAMPLE_SCALE[next_byte(b) % 4u];
    for (unsigned rotor = 0u; rotor < r->cfg.rpm_rotors; ++rotor) {
        r->tail_hz[rotor] = (ladrc_real_t)(1.1 * r->top_hz * (double)next_byte(b) / 255.0);
    }
    r->tail_abs = 0.0;
    for (unsigned ch = 0u; ch < r->cfg.channels; ++ch) {
        r->tail_in[ch] = (ladrc_real_t)(scale * ((double)next_byte(b) - 127.5) / 127.5);
        r->tail_abs = fmax(r->tail_abs, fabs((double)r->tail_in[ch]));
    }
}

/* The tail flown against a fresh twin: within tolerance by the recovery bound. */
static void fly_tail(run_t *r)
{
    double gap = 0.0;
    if (r->cfg.rpm_rotors > 0u) {
        memcpy(r->hz, r->tail_hz, sizeof r->hz);
        set_speeds(r); /* the bound's slowest section is one of the centres of the tail */
    }
    r->largest = fmax(r->largest, r->tail_abs);
    const double tol = gfr_tolerance(&r->f, r->tail_abs);
    /* Either output is within gain x the largest sample it took: their gap within twice that. */
    const double error0 = 2.0 * r->gain * r->largest;
    const double bound_ticks = gfr_recovery_ticks_max(&r->f, error0, tol);
    if (r->gain < 0.0 || bound_ticks > (double)TAIL_TICKS_MAX) {
        return; /* too slow to fly here (see the top of the file) */
    }
    const long ticks = gfr_fly_tail(&r->f, &r->twin, &r->cfg, r->cfg.rpm_rotors > 0u ? r->tail_hz : NULL, r->tail_in,
                                    tol, (long)bound_ticks + QUIET_TICKS, QUIET_TICKS, &gap);
    FUZZ_CHECK(ticks >= 0 && (double)ticks <= bound_ticks,
               "after %ld ticks: %ld ticks to recover, bound %.0f (slowest section %.1f ticks), gap %g, tolerance %g "
               "(largest sample %g, gain %g)",
               r->ticks, ticks, bound_ticks, gfr_slowest_ticks(&r->f, NULL), gap, tol, r->largest, r->gain);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static run_t r;
    bytes_t b = {data, size, 0u};
    memset(&r, 0, sizeof r);
    decode_config(&b, &r.cfg);
    if (ladrc_gyro_filter_init(&r.f, &r.cfg) != LADRC_OK) {
        return 0;
    }
    r.top_hz = (double)r.f.centre_max_hz;
    r.gain = gfr_output_gain(&r.f);
    decode_tail(&r, &b);
    fly_sequence(&r, &b);
    fly_tail(&r);
    return 0;
}
