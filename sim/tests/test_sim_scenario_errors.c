/* SPDX-License-Identifier: BSD-3-Clause */
/* Scenario files, malformed: each error with its line, column and message,
 * the checks across keys after the whole file, the run's limits, what the
 * library refuses at the key responsible, the arguments refused. */
#include "unity.h"
#include "scenario_cases.h"

static void test_structure_errors(void)
{
    static const bad_case_t cases[] = {
        {.text = "[runn]\n", .line = 1, .column = 2, .message = "unknown section [runn]"},
        {.text = "[run\nduration_s = 1\n", .line = 1, .column = 5, .message = "expected ']'"},
        {.text = "[run] x\n", .line = 1, .column = 7, .message = "trailing characters after ']'"},
        {.text = "[ ]\n", .line = 1, .column = 3, .message = "expected a section name"},
        {.text = "[run extra]\n", .line = 1, .column = 6, .message = "unexpected 'extra' in the section header"},
        {.text = "[controller]\n", .line = 1, .column = 12, .message = "expected a controller name after 'controller'"},
        {.text = "[controller PDI]\n",
         .line = 1,
         .column = 13,
         .message = "unknown controller 'PDI' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {.text = "[controller PID PID]\n",
         .line = 1,
         .column = 17,
         .message = "unexpected 'PID' in the section header"},
        {.text = "[run]\nduration_s = 1\n\n[run]\n",
         .line = 4,
         .column = 1,
         .message = "section [run] already given on line 1"},
        {.text = "[run]\nduration_s = 1\n[controller PID]\n[controller PID]\n",
         .line = 4,
         .column = 1,
         .message = "section [controller PID] already given on line 3"},
        {.text = "# top\nduration_s = 1\n", .line = 2, .column = 1, .message = "key 'duration_s' before any [section]"},
        {.text = "[run]\nduraton_s = 3\n", .line = 2, .column = 1, .message = "unknown key 'duraton_s' in [run]"},
        {.text = "[vehicle]\n  mass = 3\n", .line = 2, .column = 3, .message = "unknown key 'mass' in [vehicle]"},
        {.text = "[controller LADRC]\nkp = 3\n",
         .line = 2,
         .column = 1,
         .message = "unknown key 'kp' in [controller LADRC]"},
        {.text = "[run]\nduration_s 3\n", .line = 2, .column = 12, .message = "expected '=' after 'duration_s'"},
        {.text = "[run]\nduration-s = 3\n", .line = 2, .column = 9, .message = "expected '=' after 'duration'"},
        {.text = "[run]\nduration_s =\n", .line = 2, .column = 13, .message = "missing value for 'duration_s'"},
        {.text = "[run]\nduration_s =   # nothing\n",
         .line = 2,
         .column = 13,
         .message = "missing value for 'duration_s'"},
        {.text = "[run]\n= 3\n", .line = 2, .column = 1, .message = "expected a key or a [section]"},
        {.text = "[run]\nduration_s = 1\nseed = 1\nduration_s = 2\n",
         .line = 4,
         .column = 1,
         .message = "duplicate key 'duration_s' (first given on line 2)"},
        {.text = "[run]\nduration_s = 1\n[sensors]\nangle_noise_std_deg = 0.1\nangle_noise_var_deg2 = 0.01\n",
         .line = 5,
         .column = 1,
         .message = "'angle_noise_var_deg2' and 'angle_noise_std_deg' (line 4) set the same value"},
        {.text = "[run]\nduration_s = 1\n[sensors]\nrate_noise_var_deg2_s2 = 1\nrate_noise_std_deg_s = 1\n",
         .line = 5,
         .column = 1,
         .message = "'rate_noise_std_deg_s' and 'rate_noise_var_deg2_s2' (line 4) set the same value"},
        {.text = "[controller LADRC]\npid_kp = 1\n",
         .line = 2,
         .column = 1,
         .message = "'pid_kp' does not apply to LADRC"},
        {.text = "[controller PID]\nwc_rad_s = 1\n",
         .line = 2,
         .column = 1,
         .message = "'wc_rad_s' does not apply to PID"},
        {.text = "[controller LP-MLADRC]\nhp_freq_mode = known\n",
         .line = 2,
         .column = 1,
         .message = "'hp_freq_mode' does not apply to LP-MLADRC"},
        {.text = "[controller LADRC]\nlevant_lipschitz_rad_s4 = 1\n",
         .line = 2,
         .column = 1,
         .message = "'levant_lipschitz_rad_s4' does not apply to LADRC"},
        {.text = "[controller HP-MLADRC]\ntd_accel_rad_s2 = 1\n",
         .line = 2,
         .column = 1,
         .message = "'td_accel_rad_s2' does not apply to HP-MLADRC"},
        {.text = "[controller PID]\ncoupling_feed = no\n",
         .line = 2,
         .column = 1,
         .message = "'coupling_feed' does not apply to PID"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_value_errors(void)
{
    static const bad_case_t cases[] = {
        {.text = "[run]\nduration_s = 3x\n", .line = 2, .column = 14, .message = "expected a number, got '3x'"},
        {.text = "[run]\nduration_s = 3 4\n", .line = 2, .column = 16, .message = "expected a single number"},
        {.text = "[run]\nduration_s = abc\n", .line = 2, .column = 14, .message = "expected a number, got 'abc'"},
        {.text = "[run]\nduration_s = -\n", .line = 2, .column = 14, .message = "expected a number, got '-'"},
        {.text = "[run]\nduration_s = 0x10\n", .line = 2, .column = 14, .message = "expected a number, got '0x10'"},
        {.text = "[run]\nduration_s = inf\n", .line = 2, .column = 14, .message = "expected a number, got 'inf'"},
        {.text = "[run]\nduration_s = 1e999\n", .line = 2, .column = 14, .message = "number out of range"},
        {.text = "[run]\nduration_s = -1\n",
         .line = 2,
         .column = 14,
         .message = "duration_s must be > 0 and at most 100000"},
        {.text = "[run]\nduration_s = 0\n",
         .line = 2,
         .column = 14,
         .message = "duration_s must be > 0 and at most 100000"},
        {.text = "[run]\ncontrol_dt_s = 0\n",
         .line = 2,
         .column = 16,
         .message = "control_dt_s must be between 1e-05 and 0.1"},
        {.text = "[run]\ncontrol_dt_s = -1e-3\n",
         .line = 2,
         .column = 16,
         .message = "control_dt_s must be between 1e-05 and 0.1"},
        {.text = "[run]\nplant_substeps = 0\n",
         .line = 2,
         .column = 18,
         .message = "plant_substeps must be between 1 and 1000"},
        {.text = "[run]\nplant_substeps = 2.5\n", .line = 2, .column = 18, .message = "expected an integer, got '2.5'"},
        {.text = "[run]\nplant_substeps = 2 3\n",
         .line = 2,
         .column = 20,
         .message = "expected a single integer, got '3'"},
        {.text = "[run]\nplant_substeps = 99999999999\n", .line = 2, .column = 18, .message = "number out of range"},
        {.text = "[run]\nseed = -1\n", .line = 2, .column = 8, .message = "expected an unsigned integer, got '-1'"},
        {.text = "[run]\nseed = 18446744073709551616\n",
         .line = 2,
         .column = 8,
         .message = "seed out of range (at most 18446744073709551615)"},
        {.text = "[run]\nkind = attitud\n",
         .line = 2,
         .column = 8,
         .message = "expected attitude or differentiator, got 'attitud'"},
        {.text = "[run]\ncontrollers = LADRC PDI\n",
         .line = 2,
         .column = 21,
         .message = "unknown controller 'PDI' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {.text = "[run]\ncontrollers = ladrc\n",
         .line = 2,
         .column = 15,
         .message = "unknown controller 'ladrc' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
        {.text = "[run]\ncontrollers = LADRC PID LADRC\n",
         .line = 2,
         .column = 25,
         .message = "controller 'LADRC' listed twice"},
        {.text = "[vehicle]\ninertia_kg_m2 = 1 2\n", .line = 2, .column = 20, .message = "expected 3 numbers"},
        {.text = "[vehicle]\ninertia_kg_m2 = 1 2 3 4\n", .line = 2, .column = 23, .message = "expected 3 numbers"},
        {.text = "[vehicle]\ninertia_kg_m2 = 1 -2 3\n",
         .line = 2,
         .column = 19,
         .message = "inertia_kg_m2 must be > 0"},
        {.text = "[vehicle]\nmass_kg = 0\n", .line = 2, .column = 11, .message = "mass_kg must be > 0"},
        {.text = "[vehicle]\nrot_drag_Nm_s = -0.1\n", .line = 2, .column = 17, .message = "rot_drag_Nm_s must be >= 0"},
        {.text = "[rotors]\nideal = maybe\n", .line = 2, .column = 9, .message = "expected yes or no, got 'maybe'"},
        {.text = "[rotors]\nideal = yes no\n", .line = 2, .column = 13, .message = "expected yes or no, got 'no'"},
        {.text = "[rotors]\nmotor_tau_s = -0.02\n", .line = 2, .column = 15, .message = "motor_tau_s must be >= 0"},
        {.text = "[rotors]\ntilt_max_deg = 90\n",
         .line = 2,
         .column = 16,
         .message = "tilt_max_deg must be > 0 and < 90"},
        {.text = "[sensors]\nangle_noise_std_deg = -0.1\n",
         .line = 2,
         .column = 23,
         .message = "angle_noise_std_deg must be >= 0"},
        {.text = "[sensors]\nangle_noise_var_deg2 = -1e-3\n",
         .line = 2,
         .column = 24,
         .message = "angle_noise_var_deg2 must be >= 0"},
        {.text = "[sensors]\ndelay_ticks = 513\n",
         .line = 2,
         .column = 15,
         .message = "delay_ticks must be between 0 and 512"},
        {.text = "[sensors]\ndelay_ticks = -1\n",
         .line = 2,
         .column = 15,
         .message = "delay_ticks must be between 0 and 512"},
        {.text = "[mismatch]\ninertia_scale = 1 1 0\n",
         .line = 2,
         .column = 21,
         .message = "inertia_scale must be > 0"},
        {.text = "[metrics]\nerror_window_s = 5 5\n",
         .line = 2,
         .column = 18,
         .message = "error_window_s: window start must be before its end"},
        {.text = "[metrics]\nsteady_window_s = 6 5\n",
         .line = 2,
         .column = 19,
         .message = "steady_window_s: window start must be before its end"},
        {.text = "[metrics]\nsettle_window_s = -1 5\n",
         .line = 2,
         .column = 19,
         .message = "settle_window_s must start at or after 0"},
        {.text = "[metrics]\nerror_window_s = 5\n", .line = 2, .column = 19, .message = "expected two numbers FROM TO"},
        {.text = "[metrics]\nerror_window_s = 1 2 3\n",
         .line = 2,
         .column = 22,
         .message = "expected two numbers FROM TO"},
        {.text = "[metrics]\nsettle_band_deg = 0\n", .line = 2, .column = 19, .message = "settle_band_deg must be > 0"},
        {.text = "[controller LADRC]\nwc_rad_s = 0\n", .line = 2, .column = 12, .message = "wc_rad_s must be > 0"},
        {.text = "[controller LADRC]\nleso_method = rk4\n",
         .line = 2,
         .column = 15,
         .message = "expected zoh or euler, got 'rk4'"},
        {.text = "[controller HP-MLADRC]\nhp_freq_mode = guess\n",
         .line = 2,
         .column = 16,
         .message = "expected known or online, got 'guess'"},
        {.text = "[controller PID]\npid_kd = -0.05\n", .line = 2, .column = 10, .message = "pid_kd must be >= 0"},
        {.text = "[differentiator]\nnoise_var = -1\n", .line = 2, .column = 13, .message = "noise_var must be >= 0"},
        {.text = "[differentiator]\ntd_h0_s = 0\n", .line = 2, .column = 11, .message = "td_h0_s must be > 0"},
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
        {.text = "[reference]\nroll = 5 + sn(t)\n", .line = 2, .column = 12, .message = "unknown function 'sn'"},
        {.text = "[reference]\n  roll =\t5 + 15*cos(pi*t/2\n", .line = 2, .column = 27, .message = "expected ')'"},
        {.text = "[reference]\nroll = 5 +\n", .line = 2, .column = 11, .message = "expected a number, name or '('"},
        {.text = "[reference]\nroll = 5 5\n", .line = 2, .column = 10, .message = "trailing characters"},
        {.text = "[disturbance]\nroll = 2 .. 6 : 8 +\n",
         .line = 2,
         .column = 20,
         .message = "expected a number, name or '('"},
        {.text = "[disturbance]\nroll = 2 .. 6 :   x\n", .line = 2, .column = 19, .message = "unknown name 'x'"},
        {.text = "[disturbance]\nroll = 2 .. 6 :\n",
         .line = 2,
         .column = 16,
         .message = "expected an expression after ':'"},
        {.text = "[disturbance]\nroll = 6 .. 2 : 1\n",
         .line = 2,
         .column = 8,
         .message = "window start must be before its end"},
        {.text = "[disturbance]\nroll = 2 .. 2 : 1\n",
         .line = 2,
         .column = 8,
         .message = "window start must be before its end"},
        {.text = "[disturbance]\nroll = 2 .. x : 1\n",
         .line = 2,
         .column = 13,
         .message = "expected a number, got 'x'"},
        {.text = "[disturbance]\nroll = 2 3 .. 4 : 1\n",
         .line = 2,
         .column = 8,
         .message = "expected a number, got '2 3'"},
        {.text = "[disturbance]\nroll = 2 : 1\n",
         .line = 2,
         .column = 8,
         .message = "expected 'FROM .. TO' before ':'"},
        {.text = "[disturbance]\nroll = 2 .. 6 1\n",
         .line = 2,
         .column = 10,
         .message = "expected ':' between the window and the expression"},
        {.text = "[disturbance]\nroll = 2 .. 6 : 1\nroll = 5 .. 8 : 2\n",
         .line = 3,
         .column = 8,
         .message = "window (5, 8] overlaps the one given on line 2"},
        {.text = "[disturbance]\nroll = 1\nroll = 5 .. 8 : 2\n",
         .line = 3,
         .column = 8,
         .message = "window (5, 8] overlaps the one given on line 2"},
        {.text = "[disturbance]\nroll = 5 .. 8 : 2\nroll = 1\n",
         .line = 3,
         .column = 8,
         .message = "window (-inf, inf] overlaps the one given on line 2"},
        {.text = "[disturbance]\nroll = .. 6 : 2\nroll = 5 .. : 1\n",
         .line = 3,
         .column = 8,
         .message = "window (5, inf] overlaps the one given on line 2"},
        {.text = nine_pieces, .line = 10, .column = 1, .message = "more than 8 pieces for 'yaw'"},
        {.text = too_long, .line = 2, .column = 103, .message = "expression too long"},
        {.text = "[differentiator]\nsignal = sin(t\n", .line = 2, .column = 15, .message = "expected ')'"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_errors_checked_after_the_whole_file(void)
{
    static const bad_case_t cases[] = {
        {.text = "", .line = 1, .column = 1, .message = "missing required key 'duration_s' in [run]"},
        {.text = "[vehicle]\nmass_kg = 1\n",
         .line = 1,
         .column = 1,
         .message = "missing required key 'duration_s' in [run]"},
        {.text = "[vehicle]\nmass_kg = 1\n[run]\nseed = 3\n",
         .line = 3,
         .column = 1,
         .message = "missing required key 'duration_s' in [run]"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n",
         .line = 1,
         .column = 1,
         .message = "missing required key 'signal' in [differentiator]"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\n",
         .line = 4,
         .column = 1,
         .message = "missing required key 'derivative' in [differentiator]"},
        {.text = "[vehicle]\nmass_kg = 1\n[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\n"
                 "signal = t\nderivative = 1\n",
         .line = 1,
         .column = 1,
         .message = "[vehicle] does not apply to kind = differentiator"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
                 "[controller PID]\npid_kp = 1\n",
         .line = 7,
         .column = 1,
         .message = "[controller PID] does not apply to kind = differentiator"},
        {.text = "[run]\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n",
         .line = 3,
         .column = 1,
         .message = "[differentiator] does not apply to kind = attitude"},
        {.text = "[run]\nduration_s = 1\ncontrollers = PID\nkind = differentiator\n[differentiator]\nsignal = t\n"
                 "derivative = 1\n",
         .line = 3,
         .column = 1,
         .message = "'controllers' does not apply to kind = differentiator"},
        {.text = "[run]\nplant_substeps = 2\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\n"
                 "derivative = 1\n",
         .line = 2,
         .column = 1,
         .message = "'plant_substeps' does not apply to kind = differentiator"},
        {.text = "[run]\nduration_s = 0.01\ncontrol_dt_s = 0.02\n",
         .line = 3,
         .column = 16,
         .message = "control_dt_s (0.02) must not exceed duration_s (0.01)"},
        {.text = "[run]\nduration_s = 0.0005\n",
         .line = 2,
         .column = 14,
         .message = "control_dt_s (0.001) must not exceed duration_s (0.0005)"},
        {.text = "[metrics]\nerror_window_s = 0 31\n[run]\nduration_s = 30\n",
         .line = 2,
         .column = 18,
         .message = "error_window_s ends after the run (duration_s = 30)"},
        {.text = "[run]\nduration_s = 30\n[metrics]\nsteady_window_s = 20 30.5\n",
         .line = 4,
         .column = 19,
         .message = "steady_window_s ends after the run (duration_s = 30)"},
        {.text = "[run]\nduration_s = 3\n[metrics]\nsettle_window_s = 0 4\n",
         .line = 4,
         .column = 19,
         .message = "settle_window_s ends after the run (duration_s = 3)"},
        /* two of them: the earlier in the file is reported */
        {.text = "[run]\nduration_s = 1\n[metrics]\nsettle_window_s = 0 4\nerror_window_s = 0 2\n",
         .line = 4,
         .column = 19,
         .message = "settle_window_s ends after the run (duration_s = 1)"},
        {.text = "[metrics]\nerror_window_s = 0 50\n[run]\nduration_s = 0.004\ncontrol_dt_s = 0.005\n",
         .line = 2,
         .column = 18,
         .message = "error_window_s ends after the run (duration_s = 0.004)"},
        {.text = "[run]\nduration_s = 0.004\ncontrol_dt_s = 0.005\n[metrics]\nerror_window_s = 0 50\n",
         .line = 3,
         .column = 16,
         .message = "control_dt_s (0.005) must not exceed duration_s (0.004)"},
        /* found by tests/fuzz/fuzz_scenario: [differentiator] has a window too */
        {.text =
             "[run]\nkind = differentiator\nduration_s = 9\n[differentiator]\nsignal = sin(t)\nderivative = cos(t)\n"
             "error_window_s = 2 10\n",
         .line = 7,
         .column = 18,
         .message = "error_window_s ends after the run (duration_s = 9)"},
        {.text = "[run]\nduration_s = 1\n[rotors]\nideal = no\n",
         .line = 4,
         .column = 9,
         .message = "ideal = no needs w2_max_rad2_s2"},
        {.text = "[run]\nduration_s = 1\n[rotors]\nw2_max_rad2_s2 = 1e4\nw2_min_rad2_s2 = 2e4\nideal = no\n",
         .line = 4,
         .column = 18,
         .message = "w2_max_rad2_s2 must be > w2_min_rad2_s2 (20000)"},
        {.text = "[run]\nduration_s = 1\n[rotors]\nw2_min_rad2_s2 = 1e4\n",
         .line = 4,
         .column = 1,
         .message = "'w2_min_rad2_s2' does not apply with ideal = yes"},
        {.text = "[run]\nduration_s = 1\n[rotors]\nideal = yes\nw2_max_rad2_s2 = 1e4\n",
         .line = 5,
         .column = 1,
         .message = "'w2_max_rad2_s2' does not apply with ideal = yes"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\ncontrol_dt_s = 0.01\n[differentiator]\nsignal = t\n"
                 "derivative = 1\ntd_h0_s = 0.005\n",
         .line = 8,
         .column = 11,
         .message = "td_h0_s must be >= control_dt_s (0.01)"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_run_limits_are_errors_at_the_key_responsible(void)
{
    static const bad_case_t cases[] = {
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 1e-300\n",
         .line = 3,
         .column = 16,
         .message = "control_dt_s must be between 1e-05 and 0.1"},
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 9.9e-6\n",
         .line = 3,
         .column = 16,
         .message = "control_dt_s must be between 1e-05 and 0.1"},
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 0.11\n",
         .line = 3,
         .column = 16,
         .message = "control_dt_s must be between 1e-05 and 0.1"},
        {.text = "[run]\nduration_s = 1e9\n",
         .line = 2,
         .column = 14,
         .message = "duration_s must be > 0 and at most 100000"},
        {.text = "[run]\nduration_s = 100000.1\n",
         .line = 2,
         .column = 14,
         .message = "duration_s must be > 0 and at most 100000"},
        {.text = "[run]\nduration_s = 1\nplant_substeps = 1000000000\n",
         .line = 3,
         .column = 18,
         .message = "plant_substeps must be between 1 and 1000"},
        {.text = "[run]\nduration_s = 1\nplant_substeps = 1001\n",
         .line = 3,
         .column = 18,
         .message = "plant_substeps must be between 1 and 1000"},
        {.text = "[run]\nduration_s = 1e5\ncontrol_dt_s = 1e-4\n",
         .line = 3,
         .column = 16,
         .message = "the run takes 1e+09 control periods (duration_s / control_dt_s), more than 1e+08"},
        {.text = "[run]\nkind = differentiator\nduration_s = 2000\ncontrol_dt_s = 1e-5\n[differentiator]\nsignal = t\n"
                 "derivative = 1\n",
         .line = 4,
         .column = 16,
         .message = "the run takes 2e+08 control periods (duration_s / control_dt_s), more than 1e+08"},
        {.text = "[run]\nduration_s = 10000\nplant_substeps = 1000\n",
         .line = 3,
         .column = 18,
         .message = "the run takes 1e+10 plant steps (duration_s / control_dt_s x plant_substeps), more than 1e+09"},
        {.text = "[run]\nplant_substeps = 200\nduration_s = 10000\ncontrol_dt_s = 0.001\n",
         .line = 2,
         .column = 18,
         .message = "the run takes 2e+09 plant steps (duration_s / control_dt_s x plant_substeps), more than 1e+09"},
        /* the plant step against the plant's time constants */
        {.text = "[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 1e-5\n",
         .line = 4,
         .column = 15,
         .message = "the plant step control_dt_s / plant_substeps (0.0001 s) is longer than motor_tau_s (1e-05 s): "
                    "plant_substeps must be at least 100"},
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 0.1\nplant_substeps = 1\n",
         .line = 4,
         .column = 18,
         .message = "the plant step control_dt_s / plant_substeps (0.1 s) is longer than the drag time constant J / "
                    "rot_drag_Nm_s (0.0605 s): plant_substeps must be at least 2"},
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 0.1\n[rotors]\nmotor_tau_s = 1e-5\n",
         .line = 3,
         .column = 16,
         .message = "the plant step control_dt_s / plant_substeps (0.01 s) is longer than motor_tau_s (1e-05 s): "
                    "more than 1000 plant_substeps would be needed"},
        {.text = "[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 100\n",
         .line = 4,
         .column = 17,
         .message = "the plant step control_dt_s / plant_substeps (0.0001 s) is longer than the drag time constant J / "
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
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 0.05\n",
         .line = 3,
         .column = 16,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_HP_FIT_DECIMATION},
        {.text = "[run]\nduration_s = 1\ncontrol_dt_s = 0.02\ncontrollers = LP-MLADRC\n",
         .line = 3,
         .column = 16,
         .who = "LP-MLADRC",
         .status = LADRC_ERR_RLS_LAMBDA0},
        /* what the controllers assume underflows even in double */
        {.text = "[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 0\ninertia_kg_m2 = 1 1e-200 1\n[mismatch]\n"
                 "inertia_scale = 1 1e-200 1\n",
         .line = 5,
         .column = 17,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_INERTIA_KG_M2},
#if !defined(LADRC_REAL_DOUBLE)
        /* values that leave float's range on the way to the library */
        {.text = "[run]\nduration_s = 1\n[vehicle]\nrot_drag_Nm_s = 0\ninertia_kg_m2 = 1 1e-50 1\n",
         .line = 5,
         .column = 17,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_INERTIA_KG_M2},
        {.text = "[run]\nduration_s = 1\n[mismatch]\ninertia_scale = 1 1 1e-45\n",
         .line = 4,
         .column = 17,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_INERTIA_KG_M2},
        {.text = "[run]\nduration_s = 1\n[controller PID]\npid_kp = 1e39\n",
         .line = 4,
         .column = 10,
         .who = "PID",
         .status = LADRC_ERR_PID_KP},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\nwc_rad_s = 1e-50\n",
         .line = 4,
         .column = 12,
         .who = "LADRC",
         .status = LADRC_ERR_WC_RAD_S},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntd_accel_rad_s2 = 1e39\n",
         .line = 4,
         .column = 19,
         .who = "LADRC",
         .status = LADRC_ERR_TD_ACCEL_RAD_S2},
        {.text = "[run]\nduration_s = 1\n[controller LP-MLADRC]\nlevant_lipschitz_rad_s4 = 1e-40\n",
         .line = 4,
         .column = 27,
         .who = "LP-MLADRC",
         .status = LADRC_ERR_LEVANT_RANGE},
        {.text = "[run]\nduration_s = 1\n[rotors]\nideal = no\nw2_max_rad2_s2 = 1e40\n",
         .line = 5,
         .column = 18,
         .who = "the mixer",
         .status = LADRC_ERR_MIXER_W2_MAX},
        {.text = "[run]\nduration_s = 1\n[vehicle]\nmass_kg = 1e39\n",
         .line = 4,
         .column = 11,
         .who = "the mixer",
         .status = LADRC_ERR_MIXER_MASS_KG},
        {.text = "[run]\nduration_s = 1\n[vehicle]\nyaw_coeff_Nm_s2 = 1e-46\n",
         .line = 4,
         .column = 19,
         .who = "the mixer",
         .status = LADRC_ERR_MIXER_B_NM_S2},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
                 "levant_lipschitz_rad_s4 = 1e-40\n",
         .line = 7,
         .column = 27,
         .who = "Levant's differentiator",
         .status = LADRC_ERR_LEVANT_RANGE},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
                 "td_accel_rad_s2 = 1e39\n",
         .line = 7,
         .column = 19,
         .who = "the tracking differentiator",
         .status = LADRC_ERR_TD_ACCEL_RAD_S2},
#endif
        /* actuator models the library does not take: at the key that sets them */
        {.text = "[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 2\n",
         .line = 4,
         .column = 15,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_MOTOR_TAU_S},
        {.text = "[run]\nduration_s = 1\n[sensors]\ndelay_ticks = 401\n",
         .line = 4,
         .column = 15,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_DELAY_TICKS},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\nmodel_delay_ticks = 401\n",
         .line = 4,
         .column = 21,
         .who = "LADRC",
         .status = LADRC_ERR_DELAY_TICKS},
        {.text = "[run]\nduration_s = 1\n[controller LP-MLADRC]\nmodel_motor_tau_s = 1.5\n",
         .line = 4,
         .column = 21,
         .who = "LP-MLADRC",
         .status = LADRC_ERR_MOTOR_TAU_S},
        /* INDI's gains beyond the sampled loop's bound, its filter beyond Nyquist */
        {.text = "[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_rate_kp_per_s = 1000\n",
         .line = 5,
         .column = 22,
         .who = "INDI",
         .status = LADRC_ERR_INDI_RATE_KP},
        {.text = "[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_att_kp_per_s = 2000\n",
         .line = 5,
         .column = 21,
         .who = "INDI",
         .status = LADRC_ERR_INDI_ATT_KP},
        {.text = "[run]\nduration_s = 1\ncontrollers = INDI\n[controller INDI]\nindi_filter_rad_s = 4000\n",
         .line = 5,
         .column = 21,
         .who = "INDI",
         .status = LADRC_ERR_INDI_FILTER},
        /* CASCADED's gains: at their key */
        {.text = "[run]\nduration_s = 1\ncontrollers = CASCADED\n[controller CASCADED]\ncas_att_kp = 2000\n",
         .line = 5,
         .column = 14,
         .who = "CASCADED",
         .status = LADRC_ERR_CAS_ATT_KP},
        {.text =
             "[run]\nduration_s = 1\ncontrollers = LADRC CASCADED\n[controller CASCADED]\ncas_rate_max_deg_s = 6000\n",
         .line = 5,
         .column = 22,
         .who = "CASCADED",
         .status = LADRC_ERR_CAS_RATE_MAX},
        /* combinations */
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\nleso_method = euler\nwo_rad_s = 3000\n",
         .line = 5,
         .column = 12,
         .who = "LADRC",
         .status = LADRC_ERR_LESO_EULER_UNSTABLE},
        {.text = "[run]\nduration_s = 1\n[controller HP-MLADRC]\nhp_freq_rad_s = 5000\n",
         .line = 4,
         .column = 17,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_HP_FREQ_RAD_S},
        {.text = "[run]\nduration_s = 1\n[controller HP-MLADRC]\nhp_freq_mode = known\nhp_freq_rad_s = 500\n",
         .line = 5,
         .column = 17,
         .who = "HP-MLADRC",
         .status = LADRC_ERR_HP_FIT_DECIMATION},
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

/* [wind], [vibration], [filter], the new [rotors] and [sensors] keys and
 * the recorded-series keys: out of range, inconsistent, or refused by the
 * library's gyro filter, each at its key. */
static void test_environment_errors(void)
{
    static const bad_case_t cases[] = {
        {.text = "[wind]\nturbulence = strong\n",
         .line = 2,
         .column = 14,
         .message = "expected off, light, moderate, severe or sigma, got 'strong'"},
        {.text = "[run]\nduration_s = 1\n[wind]\nturbulence = sigma\n",
         .line = 4,
         .column = 14,
         .message = "turbulence = sigma needs sigma_m_s > 0"},
        {.text = "[run]\nduration_s = 1\n[wind]\nsigma_m_s = 2\n",
         .line = 4,
         .column = 1,
         .message = "'sigma_m_s' applies only with turbulence = sigma"},
        {.text = "[wind]\nturbulence = sigma\nsigma_m_s = 31\n",
         .line = 3,
         .column = 13,
         .message = "sigma_m_s must be between 0 and 30"},
        {.text = "[wind]\naltitude_m = 400\n",
         .line = 2,
         .column = 14,
         .message = "altitude_m must be > 0 and at most 304.8 (1000 ft)"},
        {.text = "[wind]\nmean_m_s = -1\n", .line = 2, .column = 12, .message = "mean_m_s must be between 0 and 50"},
        {.text = "[wind]\nfrom_deg = 360\n", .line = 2, .column = 12, .message = "from_deg must be >= 0 and below 360"},
        {.text = "[vibration]\norders = 1 2 3 4 5\n", .line = 2, .column = 18, .message = "expected at most 4 numbers"},
        {.text = "[vibration]\norders = 0\n",
         .line = 2,
         .column = 10,
         .message = "orders must be between 0.001 and 100"},
        {.text = "[vibration]\norders = 1 100.5\n",
         .line = 2,
         .column = 12,
         .message = "orders must be between 0.001 and 100"},
        {.text = "[vibration]\norders = 1\ngyro_deg_s = -1\n",
         .line = 3,
         .column = 14,
         .message = "gyro_deg_s must be between 0 and 5729 (100 rad/s)"},
        /* values the runner's vibration would refuse are refused at their key */
        {.text = "[vibration]\norders = 1\ngyro_deg_s = 1e4\n",
         .line = 3,
         .column = 14,
         .message = "gyro_deg_s must be between 0 and 5729 (100 rad/s)"},
        {.text = "[vibration]\norders = 1 2\naccel_m_s2 = 1 1001\n",
         .line = 3,
         .column = 16,
         .message = "accel_m_s2 must be between 0 and 1000"},
        {.text = "[vibration]\norders = 1\naxis_gain = 1 101 1\n",
         .line = 3,
         .column = 15,
         .message = "axis_gain must be between 0 and 100"},
        {.text = "[vibration]\norders = 1\naxis_gain = 1 1\n",
         .line = 3,
         .column = 16,
         .message = "expected 3 numbers"},
        {.text = "[run]\nduration_s = 1\n[vibration]\norders = 1 2\ngyro_deg_s = 1\n",
         .line = 5,
         .column = 14,
         .message = "gyro_deg_s gives 1 numbers; orders gives 2 (one per order)"},
        {.text = "[run]\nduration_s = 1\n[vibration]\ngyro_deg_s = 1\n",
         .line = 4,
         .column = 1,
         .message = "the vibration's amplitudes need its orders (orders = 1 2 3 ...)"},
        {.text = "[filter]\nlpf_order = 3\n", .line = 2, .column = 13, .message = "lpf_order must be 0, 1 or 2"},
        {.text = "[run]\nduration_s = 1\n[filter]\nlpf_order = 2\nlpf_hz = 600\n",
         .line = 5,
         .column = 10,
         .message = "lpf_hz must be below the Nyquist frequency 0.5 / control_dt_s (500 Hz)"},
        {.text = "[run]\nduration_s = 1\n[filter]\nnotch_hz = 100 460\n",
         .line = 4,
         .column = 12,
         .message = "notch_hz 460 must be below 450 Hz (0.9 of the Nyquist frequency)"},
        {.text = "[filter]\nrpm_harmonics = 5\n",
         .line = 2,
         .column = 17,
         .message = "rpm_harmonics must be between 0 and 4"},
        {.text = "[filter]\nrpm_harmonics = 2\nrpm_q = 0\n",
         .line = 3,
         .column = 9,
         .message = "rpm_q must be between 0.1 and 100"},
        {.text = "[run]\nduration_s = 1\n[filter]\nrpm_harmonics = 2\nrpm_min_hz = 500\n",
         .line = 5,
         .column = 14,
         .message = "rpm_min_hz must be below 450 Hz (0.9 of the Nyquist frequency)"},
        {.text = "[rotors]\nmotor_tau_down_s = -1\n",
         .line = 2,
         .column = 20,
         .message = "motor_tau_down_s must be >= 0"},
        {.text = "[rotors]\nbattery_drop = 1\n",
         .line = 2,
         .column = 16,
         .message = "battery_drop must be >= 0 and < 1"},
        {.text = "[rotors]\nrotor_drag_per_s = 0.3\nrotor_drag_N_s_m = 1e-3\n",
         .line = 3,
         .column = 1,
         .message = "'rotor_drag_N_s_m' and 'rotor_drag_per_s' (line 2) set the same value"},
        {.text = "[disturbance]\nseries_end = wrap\n",
         .line = 2,
         .column = 14,
         .message = "expected repeat, hold or refuse, got 'wrap'"},
        {.text = "[run]\nduration_s = 10\n[phases]\narm_s = 1\n",
         .line = 4,
         .column = 1,
         .message = "the ground phases need takeoff_s (the vehicle starts on the ground)"},
        {.text = "[run]\nduration_s = 10\n[phases]\ntakeoff_s = 2 1\n",
         .line = 4,
         .column = 13,
         .message = "takeoff_s must increase"},
        {.text = "[run]\nduration_s = 10\n[phases]\ntakeoff_s = 10\n",
         .line = 4,
         .column = 13,
         .message = "takeoff_s 10 is not before the run's end (duration_s 10)"},
        {.text = "[run]\nduration_s = 10\n[phases]\narm_s = 3\ntakeoff_s = 2\n",
         .line = 5,
         .column = 13,
         .message = "takeoff_s 2 while disarmed"},
        {.text = "[run]\nduration_s = 10\n[phases]\ntakeoff_s = 2\nland_s = 4\ndisarm_s = 3\n",
         .line = 6,
         .column = 12,
         .message = "disarm_s 3 in the air (land first)"},
        {.text = "[run]\nduration_s = 10\n[phases]\ntakeoff_s = 2\nland_s = 2\n",
         .line = 4,
         .column = 13,
         .message = "takeoff_s and land_s both at 2 s"},
        {.text = "[run]\nduration_s = 10\n[phases]\ntakeoff_s = 2 5\n",
         .line = 4,
         .column = 13,
         .message = "takeoff_s 5 in the air"},
        {.text = "[phases]\nground_deg = 30 0\n",
         .line = 2,
         .column = 14,
         .message = "ground_deg must be within (-30, 30)"},
        {.text = "[vehicle]\nkinematics = euler\n",
         .line = 2,
         .column = 14,
         .message = "expected paper or rigid, got 'euler'"},
        {.text = "[reference]\nframe = quat\n",
         .line = 2,
         .column = 9,
         .message = "expected euler or quaternion, got 'quat'"},
        {.text = "[reference]\nframe = quaternion\nyaw_weight = 0\n",
         .line = 3,
         .column = 14,
         .message = "yaw_weight must be > 0 and at most 1"},
        {.text = "[run]\nduration_s = 1\n[reference]\nyaw_weight = 0.5\n",
         .line = 4,
         .column = 1,
         .message = "'yaw_weight' applies only with frame = quaternion"},
        {.text = "[run]\nduration_s = 1\n[reference]\nframe = quaternion\n[filter]\nangle = yes\n",
         .line = 6,
         .column = 9,
         .message = "angle = yes needs [reference] frame = euler (the quaternion frame takes the attitude unfiltered)"},
        {.text = "[run]\nduration_s = 1\n[reference]\nframe = quaternion\n[controller LADRC]\nwrap_yaw = no\n",
         .line = 6,
         .column = 12,
         .message = "wrap_yaw = no needs [reference] frame = euler (the quaternion frame wraps every axis)"},
    };
    CHECK_BAD_CASES(cases);
#ifndef LADRC_REAL_DOUBLE
    /* Within every range, yet a notch of Q 100 at 0.01 Hz rounds to an
     * unstable section in float (its poles 6e-7 inside the unit circle). */
    static const bad_case_t refused[] = {
        {.text = "[run]\nduration_s = 1\n[filter]\nrpm_harmonics = 2\nrpm_q = 100\nrpm_min_hz = 0.01\n",
         .line = 5,
         .column = 9,
         .message =
             "the gyro filter refuses it: LADRC_ERR_GYRO_RPM_Q: gyro filter rpm_q must be finite, > 0 and neither "
             "too high nor too low for a stable notch"},
        /* the same refusal of a key the file left at its default: at the [filter] header */
        {.text = "[run]\nduration_s = 1\n[filter]\nrpm_harmonics = 2\nrpm_min_hz = 0.00001\n",
         .line = 3,
         .column = 1,
         .message = "the gyro filter refuses rpm_q's default: LADRC_ERR_GYRO_RPM_Q: gyro filter rpm_q must be "
                    "finite, > 0 and neither too high nor too low for a stable notch"},
    };
    CHECK_BAD_CASES(refused);
#endif
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

/* [excitation] and [run] log: ranges, the chirp's frequencies against each
 * other and the control rate, the chirps within the run, the list of forms. */
static void test_excitation_and_log_errors(void)
{
    static const bad_case_t cases[] = {
        {.text = "[excitation]\naxis = x\n",
         .line = 2,
         .column = 8,
         .message = "expected roll, pitch, yaw or all, got 'x'"},
        {.text = "[excitation]\namplitude = 0\n",
         .line = 2,
         .column = 13,
         .message = "amplitude must be > 0 and at most 1"},
        {.text = "[excitation]\namplitude = 1.01\n",
         .line = 2,
         .column = 13,
         .message = "amplitude must be > 0 and at most 1"},
        {.text = "[run]\nduration_s = 20\n[excitation]\namplitude = 0.1 0.2\n",
         .line = 4,
         .column = 13,
         .message = "amplitude gives 2 numbers: one for every axis, or three (roll, pitch, yaw)"},
        {.text = "[excitation]\nf0_hz = 0\n", .line = 2, .column = 9, .message = "f0_hz must be > 0"},
        {.text = "[excitation]\nstart_s = -1\n", .line = 2, .column = 11, .message = "start_s must be >= 0"},
        {.text = "[excitation]\nduration_s = 0\n", .line = 2, .column = 14, .message = "duration_s must be > 0"},
        /* f1 beyond 0.45 / control_dt_s (450 Hz at 1 kHz), given */
        {.text = "[run]\nduration_s = 20\n[excitation]\nf1_hz = 451\n",
         .line = 4,
         .column = 9,
         .message = "f1_hz must be at most 0.45 / control_dt_s (450 Hz)"},
        /* the default f1 is capped there: 22.5 Hz at 50 Hz, below a given f0 */
        {.text = "[run]\nduration_s = 20\ncontrol_dt_s = 0.02\n[excitation]\nf0_hz = 30\n",
         .line = 5,
         .column = 9,
         .message = "f0_hz (30) must be below f1_hz (22.5)"},
        {.text = "[run]\nduration_s = 20\n[excitation]\nf1_hz = 0.5\n",
         .line = 4,
         .column = 9,
         .message = "f0_hz (1) must be below f1_hz (0.5)"},
        {.text = "[run]\nduration_s = 20\n[excitation]\nf1_hz = 10\nf0_hz = 10\n",
         .line = 5,
         .column = 9,
         .message = "f0_hz (10) must be below f1_hz (10)"},
        /* the defaults, start 1 s and 10 s long: at the section's header */
        {.text = "[run]\nduration_s = 10\n[excitation]\n",
         .line = 3,
         .column = 1,
         .message = "the chirp ends at 11 s, after the run's end (duration_s = 10)"},
        {.text = "[run]\nduration_s = 10\n[excitation]\nstart_s = 0.5\n",
         .line = 4,
         .column = 11,
         .message = "the chirp ends at 10.5 s, after the run's end (duration_s = 10)"},
        {.text = "[run]\nduration_s = 10\n[excitation]\nstart_s = 0\nduration_s = 11\n",
         .line = 5,
         .column = 14,
         .message = "the chirp ends at 11 s, after the run's end (duration_s = 10)"},
        {.text = "[run]\nduration_s = 20\n[excitation]\naxis = all\n",
         .line = 4,
         .column = 8,
         .message = "the three chirps end at 31 s, after the run's end (duration_s = 20)"},
        {.text = "[run]\nkind = differentiator\nduration_s = 20\n[differentiator]\nsignal = t\nderivative = 1\n"
                 "[excitation]\n",
         .line = 7,
         .column = 1,
         .message = "[excitation] does not apply to kind = differentiator"},
        {.text = "[run]\nlog = blackbox\n",
         .line = 2,
         .column = 7,
         .message = "expected betaflight, px4 or generic, got 'blackbox'"},
        {.text = "[run]\nlog = px4, px4\n", .line = 2, .column = 12, .message = "'px4' listed twice in log"},
        {.text = "[run]\nlog = px4,,generic\n",
         .line = 2,
         .column = 11,
         .message = "expected betaflight, px4 or generic before ','"},
        {.text = "[run]\nlog = generic,\n", .line = 2, .column = 15, .message = "expected betaflight, px4 or generic"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\nlog = px4\n[differentiator]\nsignal = t\n"
                 "derivative = 1\n",
         .line = 4,
         .column = 1,
         .message = "'log' does not apply to kind = differentiator"},
    };
    CHECK_BAD_CASES(cases);
    /* exactly at the limits: accepted */
    parse_ok("[run]\nduration_s = 11\n[excitation]\nf1_hz = 450\n");
    parse_ok("[run]\nduration_s = 31\n[excitation]\naxis = all\n");
}

static void test_long_values_are_rejected_not_truncated(void)
{
    static char text[2048];
    strcpy(text, "[run]\nduration_s = 1\noutput_dir = ");
    for (int i = 0; i < SIM_PATH_LEN; ++i) {
        strcat(text, "a");
    }
    strcat(text, "\n");
    const bad_case_t cases[] = {
        {.text = text, .line = 3, .column = 14, .message = "output_dir longer than 511 characters"}};
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

static void test_an_endless_file_is_refused_at_its_size_bound(void)
{
    /* /dev/zero given as a scenario: refused after 16 MiB, not read until memory runs out */
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_load(&sc, "/dev/zero", &err));
    TEST_ASSERT_EQUAL_STRING("/dev/zero", err.path);
    TEST_ASSERT_NOT_NULL_MESSAGE(strstr(err.message, "larger than 16 MiB"), err.message);
}

/* Every [vibration] value the parser takes, at the ends of its ranges, is
 * one the run's vibration starts with: no refusal after parsing. */
static void test_vibration_accepted_at_its_limits_starts(void)
{
    static const char *const texts[] = {
        "[run]\nduration_s = 1\n[vibration]\norders = 0.001 100\ngyro_deg_s = 5729 0\naccel_m_s2 = 1000 0\n"
        "axis_gain = 100 0 100\n",
        "[run]\nduration_s = 1\n[vibration]\norders = 1 2 3 4\ngyro_deg_s = 0 0 0 5729\n"
        "accel_m_s2 = 0 1000 0 0\naxis_gain = 0 0 0\n",
    };
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; ++i) {
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_scenario_parse(&sc, texts[i], "ok.ini", &err), err.message);
        const sim_vibration_config_t cfg = sim_setup_vibration(&sc);
        sim_vibration_t v;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sim_vibration_init(&v, &cfg, 1u), texts[i]);
    }
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
    RUN_TEST(test_environment_errors);
    RUN_TEST(test_a_controller_not_listed_is_checked_when_chosen);
    RUN_TEST(test_parse_buffer_needs_no_nul_and_refuses_one_inside);
    RUN_TEST(test_excitation_and_log_errors);
    RUN_TEST(test_long_values_are_rejected_not_truncated);
    RUN_TEST(test_null_arguments_are_refused_and_err_is_optional);
    RUN_TEST(test_an_endless_file_is_refused_at_its_size_bound);
    RUN_TEST(test_vibration_accepted_at_its_limits_starts);
    return UNITY_END();
}
