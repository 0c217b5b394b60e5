/* SPDX-License-Identifier: BSD-3-Clause */
/* The shipped scenarios as files: the paper's cases against its Table 2,
 * the differentiator and step scenarios, the tuned ones; reading a file
 * that is missing or holds a NUL byte. */
#include "unity.h"
#include "scenario_cases.h"

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
    static const char *const files[] = {"steps.ini",
                                        "real_paper_lag20.ini",
                                        "real_paper_lag30.ini",
                                        "real_paper_lag40.ini",
                                        "real_heavy_lag20.ini",
                                        "real_heavy_lag30.ini",
                                        "real_heavy_lag40.ini"};
    for (unsigned f = 0; f < sizeof files / sizeof files[0]; ++f) {
        load_ok(files[f]);
        /* every controller before RATE-ADRC at least (the files choose
         * whether to fly it too), each listed one tuned */
        TEST_ASSERT_TRUE_MESSAGE(sc.n_controllers >= SIM_CTRL_RATE_ADRC, files[f]);
        for (int id = 0; id < SIM_CTRL_RATE_ADRC; ++id) {
            int listed = 0;
            for (int c = 0; c < sc.n_controllers; ++c) {
                listed |= (int)sc.controllers[c] == id;
            }
            TEST_ASSERT_TRUE_MESSAGE(listed, files[f]);
        }
        for (int c = 0; c < sc.n_controllers; ++c) {
            TEST_ASSERT_EQUAL_INT_MESSAGE(SIM_TUNE_MARGINS, sc.overrides[sc.controllers[c]].tune, files[f]);
        }
        if (f == 0)
            continue;
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

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_shipped_paper_scenario);
    RUN_TEST(test_shipped_paper_noisy_scenario);
    RUN_TEST(test_shipped_table3_differentiator_scenario);
    RUN_TEST(test_shipped_steps_scenario);
    RUN_TEST(test_shipped_steps_and_real_scenarios_tune_every_controller);
    RUN_TEST(test_load_reports_a_missing_file_at_line_0);
    RUN_TEST(test_load_rejects_a_nul_byte_where_it_is);
    return UNITY_END();
}
