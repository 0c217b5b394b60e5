/* SPDX-License-Identifier: BSD-3-Clause */
/* Scenario files, malformed: each error with its line, column and message,
 * the checks across keys after the whole file, the run's limits, what the
 * library refuses at the key responsible, the arguments refused. */
#include "unity.h"
#include "scenario_cases.h"

static void test_structure_errors(void)
{
    static const bad_case_t cases[] = {
        {"[runn]\n", 1, 2, "unknown section [runn]"},
        {"[run\nduration_s = 1\n", 1, 5, "expected ']'"},
        {"[run] x\n", 1, 7, "trailing characters after ']'"},
        {"[ ]\n", 1, 3, "expected a section name"},
        {"[run extra]\n", 1, 6, "unexpected 'extra' in the section header"},
        {"[controller]\n", 1, 12, "expected a controller name after 'controller'"},
        {"[controller PDI]\n", 1, 13,
         "unknown controller 'PDI' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {"[controller PID PID]\n", 1, 17, "unexpected 'PID' in the section header"},
        {"[run]\nduration_s = 1\n\n[run]\n", 4, 1, "section [run] already given on line 1"},
        {"[run]\nduration_s = 1\n[controller PID]\n[controller PID]\n", 4, 1,
         "section [controller PID] already given on line 3"},
        {"# top\nduration_s = 1\n", 2, 1, "key 'duration_s' before any [section]"},
        {"[run]\nduraton_s = 3\n", 2, 1, "unknown key 'duraton_s' in [run]"},
        {"[vehicle]\n  mass = 3\n", 2, 3, "unknown key 'mass' in [vehicle]"},
        {"[controller LADRC]\nkp = 3\n", 2, 1, "unknown key 'kp' in [controller LADRC]"},
        {"[run]\nduration_s 3\n", 2, 12, "expected '=' after 'duration_s'"},
        {"[run]\nduration-s = 3\n", 2, 9, "expected '=' after 'duration'"},
        {"[run]\nduration_s =\n", 2, 13, "missing value for 'duration_s'"},
        {"[run]\nduration_s =   # nothing\n", 2, 13, "missing value for 'duration_s'"},
        {"[run]\n= 3\n", 2, 1, "expected a key or a [section]"},
        {"[run]\nduration_s = 1\nseed = 1\nduration_s = 2\n", 4, 1,
         "duplicate key 'duration_s' (first given on line 2)"},
        {"[run]\nduration_s = 1\n[sensors]\nangle_noise_std_deg = 0.1\nangle_noise_var_deg2 = 0.01\n", 5, 1,
         "'angle_noise_var_deg2' and 'angle_noise_std_deg' (line 4) set the same value"},
        {"[run]\nduration_s = 1\n[sensors]\nrate_noise_var_deg2_s2 = 1\nrate_noise_std_deg_s = 1\n", 5, 1,
         "'rate_noise_std_deg_s' and 'rate_noise_var_deg2_s2' (line 4) set the same value"},
        {"[controller LADRC]\npid_kp = 1\n", 2, 1, "'pid_kp' does not apply to LADRC"},
        {"[controller PID]\nwc_rad_s = 1\n", 2, 1, "'wc_rad_s' does not apply to PID"},
        {"[controller LP-MLADRC]\nhp_freq_mode = known\n", 2, 1, "'hp_freq_mode' does not apply to LP-MLADRC"},
        {"[controller LADRC]\nlevant_lipschitz_rad_s4 = 1\n", 2, 1,
         "'levant_lipschitz_rad_s4' does not apply to LADRC"},
        {"[controller HP-MLADRC]\ntd_accel_rad_s2 = 1\n", 2, 1, "'td_accel_rad_s2' does not apply to HP-MLADRC"},
        {"[controller PID]\ncoupling_feed = no\n", 2, 1, "'coupling_feed' does not apply to PID"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_value_errors(void)
{
    static const bad_case_t cases[] = {
        {"[run]\nduration_s = 3x\n", 2, 14, "expected a number, got '3x'"},
        {"[run]\nduration_s = 3 4\n", 2, 16, "expected a single number"},
        {"[run]\nduration_s = abc\n", 2, 14, "expected a number, got 'abc'"},
        {"[run]\nduration_s = -\n", 2, 14, "expected a number, got '-'"},
        {"[run]\nduration_s = 0x10\n", 2, 14, "expected a number, got '0x10'"},
        {"[run]\nduration_s = inf\n", 2, 14, "expected a number, got 'inf'"},
        {"[run]\nduration_s = 1e999\n", 2, 14, "number out of range"},
        {"[run]\nduration_s = -1\n", 2, 14, "duration_s must be > 0 and at most 100000"},
        {"[run]\nduration_s = 0\n", 2, 14, "duration_s must be > 0 and at most 100000"},
        {"[run]\ncontrol_dt_s = 0\n", 2, 16, "control_dt_s must be between 1e-05 and 0.1"},
        {"[run]\ncontrol_dt_s = -1e-3\n", 2, 16, "control_dt_s must be between 1e-05 and 0.1"},
        {"[run]\nplant_substeps = 0\n", 2, 18, "plant_substeps must be between 1 and 1000"},
        {"[run]\nplant_substeps = 2.5\n", 2, 18, "expected an integer, got '2.5'"},
        {"[run]\nplant_substeps = 2 3\n", 2, 20, "expected a single integer, got '3'"},
        {"[run]\nplant_substeps = 99999999999\n", 2, 18, "number out of range"},
        {"[run]\nseed = -1\n", 2, 8, "expected an unsigned integer, got '-1'"},
        {"[run]\nseed = 18446744073709551616\n", 2, 8, "seed out of range (at most 18446744073709551615)"},
        {"[run]\nkind = attitud\n", 2, 8, "expected attitude or differentiator, got 'attitud'"},
        {"[run]\ncontrollers = LADRC PDI\n", 2, 21,
         "unknown controller 'PDI' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {"[run]\ncontrollers = ladrc\n", 2, 15,
         "unknown controller 'ladrc' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {"[run]\ncontrollers = LADRC PID LADRC\n", 2, 25, "controller 'LADRC' listed twice"},
        {"[vehicle]\ninertia_kg_m2 = 1 2\n", 2, 20, "expected 3 numbers"},
        {"[vehicle]\ninertia_kg_m2 = 1 2 3 4\n", 2, 23, "expected 3 numbers"},
        {"[vehicle]\ninertia_kg_m2 = 1 -2 3\n", 2, 19, "inertia_kg_m2 must be > 0"},
        {"[vehicle]\nmass_kg = 0\n", 2, 11, "mass_kg must be > 0"},
        {"[vehicle]\nrot_drag_Nm_s = -0.1\n", 2, 17, "rot_drag_Nm_s must be >= 0"},
        {"[rotors]\nideal = maybe\n", 2, 9, "expected yes or no, got 'maybe'"},
        {"[rotors]\nideal = yes no\n", 2, 13, "expected yes or no, got 'no'"},
        {"[rotors]\nmotor_tau_s = -0.02\n", 2, 15, "motor_tau_s must be >= 0"},
        {"[rotors]\ntilt_max_deg = 90\n", 2, 16, "tilt_max_deg must be > 0 and < 90"},
        {"[sensors]\nangle_noise_std_deg = -0.1\n", 2, 23, "angle_noise_std_deg must be >= 0"},
        {"[sensors]\nangle_noise_var_deg2 = -1e-3\n", 2, 24, "angle_noise_var_deg2 must be >= 0"},
        {"[sensors]\ndelay_ticks = 65\n", 2, 15, "delay_ticks must be between 0 and 64"},
        {"[sensors]\ndelay_ticks = -1\n", 2, 15, "delay_ticks must be between 0 and 64"},
        {"[mismatch]\ninertia_scale = 1 1 0\n", 2, 21, "inertia_scale must be > 0"},
        {"[metrics]\nerror_window_s = 5 5\n", 2, 18, "error_window_s: window start must be before its end"},
        {"[metrics]\nsteady_window_s = 6 5\n", 2, 19, "steady_window_s: window start must be before its end"},
        {"[metrics]\nsettle_window_s = -1 5\n", 2, 19, "settle_window_s must start at or after 0"},
        {"[metrics]\nerror_window_s = 5\n", 2, 19, "expected two numbers FROM TO"},
        {"[metrics]\nerror_window_s = 1 2 3\n", 2, 22, "expected two numbers FROM TO"},
        {"[metrics]\nsettle_band_deg = 0\n", 2, 19, "settle_band_deg must be > 0"},
        {"[controller LADRC]\nwc_rad_s = 0\n", 2, 12, "wc_rad_s must be > 0"},
        {"[controller LADRC]\nleso_method = rk4\n", 2, 15, "expected zoh or euler, got 'rk4'"},
        {"[controller HP-MLADRC]\nhp_freq_mode = guess\n", 2, 16, "expected known or online, got 'guess'"},
        {"[controller PID]\npid_kd = -0.05\n", 2, 10, "pid_kd must be >= 0"},
        {"[differentiator]\nnoise_var = -1\n", 2, 13, "noise_var must be >= 0"},
        {"[differentiator]\ntd_h0_s = 0\n", 2, 11, "td_h0_s must be > 0"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_signal_errors_point_into_the_expression(void)
{
    static char nine_pieces[400];
    strcpy(nine_pieces, "[disturbance]\n");
    for (int i = 0; i < 9; ++i) {
        char line[40];
        snprintf(line, sizeof line, "yaw = %d .. %d : 1\n", i, i + 1);
        strcat(nine_pieces, line);
    }
    static char too_long[400];
    strcpy(too_long, "[reference]\nroll = t");
    for (int i = 1; i < 49; ++i) {
        strcat(too_long, "+t");
    }
    const bad_case_t cases[] = {
        {"[reference]\nroll = 5 + sn(t)\n", 2, 12, "unknown function 'sn'"},
        {"[reference]\n  roll =\t5 + 15*cos(pi*t/2\n", 2, 27, "expected ')'"},
        {"[reference]\nroll = 5 +\n", 2, 11, "expected a number, name or '('"},
        {"[reference]\nroll = 5 5\n", 2, 10, "trailing characters"},
        {"[disturbance]\nroll = 2 .. 6 : 8 +\n", 2, 20, "expected a number, name or '('"},
        {"[disturbance]\nroll = 2 .. 6 :   x\n", 2, 19, "unknown name 'x'"},
        {"[disturbance]\nroll = 2 .. 6 :\n", 2, 16, "expected an expression after ':'"},
        {"[disturbance]\nroll = 6 .. 2 : 1\n", 2, 8, "window start must be before its end"},
        {"[disturbance]\nroll = 2 .. 2 : 1\n", 2, 8, "window start must be before its end"},
        {"[disturbance]\nroll = 2 .. x : 1\n", 2, 13, "expected a number, got 'x'"},
        {"[disturbance]\nroll = 2 3 .. 4 : 1\n", 2, 8, "expected a number, got '2 3'"},
        {"[disturbance]\nroll = 2 : 1\n", 2, 8, "expected 'FROM .. TO' before ':'"},
        {"[disturbance]\nroll = 2 .. 6 1\n", 2, 10, "expected ':' between the window and the expression"},
        {"[disturbance]\nroll = 2 .. 6 : 1\nroll = 5 .. 8 : 2\n", 3, 8,
         "window (5, 8] overlaps the one given on line 2"},
        {"[disturbance]\nroll = 1\nroll = 5 .. 8 : 2\n", 3, 8, "window (5, 8] overlaps the one given on line 2"},
        {"[disturbance]\nroll = 5 .. 8 : 2\nroll = 1\n", 3, 8, "window (-inf, inf] overlaps the one given on line 2"},
        {"[disturbance]\nroll = .. 6 : 2\nroll = 5 .. : 1\n", 3, 8, "window (5, inf] overlaps the one given on line 2"},
        {nine_pieces, 10, 1, "more than 8 pieces for 'yaw'"},
        {too_long, 2, 103, "expression too long"},
        {"[differentiator]\nsignal = sin(t\n", 2, 15, "expected ')'"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_errors_checked_after_the_whole_file(void)
{
    static const bad_case_t cases[] = {
        {"", 1, 1, "missing required key 'duration_s' in [run]"},
        {"[vehicle]\nmass_kg = 1\n", 1, 1, "missing required key 'duration_s' in [run]"},
        {"[vehicle]\nmass_kg = 1\n[run]\nseed = 3\n", 3, 1, "missing required key 'duration_s' in [run]"},
        {"[run]\nkind = differentiator\nduration_s = 1\n", 1, 1, "missing required key 'signal' in [differentiator]"},
        {"[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\n", 4, 1,
         "missing required key 'derivative' in [differentiator]"},
        {"[vehicle]\nmass_kg = 1\n[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\n"
         "signal = t\nderivative = 1\n",
         1, 1, "[vehicle] does not apply to kind = differentiator"},
        {"[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
         "[controller PID]\npid_kp = 1\n",
         7, 1, "[controller PID] does not apply to kind = differentiator"},
        {"[run]\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n", 3, 1,
         "[differentiator] does not apply to kind = attitude"},
        {"[run]\nduration_s = 1\ncontrollers = PID\nkind = differentiator\n[differentiator]\nsignal = t\n"
         "derivative = 1\n",
         3, 1, "'controllers' does not apply to kind = differentiator"},
        {"[run]\nplant_substeps = 2\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\n"
         "derivative = 1\n",
         2, 1, "'plant_substeps' does not apply to kind = differentiator"},
        {"[run]\nduration_s = 0.01\ncontrol_dt_s = 0.02\n", 3, 16,
         "control_dt_s (0.02) must not exceed duration_s (0.01)"},
        {"[run]\nduration_s = 0.0005\n", 2, 14, "control_dt_s (0.001) must not exceed duration_s (0.0005)"},
        {"[metrics]\nerror_window_s = 0 31\n[run]\nduration_s = 30\n", 2, 18,
         "error_window_s ends after the run (duration_s = 30)"},
        {"[run]\nduration_s = 30\n[metrics]\nsteady_window_s = 20 30.5\n", 4, 19,
         "steady_window_s ends after the run (duration_s = 30)"},
        {"[run]\nduration_s = 3\n[metrics]\nsettle_window_s = 0 4\n", 4, 19,
         "settle_window_s ends after the run (duration_s = 3)"},
        /* two of them: the earlier in the file is reported */
        {"[run]\nduration_s = 1\n[metrics]\nsettle_window_s = 0 4\nerror_window_s = 0 2\n", 4, 19,
         "settle_window_s ends after the run (duration_s = 1)"},
        {"[metrics]\nerror_window_s = 0 50\n[run]\nduration_s = 0.004\ncontrol_dt_s = 0.005\n", 2, 18,
         "error_window_s ends after the run (duration_s = 0.004)"},
        {"[run]\nduration_s = 0.004\ncontrol_dt_s = 0.005\n[metrics]\nerror_window_s = 0 50\n", 3, 16,
         "control_dt_s (0.005) must not exceed duration_s (0.004)"},
        /* found by tests/fuzz/fuzz_scenario: [differentiator] has a window too */
        {"[run]\nkind = differentiator\nduration_s = 9\n[differentiator]\nsignal = sin(t)\nderivative = cos(t)\n"
         "error_window_s = 2 10\n",
         7, 18, "error_window_s ends after the run (duration_s = 9)"},
        {"[run]\nduration_s = 1\n[rotors]\nideal = no\n", 4, 9, "ideal = no needs w2_max_rad2_s2"},
        {"[run]\nduration_s = 1\n[rotors]\nw2_max_rad2_s2 = 1e4\nw2_min_rad2_s2 = 2e4\nideal = no\n", 4, 18,
         "w2_max_rad2_s2 must be > w2_min_rad2_s2 (20000)"},
        {"[run]\nduration_s = 1\n[rotors]\nw2_min_rad2_s2 = 1e4\n", 4, 1,
         "'w2_min_rad2_s2' does not apply with ideal = yes"},
        {"[run]\nduration_s = 1\n[rotors]\nideal = yes\nw2_max_rad2_s2 = 1e4\n", 5, 1,
         "'w2_max_rad2_s2' does not apply with ideal = yes"},
        {"[run]\nkind = differentiator\nduration_s = 1\ncontrol_dt_s = 0.01\n[differentiator]\nsignal = t\n"
         "derivative = 1\ntd_h0_s = 0.005\n",
         8, 11, "td_h0_s must be >= control_dt_s (0.01)"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_run_limits_are_errors_at_the_key_responsible(void)
{
    static const bad_case_t cases[] = {
        {"[run]\nduration_s = 1\ncontrol_dt_s = 1e-300\n", 3, 16, "control_dt_s must be between 1e-05 and 0.1"},
        {"[run]\nduration_s = 1\ncontrol_dt_s = 9.9e-6\n", 3, 16, "control_dt_s must be between 1e-05 and 0.1"},
        {"[run]\nduration_s = 1\ncontrol_dt_s = 0.11\n", 3, 16, "control_dt_s must be between 1e-05 and 0.1"},
        {"[run]\nduration_s = 1e9\n", 2, 14, "duration_s must be > 0 and at most 100000"},
        {"[run]\nduration_s = 100000.1\n", 2, 14, "duration_s must be > 0 and at most 100000"},
        {"[run]\nduration_s = 1\nplant_substeps = 1000000000\n", 3, 18, "plant_substeps must be between 1 and 1000"},
        {"[run]\nduration_s = 1\nplant_substeps = 1001\n", 3, 18, "plant_substeps must be between 1 and 1000"},
        {"[run]\nduration_s = 1e5\ncontrol_dt_s = 1e-4\n", 3, 16,
         "the run takes 1e+09 control periods (duration_s / control_dt_s), more than 1e+08"},
        {"[run]\nkind = differentiator\nduration_s = 2000\ncontrol_dt_s = 1e-5\n[differentiator]\nsignal = t\n"
         "derivative = 1\n",
         4, 16, "the run takes 2e+08 control periods (duration_s / control_dt_s), more than 1e+08"},
        {"[run]\nduration_s = 10000\nplant_substeps = 1000\n", 3, 18,
         "the run takes 1e+10 plant steps (duration_s / control_dt_s x plant_substeps), more than 1e+09"},
        {"[run]\nplant_substeps = 200\nduration_s = 10000\ncontrol_dt_s = 0.001\n", 2, 18,
         "the run takes 2e+09 plant steps (duration_s / control_dt_s x plant_substeps), more than 1e+09"},
        /* the plant step against the plant's time constants */
        {"[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 1e-5\n", 4, 15,
         "the plant step control_dt_s / plant_substeps (0.0001 s) is longer than motor_tau_s (1e-05 s): "
         "plant_substeps must be at least 100"},
        {"[run]\nduration_s = 1\ncontrol_dt_s = 0.1\nplant_substeps = 1\n", 4, 18,
         "the plant step control_dt_s / plant_substeps (0.1 s) is longer than the drag time constant J / "
         "rot_drag_Nm_s (0.0605 s): plant_substeps must be at least 2"},
        {"[run]\nduration_s = 1\ncontrol_dt_s = 0.1\n[rotors]\nmotor_tau_s = 1e-5\n", 3, 16,
         "the plant step control_dt_s / plant_substeps (0.01 s) is longer than motor_tau_s (1e-05 s): "
         "more than 1000 plant_substeps would be needed"},
        {"[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 100\n", 4, 17,
         "the plant step control_dt_s / plant_substeps (0.0001 s) is longer than the drag time constant J / "
         "rot_drag_Nm_s (5.445e-05 s): plant_substeps must be at least 19"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_runs_at_the_limits_are_accepted(void)
{
    parse_ok("[run]\nduration_s = 1\ncontrol_dt_s = 1e-5\nplant_substeps = 1000\n");
    parse_ok("[run]\nduration_s = 1e5\n"); /* 1e8 control periods, 1e9 plant steps */
    TEST_ASSERT_EQUAL_INT(4, sc.n_controllers);
    /* at 10 Hz PID only: LADRC's default wc = 15 rad/s needs wc dt < 1 */
    parse_ok("[run]\nduration_s = 1\ncontrol_dt_s = 0.1\nplant_substeps = 2\ncontrollers = PID\n");
    parse_ok("[run]\nduration_s = 1\ncontrol_dt_s = 0.005\n");         /* every controller at 200 Hz */
    parse_ok("[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 1e-4\n"); /* plant step = the lag */
    parse_ok("[run]\nkind = differentiator\nduration_s = 1\ncontrol_dt_s = 0.1\n[differentiator]\nsignal = t\n"
             "derivative = 1\n");
}

/* What the library refuses: message from ladrc_status_str, at the key. */
typedef struct {
    const char *text;
    int line;
    int column;
    const char *who;
    ladrc_status_t status;
} refused_case_t;

static void test_values_the_library_refuses_are_errors_at_their_key(void)
{
    static const refused_case_t cases[] = {
        /* the modified variants' estimators need a faster loop than 20 Hz */
        {"[run]\nduration_s = 1\ncontrol_dt_s = 0.05\n", 3, 16, "HP-MLADRC", LADRC_ERR_HP_FIT_DECIMATION},
        {"[run]\nduration_s = 1\ncontrol_dt_s = 0.02\ncontrollers = LP-MLADRC\n", 3, 16, "LP-MLADRC",
         LADRC_ERR_RLS_LAMBDA0},
        /* what the controllers assume underflows even in double */
        {"[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 0\ninertia_kg_m2 = 1 1e-200 1\n[mismatch]\n"
         "inertia_scale = 1 1e-200 1\n",
         5, 17, "HP-MLADRC", LADRC_ERR_INERTIA_KG_M2},
#if !defined(LADRC_REAL_DOUBLE)
        /* values that leave float's range on the way to the library */
        {"[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 0\ninertia_kg_m2 = 1 1e-50 1\n", 5, 17, "HP-MLADRC",
         LADRC_ERR_INERTIA_KG_M2},
        {"[run]\nduration_s = 1\n[mismatch]\ninertia_scale = 1 1 1e-45\n", 4, 17, "HP-MLADRC", LADRC_ERR_INERTIA_KG_M2},
        {"[run]\nduration_s = 1\n[controller PID]\npid_kp = 1e39\n", 4, 10, "PID", LADRC_ERR_PID_KP},
        {"[run]\nduration_s = 1\n[controller LADRC]\nwc_rad_s = 1e-50\n", 4, 12, "LADRC", LADRC_ERR_WC_RAD_S},
        {"[run]\nduration_s = 1\n[controller LADRC]\ntd_accel_rad_s2 = 1e39\n", 4, 19, "LADRC",
         LADRC_ERR_TD_ACCEL_RAD_S2},
        {"[run]\nduration_s = 1\n[controller LP-MLADRC]\nlevant_lipschitz_rad_s4 = 1e-40\n", 4, 27, "LP-MLADRC",
         LADRC_ERR_LEVANT_RANGE},
        {"[run]\nduration_s = 1\n[rotors]\nideal = no\nw2_max_rad2_s2 = 1e40\n", 5, 18, "the mixer",
         LADRC_ERR_MIXER_W2_MAX},
        {"[run]\nduration_s = 1\n[vehicle]\nmass_kg = 1e39\n", 4, 11, "the mixer", LADRC_ERR_MIXER_MASS_KG},
        {"[run]\nduration_s = 1\n[vehicle]\nyaw_coeff_Nm_s2 = 1e-46\n", 4, 19, "the mixer", LADRC_ERR_MIXER_B_NM_S2},
        {"[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
         "levant_lipschitz_rad_s4 = 1e-40\n",
         7, 27, "Levant's differentiator", LADRC_ERR_LEVANT_RANGE},
        {"[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
         "td_accel_rad_s2 = 1e39\n",
         7, 19, "the tracking differentiator", LADRC_ERR_TD_ACCEL_RAD_S2},
#endif
        /* actuator models the library does not take: at the key that sets them */
        {"[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 2\n", 4, 15, "HP-MLADRC", LADRC_ERR_MOTOR_TAU_S},
        {"[run]\nduration_s = 1\n[sensors]\ndelay_ticks = 9\n", 4, 15, "HP-MLADRC", LADRC_ERR_DELAY_TICKS},
        {"[run]\nduration_s = 1\n[controller LADRC]\nmodel_delay_ticks = 12\n", 4, 21, "LADRC", LADRC_ERR_DELAY_TICKS},
        {"[run]\nduration_s = 1\n[controller LP-MLADRC]\nmodel_motor_tau_s = 1.5\n", 4, 21, "LP-MLADRC",
         LADRC_ERR_MOTOR_TAU_S},
        /* INDI's gains beyond the sampled loop's bound, its filter beyond Nyquist */
        {"[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_rate_kp_per_s = 1000\n", 5, 22, "INDI",
         LADRC_ERR_INDI_RATE_KP},
        {"[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_att_kp_per_s = 2000\n", 5, 21, "INDI",
         LADRC_ERR_INDI_ATT_KP},
        {"[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_filter_rad_s = 4000\n", 5, 21, "INDI",
         LADRC_ERR_INDI_FILTER},
        /* CASCADED's gains: at their key */
        {"[run]\nduration_s = 1\ncontrollers = CASCADED\n[controller CASCADED]\ncas_att_kp = 2000\n", 5, 14, "CASCADED",
         LADRC_ERR_CAS_ATT_KP},
        {"[run]\nduration_s = 1\ncontrollers = LADRC CASCADED\n[controller CASCADED]\ncas_rate_max_deg_s = 6000\n", 5,
         22, "CASCADED", LADRC_ERR_CAS_RATE_MAX},
        /* combinations */
        {"[run]\nduration_s = 1\n[controller LADRC]\nleso_method = euler\nwo_rad_s = 3000\n", 5, 12, "LADRC",
         LADRC_ERR_LESO_EULER_UNSTABLE},
        {"[run]\nduration_s = 1\n[controller HP-MLADRC]\nhp_freq_rad_s = 5000\n", 4, 17, "HP-MLADRC",
         LADRC_ERR_HP_FREQ_RAD_S},
        {"[run]\nduration_s = 1\n[controller HP-MLADRC]\nhp_freq_mode = known\nhp_freq_rad_s = 500\n", 5, 17,
         "HP-MLADRC", LADRC_ERR_HP_FIT_DECIMATION},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const refused_case_t *c = &cases[i];
        char what[400], message[300];
        snprintf(what, sizeof what, "case %u <<%s>>", (unsigned)i, c->text);
        snprintf(message, sizeof message, "%s does not start: %s", c->who, ladrc_status_str(c->status));
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_scenario_parse(&sc, c->text, "bad.ini", &err), what);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(message, err.message, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->line, err.line, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->column, err.column, what);
    }
}

static void test_a_controller_not_listed_is_checked_when_chosen(void)
{
    /* HP-MLADRC cannot run at 20 Hz; the file does not ask for it */
    parse_ok("[run]\nduration_s = 1\ncontrol_dt_s = 0.05\ncontrollers = PID LADRC\n");
    TEST_ASSERT_EQUAL_INT(0, sc.controller_error[SIM_CTRL_PID].line);
    TEST_ASSERT_EQUAL_INT(3, sc.controller_error[SIM_CTRL_HP_MLADRC].line);

    const sim_controller_id_t pid_hp[] = {SIM_CTRL_PID, SIM_CTRL_HP_MLADRC};
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, pid_hp, 2, &err));
    TEST_ASSERT_EQUAL_STRING("dir/test.ini", err.path);
    TEST_ASSERT_EQUAL_INT(3, err.line);
    TEST_ASSERT_EQUAL_INT(16, err.column);
    char message[300];
    snprintf(message, sizeof message, "HP-MLADRC does not start: %s", ladrc_status_str(LADRC_ERR_HP_FIT_DECIMATION));
    TEST_ASSERT_EQUAL_STRING(message, err.message);
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers); /* unchanged */
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, sc.controllers[0]);

    const sim_controller_id_t ladrc_only[] = {SIM_CTRL_LADRC};
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_set_controllers(&sc, ladrc_only, 1, &err));
    TEST_ASSERT_EQUAL_INT(1, sc.n_controllers);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_LADRC, sc.controllers[0]);

    const sim_controller_id_t twice[] = {SIM_CTRL_PID, SIM_CTRL_PID};
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, twice, 2, &err));
    TEST_ASSERT_EQUAL_STRING("controller 'PID' listed twice", err.message);
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, ladrc_only, 0, &err));
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(NULL, ladrc_only, 1, NULL));
    const sim_controller_id_t unknown[] = {SIM_CTRL_COUNT};
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, unknown, 1, &err));
    TEST_ASSERT_EQUAL_INT(1, sc.n_controllers);
}

static void test_parse_buffer_needs_no_nul_and_refuses_one_inside(void)
{
    static const char text[] = "[run]\nduration_s = 7\nseed = 3";
    /* without its last byte: seed = 3 still parses, as "seed = " would not */
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_parse_buffer(&sc, text, sizeof text - 1, "buf.ini", &err));
    assert_close(7.0, sc.duration_s, "duration_s");
    TEST_ASSERT_TRUE(sc.seed == 3u);
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse_buffer(&sc, text, sizeof text - 2, "buf.ini", &err));
    TEST_ASSERT_EQUAL_STRING("missing value for 'seed'", err.message);
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse_buffer(&sc, text, sizeof text, "buf.ini", &err));
    TEST_ASSERT_EQUAL_STRING("unexpected NUL byte", err.message);
    TEST_ASSERT_EQUAL_INT(3, err.line);
    TEST_ASSERT_EQUAL_INT(9, err.column);
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse_buffer(&sc, "", 0, "buf.ini", &err));
    TEST_ASSERT_EQUAL_STRING("missing required key 'duration_s' in [run]", err.message);
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse_buffer(&sc, NULL, 0, "buf.ini", &err));
}

static void test_long_values_are_rejected_not_truncated(void)
{
    static char text[2048];
    strcpy(text, "[run]\nduration_s = 1\noutput_dir = ");
    for (int i = 0; i < SIM_PATH_LEN; ++i) {
        strcat(text, "a");
    }
    strcat(text, "\n");
    const bad_case_t cases[] = {{text, 3, 14, "output_dir longer than 511 characters"}};
    CHECK_BAD_CASES(cases);
}

static void test_null_arguments_are_refused_and_err_is_optional(void)
{
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(NULL, "[run]\nduration_s = 1\n", "x.ini", &err));
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, NULL, "x.ini", &err));
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_load(&sc, NULL, &err));
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_parse(&sc, "[run]\nduration_s = 1\n", "x.ini", NULL));
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, "[run]\n", "x.ini", NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_structure_errors);
    RUN_TEST(test_value_errors);
    RUN_TEST(test_signal_errors_point_into_the_expression);
    RUN_TEST(test_errors_checked_after_the_whole_file);
    RUN_TEST(test_run_limits_are_errors_at_the_key_responsible);
    RUN_TEST(test_runs_at_the_limits_are_accepted);
    RUN_TEST(test_values_the_library_refuses_are_errors_at_their_key);
    RUN_TEST(test_a_controller_not_listed_is_checked_when_chosen);
    RUN_TEST(test_parse_buffer_needs_no_nul_and_refuses_one_inside);
    RUN_TEST(test_long_values_are_rejected_not_truncated);
    RUN_TEST(test_null_arguments_are_refused_and_err_is_optional);
    return UNITY_END();
}
