/* SPDX-License-Identifier: BSD-3-Clause */
/* HP-MLADRC on the paper's case: the paper's vehicle (rigid body with drag
 * and coupling), references and Table 2 disturbances, the attitude layer at
 * 1 kHz with ideal actuators; the figures the method is judged by, known and
 * online frequency. */
#include "unity.h"
#include "ladrc/attitude.h"
#include "test_rigid_body.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3
#define PI 3.14159265358979
#define DEG (PI / 180.0)
#define RUN_S 30.0
#define JUMP_S 12.0 /* the tone jumps from pi/4 to 3 rad/s */
#define STOP_S 25.0 /* the disturbance stops */
/* The steady band over (20, 25] s on every axis: the paper reports 0.0073
 * deg; the bars are ten times narrower known, the paper's figure online
 * (measured 0.00075 deg both). */
#define BAND_KNOWN_MAX_DEG 0.001
#define BAND_ONLINE_MAX_DEG 0.0073
/* After the jump |error| stays under 0.01 deg within these (measured 1.46
 * and 2.47 s). */
#define RELOCK_KNOWN_MAX_S 1.5
#define RELOCK_ONLINE_MAX_S 3.0
/* Angle noise of variance 0.001 deg^2: band within 0.03 deg (measured 0.025). */
#define NOISE_STD_RAD (0.0316227766 * DEG)
#define NOISY_BAND_MAX_DEG 0.03
/* After the stop |error| under 0.1 deg within this (measured 0.39 s, both
 * modes). */
#define STOP_SETTLE_MAX_S 0.5

void setUp(void)
{
}
void tearDown(void)
{
}

static double reference(int axis, double t, double scale)
{
    if (axis == 0) {
        return scale * (5.0 + 15.0 * cos(0.5 * PI * t)) * DEG;
    }
    return axis == 1 ? scale * 10.0 * cos(0.5 * PI * t) * DEG : 0.0;
}

/* Table 2: roll and yaw 20 - 120 sin, pitch 20 + 120 sin (rad/s^2). */
static double disturbance(int axis, double t)
{
    const double sign = (axis == 1) ? 1.0 : -1.0;
    if (t <= 2.0 || t > STOP_S) {
        return 0.0;
    }
    if (t <= 6.0) {
        return axis == 0 ? 8.0 : 6.0;
    }
    return 20.0 + sign * 120.0 * sin(t <= JUMP_S ? 0.25 * PI * t : 3.0 * t);
}

typedef struct {
    double band_deg;      /* largest |error| over (20, 25] s, worst axis */
    double relock_s;      /* after the jump until |error| stays under 0.01 deg, worst axis */
    double rms_deg;       /* RMS error over (12, 25] s, worst axis */
    double stop_settle_s; /* after the stop until |error| stays under 0.1 deg, worst axis */
    double stop_max_deg;  /* largest |error| after the stop, worst axis */
} paper_result_t;

static paper_result_t fly(ladrc_variant_t variant, ladrc_hp_freq_mode_t mode, double noise_std_rad, double ref_scale)
{
    static const ladrc_real_t inertia[3] = {5.445e-3f, 5.445e-3f, 1.089e-2f};
    ladrc_attitude_config_t cfg;
    ladrc_attitude_config_default(&cfg, variant, (ladrc_real_t)DT_S, inertia, 0.09f);
    for (int i = 0; i < 3; ++i) {
        cfg.axis[i].hp_freq_mode = mode;
        if (mode == LADRC_HP_FREQ_KNOWN) {
            cfg.axis[i].hp_n_tones = 1u; /* the paper's assumption: the frequency of the steady tone */
            cfg.axis[i].hp_freq_rad_s[0] = 3.0f;
        }
    }
    ladrc_attitude_t att;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_attitude_init(&att, &cfg, NULL));
    test_rigid_body_t body;
    test_rigid_body_init(&body);
    unsigned seed = 88172645u;
    paper_result_t res = {.band_deg = 0.0, .relock_s = 0.0, .rms_deg = 0.0, .stop_settle_s = 0.0, .stop_max_deg = 0.0};
    double sum_sq[3] = {0.0, 0.0, 0.0};
    long rms_samples = 0;
    const long ticks = (long)(RUN_S / DT_S + 0.5);
    for (long k = 0; k < ticks; ++k) {
        const double t = (double)k * DT_S;
        ladrc_real_t ref[3], angle[3], rate[3], torque[3];
        double dist[3], tq[3];
        for (int i = 0; i < 3; ++i) {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            /* uniform noise of the given standard deviation */
            const double noise = noise_std_rad * 3.4641016 * ((double)(seed >> 8) / 16777216.0 - 0.5);
            ref[i] = (ladrc_real_t)reference(i, t, ref_scale);
            angle[i] = (ladrc_real_t)(body.angle_rad[i] + noise);
            rate[i] = (ladrc_real_t)body.rate_rad_s[i];
            dist[i] = disturbance(i, t + 0.5 * DT_S);
        }
        (void)ladrc_attitude_step(&att, ref, angle, rate, torque);
        ladrc_attitude_set_applied(&att, torque);
        for (int i = 0; i < 3; ++i) {
            tq[i] = torque[i];
        }
        test_rigid_body_step(&body, tq, dist, DT_S, 2);
        const double tn = t + DT_S;
        for (int i = 0; i < 3; ++i) {
            const double e = fabs(reference(i, tn, ref_scale) - body.angle_rad[i]) / DEG;
            TEST_ASSERT_TRUE_MESSAGE(isfinite(e) && e < 90.0, "the loop diverged");
            if (tn > 20.0 && tn <= STOP_S) {
                res.band_deg = fmax(res.band_deg, e);
            }
            if (tn > JUMP_S && tn <= STOP_S) {
                sum_sq[i] += e * e;
                if (e >= 0.01) {
                    res.relock_s = fmax(res.relock_s, tn - JUMP_S);
                }
            }
            if (tn > STOP_S) {
                res.stop_max_deg = fmax(res.stop_max_deg, e);
                if (e >= 0.1) {
                    res.stop_settle_s = fmax(res.stop_settle_s, tn - STOP_S);
                }
            }
        }
        if (tn > JUMP_S && tn <= STOP_S) {
            rms_samples++;
        }
    }
    for (int i = 0; i < 3; ++i) {
        res.rms_deg = fmax(res.rms_deg, sqrt(sum_sq[i] / (double)rms_samples));
    }
    return res;
}

static void say(const char *what, const paper_result_t *r)
{
    char msg[200];
    snprintf(msg, sizeof msg,
             "%s: band %.5f deg, under 0.01 deg %.2f s after the jump, RMS (12, 25] %.4f deg, "
             "under 0.1 deg %.2f s after the stop (largest %.3f deg)",
             what, r->band_deg, r->relock_s, r->rms_deg, r->stop_settle_s, r->stop_max_deg);
    TEST_MESSAGE(msg);
}

static void test_known_frequency_holds_a_tenth_of_the_papers_band_and_relocks_in_time(void)
{
    const paper_result_t r = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_KNOWN, 0.0, 1.0);
    say("HP known", &r);
    TEST_ASSERT_LESS_THAN_FLOAT((float)BAND_KNOWN_MAX_DEG, (float)r.band_deg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)RELOCK_KNOWN_MAX_S, (float)r.relock_s);
}

static void test_online_frequency_holds_the_papers_band_and_relocks_in_time(void)
{
    const paper_result_t r = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE, 0.0, 1.0);
    say("HP online", &r);
    TEST_ASSERT_LESS_THAN_FLOAT((float)BAND_ONLINE_MAX_DEG, (float)r.band_deg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)RELOCK_ONLINE_MAX_S, (float)r.relock_s);
}

static void test_a_stopped_tone_is_dropped_within_half_a_second_below_ladrcs_error(void)
{
    const paper_result_t hp = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE, 0.0, 1.0);
    const paper_result_t known = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_KNOWN, 0.0, 1.0);
    const paper_result_t ladrc = fly(LADRC_VARIANT_LADRC, LADRC_HP_FREQ_ONLINE, 0.0, 1.0);
    const paper_result_t lp = fly(LADRC_VARIANT_LP_MLADRC, LADRC_HP_FREQ_ONLINE, 0.0, 1.0);
    say("LADRC", &ladrc);
    say("LP", &lp);
    TEST_ASSERT_LESS_THAN_FLOAT((float)STOP_SETTLE_MAX_S, (float)hp.stop_settle_s);
    TEST_ASSERT_LESS_THAN_FLOAT((float)ladrc.stop_max_deg, (float)hp.stop_max_deg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)STOP_SETTLE_MAX_S, (float)known.stop_settle_s);
    TEST_ASSERT_LESS_THAN_FLOAT((float)ladrc.stop_max_deg, (float)known.stop_max_deg);
    /* HP's RMS over (12, 25] s carries the LADRC-like seconds after the jump
     * and stays above LP's (docs/comparisons.md, "HP-MLADRC against its targets"); it must stay below LADRC's */
    TEST_ASSERT_LESS_THAN_FLOAT((float)ladrc.rms_deg, (float)hp.rms_deg);
}

static void test_angle_noise_keeps_the_band_within_three_hundredths_of_a_degree(void)
{
    const paper_result_t known = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_KNOWN, NOISE_STD_RAD, 1.0);
    const paper_result_t online = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE, NOISE_STD_RAD, 1.0);
    say("HP known, noisy", &known);
    say("HP online, noisy", &online);
    TEST_ASSERT_LESS_THAN_FLOAT((float)NOISY_BAND_MAX_DEG, (float)known.band_deg);
    TEST_ASSERT_LESS_THAN_FLOAT((float)NOISY_BAND_MAX_DEG, (float)online.band_deg);
}

static void test_twice_the_reference_does_not_stall_the_compensation(void)
{
    /* the drag and coupling that move with the reference are kept out of the
     * estimator's sample, so a larger reference leaves the band as it was */
    const paper_result_t r = fly(LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE, 0.0, 2.0);
    say("HP online, reference x2", &r);
    TEST_ASSERT_LESS_THAN_FLOAT((float)BAND_ONLINE_MAX_DEG, (float)r.band_deg);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_known_frequency_holds_a_tenth_of_the_papers_band_and_relocks_in_time);
    RUN_TEST(test_online_frequency_holds_the_papers_band_and_relocks_in_time);
    RUN_TEST(test_a_stopped_tone_is_dropped_within_half_a_second_below_ladrcs_error);
    RUN_TEST(test_angle_noise_keeps_the_band_within_three_hundredths_of_a_degree);
    RUN_TEST(test_twice_the_reference_does_not_stall_the_compensation);
    return UNITY_END();
}
