#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Identification from flight logs against the truth, on random airframes.

Draws N airframes (mass, arm, inertia, motor lag, delay, damping, control
rate, gyro noise, vibration and turbulence), flies each three times with
ladrc_sil (CASCADED tuned by tune = margins): through a chirp on each axis
in turn ([excitation]), through ordinary manoeuvres, and in hover (no
reference: the turbulence and the noise are all the excitation); every run
writes its log in the Betaflight and PX4 forms ([run] log). ladrc_replay
--identify-only identifies each log whole and each half of it (--from,
--to), and the figures are held to:
  chirp, whole log:  b0 within 5 %, the motor lag within 10 % or 2 ms, the
                     delay exact;
  every kind and scope: the true b0 inside the stated 95 % interval in at
                     least 90 % of the axes where b0 is told (or, where
                     that is not met yet, KNOWN_SHORT's floor) (not flagged
                     "b0 not told", 0x100: no interval is claimed there),
                     and the lag and delay inside theirs where they are
                     stated (neither flagged as not told apart, 0x80, nor
                     the axis's b0 as not told).

Usage: tools/log_ident_check.py --sil BIN --replay BIN [--n 20] [--seed 1]
                                [--out DIR] [--jobs 2] [--markdown FILE] [--reuse]
(--reuse: the flights already in DIR are not flown again.) Prints one line per log and axis, the coverage table (kind x scope x form)
and a summary; exit status 1 when a figure is missed, 2 on bad usage or a
tool that failed.
"""
import argparse
import concurrent.futures
import csv
import glob
import math
import os
import random
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, write_whole  # noqa: E402

G = 9.81
AXES = ("roll", "pitch", "yaw")
FORMS = {"betaflight": "CASCADED_betaflight.csv", "px4": "CASCADED_px4"}
B0_TOL, LAG_REL_TOL, LAG_ABS_TOL_S = 0.05, 0.10, 0.002
SIL_BATCH = 30  # scenarios per ladrc_sil call (it takes 32 at most)
FLIGHTS = ("chirp", "manoeuvres", "hover")
DURATION_S = {"chirp": 40, "manoeuvres": 30, "hover": 30}
# A 95 % interval is held to cover the truth in at least this share of the
# axes of each kind, scope and form (20 airframes x 3 axes: 60 each; a
# share of 0.9 is 6 misses, where an exact 95 % interval misses 3 +- 1.7).
COVERAGE_MIN = 0.90
# Where the 90 % is not met yet (docs/flight-logs.md says why), the share
# measured, less some slack (a few axes: rounding across compilers moves a
# borderline interval), is held as the floor instead: the check fails on a
# regression, and prints the gap, rather than failing on the known gap.
KNOWN_SHORT = {("chirp", "second half"): 0.45, ("manoeuvres", "whole"): 0.80, ("manoeuvres", "first half"): 0.85,
               ("hover", "whole"): 0.0, ("hover", "first half"): 0.0, ("hover", "second half"): 0.0}
WARN_NARROW = 0x80  # SIM_IDENT_WARN_NARROW: lag and delay not told apart
WARN_B0_NOT_TOLD = 0x100  # SIM_IDENT_WARN_B0_NOT_TOLD
TURBULENCE = ("off", "light", "moderate")


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
    # drawn apart so that the airframes above stay those of earlier seeds
    af["turbulence"] = random.Random(1000003 * k + 7).choice(TURBULENCE)
    authority = (arm * mass * G / 2.0, arm * mass * G / 2.0, b * mass * G / kl)
    af["b0"] = tuple(a / ji for a, ji in zip(authority, j))
    return af


def scenario(af, flight):
    """The scenario text of one flight (chirp or manoeuvres) of an airframe."""
    j = af["J"]
    if flight == "chirp":
        duration, middle = 40, ("[excitation]\naxis = all\namplitude = 0.3 0.3 0.8\nf0_hz = 1\nf1_hz = 40\n"
                                "start_s = 1\nduration_s = 12\n\n[reference]\nroll = 0\npitch = 0\nyaw = 0\n")
    elif flight == "hover":
        duration, middle = DURATION_S[flight], "[reference]\nroll = 0\npitch = 0\nyaw = 0\n"
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

[wind]
turbulence = {af['turbulence']}
altitude_m = 10

{middle}
[controller CASCADED]
tune = margins
"""


def read_identification(path):
    with open(path, newline="") as f:
        return {row["axis"]: row for row in csv.DictReader(f)}


def covers(af, row, axis):
    """(b0 inside, lag and delay stated, lag and delay inside) for one axis."""
    i = AXES.index(axis)
    b0_in = float(row["b0_lo_rad_s2"]) <= af["b0"][i] <= float(row["b0_hi_rad_s2"])
    stated = not int(row["warnings"]) & (WARN_NARROW | WARN_B0_NOT_TOLD)
    lag_in = (float(row["lag_lo_s"]) <= af["tau"] <= float(row["lag_hi_s"])
              and int(row["delay_lo_ticks"]) <= af["delay"] <= int(row["delay_hi_ticks"]))
    return b0_in, stated, lag_in


def chirp_figures(af, row, axis):
    """(passed, b0 error, lag error over its allowance, delay right) of a whole chirp log's axis."""
    i = AXES.index(axis)
    b0_err = (float(row["b0_rad_s2"]) - af["b0"][i]) / af["b0"][i]
    lag_err = abs(float(row["lag_s"]) - af["tau"]) / max(LAG_REL_TOL * af["tau"], LAG_ABS_TOL_S)
    delay_ok = int(row["delay_ticks"]) == af["delay"]
    return abs(b0_err) <= B0_TOL and lag_err <= 1.0 and delay_ok, b0_err, lag_err, delay_ok


def describe(af, row, axis):
    i = AXES.index(axis)
    b0, lag, d = float(row["b0_rad_s2"]), float(row["lag_s"]), int(row["delay_ticks"])
    return (f"b0 {b0:8.4g} [{float(row['b0_lo_rad_s2']):8.4g}, {float(row['b0_hi_rad_s2']):8.4g}] "
            f"(true {af['b0'][i]:8.4g}, {100 * (b0 - af['b0'][i]) / af['b0'][i]:+6.2f} %) "
            f"lag {1e3 * lag:5.1f} [{1e3 * float(row['lag_lo_s']):5.1f}, {1e3 * float(row['lag_hi_s']):5.1f}] ms "
            f"(true {1e3 * af['tau']:5.1f}) delay {d} [{row['delay_lo_ticks']}, {row['delay_hi_ticks']}] "
            f"(true {af['delay']}) warnings {int(row['warnings']):#05x}")


def scopes(flight):
    """The whole log and its two halves, as (name, --from, --to)."""
    half = DURATION_S[flight] / 2.0
    return (("whole", None, None), ("first half", 0.0, half), ("second half", half, float(DURATION_S[flight])))


def coverage_table(cov):
    """The markdown table of the coverage counts."""
    lines = ["| flight | scope | form | b0 told | b0 covered where told | b0 covered, all | lag and delay covered "
             "where stated |", "|---|---|---|---|---|---|---|"]
    for (flight, scope, form), c in cov.items():
        told = c["n"] - c["not_told"]
        lines.append(f"| {flight} | {scope} | {form} | {told}/{c['n']} | {c['b0_told']}/{told} | {c['b0']}/{c['n']} | "
                     f"{c['lag']}/{c['stated']} |")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sil", required=True)
    ap.add_argument("--replay", required=True)
    ap.add_argument("--n", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", default="build/log_ident_check")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--markdown")
    ap.add_argument("--reuse", action="store_true")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    airframes = [draw(rng, k) for k in range(args.n)]
    flights = [(af, flight) for af in airframes for flight in FLIGHTS]
    files = [os.path.join(args.out, f"af{af['k']:02d}_{flight}.ini") for af, flight in flights]
    # what it reads: the tools it runs, the scenarios it writes and flies, the flights' logs and replays
    refuse_inputs("log_ident_check", {"--markdown": args.markdown}, [args.sil, args.replay] + files +
                  glob.glob(os.path.join(args.out, "af*", "**"), recursive=True))
    os.makedirs(args.out, exist_ok=True)
    for path, (af, flight) in zip(files, flights):
        write_whole(path, scenario(af, flight))
    flown_before = all(os.path.isdir(f[:-len(".ini")]) for f in files)
    for first in range(0, 0 if args.reuse and flown_before else len(files), SIL_BATCH):
        flown = subprocess.run([args.sil, *files[first:first + SIL_BATCH], "--out", args.out, "--jobs",
                                str(args.jobs), "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if flown.returncode != 0:
            sys.stderr.write(flown.stderr)
            sys.exit(f"log_ident_check: ladrc_sil failed ({flown.returncode})")

    def identify(task):
        af, flight, form, (scope, t_from, t_to) = task
        run = os.path.join(args.out, f"af{af['k']:02d}_{flight}")
        out = os.path.join(run, f"ident_{form}_{scope.replace(' ', '_')}")
        window = [] if t_from is None else ["--from", str(t_from), "--to", str(t_to)]
        done = subprocess.run([args.replay, os.path.join(run, FORMS[form]), "--format", form, "--identify-only",
                               "--quiet", "--out", out, *window], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                              text=True)
        if done.returncode not in (0, 1):
            return task, None, done.stderr
        return task, read_identification(os.path.join(out, "identification.csv")), ""

    tasks = [(af, flight, form, scope) for af in airframes for flight in FLIGHTS for scope in scopes(flight)
             for form in FORMS]
    cov = {(flight, scope[0], form): {"n": 0, "b0": 0, "b0_told": 0, "stated": 0, "lag": 0, "not_told": 0}
           for flight in FLIGHTS for scope in scopes(flight) for form in FORMS}
    chirp_failed, lines, worst = 0, [], [0.0, 0.0, 0]
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for (af, flight, form, scope), rows, err in pool.map(identify, tasks):
            if rows is None:
                sys.exit(f"log_ident_check: ladrc_replay failed on airframe {af['k']} {flight} {scope[0]} {form}: "
                         f"{err}")
            for axis in AXES:
                b0_in, stated, lag_in = covers(af, rows[axis], axis)
                c = cov[(flight, scope[0], form)]
                c["n"] += 1
                c["b0"] += b0_in
                c["stated"] += stated
                c["lag"] += stated and lag_in
                told = not int(rows[axis]["warnings"]) & WARN_B0_NOT_TOLD
                c["not_told"] += not told
                c["b0_told"] += told and b0_in
                ok = (b0_in or not told) and (lag_in or not stated)
                if flight == "chirp" and scope[0] == "whole":
                    passed, b0_err, lag_err, delay_ok = chirp_figures(af, rows[axis], axis)
                    chirp_failed += not passed
                    ok = ok and passed
                    worst = [max(worst[0], abs(b0_err)), max(worst[1], lag_err), worst[2] + (not delay_ok)]
                line = (f"{'ok  ' if ok else 'MISS'} af{af['k']:02d} {flight:10s} {scope[0]:11s} {form:10s} "
                        f"{axis:5s} {describe(af, rows[axis], axis)}")
                lines.append(line)
                print(line)
    table = coverage_table(cov)
    low = [k for k, c in cov.items() if c["b0_told"] < COVERAGE_MIN * (c["n"] - c["not_told"])
           or (c["stated"] > 0 and c["lag"] < COVERAGE_MIN * c["stated"])]
    floor = {k: KNOWN_SHORT.get(k[:2], COVERAGE_MIN) for k in cov}
    regressed = [k for k, c in cov.items() if c["b0_told"] < floor[k] * (c["n"] - c["not_told"])
                 or (c["stated"] > 0 and c["lag"] < floor[k] * c["stated"])]
    b0_all = sum(c["b0"] for c in cov.values())
    n_all = sum(c["n"] for c in cov.values())
    told_all = n_all - sum(c["not_told"] for c in cov.values())
    b0_told_all = sum(c["b0_told"] for c in cov.values())
    n_chirp = len(airframes) * len(FORMS) * 3
    summary = (f"{len(airframes)} airframes, {len(FORMS)} forms, 3 axes: chirp (whole log): largest b0 error "
               f"{100 * worst[0]:.2f} % (5 % allowed), largest lag error {worst[1]:.2f} of its allowance, wrong "
               f"delays {worst[2]} of {n_chirp}; b0 told in {told_all} of {n_all} axes over every kind and scope, the "
               f"truth inside its 95 % interval in {b0_told_all} of those ({100.0 * b0_told_all / max(told_all, 1):.1f} "
               f"%; {b0_all} of all {n_all}), below {100 * COVERAGE_MIN:.0f} % in {len(low)} of {len(cov)} "
               f"kind-scope-forms (known), figures missed: {chirp_failed + len(regressed)}")
    print("\n".join(table))
    print(summary)
    if args.markdown:
        write_whole(args.markdown,
                    summary + "\n\n" + "\n".join(table) + "\n\n```\n" + "\n".join(lines) + "\n```\n")
    sys.exit(1 if chirp_failed or regressed else 0)


if __name__ == "__main__":
    main()
