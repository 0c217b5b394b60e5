/* SPDX-License-Identifier: BSD-3-Clause */
/* The command line's settings (SECTION.KEY=VALUE after the file) and the
 * one rule of a controller list. */
#include "unity.h"
#include "scenario_cases.h"

static int parse_with(const char *text, const char *const *sets, int n)
{
    memset(&err, 0, sizeof err);
    return sim_scenario_parse_buffer_with(&sc, text, strlen(text), "f.ini", sets, n, &err);
}

static void test_settings_replace_the_files_values(void)
{
    const char *text = "[run]\nduration_s = 2\nseed = 5\n[reference]\nroll = 0 .. 1 : 3\nroll = 1 .. : 4\n"
                       "[sensors]\nangle_noise_var_deg2 = 4\n[controller LADRC]\nwc_rad_s = 10\n";
    const char *sets[] = {"run.seed=9",
                          "controller:LADRC.wc_rad_s=20",
                          "controller PID.pid_kp = 2",
                          "reference.roll=.. 0.5: 7",
                          "reference.roll=0.5 ..: 8",
                          "sensors.angle_noise_std_deg=1",
                          "metrics.settle_band_deg=2"};
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, parse_with(text, sets, 7), err.message);
    TEST_ASSERT_TRUE(sc.seed == 9u);
    assert_close(20.0, sc.overrides[SIM_CTRL_LADRC].wc_rad_s, "LADRC wc");
    assert_close(2.0, sc.overrides[SIM_CTRL_PID].pid_kp, "PID kp (a section the file lacks)");
    /* the file's two pieces are gone, the settings' two remain */
    TEST_ASSERT_EQUAL_INT(2, sc.reference[0].n_pieces);
    assert_close(7.0 * DEG, sim_signal_eval(&sc.reference[0], 0.25), "roll before 0.5 s");
    assert_close(8.0 * DEG, sim_signal_eval(&sc.reference[0], 3.0), "roll after 0.5 s");
    /* the twin key replaces the file's variance: std 1 deg, not sqrt(4) */
    assert_close(1.0 * DEG, sc.angle_noise_std_rad, "angle noise std");
    assert_close(2.0, sc.settle_band_deg, "settle band");
    TEST_ASSERT_EQUAL_INT(12, sc.first_set_line); /* 11 lines with the final empty one */
    /* what the file gives alone stays */
    TEST_ASSERT_EQUAL_INT(0, parse_with(text, NULL, 0));
    TEST_ASSERT_TRUE(sc.seed == 5u);
    assert_close(10.0, sc.overrides[SIM_CTRL_LADRC].wc_rad_s, "LADRC wc from the file");
}

static void test_setting_errors_name_the_setting_and_column(void)
{
    static const struct {
        const char *set;
        int column;
        const char *message;
    } cases[] = {
        {.set = "run.seed=abc", .column = 10, .message = "expected an unsigned integer, got 'abc'"},
        {.set = "seed=3", .column = 1, .message = "expected SECTION.KEY=VALUE, got 'seed=3'"},
        {.set = "runs.seed=3", .column = 1, .message = "unknown section 'runs'"},
        {.set = "run.sed=3", .column = 5, .message = "unknown key 'sed' in [run]"},
        {.set = "controller:LADRC.pid_kp=1", .column = 18, .message = "'pid_kp' does not apply to LADRC"},
        {.set = "controller:XY.wc_rad_s=1",
         .column = 12,
         .message = "unknown controller 'XY' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, "
                    "CASCADED or INDI)"},
        {.set = "controller.wc_rad_s=1",
         .column = 11,
         .message = "expected a controller name after 'controller' ('controller:NAME.KEY=VALUE')"},
        {.set = "controller:LADRC.wc_rad_s=-1", .column = 27, .message = "wc_rad_s must be > 0"},
        {.set = "run.duration_s=", .column = 16, .message = "missing value for 'duration_s'"},
        {.set = "run.controllers=LADRC,,PID", .column = 23, .message = "expected a controller name before ','"},
    };
    const char *text = "[run]\nduration_s = 2\n";
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const char *sets[] = {"metrics.settle_band_deg=1", cases[i].set};
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, parse_with(text, sets, 2), cases[i].set);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(cases[i].message, err.message, cases[i].set);
        /* the file has 3 lines (the last empty): the settings are lines 4 and 5 */
        TEST_ASSERT_EQUAL_INT_MESSAGE(4, err.first_set_line, cases[i].set);
        TEST_ASSERT_EQUAL_INT_MESSAGE(5, err.line, cases[i].set);
        TEST_ASSERT_EQUAL_INT_MESSAGE(cases[i].column, err.column, cases[i].set);
    }
    /* a key set twice on the command line is a duplicate; a signal adds pieces */
    const char *twice[] = {"run.seed=2", "run.seed=3"};
    TEST_ASSERT_EQUAL_INT(-1, parse_with(text, twice, 2));
    TEST_ASSERT_EQUAL_STRING("duplicate key 'seed' (set twice on the command line)", err.message);
    const char *overlap[] = {"reference.roll=0..2: 1", "reference.roll=1..3: 2"};
    TEST_ASSERT_EQUAL_INT(-1, parse_with(text, overlap, 2));
    TEST_ASSERT_EQUAL_STRING("window (1, 3] overlaps another setting of 'roll' on the command line", err.message);
    /* a consistency error caused by a setting points at it */
    const char *no_rate[] = {"run.controllers=INDI", "sensors.use_rate=no"};
    TEST_ASSERT_EQUAL_INT(-1, parse_with(text, no_rate, 2));
    TEST_ASSERT_EQUAL_INT(5, err.line);
    TEST_ASSERT_EQUAL_INT(18, err.column);
    /* file errors keep their place, with first_set_line telling them apart */
    TEST_ASSERT_EQUAL_INT(-1, parse_with("[run]\nduration_s = x\n", twice, 1));
    TEST_ASSERT_EQUAL_INT(2, err.line);
    TEST_ASSERT_TRUE(err.line < err.first_set_line || err.first_set_line == 0);
}

static void test_controller_lists_take_commas_spaces_or_both(void)
{
    static const char *const same[] = {"LADRC PID", "LADRC,PID", "LADRC, PID", " LADRC ,PID ", "LADRC\tPID"};
    for (size_t i = 0; i < sizeof same / sizeof same[0]; ++i) {
        sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
        int n = 0;
        size_t at = 0;
        char msg[160] = "";
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_controller_list_parse(same[i], ids, &n, &at, msg, sizeof msg), same[i]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(2, n, same[i]);
        TEST_ASSERT_EQUAL_INT(SIM_CTRL_LADRC, ids[0]);
        TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, ids[1]);
    }
    static const struct {
        const char *text;
        size_t at;
        const char *message;
    } bad[] = {
        {.text = "LADRC,", .at = 6, .message = "expected a controller name"},
        {.text = ",LADRC", .at = 0, .message = "expected a controller name before ','"},
        {.text = "LADRC,,PID", .at = 6, .message = "expected a controller name before ','"},
        {.text = "LADRC PID,LADRC", .at = 10, .message = "controller 'LADRC' listed twice"},
        {.text = "LADRC;PID",
         .at = 0,
         .message = "unknown controller 'LADRC;PID' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or "
                    "INDI)"},
        {.text = "", .at = 0, .message = "expected a controller name"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        sim_controller_id_t ids[SIM_MAX_CONTROLLERS];
        int n = 0;
        size_t at = 99;
        char msg[160] = "";
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_controller_list_parse(bad[i].text, ids, &n, &at, msg, sizeof msg),
                                      bad[i].text);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(bad[i].message, msg, bad[i].text);
        TEST_ASSERT_EQUAL_INT_MESSAGE((int)bad[i].at, (int)at, bad[i].text);
    }
    /* the file reads the same rule, and points into the value */
    parse_ok("[run]\nduration_s = 1\ncontrollers = PID, LADRC\n");
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, sc.controllers[0]);
    const bad_case_t cases[] = {{.text = "[run]\nduration_s = 1\ncontrollers = PID,\n",
                                 .line = 3,
                                 .column = 19,
                                 .message = "expected a controller name"}};
    CHECK_BAD_CASES(cases);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_settings_replace_the_files_values);
    RUN_TEST(test_setting_errors_name_the_setting_and_column);
    RUN_TEST(test_controller_lists_take_commas_spaces_or_both);
    return UNITY_END();
}
