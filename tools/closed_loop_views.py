#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The field's views of each controller in closed loop on a log's airframe (docs/flight-logs.md,
"The field's views"). ladrc_replay's replay is open loop: a controller's command is worked out on
the log's gyro, so it has no step response of its own. This flies one: the airframe ladrc_replay
identified (REPLAY_DIR/airframe.ini, with the log's gyro noise) with the log's setpoints as the
reference (`[reference] series`), every controller of the scenario tuned as it says, each flight
written as a log; then the step response, frequency response and noise against throttle of the log
flown (LOG) and of each flight side by side.

Usage: closed_loop_views.py REPLAY_DIR LOG [--format F] [--map FIELD=SOURCE]... [--seconds S]
                            [--controllers LIST] [--bin DIR]

Writes REPLAY_DIR/log_reference.csv (the setpoints, the first S seconds: default 120),
REPLAY_DIR/closed_loop_flights/ (ladrc_sil's output) and REPLAY_DIR/closed_loop/ (the views'
CSVs and response_step.png, response_freq.png, response_noise.png). --bin: the folder of
ladrc_views and ladrc_sil (default build/host-release/sim). Exit status 1 when a step fails.
"""
import argparse
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import response_plot  # noqa: E402
from output_files import refuse_inputs, refuse_inside  # noqa: E402


def run(cmd):
    print("+ " + " ".join(cmd), flush=True)
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("replay_dir")
    ap.add_argument("log")
    ap.add_argument("--format", default="betaflight")
    ap.add_argument("--map", action="append", default=[])
    ap.add_argument("--seconds", type=float, default=120.0)
    ap.add_argument("--controllers", default=None)
    ap.add_argument("--bin", default=os.path.join("build", "host-release", "sim"))
    args = ap.parse_args()
    views = os.path.join(args.bin, "ladrc_views")
    sil = os.path.join(args.bin, "ladrc_sil")
    ini = os.path.join(args.replay_dir, "airframe.ini")
    if not os.path.isfile(ini):
        sys.exit("closed_loop_views: %s is missing (ladrc_replay LOG --out %s writes it)" % (ini, args.replay_dir))
    ref = os.path.join(args.replay_dir, "log_reference.csv")
    flights = os.path.join(args.replay_dir, "closed_loop_flights")
    out = os.path.join(args.replay_dir, "closed_loop")
    # its outputs: the setpoints' series, and two folders whose contents each run replaces
    refuse_inputs("closed_loop_views", {"log_reference.csv": ref}, [args.log, ini])
    refuse_inside("closed_loop_views", {"closed_loop_flights/": flights, "closed_loop/": out}, [args.log, ini])
    log_opts = ["--format", args.format] + [x for m in args.map for x in ("--map", m)]

    r = run([views, "--reference", ref, "--seconds", "%g" % args.seconds] + log_opts + [args.log])
    if r.returncode != 0:
        sys.exit("closed_loop_views: " + r.stderr.strip())
    seconds = float(r.stdout.split(":")[1].split()[0])
    duration = int(seconds * 10) / 10.0  # whole tenths: the series covers the run
    if duration < 4.0:
        sys.exit("closed_loop_views: %s: %.1f s of setpoints, too short for a 2 s window" % (args.log, seconds))

    sets = ["run.duration_s=%g" % duration, "run.log=generic",
            "reference.series=log_reference.csv", "reference.series_interp=linear", "reference.series_end=hold",
            # the airframe's own test signals off: the log's setpoints alone
            "reference.roll=0", "reference.pitch=0", "reference.yaw=0",
            "disturbance.roll=0", "disturbance.pitch=0", "disturbance.yaw=0",
            # a log integrates flips to whole turns: a run diverges on a lost vehicle, not on a late one
            "metrics.diverge_limit_deg=720",
            # the airframe's metric windows, fitted to the run's length
            "metrics.error_window_s=0 %g" % duration, "metrics.steady_window_s=%g %g" % (duration / 2, duration),
            "metrics.settle_window_s=1 3"]
    cmd = [sil, ini, "--out", flights, "--quiet"] + [x for s in sets for x in ("--set", s)]
    if args.controllers:
        cmd += ["--controllers", args.controllers]
    r = run(cmd)  # its tables are not printed: the views below are what this is for
    if r.returncode not in (0, 3):  # 3: a run diverged, the others wrote their logs
        sys.exit("closed_loop_views: ladrc_sil failed (%d): %s" % (r.returncode, r.stderr.strip()))
    scen_dir = os.path.join(flights, "airframe")
    sources = ["LOG=" + args.log]
    flown = sorted(f[: -len("_log.csv")] for f in os.listdir(scen_dir) if f.endswith("_log.csv"))
    if not flown:
        sys.exit("closed_loop_views: no flight log in %s" % scen_dir)
    cmd = [views, "--out", out] + log_opts + sources + ["--format", "generic"]
    cmd += ["%s=%s" % (c, os.path.join(scen_dir, c + "_log.csv")) for c in flown]
    r = run(cmd)
    print(r.stdout, end="")
    if r.returncode != 0:
        sys.exit("closed_loop_views: " + r.stderr.strip())
    print("closed_loop_views: " + ", ".join(response_plot.draw(out)))


if __name__ == "__main__":
    main()
