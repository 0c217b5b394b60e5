#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Identification from flight logs against the truth, on random airframes.

Draws N airframes (mass, arm, inertia, motor lag, delay, damping, control
rate, gyro noise and vibration), flies each twice with ladrc_sil (CASCADED
tuned by tune = margins): once through a chirp on each axis in turn
([excitation]), once through ordinary manoeuvres; both runs write their log
in the Betaflight and PX4 forms ([run] log). ladrc_replay --identify-only
identifies each log, and the figures are held to:
  chirp:       b0 within 5 %, the motor lag within 10 % or 2 ms, the delay exact;
  manoeuvres:  the truth inside the stated intervals, or a weak-excitation warning.

Usage: tools/log_ident_check.py --sil BIN --replay BIN [--n 20] [--seed 1]
                                [--out DIR] [--jobs 2] [--markdown FILE]
Prints one line per log and axis and a summary; exit status 1 when a
figure is missed, 2 on bad usage or a tool that failed.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import random
import subprocess
import sys

G = 9.81
AXES = ("roll", "pitch", "yaw")
FORMS = {"betaflight": "CASCADED_betaflight.csv", "px4": "CASCADED_px4"}
B0_TOL, LAG_REL_TOL, LAG_ABS_TOL_S = 0.05, 0.10, 0.002
SIL_BATCH = 30  # scenarios per ladrc_sil call (it takes 32 at most)


def draw(rng, k):
    """One airframe: its scenario values and the truth the logs must give."""
    mass = math.exp(rng.uniform(math.log(0.25), math.log(3.0)))
    arm = 0.15 * mass ** (1.0 / 3.0) * rng.uniform(0.8, 1.2)
    j_roll = rng.uniform(0.25, 0.6) * mass * arm * arm
    j = (j_roll, j_roll * rng.uniform(1.0, 1.1), j_roll * rng.uniform(1.6, 1.95))
    hover_hz = rng.uniform(80.0, 250.0)
    w2_hover = (2.0 * math.pi * hover_hz) ** 2
    kl = mass * G / (4.0 * w2_hover)
    b = kl * rng.uniform(0.01, 0.03)
    damping = rng.uniform(0.0, 5.0)  # 1/s about roll
    af = {
        "k": k,
        "mass": mass, "arm": arm, "J": j, "kL": kl, "b": b, "kt": damping * j_roll,
        "w2_hover": w2_hover,
        "tau": rng.uniform(0.010, 0.060),
        "delay": rng.randint(0, 4),
        "dt": rng.choice((0.001, 0.001, 0.002)),
        "noise_deg_s": rng.uniform(0.1, 0.8),
        "vib_deg_s": rng.uniform(0.0, 1.5),
    }
    authority = (arm * mass * G / 2.0, arm * mass * G / 2.0, b * mass * G / kl)
    af["b0"] = tuple(a / ji for a, ji in zip(authority, j))
    return af


def scenario(af, flight):
    """The scenario text of one flight (chirp or manoeuvres) of an airframe."""
    j = af["J"]
    if flight == "chirp":
        duration, middle = 40, ("[excitation]\naxis = all\namplitude = 0.3 0.3 0.8\nf0_hz = 1\nf1_hz = 40\n"
                                "start_s = 1\nduration_s = 12\n\n[reference]\nroll = 0\npitch = 0\nyaw = 0\n")
    else:
        duration, middle = 30, ("[reference]                     # degrees: a pilot's steps and sweeps\n"
                                "roll = 2 .. 6 : 15\nroll = 6 .. 10 : -15\nroll = 14 .. 26 : 20*sin(1.7*t)\n"
                                "pitch = 4 .. 8 : -12\npitch = 8 .. 12 : 12\npitch = 16 .. 28 : 15*cos(1.1*t)\n"
                                "yaw = 3 .. 9 : 30\nyaw = 18 .. 24 : -20\n")
    return f"""# Airframe {af['k']} of tools/log_ident_check.py, {flight}
[run]
duration_s = {duration}
control_dt_s = {af['dt']}
plant_substeps = 10
seed = {100 + af['k']}
controllers = CASCADED
log = betaflight px4

[vehicle]
mass_kg = {af['mass']:.9g}
inertia_kg_m2 = {j[0]:.9g} {j[1]:.9g} {j[2]:.9g}
arm_m = {af['arm']:.9g}
thrust_coeff_N_s2 = {af['kL']:.9g}
yaw_coeff_Nm_s2 = {af['b']:.9g}
rot_drag_Nm_s = {af['kt']:.9g}
g_m_s2 = {G}

[rotors]
ideal = no
w2_min_rad2_s2 = {0.05 * af['w2_hover']:.9g}
w2_max_rad2_s2 = {2.0 * af['w2_hover']:.9g}
motor_tau_s = {af['tau']:.9g}

[sensors]
angle_noise_std_deg = 0.05
rate_noise_std_deg_s = {af['noise_deg_s']:.6g}
delay_ticks = {af['delay']}
use_rate = yes

[vibration]
orders = 1 2 3
gyro_deg_s = {af['vib_deg_s']:.4g} {0.3 * af['vib_deg_s']:.4g} {0.15 * af['vib_deg_s']:.4g}
accel_m_s2 = 1 0.3 0.2

{middle}
[controller CASCADED]
tune = margins
"""


def read_identification(path):
    with open(path, newline="") as f:
        return {row["axis"]: row for row in csv.DictReader(f)}


def inside(af, row, axis):
    """1 when b0, the lag and the delay of the truth all lie in the stated intervals."""
    i = AXES.index(axis)
    return (float(row["b0_lo_rad_s2"]) <= af["b0"][i] <= float(row["b0_hi_rad_s2"])
            and float(row["lag_lo_s"]) <= af["tau"] <= float(row["lag_hi_s"])
            and int(row["delay_lo_ticks"]) <= af["delay"] <= int(row["delay_hi_ticks"]))


def judge(af, flight, row, axis):
    """(passed, text) of one axis's identification against the truth."""
    i = AXES.index(axis)
    b0_t, tau_t, d_t = af["b0"][i], af["tau"], af["delay"]
    b0, lag, d = float(row["b0_rad_s2"]), float(row["lag_s"]), int(row["delay_ticks"])
    warn = int(row["warnings"])
    b0_err, lag_err = (b0 - b0_t) / b0_t, lag - tau_t
    if flight == "chirp":
        ok = abs(b0_err) <= B0_TOL and abs(lag_err) <= max(LAG_REL_TOL * tau_t, LAG_ABS_TOL_S) and d == d_t
    else:
        ok = inside(af, row, axis) or warn != 0
    text = (f"b0 {b0:8.4g} (true {b0_t:8.4g}, {100 * b0_err:+6.2f} %) lag {1e3 * lag:5.1f} ms "
            f"(true {1e3 * tau_t:5.1f}) delay {d} (true {d_t}) warnings {warn:#04x}")
    return ok, text, b0_err, lag_err, d == d_t, warn


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sil", required=True)
    ap.add_argument("--replay", required=True)
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="build/log_ident_check")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--markdown")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    airframes = [draw(rng, k) for k in range(args.n)]
    os.makedirs(args.out, exist_ok=True)
    files = []
    for af in airframes:
        for flight in ("chirp", "manoeuvres"):
            path = os.path.join(args.out, f"af{af['k']:02d}_{flight}.ini")
            with open(path, "w") as f:
                f.write(scenario(af, flight))
            files.append(path)
    for first in range(0, len(files), SIL_BATCH):
        flown = subprocess.run([args.sil, *files[first:first + SIL_BATCH], "--out", args.out, "--jobs",
                                str(args.jobs), "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if flown.returncode != 0:
            sys.stderr.write(flown.stderr)
            sys.exit(f"log_ident_check: ladrc_sil failed ({flown.returncode})")

    def identify(task):
        af, flight, form = task
        run = os.path.join(args.out, f"af{af['k']:02d}_{flight}")
        out = os.path.join(run, f"ident_{form}")
        done = subprocess.run([args.replay, os.path.join(run, FORMS[form]), "--format", form, "--identify-only",
                               "--quiet", "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if done.returncode not in (0, 1):
            return task, None, done.stderr
        return task, read_identification(os.path.join(out, "identification.csv")), ""

    tasks = [(af, flight, form) for af in airframes for flight in ("chirp", "manoeuvres") for form in FORMS]
    failed, lines, worst = 0, [], {"chirp": [0.0, 0.0, 0], "manoeuvres": [0, 0, 0, 0]}
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for (af, flight, form), rows, err in pool.map(identify, tasks):
            if rows is None:
                sys.exit(f"log_ident_check: ladrc_replay failed on airframe {af['k']} {flight} {form}: {err}")
            for axis in AXES:
                ok, text, b0_err, lag_err, delay_ok, warn = judge(af, flight, rows[axis], axis)
                failed += not ok
                line = f"{'ok  ' if ok else 'MISS'} af{af['k']:02d} {flight:10s} {form:10s} {axis:5s} {text}"
                lines.append(line)
                print(line)
                w = worst[flight]
                if flight == "chirp":
                    w[0] = max(w[0], abs(b0_err))
                    w[1] = max(w[1], abs(lag_err) / max(LAG_REL_TOL * af["tau"], LAG_ABS_TOL_S))
                    w[2] += not delay_ok
                else:
                    w[0] += warn != 0
                    w[1] += ok and warn == 0
                    w[2] += 1
                    w[3] += inside(af, rows[axis], axis)
    n_axes = len(airframes) * len(FORMS) * 3
    summary = (f"{len(airframes)} airframes, {len(FORMS)} forms, 3 axes: chirp: largest b0 error "
               f"{100 * worst['chirp'][0]:.2f} % (5 % allowed), largest lag error {worst['chirp'][1]:.2f} of its "
               f"allowance, wrong delays {worst['chirp'][2]} of {n_axes}; manoeuvres: the truth inside every "
               f"stated interval in {worst['manoeuvres'][3]} of {worst['manoeuvres'][2]}, a weak-excitation warning "
               f"in {worst['manoeuvres'][0]}, neither in {worst['manoeuvres'][2] - worst['manoeuvres'][1] - worst['manoeuvres'][0]}"
               f"; figures missed: {failed}")
    print(summary)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(summary + "\n\n```\n" + "\n".join(lines) + "\n```\n")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
