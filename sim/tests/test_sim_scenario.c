/* SPDX-License-Identifier: BSD-3-Clause */
/* Scenario files: the defaults, every key read into its field with its unit,
 * piecewise signals and their (from, to] windows, the shipped scenarios, and
 * each malformed input with the error's line, column and message. */
#include "unity.h"
#include "scenario.h"
#include "setup.h"
#include "ladrc/types.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef SIM_SCENARIO_DIR
#error "SIM_SCENARIO_DIR must name the scenarios directory"
#endif

/* Values are parsed with strtod and converted with one multiplication (deg
 * -> rad) or a square root and a multiplication (variance -> std), so they
 * match the same double computation here to an ulp or two; 1e-12 relative
 * is far below any wrong unit or field. */
#define REL_TOL 1e-12

static const double PI = 3.14159265358979323846;
#define DEG (PI / 180.0)

/* large: one scenario holds 8 signals of 8 compiled expressions */
static sim_scenario_t sc;
static sim_parse_error_t err;

void setUp(void) { memset(&err, 0, sizeof err); }
void tearDown(void) {}

static void assert_close(double expected, double actual, const char *what)
{
    char message[200];
    snprintf(message, sizeof message, "%s: expected %.17g, got %.17g", what, expected, actual);
    TEST_ASSERT_TRUE_MESSAGE(fabs(actual - expected) <= REL_TOL * (1.0 + fabs(expected)), message);
}

/* Parses text that must be valid. */
static void parse_ok(const char *text)
{
    const int rc = sim_scenario_parse(&sc, text, "dir/test.ini", &err);
    char message[300];
    snprintf(message, sizeof message, "%d:%d: %s", err.line, err.column, err.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, message);
}

typedef struct {
    const char *text;
    int line;
    int column;
    const char *message;
} bad_case_t;

static void check_bad_cases(const bad_case_t *cases, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        const bad_case_t *c = &cases[i];
        char what[400];
        snprintf(what, sizeof what, "case %u <<%s>>", (unsigned)i, c->text);
        memset(&err, 0, sizeof err);
        TEST_ASSERT_EQUAL_INT_MESSAGE(-1, sim_scenario_parse(&sc, c->text, "bad.ini", &err), what);
        TEST_ASSERT_EQUAL_STRING_MESSAGE(c->message, err.message, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->line, err.line, what);
        TEST_ASSERT_EQUAL_INT_MESSAGE(c->column, err.column, what);
        TEST_ASSERT_EQUAL_STRING_MESSAGE("bad.ini", err.path, what);
    }
}

#define CHECK_BAD_CASES(cases) check_bad_cases((cases), sizeof(cases) / sizeof((cases)[0]))

/* ---- well-formed input ----------------------------------------------------- */

static void test_defaults_fill_every_key_not_given(void)
{
    parse_ok("[run]\nduration_s = 12\n");
    TEST_ASSERT_EQUAL_STRING("test", sc.name);
    TEST_ASSERT_EQUAL_STRING("dir/test.ini", sc.path);
    TEST_ASSERT_EQUAL_INT(SIM_KIND_ATTITUDE, sc.kind);
    assert_close(12.0, sc.duration_s, "duration_s");
    assert_close(0.001, sc.control_dt_s, "control_dt_s");
    TEST_ASSERT_EQUAL_INT(10, sc.plant_substeps);
    TEST_ASSERT_TRUE(sc.seed == 1u);
    TEST_ASSERT_EQUAL_STRING("out/test", sc.output_dir);
    TEST_ASSERT_EQUAL_INT(4, sc.n_controllers);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_HP_MLADRC, sc.controllers[0]);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_LP_MLADRC, sc.controllers[1]);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_LADRC, sc.controllers[2]);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, sc.controllers[3]);

    /* paper Table 1 */
    assert_close(0.8, sc.mass_kg, "mass_kg");
    assert_close(5.445e-3, sc.inertia_kg_m2[0], "Jx");
    assert_close(5.445e-3, sc.inertia_kg_m2[1], "Jy");
    assert_close(1.089e-2, sc.inertia_kg_m2[2], "Jz");
    assert_close(0.165, sc.arm_m, "arm_m");
    assert_close(2.98e-5, sc.thrust_coeff_N_s2, "kL");
    assert_close(2e-6, sc.yaw_coeff_Nm_s2, "b");
    assert_close(0.09, sc.rot_drag_Nm_s, "kt");
    assert_close(9.81, sc.g_m_s2, "g");

    TEST_ASSERT_EQUAL_INT(1, sc.rotors_ideal);
    assert_close(0.0, sc.w2_min_rad2_s2, "w2_min");
    TEST_ASSERT_TRUE(isinf(sc.w2_max_rad2_s2) && sc.w2_max_rad2_s2 > 0.0);
    assert_close(0.0, sc.motor_tau_s, "motor_tau_s");
    assert_close(40.0 * DEG, sc.tilt_max_rad, "tilt_max");

    assert_close(0.0, sc.angle_noise_std_rad, "angle noise");
    assert_close(0.0, sc.rate_noise_std_rad_s, "rate noise");
    TEST_ASSERT_EQUAL_INT(0, sc.delay_ticks);
    TEST_ASSERT_EQUAL_INT(1, sc.use_rate);
    for (int i = 0; i < 3; ++i) {
        assert_close(1.0, sc.inertia_scale[i], "inertia_scale");
        TEST_ASSERT_EQUAL_INT(0, sc.reference[i].n_pieces);
        TEST_ASSERT_EQUAL_INT(0, sc.disturbance[i].n_pieces);
        assert_close(DEG, sc.reference[i].scale, "reference scale");
        assert_close(1.0, sc.disturbance[i].scale, "disturbance scale");
        assert_close(0.0, sim_signal_eval(&sc.reference[i], 3.0), "reference value");
        assert_close(0.0, sim_signal_eval(&sc.disturbance[i], 3.0), "disturbance value");
    }
    assert_close(1.0, sc.rot_drag_scale, "rot_drag_scale");

    for (int c = 0; c < SIM_CTRL_COUNT; ++c) {
        const sim_overrides_t *o = &sc.overrides[c];
        TEST_ASSERT_TRUE(isnan(o->wc_rad_s) && isnan(o->wo_rad_s) && isnan(o->hp_freq_rad_s));
        TEST_ASSERT_TRUE(isnan(o->levant_lipschitz_rad_s4) && isnan(o->td_accel_rad_s2));
        TEST_ASSERT_TRUE(isnan(o->pid_kp) && isnan(o->pid_ki) && isnan(o->pid_kd));
        TEST_ASSERT_TRUE(isnan(o->indi_att_kp_per_s) && isnan(o->indi_rate_kp_per_s) && isnan(o->indi_filter_rad_s));
        TEST_ASSERT_EQUAL_INT(-1, o->leso_method);
        TEST_ASSERT_EQUAL_INT(-1, o->hp_freq_mode);
        TEST_ASSERT_EQUAL_INT(-1, o->coupling_feed);
        TEST_ASSERT_TRUE(isnan(o->model_motor_tau_s));
        TEST_ASSERT_EQUAL_INT(-1, o->model_delay_ticks);
        TEST_ASSERT_EQUAL_INT(-1, o->wrap_yaw);
    }

    /* metric windows: the whole run */
    assert_close(0.0, sc.error_window_s[0], "error from");
    assert_close(12.0, sc.error_window_s[1], "error to");
    assert_close(0.0, sc.steady_window_s[0], "steady from");
    assert_close(12.0, sc.steady_window_s[1], "steady to");
    assert_close(0.5, sc.settle_band_deg, "settle band");
    assert_close(0.0, sc.settle_after_s, "settle from");
    assert_close(12.0, sc.settle_until_s, "settle to");

    TEST_ASSERT_EQUAL_INT(0, sc.diff_signal.n_pieces);
    TEST_ASSERT_EQUAL_INT(0, sc.diff_derivative.n_pieces);
    assert_close(0.0, sc.diff_noise_var, "diff noise");
    TEST_ASSERT_TRUE(isnan(sc.diff_levant_lipschitz) && isnan(sc.diff_td_accel) && isnan(sc.diff_td_h0_s));
}

static void test_every_attitude_key_lands_in_its_field_in_its_unit(void)
{
    parse_ok("[run]\n"
             "kind = attitude\n"
             "duration_s = 20\n"
             "control_dt_s = 2e-3\n"
             "plant_substeps = 4\n"
             "seed = 18446744073709551615\n"
             "output_dir = results/my run\n"
             "controllers = PID LADRC\n"
             "[vehicle]\n"
             "mass_kg = 1.5\n"
             "inertia_kg_m2 = 1e-2 2e-2 3e-2\n"
             "arm_m = .25\n"
             "thrust_coeff_N_s2 = 3e-5\n"
             "yaw_coeff_Nm_s2 = 4e-6\n"
             "rot_drag_Nm_s = 0\n"
             "g_m_s2 = 9.8\n"
             "[rotors]\n"
             "ideal = no\n"
             "w2_min_rad2_s2 = 1e4\n"
             "w2_max_rad2_s2 = 2e5\n"
             "motor_tau_s = 0.02\n"
             "tilt_max_deg = 30\n"
             "[sensors]\n"
             "angle_noise_var_deg2 = 0.04\n"
             "rate_noise_std_deg_s = 0.5\n"
             "delay_ticks = 64\n"
             "use_rate = no\n"
             "[mismatch]\n"
             "inertia_scale = 1.1 0.9 0.95\n" /* the model stays a rigid body */
             "rot_drag_scale = 0.5\n"
             "[reference]\n"
             "roll = 10\n"
             "pitch = -t\n"
             "yaw = 1 .. : 3\n"
             "[disturbance]\n"
             "roll = 2 .. 6 : 8\n"
             "pitch = 6\n"
             "yaw = .. 1 : -4\n"
             "[metrics]\n"
             "error_window_s = 1 20\n"
             "steady_window_s = 15 18.5\n"
             "settle_band_deg = 0.2\n"
             "settle_window_s = 2 4\n"
             "[controller LADRC]\n" /* the library models at most 8 ticks of delay */
             "model_delay_ticks = 8\n");
    TEST_ASSERT_EQUAL_INT(SIM_KIND_ATTITUDE, sc.kind);
    assert_close(20.0, sc.duration_s, "duration_s");
    assert_close(2e-3, sc.control_dt_s, "control_dt_s");
    TEST_ASSERT_EQUAL_INT(4, sc.plant_substeps);
    TEST_ASSERT_TRUE(sc.seed == UINT64_MAX);
    TEST_ASSERT_EQUAL_STRING("results/my run", sc.output_dir);
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, sc.controllers[0]);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_LADRC, sc.controllers[1]);

    assert_close(1.5, sc.mass_kg, "mass_kg");
    assert_close(1e-2, sc.inertia_kg_m2[0], "Jx");
    assert_close(2e-2, sc.inertia_kg_m2[1], "Jy");
    assert_close(3e-2, sc.inertia_kg_m2[2], "Jz");
    assert_close(0.25, sc.arm_m, "arm_m");
    assert_close(3e-5, sc.thrust_coeff_N_s2, "kL");
    assert_close(4e-6, sc.yaw_coeff_Nm_s2, "b");
    assert_close(0.0, sc.rot_drag_Nm_s, "kt");
    assert_close(9.8, sc.g_m_s2, "g");

    TEST_ASSERT_EQUAL_INT(0, sc.rotors_ideal);
    assert_close(1e4, sc.w2_min_rad2_s2, "w2_min");
    assert_close(2e5, sc.w2_max_rad2_s2, "w2_max");
    assert_close(0.02, sc.motor_tau_s, "motor_tau_s");
    assert_close(30.0 * DEG, sc.tilt_max_rad, "tilt_max");

    assert_close(0.2 * DEG, sc.angle_noise_std_rad, "angle noise from a variance");
    assert_close(0.5 * DEG, sc.rate_noise_std_rad_s, "rate noise");
    TEST_ASSERT_EQUAL_INT(64, sc.delay_ticks);
    TEST_ASSERT_EQUAL_INT(0, sc.use_rate);

    assert_close(1.1, sc.inertia_scale[0], "inertia_scale x");
    assert_close(0.9, sc.inertia_scale[1], "inertia_scale y");
    assert_close(0.95, sc.inertia_scale[2], "inertia_scale z");
    assert_close(0.5, sc.rot_drag_scale, "rot_drag_scale");

    assert_close(10.0 * DEG, sim_signal_eval(&sc.reference[0], 7.0), "roll ref, degrees to rad");
    assert_close(-7.0 * DEG, sim_signal_eval(&sc.reference[1], 7.0), "pitch ref");
    assert_close(0.0, sim_signal_eval(&sc.reference[2], 1.0), "yaw ref at 1");
    assert_close(3.0 * DEG, sim_signal_eval(&sc.reference[2], 1.5), "yaw ref after 1");
    assert_close(8.0, sim_signal_eval(&sc.disturbance[0], 4.0), "roll d");
    assert_close(6.0, sim_signal_eval(&sc.disturbance[1], -3.0), "pitch d everywhere");
    assert_close(-4.0, sim_signal_eval(&sc.disturbance[2], 1.0), "yaw d up to 1");
    assert_close(0.0, sim_signal_eval(&sc.disturbance[2], 1.001), "yaw d after 1");

    assert_close(1.0, sc.error_window_s[0], "error from");
    assert_close(20.0, sc.error_window_s[1], "error to");
    assert_close(15.0, sc.steady_window_s[0], "steady from");
    assert_close(18.5, sc.steady_window_s[1], "steady to");
    assert_close(0.2, sc.settle_band_deg, "settle band");
    assert_close(2.0, sc.settle_after_s, "settle from");
    assert_close(4.0, sc.settle_until_s, "settle to");
}

static void test_std_and_variance_keys_set_the_same_noise(void)
{
    parse_ok("[run]\nduration_s = 1\n[sensors]\nangle_noise_std_deg = 0.03\nrate_noise_var_deg2_s2 = 4\n");
    assert_close(0.03 * DEG, sc.angle_noise_std_rad, "angle std");
    assert_close(2.0 * DEG, sc.rate_noise_std_rad_s, "rate from variance");
    parse_ok("[run]\nduration_s = 1\n[sensors]\nangle_noise_var_deg2 = 0.001\n");
    assert_close(sqrt(0.001) * DEG, sc.angle_noise_std_rad, "paper noise");
}

static void test_every_override_key_lands_in_its_controller(void)
{
    parse_ok("[run]\nduration_s = 1\n"
             "[controller HP-MLADRC]\n"
             "wc_rad_s = 15\nwo_rad_s = 75\nleso_method = euler\ncoupling_feed = no\n"
             "hp_freq_mode = online\nhp_freq_rad_s = 3\nlevant_lipschitz_rad_s4 = 500\n"
             "[controller LP-MLADRC]\n"
             "levant_lipschitz_rad_s4 = 200\nleso_method = zoh\ncoupling_feed = yes\n"
             "[controller LADRC]\n"
             "td_accel_rad_s2 = 25\nwc_rad_s = 10\n"
             "[controller PID]\n"
             "pid_kp = 20\npid_ki = 20\npid_kd = 0.05\n"
             "[controller CASCADED]\n"
             "cas_att_kp = 7\ncas_rate_max_deg_s = 300\ncas_rate_kp = 0.2\ncas_rate_ki = 1.5\n"
             "cas_rate_kd = 0.003\ncas_d_filter_tau_s = 0.004\ncas_i_limit_Nm = 0.1\ntd_accel_rad_s2 = 30\n"
             "wrap_yaw = no\n");
    const sim_overrides_t *hp = &sc.overrides[SIM_CTRL_HP_MLADRC];
    assert_close(15.0, hp->wc_rad_s, "hp wc");
    assert_close(75.0, hp->wo_rad_s, "hp wo");
    TEST_ASSERT_EQUAL_INT(1, hp->leso_method); /* LADRC_LESO_EULER */
    TEST_ASSERT_EQUAL_INT(0, hp->coupling_feed);
    TEST_ASSERT_EQUAL_INT(1, hp->hp_freq_mode); /* LADRC_HP_FREQ_ONLINE */
    assert_close(3.0, hp->hp_freq_rad_s, "hp freq");
    assert_close(500.0, hp->levant_lipschitz_rad_s4, "hp L");
    TEST_ASSERT_TRUE(isnan(hp->td_accel_rad_s2) && isnan(hp->pid_kp));

    const sim_overrides_t *lp = &sc.overrides[SIM_CTRL_LP_MLADRC];
    assert_close(200.0, lp->levant_lipschitz_rad_s4, "lp L");
    TEST_ASSERT_EQUAL_INT(0, lp->leso_method); /* LADRC_LESO_ZOH */
    TEST_ASSERT_EQUAL_INT(1, lp->coupling_feed);
    TEST_ASSERT_TRUE(isnan(lp->wc_rad_s));
    TEST_ASSERT_EQUAL_INT(-1, lp->hp_freq_mode);

    const sim_overrides_t *ladrc = &sc.overrides[SIM_CTRL_LADRC];
    assert_close(25.0, ladrc->td_accel_rad_s2, "ladrc R");
    assert_close(10.0, ladrc->wc_rad_s, "ladrc wc");
    TEST_ASSERT_TRUE(isnan(ladrc->wo_rad_s));

    const sim_overrides_t *cas = &sc.overrides[SIM_CTRL_CASCADED];
    assert_close(7.0, cas->cas_att_kp, "cas att_kp");
    assert_close(300.0, cas->cas_rate_max_deg_s, "cas rate max");
    assert_close(0.2, cas->cas_rate_kp, "cas kp");
    assert_close(1.5, cas->cas_rate_ki, "cas ki");
    assert_close(0.003, cas->cas_rate_kd, "cas kd");
    assert_close(0.004, cas->cas_d_filter_tau_s, "cas tau");
    assert_close(0.1, cas->cas_i_limit_Nm, "cas i limit");
    assert_close(30.0, cas->td_accel_rad_s2, "cas R");
    TEST_ASSERT_EQUAL_INT(0, cas->wrap_yaw);
    ladrc_attitude_config_t acfg;
    sim_setup_attitude(&sc, SIM_CTRL_CASCADED, &acfg);
    TEST_ASSERT_FLOAT_WITHIN(1e-6, 300.0 * DEG, (double)acfg.axis[1].cas_rate_max_rad_s);
    TEST_ASSERT_FLOAT_WITHIN(1e-7, 0.2, (double)acfg.axis[2].cas_rate_kp);

    const sim_overrides_t *pid = &sc.overrides[SIM_CTRL_PID];
    assert_close(20.0, pid->pid_kp, "kp");
    assert_close(20.0, pid->pid_ki, "ki");
    assert_close(0.05, pid->pid_kd, "kd");
    TEST_ASSERT_TRUE(isnan(pid->wc_rad_s));
    TEST_ASSERT_EQUAL_INT(-1, pid->coupling_feed);
}

static void test_tune_keys_land_in_their_controller_with_their_defaults(void)
{
    parse_ok("[run]\nduration_s = 1\n"
             "[controller LADRC]\ntune = margins\ntune_phase_margin_deg = 50\ntune_gain_margin_db = 8\n"
             "[controller PID]\ntune = margins\n"
             "[controller LP-MLADRC]\ntune = none\n"
             "[controller CASCADED]\ntune = margins\n[controller INDI]\ntune = margins\n");
    const sim_overrides_t *o = sc.overrides;
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_MARGINS, o[SIM_CTRL_CASCADED].tune);
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_MARGINS, o[SIM_CTRL_INDI].tune);
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_MARGINS, o[SIM_CTRL_LADRC].tune);
    assert_close(50.0, o[SIM_CTRL_LADRC].tune_pm_deg, "pm target");
    assert_close(8.0, o[SIM_CTRL_LADRC].tune_gm_db, "gm target");
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_MARGINS, o[SIM_CTRL_PID].tune);
    TEST_ASSERT_TRUE(isnan(o[SIM_CTRL_PID].tune_pm_deg) && isnan(o[SIM_CTRL_PID].tune_gm_db));
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_NONE, o[SIM_CTRL_LP_MLADRC].tune);
    TEST_ASSERT_EQUAL_INT(-1, o[SIM_CTRL_HP_MLADRC].tune); /* absent: none */
    /* where the errors of the tuning point: the value of each tune key */
    TEST_ASSERT_EQUAL_INT(4, sc.tune_line[SIM_CTRL_LADRC]);
    TEST_ASSERT_EQUAL_INT(8, sc.tune_column[SIM_CTRL_LADRC]);
    TEST_ASSERT_EQUAL_INT(8, sc.tune_line[SIM_CTRL_PID]);
    TEST_ASSERT_EQUAL_INT(0, sc.tune_line[SIM_CTRL_HP_MLADRC]);
    /* parsing tunes nothing: the gains stay the library's until sim_tune_controller runs */
    for (int id = 0; id < SIM_CTRL_COUNT; ++id) TEST_ASSERT_EQUAL_INT(0, sc.tuning[id].tuned);
    assert_close(45.0, SIM_TUNE_PM_DEG_DEFAULT, "default PM target");
    assert_close(6.0, SIM_TUNE_GM_DB_DEFAULT, "default GM target");
}

static void test_tune_errors_name_the_key(void)
{
    static const bad_case_t cases[] = {
        {"[run]\nduration_s = 1\n[controller LADRC]\ntune = auto\n", 4, 8,
         "expected none or margins, got 'auto'"},
        {"[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\nwc_rad_s = 20\n", 5, 1,
         "'wc_rad_s' conflicts with tune = margins (line 4), which chooses the gains: give one of them"},
        {"[run]\nduration_s = 1\n[controller HP-MLADRC]\nwo_rad_s = 50\ntune = margins\n", 4, 1,
         "'wo_rad_s' conflicts with tune = margins (line 5), which chooses the gains: give one of them"},
        {"[run]\nduration_s = 1\n[controller PID]\ntune = margins\npid_kd = 0.1\n", 5, 1,
         "'pid_kd' conflicts with tune = margins (line 4), which chooses the gains: give one of them"},
        /* the baselines' tuned gains too; their other keys stay free (cas_rate_max_deg_s) */
        {"[run]\nduration_s = 1\n[controller CASCADED]\ntune = margins\ncas_rate_max_deg_s = 200\n"
         "cas_rate_kd = 0.01\n",
         6, 1, "'cas_rate_kd' conflicts with tune = margins (line 4), which chooses the gains: give one of them"},
        {"[run]\nduration_s = 1\n[controller INDI]\nindi_filter_rad_s = 60\ntune = margins\n", 4, 1,
         "'indi_filter_rad_s' conflicts with tune = margins (line 5), which chooses the gains: give one of them"},
        {"[run]\nduration_s = 1\n[controller LADRC]\ntune_phase_margin_deg = 50\n", 4, 1,
         "'tune_phase_margin_deg' applies only with tune = margins"},
        {"[run]\nduration_s = 1\n[controller PID]\ntune = none\ntune_gain_margin_db = 6\n", 5, 1,
         "'tune_gain_margin_db' applies only with tune = margins"},
        {"[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_phase_margin_deg = 90\n", 5, 25,
         "tune_phase_margin_deg must be > 0 and < 90"},
        {"[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_gain_margin_db = 0\n", 5, 23,
         "tune_gain_margin_db must be > 0"},
        {"[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
         "[controller LADRC]\ntune = margins\n",
         7, 1, "[controller LADRC] does not apply to kind = differentiator"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_controllers_model_the_airframe_unless_told_otherwise(void)
{
    /* given: a lagging, late airframe; LADRC flies unmodelled, LP with its
     * own model, PID without wrapping its yaw */
    parse_ok("[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = 0.03\n[sensors]\ndelay_ticks = 2\n"
             "[controller LADRC]\nmodel_motor_tau_s = 0\nmodel_delay_ticks = 0\n"
             "[controller LP-MLADRC]\nmodel_motor_tau_s = 0.02\nwrap_yaw = no\n"
             "[controller PID]\nwrap_yaw = no\n");
    ladrc_attitude_config_t cfg;
    /* when / then */
    sim_setup_attitude(&sc, SIM_CTRL_HP_MLADRC, &cfg);
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_FLOAT_WITHIN(1e-9f, 0.03f, cfg.axis[i].motor_tau_s);
        TEST_ASSERT_EQUAL_INT(2, cfg.axis[i].delay_ticks);
        TEST_ASSERT_EQUAL_INT(i == 2, cfg.axis[i].wrap_angle);
    }
    TEST_ASSERT_EQUAL_INT(1, sim_setup_wraps_yaw(&sc, SIM_CTRL_HP_MLADRC));
    sim_setup_attitude(&sc, SIM_CTRL_LADRC, &cfg);
    TEST_ASSERT_EQUAL_FLOAT(0.0f, cfg.axis[0].motor_tau_s);
    TEST_ASSERT_EQUAL_INT(0, cfg.axis[0].delay_ticks);
    TEST_ASSERT_EQUAL_INT(1, cfg.axis[2].wrap_angle);
    sim_setup_attitude(&sc, SIM_CTRL_LP_MLADRC, &cfg);
    TEST_ASSERT_FLOAT_WITHIN(1e-9f, 0.02f, cfg.axis[1].motor_tau_s);
    TEST_ASSERT_EQUAL_INT(2, cfg.axis[1].delay_ticks);
    TEST_ASSERT_EQUAL_INT(0, cfg.axis[2].wrap_angle);
    TEST_ASSERT_EQUAL_INT(0, sim_setup_wraps_yaw(&sc, SIM_CTRL_LP_MLADRC));
    sim_setup_attitude(&sc, SIM_CTRL_PID, &cfg);
    TEST_ASSERT_EQUAL_INT(0, cfg.axis[2].wrap_angle);
    TEST_ASSERT_EQUAL_INT(0, sim_setup_wraps_yaw(&sc, SIM_CTRL_PID));
}

static void test_every_differentiator_key_lands_in_its_field(void)
{
    parse_ok("[run]\nkind = differentiator\nduration_s = 10\ncontrol_dt_s = 0.002\nseed = 7\n"
             "output_dir = o\n"
             "[differentiator]\nsignal = sin(t)\nderivative = cos(t)\nnoise_var = 0.001\n"
             "levant_lipschitz_rad_s4 = 10\ntd_accel_rad_s2 = 12\ntd_h0_s = 0.002\n");
    TEST_ASSERT_EQUAL_INT(SIM_KIND_DIFFERENTIATOR, sc.kind);
    assert_close(10.0, sc.duration_s, "duration_s");
    assert_close(0.002, sc.control_dt_s, "dt");
    TEST_ASSERT_TRUE(sc.seed == 7u);
    TEST_ASSERT_EQUAL_STRING("o", sc.output_dir);
    TEST_ASSERT_EQUAL_INT(0, sc.n_controllers);
    assert_close(sin(0.4), sim_signal_eval(&sc.diff_signal, 0.4), "signal, no unit factor");
    assert_close(cos(0.4), sim_signal_eval(&sc.diff_derivative, 0.4), "derivative");
    assert_close(0.001, sc.diff_noise_var, "noise_var");
    assert_close(10.0, sc.diff_levant_lipschitz, "L");
    assert_close(12.0, sc.diff_td_accel, "R");
    assert_close(0.002, sc.diff_td_h0_s, "h0");
}

static void test_signal_windows_hold_from_exclusive_to_inclusive(void)
{
    parse_ok("[run]\nduration_s = 30\n[disturbance]\n"
             "roll = 2 .. 6 : 8\n"
             "roll = 6 .. 12 : 20 - t\n"
             "roll = 25 .. : 1\n");
    const sim_signal_t *d = &sc.disturbance[0];
    TEST_ASSERT_EQUAL_INT(3, d->n_pieces);
    assert_close(0.0, sim_signal_eval(d, 0.0), "before");
    assert_close(0.0, sim_signal_eval(d, 2.0), "at from: outside");
    assert_close(8.0, sim_signal_eval(d, nextafter(2.0, 3.0)), "just after from");
    assert_close(8.0, sim_signal_eval(d, 6.0), "at to: inside");
    assert_close(20.0 - nextafter(6.0, 7.0), sim_signal_eval(d, nextafter(6.0, 7.0)), "next piece");
    assert_close(8.0, sim_signal_eval(d, 12.0), "12 is the second piece's end");
    assert_close(0.0, sim_signal_eval(d, nextafter(12.0, 13.0)), "gap");
    assert_close(0.0, sim_signal_eval(d, 25.0), "unbounded piece starts after 25");
    assert_close(1.0, sim_signal_eval(d, 1e9), "unbounded above");
    TEST_ASSERT_TRUE(isinf(d->to_s[2]) && d->to_s[2] > 0.0);
    assert_close(2.0, d->from_s[0], "first piece's start");
}

static void test_signal_eval_takes_the_first_piece_that_holds_t_and_scales_it(void)
{
    static sim_signal_t sig;
    memset(&sig, 0, sizeof sig);
    sig.scale = 2.0;
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&sig.expr[0], "1", NULL));
    TEST_ASSERT_EQUAL_INT(0, sim_expr_compile(&sig.expr[1], "t", NULL));
    sig.from_s[0] = 0.0;
    sig.to_s[0] = 1.0;
    sig.from_s[1] = -INFINITY;
    sig.to_s[1] = INFINITY;
    sig.n_pieces = 2;
    assert_close(2.0, sim_signal_eval(&sig, 0.5), "first piece");
    assert_close(2.0, sim_signal_eval(&sig, 1.0), "first piece at its end");
    assert_close(0.0, sim_signal_eval(&sig, 0.0), "second piece at 0: t");
    assert_close(-6.0, sim_signal_eval(&sig, -3.0), "second piece");
    sig.n_pieces = 0;
    assert_close(0.0, sim_signal_eval(&sig, 0.5), "no pieces");
}

static void test_layout_comments_blank_lines_crlf_tabs_and_bom(void)
{
    parse_ok("\xEF\xBB\xBF# heading\r\n"
             "\r\n"
             "  [ run ]   # a section\r\n"
             "\tduration_s=5# no spaces\r\n"
             "controllers =\tLADRC   PID  \r\n"
             "[reference]\n"
             "roll = 2*t  # comment after an expression\n"
             "   \t\n"
             "# [vehicle]\n"
             "# mass_kg = oops");
    assert_close(5.0, sc.duration_s, "duration_s");
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers);
    assert_close(6.0 * DEG, sim_signal_eval(&sc.reference[0], 3.0), "roll");
    assert_close(0.8, sc.mass_kg, "commented key not read");
}

static void test_name_and_default_output_dir_come_from_the_file_name(void)
{
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_parse(&sc, "[run]\nduration_s = 1\n", "a/b.c/gust.v2.ini", &err));
    TEST_ASSERT_EQUAL_STRING("gust.v2", sc.name);
    TEST_ASSERT_EQUAL_STRING("out/gust.v2", sc.output_dir);
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_parse(&sc, "[run]\nduration_s = 1\n", "plain", &err));
    TEST_ASSERT_EQUAL_STRING("plain", sc.name);
    TEST_ASSERT_EQUAL_INT(0, sim_scenario_parse(&sc, "[run]\nduration_s = 1\n", NULL, &err));
    TEST_ASSERT_EQUAL_STRING("scenario", sc.name);
    TEST_ASSERT_EQUAL_STRING("out/scenario", sc.output_dir);
}

static void test_controller_names(void)
{
    TEST_ASSERT_EQUAL_STRING("HP-MLADRC", sim_controller_name(SIM_CTRL_HP_MLADRC));
    TEST_ASSERT_EQUAL_STRING("LP-MLADRC", sim_controller_name(SIM_CTRL_LP_MLADRC));
    TEST_ASSERT_EQUAL_STRING("LADRC", sim_controller_name(SIM_CTRL_LADRC));
    TEST_ASSERT_EQUAL_STRING("PID", sim_controller_name(SIM_CTRL_PID));
    TEST_ASSERT_EQUAL_STRING("INDI", sim_controller_name(SIM_CTRL_INDI));
    TEST_ASSERT_EQUAL_STRING("?", sim_controller_name(SIM_CTRL_COUNT));
}

/* ---- shipped scenarios ---------------------------------------------------- */

static void load_ok(const char *file)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", SIM_SCENARIO_DIR, file);
    const int rc = sim_scenario_load(&sc, path, &err);
    char message[SIM_PATH_LEN + sizeof err.message + 32];
    snprintf(message, sizeof message, "%s:%d:%d: %s", err.path, err.line, err.column, err.message);
    TEST_ASSERT_EQUAL_INT_MESSAGE(0, rc, message);
}

/* The paper's Table 2 disturbance of one axis, as docs/method.md states it. */
static double table2(int axis, double t)
{
    const double sign = (axis == 1) ? 1.0 : -1.0; /* pitch has +120 */
    if (t <= 2.0 || t > 25.0) {
        return 0.0;
    }
    if (t <= 6.0) {
        return axis == 0 ? 8.0 : 6.0;
    }
    if (t <= 12.0) {
        return 20.0 + sign * 120.0 * sin(0.25 * PI * t);
    }
    return 20.0 + sign * 120.0 * sin(3.0 * t);
}

static void check_paper_case(const char *name)
{
    TEST_ASSERT_EQUAL_STRING(name, sc.name);
    TEST_ASSERT_EQUAL_INT(SIM_KIND_ATTITUDE, sc.kind);
    assert_close(30.0, sc.duration_s, "duration_s");
    assert_close(0.001, sc.control_dt_s, "dt");
    TEST_ASSERT_EQUAL_INT(10, sc.plant_substeps);
    TEST_ASSERT_EQUAL_INT(6, sc.n_controllers); /* the paper's four, then CASCADED and INDI */
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_CASCADED, sc.controllers[4]);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_INDI, sc.controllers[5]);
    TEST_ASSERT_EQUAL_INT(1, sc.rotors_ideal);
    assert_close(0.8, sc.mass_kg, "m");
    assert_close(1.089e-2, sc.inertia_kg_m2[2], "Jz");
    for (double t = 0.0; t <= 30.0; t += 0.01) {
        assert_close((5.0 + 15.0 * cos(PI * t / 2.0)) * DEG, sim_signal_eval(&sc.reference[0], t), "roll ref");
        assert_close(10.0 * cos(PI * t / 2.0) * DEG, sim_signal_eval(&sc.reference[1], t), "pitch ref");
        assert_close(0.0, sim_signal_eval(&sc.reference[2], t), "yaw ref");
        for (int axis = 0; axis < 3; ++axis) {
            assert_close(table2(axis, t), sim_signal_eval(&sc.disturbance[axis], t), "Table 2");
        }
    }
    /* the window edges exactly */
    const double edges[] = {2.0, 6.0, 12.0, 25.0};
    for (int i = 0; i < 4; ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            assert_close(table2(axis, edges[i]), sim_signal_eval(&sc.disturbance[axis], edges[i]), "edge");
            const double after = nextafter(edges[i], 100.0);
            assert_close(table2(axis, after), sim_signal_eval(&sc.disturbance[axis], after), "after edge");
        }
    }
    assert_close(0.0, sc.error_window_s[0], "error from");
    assert_close(30.0, sc.error_window_s[1], "error to");
    assert_close(20.0, sc.steady_window_s[0], "steady from");
    assert_close(25.0, sc.steady_window_s[1], "steady to");
}

static void test_shipped_paper_scenario(void)
{
    load_ok("paper.ini");
    check_paper_case("paper");
    assert_close(0.0, sc.angle_noise_std_rad, "no noise");
}

static void test_shipped_paper_noisy_scenario(void)
{
    load_ok("paper_noisy.ini");
    check_paper_case("paper_noisy");
    assert_close(sqrt(0.001) * DEG, sc.angle_noise_std_rad, "variance 0.001 deg^2");
    assert_close(0.0, sc.rate_noise_std_rad_s, "clean rates");
}

static void test_shipped_table3_differentiator_scenario(void)
{
    load_ok("table3_differentiator.ini");
    TEST_ASSERT_EQUAL_INT(SIM_KIND_DIFFERENTIATOR, sc.kind);
    assert_close(10.0, sc.duration_s, "duration");
    assert_close(0.001, sc.control_dt_s, "1 kHz");
    assert_close(sin(2.0), sim_signal_eval(&sc.diff_signal, 2.0), "signal");
    assert_close(cos(2.0), sim_signal_eval(&sc.diff_derivative, 2.0), "derivative");
    assert_close(0.001, sc.diff_noise_var, "noise");
    assert_close(10.0, sc.diff_levant_lipschitz, "L");
    assert_close(10.0, sc.diff_td_accel, "R");
    assert_close(0.01, sc.diff_td_h0_s, "h0");
}

static void test_shipped_steps_scenario(void)
{
    load_ok("steps.ini");
    TEST_ASSERT_EQUAL_INT(0, sc.rotors_ideal);
    assert_close(1e4, sc.w2_min_rad2_s2, "w2 min");
    assert_close(2e5, sc.w2_max_rad2_s2, "w2 max");
    assert_close(0.02, sc.motor_tau_s, "lag");
    TEST_ASSERT_EQUAL_INT(1, sc.use_rate);
    const double step_at[3] = {1.0, 4.0, 7.0};
    for (int axis = 0; axis < 3; ++axis) {
        assert_close(0.0, sim_signal_eval(&sc.reference[axis], step_at[axis]), "before the step");
        assert_close(10.0 * DEG, sim_signal_eval(&sc.reference[axis], nextafter(step_at[axis], 10.0)), "step");
        assert_close(0.0, sim_signal_eval(&sc.disturbance[axis], 5.0), "no disturbance");
    }
}

static void test_shipped_steps_and_real_scenarios_tune_every_controller(void)
{
    static const char *const files[] = {"steps.ini",           "real_paper_lag20.ini", "real_paper_lag30.ini",
                                        "real_paper_lag40.ini", "real_heavy_lag20.ini", "real_heavy_lag30.ini",
                                        "real_heavy_lag40.ini"};
    for (unsigned f = 0; f < sizeof files / sizeof files[0]; ++f) {
        load_ok(files[f]);
        TEST_ASSERT_EQUAL_INT_MESSAGE(SIM_CTRL_COUNT, sc.n_controllers, files[f]);
        for (int id = 0; id < SIM_CTRL_COUNT; ++id) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(SIM_TUNE_MARGINS, sc.overrides[id].tune, files[f]);
        }
        if (f == 0) continue;
        TEST_ASSERT_EQUAL_INT_MESSAGE(0, sc.rotors_ideal, files[f]);
        TEST_ASSERT_TRUE_MESSAGE(sc.motor_tau_s >= 0.02 && sc.motor_tau_s <= 0.04, files[f]);
        TEST_ASSERT_TRUE_MESSAGE(sc.delay_ticks >= 1 && sc.delay_ticks <= 2, files[f]);
        TEST_ASSERT_TRUE_MESSAGE(sc.angle_noise_std_rad > 0.0 && sc.rate_noise_std_rad_s > 0.0, files[f]);
        /* thrust-to-weight about 2: the top rotor limit is twice hover's w^2 */
        const double hover_w2 = sc.mass_kg * sc.g_m_s2 / (4.0 * sc.thrust_coeff_N_s2);
        TEST_ASSERT_TRUE_MESSAGE(fabs(sc.w2_max_rad2_s2 / hover_w2 - 2.0) < 0.02, files[f]);
    }
}

static void test_load_reports_a_missing_file_at_line_0(void)
{
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_load(&sc, "no/such/file.ini", &err));
    TEST_ASSERT_EQUAL_STRING("no/such/file.ini", err.path);
    TEST_ASSERT_EQUAL_INT(0, err.line);
    TEST_ASSERT_EQUAL_INT(0, err.column);
    TEST_ASSERT_EQUAL_INT(0, strncmp(err.message, "cannot open: ", 13));
}

static void test_load_rejects_a_nul_byte_where_it_is(void)
{
    const char *path = "test_sim_scenario_nul.ini";
    FILE *f = fopen(path, "wb");
    TEST_ASSERT_NOT_NULL(f);
    static const char text[] = "[run]\nduration_s = 1\nse\0ed = 2\n";
    TEST_ASSERT_EQUAL_UINT(sizeof text - 1, (unsigned)fwrite(text, 1, sizeof text - 1, f));
    fclose(f);
    const int rc = sim_scenario_load(&sc, path, &err);
    remove(path);
    TEST_ASSERT_EQUAL_INT(-1, rc);
    TEST_ASSERT_EQUAL_STRING("unexpected NUL byte", err.message);
    TEST_ASSERT_EQUAL_INT(3, err.line);
    TEST_ASSERT_EQUAL_INT(3, err.column);
}

/* ---- malformed input -------------------------------------------------------- */

static void test_structure_errors(void)
{
    static const bad_case_t cases[] = {
        {"[runn]\n", 1, 2, "unknown section [runn]"},
        {"[run\nduration_s = 1\n", 1, 5, "expected ']'"},
        {"[run] x\n", 1, 7, "trailing characters after ']'"},
        {"[ ]\n", 1, 3, "expected a section name"},
        {"[run extra]\n", 1, 6, "unexpected 'extra' in the section header"},
        {"[controller]\n", 1, 12, "expected a controller name after 'controller'"},
        {"[controller PDI]\n", 1, 13, "unknown controller 'PDI' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or INDI)"},
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
        {"[disturbance]\nroll = 2 .. 6 : 1\nroll = 5 .. 8 : 2\n", 3, 8, "window (5, 8] overlaps the one given on line 2"},
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
        {"[run]\nkind = differentiator\nduration_s = 1\n", 1, 1,
         "missing required key 'signal' in [differentiator]"},
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
        {"[run]\nduration_s = 0.01\ncontrol_dt_s = 0.02\n", 3, 16, "control_dt_s (0.02) must not exceed duration_s (0.01)"},
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
    parse_ok("[run]\nduration_s = 1\ncontrol_dt_s = 0.005\n"); /* every controller at 200 Hz */
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
        {"[run]\nduration_s = 1\n[controller LADRC]\nmodel_delay_ticks = 12\n", 4, 21, "LADRC",
         LADRC_ERR_DELAY_TICKS},
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
        {"[run]\nduration_s = 1\ncontrollers = CASCADED\n[controller CASCADED]\ncas_att_kp = 2000\n", 5, 14,
         "CASCADED", LADRC_ERR_CAS_ATT_KP},
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

static void test_indi_keys_land_and_indi_needs_the_rate(void)
{
    /* given: INDI listed with its three gains */
    parse_ok("[run]\nduration_s = 1\ncontrollers = LADRC INDI\n[controller INDI]\nindi_att_kp_per_s = 12\n"
             "indi_rate_kp_per_s = 30\nindi_filter_rad_s = 60\ntd_accel_rad_s2 = 30\n");
    ladrc_attitude_config_t cfg;
    sim_setup_attitude(&sc, SIM_CTRL_INDI, &cfg);
    /* then: they reach every axis; the variant is INDI */
    for (int i = 0; i < 3; ++i) {
        TEST_ASSERT_EQUAL_INT(LADRC_VARIANT_INDI, cfg.axis[i].variant);
        TEST_ASSERT_EQUAL_FLOAT(12.0f, cfg.axis[i].indi_att_kp_per_s);
        TEST_ASSERT_EQUAL_FLOAT(30.0f, cfg.axis[i].indi_rate_kp_per_s);
        TEST_ASSERT_EQUAL_FLOAT(60.0f, cfg.axis[i].indi_filter_rad_s);
        TEST_ASSERT_EQUAL_FLOAT(30.0f, cfg.axis[i].td_accel_rad_s2);
    }
    TEST_ASSERT_EQUAL_INT(2, sc.n_controllers);
    /* an INDI key on another controller is an error */
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, "[run]\nduration_s = 1\n[controller LADRC]\nindi_filter_rad_s = 9\n",
                                                 "bad.ini", &err));
    /* without the measured rate INDI cannot fly: refused where it is listed ... */
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_parse(&sc, "[run]\nduration_s = 1\ncontrollers = INDI\n[sensors]\nuse_rate = no\n",
                                                 "bad.ini", &err));
    TEST_ASSERT_EQUAL_STRING("INDI needs the measured rate ([sensors] use_rate = yes)", err.message);
    TEST_ASSERT_EQUAL_INT(5, err.line);
    /* ... and kept for --controllers where it is not */
    parse_ok("[run]\nduration_s = 1\n[sensors]\nuse_rate = no\n");
    TEST_ASSERT_EQUAL_INT(4, sc.n_controllers); /* the default list: the paper's four */
    TEST_ASSERT_EQUAL_INT(4, sc.controller_error[SIM_CTRL_INDI].line);
    const sim_controller_id_t indi[] = {SIM_CTRL_INDI};
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, indi, 1, &err));
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

/* ---- command-line settings and the list rule --------------------------------- */

static int parse_with(const char *text, const char *const *sets, int n)
{
    memset(&err, 0, sizeof err);
    return sim_scenario_parse_buffer_with(&sc, text, strlen(text), "f.ini", sets, n, &err);
}

static void test_settings_replace_the_files_values(void)
{
    const char *text = "[run]\nduration_s = 2\nseed = 5\n[reference]\nroll = 0 .. 1 : 3\nroll = 1 .. : 4\n"
                       "[sensors]\nangle_noise_var_deg2 = 4\n[controller LADRC]\nwc_rad_s = 10\n";
    const char *sets[] = {"run.seed=9", "controller:LADRC.wc_rad_s=20", "controller PID.pid_kp = 2",
                          "reference.roll=.. 0.5: 7", "reference.roll=0.5 ..: 8",
                          "sensors.angle_noise_std_deg=1", "metrics.settle_band_deg=2"};
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
        {"run.seed=abc", 10, "expected an unsigned integer, got 'abc'"},
        {"seed=3", 1, "expected SECTION.KEY=VALUE, got 'seed=3'"},
        {"runs.seed=3", 1, "unknown section 'runs'"},
        {"run.sed=3", 5, "unknown key 'sed' in [run]"},
        {"controller:LADRC.pid_kp=1", 18, "'pid_kp' does not apply to LADRC"},
        {"controller:XY.wc_rad_s=1", 12, "unknown controller 'XY' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, "
                                         "CASCADED or INDI)"},
        {"controller.wc_rad_s=1", 11, "expected a controller name after 'controller' ('controller:NAME.KEY=VALUE')"},
        {"controller:LADRC.wc_rad_s=-1", 27, "wc_rad_s must be > 0"},
        {"run.duration_s=", 16, "missing value for 'duration_s'"},
        {"run.controllers=LADRC,,PID", 23, "expected a controller name before ','"},
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
        {"LADRC,", 6, "expected a controller name"},
        {",LADRC", 0, "expected a controller name before ','"},
        {"LADRC,,PID", 6, "expected a controller name before ','"},
        {"LADRC PID,LADRC", 10, "controller 'LADRC' listed twice"},
        {"LADRC;PID", 0, "unknown controller 'LADRC;PID' (expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED or "
                         "INDI)"},
        {"", 0, "expected a controller name"},
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
    const bad_case_t cases[] = {{"[run]\nduration_s = 1\ncontrollers = PID,\n", 3, 19, "expected a controller name"}};
    CHECK_BAD_CASES(cases);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_fill_every_key_not_given);
    RUN_TEST(test_every_attitude_key_lands_in_its_field_in_its_unit);
    RUN_TEST(test_controllers_model_the_airframe_unless_told_otherwise);
    RUN_TEST(test_tune_keys_land_in_their_controller_with_their_defaults);
    RUN_TEST(test_tune_errors_name_the_key);
    RUN_TEST(test_std_and_variance_keys_set_the_same_noise);
    RUN_TEST(test_every_override_key_lands_in_its_controller);
    RUN_TEST(test_every_differentiator_key_lands_in_its_field);
    RUN_TEST(test_signal_windows_hold_from_exclusive_to_inclusive);
    RUN_TEST(test_signal_eval_takes_the_first_piece_that_holds_t_and_scales_it);
    RUN_TEST(test_layout_comments_blank_lines_crlf_tabs_and_bom);
    RUN_TEST(test_name_and_default_output_dir_come_from_the_file_name);
    RUN_TEST(test_controller_names);
    RUN_TEST(test_shipped_paper_scenario);
    RUN_TEST(test_shipped_paper_noisy_scenario);
    RUN_TEST(test_shipped_table3_differentiator_scenario);
    RUN_TEST(test_shipped_steps_scenario);
    RUN_TEST(test_shipped_steps_and_real_scenarios_tune_every_controller);
    RUN_TEST(test_load_reports_a_missing_file_at_line_0);
    RUN_TEST(test_load_rejects_a_nul_byte_where_it_is);
    RUN_TEST(test_structure_errors);
    RUN_TEST(test_value_errors);
    RUN_TEST(test_signal_errors_point_into_the_expression);
    RUN_TEST(test_errors_checked_after_the_whole_file);
    RUN_TEST(test_run_limits_are_errors_at_the_key_responsible);
    RUN_TEST(test_runs_at_the_limits_are_accepted);
    RUN_TEST(test_values_the_library_refuses_are_errors_at_their_key);
    RUN_TEST(test_a_controller_not_listed_is_checked_when_chosen);
    RUN_TEST(test_indi_keys_land_and_indi_needs_the_rate);
    RUN_TEST(test_parse_buffer_needs_no_nul_and_refuses_one_inside);
    RUN_TEST(test_long_values_are_rejected_not_truncated);
    RUN_TEST(test_null_arguments_are_refused_and_err_is_optional);
    RUN_TEST(test_settings_replace_the_files_values);
    RUN_TEST(test_setting_errors_name_the_setting_and_column);
    RUN_TEST(test_controller_lists_take_commas_spaces_or_both);
    return UNITY_END();
}
