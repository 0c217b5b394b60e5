/* SPDX-License-Identifier: BSD-3-Clause */
/* A log's noise as the tuning takes it: the logged command's noise above
 * 20 Hz (log/log_noise.h) on a generated log with a known tone, and the
 * identified airframe's scenario (log/airframe.h) carrying it as the LADRC
 * family's per-axis cap in N m and the proposed stage as its [filter],
 * read back by the scenario parser. */
#define _POSIX_C_SOURCE 200809L /* mkstemp */
#include "unity.h"
#include "log/airframe.h"
#include "log/log_noise.h"
#include "scenario/scenario.h"
#include "scenario/setup.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846
/* A 50 Hz tone of amplitude 0.1 has rms 0.0707; Welch's Hann segments
 * spread it over a few bins, all above 20 Hz: the band's rms is the tone's
 * to the rounding of the window's power, 1e-3 relative allows it. */
#define TONE_REL_TOL 1e-3
/* The scenario file carries the cap with 6 significant digits. */
#define CAP_REL_TOL 1e-5

static char path[64];
static sim_scenario_t sc;

void setUp(void)
{
    path[0] = '\0';
}

void tearDown(void)
{
    if (path[0] != '\0') {
        remove(path);
    }
}

static FILE *temp_file(void)
{
    snprintf(path, sizeof path, "/tmp/test_sim_log_noise_XXXXXX");
    const int fd = mkstemp(path);
    TEST_ASSERT_TRUE(fd >= 0);
    FILE *f = fdopen(fd, "w");
    TEST_ASSERT_NOT_NULL(f);
    return f;
}

static void test_the_logged_command_noise_above_20_hz_is_its_tone(void)
{
    FILE *f = temp_file();
    fprintf(f, "time,gyro[0],gyro[1],gyro[2],command[0],command[1],command[2]\n");
    for (int k = 0; k < 20000; ++k) {
        const double t = 1e-3 * k;
        /* roll: a slow swing (below 20 Hz) and a 50 Hz tone; pitch the swing only; yaw nothing */
        fprintf(f, "%.6f,0,0,0,%.9g,%.9g,0\n", t, 0.3 * sin(2.0 * PI * 2.0 * t) + 0.1 * sin(2.0 * PI * 50.0 * t),
                0.3 * sin(2.0 * PI * 2.0 * t));
    }
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    sim_log_options_t opt;
    sim_log_options_default(&opt);
    opt.format = SIM_LOG_GENERIC;
    snprintf(opt.path, sizeof opt.path, "%s", path);
    static sim_log_noise_t n;
    char err[256];
    TEST_ASSERT_EQUAL_INT(0, sim_log_noise_measure(&opt, 30.0, &n, err, sizeof err));
    TEST_ASSERT_FLOAT_WITHIN(TONE_REL_TOL * 0.1 / sqrt(2.0), 0.1 / sqrt(2.0), sim_log_noise_command_above(&n, 0, 20.0));
    /* the swing's leakage above 20 Hz through the Hann window: under 1e-4 of it */
    TEST_ASSERT_TRUE(sim_log_noise_command_above(&n, 1, 20.0) < 1e-4 * 0.3);
    TEST_ASSERT_TRUE(isnan(sim_log_noise_chain_phase_deg(&n, 0))); /* no gyro before the filters */
}

/* An identified airframe as ladrc_replay fills it. */
static void airframe(sim_airframe_t *a)
{
    memset(a, 0, sizeof *a);
    a->dt_s = 0.001;
    const double b0[3] = {110.0, 125.0, 48.0};
    for (int i = 0; i < 3; ++i) {
        a->axis[i].b0 = b0[i];
        /* told (sim_ident_b0_told): the airframe flies b0 itself */
        a->axis[i].b0_lo = 0.95 * b0[i];
        a->axis[i].b0_hi = 1.05 * b0[i];
        a->axis[i].samples = SIM_IDENT_MIN_SAMPLES;
        a->axis[i].r2 = 0.9;
        a->axis[i].band_share = 0.8;
        a->axis[i].lag_s = 0.03;
        a->axis[i].delay_ticks = 2;
        a->axis[i].damping_per_s = 10.0;
        a->noise_floor_rad_s_rthz[i] = 1e-3;
        a->log_cmd_noise[i] = 0.02 + 0.01 * i;
    }
    a->has_filter = 1;
    ladrc_gyro_filter_config_default(&a->filter, 0.001f, 3);
    a->filter.lpf_order = 2;
    a->filter.lpf_cutoff_hz = 120.0f;
    a->filter.n_notches = 2;
    a->filter.notch_hz[0] = 80.0f;
    a->filter.notch_hz[1] = 160.0f;
    a->filter.notch_q = 5.0f;
}

static void test_the_airframe_caps_the_family_in_newton_metres_and_flies_the_stage(void)
{
    static sim_airframe_t a;
    airframe(&a);
    FILE *f = temp_file();
    char why[256];
    TEST_ASSERT_EQUAL_INT(0, sim_airframe_write(f, &a, "test.csv", NULL, NULL, why, sizeof why));
    TEST_ASSERT_EQUAL_INT(0, fclose(f));
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_load(&sc, path, &err), err.message);
    const sim_controller_id_t family[4] = {SIM_CTRL_HP_MLADRC, SIM_CTRL_LP_MLADRC, SIM_CTRL_LADRC, SIM_CTRL_RATE_ADRC};
    for (int i = 0; i < 3; ++i) {
        /* a command of 1 is the replay's authority: the cap is the logged noise times it */
        const double torque = sim_setup_authority_Nm(&sc, i);
        TEST_ASSERT_FLOAT_WITHIN(CAP_REL_TOL * torque, torque, sim_airframe_torque_per_command_Nm(&a, i));
        for (int c = 0; c < 4; ++c) {
            const double cap = sc.overrides[family[c]].tune_noise_axis_max_Nm[i];
            TEST_ASSERT_FLOAT_WITHIN(CAP_REL_TOL * cap, a.log_cmd_noise[i] * torque, cap);
        }
        TEST_ASSERT_TRUE(isnan(sc.overrides[SIM_CTRL_CASCADED].tune_noise_axis_max_Nm[i]));
        TEST_ASSERT_TRUE(isnan(sc.overrides[SIM_CTRL_INDI].tune_noise_axis_max_Nm[i]));
    }
    TEST_ASSERT_TRUE(sim_setup_filters_gyro(&sc));
    ladrc_gyro_filter_config_t cfg;
    sim_setup_gyro_filter(&sc, &cfg);
    TEST_ASSERT_EQUAL_UINT(2, cfg.lpf_order);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 120.0f, cfg.lpf_cutoff_hz);
    TEST_ASSERT_EQUAL_UINT(2, cfg.n_notches);
    TEST_ASSERT_FLOAT_WITHIN(1e-3f, 160.0f, cfg.notch_hz[1]);
    TEST_ASSERT_FLOAT_WITHIN(1e-4f, 5.0f, cfg.notch_q);
}

static void test_a_per_axis_cap_conflicts_with_the_others(void)
{
    static const char *const text =
        "[run]\nduration_s = 1\ncontrollers = LADRC CASCADED\n[controller CASCADED]\ntune = margins\n"
        "[controller LADRC]\ntune = margins\ntune_noise_max_Nm = 0.01\ntune_noise_axis_max_Nm = 0.01 0.01 0.02\n";
    sim_parse_error_t err;
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, text, "caps.ini", &err));
    TEST_ASSERT_EQUAL_INT(9, err.line);
    TEST_ASSERT_NOT_NULL(strstr(err.message, "conflicts with tune_noise_max_Nm"));
    static const char *const untuned = "[run]\nduration_s = 1\ncontrollers = LADRC\n[controller LADRC]\n"
                                       "tune_noise_axis_max_Nm = 0.01 0.01 0.02\n";
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, untuned, "caps.ini", &err));
    TEST_ASSERT_NOT_NULL(strstr(err.message, "applies only with tune = margins"));
    static const char *const negative =
        "[run]\nduration_s = 1\ncontrollers = LADRC\n[controller LADRC]\ntune = margins\n"
        "tune_noise_axis_max_Nm = 0.01 -0.01 0.02\n";
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, negative, "caps.ini", &err));
    TEST_ASSERT_EQUAL_INT(6, err.line);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_the_logged_command_noise_above_20_hz_is_its_tone);
    RUN_TEST(test_the_airframe_caps_the_family_in_newton_metres_and_flies_the_stage);
    RUN_TEST(test_a_per_axis_cap_conflicts_with_the_others);
    return UNITY_END();
}
