/* SPDX-License-Identifier: BSD-3-Clause */
/* Scenario files, well-formed: the defaults, every key read into its field
 * with its unit, each controller's overrides and tuning keys, the layout of
 * a file (comments, blank lines, CRLF, tabs, a byte order mark), the name. */
#include "unity.h"
#include "scenario_cases.h"
#include "scenario/excitation.h"

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
    TEST_ASSERT_EQUAL_INT(0, sc.rigid_body); /* the paper's kinematics, Euler frame */
    TEST_ASSERT_EQUAL_INT(LADRC_FRAME_EULER, sc.frame);
    assert_close((double)LADRC_YAW_WEIGHT_DEFAULT, sc.yaw_weight, "yaw_weight"); /* the library's */

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
             "kinematics = rigid\n"
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
             "frame = quaternion\n"
             "yaw_weight = 0.25\n"
             "[disturbance]\n"
             "roll = 2 .. 6 : 8\n"
             "pitch = 6\n"
             "yaw = .. 1 : -4\n"
             "[metrics]\n"
             "error_window_s = 1 20\n"
             "steady_window_s = 15 18.5\n"
             "settle_band_deg = 0.2\n"
             "settle_window_s = 2 4\n"
             "[wind]\n"
             "mean_m_s = 5\n"
             "from_deg = 270\n"
             "[phases]\n"
             "arm_s = 1 15\n"
             "takeoff_s = 4 16\n"
             "land_s = 12\n"
             "disarm_s = 13\n"
             "ground_deg = 4 -2.5\n"
             "ground_thrust = 0.3\n"
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
    TEST_ASSERT_EQUAL_INT(1, sc.rigid_body);
    TEST_ASSERT_EQUAL_INT(LADRC_FRAME_QUATERNION, sc.frame);
    assert_close(5.0, sc.mean_wind_m_s, "mean wind");
    assert_close(270.0 * DEG, sc.mean_wind_from_rad, "wind from, degrees to rad");
    /* the timeline: arm, take off, land, disarm, arm, take off */
    static const int kinds[6] = {SIM_EVENT_ARM,    SIM_EVENT_TAKEOFF, SIM_EVENT_LAND,
                                 SIM_EVENT_DISARM, SIM_EVENT_ARM,     SIM_EVENT_TAKEOFF};
    static const double times[6] = {1, 4, 12, 13, 15, 16};
    TEST_ASSERT_EQUAL_INT(6, sc.n_events);
    for (int e = 0; e < 6; ++e) {
        TEST_ASSERT_EQUAL_INT(kinds[e], sc.event_kind[e]);
        assert_close(times[e], sc.event_s[e], "event time");
    }
    assert_close(4.0 * DEG, sc.ground_rad[0], "ground roll");
    assert_close(-2.5 * DEG, sc.ground_rad[1], "ground pitch");
    assert_close(0.3, sc.ground_thrust, "ground thrust");
    assert_close(0.25, sc.yaw_weight, "yaw_weight");

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
             "tune_step_deg = 5\ntune_disturbance_step_rad_s2 = 0\n"
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
    assert_close(5.0 * (3.14159265358979323846 / 180.0), o[SIM_CTRL_LADRC].tune_step_rad, "objective's reference step");
    TEST_ASSERT_TRUE(o[SIM_CTRL_LADRC].tune_dist_rad_s2 == 0.0);
    TEST_ASSERT_TRUE(isnan(o[SIM_CTRL_PID].tune_step_rad) && isnan(o[SIM_CTRL_PID].tune_dist_rad_s2));
    TEST_ASSERT_EQUAL_INT(SIM_TUNE_NONE, o[SIM_CTRL_LP_MLADRC].tune);
    TEST_ASSERT_EQUAL_INT(-1, o[SIM_CTRL_HP_MLADRC].tune); /* absent: none */
    /* where the errors of the tuning point: the value of each tune key */
    TEST_ASSERT_EQUAL_INT(4, sc.tune_line[SIM_CTRL_LADRC]);
    TEST_ASSERT_EQUAL_INT(8, sc.tune_column[SIM_CTRL_LADRC]);
    TEST_ASSERT_EQUAL_INT(10, sc.tune_line[SIM_CTRL_PID]);
    TEST_ASSERT_EQUAL_INT(0, sc.tune_line[SIM_CTRL_HP_MLADRC]);
    /* parsing tunes nothing: the gains stay the library's until sim_tune_controller runs */
    for (int id = 0; id < SIM_CTRL_COUNT; ++id)
        TEST_ASSERT_EQUAL_INT(0, sc.tuning[id].tuned);
    /* the noise cap's keys: absent, no cap and no reference, ratio 1 */
    TEST_ASSERT_TRUE(isnan(o[SIM_CTRL_LADRC].tune_noise_max_Nm));
    TEST_ASSERT_EQUAL_INT(-1, o[SIM_CTRL_LADRC].tune_noise_ref);
    assert_close(1.0, o[SIM_CTRL_LADRC].tune_noise_ratio, "default noise ratio");
    assert_close(45.0, SIM_TUNE_PM_DEG_DEFAULT, "default PM target");
    assert_close(6.0, SIM_TUNE_GM_DB_DEFAULT, "default GM target");
}

static void test_tune_errors_name_the_key(void)
{
    static const bad_case_t cases[] = {
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = auto\n",
         .line = 4,
         .column = 8,
         .message = "expected none or margins, got 'auto'"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune_phase_margin_deg = 50\n",
         .line = 4,
         .column = 1,
         .message = "'tune_phase_margin_deg' applies only with tune = margins"},
        {.text = "[run]\nduration_s = 1\n[controller PID]\ntune = none\ntune_gain_margin_db = 6\n",
         .line = 5,
         .column = 1,
         .message = "'tune_gain_margin_db' applies only with tune = margins"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_phase_margin_deg = 90\n",
         .line = 5,
         .column = 25,
         .message = "tune_phase_margin_deg must be > 0 and < 90"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_gain_margin_db = 0\n",
         .line = 5,
         .column = 23,
         .message = "tune_gain_margin_db must be > 0"},
        {.text = "[run]\nduration_s = 1\n[controller PID]\ntune_step_deg = 5\n",
         .line = 4,
         .column = 1,
         .message = "'tune_step_deg' applies only with tune = margins"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_step_deg = 30\n",
         .line = 5,
         .column = 17,
         .message = "tune_step_deg must be between 0 and 28.6"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_disturbance_step_rad_s2 = -1\n",
         .line = 5,
         .column = 32,
         .message = "tune_disturbance_step_rad_s2 must be >= 0"},
        {.text = "[run]\nkind = differentiator\nduration_s = 1\n[differentiator]\nsignal = t\nderivative = 1\n"
                 "[controller LADRC]\ntune = margins\n",
         .line = 7,
         .column = 1,
         .message = "[controller LADRC] does not apply to kind = differentiator"},
    };
    CHECK_BAD_CASES(cases);
}

static void test_noise_cap_keys_land_in_their_controller(void)
{
    parse_ok("[run]\nduration_s = 1\ncontrollers = LADRC PID RATE-ADRC\n[sensors]\nuse_rate = yes\n"
             "[controller LADRC]\ntune = margins\ntune_noise_ref = PID\ntune_noise_ratio = 1.5\n"
             "[controller PID]\ntune = margins\ntune_noise_max_Nm = 0.02\n"
             "[controller RATE-ADRC]\ntune = margins\ntune_noise_ref = PID\n");
    const sim_overrides_t *o = sc.overrides;
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, o[SIM_CTRL_LADRC].tune_noise_ref);
    assert_close(1.5, o[SIM_CTRL_LADRC].tune_noise_ratio, "noise ratio");
    TEST_ASSERT_TRUE(isnan(o[SIM_CTRL_LADRC].tune_noise_max_Nm));
    assert_close(0.02, o[SIM_CTRL_PID].tune_noise_max_Nm, "noise cap");
    TEST_ASSERT_EQUAL_INT(-1, o[SIM_CTRL_PID].tune_noise_ref);
    TEST_ASSERT_EQUAL_INT(SIM_CTRL_PID, o[SIM_CTRL_RATE_ADRC].tune_noise_ref);
}

static void test_bad_noise_cap_keys_fail_at_the_key(void)
{
    static const bad_case_t cases[] = {
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune_noise_max_Nm = 0.1\n",
         .line = 4,
         .column = 1,
         .message = "'tune_noise_max_Nm' applies only with tune = margins"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_max_Nm = 0\n",
         .line = 5,
         .column = 21,
         .message = "tune_noise_max_Nm must be > 0"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = FOO\n",
         .line = 5,
         .column = 18,
         .message = "expected HP-MLADRC, LP-MLADRC, LADRC, PID, CASCADED, INDI or RATE-ADRC, got 'FOO'"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = LADRC\n",
         .line = 5,
         .column = 18,
         .message = "tune_noise_ref must name another controller, not LADRC itself"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = PID\n",
         .line = 5,
         .column = 18,
         .message = "tune_noise_ref: PID is not tuned (its tune = margins is missing)"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = CASCADED\n"
                 "[controller CASCADED]\ntune = margins\n",
         .line = 5,
         .column = 18,
         .message = "tune_noise_ref: the scenario does not fly CASCADED ([run] controllers)"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = PID\n"
                 "[controller PID]\ntune = margins\ntune_noise_ref = LADRC\n",
         .line = 5,
         .column = 18,
         .message = "tune_noise_ref: PID takes its own cap from another controller's noise; name one that does not"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_max_Nm = 0.1\n"
                 "tune_noise_ref = PID\n[controller PID]\ntune = margins\n",
         .line = 6,
         .column = 1,
         .message = "'tune_noise_ref' conflicts with tune_noise_max_Nm (line 5): give one of them"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ratio = 2\n",
         .line = 5,
         .column = 1,
         .message = "'tune_noise_ratio' applies only with tune_noise_ref"},
        {.text = "[run]\nduration_s = 1\n[controller LADRC]\ntune = margins\ntune_noise_ref = PID\n"
                 "tune_noise_ratio = -1\n[controller PID]\ntune = margins\n",
         .line = 6,
         .column = 20,
         .message = "tune_noise_ratio must be > 0"},
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
    TEST_ASSERT_EQUAL_INT(
        -1,
        sim_scenario_parse(&sc, "[run]\nduration_s = 1\n[controller LADRC]\nindi_filter_rad_s = 9\n", "bad.ini", &err));
    /* without the measured rate INDI cannot fly: refused where it is listed ... */
    TEST_ASSERT_EQUAL_INT(
        -1, sim_scenario_parse(&sc, "[run]\nduration_s = 1\ncontrollers = INDI\n[sensors]\nuse_rate = no\n", "bad.ini",
                               &err));
    TEST_ASSERT_EQUAL_STRING("INDI needs the measured rate ([sensors] use_rate = yes)", err.message);
    TEST_ASSERT_EQUAL_INT(5, err.line);
    /* ... and kept for --controllers where it is not */
    parse_ok("[run]\nduration_s = 1\n[sensors]\nuse_rate = no\n");
    TEST_ASSERT_EQUAL_INT(4, sc.n_controllers); /* the default list: the paper's four */
    TEST_ASSERT_EQUAL_INT(4, sc.controller_error[SIM_CTRL_INDI].line);
    const sim_controller_id_t indi[] = {SIM_CTRL_INDI};
    TEST_ASSERT_EQUAL_INT(-1, sim_scenario_set_controllers(&sc, indi, 1, &err));
}

/* [excitation]: absent, none; given, every key in its field, the defaults
 * for the rest (f1 capped at 0.45 / control_dt_s when not given); [run]
 * log: the forms as bits, in any order and separation. */
static void test_excitation_and_log_keys_land_in_their_fields(void)
{
    parse_ok("[run]\nduration_s = 12\n");
    TEST_ASSERT_EQUAL_INT(0, sc.excite_on);
    TEST_ASSERT_EQUAL_INT(0, sc.log_forms);

    parse_ok("[run]\nduration_s = 12\n[excitation]\n");
    TEST_ASSERT_EQUAL_INT(1, sc.excite_on);
    TEST_ASSERT_EQUAL_INT(SIM_EXCITE_ROLL, sc.excite_axis);
    assert_close(0.2, sc.excite_amplitude[0], "amplitude");
    TEST_ASSERT_EQUAL_INT(1, sc.excite_n_amplitudes);
    assert_close(1.0, sc.excite_f0_hz, "f0_hz");
    assert_close(40.0, sc.excite_f1_hz, "f1_hz");
    assert_close(1.0, sc.excite_start_s, "start_s");
    assert_close(10.0, sc.excite_duration_s, "duration_s");

    parse_ok("[run]\nduration_s = 40\ncontrol_dt_s = 0.004\ncontrollers = PID\nlog = generic px4,betaflight\n"
             "[excitation]\naxis = all\namplitude = 1\nf0_hz = 0.5\nf1_hz = 112.5\nstart_s = 0\nduration_s = 13\n");
    TEST_ASSERT_EQUAL_INT(SIM_EXCITE_ALL, sc.excite_axis);
    assert_close(1.0, sc.excite_amplitude[0], "amplitude");
    assert_close(0.5, sc.excite_f0_hz, "f0_hz");
    assert_close(112.5, sc.excite_f1_hz, "f1_hz"); /* 0.45 / 0.004, given: accepted */
    assert_close(0.0, sc.excite_start_s, "start_s");
    assert_close(13.0, sc.excite_duration_s, "duration_s");
    assert_close(40.0, sc.duration_s, "[run] duration_s"); /* a key of the same name elsewhere */
    TEST_ASSERT_EQUAL_INT(SIM_RUN_LOG_BETAFLIGHT | SIM_RUN_LOG_PX4 | SIM_RUN_LOG_GENERIC, sc.log_forms);

    parse_ok("[run]\nduration_s = 12\ncontrol_dt_s = 0.02\ncontrollers = PID\nlog = px4\n[excitation]\naxis = yaw\n");
    TEST_ASSERT_EQUAL_INT(SIM_EXCITE_YAW, sc.excite_axis);

    assert_close(22.5, sc.excite_f1_hz, "f1_hz capped at 0.45 / control_dt_s");
    TEST_ASSERT_EQUAL_INT(SIM_RUN_LOG_PX4, sc.log_forms);
    /* one amplitude per axis: each chirp at its own */
    parse_ok("[run]\nduration_s = 40\n[excitation]\naxis = all\namplitude = 0.1 0.2 0.6\nduration_s = 10\n");
    TEST_ASSERT_EQUAL_INT(3, sc.excite_n_amplitudes);
    assert_close(0.6, sc.excite_amplitude[2], "yaw's amplitude");
    double c[3], peak[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 31000; ++k) {
        sim_excitation_at(&sc, 1.0 + k * 1e-3, c);
        for (int i = 0; i < 3; ++i) {
            peak[i] = fmax(peak[i], fabs(c[i]));
        }
    }
    for (int i = 0; i < 3; ++i) { /* sampled at 1 ms, the 1 Hz start's peaks reach the amplitude within 1e-5 */
        TEST_ASSERT_TRUE(fabs(peak[i] - sc.excite_amplitude[i]) <= 1e-5);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_defaults_fill_every_key_not_given);
    RUN_TEST(test_every_attitude_key_lands_in_its_field_in_its_unit);
    RUN_TEST(test_noise_cap_keys_land_in_their_controller);
    RUN_TEST(test_bad_noise_cap_keys_fail_at_the_key);
    RUN_TEST(test_controllers_model_the_airframe_unless_told_otherwise);
    RUN_TEST(test_tune_keys_land_in_their_controller_with_their_defaults);
    RUN_TEST(test_tune_errors_name_the_key);
    RUN_TEST(test_std_and_variance_keys_set_the_same_noise);
    RUN_TEST(test_every_override_key_lands_in_its_controller);
    RUN_TEST(test_every_differentiator_key_lands_in_its_field);
    RUN_TEST(test_layout_comments_blank_lines_crlf_tabs_and_bom);
    RUN_TEST(test_name_and_default_output_dir_come_from_the_file_name);
    RUN_TEST(test_controller_names);
    RUN_TEST(test_indi_keys_land_and_indi_needs_the_rate);
    RUN_TEST(test_excitation_and_log_keys_land_in_their_fields);
    return UNITY_END();
}
