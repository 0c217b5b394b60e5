/* SPDX-License-Identifier: BSD-3-Clause */
/* The modified LADRC in closed loop on a double-integrator test plant at
 * 1 kHz (wc = 15, wo = 75, J = 5.445e-3 kg m^2): HP-MLADRC against plain
 * LADRC and LP-MLADRC on one tone, a sweep of tones, two tones, a chirp,
 * angle noise, and a tone that jumps or stops. Each run starts the
 * disturbance at 2 s on a level reference. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "test_noise.h"
#include "test_plant.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3
#define PI 3.14159265358979
#define DEG (PI / 180.0)
#define ONSET_S 2.0
/* The bar for HP on one tone of 120 rad/s^2 from 1 rad/s up: at least 20
 * times narrower than LADRC (measured 200x and more, see the sweep). */
#define HP_MIN_IMPROVEMENT 20.0
/* LP tracks the disturbance with a 75 rad/s first-order lag: at 3 rad/s a 4%
 * residual, so about 25x narrower than LADRC; 10x is the bar. */
#define LP_MIN_IMPROVEMENT 10.0
/* Two tones: at least this much narrower than LADRC (and no wider than LP). */
#define HP_TWO_TONE_IMPROVEMENT 5.0
/* "Never worse than LADRC": the same plant and reference, so only the
 * compensation differs; 1% leaves room for float-level differences. */
#define NEVER_WORSE_REL_TOL 0.01
/* Angle noise of the paper's noisy case: variance 0.001 deg^2. */
#define NOISE_STD_RAD (0.0316227766 * DEG)
/* With that noise the band must stay within 0.03 deg (measured 0.012). */
#define NOISY_BAND_MAX_RAD (0.03 * DEG)

void setUp(void)
{
}
void tearDown(void)
{
}

typedef enum { SHAPE_TONES, SHAPE_CHIRP, SHAPE_JUMP } shape_t;

/* From ONSET_S to stop_s (rad/s^2): bias + amp sin(w t) + amp2 sin(w2 t);
 * CHIRP: bias + amp sin of a frequency sweeping w to w2 over 20 s; JUMP:
 * the tone runs at w until jump_s, then at w2. */
typedef struct {
    shape_t shape;
    double bias, amp, w, amp2, w2;
    double jump_s, stop_s;
} dist_t;

static double disturbance(double t, const void *ctx)
{
    const dist_t *d = (const dist_t *)ctx;
    if (t <= ONSET_S || t > d->stop_s) {
        return 0.0;
    }
    const double tau = t - ONSET_S;
    switch (d->shape) {
    case SHAPE_CHIRP:
        return d->bias + d->amp * sin(d->w * tau + (d->w2 - d->w) * tau * tau / 40.0);
    case SHAPE_JUMP:
        return d->bias + d->amp * sin((t <= d->jump_s ? d->w : d->w2) * t);
    default:
        return d->bias + d->amp * sin(d->w * t) + d->amp2 * sin(d->w2 * t);
    }
}

typedef struct {
    ladrc_variant_t variant;
    ladrc_hp_freq_mode_t freq_mode;
    double known_w_rad_s; /* KNOWN: the frequency given */
    dist_t d;
    double noise_std_rad;
    double from_s, to_s; /* window of the band and the RMS */
    double event_s;      /* settling is measured from here */
} run_t;

typedef struct {
    double band_rad;      /* largest |error| in (from_s, to_s] */
    double rms_rad;       /* RMS error in (from_s, to_s] */
    double settle_s;      /* from event_s until |error| stays under settle_band */
    double max_after_rad; /* largest |error| after event_s */
} result_t;

static result_t fly(const run_t *r, double settle_band_rad)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, r->variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.hp_freq_mode = r->freq_mode;
    if (r->freq_mode == LADRC_HP_FREQ_KNOWN) {
        cfg.hp_n_tones = 1u;
        cfg.hp_freq_rad_s[0] = (ladrc_real_t)r->known_w_rad_s;
    }
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    test_double_integrator_t plant;
    test_plant_init(&plant, 1.0 / J_KG_M2, disturbance, &r->d);
    unsigned seed = 2463534242u;
    result_t res = {.band_rad = 0.0, .rms_rad = 0.0, .settle_s = 0.0, .max_after_rad = 0.0};
    double sum_sq = 0.0;
    long samples = 0;
    double last_outside_s = r->event_s;
    const long n = (long)(r->to_s / DT_S + 0.5);
    for (long k = 0; k < n; ++k) {
        const double noise = r->noise_std_rad > 0.0 ? r->noise_std_rad * test_gaussian(&seed) : 0.0;
        /* LP needs the rate; LADRC and HP ignore it */
        const double u =
            axis_command_with_rate(&axis, 0.0f, (ladrc_real_t)(plant.y_rad + noise), (ladrc_real_t)plant.rate_rad_s);
        test_plant_step(&plant, u, DT_S, 1);
        const double t = (double)(k + 1) * DT_S;
        const double e = fabs(plant.y_rad);
        if (!isfinite(e) || e > 10.0) {
            res.band_rad = res.rms_rad = res.max_after_rad = HUGE_VAL;
            res.settle_s = HUGE_VAL;
            return res;
        }
        if (t > r->from_s) {
            res.band_rad = fmax(res.band_rad, e);
            sum_sq += e * e;
            samples++;
        }
        if (t > r->event_s) {
            res.max_after_rad = fmax(res.max_after_rad, e);
            if (e >= settle_band_rad) {
                last_outside_s = t;
            }
        }
    }
    res.rms_rad = sqrt(sum_sq / (double)(samples > 0 ? samples : 1));
    res.settle_s = last_outside_s - r->event_s;
    return res;
}

static run_t tone_run(ladrc_variant_t variant, double amp, double w)
{
    const run_t r = {.variant = variant,
                     .freq_mode = LADRC_HP_FREQ_ONLINE,
                     .known_w_rad_s = w,
                     .d = {.shape = SHAPE_TONES,
                           .bias = 20.0,
                           .amp = amp,
                           .w = w,
                           .amp2 = 0.0,
                           .w2 = 0.0,
                           .jump_s = 0.0,
                           .stop_s = 1e9},
                     .noise_std_rad = 0.0,
                     .from_s = 15.0,
                     .to_s = 25.0,
                     .event_s = 0.0};
    return r;
}

static void message(const char *what, double hp, double ladrc)
{
    char msg[160];
    snprintf(msg, sizeof msg, "%s: HP %.5f deg, LADRC %.5f deg (%.0fx narrower)", what, hp / DEG, ladrc / DEG,
             ladrc / hp);
    TEST_MESSAGE(msg);
}

static void test_hp_known_and_online_hold_the_papers_tone_to_a_thousandth_of_a_degree(void)
{
    /* 20 + 120 sin(3 t): the bar for the paper case is 0.001 deg known
     * and 0.0073 deg online; on this plant both reach about 2e-4 deg. */
    const double bar_known_rad = 0.001 * DEG;
    const double bar_online_rad = 0.0073 * DEG;
    run_t r = tone_run(LADRC_VARIANT_HP_MLADRC, 120.0, 3.0);
    const double online = fly(&r, 1.0).band_rad;
    r.freq_mode = LADRC_HP_FREQ_KNOWN;
    const double known = fly(&r, 1.0).band_rad;
    r.variant = LADRC_VARIANT_LADRC;
    const double ladrc = fly(&r, 1.0).band_rad;
    message("known", known, ladrc);
    message("online", online, ladrc);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(bar_known_rad), (float)(known));
    TEST_ASSERT_LESS_THAN_FLOAT((float)(bar_online_rad), (float)(online));
}

static void test_lp_band_is_10x_narrower_than_ladrc(void)
{
    const run_t lp = tone_run(LADRC_VARIANT_LP_MLADRC, 120.0, 3.0);
    const run_t ladrc = tone_run(LADRC_VARIANT_LADRC, 120.0, 3.0);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(fly(&ladrc, 1.0).band_rad / LP_MIN_IMPROVEMENT),
                                (float)(fly(&lp, 1.0).band_rad));
}

static void test_hp_online_beats_ladrc_on_every_tone_of_a_sweep(void)
{
    const double freqs[] = {0.5, 1.0, 2.0, 3.0, 5.0, 8.0, 12.0, 20.0};
    const double amps[] = {30.0, 120.0};
    for (unsigned i = 0; i < sizeof freqs / sizeof freqs[0]; ++i) {
        for (unsigned j = 0; j < 2u; ++j) {
            const run_t hp_run = tone_run(LADRC_VARIANT_HP_MLADRC, amps[j], freqs[i]);
            const run_t ladrc_run = tone_run(LADRC_VARIANT_LADRC, amps[j], freqs[i]);
            const result_t hp = fly(&hp_run, 1.0);
            const result_t ladrc = fly(&ladrc_run, 1.0);
            char what[64];
            snprintf(what, sizeof what, "w %.1f rad/s, A %.0f", freqs[i], amps[j]);
            message(what, hp.band_rad, ladrc.band_rad);
            const double never_worse = 1.0 + NEVER_WORSE_REL_TOL;
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((float)(ladrc.band_rad * never_worse), (float)(hp.band_rad), what);
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((float)(ladrc.rms_rad * never_worse), (float)(hp.rms_rad), what);
            if (freqs[i] >= 1.0 && amps[j] == 120.0) {
                TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE((float)(ladrc.band_rad / HP_MIN_IMPROVEMENT), (float)(hp.band_rad),
                                                    what);
            }
        }
    }
}

static void test_hp_online_rejects_two_tones(void)
{
    const dist_t pairs[] = {{.shape = SHAPE_TONES,
                             .bias = 20.0,
                             .amp = 120.0,
                             .w = 3.0,
                             .amp2 = 30.0,
                             .w2 = 8.0,
                             .jump_s = 0.0,
                             .stop_s = 1e9},
                            {.shape = SHAPE_TONES,
                             .bias = 20.0,
                             .amp = 60.0,
                             .w = 3.0,
                             .amp2 = 60.0,
                             .w2 = 5.0,
                             .jump_s = 0.0,
                             .stop_s = 1e9}};
    for (unsigned i = 0; i < 2u; ++i) {
        run_t r = {.variant = LADRC_VARIANT_HP_MLADRC,
                   .freq_mode = LADRC_HP_FREQ_ONLINE,
                   .known_w_rad_s = 0.0,
                   .d = pairs[i],
                   .noise_std_rad = 0.0,
                   .from_s = 15.0,
                   .to_s = 25.0,
                   .event_s = 0.0};
        const double hp = fly(&r, 1.0).band_rad;
        r.variant = LADRC_VARIANT_LP_MLADRC;
        const double lp = fly(&r, 1.0).band_rad;
        r.variant = LADRC_VARIANT_LADRC;
        const double ladrc = fly(&r, 1.0).band_rad;
        char what[64];
        snprintf(what, sizeof what, "%.0f sin %.0ft + %.0f sin %.0ft", pairs[i].amp, pairs[i].w, pairs[i].amp2,
                 pairs[i].w2);
        message(what, hp, ladrc);
        TEST_ASSERT_LESS_THAN_FLOAT_MESSAGE((float)(ladrc / HP_TWO_TONE_IMPROVEMENT), (float)(hp), what);
        TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((float)(lp), (float)(hp), what);
    }
}

static void test_hp_online_is_never_worse_than_ladrc_on_a_chirp(void)
{
    /* 120 sin of a tone sweeping 0.5 -> 15 rad/s over 20 s */
    run_t r = {.variant = LADRC_VARIANT_HP_MLADRC,
               .freq_mode = LADRC_HP_FREQ_ONLINE,
               .known_w_rad_s = 0.0,
               .d = {.shape = SHAPE_CHIRP,
                     .bias = 20.0,
                     .amp = 120.0,
                     .w = 0.5,
                     .amp2 = 0.0,
                     .w2 = 15.0,
                     .jump_s = 0.0,
                     .stop_s = 22.0},
               .noise_std_rad = 0.0,
               .from_s = ONSET_S,
               .to_s = 22.0,
               .event_s = 0.0};
    const result_t hp = fly(&r, 1.0);
    r.variant = LADRC_VARIANT_LADRC;
    const result_t ladrc = fly(&r, 1.0);
    message("chirp", hp.band_rad, ladrc.band_rad);
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT((float)(ladrc.band_rad * (1.0 + NEVER_WORSE_REL_TOL)), (float)(hp.band_rad));
    TEST_ASSERT_LESS_OR_EQUAL_FLOAT((float)(ladrc.rms_rad * (1.0 + NEVER_WORSE_REL_TOL)), (float)(hp.rms_rad));
}

static void test_hp_stays_within_three_hundredths_of_a_degree_with_angle_noise(void)
{
    for (int known = 0; known < 2; ++known) {
        run_t r = tone_run(LADRC_VARIANT_HP_MLADRC, 120.0, 3.0);
        r.noise_std_rad = NOISE_STD_RAD;
        r.freq_mode = known ? LADRC_HP_FREQ_KNOWN : LADRC_HP_FREQ_ONLINE;
        const double hp = fly(&r, 1.0).band_rad;
        r.variant = LADRC_VARIANT_LADRC;
        message(known ? "noisy, known" : "noisy, online", hp, fly(&r, 1.0).band_rad);
        TEST_ASSERT_LESS_THAN_FLOAT((float)(NOISY_BAND_MAX_RAD), (float)(hp));
    }
}

static void test_hp_relocks_after_a_frequency_jump(void)
{
    /* 0.785 -> 3 rad/s at 12 s (the paper's jump): |error| under 0.01 deg
     * within 2 s known and 3 s online on this plant (measured 1.52 and
     * 2.31 s; the paper case's own figures, 1.5 and 3 s, are checked on the
     * paper's vehicle in test_hp_paper). */
    const double limit_known_s = 2.0;
    const double limit_online_s = 3.0;
    /* known: the frequency after the jump (the paper's assumption) */
    run_t r = {.variant = LADRC_VARIANT_HP_MLADRC,
               .freq_mode = LADRC_HP_FREQ_ONLINE,
               .known_w_rad_s = 3.0,
               .d = {.shape = SHAPE_JUMP,
                     .bias = 20.0,
                     .amp = 120.0,
                     .w = 0.25 * PI,
                     .amp2 = 0.0,
                     .w2 = 3.0,
                     .jump_s = 12.0,
                     .stop_s = 1e9},
               .noise_std_rad = 0.0,
               .from_s = 20.0,
               .to_s = 25.0,
               .event_s = 12.0};
    const double online_s = fly(&r, 0.01 * DEG).settle_s;
    r.freq_mode = LADRC_HP_FREQ_KNOWN;
    const double known_s = fly(&r, 0.01 * DEG).settle_s;
    char msg[96];
    snprintf(msg, sizeof msg, "under 0.01 deg %.2f s after the jump known, %.2f s online", known_s, online_s);
    TEST_MESSAGE(msg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(limit_known_s), (float)(known_s));
    TEST_ASSERT_LESS_THAN_FLOAT((float)(limit_online_s), (float)(online_s));
}

static void test_hp_drops_a_tone_that_stops_within_half_a_second(void)
{
    /* The tone stops at 12 s; |error| back under 0.1 deg within 0.5 s (the
     * issue's bar), its largest error there below LADRC's. */
    const double limit_s = 0.5;
    run_t r = {.variant = LADRC_VARIANT_HP_MLADRC,
               .freq_mode = LADRC_HP_FREQ_ONLINE,
               .known_w_rad_s = 3.0,
               .d = {.shape = SHAPE_TONES,
                     .bias = 20.0,
                     .amp = 120.0,
                     .w = 3.0,
                     .amp2 = 0.0,
                     .w2 = 0.0,
                     .jump_s = 0.0,
                     .stop_s = 12.0},
               .noise_std_rad = 0.0,
               .from_s = 12.0,
               .to_s = 17.0,
               .event_s = 12.0};
    const result_t hp = fly(&r, 0.1 * DEG);
    r.variant = LADRC_VARIANT_LADRC;
    const result_t ladrc = fly(&r, 0.1 * DEG);
    char msg[128];
    snprintf(msg, sizeof msg, "after the stop: HP under 0.1 deg in %.2f s, largest %.3f deg (LADRC %.3f deg)",
             hp.settle_s, hp.max_after_rad / DEG, ladrc.max_after_rad / DEG);
    TEST_MESSAGE(msg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(limit_s), (float)(hp.settle_s));
    TEST_ASSERT_LESS_THAN_FLOAT((float)(ladrc.max_after_rad), (float)(hp.max_after_rad));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hp_known_and_online_hold_the_papers_tone_to_a_thousandth_of_a_degree);
    RUN_TEST(test_lp_band_is_10x_narrower_than_ladrc);
    RUN_TEST(test_hp_online_beats_ladrc_on_every_tone_of_a_sweep);
    RUN_TEST(test_hp_online_rejects_two_tones);
    RUN_TEST(test_hp_online_is_never_worse_than_ladrc_on_a_chirp);
    RUN_TEST(test_hp_stays_within_three_hundredths_of_a_degree_with_angle_noise);
    RUN_TEST(test_hp_relocks_after_a_frequency_jump);
    RUN_TEST(test_hp_drops_a_tone_that_stops_within_half_a_second);
    return UNITY_END();
}
