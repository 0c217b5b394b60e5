#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The Python binding against the C library, bit for bit.

Usage: test_binding.py TRACE_PROGRAM TRACE_FILE
(LADRC_LIBRARY names the shared library and PYTHONPATH holds python/, or the
package is installed: tools/run_tests.sh python-package.)

Runs TRACE_PROGRAM (tests/python/binding_trace.c), which flies closed loops
with the library and writes each tick's inputs and outputs as the bits of the
reals; replays the inputs through the binding with the same configs (given as
dicts) and requires every output to have the same bits. Also checks that an
invalid config raises LadrcError with the library's status text. Exits 77
(skipped) when NumPy is missing."""
import subprocess
import sys

try:
    import numpy as np
except ImportError:
    print("SKIPPED: NumPy is not installed (Debian: apt-get install python3-numpy)")
    sys.exit(77)

import ladrc

VARIANTS = ["LADRC", "LP_MLADRC", "HP_MLADRC", "PID", "CASCADED", "INDI", "RATE_ADRC"]


def axis_dict(variant):
    """The overrides of binding_trace.c's axis_overrides(), as a dict."""
    d = {"variant": variant, "dt_s": 0.001, "inertia_kg_m2": 5.445e-3,
         "wc_rad_s": 18.0, "u_min_Nm": -0.05, "u_max_Nm": 0.05,
         "motor_tau_s": 0.02, "delay_ticks": 2, "wrap_angle": 1}
    if variant == "HP_MLADRC":
        d.update(hp_freq_mode="ONLINE")
    if variant == "PID":
        d.update(pid_kp=0.2)
    if variant == "INDI":
        d.update(indi_rate_kp_per_s=25.0)
    if variant == "RATE_ADRC":
        d.update(radrc_kp_per_s=30.0, radrc_att_kp_per_s=8.0, radrc_rate_max_rad_s=2.0)
    if variant == "CASCADED":
        d.update(cas_att_kp=6.0, cas_rate_max_rad_s=2.0, cas_i_limit_Nm=0.01)
    return d


def main():
    exe, trace = sys.argv[1], sys.argv[2]
    subprocess.run([exe, trace], check=True)
    lib = ladrc.load()
    utype = np.uint32 if lib.dtype == np.float32 else np.uint64
    lines = open(trace).read().split("\n")
    real_size = int(lines[0].split()[1])
    assert real_size == np.dtype(lib.dtype).itemsize, "trace and library differ in the real type"

    def reals(words):
        return np.array([int(w, 16) for w in words], dtype=utype).view(lib.dtype)

    def bits(x):
        return np.asarray(x, dtype=lib.dtype).view(utype)

    axis_rows = {v: [] for v in range(len(VARIANTS))}
    att_rows = []
    for line in lines[1:]:
        w = line.split()
        if not w:
            continue
        if w[0] == "axis":
            axis_rows[int(w[1])].append(w[2:])
        elif w[0] == "att":
            att_rows.append(w[1:])
    failures = []
    checked = 0

    for v, rows in axis_rows.items():
        axis = ladrc.Axis(axis_dict(VARIANTS[v]))
        for k, row in enumerate(rows):
            ref, angle, rate, u_c = reals(row[:4])
            u = axis.step(ref, angle, rate)
            axis.set_applied(u)
            checked += 1
            if bits(u) != bits(u_c) or axis.faults != int(row[4]):
                failures.append(f"axis {VARIANTS[v]} tick {k}: binding {u!r} faults {axis.faults}, "
                                f"C {u_c!r} faults {row[4]}")
                break

    # The array form: Axis.run over the same inputs gives the same commands.
    for v, rows in axis_rows.items():
        x = np.array([reals(row[:4]) for row in rows])
        u, faults = ladrc.Axis(axis_dict(VARIANTS[v])).run(x[:, 0], x[:, 1], x[:, 2])
        checked += len(rows)
        if not (np.array_equal(bits(u), bits(x[:, 3]))
                and np.array_equal(faults, np.array([int(row[4]) for row in rows]))):
            failures.append(f"axis {VARIANTS[v]}: Axis.run differs from the C trace")

    att = ladrc.Attitude({"variant": "HP_MLADRC", "dt_s": 0.001,
                          "inertia_kg_m2": [5.445e-3, 5.445e-3, 1.089e-2], "drag_Nms": 0.09,
                          "axis": {"wc_rad_s": 16.0}})
    mixer = ladrc.Mixer({"kL_N_s2": 2.98e-5, "arm_m": 0.165, "b_Nm_s2": 2e-6, "mass_kg": 0.8,
                         "g_m_s2": 9.81, "w2_min_rad2_s2": 6.2e4, "w2_max_rad2_s2": 6.9e4,
                         "tilt_max_rad": 0.7, "mode": "SATURATE"})
    saturated_ticks = 0
    for k, row in enumerate(att_rows):
        x = reals(row[:20])
        ref, angle, rate, torque_c = x[0:3], x[3:6], x[6:9], x[9:12]
        thrust_c, w2_c, achieved_c = x[12], x[13:17], x[17:20]
        torque, faults = att.step(ref, angle, rate)
        thrust = mixer.thrust_from_tilt(angle[0], angle[1])
        out = mixer.step(thrust, torque)
        att.set_applied(out.torque_Nm)
        checked += 1
        saturated_ticks += out.saturated != 0
        same = (np.array_equal(bits(torque), bits(torque_c)) and bits(thrust) == bits(thrust_c)
                and np.array_equal(bits(out.w2_rad2_s2), bits(w2_c))
                and np.array_equal(bits(out.torque_Nm), bits(achieved_c))
                and faults == int(row[20]) and out.saturated == int(row[21]))
        if not same:
            failures.append(f"attitude tick {k}: binding {torque} {out.w2_rad2_s2}, C {torque_c} {w2_c}")
            break

    # Statuses as exceptions with the library's text.
    try:
        ladrc.Axis({"variant": "LADRC", "dt_s": -1.0, "inertia_kg_m2": 5.445e-3})
        failures.append("a negative dt_s was accepted")
    except ladrc.LadrcError as e:
        if not str(e).startswith("LADRC_ERR_DT_S"):
            failures.append(f"dt_s error text: {e}")
    try:
        ladrc.Attitude({"variant": "LADRC", "dt_s": 0.001, "inertia_kg_m2": [1e-3, 1e-3, 2e-3],
                        "drag_Nms": 0.0, "yaw": {"wo_rad_s": 0.0}})
        failures.append("wo_rad_s = 0 was accepted")
    except ladrc.LadrcError as e:
        if e.axis != 2 or not e.text.startswith("LADRC_ERR_WO_RAD_S"):
            failures.append(f"attitude error: axis {e.axis}, text {e.text}")
    for field, value, status in (("motor_tau_s", -0.01, "LADRC_ERR_MOTOR_TAU_S"),
                                 ("delay_ticks", 401, "LADRC_ERR_DELAY_TICKS"),
                                 ("wrap_angle", 2, "LADRC_ERR_WRAP_ANGLE")):
        try:
            ladrc.Axis({"variant": "LADRC", "dt_s": 0.001, "inertia_kg_m2": 5.445e-3, field: value})
            failures.append(f"{field} = {value} was accepted")
        except ladrc.LadrcError as e:
            if not str(e).startswith(status):
                failures.append(f"{field} error text: {e}")
    try:
        ladrc.Axis({"variant": "LADRC", "dt_s": 0.001, "inertia_kg_m2": 1e-3, "wc": 3.0})
        failures.append("an unknown field was accepted")
    except KeyError:
        pass

    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        return 1
    if saturated_ticks == 0:
        print("FAILED: the trace never saturates the mixer; the case tests less than it should")
        return 1
    print(f"binding equals the C library bit for bit on {checked} ticks "
          f"({saturated_ticks} with a saturated mixer), real = {np.dtype(lib.dtype).name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
