/* SPDX-License-Identifier: BSD-3-Clause */
/* Mixer: allocation against the forward model, hover and tilt thrust on the
 * paper's vehicle, saturation priorities, flags, ideal mode and faults. */
#include "unity.h"
#include "ladrc/mixer.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

/* Paper vehicle (Table 1). */
#define KL_N_S2 2.98e-5
#define ARM_M 0.165
#define B_NM_S2 2e-6
#define MASS_KG 0.8
#define G_M_S2 9.81
/* Rotor limits of the tests: idle at 100 rad/s, top at 447 rad/s (thrust to
 * weight 3); hover sits at 65839 rad^2/s^2. */
#define W2_MIN 1e4
#define W2_MAX 2e5
#define TILT_MAX_RAD 0.7853981633974483 /* 45 deg */

/* Round trip allocation -> forward model, requests up to 30 N and 1.2 N m:
 * w^2 up to 4e5 with a float ulp of 0.03, a few roundings per rotor. Measured
 * (float, 5000 requests) 2.4e-6 N, 2.4e-7 N m roll/pitch, 1.1e-7 N m yaw;
 * 1e-5 N (+ 1e-6 of the thrust) and 1e-6 N m leave a margin of 4x or more. */
#define THRUST_REL_TOL 1e-6
#define THRUST_ABS_TOL_N 1e-5
#define TORQUE_TOL_NM 1e-6
/* w^2 near hover (65839): a handful of float roundings of 2^-24 relative,
 * 0.004 each; measured 0.004. */
#define W2_TOL 0.05
/* Expected values of the priority scenarios, computed in double from the
 * allocation; the mixer works in float on w^2 up to 2.6e5 (ulp 0.016-0.03),
 * measured errors below 2e-7 N m and 4e-6 N. */
#define SCENARIO_TORQUE_TOL_NM 2e-6
#define SCENARIO_THRUST_TOL_N 2e-5
/* Thrust from tilt: cos and a division in float, 3 roundings on ~11 N. */
#define TILT_THRUST_TOL_N 1e-5
/* w^2 limits: the final clamp makes them exact, so no tolerance at all. */
/* "Fits" margin of the random priority checks: requests within 0.1 % of a
 * limit are left out, since float rounding may decide them either way. */
#define FIT_MARGIN 1e-3
/* Ratio of scaled roll and pitch: cross product relative to |tau|^2. Measured
 * 4e-8; float rounding of w^2 on a 1e5 scale gives ~1e-7. */
#define RATIO_REL_TOL 1e-5

/* The report promise (mixer.h): an axis reports its request while the rotors give
 * it within 8 eps coef sum|w^2| (+ 16 subnormals), the forward model otherwise.
 * Against the forward model in double add the float forward model's own rounding
 * (two sums and a product on sum|w^2|): 2 eps coef sum|w^2|. */
#define REPORT_TOL_EPS 8.0
#define FORWARD_ROUNDING_EPS 2.0
#define REPORT_TOL_SUBNORMALS 32.0

#define N_RANDOM 5000

static ladrc_mixer_config_t config(ladrc_mixer_mode_t mode)
{
    ladrc_mixer_config_t cfg;
    cfg.kL_N_s2 = (ladrc_real_t)KL_N_S2;
    cfg.arm_m = (ladrc_real_t)ARM_M;
    cfg.b_Nm_s2 = (ladrc_real_t)B_NM_S2;
    cfg.mass_kg = (ladrc_real_t)MASS_KG;
    cfg.g_m_s2 = (ladrc_real_t)G_M_S2;
    cfg.w2_min_rad2_s2 = (ladrc_real_t)W2_MIN;
    cfg.w2_max_rad2_s2 = (ladrc_real_t)W2_MAX;
    cfg.tilt_max_rad = (ladrc_real_t)TILT_MAX_RAD;
    cfg.mode = mode;
    return cfg;
}

static void init_mixer(ladrc_mixer_t *mx, ladrc_mixer_mode_t mode)
{
    const ladrc_mixer_config_t cfg = config(mode);
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_init(mx, &cfg));
}

void setUp(void)
{
}
void tearDown(void)
{
}

/* ------------------------------------------------------------ references */

/* Forward model in double from the mixer's w^2. */
static void forward_double(const ladrc_real_t w2[4], double *thrust_N, double torque_Nm[3])
{
    const double w[4] = {w2[0], w2[1], w2[2], w2[3]};
    *thrust_N = KL_N_S2 * (w[0] + w[1] + w[2] + w[3]);
    torque_Nm[0] = ARM_M * KL_N_S2 * (w[1] - w[3]);
    torque_Nm[1] = ARM_M * KL_N_S2 * (w[2] - w[0]);
    torque_Nm[2] = B_NM_S2 * (-w[0] + w[1] - w[2] + w[3]);
}

/* Allocation (eq. 33) in double, split into its parts. */
typedef struct {
    double collective; /* a/4 */
    double rp[4];      /* roll/pitch part per rotor */
    double yaw[4];     /* yaw part per rotor */
} split_t;

static split_t split_double(double thrust_N, const ladrc_real_t torque_Nm[3])
{
    const double p2 = torque_Nm[0] / (2.0 * ARM_M * KL_N_S2);
    const double q2 = torque_Nm[1] / (2.0 * ARM_M * KL_N_S2);
    const double r4 = torque_Nm[2] / (4.0 * B_NM_S2);
    split_t s;
    s.collective = thrust_N / (4.0 * KL_N_S2);
    s.rp[0] = -q2;
    s.rp[1] = p2;
    s.rp[2] = q2;
    s.rp[3] = -p2;
    s.yaw[0] = -r4;
    s.yaw[1] = r4;
    s.yaw[2] = -r4;
    s.yaw[3] = r4;
    return s;
}

/* Tolerance of the report on an axis with coefficient coef (kL, l kL or b) for
 * rotors w2, against the double forward model. */
static double report_tol(const ladrc_real_t w2[4], double coef)
{
    const double sum = fabs((double)w2[0]) + fabs((double)w2[1]) + fabs((double)w2[2]) + fabs((double)w2[3]);
    return (REPORT_TOL_EPS + FORWARD_ROUNDING_EPS) * LADRC_REAL_EPS * coef * sum +
           REPORT_TOL_SUBNORMALS * LADRC_REAL_MIN * LADRC_REAL_EPS;
}

/* |actual - expected| <= tol, compared in double: the Unity float asserts round to
 * float, coarser than the report tolerance of the double build. */
#define ASSERT_REPORT_WITHIN(tol, expected, actual) assert_report_within((tol), (expected), (double)(actual), __LINE__)

static void assert_report_within(double tol, double expected, double actual, int line)
{
    if (!(fabs(actual - expected) <= tol)) {
        char msg[160];
        snprintf(msg, sizeof msg, "Expected %.17g Was %.17g (tolerance %.3g), line %d", expected, actual, tol, line);
        TEST_FAIL_MESSAGE(msg);
    }
}

static double spread4(const double v[4])
{
    double lo = v[0];
    double hi = v[0];
    int i;
    for (i = 1; i < 4; ++i) {
        lo = fmin(lo, v[i]);
        hi = fmax(hi, v[i]);
    }
    return hi - lo;
}

/* Seeded xorshift32: the same requests on every platform. */
static uint32_t rng_state;

static double uniform(double lo, double hi)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 17;
    rng_state ^= rng_state << 5;
    return lo + (hi - lo) * ((double)rng_state / 4294967296.0);
}

typedef struct {
    ladrc_real_t thrust_N;
    ladrc_real_t torque_Nm[3];
} request_t;

/* Half the draws are flight-like (most fit), half wide: thrust from below 0
 * to beyond the 23.8 N the rotors give, torques up to twice what roll/pitch
 * alone can fit (0.93 N m) and yaw up to 1.9x the 0.19 N m that fits alone. */
static request_t random_request(void)
{
    const double scale = (uniform(0.0, 1.0) < 0.5) ? 0.2 : 1.0;
    request_t r;
    r.thrust_N = (ladrc_real_t)((scale < 1.0) ? uniform(4.0, 16.0) : uniform(-2.0, 30.0));
    r.torque_Nm[0] = (ladrc_real_t)uniform(-scale, scale);
    r.torque_Nm[1] = (ladrc_real_t)uniform(-scale, scale);
    r.torque_Nm[2] = (ladrc_real_t)uniform(-0.5 * scale, 0.5 * scale);
    return r;
}

static int same_bits(ladrc_real_t a, ladrc_real_t b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* Field by field: struct padding may differ between copies. */
static void assert_same_output(const ladrc_mixer_output_t *expected, const ladrc_mixer_output_t *actual)
{
    TEST_ASSERT_EQUAL_MEMORY(expected->w2_rad2_s2, actual->w2_rad2_s2, sizeof actual->w2_rad2_s2);
    TEST_ASSERT_EQUAL_MEMORY(expected->w_rad_s, actual->w_rad_s, sizeof actual->w_rad_s);
    TEST_ASSERT_EQUAL_MEMORY(&expected->thrust_N, &actual->thrust_N, sizeof actual->thrust_N);
    TEST_ASSERT_EQUAL_MEMORY(expected->torque_Nm, actual->torque_Nm, sizeof actual->torque_Nm);
    TEST_ASSERT_EQUAL_HEX8(expected->saturated, actual->saturated);
    TEST_ASSERT_EQUAL_HEX8(expected->faults, actual->faults);
}

/* ------------------------------------------------------------ allocation */

static void test_mixer_allocation_followed_by_the_forward_model_gives_back_the_request(void)
{
    /* given */
    ladrc_mixer_t mx;
    double worst[4] = {0.0, 0.0, 0.0, 0.0};
    char msg[160];
    int n;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    rng_state = 12345u;
    for (n = 0; n < N_RANDOM; ++n) {
        const request_t r = random_request();
        ladrc_real_t w2[4];
        double thrust_N;
        double torque_Nm[3];
        int i;
        /* when */
        ladrc_mixer_allocate(&mx, r.thrust_N, r.torque_Nm, w2);
        forward_double(w2, &thrust_N, torque_Nm);
        /* then */
        TEST_ASSERT_FLOAT_WITHIN(THRUST_ABS_TOL_N + THRUST_REL_TOL * fabs(r.thrust_N), r.thrust_N, thrust_N);
        worst[0] = fmax(worst[0], fabs(thrust_N - r.thrust_N));
        for (i = 0; i < 3; ++i) {
            TEST_ASSERT_FLOAT_WITHIN(TORQUE_TOL_NM, r.torque_Nm[i], torque_Nm[i]);
            worst[i + 1] = fmax(worst[i + 1], fabs(torque_Nm[i] - r.torque_Nm[i]));
        }
    }
    snprintf(msg, sizeof msg, "round trip worst: thrust %.2e N, roll %.2e, pitch %.2e, yaw %.2e N m", worst[0],
             worst[1], worst[2], worst[3]);
    TEST_MESSAGE(msg);
}

static void test_mixer_forward_model_matches_the_paper_equations(void)
{
    /* given: distinct rotor speeds */
    ladrc_mixer_t mx;
    const ladrc_real_t w2[4] = {LADRC_R(50000.0), LADRC_R(60000.0), LADRC_R(70000.0), LADRC_R(90000.0)};
    ladrc_real_t thrust_N;
    ladrc_real_t torque_Nm[3];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    ladrc_mixer_forward(&mx, w2, &thrust_N, torque_Nm);
    /* then: U_L = kL sum, tau_x = l kL (w2 - w4), tau_y = l kL (w3 - w1), tau_z = b (-w1 + w2 - w3 + w4) */
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_THRUST_TOL_N, KL_N_S2 * 270000.0, thrust_N);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, ARM_M * KL_N_S2 * -30000.0, torque_Nm[0]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, ARM_M * KL_N_S2 * 20000.0, torque_Nm[1]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, B_NM_S2 * 30000.0, torque_Nm[2]);
}

static void test_mixer_hover_of_the_paper_vehicle_gives_m_g_over_4_kL_on_every_rotor(void)
{
    /* given: the paper's vehicle, both modes */
    const ladrc_mixer_mode_t modes[2] = {LADRC_MIXER_SATURATE, LADRC_MIXER_IDEAL};
    const ladrc_real_t no_torque[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const double hover = MASS_KG * G_M_S2 / (4.0 * KL_N_S2);
    int m;
    for (m = 0; m < 2; ++m) {
        ladrc_mixer_t mx;
        ladrc_mixer_output_t out;
        int i;
        init_mixer(&mx, modes[m]);
        /* when */
        const ladrc_fault_t faults = ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), no_torque, &out);
        /* then: 65839 rad^2/s^2 (256.6 rad/s) each, nothing saturated */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, faults);
        TEST_ASSERT_EQUAL_HEX8(0u, out.saturated);
        for (i = 0; i < 4; ++i) {
            TEST_ASSERT_FLOAT_WITHIN(W2_TOL, hover, out.w2_rad2_s2[i]);
            TEST_ASSERT_FLOAT_WITHIN(W2_TOL / 256.0, sqrt(hover), out.w_rad_s[i]);
        }
    }
}

static void test_mixer_holds_hover_after_init(void)
{
    /* given / when: a fresh mixer */
    ladrc_mixer_t mx;
    const double hover = MASS_KG * G_M_S2 / (4.0 * KL_N_S2);
    int i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* then: its held output is hover, no torque, no flags */
    for (i = 0; i < 4; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(W2_TOL, hover, mx.out.w2_rad2_s2[i]);
    }
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_THRUST_TOL_N, MASS_KG * G_M_S2, mx.out.thrust_N);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, 0.0, mx.out.torque_Nm[0]);
    TEST_ASSERT_EQUAL_HEX8(0u, mx.out.saturated);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_mixer_get_faults(&mx));
}

/* ------------------------------------------------------- thrust from tilt */

static void test_mixer_thrust_from_tilt_is_m_g_over_cos_roll_cos_pitch(void)
{
    /* given */
    const double angles[][2] = {{0.0, 0.0}, {0.3, 0.0}, {0.0, -0.4}, {-0.35, 0.5}, {0.6, 0.2}};
    ladrc_mixer_t mx;
    size_t i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    for (i = 0; i < sizeof angles / sizeof angles[0]; ++i) {
        /* when: tilts within the 45 deg limit (cos product >= 0.707) */
        const ladrc_real_t t =
            ladrc_mixer_thrust_from_tilt(&mx, (ladrc_real_t)angles[i][0], (ladrc_real_t)angles[i][1]);
        /* then */
        TEST_ASSERT_FLOAT_WITHIN(TILT_THRUST_TOL_N, MASS_KG * G_M_S2 / (cos(angles[i][0]) * cos(angles[i][1])), t);
    }
}

static void test_mixer_thrust_from_tilt_is_capped_at_the_tilt_limit(void)
{
    /* given: tilts beyond 45 deg, up to upside down */
    const double angles[][2] = {{0.8, 0.0}, {0.6, 0.6}, {1.5707963, 0.0}, {3.0, 0.0}, {0.0, -2.0}};
    const double capped = MASS_KG * G_M_S2 / cos(TILT_MAX_RAD);
    ladrc_mixer_t mx;
    size_t i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    for (i = 0; i < sizeof angles / sizeof angles[0]; ++i) {
        /* when */
        const ladrc_real_t t =
            ladrc_mixer_thrust_from_tilt(&mx, (ladrc_real_t)angles[i][0], (ladrc_real_t)angles[i][1]);
        /* then: m g / cos(45 deg) = 11.10 N, never more */
        TEST_ASSERT_FLOAT_WITHIN(TILT_THRUST_TOL_N, capped, t);
    }
}

static void test_mixer_thrust_from_tilt_of_an_unknown_attitude_is_the_weight(void)
{
    /* given */
    ladrc_mixer_t mx;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when / then */
    TEST_ASSERT_FLOAT_WITHIN(TILT_THRUST_TOL_N, MASS_KG * G_M_S2,
                             ladrc_mixer_thrust_from_tilt(&mx, (ladrc_real_t)NAN, LADRC_R(0.1)));
    TEST_ASSERT_FLOAT_WITHIN(TILT_THRUST_TOL_N, MASS_KG * G_M_S2,
                             ladrc_mixer_thrust_from_tilt(&mx, LADRC_R(0.1), (ladrc_real_t)INFINITY));
}

/* ---------------------------------------------------- saturation priority */

static void test_mixer_request_within_the_limits_is_passed_through_bit_for_bit(void)
{
    /* given: a request that fits, with torques whose round trip is not exact */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0123), LADRC_R(-0.0317), LADRC_R(0.00291)};
    const ladrc_real_t thrust_N = LADRC_R(8.137);
    ladrc_real_t w2[4];
    int i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    ladrc_mixer_allocate(&mx, thrust_N, torque_Nm, w2);
    /* when */
    (void)ladrc_mixer_step(&mx, thrust_N, torque_Nm, &out);
    /* then: rotors as allocated, achieved = request exactly, no flags */
    TEST_ASSERT_EQUAL_MEMORY(w2, out.w2_rad2_s2, sizeof w2);
    TEST_ASSERT_EQUAL_MEMORY(&thrust_N, &out.thrust_N, sizeof thrust_N);
    TEST_ASSERT_EQUAL_MEMORY(torque_Nm, out.torque_Nm, sizeof torque_Nm);
    TEST_ASSERT_EQUAL_HEX8(0u, out.saturated);
    for (i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(out.w2_rad2_s2[i] >= (ladrc_real_t)W2_MIN);
    }
}

static void test_mixer_thrust_beyond_the_top_moves_down_and_roll_stays_exact(void)
{
    /* given: 30 N (a/4 = 251678 > 2e5) with 0.1 N m roll (p/2 = 10169): fits once shifted */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.1), LADRC_R(0.0), LADRC_R(0.0)};
    const split_t s = split_double(30.0, torque_Nm);
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, LADRC_R(30.0), torque_Nm, &out);
    /* then: torques exact, rotor 2 at the top, thrust 4 kL (w2_max - p/2) = 22.63 N */
    TEST_ASSERT_EQUAL_MEMORY(torque_Nm, out.torque_Nm, sizeof torque_Nm);
    TEST_ASSERT_EQUAL_HEX8(LADRC_MIXER_SAT_THRUST, out.saturated);
    TEST_ASSERT_FLOAT_WITHIN(W2_TOL, W2_MAX, out.w2_rad2_s2[1]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_THRUST_TOL_N, 4.0 * KL_N_S2 * (W2_MAX - s.rp[1]), out.thrust_N);
}

static void test_mixer_thrust_below_the_bottom_moves_up_and_roll_stays_exact(void)
{
    /* given: 0.5 N (a/4 = 4195) with 0.1 N m roll: rotor 4 would go below idle */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.1), LADRC_R(0.0), LADRC_R(0.0)};
    const split_t s = split_double(0.5, torque_Nm);
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, LADRC_R(0.5), torque_Nm, &out);
    /* then: torques exact, rotor 4 at idle, thrust 4 kL (w2_min + p/2) = 2.40 N */
    TEST_ASSERT_EQUAL_MEMORY(torque_Nm, out.torque_Nm, sizeof torque_Nm);
    TEST_ASSERT_EQUAL_HEX8(LADRC_MIXER_SAT_THRUST, out.saturated);
    TEST_ASSERT_FLOAT_WITHIN(W2_TOL, W2_MIN, out.w2_rad2_s2[3]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_THRUST_TOL_N, 4.0 * KL_N_S2 * (W2_MIN + s.rp[1]), out.thrust_N);
}

static void test_mixer_gives_up_yaw_before_roll_and_pitch(void)
{
    /* given: hover, roll 0.5 N m (P = p/2 = 50845), yaw 1 N m (Y = r/4 = 125000):
     * spread P + 2Y = 300845 > range 190000 */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.5), LADRC_R(0.0), LADRC_R(1.0)};
    const split_t s = split_double(MASS_KG * G_M_S2, torque_Nm);
    const double range = W2_MAX - W2_MIN;
    const double yaw_kept = (range - s.rp[1]) / 2.0; /* largest Y with P + 2Y <= range */
    char msg[120];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), torque_Nm, &out);
    /* then: roll and pitch exact, yaw 4 b Y = 0.557 N m, same sign; the
     * collective moved to make room (lowest priority) */
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[0], &out.torque_Nm[0], sizeof torque_Nm[0]);
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[1], &out.torque_Nm[1], sizeof torque_Nm[1]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, 4.0 * B_NM_S2 * yaw_kept, out.torque_Nm[2]);
    TEST_ASSERT_EQUAL_HEX8(LADRC_MIXER_SAT_YAW | LADRC_MIXER_SAT_THRUST, out.saturated);
    snprintf(msg, sizeof msg, "yaw 1 N m asked, %.5f N m kept (expected %.5f); thrust %.3f N", (double)out.torque_Nm[2],
             4.0 * B_NM_S2 * yaw_kept, (double)out.thrust_N);
    TEST_MESSAGE(msg);
}

static void test_mixer_scales_too_much_roll_and_pitch_keeping_their_ratio(void)
{
    /* given: roll 1 N m, pitch 0.5 N m: 2 p/2 = 203380 > range 190000; a small yaw */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1.0), LADRC_R(0.5), LADRC_R(0.1)};
    const split_t s = split_double(MASS_KG * G_M_S2, torque_Nm);
    const double k = (W2_MAX - W2_MIN) / (2.0 * s.rp[1]);
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), torque_Nm, &out);
    /* then: both scaled by range / spread = 0.934, ratio 2 kept, rotors 2 and 4 at the limits */
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, k * 1.0, out.torque_Nm[0]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, k * 0.5, out.torque_Nm[1]);
    TEST_ASSERT_FLOAT_WITHIN(RATIO_REL_TOL, 2.0, (double)out.torque_Nm[0] / out.torque_Nm[1]);
    TEST_ASSERT_FLOAT_WITHIN(W2_TOL, W2_MAX, out.w2_rad2_s2[1]);
    TEST_ASSERT_FLOAT_WITHIN(W2_TOL, W2_MIN, out.w2_rad2_s2[3]);
    TEST_ASSERT_TRUE((out.saturated & (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH)) ==
                     (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH));
    /* the yaw (12500 per rotor) still fits beside them: rotors 2 and 4 move together */
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[2], &out.torque_Nm[2], sizeof torque_Nm[2]);
}

static void test_mixer_does_not_flag_an_axis_with_no_request_when_the_other_is_scaled(void)
{
    /* given: 1.2 N m roll alone (2 p/2 = 244057 > range), no pitch, no yaw */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1.2), LADRC_R(0.0), LADRC_R(0.0)};
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), torque_Nm, &out);
    /* then: roll cut to range / (2 p/2) of itself, pitch and yaw exactly 0 */
    TEST_ASSERT_TRUE((out.saturated & LADRC_MIXER_SAT_ROLL) != 0u);
    TEST_ASSERT_TRUE((out.saturated & (LADRC_MIXER_SAT_PITCH | LADRC_MIXER_SAT_YAW)) == 0u);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, (W2_MAX - W2_MIN) * ARM_M * KL_N_S2, out.torque_Nm[0]);
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[1], &out.torque_Nm[1], sizeof torque_Nm[1]);
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[2], &out.torque_Nm[2], sizeof torque_Nm[2]);
}

/* ------------------------------------------------- properties over requests */

static void test_mixer_keeps_every_rotor_within_the_limits_for_random_requests(void)
{
    /* given */
    ladrc_mixer_t mx;
    int n;
    int saturated = 0;
    char msg[100];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    rng_state = 2024u;
    for (n = 0; n < N_RANDOM; ++n) {
        const request_t r = random_request();
        ladrc_mixer_output_t out;
        int i;
        /* when */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_mixer_step(&mx, r.thrust_N, r.torque_Nm, &out));
        /* then */
        for (i = 0; i < 4; ++i) {
            TEST_ASSERT_TRUE(out.w2_rad2_s2[i] >= (ladrc_real_t)W2_MIN);
            TEST_ASSERT_TRUE(out.w2_rad2_s2[i] <= (ladrc_real_t)W2_MAX);
        }
        saturated += (out.saturated != 0u) ? 1 : 0;
    }
    snprintf(msg, sizeof msg, "%d of %d random requests saturated", saturated, N_RANDOM);
    TEST_MESSAGE(msg);
}

static void test_mixer_flags_an_axis_exactly_when_achieved_differs_from_requested(void)
{
    /* given */
    static const unsigned bits[3] = {LADRC_MIXER_SAT_ROLL, LADRC_MIXER_SAT_PITCH, LADRC_MIXER_SAT_YAW};
    ladrc_mixer_t mx;
    int n;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    rng_state = 777u;
    for (n = 0; n < N_RANDOM; ++n) {
        const request_t r = random_request();
        ladrc_mixer_output_t out;
        int i;
        /* when */
        (void)ladrc_mixer_step(&mx, r.thrust_N, r.torque_Nm, &out);
        /* then */
        TEST_ASSERT_EQUAL_INT(!same_bits(r.thrust_N, out.thrust_N), (out.saturated & LADRC_MIXER_SAT_THRUST) != 0u);
        for (i = 0; i < 3; ++i) {
            TEST_ASSERT_EQUAL_INT(!same_bits(r.torque_Nm[i], out.torque_Nm[i]), (out.saturated & bits[i]) != 0u);
        }
    }
}

static void test_mixer_achieved_values_are_the_forward_model_of_the_rotors(void)
{
    /* given */
    ladrc_mixer_t mx;
    int n;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    rng_state = 99u;
    for (n = 0; n < N_RANDOM; ++n) {
        const request_t r = random_request();
        ladrc_mixer_output_t out;
        double thrust_N;
        double torque_Nm[3];
        int i;
        /* when */
        (void)ladrc_mixer_step(&mx, r.thrust_N, r.torque_Nm, &out);
        forward_double(out.w2_rad2_s2, &thrust_N, torque_Nm);
        /* then: copied or computed, the report is what the rotors give */
        ASSERT_REPORT_WITHIN(report_tol(out.w2_rad2_s2, KL_N_S2), thrust_N, out.thrust_N);
        for (i = 0; i < 3; ++i) {
            ASSERT_REPORT_WITHIN(report_tol(out.w2_rad2_s2, (i < 2) ? ARM_M * KL_N_S2 : B_NM_S2), torque_Nm[i],
                                 out.torque_Nm[i]);
        }
    }
}

static void test_mixer_priorities_hold_for_random_requests(void)
{
    /* given */
    ladrc_mixer_t mx;
    const double range = W2_MAX - W2_MIN;
    int n;
    int counts[3] = {0, 0, 0};
    char msg[160];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    rng_state = 31337u;
    for (n = 0; n < N_RANDOM; ++n) {
        const request_t r = random_request();
        const split_t s = split_double(r.thrust_N, r.torque_Nm);
        double rp_yaw[4];
        ladrc_mixer_output_t out;
        int i;
        for (i = 0; i < 4; ++i) {
            rp_yaw[i] = s.rp[i] + s.yaw[i];
        }
        /* when */
        (void)ladrc_mixer_step(&mx, r.thrust_N, r.torque_Nm, &out);
        /* then: roll and pitch that fit are never touched ... */
        if (spread4(s.rp) < range * (1.0 - FIT_MARGIN)) {
            TEST_ASSERT_EQUAL_HEX8(0u, out.saturated & (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH));
            ++counts[0];
        } else if (spread4(s.rp) > range * (1.0 + FIT_MARGIN)) {
            /* ... too much is scaled in the requested direction ... */
            const double cross = (double)out.torque_Nm[0] * r.torque_Nm[1] - (double)out.torque_Nm[1] * r.torque_Nm[0];
            const double norm2 = (double)r.torque_Nm[0] * r.torque_Nm[0] + (double)r.torque_Nm[1] * r.torque_Nm[1];
            const double dot = (double)out.torque_Nm[0] * r.torque_Nm[0] + (double)out.torque_Nm[1] * r.torque_Nm[1];
            TEST_ASSERT_FLOAT_WITHIN(RATIO_REL_TOL, 0.0, cross / norm2);
            TEST_ASSERT_TRUE(dot > 0.0 && dot < norm2);
            ++counts[1];
        }
        /* ... and yaw that fits beside them is never touched either */
        if (spread4(rp_yaw) < range * (1.0 - FIT_MARGIN)) {
            TEST_ASSERT_EQUAL_HEX8(0u, out.saturated &
                                           (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH | LADRC_MIXER_SAT_YAW));
            ++counts[2];
        }
    }
    snprintf(msg, sizeof msg, "roll/pitch fit %d, roll/pitch scaled %d, all torques fit %d of %d", counts[0], counts[1],
             counts[2], N_RANDOM);
    TEST_MESSAGE(msg);
    /* the draw must exercise every branch */
    TEST_ASSERT_TRUE(counts[0] > 100 && counts[1] > 100 && counts[2] > 100);
}

/* ------------------------------------------- huge finite requests (defect A) */

/* Every reported value against the forward model of the rotors the step gave. */
static void assert_report_is_the_forward_model(const ladrc_mixer_output_t *out)
{
    double thrust_N;
    double torque_Nm[3];
    int i;
    forward_double(out->w2_rad2_s2, &thrust_N, torque_Nm);
    ASSERT_REPORT_WITHIN(report_tol(out->w2_rad2_s2, KL_N_S2), thrust_N, out->thrust_N);
    for (i = 0; i < 3; ++i) {
        ASSERT_REPORT_WITHIN(report_tol(out->w2_rad2_s2, (i < 2) ? ARM_M * KL_N_S2 : B_NM_S2), torque_Nm[i],
                             out->torque_Nm[i]);
    }
}

static void test_mixer_huge_roll_beside_a_huge_thrust_reports_what_the_rotors_give(void)
{
    /* given: roll 1e20 N m beside a thrust of 1e30 N. Split into w^2 parts, the
     * roll part (1e25) vanished in the collective (8e33): the rotors gave no
     * roll, yet 1e20 N m was reported achieved, unflagged. */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1e20), LADRC_R(0.0), LADRC_R(0.0)};
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    const ladrc_fault_t f = ladrc_mixer_step(&mx, LADRC_R(1e30), torque_Nm, &out);
    /* then: the report is what the rotors give, roll and thrust flagged; roll
     * keeps its priority over thrust: the most the rotors have, l kL (w2_max - w2_min) */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, f);
    assert_report_is_the_forward_model(&out);
    TEST_ASSERT_EQUAL_HEX8(LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_THRUST, out.saturated);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, ARM_M * KL_N_S2 * (W2_MAX - W2_MIN), out.torque_Nm[0]);
}

static void test_mixer_huge_yaw_does_not_take_the_place_of_roll_and_pitch(void)
{
    /* given: hover, roll 0.1 and pitch -0.1 N m (they fit), yaw 1e8 N m. The yaw
     * part of w^2 (1.25e13) swamped the roll/pitch parts: the rotors dropped
     * roll and pitch (priority inverted) and reported them achieved, unflagged. */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.1), LADRC_R(-0.1), LADRC_R(1e8)};
    double fwd_thrust_N;
    double fwd_torque_Nm[3];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), torque_Nm, &out);
    /* then: the rotors give roll and pitch as asked, yaw is what is left */
    forward_double(out.w2_rad2_s2, &fwd_thrust_N, fwd_torque_Nm);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, 0.1, fwd_torque_Nm[0]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, -0.1, fwd_torque_Nm[1]);
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[0], &out.torque_Nm[0], sizeof torque_Nm[0]);
    TEST_ASSERT_EQUAL_MEMORY(&torque_Nm[1], &out.torque_Nm[1], sizeof torque_Nm[1]);
    TEST_ASSERT_EQUAL_HEX8(0u, out.saturated & (LADRC_MIXER_SAT_ROLL | LADRC_MIXER_SAT_PITCH));
    TEST_ASSERT_TRUE((out.saturated & LADRC_MIXER_SAT_YAW) != 0u);
    TEST_ASSERT_TRUE(out.torque_Nm[2] > LADRC_R(0.0));
    assert_report_is_the_forward_model(&out);
}

static void test_mixer_huge_roll_reports_the_yaw_the_rotors_give(void)
{
    /* given: hover and a roll of 1e20 N m, no yaw. The collective and yaw were
     * recomputed from w^2 near 1e25, whose rounding left a yaw of -0.263 N m
     * on the rotors while 0 was reported. */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1e20), LADRC_R(0.0), LADRC_R(0.0)};
    double fwd_thrust_N;
    double fwd_torque_Nm[3];
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)(MASS_KG * G_M_S2), torque_Nm, &out);
    /* then: reported yaw = the rotors' yaw, and that is the 0 asked for */
    forward_double(out.w2_rad2_s2, &fwd_thrust_N, fwd_torque_Nm);
    ASSERT_REPORT_WITHIN(report_tol(out.w2_rad2_s2, B_NM_S2), fwd_torque_Nm[2], out.torque_Nm[2]);
    TEST_ASSERT_FLOAT_WITHIN(SCENARIO_TORQUE_TOL_NM, 0.0, fwd_torque_Nm[2]);
    TEST_ASSERT_EQUAL_HEX8(0u, out.saturated & (LADRC_MIXER_SAT_PITCH | LADRC_MIXER_SAT_YAW));
    assert_report_is_the_forward_model(&out);
}

/* ------------------------------------------------------------- ideal mode */

static void test_mixer_ideal_mode_lets_w2_go_negative_and_reports_the_request_exactly(void)
{
    /* given: the paper's ideal rotors; hover with 1 N m roll (p/2 = 101690 > a/4 = 65839) */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t thrust_N = (ladrc_real_t)(MASS_KG * G_M_S2);
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1.0), LADRC_R(-0.3), LADRC_R(0.2)};
    const split_t s = split_double(thrust_N, torque_Nm);
    double fwd_thrust_N;
    double fwd_torque_Nm[3];
    int i;
    init_mixer(&mx, LADRC_MIXER_IDEAL);
    /* when */
    (void)ladrc_mixer_step(&mx, thrust_N, torque_Nm, &out);
    /* then: rotor 4 negative (w = 0), nothing flagged, request reported bit for bit,
     * and the rotors really give the request */
    TEST_ASSERT_FLOAT_WITHIN(W2_TOL * 4.0, s.collective + s.rp[3] + s.yaw[3], out.w2_rad2_s2[3]);
    TEST_ASSERT_TRUE(out.w2_rad2_s2[3] < LADRC_R(0.0));
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.w_rad_s[3]);
    TEST_ASSERT_EQUAL_HEX8(0u, out.saturated);
    TEST_ASSERT_EQUAL_MEMORY(&thrust_N, &out.thrust_N, sizeof thrust_N);
    TEST_ASSERT_EQUAL_MEMORY(torque_Nm, out.torque_Nm, sizeof torque_Nm);
    forward_double(out.w2_rad2_s2, &fwd_thrust_N, fwd_torque_Nm);
    TEST_ASSERT_FLOAT_WITHIN(THRUST_ABS_TOL_N + THRUST_REL_TOL * fabs(thrust_N), thrust_N, fwd_thrust_N);
    for (i = 0; i < 3; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(TORQUE_TOL_NM, torque_Nm[i], fwd_torque_Nm[i]);
    }
}

static void test_mixer_ideal_mode_ignores_the_rotor_limits(void)
{
    /* given: ideal mode with limits that the request exceeds on both sides */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0), LADRC_R(2.0), LADRC_R(0.0)};
    ladrc_real_t w2[4];
    init_mixer(&mx, LADRC_MIXER_IDEAL);
    ladrc_mixer_allocate(&mx, LADRC_R(40.0), torque_Nm, w2);
    /* when */
    (void)ladrc_mixer_step(&mx, LADRC_R(40.0), torque_Nm, &out);
    /* then: the allocation itself */
    TEST_ASSERT_EQUAL_MEMORY(w2, out.w2_rad2_s2, sizeof w2);
    TEST_ASSERT_TRUE(out.w2_rad2_s2[2] > (ladrc_real_t)W2_MAX);
    TEST_ASSERT_EQUAL_HEX8(0u, out.saturated);
}

/* ----------------------------------------------------------------- faults */

static void test_mixer_non_finite_request_returns_the_previous_output_with_an_input_fault(void)
{
    /* given: a mixer that mixed one good request, and its twin */
    const ladrc_real_t good[3] = {LADRC_R(0.05), LADRC_R(-0.02), LADRC_R(0.01)};
    const ladrc_real_t bad_torques[3][3] = {{(ladrc_real_t)NAN, LADRC_R(0.0), LADRC_R(0.0)},
                                            {LADRC_R(0.0), (ladrc_real_t)INFINITY, LADRC_R(0.0)},
                                            {LADRC_R(0.0), LADRC_R(0.0), (ladrc_real_t)-INFINITY}};
    ladrc_mixer_t mx;
    ladrc_mixer_t twin;
    ladrc_mixer_output_t first;
    ladrc_mixer_output_t held;
    ladrc_mixer_output_t after;
    ladrc_mixer_output_t after_twin;
    int i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    init_mixer(&twin, LADRC_MIXER_SATURATE);
    (void)ladrc_mixer_step(&mx, LADRC_R(9.0), good, &first);
    for (i = 0; i < 4; ++i) {
        /* when: a NaN thrust, then each torque non-finite in turn */
        const ladrc_fault_t f = (i == 0) ? ladrc_mixer_step(&mx, (ladrc_real_t)NAN, good, &held)
                                         : ladrc_mixer_step(&mx, LADRC_R(9.0), bad_torques[i - 1], &held);
        /* then: input fault, the previous rotors and achieved values */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, f);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, held.faults);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_mixer_get_faults(&mx));
        TEST_ASSERT_EQUAL_MEMORY(first.w2_rad2_s2, held.w2_rad2_s2, sizeof first.w2_rad2_s2);
        TEST_ASSERT_EQUAL_MEMORY(first.torque_Nm, held.torque_Nm, sizeof first.torque_Nm);
    }
    /* and when the request is good again, it mixes as a mixer that never saw the faults */
    (void)ladrc_mixer_step(&mx, LADRC_R(7.0), good, &after);
    (void)ladrc_mixer_step(&twin, LADRC_R(7.0), good, &after_twin);
    assert_same_output(&after_twin, &after);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, after.faults);
}

static void test_mixer_non_finite_first_request_gives_hover(void)
{
    /* given: a fresh mixer */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const double hover = MASS_KG * G_M_S2 / (4.0 * KL_N_S2);
    int i;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when */
    const ladrc_fault_t f = ladrc_mixer_step(&mx, (ladrc_real_t)INFINITY, torque_Nm, &out);
    /* then: finite hover, input fault */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, f);
    for (i = 0; i < 4; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(W2_TOL, hover, out.w2_rad2_s2[i]);
        TEST_ASSERT_FLOAT_IS_DETERMINATE(out.w_rad_s[i]);
    }
}

static void test_mixer_mixes_a_finite_request_of_any_size_at_the_limits(void)
{
    /* given: thrusts whose allocation (a/4) or rotor sum overflows, both signs.
     * Before the request was limited these were refused with a state fault;
     * now every finite request is mixed: the thrust is what the rotors can give. */
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const ladrc_real_t huge[3] = {LADRC_REAL_MAX, LADRC_REAL_MAX * (ladrc_real_t)(2.0 * KL_N_S2), -LADRC_REAL_MAX};
    const double limit[3] = {W2_MAX, W2_MAX, W2_MIN};
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    int i;
    int j;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    for (i = 0; i < 3; ++i) {
        /* when */
        const ladrc_fault_t f = ladrc_mixer_step(&mx, huge[i], torque_Nm, &out);
        /* then: no fault, every rotor at the limit, thrust 4 kL w^2 flagged, no torque */
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, f);
        TEST_ASSERT_EQUAL_HEX8(LADRC_MIXER_SAT_THRUST, out.saturated);
        for (j = 0; j < 4; ++j) {
            TEST_ASSERT_FLOAT_WITHIN(W2_TOL, limit[i], out.w2_rad2_s2[j]);
        }
        TEST_ASSERT_FLOAT_WITHIN(SCENARIO_THRUST_TOL_N, 4.0 * KL_N_S2 * limit[i], out.thrust_N);
        TEST_ASSERT_EQUAL_MEMORY(torque_Nm, out.torque_Nm, sizeof torque_Nm);
    }
}

static void test_mixer_ideal_mode_refuses_non_finite_and_overflowing_requests(void)
{
    /* given an ideal mixer that mixed one good request: no limits, so only
     * finiteness stands between a request and the rotors */
    const ladrc_real_t good[3] = {LADRC_R(0.05), LADRC_R(-0.02), LADRC_R(0.01)};
    const ladrc_real_t nan_roll[3] = {(ladrc_real_t)NAN, LADRC_R(0.0), LADRC_R(0.0)};
    ladrc_mixer_t mx;
    ladrc_mixer_output_t first;
    ladrc_mixer_output_t held;
    init_mixer(&mx, LADRC_MIXER_IDEAL);
    (void)ladrc_mixer_step(&mx, LADRC_R(9.0), good, &first);
    /* when / then: a NaN torque is an input fault, a thrust whose a/4 = U_L/(4 kL)
     * overflows is a state fault; both hold the previous rotors */
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_INPUT, ladrc_mixer_step(&mx, LADRC_R(9.0), nan_roll, &held));
    TEST_ASSERT_EQUAL_MEMORY(first.w2_rad2_s2, held.w2_rad2_s2, sizeof first.w2_rad2_s2);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_step(&mx, LADRC_REAL_MAX, good, &held));
    TEST_ASSERT_EQUAL_MEMORY(first.w2_rad2_s2, held.w2_rad2_s2, sizeof first.w2_rad2_s2);
    TEST_ASSERT_EQUAL_MEMORY(first.torque_Nm, held.torque_Nm, sizeof first.torque_Nm);
}

/* ----------------------------------------------------------------- config */

static void test_mixer_init_rejects_every_invalid_field_with_its_own_status(void)
{
    typedef struct {
        size_t offset;
        double value;
        ladrc_status_t expected;
    } bad_field_t;
    const bad_field_t cases[] = {
        {.offset = offsetof(ladrc_mixer_config_t, kL_N_s2), .value = 0.0, .expected = LADRC_ERR_MIXER_KL_N_S2},
        {.offset = offsetof(ladrc_mixer_config_t, kL_N_s2), .value = -1e-5, .expected = LADRC_ERR_MIXER_KL_N_S2},
        {.offset = offsetof(ladrc_mixer_config_t, kL_N_s2), .value = (double)NAN, .expected = LADRC_ERR_MIXER_KL_N_S2},
        {.offset = offsetof(ladrc_mixer_config_t, kL_N_s2),
         .value = 1e-39,
         .expected = LADRC_ERR_MIXER_KL_N_S2}, /* denormal: 1/(4 kL) = Inf */
        {.offset = offsetof(ladrc_mixer_config_t, arm_m), .value = 0.0, .expected = LADRC_ERR_MIXER_ARM_M},
        {.offset = offsetof(ladrc_mixer_config_t, arm_m), .value = (double)INFINITY, .expected = LADRC_ERR_MIXER_ARM_M},
        {.offset = offsetof(ladrc_mixer_config_t, b_Nm_s2), .value = -2e-6, .expected = LADRC_ERR_MIXER_B_NM_S2},
        {.offset = offsetof(ladrc_mixer_config_t, b_Nm_s2), .value = (double)NAN, .expected = LADRC_ERR_MIXER_B_NM_S2},
        {.offset = offsetof(ladrc_mixer_config_t, b_Nm_s2),
         .value = 1e-40,
         .expected = LADRC_ERR_MIXER_B_NM_S2}, /* 1/(4 b) = Inf */
        {.offset = offsetof(ladrc_mixer_config_t, mass_kg), .value = 0.0, .expected = LADRC_ERR_MIXER_MASS_KG},
        {.offset = offsetof(ladrc_mixer_config_t, mass_kg),
         .value = (double)INFINITY,
         .expected = LADRC_ERR_MIXER_MASS_KG},
        {.offset = offsetof(ladrc_mixer_config_t, mass_kg),
         .value = 3.4e38,
         .expected = LADRC_ERR_MIXER_MASS_KG}, /* m g = Inf */
        {.offset = offsetof(ladrc_mixer_config_t, g_m_s2), .value = -9.81, .expected = LADRC_ERR_MIXER_G_M_S2},
        {.offset = offsetof(ladrc_mixer_config_t, g_m_s2), .value = (double)NAN, .expected = LADRC_ERR_MIXER_G_M_S2},
        {.offset = offsetof(ladrc_mixer_config_t, w2_min_rad2_s2), .value = -1.0, .expected = LADRC_ERR_MIXER_W2_MIN},
        {.offset = offsetof(ladrc_mixer_config_t, w2_min_rad2_s2),
         .value = (double)NAN,
         .expected = LADRC_ERR_MIXER_W2_MIN},
        {.offset = offsetof(ladrc_mixer_config_t, w2_min_rad2_s2),
         .value = (double)-INFINITY,
         .expected = LADRC_ERR_MIXER_W2_MIN},
        {.offset = offsetof(ladrc_mixer_config_t, w2_max_rad2_s2), .value = W2_MIN, .expected = LADRC_ERR_MIXER_W2_MAX},
        {.offset = offsetof(ladrc_mixer_config_t, w2_max_rad2_s2), .value = 5e3, .expected = LADRC_ERR_MIXER_W2_MAX},
        {.offset = offsetof(ladrc_mixer_config_t, w2_max_rad2_s2),
         .value = (double)INFINITY,
         .expected = LADRC_ERR_MIXER_W2_MAX},
        {.offset = offsetof(ladrc_mixer_config_t, w2_max_rad2_s2),
         .value = (double)NAN,
         .expected = LADRC_ERR_MIXER_W2_MAX},
        {.offset = offsetof(ladrc_mixer_config_t, tilt_max_rad),
         .value = 0.0,
         .expected = LADRC_ERR_MIXER_TILT_MAX_RAD},
        {.offset = offsetof(ladrc_mixer_config_t, tilt_max_rad),
         .value = -0.5,
         .expected = LADRC_ERR_MIXER_TILT_MAX_RAD},
        {.offset = offsetof(ladrc_mixer_config_t, tilt_max_rad),
         .value = 1.5707964,
         .expected = LADRC_ERR_MIXER_TILT_MAX_RAD},
        {.offset = offsetof(ladrc_mixer_config_t, tilt_max_rad),
         .value = 5.0,
         .expected = LADRC_ERR_MIXER_TILT_MAX_RAD},
        {.offset = offsetof(ladrc_mixer_config_t, tilt_max_rad),
         .value = (double)NAN,
         .expected = LADRC_ERR_MIXER_TILT_MAX_RAD},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        /* given: a valid config with one field made invalid */
        ladrc_mixer_config_t cfg = config(LADRC_MIXER_SATURATE);
        const ladrc_real_t value = (ladrc_real_t)cases[i].value;
        ladrc_mixer_t mx;
        char msg[64];
        memcpy((char *)&cfg + cases[i].offset, &value, sizeof value);
        snprintf(msg, sizeof msg, "case %u", (unsigned)i);
        /* when / then */
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].expected, ladrc_mixer_init(&mx, &cfg), msg);
    }
}

static ladrc_real_t step_toward(ladrc_real_t x, double direction)
{
#ifdef LADRC_REAL_DOUBLE
    return nextafter(x, direction);
#else
    return nextafterf(x, (float)direction);
#endif
}

static void test_mixer_init_accepts_each_field_at_its_bounds_and_rejects_just_beyond(void)
{
    typedef struct {
        size_t offset;
        ladrc_real_t lo, hi;
        ladrc_status_t status;
    } bound_t;
    const bound_t bounds[] = {
        {.offset = offsetof(ladrc_mixer_config_t, kL_N_s2),
         .lo = LADRC_MIXER_KL_MIN_N_S2,
         .hi = LADRC_MIXER_KL_MAX_N_S2,
         .status = LADRC_ERR_MIXER_KL_N_S2},
        {.offset = offsetof(ladrc_mixer_config_t, arm_m),
         .lo = LADRC_MIXER_ARM_MIN_M,
         .hi = LADRC_MIXER_ARM_MAX_M,
         .status = LADRC_ERR_MIXER_ARM_M},
        {.offset = offsetof(ladrc_mixer_config_t, b_Nm_s2),
         .lo = LADRC_MIXER_B_MIN_NM_S2,
         .hi = LADRC_MIXER_B_MAX_NM_S2,
         .status = LADRC_ERR_MIXER_B_NM_S2},
        {.offset = offsetof(ladrc_mixer_config_t, mass_kg),
         .lo = LADRC_MIXER_MASS_MIN_KG,
         .hi = LADRC_MIXER_MASS_MAX_KG,
         .status = LADRC_ERR_MIXER_MASS_KG},
        {.offset = offsetof(ladrc_mixer_config_t, g_m_s2),
         .lo = LADRC_MIXER_G_MIN_M_S2,
         .hi = LADRC_MIXER_G_MAX_M_S2,
         .status = LADRC_ERR_MIXER_G_M_S2},
        {.offset = offsetof(ladrc_mixer_config_t, w2_max_rad2_s2),
         .lo = LADRC_MIXER_W2_MAX_MIN_RAD2_S2,
         .hi = LADRC_MIXER_W2_MAX_MAX_RAD2_S2,
         .status = LADRC_ERR_MIXER_W2_MAX},
    };
    size_t i;
    for (i = 0; i < sizeof bounds / sizeof bounds[0]; ++i) {
        /* given: the paper's config with one field at, then just beyond, each bound
         * (w2_min 0 so that w2_max may go down to its bound) */
        const ladrc_real_t values[4] = {bounds[i].lo, bounds[i].hi, step_toward(bounds[i].lo, -INFINITY),
                                        step_toward(bounds[i].hi, INFINITY)};
        int k;
        for (k = 0; k < 4; ++k) {
            ladrc_mixer_config_t cfg = config(LADRC_MIXER_SATURATE);
            ladrc_mixer_t mx;
            char msg[64];
            cfg.w2_min_rad2_s2 = LADRC_R(0.0);
            memcpy((char *)&cfg + bounds[i].offset, &values[k], sizeof values[k]);
            snprintf(msg, sizeof msg, "field %u, value %.9g", (unsigned)i, (double)values[k]);
            /* when / then */
            TEST_ASSERT_EQUAL_INT_MESSAGE((k < 2) ? LADRC_OK : bounds[i].status, ladrc_mixer_init(&mx, &cfg), msg);
        }
    }
}

static void test_mixer_init_in_ideal_mode_does_not_bound_the_unused_rotor_limits(void)
{
    /* given: ideal rotors with limits a simulation may pass for "none" */
    ladrc_mixer_config_t cfg = config(LADRC_MIXER_IDEAL);
    ladrc_mixer_t mx;
    cfg.w2_min_rad2_s2 = LADRC_R(-1e30);
    cfg.w2_max_rad2_s2 = LADRC_R(1e30);
    /* when / then */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_init(&mx, &cfg));
    cfg.mode = LADRC_MIXER_SATURATE;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_W2_MIN, ladrc_mixer_init(&mx, &cfg));
    cfg.w2_min_rad2_s2 = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_W2_MAX, ladrc_mixer_init(&mx, &cfg));
}

static void test_mixer_init_rejects_an_unknown_mode(void)
{
    /* given */
    ladrc_mixer_config_t cfg = config(LADRC_MIXER_SATURATE);
    ladrc_mixer_t mx;
    cfg.mode = (ladrc_mixer_mode_t)2;
    /* when / then */
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_MODE, ladrc_mixer_init(&mx, &cfg));
}

static void test_mixer_init_accepts_negative_w2_min_only_in_ideal_mode(void)
{
    /* given */
    ladrc_mixer_config_t cfg = config(LADRC_MIXER_IDEAL);
    ladrc_mixer_t mx;
    cfg.w2_min_rad2_s2 = LADRC_R(-1e5);
    /* when / then */
    TEST_ASSERT_EQUAL_INT(LADRC_OK, ladrc_mixer_init(&mx, &cfg));
    cfg.mode = LADRC_MIXER_SATURATE;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_W2_MIN, ladrc_mixer_init(&mx, &cfg));
}

static void test_mixer_init_rejects_null_pointers(void)
{
    const ladrc_mixer_config_t cfg = config(LADRC_MIXER_SATURATE);
    ladrc_mixer_t mx;
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_mixer_init(NULL, &cfg));
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_NULL, ladrc_mixer_init(&mx, NULL));
}

static void test_mixer_rejected_by_init_keeps_its_rotors_at_zero(void)
{
    /* given: a rejected config */
    ladrc_mixer_config_t cfg = config(LADRC_MIXER_SATURATE);
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.2), LADRC_R(0.1), LADRC_R(0.05)};
    int i;
    cfg.mass_kg = LADRC_R(0.0);
    TEST_ASSERT_EQUAL_INT(LADRC_ERR_MIXER_MASS_KG, ladrc_mixer_init(&mx, &cfg));
    /* when */
    (void)ladrc_mixer_step(&mx, LADRC_R(10.0), torque_Nm, &out);
    /* then */
    for (i = 0; i < 4; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.w2_rad2_s2[i]);
        TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, out.w_rad_s[i]);
    }
}

static void test_mixer_allocate_then_saturate_gives_exactly_the_output_of_a_step(void)
{
    /* given: one request within the limits and one whose roll is beyond them */
    const ladrc_real_t torque_Nm[2][3] = {{LADRC_R(0.01), LADRC_R(-0.02), LADRC_R(0.001)},
                                          {LADRC_R(2.0), LADRC_R(-0.3), LADRC_R(0.05)}};
    const uint8_t expect_saturated[2] = {0u, 1u};
    ladrc_mixer_t mx;
    int k;
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    for (k = 0; k < 2; ++k) {
        ladrc_real_t w2[4];
        ladrc_mixer_output_t pure;
        ladrc_mixer_output_t stepped;
        /* when: the two pure stages, and a step on the same request */
        ladrc_mixer_allocate(&mx, LADRC_R(9.0), torque_Nm[k], w2);
        ladrc_mixer_saturate(&mx, w2, LADRC_R(9.0), torque_Nm[k], &pure);
        (void)ladrc_mixer_step(&mx, LADRC_R(9.0), torque_Nm[k], &stepped);
        /* then: the same output bit for bit, cut back only in the second case */
        TEST_ASSERT_EQUAL_INT(expect_saturated[k], stepped.saturated != 0u);
        TEST_ASSERT_EQUAL_HEX8(stepped.saturated, pure.saturated);
        TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, pure.faults);
        TEST_ASSERT_EQUAL_MEMORY(stepped.w2_rad2_s2, pure.w2_rad2_s2, sizeof pure.w2_rad2_s2);
        TEST_ASSERT_EQUAL_MEMORY(stepped.w_rad_s, pure.w_rad_s, sizeof pure.w_rad_s);
        TEST_ASSERT_EQUAL_MEMORY(&stepped.thrust_N, &pure.thrust_N, sizeof pure.thrust_N);
        TEST_ASSERT_EQUAL_MEMORY(stepped.torque_Nm, pure.torque_Nm, sizeof pure.torque_Nm);
    }
}

static void test_mixer_saturate_leaves_its_output_alone_for_what_it_cannot_mix(void)
{
    /* given: an output filled with a marker, a non-finite w^2, and in ideal mode a
     * w^2 beyond the range whose sums could overflow */
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    const ladrc_real_t nan_w2[4] = {(ladrc_real_t)NAN, LADRC_R(6e4), LADRC_R(6e4), LADRC_R(6e4)};
    const ladrc_real_t huge_w2[4] = {LADRC_REAL_MAX, LADRC_REAL_MAX, LADRC_REAL_MAX, LADRC_REAL_MAX};
    ladrc_mixer_t mx;
    ladrc_mixer_t ideal;
    ladrc_mixer_output_t marker;
    ladrc_mixer_output_t out;
    memset(&marker, 0x5a, sizeof marker);
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    init_mixer(&ideal, LADRC_MIXER_IDEAL);
    /* when / then: untouched */
    out = marker;
    ladrc_mixer_saturate(&mx, nan_w2, LADRC_R(7.0), torque_Nm, &out);
    TEST_ASSERT_EQUAL_MEMORY(&marker, &out, sizeof out);
    ladrc_mixer_saturate(&ideal, huge_w2, LADRC_REAL_MAX, torque_Nm, &out);
    TEST_ASSERT_EQUAL_MEMORY(&marker, &out, sizeof out);
}

static void test_mixer_functions_tolerate_null_pointers(void)
{
    if (LADRC_ASSERTS_ENABLED) {
        TEST_IGNORE_MESSAGE("passes NULL instances: with LADRC_ASSERT on, that is the programmer error it catches");
    }
    /* given */
    ladrc_mixer_t mx;
    ladrc_mixer_output_t out;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(0.0), LADRC_R(0.0), LADRC_R(0.0)};
    ladrc_real_t w2[4] = {LADRC_R(1.0), LADRC_R(2.0), LADRC_R(3.0), LADRC_R(4.0)};
    ladrc_real_t thrust_N = LADRC_R(-1.0);
    ladrc_real_t torque_out[3] = {LADRC_R(-1.0), LADRC_R(-1.0), LADRC_R(-1.0)};
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    /* when / then: no crash, outputs untouched, neutral results */
    ladrc_mixer_reset(NULL);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 0.0, ladrc_mixer_thrust_from_tilt(NULL, LADRC_R(0.0), LADRC_R(0.0)));
    ladrc_mixer_allocate(NULL, LADRC_R(1.0), torque_Nm, w2);
    ladrc_mixer_allocate(&mx, LADRC_R(1.0), NULL, w2);
    ladrc_mixer_allocate(&mx, LADRC_R(1.0), torque_Nm, NULL);
    TEST_ASSERT_FLOAT_WITHIN(0.0, 1.0, w2[0]);
    ladrc_mixer_forward(NULL, w2, &thrust_N, torque_out);
    ladrc_mixer_forward(&mx, NULL, &thrust_N, torque_out);
    ladrc_mixer_forward(&mx, w2, NULL, torque_out);
    ladrc_mixer_forward(&mx, w2, &thrust_N, NULL);
    TEST_ASSERT_FLOAT_WITHIN(0.0, -1.0, thrust_N);
    TEST_ASSERT_FLOAT_WITHIN(0.0, -1.0, torque_out[0]);
    ladrc_mixer_saturate(NULL, w2, LADRC_R(1.0), torque_Nm, &out);
    ladrc_mixer_saturate(&mx, NULL, LADRC_R(1.0), torque_Nm, &out);
    ladrc_mixer_saturate(&mx, w2, LADRC_R(1.0), NULL, &out);
    ladrc_mixer_saturate(&mx, w2, LADRC_R(1.0), torque_Nm, NULL);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_step(NULL, LADRC_R(1.0), torque_Nm, &out));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_get_faults(NULL));
    /* a missing torque is a programmer error (the state untouched); a missing output is allowed */
    const ladrc_mixer_output_t held = mx.out;
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_STATE, ladrc_mixer_step(&mx, LADRC_R(1.0), NULL, &out));
    TEST_ASSERT_EQUAL_INT(0, memcmp(&held, &mx.out, sizeof held));
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_mixer_step(&mx, LADRC_R(1.0), torque_Nm, NULL));
}

static void test_mixer_reset_returns_to_hover_and_clears_faults(void)
{
    /* given: a mixer that faulted after a hard manoeuvre */
    ladrc_mixer_t mx;
    ladrc_mixer_t fresh;
    const ladrc_real_t torque_Nm[3] = {LADRC_R(1.0), LADRC_R(1.0), LADRC_R(1.0)};
    init_mixer(&mx, LADRC_MIXER_SATURATE);
    init_mixer(&fresh, LADRC_MIXER_SATURATE);
    (void)ladrc_mixer_step(&mx, LADRC_R(30.0), torque_Nm, NULL);
    (void)ladrc_mixer_step(&mx, (ladrc_real_t)NAN, torque_Nm, NULL);
    /* when */
    ladrc_mixer_reset(&mx);
    /* then */
    assert_same_output(&fresh.out, &mx.out);
    TEST_ASSERT_EQUAL_HEX8(LADRC_FAULT_NONE, ladrc_mixer_get_faults(&mx));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_mixer_allocation_followed_by_the_forward_model_gives_back_the_request);
    RUN_TEST(test_mixer_forward_model_matches_the_paper_equations);
    RUN_TEST(test_mixer_hover_of_the_paper_vehicle_gives_m_g_over_4_kL_on_every_rotor);
    RUN_TEST(test_mixer_holds_hover_after_init);
    RUN_TEST(test_mixer_thrust_from_tilt_is_m_g_over_cos_roll_cos_pitch);
    RUN_TEST(test_mixer_thrust_from_tilt_is_capped_at_the_tilt_limit);
    RUN_TEST(test_mixer_thrust_from_tilt_of_an_unknown_attitude_is_the_weight);
    RUN_TEST(test_mixer_request_within_the_limits_is_passed_through_bit_for_bit);
    RUN_TEST(test_mixer_thrust_beyond_the_top_moves_down_and_roll_stays_exact);
    RUN_TEST(test_mixer_thrust_below_the_bottom_moves_up_and_roll_stays_exact);
    RUN_TEST(test_mixer_gives_up_yaw_before_roll_and_pitch);
    RUN_TEST(test_mixer_scales_too_much_roll_and_pitch_keeping_their_ratio);
    RUN_TEST(test_mixer_does_not_flag_an_axis_with_no_request_when_the_other_is_scaled);
    RUN_TEST(test_mixer_keeps_every_rotor_within_the_limits_for_random_requests);
    RUN_TEST(test_mixer_flags_an_axis_exactly_when_achieved_differs_from_requested);
    RUN_TEST(test_mixer_achieved_values_are_the_forward_model_of_the_rotors);
    RUN_TEST(test_mixer_priorities_hold_for_random_requests);
    RUN_TEST(test_mixer_huge_roll_beside_a_huge_thrust_reports_what_the_rotors_give);
    RUN_TEST(test_mixer_huge_yaw_does_not_take_the_place_of_roll_and_pitch);
    RUN_TEST(test_mixer_huge_roll_reports_the_yaw_the_rotors_give);
    RUN_TEST(test_mixer_ideal_mode_lets_w2_go_negative_and_reports_the_request_exactly);
    RUN_TEST(test_mixer_ideal_mode_ignores_the_rotor_limits);
    RUN_TEST(test_mixer_non_finite_request_returns_the_previous_output_with_an_input_fault);
    RUN_TEST(test_mixer_non_finite_first_request_gives_hover);
    RUN_TEST(test_mixer_mixes_a_finite_request_of_any_size_at_the_limits);
    RUN_TEST(test_mixer_ideal_mode_refuses_non_finite_and_overflowing_requests);
    RUN_TEST(test_mixer_init_rejects_every_invalid_field_with_its_own_status);
    RUN_TEST(test_mixer_init_accepts_each_field_at_its_bounds_and_rejects_just_beyond);
    RUN_TEST(test_mixer_init_in_ideal_mode_does_not_bound_the_unused_rotor_limits);
    RUN_TEST(test_mixer_init_rejects_an_unknown_mode);
    RUN_TEST(test_mixer_init_accepts_negative_w2_min_only_in_ideal_mode);
    RUN_TEST(test_mixer_init_rejects_null_pointers);
    RUN_TEST(test_mixer_rejected_by_init_keeps_its_rotors_at_zero);
    RUN_TEST(test_mixer_allocate_then_saturate_gives_exactly_the_output_of_a_step);
    RUN_TEST(test_mixer_saturate_leaves_its_output_alone_for_what_it_cannot_mix);
    RUN_TEST(test_mixer_functions_tolerate_null_pointers);
    RUN_TEST(test_mixer_reset_returns_to_hover_and_clears_faults);
    return UNITY_END();
}
