/* SPDX-License-Identifier: BSD-3-Clause */
/* HP-MLADRC on the gyro (hp_sample = LADRC_HP_SAMPLE_GYRO) in closed loop on
 * a small plant with a real motor: J = 0.0139 kg m^2 (a 1.96 kg quad), a
 * 30 ms motor lag the axis models, 1 kHz, gyro noise 0.5 deg/s, angle noise
 * 0.05 deg; wc = 6.4, wo = 51 (what tune = margins gives LP-MLADRC there).
 * Against LP-MLADRC with the same gains. */
#include "unity.h"
#include "test_axis_command.h"
#include "ladrc/axis.h"
#include "test_gyro_quad.h"
#include "test_noise.h"
#include "test_plant.h"

#include <math.h>
#include <stdio.h>

#define ONSET_S 2.0
/* The steady tone: 30 rad/s^2 (a fifth of the authority of such a quad) at
 * 9 rad/s, known to the estimator; the window starts once the gate has had
 * 10 s (engaged, it holds the weight at 1). */
#define TONE_RAD_S2 30.0
#define TONE_W_RAD_S 9.0
#define WINDOW_FROM_S 12.0
#define SLOW_TONE_W_RAD_S 3.0
#define WINDOW_TO_S 20.0
/* Engaged, HP must hold at most this share of LP's RMS over the window:
 * the fit takes the whole tone and advances it over the motor lag exactly
 * (measured 0.007x; the bar a tenth of the 0.5x asked of the variant, still
 * seven times the measurement, room for float against double). */
#define STEADY_TONE_RATIO_MAX 0.05
/* After the tone stops, the gate lets go within 0.2 s (measured 0.016 s:
 * the change detection drops the weight at once). */
#define LET_GO_S 0.2

void setUp(void)
{
}
void tearDown(void)
{
}

typedef struct {
    double amp, w, stop_s, step; /* tone amp sin(w t) over (ONSET_S, stop_s], plus a step */
} dist_t;

static double disturbance(double t, const void *ctx)
{
    const dist_t *d = (const dist_t *)ctx;
    if (t <= ONSET_S) {
        return 0.0;
    }
    return d->step + ((t <= d->stop_s) ? d->amp * sin(d->w * t) : 0.0);
}

static ladrc_axis_config_t config(ladrc_variant_t variant)
{
    ladrc_axis_config_t cfg = test_gyro_quad_config(variant);
    cfg.hp_freq_mode = LADRC_HP_FREQ_KNOWN;
    cfg.hp_n_tones = 1u;
    cfg.hp_freq_rad_s[0] = (ladrc_real_t)TONE_W_RAD_S;
    return cfg;
}

typedef struct {
    double rms_rad;            /* RMS angle error over the window */
    double weight_at_stop;     /* HP's gate weight when the tone stops */
    double let_go_s;           /* from the stop until the weight is 0 (HUGE_VAL: never) */
    double max_torque_diff_Nm; /* largest |torque - twin's torque|, twin given */
    double max_error_rad;      /* largest |angle error| over the window */
} result_t;

/* Flies the axis; with twin, a second axis on the same measurements whose
 * torques are compared (the plant follows the first). */
static result_t fly(const ladrc_axis_config_t *cfg, const ladrc_axis_config_t *twin_cfg, const dist_t *d, double from_s,
                    double to_s)
{
    ladrc_axis_t axis, twin;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, cfg));
    if (twin_cfg != NULL) {
        TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&twin, twin_cfg));
    }
    double y = 0.0, w = 0.0, m = 0.0;
    unsigned seed = 2463534242u;
    result_t r = {
        .rms_rad = 0.0, .weight_at_stop = 0.0, .let_go_s = HUGE_VAL, .max_torque_diff_Nm = 0.0, .max_error_rad = 0.0};
    double sum_sq = 0.0;
    long samples = 0;
    const long n = (long)(to_s / DT_S + 0.5);
    for (long k = 0; k < n; ++k) {
        const double t = (double)k * DT_S;
        const ladrc_real_t angle = (ladrc_real_t)(y + ANGLE_NOISE_RAD * test_gaussian(&seed));
        const ladrc_real_t rate = (ladrc_real_t)(w + GYRO_NOISE_RAD_S * test_gaussian(&seed));
        const double u = axis_command_with_rate(&axis, 0.0f, angle, rate);
        if (twin_cfg != NULL) {
            const double u_twin = axis_command_with_rate(&twin, 0.0f, angle, rate);
            r.max_torque_diff_Nm = fmax(r.max_torque_diff_Nm, fabs(u - u_twin));
        }
        const ladrc_hp_estimator_t *hp = ladrc_axis_get_hp(&axis);
        if (hp != NULL) {
            const double weight = (double)ladrc_hp_get_weight(hp);
            if (t <= d->stop_s) {
                r.weight_at_stop = weight;
            } else if (weight == 0.0 && r.let_go_s == HUGE_VAL) {
                r.let_go_s = t - d->stop_s;
            }
        }
        double dy, dw;
        const double f = disturbance(t, d);
        test_lag_step(DT_S, TAU_S, u, &m, &dy, &dw);
        y += w * DT_S + dy / J_KG_M2 + 0.5 * f * DT_S * DT_S;
        w += dw / J_KG_M2 + f * DT_S;
        TEST_ASSERT_TRUE_MESSAGE(isfinite(y) && fabs(y) < 1.0, "diverged");
        if (t + DT_S > from_s) {
            r.max_error_rad = fmax(r.max_error_rad, fabs(y));
            sum_sq += y * y;
            samples++;
        }
    }
    r.rms_rad = sqrt(sum_sq / (double)samples);
    return r;
}

static void test_without_a_tone_it_flies_as_lp_mladrc(void)
{
    /* a wind step and no tone: the gate stays shut, every torque is LP's */
    const ladrc_axis_config_t hp = config(LADRC_VARIANT_HP_MLADRC);
    const ladrc_axis_config_t lp = config(LADRC_VARIANT_LP_MLADRC);
    const dist_t d = {.amp = 0.0, .w = TONE_W_RAD_S, .stop_s = 1e9, .step = 20.0};
    const result_t r = fly(&hp, &lp, &d, WINDOW_FROM_S, WINDOW_TO_S);
    TEST_ASSERT_EQUAL_FLOAT(0.0, r.weight_at_stop);
    /* bit for bit: the sum LP + 0 is LP */
    TEST_ASSERT_EQUAL_FLOAT(0.0, r.max_torque_diff_Nm);
}

static void test_on_a_steady_tone_it_cuts_lp_mladrcs_error_twentyfold(void)
{
    const ladrc_axis_config_t hp = config(LADRC_VARIANT_HP_MLADRC);
    const ladrc_axis_config_t lp = config(LADRC_VARIANT_LP_MLADRC);
    const dist_t d = {.amp = TONE_RAD_S2, .w = TONE_W_RAD_S, .stop_s = 1e9, .step = 5.0};
    const result_t r_hp = fly(&hp, NULL, &d, WINDOW_FROM_S, WINDOW_TO_S);
    const result_t r_lp = fly(&lp, NULL, &d, WINDOW_FROM_S, WINDOW_TO_S);
    char msg[128];
    snprintf(msg, sizeof msg, "RMS HP %.4f deg, LP %.4f deg (ratio %.3f)", r_hp.rms_rad / DEG, r_lp.rms_rad / DEG,
             r_hp.rms_rad / r_lp.rms_rad);
    TEST_ASSERT_TRUE_MESSAGE(r_hp.rms_rad <= STEADY_TONE_RATIO_MAX * r_lp.rms_rad, msg);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(1.0, r_hp.weight_at_stop, "engaged");
}

static void test_engaging_never_makes_the_error_larger_than_lp_mladrcs(void)
{
    /* from a second after the onset, over the gate's opening: LP gives up
     * at once what the fit takes over, so no step passes through its lead */
    /* a slow tone, which LP tracks closely: a step through its lead would show */
    ladrc_axis_config_t hp = config(LADRC_VARIANT_HP_MLADRC);
    ladrc_axis_config_t lp = config(LADRC_VARIANT_LP_MLADRC);
    hp.hp_freq_rad_s[0] = lp.hp_freq_rad_s[0] = (ladrc_real_t)SLOW_TONE_W_RAD_S;
    const dist_t d = {.amp = TONE_RAD_S2, .w = SLOW_TONE_W_RAD_S, .stop_s = 1e9, .step = 5.0};
    const result_t r_hp = fly(&hp, NULL, &d, ONSET_S + 1.0, WINDOW_TO_S);
    const result_t r_lp = fly(&lp, NULL, &d, ONSET_S + 1.0, WINDOW_TO_S);
    char msg[96];
    snprintf(msg, sizeof msg, "max error HP %.4f deg, LP %.4f deg", r_hp.max_error_rad / DEG, r_lp.max_error_rad / DEG);
    TEST_ASSERT_TRUE_MESSAGE(r_hp.max_error_rad <= r_lp.max_error_rad, msg);
}

static void test_the_gate_lets_go_when_the_tone_stops(void)
{
    const ladrc_axis_config_t hp = config(LADRC_VARIANT_HP_MLADRC);
    const dist_t d = {.amp = TONE_RAD_S2, .w = TONE_W_RAD_S, .stop_s = 12.0, .step = 5.0};
    const result_t r = fly(&hp, NULL, &d, 12.0, 16.0);
    TEST_ASSERT_EQUAL_FLOAT_MESSAGE(1.0, r.weight_at_stop, "engaged before the stop");
    char msg[64];
    snprintf(msg, sizeof msg, "let go after %.3f s", r.let_go_s);
    TEST_ASSERT_TRUE_MESSAGE(r.let_go_s <= LET_GO_S, msg);
}

static void test_a_non_finite_rate_holds_the_estimates_and_is_flagged(void)
{
    ladrc_axis_config_t cfg = config(LADRC_VARIANT_HP_MLADRC);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    for (int k = 0; k < 100; ++k) {
        (void)axis_command_with_rate(&axis, 0.0f, 0.0f, (ladrc_real_t)(0.01 * k));
    }
    const ladrc_real_t before = ladrc_lp_get_estimate(ladrc_axis_get_lp(&axis));
    ladrc_real_t torque = 0.0f;
    const ladrc_real_t bad_rate = (ladrc_real_t)NAN;
    const ladrc_fault_t f = ladrc_axis_step(&axis, 0.0f, 0.0f, &bad_rate, &torque);
    TEST_ASSERT_TRUE((f & LADRC_FAULT_RATE) != 0u);
    TEST_ASSERT_TRUE(isfinite((double)torque));
    TEST_ASSERT_EQUAL_FLOAT(before, ladrc_lp_get_estimate(ladrc_axis_get_lp(&axis)));
    TEST_ASSERT_FALSE(ladrc_is_finite(ladrc_lp_get_sample(ladrc_axis_get_lp(&axis))));
}

static void test_init_refuses_an_unknown_sample(void)
{
    ladrc_axis_config_t cfg = config(LADRC_VARIANT_HP_MLADRC);
    cfg.hp_sample = (ladrc_hp_sample_t)2;
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_HP_SAMPLE, ladrc_axis_init(&axis, &cfg));
    /* the observer sample keeps no LP: no LP estimator to read */
    cfg.hp_sample = LADRC_HP_SAMPLE_OBSERVER;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    TEST_ASSERT_NULL(ladrc_axis_get_lp(&axis));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_without_a_tone_it_flies_as_lp_mladrc);
    RUN_TEST(test_on_a_steady_tone_it_cuts_lp_mladrcs_error_twentyfold);
    RUN_TEST(test_engaging_never_makes_the_error_larger_than_lp_mladrcs);
    RUN_TEST(test_the_gate_lets_go_when_the_tone_stops);
    RUN_TEST(test_a_non_finite_rate_holds_the_estimates_and_is_flagged);
    RUN_TEST(test_init_refuses_an_unknown_sample);
    return UNITY_END();
}
