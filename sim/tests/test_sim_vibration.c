/* SPDX-License-Identifier: BSD-3-Clause */
/* Simulator propeller vibration (plant/vibration.h): its lines sit at the
 * rotors' speeds and their orders, follow the speeds, and integrate into
 * the angle. */
#include "unity.h"
#include "plant/vibration.h"

#include <math.h>
#include <string.h>

void setUp(void)
{
}
void tearDown(void)
{
}

#define TWO_PI 6.283185307179586
#define N_SAMPLES 4096
#define DT_S 5e-4 /* 2 kHz: Nyquist 1 kHz */

static sim_vibration_config_t three_orders(void)
{
    sim_vibration_config_t c;
    memset(&c, 0, sizeof c);
    c.n_orders = 3;
    c.order[0] = 1.0;
    c.order[1] = 2.0;
    c.order[2] = 3.0;
    c.gyro_rad_s[0] = 0.03;
    c.gyro_rad_s[1] = 0.01;
    c.gyro_rad_s[2] = 0.005;
    c.axis_gain[0] = c.axis_gain[1] = 1.0;
    c.axis_gain[2] = 0.5;
    return c;
}

/* |DFT| of x at bin k, by direct summation. */
static double dft_magnitude(const double *x, int n, int k)
{
    double re = 0.0, im = 0.0;
    for (int i = 0; i < n; ++i) {
        re += x[i] * cos(TWO_PI * k * i / n);
        im -= x[i] * sin(TWO_PI * k * i / n);
    }
    return sqrt(re * re + im * im);
}

/* The bins of the local maxima of |DFT| above `floor`, up to max_peaks. */
static int spectral_peaks(const double *x, int n, double floor, int *bins, int max_peaks)
{
    static double mag[N_SAMPLES / 2];
    for (int k = 0; k < n / 2; ++k) {
        mag[k] = dft_magnitude(x, n, k);
    }
    int found = 0;
    for (int k = 1; k + 1 < n / 2 && found < max_peaks; ++k) {
        if (mag[k] > floor && mag[k] >= mag[k - 1] && mag[k] > mag[k + 1]) {
            bins[found++] = k;
        }
    }
    return found;
}

static void test_lines_sit_at_each_rotor_speed_and_its_orders_within_a_bin(void)
{
    sim_vibration_t v;
    const sim_vibration_config_t c = three_orders();
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&v, &c, 7u));
    /* rotors at 90, 130, 170, 210 Hz (orders up to 630 Hz, below Nyquist) */
    const double hz[4] = {90.0, 130.0, 170.0, 210.0};
    double w2[4];
    for (int i = 0; i < 4; ++i) {
        w2[i] = pow(TWO_PI * hz[i], 2);
    }
    static double roll[N_SAMPLES];
    for (int k = 0; k < N_SAMPLES; ++k) {
        double g[3] = {0.0, 0.0, 0.0};
        sim_vibration_tick(&v, w2, DT_S, g, NULL, NULL);
        roll[k] = g[0];
    }
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(fabs(hz[i] - sim_vibration_rotor_hz(&v, i)) <= 1e-9);
    }
    /* a line of amplitude a over N samples gives |DFT| near a N / 2 (less
     * off-bin, at worst by 2/pi without a window); the smallest, 0.005,
     * gives >= 6.5 at 4096 samples, and the leakage of the others stays
     * below 1.5 a few bins away: 3 separates lines from leakage */
    int bins[32];
    const int n = spectral_peaks(roll, N_SAMPLES, 3.0, bins, 32);
    const double bin_hz = 1.0 / (N_SAMPLES * DT_S);
    TEST_ASSERT_EQUAL_INT(12, n);
    for (int i = 0; i < 4; ++i) {
        for (int k = 1; k <= 3; ++k) {
            const double f = hz[i] * k;
            int near = 0;
            for (int j = 0; j < n; ++j) {
                near |= fabs(bins[j] * bin_hz - f) <= bin_hz;
            }
            TEST_ASSERT_TRUE_MESSAGE(near, "a rotor line is not within one bin of rotor rate x order");
        }
    }
}

static void test_lines_follow_the_rotor_speed(void)
{
    sim_vibration_t v;
    sim_vibration_config_t c = three_orders();
    c.n_orders = 1;
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&v, &c, 3u));
    /* 100 Hz for a while, then 150 Hz: the second window's line moves */
    double w2[4];
    for (int i = 0; i < 4; ++i) {
        w2[i] = pow(TWO_PI * 100.0, 2);
    }
    static double pitch[N_SAMPLES];
    for (int k = 0; k < N_SAMPLES; ++k) {
        double g[3] = {0.0, 0.0, 0.0};
        sim_vibration_tick(&v, w2, DT_S, g, NULL, NULL);
    }
    for (int i = 0; i < 4; ++i) {
        w2[i] = pow(TWO_PI * 150.0, 2);
    }
    for (int k = 0; k < N_SAMPLES; ++k) {
        double g[3] = {0.0, 0.0, 0.0};
        sim_vibration_tick(&v, w2, DT_S, g, NULL, NULL);
        pitch[k] = g[1];
    }
    int bins[8];
    const int n = spectral_peaks(pitch, N_SAMPLES, 3.0, bins, 8);
    const double bin_hz = 1.0 / (N_SAMPLES * DT_S);
    TEST_ASSERT_EQUAL_INT(1, n);
    TEST_ASSERT_TRUE(fabs(bins[0] * bin_hz - 150.0) <= bin_hz);
}

static void test_the_angle_carries_the_integral_of_the_gyro_line(void)
{
    sim_vibration_t v;
    sim_vibration_config_t c = three_orders();
    c.n_orders = 1;
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&v, &c, 11u));
    const double w = TWO_PI * 120.0;
    double w2[4] = {w * w, w * w, w * w, w * w};
    double integral[3] = {0.0, 0.0, 0.0}, last_g[3] = {0.0, 0.0, 0.0}, max_gap = 0.0, max_angle = 0.0;
    const double dt = 1e-5; /* fine steps: the trapezoid sum is the integral to 1e-6 of it */
    for (int k = 0; k < 20000; ++k) {
        double g[3] = {0.0, 0.0, 0.0}, a[3] = {0.0, 0.0, 0.0};
        sim_vibration_tick(&v, w2, dt, g, a, NULL);
        if (k == 0) {
            for (int i = 0; i < 3; ++i) {
                integral[i] = a[i]; /* the integration constant */
            }
        } else {
            for (int i = 0; i < 3; ++i) {
                integral[i] += 0.5 * (g[i] + last_g[i]) * dt;
            }
        }
        for (int i = 0; i < 3; ++i) {
            last_g[i] = g[i];
            max_gap = fmax(max_gap, fabs(integral[i] - a[i]));
            max_angle = fmax(max_angle, fabs(a[i]));
        }
    }
    /* four rotors of 0.03 rad/s at 754 rad/s: up to 1.6e-4 rad; the
     * trapezoid's error (w dt)^2 / 12 relative, 5e-7, over 0.2 s */
    TEST_ASSERT_TRUE(max_angle > 3e-5);
    TEST_ASSERT_TRUE(max_gap < 1e-3 * max_angle);
}

static void test_same_seed_same_vibration_and_bad_configs_refused(void)
{
    sim_vibration_t a, b;
    sim_vibration_config_t c = three_orders();
    c.accel_m_s2[0] = 2.0;
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&a, &c, 5u));
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&b, &c, 5u));
    const double w2[4] = {1e6, 1.1e6, 1.2e6, -1.3e6};
    for (int k = 0; k < 100; ++k) {
        double ga[3] = {0}, gb[3] = {0}, xa[3] = {0}, xb[3] = {0};
        sim_vibration_tick(&a, w2, DT_S, ga, NULL, xa);
        sim_vibration_tick(&b, w2, DT_S, gb, NULL, xb);
        TEST_ASSERT_TRUE(memcmp(ga, gb, sizeof ga) == 0 && memcmp(xa, xb, sizeof xa) == 0);
        TEST_ASSERT_TRUE(xa[0] != 0.0);
    }
    sim_vibration_t untouched;
    memset(&untouched, 0x5a, sizeof untouched);
    sim_vibration_config_t bad = c;
    bad.n_orders = SIM_VIB_MAX_ORDERS + 1;
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(&untouched, &bad, 1u));
    bad = c;
    bad.order[1] = 0.0;
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(&untouched, &bad, 1u));
    bad = c;
    bad.gyro_rad_s[2] = NAN;
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(&untouched, &bad, 1u));
    bad = c;
    bad.axis_gain[2] = -1.0;
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(&untouched, &bad, 1u));
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(NULL, &c, 1u));
    TEST_ASSERT_EQUAL_INT(-1, sim_vibration_init(&untouched, NULL, 1u));
    /* no orders: nothing added, the rotor speeds still reported */
    bad = c;
    bad.n_orders = 0;
    TEST_ASSERT_EQUAL_INT(0, sim_vibration_init(&a, &bad, 1u));
    double g[3] = {0.0, 0.0, 0.0};
    sim_vibration_tick(&a, w2, DT_S, g, g, g);
    TEST_ASSERT_TRUE(g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0);
    TEST_ASSERT_TRUE(fabs(sqrt(1.3e6) / TWO_PI - sim_vibration_rotor_hz(&a, 3)) <= 1e-9);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_lines_sit_at_each_rotor_speed_and_its_orders_within_a_bin);
    RUN_TEST(test_lines_follow_the_rotor_speed);
    RUN_TEST(test_the_angle_carries_the_integral_of_the_gyro_line);
    RUN_TEST(test_same_seed_same_vibration_and_bad_configs_refused);
    return UNITY_END();
}
