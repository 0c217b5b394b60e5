#!/usr/bin/env python3
"""The acceptance verdict of one `ladrc_replay LOG` run (tools/real_logs.sh calls it).

    real_logs_report.py --log LOG --status N --out DIR --stdout FILE --stderr FILE --seconds S

Prints, for the log: the exit status and wall time; the controllers replayed and
those untunable with the reason ladrc_replay gave; per axis the command noise
above 20 Hz of the logged controller and of the quietest replayed controller of
the LADRC family; and the verdict. Exit status 0 when the log passes, 1 when it
fails.

Acceptance (issue 38): exit status 0; every controller either replayed or
reported untunable with its reason; on every axis the LADRC family's quietest
controller puts no more command noise above 20 Hz into the motors than the
logged controller did.

The noise above 20 Hz is read from replay_summary.csv (written by
sim/cli/replay_report.c): its `noise_above_20hz` column when the file has one,
else sqrt(noise_20_100hz^2 + noise_above_100hz^2): the bands are disjoint sums
of the same Welch spectrum's bins, so their powers add.
"""

import argparse
import csv
import glob
import math
import os
import re
import sys

# the controllers of axis_adrc.c (docs/architecture.md: the LADRC family)
LADRC_FAMILY = ("LADRC", "LP-MLADRC", "HP-MLADRC")
LOG_SOURCE = "LOG"
AXES = ("roll", "pitch", "yaw")
# a tuning note on stderr: 'path:line:col: message' (warnings say so first)
# an untunable controller's reason is shown up to this many characters (its
# full text is on ladrc_replay's stderr, kept with --keep)
REASON_CHARS = 240
# ladrc_replay's own line for a controller it does not replay
NOT_REPLAYED = re.compile(r"^untunable (?P<name>[\w-]+), not replayed: (?P<message>.*)$")
NOTE = re.compile(r"^(?P<where>[^:\s][^:]*:\d+:\d+): (?P<message>.*)$")


def read_summary(path):
    """Rows of replay_summary.csv: {source: {axis: row}}, the untunable sources and their reasons."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    replayed, untunable, reasons = {}, [], {}
    for row in rows:
        if row.get("ticks") == "untunable":
            if row["source"] not in untunable:
                untunable.append(row["source"])
            # its reason, in the status column when the summary has one ("untunable: why")
            status = row.get("status") or ""
            if status.startswith("untunable: "):
                reasons.setdefault(row["source"], status[len("untunable: "):])
            continue
        replayed.setdefault(row["source"], {})[row["axis"]] = row
    return replayed, untunable, reasons


def noise_above_20hz(row):
    """The command's rms above 20 Hz, and how it was had."""
    if "noise_above_20hz" in row and row["noise_above_20hz"] not in ("", None):
        return float(row["noise_above_20hz"]), "noise_above_20hz"
    mid, high = float(row["noise_20_100hz"]), float(row["noise_above_100hz"])
    return math.hypot(mid, high), "hypot(noise_20_100hz, noise_above_100hz)"


def untunable_reasons(stderr_text, names):
    """Each untunable controller's reason: the stderr notes that name it and are not warnings."""
    reasons = {}
    for line in stderr_text.splitlines():
        m = NOT_REPLAYED.match(line.strip())
        if m and m.group("name") in names:
            reasons.setdefault(m.group("name"), m.group("message"))
            continue
        m = NOTE.match(line.strip())
        if not m or m.group("message").startswith("warning:"):
            continue
        for name in names:
            if re.search(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", m.group("message")):
                reasons.setdefault(name, m.group("message"))
    return reasons


def timings(stdout_text):
    """', identified in X s, replayed in Y s' from ladrc_replay's own lines, when printed."""
    found = ""
    m = re.search(r"identified in ([0-9.]+) s", stdout_text)
    if m:
        found += f", identified in {m.group(1)} s"
    m = re.search(r"^replayed .* in ([0-9.]+) s: ([0-9.]+x) real time", stdout_text, re.M)
    if m:
        found += f", replayed in {m.group(1)} s ({m.group(2)} real time)"
    return found


def status_causes(stdout_text, replayed):
    """What made the status 1: the identification's warnings, the controllers that faulted."""
    causes = []
    warnings = [l for l in stdout_text.splitlines() if l.startswith("warning: ")]
    if warnings:
        axes = sorted({l.split(":")[1].strip() for l in warnings if l.count(":") >= 2})
        causes.append(f"{len(warnings)} identification warnings ({', '.join(axes)})")
    for name, axes in replayed.items():
        ticks = max((int(float(r.get("fault_ticks") or 0)) for r in axes.values()), default=0)
        if name != LOG_SOURCE and ticks > 0:
            causes.append(f"{name} faulted ({ticks} ticks)")
    return "; ".join(causes) or "(not told by the outputs)"


def last_error(stdout_text, stderr_text):
    lines = [l for l in stderr_text.splitlines() if l.strip() and not l.startswith("\r")]
    errors = [l for l in lines if "warning:" not in l]
    return (errors or lines or ["(no message)"])[-1].strip()


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--log", required=True)
    p.add_argument("--status", type=int, required=True)
    p.add_argument("--out", required=True, help="the directory ladrc_replay ran in")
    p.add_argument("--stdout", required=True)
    p.add_argument("--stderr", required=True)
    p.add_argument("--seconds", type=float, required=True)
    p.add_argument("--noise", choices=("gate", "report"), default="gate",
                   help="gate: a family louder than the log fails the log; report: said, not failed")
    a = p.parse_args(argv)

    with open(a.stdout, errors="replace") as f:
        out_text = f.read()
    with open(a.stderr, errors="replace") as f:
        err_text = f.read().replace("\r", "\n")
    failures = []
    print(f"== {a.log}")
    print(f"   exit status {a.status}, {a.seconds:.1f} s{timings(out_text)}")
    if a.status != 0:
        failures.append(f"exit status {a.status}")
        if a.status == 2:
            print(f"   refused: {last_error(out_text, err_text)}")

    summaries = sorted(glob.glob(os.path.join(a.out, "**", "replay_summary.csv"), recursive=True))
    if not summaries:
        failures.append("no replay_summary.csv written")
        print("   no replay_summary.csv: nothing replayed")
        print(f"   verdict: FAIL ({'; '.join(failures)})")
        return 1
    replayed, untunable, reasons = read_summary(summaries[0])
    for name, why in untunable_reasons(err_text + "\n" + out_text, untunable).items():
        reasons.setdefault(name, why)
    print("   replayed: " + (", ".join(s for s in replayed if s != LOG_SOURCE) or "none"))
    if a.status == 1:
        print(f"   status 1 from: {status_causes(out_text, replayed)}")
    for name in untunable:
        reason = reasons.get(name)
        shown = reason if reason is None or len(reason) <= REASON_CHARS else reason[:REASON_CHARS] + " ..."
        print(f"   untunable: {name}: {shown or '(no reason printed)'}")
        if not reason:
            failures.append(f"{name} untunable without a reason")
    if LOG_SOURCE not in replayed:
        failures.append("the summary has no LOG rows")
        print(f"   verdict: FAIL ({'; '.join(failures)})")
        return 1

    family = [s for s in LADRC_FAMILY if s in replayed]
    louder = []
    how = None
    print(f"   command noise above 20 Hz (rms, 1 = full authority):")
    for axis in AXES:
        log_noise, how = noise_above_20hz(replayed[LOG_SOURCE][axis])
        if not math.isfinite(log_noise):
            # no Welch segment: the replay is shorter than one (sim/run/spectrum.h)
            failures.append(f"{axis}: the log's noise not measured (replay shorter than a spectrum segment)")
            print(f"   {axis:5s}  log's noise not measured: the replay is shorter than one spectrum segment")
            continue
        best_name, best = None, math.inf
        for name in family:
            value, _ = noise_above_20hz(replayed[name][axis])
            if math.isfinite(value) and value < best:
                best_name, best = name, value
        if best_name is None:
            failures.append(f"{axis}: no LADRC-family controller replayed")
            print(f"   {axis:5s}  log {log_noise:.4g}  LADRC family: none replayed")
            continue
        ratio = best / log_noise if log_noise > 0 else math.inf
        ok = best <= log_noise
        print(f"   {axis:5s}  log {log_noise:.4g}  quietest {best_name} {best:.4g}  ({ratio:.2f}x) {'ok' if ok else 'LOUDER'}")
        if not ok:
            louder.append(f"{axis}: {best_name} {ratio:.2f}x the log's noise above 20 Hz")
    print(f"   (noise from {how})")
    if a.noise == "gate":
        failures.extend(louder)
    elif louder:
        print(f"   noise above the log's (reported, not gated): {'; '.join(louder)}")
    if failures:
        print(f"   verdict: FAIL ({'; '.join(failures)})")
        return 1
    print("   verdict: PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
