/* SPDX-License-Identifier: BSD-3-Clause */
/* The modified LADRC in closed loop on a double-integrator test plant at
 * 1 kHz (wc = 15, wo = 75, J = 5.445e-3 kg m^2): the HP and LP estimators
 * against plain LADRC under the paper's periodic disturbance, with noise, and
 * over a sweep of frequencies and amplitudes with a second tone present. */
#include "unity.h"
#include "ladrc/axis.h"
#include "test_plant.h"

#include <math.h>
#include <stdio.h>

#define DT_S 1e-3
#define J_KG_M2 5.445e-3
#define PI 3.14159265358979
#define DEG (PI / 180.0)
/* The bar: HP's steady band at least 20 times narrower than LADRC's. */
#define HP_MIN_IMPROVEMENT 20.0
/* LP tracks the disturbance with a 75 rad/s first-order lag: at 3 rad/s a 4%
 * residual, so about 25x narrower than LADRC; 10x is the bar. */
#define LP_MIN_IMPROVEMENT 10.0
/* "Never worse than LADRC": two different runs, so allow float-level
 * differences (measured: equal to 1e-5 where the gate stays shut). */
#define NEVER_WORSE_REL_TOL 0.01
/* Angle noise of the paper's noisy case: variance 0.001 deg^2. */
#define NOISE_STD_RAD (0.0316227766 * DEG)

void setUp(void) {}
void tearDown(void) {}

/* d = bias + amp sin(w t) + amp2 sin(w2 t), rad/s^2 */
typedef struct {
    double bias, amp, w, amp2, w2;
} tones_t;

static double tones(double t, const void *ctx)
{
    const tones_t *d = (const tones_t *)ctx;
    return d->bias + d->amp * sin(d->w * t) + d->amp2 * sin(d->w2 * t);
}

/* Deterministic Gaussian noise: xorshift32 + Box-Muller. */
static double gaussian(unsigned *state)
{
    double u[2];
    for (int i = 0; i < 2; ++i) {
        *state ^= *state << 13;
        *state ^= *state >> 17;
        *state ^= *state << 5;
        u[i] = ((*state >> 8) + 0.5) / 16777216.0;
    }
    return sqrt(-2.0 * log(u[0])) * cos(2.0 * PI * u[1]);
}

typedef struct {
    ladrc_variant_t variant;
    ladrc_hp_freq_mode_t freq_mode;
    tones_t d;
    double ref_amp_rad;  /* reference ref_amp cos(pi/2 t) */
    double noise_std_rad;
    double settle_s;     /* band measured after this ... */
    double window_s;     /* ... over this long */
} scenario_t;

/* Largest |y - ref| in the window; a huge value if the loop diverged. */
static double error_band_rad(const scenario_t *s)
{
    ladrc_axis_config_t cfg;
    ladrc_axis_config_default(&cfg, s->variant, (ladrc_real_t)DT_S, (ladrc_real_t)J_KG_M2);
    cfg.hp_freq_mode = s->freq_mode;
    cfg.hp_freq_rad_s = (ladrc_real_t)(s->freq_mode == LADRC_HP_FREQ_KNOWN ? s->d.w : 3.0);
    ladrc_axis_t axis;
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_axis_init(&axis, &cfg));
    test_double_integrator_t plant;
    test_plant_init(&plant, 1.0 / J_KG_M2, tones, &s->d);
    unsigned seed = 2463534242u;
    double band = 0.0;
    const int n = (int)((s->settle_s + s->window_s) / DT_S);
    for (int k = 0; k < n; ++k) {
        const double t = k * DT_S;
        const double ref = s->ref_amp_rad * cos(0.5 * PI * t);
        const double noise = s->noise_std_rad > 0.0 ? s->noise_std_rad * gaussian(&seed) : 0.0;
        const double u = ladrc_axis_step_with_rate(&axis, (ladrc_real_t)ref,
                                                   (ladrc_real_t)(plant.y_rad + noise),
                                                   (ladrc_real_t)plant.rate_rad_s);
        test_plant_step(&plant, u, DT_S, 1);
        if (!isfinite(plant.y_rad) || fabs(plant.y_rad) > 10.0) {
            return HUGE_VAL;
        }
        if (t >= s->settle_s) {
            band = fmax(band, fabs(plant.y_rad - ref));
        }
    }
    return band;
}

static void report(const char *what, double ladrc, double other)
{
    char msg[128];
    snprintf(msg, sizeof msg, "%s: band %.4f deg vs LADRC %.4f deg (%.0fx narrower)", what,
             other / DEG, ladrc / DEG, ladrc / other);
    TEST_MESSAGE(msg);
}

/* The paper's 12-25 s disturbance, d = 20 + 120 sin(3 t), on a still reference. */
static scenario_t paper_case(ladrc_variant_t variant, ladrc_hp_freq_mode_t mode, double noise)
{
    const scenario_t s = {variant, mode, {20.0, 120.0, 3.0, 0.0, 0.0}, 0.0, noise, 10.0, 5.0};
    return s;
}

static void check_improvement(const char *what, ladrc_variant_t variant, ladrc_hp_freq_mode_t mode,
                              double noise, double min_improvement)
{
    const scenario_t base = paper_case(LADRC_VARIANT_LADRC, mode, noise);
    const scenario_t mod = paper_case(variant, mode, noise);
    const double b_ladrc = error_band_rad(&base);
    const double b_mod = error_band_rad(&mod);
    report(what, b_ladrc, b_mod);
    TEST_ASSERT_LESS_THAN_FLOAT((float)(b_ladrc / min_improvement), (float)b_mod);
}

static void test_hp_band_is_20x_narrower_than_ladrc_with_known_frequency(void)
{
    check_improvement("HP known", LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_KNOWN, 0.0,
                      HP_MIN_IMPROVEMENT);
}

static void test_hp_band_is_20x_narrower_than_ladrc_with_online_frequency(void)
{
    check_improvement("HP online", LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE, 0.0,
                      HP_MIN_IMPROVEMENT);
}

static void test_hp_stays_bounded_and_20x_narrower_with_angle_noise(void)
{
    check_improvement("HP known, noisy", LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_KNOWN,
                      NOISE_STD_RAD, HP_MIN_IMPROVEMENT);
    check_improvement("HP online, noisy", LADRC_VARIANT_HP_MLADRC, LADRC_HP_FREQ_ONLINE,
                      NOISE_STD_RAD, HP_MIN_IMPROVEMENT);
}

static void test_lp_band_is_10x_narrower_than_ladrc(void)
{
    check_improvement("LP", LADRC_VARIANT_LP_MLADRC, LADRC_HP_FREQ_KNOWN, 0.0, LP_MIN_IMPROVEMENT);
}

static void test_hp_online_never_does_worse_than_ladrc_over_a_sweep(void)
{
    /* given a second tone: what a 15 deg reference at pi/2 rad/s induces through
     * the paper's rotor drag (kt/Jx * 15 deg * pi/2 = 7 rad/s^2), and that
     * reference moving; disturbance amplitudes 30 (4x the second tone) and 120 */
    const double freqs[] = {0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 20.0};
    const double amps[] = {30.0, 120.0};
    for (unsigned i = 0; i < sizeof freqs / sizeof freqs[0]; ++i) {
        for (unsigned j = 0; j < 2u; ++j) {
            const double period = 2.0 * PI / freqs[i];
            /* settle over 6 periods (20 s at least), measure over 2 (5 s at least) */
            scenario_t s = {LADRC_VARIANT_LADRC, LADRC_HP_FREQ_ONLINE,
                            {20.0, amps[j], freqs[i], 7.0, 0.5 * PI},
                            15.0 * DEG, 0.0, fmax(20.0, 6.0 * period), fmax(5.0, 2.0 * period)};
            const double b_ladrc = error_band_rad(&s);
            s.variant = LADRC_VARIANT_HP_MLADRC;
            const double b_hp = error_band_rad(&s);
            char msg[128];
            snprintf(msg, sizeof msg, "w %.1f rad/s, A %.0f: HP online %.4f deg, LADRC %.4f deg",
                     freqs[i], amps[j], b_hp / DEG, b_ladrc / DEG);
            TEST_MESSAGE(msg);
            TEST_ASSERT_TRUE_MESSAGE(isfinite(b_hp) && b_hp < 1.0, msg);
            TEST_ASSERT_LESS_OR_EQUAL_FLOAT_MESSAGE((float)(b_ladrc * (1.0 + NEVER_WORSE_REL_TOL)),
                                                    (float)b_hp, msg);
        }
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hp_band_is_20x_narrower_than_ladrc_with_known_frequency);
    RUN_TEST(test_hp_band_is_20x_narrower_than_ladrc_with_online_frequency);
    RUN_TEST(test_hp_stays_bounded_and_20x_narrower_with_angle_noise);
    RUN_TEST(test_lp_band_is_10x_narrower_than_ladrc);
    RUN_TEST(test_hp_online_never_does_worse_than_ladrc_over_a_sweep);
    return UNITY_END();
}
