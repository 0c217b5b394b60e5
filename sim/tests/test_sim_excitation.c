/* SPDX-License-Identifier: BSD-3-Clause */
/* [excitation]'s chirp (sim/scenario/excitation.h): its value against the
 * formula, its frequency sweeping from f0 to f1, axis = all's order, the
 * torque authority it is scaled by, and the chirp a run adds to the
 * controller's torque before the mixer (a PID without gains on ideal
 * rotors: the mixer is asked for the chirp alone). */
#define _POSIX_C_SOURCE 200809L /* mkdtemp */
#include "unity.h"
#include "run/runner.h"
#include "scenario/excitation.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

/* The chirp's phase reaches about 2 pi f1 T / ln(f1 / f0) (some 700 rad
 * below); two double evaluations of it, in another order, differ by a few
 * ulps of that, 1e-13 rad: 1e-11 of the amplitude is far below any wrong
 * factor and far above that rounding. */
#define VALUE_TOL_REL 1e-11

static sim_scenario_t sc;
static char dir[64];
static char csv_path[128];

void setUp(void)
{
    dir[0] = '\0';
}

/* The run's files and its folder, removed. */
void tearDown(void)
{
    if (dir[0] == '\0')
        return;
    char path[256];
    static const char *const names[] = {"PID.csv", "PID_log.csv"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        remove(path);
    }
    rmdir(dir);
}

/* |actual - expected| <= tol (Unity is built without doubles here). */
static void assert_within(double tol, double expected, double actual)
{
    char message[160];
    snprintf(message, sizeof message, "expected %.17g within %.3g, got %.17g", expected, tol, actual);
    TEST_ASSERT_TRUE_MESSAGE(fabs(actual - expected) <= tol, message);
}

/* The formula of docs/scenario-format.md, written out here on its own. */
static double chirp_formula(double amplitude, double f0, double f1, double T, double t)
{
    if (t < 0.0 || t >= T)
        return 0.0;
    const double L = log(f1 / f0);
    return amplitude * sin(2.0 * PI * f0 * T / L * (exp(t * L / T) - 1.0));
}

static void parse(const char *text)
{
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_parse(&sc, text, "excitation.ini", &err), err.message);
}

static void test_the_value_is_the_formula_and_zero_outside_the_chirp(void)
{
    const double a = 0.3, f0 = 1.0, f1 = 40.0, T = 10.0;
    for (int k = 0; k <= 10000; ++k) {
        const double t = -0.5 + 11.0 * k / 10000.0; /* before, through and after the chirp */
        const double expected = chirp_formula(a, f0, f1, T, t);
        assert_within(VALUE_TOL_REL * a, expected, sim_chirp_value(a, f0, f1, T, t));
    }
    assert_within(0.0, 0.0, sim_chirp_value(a, f0, f1, T, -1e-9));
    assert_within(0.0, 0.0, sim_chirp_value(a, f0, f1, T, 0.0)); /* sin 0 */
    assert_within(0.0, 0.0, sim_chirp_value(a, f0, f1, T, T));   /* [0, T) */
    assert_within(0.0, 0.0, sim_chirp_value(a, f0, f1, T, 1e3));
}

/* The local frequency of a half period (between two zero crossings) is the
 * mean of an exponential sweep over it, within (L dt / T)^2 / 24 of its
 * value at the middle: 0.2 % for the first half period below (dt 0.5 s,
 * L = ln 40, T = 10 s), less later. 1 % covers it. */
#define LOCAL_FREQ_TOL_REL 0.01
/* The crossings found by sampling every 1e-5 s are within a step of the true ones. */
#define SAMPLE_S 1e-5

static void test_the_frequency_sweeps_from_f0_to_f1(void)
{
    const double f0 = 1.0, f1 = 40.0, T = 10.0;
    assert_within(0.0, f0, sim_chirp_frequency_hz(f0, f1, T, 0.0));
    assert_within(1e-12 * f1, f1, sim_chirp_frequency_hz(f0, f1, T, T));
    double crossing[400];
    int n = 0;
    double before = sim_chirp_value(1.0, f0, f1, T, SAMPLE_S);
    for (long k = 2; k * SAMPLE_S < T && n < 400; ++k) {
        const double t = k * SAMPLE_S, now = sim_chirp_value(1.0, f0, f1, T, t);
        if ((before > 0.0) != (now > 0.0)) { /* between the samples: the one before, by linear interpolation */
            crossing[n++] = t - SAMPLE_S * now / (now - before);
        }
        before = now;
    }
    /* as many crossings as half turns of the phase at T: 2 f0 T (f1 / f0 - 1) / ln(f1 / f0) */
    const int half_turns = (int)floor(2.0 * f0 * T * (f1 / f0 - 1.0) / log(f1 / f0));
    TEST_ASSERT_EQUAL_INT(half_turns, n);
    /* the first half period (from 0) at f0, the last at f1; the ones between on the sweep */
    const double first_hz = 0.5 / crossing[0];
    assert_within(LOCAL_FREQ_TOL_REL * f0, sim_chirp_frequency_hz(f0, f1, T, 0.5 * crossing[0]), first_hz);
    TEST_ASSERT_TRUE(first_hz < 1.2 * f0); /* the sweep rises by exp(0.5 s ln 40 / 10 s) = 1.2 over it */
    for (int k = 1; k < n; ++k) {
        const double mid = 0.5 * (crossing[k] + crossing[k - 1]);
        const double local_hz = 0.5 / (crossing[k] - crossing[k - 1]);
        assert_within(LOCAL_FREQ_TOL_REL * local_hz, sim_chirp_frequency_hz(f0, f1, T, mid), local_hz);
    }
    /* the last whole half period ends within one (12.5 ms) of T: its middle within 19 ms, where the
     * sweep is 0.7 % below f1; 2 % covers that and the 1 % above */
    assert_within(0.02 * f1, f1, 0.5 / (crossing[n - 1] - crossing[n - 2]));
}

static void test_axis_all_sweeps_roll_then_pitch_then_yaw(void)
{
    parse("[run]\nduration_s = 8\n[excitation]\naxis = all\namplitude = 0.5\nf0_hz = 2\nf1_hz = 20\n"
          "start_s = 0.5\nduration_s = 2\n");
    TEST_ASSERT_EQUAL_INT(1, sc.excite_on);
    TEST_ASSERT_EQUAL_INT(3, sim_excitation_axes(&sc));
    assert_within(0.0, 6.5, sim_excitation_end_s(&sc));
    for (int k = 0; k <= 8000; ++k) {
        const double t = k * 1e-3;
        double c[3];
        sim_excitation_at(&sc, t, c);
        for (int axis = 0; axis < 3; ++axis) {
            const double start = 0.5 + 2.0 * axis;
            assert_within(VALUE_TOL_REL, chirp_formula(0.5, 2.0, 20.0, 2.0, t - start), c[axis]);
        }
    }
    /* one axis alone, the others untouched */
    parse("[run]\nduration_s = 12\n[excitation]\naxis = pitch\n");
    for (int k = 0; k <= 120; ++k) {
        double c[3];
        sim_excitation_at(&sc, 0.1 * k, c);
        assert_within(0.0, 0.0, c[0]);
        assert_within(0.0, 0.0, c[2]);
        assert_within(VALUE_TOL_REL, chirp_formula(0.2, 1.0, 40.0, 10.0, 0.1 * k - 1.0), c[1]);
    }
    /* no section: nothing */
    parse("[run]\nduration_s = 12\n");
    TEST_ASSERT_EQUAL_INT(0, sc.excite_on);
    double c[3] = {1.0, 1.0, 1.0};
    sim_excitation_at(&sc, 5.0, c);
    TEST_ASSERT_TRUE(c[0] == 0.0 && c[1] == 0.0 && c[2] == 0.0);
}

static void test_the_authority_is_one_rotor_to_zero_and_its_opposite_to_twice_hover(void)
{
    parse("[run]\nduration_s = 1\n[mismatch]\ninertia_scale = 2 2 2\n"); /* the plant's, not the model's */
    const double m = 0.8, g = 9.81, l = 0.165, kL = 2.98e-5, b = 2e-6;
    const double w2_hover = m * g / (4.0 * kL);
    /* roll: rotors 2 and 4 (l kL (w2^2 - w4^2)) at 2 hover and 0 */
    assert_within(1e-12, l * kL * (2.0 * w2_hover - 0.0), sim_setup_authority_Nm(&sc, 0));
    assert_within(1e-12, l * m * g / 2.0, sim_setup_authority_Nm(&sc, 1));
    /* yaw: b (-w1^2 + w2^2 - w3^2 + w4^2) with 2 and 4 at 2 hover, 1 and 3 at 0 */
    assert_within(1e-15, b * (2.0 * w2_hover + 2.0 * w2_hover), sim_setup_authority_Nm(&sc, 2));
    assert_within(1e-12, 2.0 * w2_hover, sim_setup_full_w2_rad2_s2(&sc));
}

/* ---- the chirp in a run -------------------------------------------------------- */

/* Index of name among the header line's comma-separated columns. */
static int column(const char *header, const char *name)
{
    int index = 0;
    const size_t n = strlen(name);
    for (const char *p = header; *p != '\0' && *p != '\n'; ++index) {
        const size_t len = strcspn(p, ",\n");
        if (len == n && strncmp(p, name, n) == 0)
            return index;
        p += len + (p[len] == ',');
    }
    TEST_FAIL_MESSAGE(name);
    return -1;
}

/* The value of column col of a line. */
static double cell(const char *line, int col)
{
    const char *p = line;
    for (int k = 0; k < col; ++k) {
        p = strchr(p, ',');
        TEST_ASSERT_NOT_NULL(p);
        ++p;
    }
    return strtod(p, NULL);
}

/* The asked torque is the controller's (0) plus the chirp, N m, rounded to
 * the library's float once; ideal rotors achieve it bit for bit. 2^-23 of
 * the value covers that rounding and the formula's (VALUE_TOL_REL). */
#define FLOAT_TOL_REL 1.2e-7

static void test_a_run_asks_the_mixer_for_the_controllers_torque_plus_the_chirp(void)
{
    static const char TEXT[] = "[run]\nduration_s = 1.7\ncontrollers = PID\nlog = generic\n"
                               "[controller PID]\npid_kp = 0\npid_ki = 0\npid_kd = 0\n"
                               "[excitation]\naxis = all\namplitude = 0.05\nf0_hz = 2\nf1_hz = 50\n"
                               "start_s = 0.1\nduration_s = 0.5\n";
    parse(TEXT);
    snprintf(dir, sizeof dir, "excitation_XXXXXX");
    TEST_ASSERT_NOT_NULL(mkdtemp(dir));
    snprintf(csv_path, sizeof csv_path, "%s/PID.csv", dir);
    sim_metrics_t m;
    char err[256] = "";
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_run_attitude(&sc, SIM_CTRL_PID, csv_path, NULL, &m, err, sizeof err), err);
    TEST_ASSERT_FALSE(m.diverged);

    char log_path[160];
    snprintf(log_path, sizeof log_path, "%s/PID_log.csv", dir);
    FILE *series = fopen(csv_path, "r");
    FILE *log = fopen(log_path, "r");
    TEST_ASSERT_NOT_NULL(series);
    TEST_ASSERT_NOT_NULL(log);
    static char series_line[16384], log_line[4096];
    TEST_ASSERT_NOT_NULL(fgets(series_line, sizeof series_line, series));
    TEST_ASSERT_NOT_NULL(fgets(log_line, sizeof log_line, log));
    static const char *const AXES[3] = {"roll", "pitch", "yaw"};
    int cmd_col[3], command_col[3];
    for (int i = 0; i < 3; ++i) {
        char name[64];
        snprintf(name, sizeof name, "torque_cmd_%s_Nm", AXES[i]);
        cmd_col[i] = column(series_line, name);
        snprintf(name, sizeof name, "command[%d]", i);
        command_col[i] = column(log_line, name);
    }
    const int time_col = column(log_line, "time");
    long ticks = 0;
    double peak[3] = {0.0, 0.0, 0.0};
    while (fgets(log_line, sizeof log_line, log) != NULL) {
        TEST_ASSERT_NOT_NULL(fgets(series_line, sizeof series_line, series));
        const double t = cell(log_line, time_col);
        assert_within(0.0, (double)ticks * sc.control_dt_s, t);
        for (int i = 0; i < 3; ++i) {
            const double authority = sim_setup_authority_Nm(&sc, i);
            const double chirp_Nm = authority * chirp_formula(0.05, 2.0, 50.0, 0.5, t - (0.1 + 0.5 * i));
            const double controller_Nm = cell(series_line, cmd_col[i]);
            const double achieved_Nm = cell(log_line, command_col[i]) * authority;
            assert_within(0.0, 0.0, controller_Nm); /* the PID without gains */
            assert_within(FLOAT_TOL_REL * fabs(chirp_Nm) + VALUE_TOL_REL * 0.05 * authority, chirp_Nm,
                          achieved_Nm - controller_Nm);
            peak[i] = fmax(peak[i], fabs(achieved_Nm) / authority);
        }
        ++ticks;
    }
    fclose(series);
    fclose(log);
    TEST_ASSERT_EQUAL_INT(1700, (int)ticks);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_TRUE(peak[i] > 0.049 && peak[i] <= 0.05); /* every axis swept at its amplitude */
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_the_value_is_the_formula_and_zero_outside_the_chirp);
    RUN_TEST(test_the_frequency_sweeps_from_f0_to_f1);
    RUN_TEST(test_axis_all_sweeps_roll_then_pitch_then_yaw);
    RUN_TEST(test_the_authority_is_one_rotor_to_zero_and_its_opposite_to_twice_hover);
    RUN_TEST(test_a_run_asks_the_mixer_for_the_controllers_torque_plus_the_chirp);
    return UNITY_END();
}
