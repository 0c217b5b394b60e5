#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""docs/flight-logs.md's generated blocks, from what tools/logs.sh wrote in OUT_DIR.

Usage: flight_logs_doc.py OUT_DIR DOC_MD

- identification: the chirp flight's airframe as scenarios/logs/chirp_flight.ini gives it (the
  truth, per unit of normalised command) beside what ladrc_replay identified from its Betaflight
  and its PX4 log; and, when OUT_DIR/check.md exists (tools/log_ident_check.py --markdown), the
  summary of the identification over random airframes and its coverage table.
- worked: the margins ladrc_margins --from-log tuned every controller to (roll), and the replay
  of the ordinary flight: per controller and axis, command rms, its noise per band, its rms
  difference from the log's command, the disturbance estimate's mean, the ticks with a fault.
"""
import csv
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import files_under, refuse_inputs  # noqa: E402
from report import rewrite_blocks  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
AXES = ("roll", "pitch", "yaw")


def scenario_values(path):
    """key -> list of numbers of the scenario's [vehicle], [rotors] and [sensors] keys."""
    values = {}
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            m = re.match(r"^([A-Za-z_0-9]+)\s*=\s*([-+0-9.eE ]+)$", line)
            if m:
                values[m.group(1)] = [float(x) for x in m.group(2).split()]
    return values


def truth(path):
    """b0 per axis (rad/s^2 per unit: the torque authority over J), lag (s), delay (ticks), damping (1/s)."""
    v = scenario_values(path)
    m, arm, kl, b, g = v["mass_kg"][0], v["arm_m"][0], v["thrust_coeff_N_s2"][0], v["yaw_coeff_Nm_s2"][0], v["g_m_s2"][0]
    authority = (arm * m * g / 2.0, arm * m * g / 2.0, b * m * g / kl)
    j = v["inertia_kg_m2"]
    lag = v["motor_tau_s"][0]
    down = v.get("motor_tau_down_s", [0.0])[0]
    return ([a / ji for a, ji in zip(authority, j)], lag, down, int(v["delay_ticks"][0]),
            [v["rot_drag_Nm_s"][0] / ji for ji in j])


def identification(path):
    with open(path, newline="") as f:
        return {row["axis"]: row for row in csv.DictReader(f)}


def interval(row, key, lo, hi, scale=1.0, fmt="%.4g"):
    return (fmt % (scale * float(row[key])) + " [" + fmt % (scale * float(row[lo])) + ", "
            + fmt % (scale * float(row[hi])) + "]")


def identification_block(out):
    b0, lag, down, delay, damping = truth(os.path.join(ROOT, "scenarios", "logs", "chirp_flight.ini"))
    forms = {"Betaflight": identification(os.path.join(out, "identify_betaflight", "identification.csv")),
             "PX4": identification(os.path.join(out, "identify_px4", "identification.csv"))}
    lines = ["The identification flight of `scenarios/logs/chirp_flight.ini` (motor lag %.0f ms up, %.0f ms "
             "down, %d ticks of delay, gyro vibration at the rotors' 40.8, 81.7 and 122.5 Hz, light "
             "turbulence), identified from each log form (95 %% intervals; `tools/logs.sh --docs` writes "
             "this):" % (1e3 * lag, 1e3 * down, delay), "",
             "| axis | truth: b0 (rad/s^2), lag (ms), delay, damping (1/s) | form | b0 | lag (ms) | delay | damping "
             "(1/s) | R^2 | warnings |", "|---|---|---|---|---|---|---|---|---|"]
    for i, axis in enumerate(AXES):
        for form, rows in forms.items():
            r = rows[axis]
            err = 100.0 * (float(r["b0_rad_s2"]) - b0[i]) / b0[i]
            lines.append("| %s | %.4g, %.0f-%.0f, %d, %.3g | %s | %s (%+.1f %%) | %s | %s | %.3g | %.3f | %s |" % (
                axis, b0[i], 1e3 * lag, 1e3 * down, delay, damping[i], form,
                interval(r, "b0_rad_s2", "b0_lo_rad_s2", "b0_hi_rad_s2"), err,
                interval(r, "lag_s", "lag_lo_s", "lag_hi_s", 1e3, "%.1f"),
                "%s [%s, %s]" % (r["delay_ticks"], r["delay_lo_ticks"], r["delay_hi_ticks"]),
                float(r["damping_per_s"]), float(r["r2"]), r["warnings"] if r["warnings"] != "0" else "none"))
    check = os.path.join(out, "check.md")
    if os.path.isfile(check):
        with open(check) as f:
            summary = f.readline().strip()
            f.readline()
            table = []
            for row in f:
                if not row.startswith("|"):
                    break
                table.append(row.rstrip("\n"))
        lines += ["", "Over 20 random airframes (`tools/log_ident_check.py`, a slow test of the suite: mass "
                  "0.25-3 kg, motor lag 10-60 ms, 0-4 ticks of delay, 500 Hz or 1 kHz, gyro noise 0.1-0.8 "
                  "deg/s, vibration 0-1.5 deg/s at the rotor orders 1-3, turbulence off, light or moderate), "
                  "each flown through chirps, through a pilot's steps and sweeps, and in hover, each log "
                  "identified whole and by halves (`--from`, `--to`), both log forms: " + summary + ".",
                  "", "The coverage of the 95 % intervals per flight, scope and form (b0 told: not flagged "
                  "0x100; the lag and delay stated: neither flagged 0x80 nor b0 not told):", ""] + table
    return lines


def margins_lines(path):
    """The tuned result of every controller's roll from ladrc_margins's output."""
    rows = []
    with open(path) as f:
        for line in f:
            m = re.match(r"^tuned (\S+) roll: (.*) -> PM ([0-9.]+) deg .* GM ([0-9.]+) dB .*crossover ([0-9.]+) rad/s", line)
            if m:
                rows.append("| %s | %s | %s | %s | %s |" % (m.group(1), m.group(2).strip(), m.group(3), m.group(4),
                                                           m.group(5)))
    return rows


def worked_block(out):
    lines = ["The worked path, on the logs `tools/logs.sh` has the simulator write (a real log goes the same "
             "way; `tools/logs.sh --docs` writes this block and the figures):", "",
             "    build/host-release/sim/ladrc_sil scenarios/logs/chirp_flight.ini scenarios/logs/ordinary_flight.ini "
             "--out build/logs-out",
             "    # the airframe from the chirp flight's Betaflight log, and from its PX4 log",
             "    build/host-release/sim/ladrc_replay build/logs-out/chirp_flight/CASCADED_betaflight.csv "
             "--identify-only",
             "    build/host-release/sim/ladrc_replay build/logs-out/chirp_flight/CASCADED_px4 --identify-only "
             "--out build/logs-out/identify_px4",
             "    # every controller's gains for it, with their margins",
             "    build/host-release/sim/ladrc_margins --from-log build/logs-out/chirp_flight/CASCADED_px4",
             "    # what each would have commanded on the ordinary flight",
             "    build/host-release/sim/ladrc_replay build/logs-out/ordinary_flight/CASCADED_px4 "
             "--scenario build/logs-out/identify_px4/airframe.ini --out build/logs-out/replay_px4",
             "    /usr/bin/python3 tools/replay_plot.py build/logs-out/replay_px4 --from 12 --to 20", "",
             "The gains `ladrc_margins --from-log` chose for roll (PM >= 45 deg, GM >= 6 dB on the identified "
             "airframe):", "", "| controller | gains | PM (deg) | GM (dB) | crossover (rad/s) |", "|---|---|---|---|---|"]
    lines += margins_lines(os.path.join(out, "margins.txt"))
    lines += ["", "The replay of the ordinary flight (a pilot's steps and sweeps in moderate turbulence, a 3 rad/s "
              "tone on roll from 15 s) from its PX4 log; commands normalised (1: the full authority), noise as rms "
              "per band, difference: rms of the controller's command less the log's (CASCADED flew it):", "",
              "| source | axis | rms | 0-20 Hz | 20-100 Hz | > 100 Hz | vs the log | disturbance estimate, mean (rad/s^2) "
              "| ticks with a fault |", "|---|---|---|---|---|---|---|---|---|"]
    with open(os.path.join(out, "replay_px4", "replay_summary.csv"), newline="") as f:
        for r in csv.DictReader(f):
            if r.get("status", "replayed") != "replayed":  # a controller not replayed: no numbers
                continue

            def num(key, fmt="%.4f"):
                x = float(r[key])
                return "-" if math.isnan(x) else fmt % x
            lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["source"], r["axis"], num("command_rms"), num("noise_0_20hz"), num("noise_20_100hz"),
                num("noise_above_100hz"), num("difference_rms"), num("estimate_mean_rad_s2", "%.3g"),
                "-" if r["source"] == "LOG" else r["fault_ticks"]))
    lines += ["", "![Each controller's command on the ordinary flight against the log's, 12-20 s]"
              "(figures/replay_commands.png)", "",
              "![The log's gyro spectrum with its vibration lines, and the commands' spectra]"
              "(figures/replay_spectrum.png)"]
    return lines


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    out, doc = sys.argv[1], sys.argv[2]
    # DOC_MD is read and rewritten in place by design; OUT_DIR's files are only read
    refuse_inputs("flight_logs_doc.py", {"DOC_MD": doc}, files_under(out, (".csv", ".md", ".ini")))
    sys.exit(rewrite_blocks(doc, {"flight-logs:identification": identification_block(out),
                                  "flight-logs:worked": worked_block(out)}))


if __name__ == "__main__":
    main()
