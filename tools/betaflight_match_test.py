#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""tools/betaflight_match.py without Betaflight: how a case is flown on both sides (its loop rate
and delay on the SITL's 8 kHz gyro and 1 kHz RC frames, Betaflight's motor_idle at the rotors' floor, the gyro
filters of the matched configuration), the refusals (a missing airframe key, a floor no
motor_idle gives, a notch with no twin), the table's ratios and misses, and a --doc pointed at
an input (exit 2, nothing written)."""

import math
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import betaflight_match as bm  # noqa: E402

AIRFRAME = """[run]
control_dt_s = {dt}
[vehicle]
inertia_kg_m2 = 0.01 0.01 0.02
arm_m = 0.2
thrust_coeff_N_s2 = 2e-5
yaw_coeff_Nm_s2 = 3e-7
[rotors]
w2_min_rad2_s2 = {w2_min}
w2_max_rad2_s2 = 5e5
motor_tau_s = 0.03
[sensors]
delay_ticks = 2
{extra}
"""


def case_file(folder, dt=0.001, w2_min=2e4, extra=""):
    path = os.path.join(folder, "case.ini")
    with open(path, "w") as f:
        f.write(AIRFRAME.format(dt=dt, w2_min=w2_min, extra=extra))
    return path


class CaseTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_1_ms_case_flies_as_it_is_every_8th_gyro_sample(self):
        c = bm.Case(case_file(self.dir), bm.CONFIGS["matched"])
        self.assertEqual((c.pid_denom, c.dt_s, c.delay_ticks), (8, 0.001, 2))
        self.assertNotIn("run.control_dt_s=0.001", c.sets)

    def test_a_2_ms_case_runs_betaflight_every_16th_gyro_sample(self):
        c = bm.Case(case_file(self.dir, dt=0.002), bm.CONFIGS["matched"])
        self.assertEqual((c.pid_denom, c.dt_s, c.delay_ticks), (16, 0.002, 2))

    def test_a_case_beyond_betaflights_loop_divider_flies_at_the_rc_frame_step(self):
        c = bm.Case(case_file(self.dir, dt=0.004), bm.CONFIGS["matched"])  # 32 gyro samples: above 16
        self.assertEqual((c.pid_denom, c.dt_s, c.delay_ticks), (8, 0.001, 8))
        self.assertIn("run.control_dt_s=0.001", c.sets)

    def test_a_case_faster_than_the_rc_frames_flies_at_1_ms_with_its_delay_in_time(self):
        c = bm.Case(case_file(self.dir, dt=0.0005), bm.CONFIGS["matched"])
        self.assertEqual((c.pid_denom, c.dt_s, c.delay_ticks), (8, 0.001, 1))  # 2 x 0.5 ms = 1 x 1 ms
        self.assertIn("run.control_dt_s=0.001", c.sets)
        self.assertIn("sensors.delay_ticks=1", c.sets)

    def test_motor_idle_is_the_rotors_floor_when_matched_and_betaflights_by_default(self):
        path = case_file(self.dir)
        self.assertEqual(bm.Case(path, bm.CONFIGS["matched"]).motor_idle, 400)  # 2e4 / 5e5 = 4 %
        self.assertEqual(bm.Case(path, bm.CONFIGS["defaults"]).motor_idle, 550)

    def test_a_floor_no_motor_idle_gives_is_refused(self):
        with self.assertRaisesRegex(bm.Refused, "w2_min_rad2_s2 / w2_max_rad2_s2 = 0.3: no Betaflight motor_idle"):
            bm.Case(case_file(self.dir, w2_min=1.5e5), bm.CONFIGS["matched"])

    def test_a_missing_airframe_key_is_refused_naming_it(self):
        path = case_file(self.dir)
        with open(path) as f:
            text = f.read().replace("arm_m = 0.2\n", "")
        with open(path, "w") as f:
            f.write(text)
        with self.assertRaisesRegex(bm.Refused, r"case.ini: \[vehicle\] arm_m missing"):
            bm.Case(path, bm.CONFIGS["matched"])

    def test_a_case_low_pass_is_betaflights_static_low_pass_1(self):
        c = bm.Case(case_file(self.dir, extra="[filter]\nrpm_harmonics = 3\nlpf_order = 2\nlpf_hz = 100\n"),
                    bm.CONFIGS["matched"])
        self.assertIn("set gyro_lpf1_type = BIQUAD", c.filter_cli)
        self.assertIn("set gyro_lpf1_static_hz = 100", c.filter_cli)
        for off in ("set gyro_lpf1_dyn_min_hz = 0", "set gyro_lpf2_static_hz = 0", "set simplified_gyro_filter = OFF"):
            self.assertIn(off, c.filter_cli)
        self.assertIn("filter.lpf_hz=100", c.sets)
        self.assertIn("filter.rpm_harmonics=0", c.sets)  # the SITL has no RPM filter

    def test_without_a_filter_the_native_first_order_has_betaflights_pt1_pole_per_tick(self):
        c = bm.Case(case_file(self.dir), bm.CONFIGS["matched"])
        self.assertIn("set gyro_lpf1_type = PT1", c.filter_cli)
        self.assertIn("set gyro_lpf1_static_hz = 250", c.filter_cli)
        self.assertIn("filter.lpf_order=1", c.sets)
        # 8 PT1 steps of k = 0.1641 at 8 kHz leave 0.2387 of the last tick's output; the bilinear
        # first order with that pole at 1 kHz: K = 0.6146, fc = atan(K) / (pi 1 ms) = 175.5 Hz
        self.assertIn("filter.lpf_hz=175.534", c.sets)
        c2 = bm.Case(case_file(self.dir, dt=0.002), bm.CONFIGS["matched"])
        self.assertIn("filter.lpf_hz=115.971", c2.sets)  # 16 steps a tick: a faster pole, below 250 Hz
        for hz, n, dt in ((250.0, 8, 1e-3), (100.0, 16, 2e-3), (400.0, 4, 5e-4)):
            fc = bm.pt1_twin_hz(hz, n, dt)
            k_bilinear = math.tan(math.pi * fc * dt)
            dt_gyro = dt / n
            k_pt1 = dt_gyro / (dt_gyro + 1 / (2 * math.pi * hz))
            self.assertAlmostEqual((1 - k_bilinear) / (1 + k_bilinear), (1 - k_pt1) ** n, places=12)

    def test_defaults_leave_the_filters_alone(self):
        c = bm.Case(case_file(self.dir, extra="[filter]\nlpf_hz = 100\n"), bm.CONFIGS["defaults"])
        self.assertEqual((c.filter_cli, c.sets), ([], []))
        self.assertEqual(c.rc_smoothing_cli, "set rc_smoothing = ON")

    def test_a_fixed_notch_has_no_twin(self):
        with self.assertRaisesRegex(bm.Refused, r"\[filter\] notch_hz: no Betaflight twin"):
            bm.Case(case_file(self.dir, extra="[filter]\nnotch_hz = 120\nlpf_hz = 100\n"), bm.CONFIGS["matched"])


class ReportTest(unittest.TestCase):
    def test_the_ratio_and_the_misses(self):
        with tempfile.TemporaryDirectory() as d:
            case = bm.Case(case_file(d), bm.CONFIGS["matched"])
        result = {"gains": {a: (30.0, 240.0) for a in bm.AXES},
                  "bf": {"roll": 1.04, "pitch": 0.94, "yaw": 0.5},
                  "native": {"roll": 1.0, "pitch": 1.0, "yaw": 0.5},
                  "gap": {a: 0.01 for a in bm.AXES}}
        lines = bm.report([(case, result)], "matched", "abc")
        rows = [line for line in lines if line.startswith("| ")][1:]
        self.assertIn("| +4.0 % |", rows[0])
        self.assertTrue(rows[0].endswith("| yes |"))
        self.assertIn("| -6.0 % |", rows[1])
        self.assertTrue(rows[1].endswith("| **no** |"))
        self.assertIn("2 of 3 case-axes within 5 %", lines[-1])


class DocTest(unittest.TestCase):
    def test_a_doc_over_an_input_is_refused_and_nothing_written(self):
        with tempfile.TemporaryDirectory() as d:
            path = case_file(d)
            with open(path) as f:
                before = f.read()
            proc = subprocess.run([sys.executable, os.path.join(HERE, "betaflight_match.py"), d, path,
                                   "--doc", path], capture_output=True, text=True)
            self.assertEqual(proc.returncode, 2)
            self.assertIn("is the same file as", proc.stderr)
            with open(path) as f:
                self.assertEqual(f.read(), before)
            self.assertEqual(os.listdir(d), ["case.ini"])


if __name__ == "__main__":
    unittest.main()
