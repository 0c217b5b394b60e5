#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Betaflight's own firmware (its SITL, in lockstep: docs/betaflight.md) against the LADRC family
and the incumbents on the realistic suite, the vibration cases and the large-angle cases; writes
docs/betaflight-study.md and its figure.

Per case:
- the library's controllers as the case lists them, each tuned by the project's rule
  (tune = margins), in one ladrc_sil run;
- Betaflight stock: the SITL folder as tools/betaflight_sitl.sh built it (Betaflight's defaults
  but for what flying the simulator needs: tools/betaflight/sitl.cli);
- Betaflight at the slider tune a pilot would pick for the airframe: the master multiplier of
  Betaflight's simplified tuning from SLIDERS, each flown on a step flight of the case's
  airframe (its references replaced by steps, its disturbances off: never the case itself), the
  one with the least RMS error taken;
- the open Betaflight ADRC (--adrc DIR, a SITL folder built from that fork) at its defaults.

Every Betaflight run flies in its own network namespace (the SITL's UDP ports are fixed), so
runs go side by side (--jobs). Usage:

  tools/betaflight_study.py --sitl DIR [--adrc DIR] [--out docs/betaflight-study.md]
                            [--work build/betaflight-study] [--jobs 2] [--cases CASE.ini ...]
"""
import argparse
import concurrent.futures
import glob
import math
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, save_figure, write_whole  # noqa: E402
from sim_output import AXES, divergence_text, is_number, load_metrics, untunable  # noqa: E402

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SIL = [os.path.join(ROOT, "build", "host-release", "sim", "ladrc_sil")]  # --sil replaces it
FAMILY = ("HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC")
INCUMBENTS = ("CASCADED", "INDI")
# Betaflight's simplified tuning, master multiplier in percent (its range 0-200; 100 = defaults)
SLIDERS = (25, 50, 75, 100, 125, 150, 200)
# The slider's step flight: 10 deg roll and pitch steps, a 20 deg yaw step, 5 s
STEP_FLIGHT = {"run.duration_s": "5",
               "reference.roll": "10*step(t - 1) - 10*step(t - 3)",
               "reference.pitch": "-10*step(t - 2) + 10*step(t - 4)",
               "reference.yaw": "20*step(t - 1.5)",
               "disturbance.roll": "0", "disturbance.pitch": "0", "disturbance.yaw": "0",
               "metrics.error_window_s": "0 5", "metrics.steady_window_s": "4.5 5", "metrics.settle_window_s": "1 5"}
BF_STOCK, BF_ANGLE, BF_SLIDER, BF_ADRC = "BF stock", "BF stock angle", "BF slider", "BF ADRC"
BF_RUNS = (BF_STOCK, BF_ANGLE, BF_SLIDER, BF_ADRC)
MATCHED = "matched"  # the family tuned under Betaflight stock's command noise
MATCHED_SUFFIX = " capped"
SITL_PROGRAM, SITL_CONFIG, SITL_CLI = "betaflight_SITL.elf", "eeprom.bin", "sitl_config.cli"


def default_cases():
    """The realistic suite, the vibration cases and the large-angle cases."""
    return [c for p in ("suite", "vibration", "large_angle") for c in sorted(glob.glob(os.path.join(ROOT, "scenarios", p, "*.ini")))]


_NAMESPACES = []


def namespaces_work():
    """True when `unshare -n` with a loopback works here (root, and a kernel that lets us)."""
    if not _NAMESPACES:
        ok = bool(shutil.which("unshare") and shutil.which("ip") and os.geteuid() == 0)
        if ok:
            ok = subprocess.run(["unshare", "-n", "sh", "-c", "ip link set lo up"], capture_output=True).returncode == 0
        _NAMESPACES.append(ok)
    return _NAMESPACES[0]


def in_namespace(cmd):
    """cmd in a network namespace of its own (its own loopback) when this machine allows it; else
    as it is (then the runs must not overlap: --jobs 1)."""
    if namespaces_work():
        inner = "ip link set lo up && exec " + " ".join(_quote(a) for a in cmd)
        return ["unshare", "-n", "sh", "-c", inner]
    return cmd


def _quote(a):
    return "'" + a.replace("'", "'\\''") + "'"


def sil(args, out_dir, betaflight=None, mode="acro"):
    """Runs ladrc_sil; (exit status, stderr). Exit 3 (a run diverged) and 4 (untunable) are results."""
    cmd = [SIL[0]] + args + ["--out", out_dir, "--no-csv"]  # not --quiet: its speed line
    if betaflight is not None:
        cmd = in_namespace(cmd + ["--controllers", "BETAFLIGHT", "--betaflight", betaflight,
                                  "--set", "controller:BETAFLIGHT.mode=" + mode])
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stderr


def speed_of(stderr):
    m = re.search(r"\(([0-9.]+)x real time\)", stderr)
    return float(m.group(1)) if m else math.nan


def slider_folder(sitl, work, percent):
    """A SITL folder whose configuration is the stock one with the master multiplier at percent."""
    folder = os.path.join(work, "sitl_slider_%d" % percent)
    if os.path.exists(os.path.join(folder, SITL_CONFIG)):
        return folder
    os.makedirs(folder, exist_ok=True)
    program = os.path.join(folder, SITL_PROGRAM)
    if not os.path.exists(program):
        os.symlink(os.path.abspath(os.path.join(sitl, SITL_PROGRAM)), program)
    with open(os.path.join(sitl, SITL_CLI)) as f:
        lines = [ln for ln in f.read().splitlines() if ln.strip() != "save"]
    lines += ["set simplified_master_multiplier = %d" % percent, "simplified_tuning apply", "save"]
    cli = os.path.join(folder, "slider.cli")
    with open(cli, "w") as f:
        f.write("\n".join(lines) + "\n")
    p = subprocess.run(in_namespace([os.path.abspath(program), "--config", "slider.cli"]), cwd=folder,
                       capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(os.path.join(folder, SITL_CONFIG)):
        sys.exit("betaflight_study: configuring the slider %d %%: exit %d: %s" % (percent, p.returncode, p.stdout[-400:]))
    return folder


def flips(case):
    """True for a case whose references turn past angle mode's limit (the large-angle cases)."""
    return os.path.basename(os.path.dirname(case)) == "large_angle"


def step_flight_args(case):
    args = [case]
    for k, v in STEP_FLIGHT.items():
        args += ["--set", "%s=%s" % (k, v)]
    return args


def total_rms(m):
    """The sum of BETAFLIGHT's RMS errors over the axes; inf when it did not fly to the end."""
    if m is None or divergence_text(m, "BETAFLIGHT") is not None:
        return math.inf
    v = [m.get(("BETAFLIGHT", "4", "error_rms_deg", a)) for a in AXES]
    return sum(v) if all(is_number(x) for x in v) else math.inf


def pick_slider(case, sitl, work, name, pool):
    """(percent, {percent: total RMS}) of the slider that flies the step flight best."""
    scores = {}
    futures = {}
    for pct in SLIDERS:
        folder = slider_folder(sitl, work, pct)
        out = os.path.join(work, "steps", name, str(pct))
        futures[pool.submit(sil, step_flight_args(case), out, folder)] = (pct, out)
    for fut in concurrent.futures.as_completed(futures):
        pct, out = futures[fut]
        rc, err = fut.result()
        if rc not in (0, 3):
            sys.exit("betaflight_study: %s: the step flight at slider %d %%: exit %d: %s" % (case, pct, rc, err.strip()[-400:]))
        scores[pct] = total_rms(load_metrics(os.path.join(out, name)))
    best = min(SLIDERS, key=lambda p: (scores[p], abs(p - 100)))
    return best, scores


def study_case(case, args, pool):
    name = os.path.splitext(os.path.basename(case))[0]
    work = args.work
    result = {"name": name, "case": os.path.relpath(case, ROOT), "metrics": {}, "speed": {}, "errors": []}
    rc, err = sil([case], os.path.join(work, "library"))
    result["metrics"]["library"] = load_metrics(os.path.join(work, "library", name))
    if rc not in (0, 3, 4):
        result["errors"].append("library controllers: exit %d: %s" % (rc, err.strip()[-300:]))
    variants = [(BF_STOCK, args.sitl, "acro")]
    if not flips(case):
        variants.append((BF_ANGLE, args.sitl, "angle"))
    pct, scores = pick_slider(case, args.sitl, work, name, pool)
    result["slider"], result["slider_scores"] = pct, scores
    variants.append((BF_SLIDER, slider_folder(args.sitl, work, pct), "acro"))
    if args.adrc:
        variants.append((BF_ADRC, args.adrc, "acro"))
    futures = {}
    again = os.path.join(work, "BF_stock_again")  # the same run twice: the same bytes?
    futures[pool.submit(sil, [case], again, args.sitl, "acro")] = (None, again)
    for label, folder, mode in variants:
        out = os.path.join(work, label.replace(" ", "_"))
        futures[pool.submit(sil, [case], out, folder, mode)] = (label, out)
    for fut in concurrent.futures.as_completed(futures):
        label, out = futures[fut]
        rc, err = fut.result()
        if label is None:
            continue
        result["metrics"][label] = load_metrics(os.path.join(out, name))
        result["speed"][label] = speed_of(err)
        if rc not in (0, 3):
            result["errors"].append("%s: exit %d: %s" % (label, rc, err.strip()[-300:]))
    caps = stock_noise_caps(result)
    if caps is not None:  # the family again, each member tuned under Betaflight stock's command noise
        sets = []
        for c in FAMILY:
            sets += ["--set", "controller:%s.tune_noise_axis_max_Nm=%.6g %.6g %.6g" % ((c,) + tuple(caps))]
        rc, err = sil([case, "--controllers", ",".join(listed_family(result))] + sets, os.path.join(work, "matched"))
        result["metrics"][MATCHED] = load_metrics(os.path.join(work, "matched", name))
        result["caps"] = caps
        if rc not in (0, 3, 4):
            result["errors"].append("the family under the noise caps: exit %d: %s" % (rc, err.strip()[-300:]))
    result["repeatable"] = same_bytes(os.path.join(again, name, "metrics.csv"),
                                      os.path.join(work, "BF_stock", name, "metrics.csv"))
    return result


def listed_family(result):
    """The family members the case flies (those in its library run)."""
    m = result["metrics"].get("library") or {}
    return [c for c in FAMILY if any(k[0] == c for k in m)]


def stock_modes(res, axis):
    """Betaflight stock's (RMS, band, noise) on the axis in its better mode (least RMS), or None."""
    modes = [v for v in (row_values(res, BF_STOCK, axis), row_values(res, BF_ANGLE, axis)) if v is not None]
    return min(modes, key=lambda v: v[0]) if modes else None


def stock_noise_caps(res):
    """Betaflight stock's command noise per axis in its better mode: the family's caps; None when it
    did not fly every axis or a noise is not a positive number."""
    caps = []
    for axis in AXES:
        v = stock_modes(res, axis)
        if v is None or v[2] is None or not v[2] > 0:
            return None
        caps.append(v[2])
    return caps


def same_bytes(a, b):
    if not (os.path.exists(a) and os.path.exists(b)):
        return False
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def value(m, controller, table, quantity, axis):
    if m is None:
        return None
    v = m.get((controller, table, quantity, axis))
    return v if is_number(v) else None


def column_source(res, label):
    """(metrics, controller) of a column: a Betaflight run, a family member's run under
    Betaflight's noise caps (its label ends in MATCHED_SUFFIX) or a library controller's."""
    if label in BF_RUNS:
        return res["metrics"].get(label), "BETAFLIGHT"
    if label.endswith(MATCHED_SUFFIX):
        return res["metrics"].get(MATCHED), label[:-len(MATCHED_SUFFIX)]
    return res["metrics"].get("library"), label


def row_values(res, label, axis):
    """(RMS deg, steady band deg, command noise N m) of a column, or None where it did not fly."""
    m, c = column_source(res, label)
    if m is None or untunable(m, c) or divergence_text(m, c) is not None:
        return None
    rms, band, noise = (value(m, c, "4", "error_rms_deg", axis), value(m, c, "5", "steady_band_deg", axis),
                        value(m, c, "-", "cmd_noise_Nm", axis))
    return None if rms is None else (rms, band, noise)


def why_not(res, label):
    """Why a column has no figures: not flown, failed, untunable or its divergence."""
    m, c = column_source(res, label)
    if m is None and label == BF_ANGLE and flips(res["case"]):
        return "not flown (past angle mode's limit)"
    if m is None:
        return "failed"
    if untunable(m, c):
        return "untunable"
    d = divergence_text(m, c)
    return d if d is not None else "-"


def family_best(res, axis, noise_cap):
    """(controller, values) of the family member with the least RMS error on the axis whose command
    noise is at most noise_cap (None: any), or None."""
    best = None
    for c in FAMILY + tuple(f + MATCHED_SUFFIX for f in FAMILY):
        v = row_values(res, c, axis)
        if v is None or (noise_cap is not None and (v[2] is None or v[2] > noise_cap)):
            continue
        if best is None or v[0] < best[1][0]:
            best = (c, v)
    return best


def fmt(v, digits=3):
    return "-" if v is None or not math.isfinite(v) else ("%.*g" % (digits, v))


def columns_of(results):
    """The columns some case has: the library's controllers it lists, then the Betaflight runs."""
    def has(res, c):
        if c in BF_RUNS:
            return c in res["metrics"]
        capped = c.endswith(MATCHED_SUFFIX)
        m = res["metrics"].get(MATCHED if capped else "library")
        name = c[:-len(MATCHED_SUFFIX)] if capped else c
        return m is not None and any(key[0] == name for key in m)
    everyone = FAMILY + tuple(f + MATCHED_SUFFIX for f in FAMILY) + INCUMBENTS + BF_RUNS
    return [c for c in everyone if any(has(r, c) for r in results)]


def verdicts(results):
    """Per case and axis: the family's best at no more command noise than BF stock, and the ratio."""
    rows, losses = [], []
    for res in results:
        for axis in AXES:
            stock = stock_modes(res, axis)
            if stock is None:
                best = family_best(res, axis, None)
                rows.append((res["name"], axis, best, None, "BF stock did not fly: " + why_not(res, BF_STOCK)))
                continue
            best = family_best(res, axis, stock[2])
            if best is None:
                lowest = family_best(res, axis, None)
                losses.append((res["name"], axis, "no family member at or under BF stock's command noise %s N m "
                               "(its most accurate, %s, %s deg at %s N m)"
                               % (fmt(stock[2]), lowest[0] if lowest else "-",
                                  fmt(lowest[1][0]) if lowest else "-", fmt(lowest[1][2]) if lowest else "-")))
                rows.append((res["name"], axis, None, stock, "loss: noise"))
                continue
            ratio = best[1][0] / stock[0] if stock[0] > 0 else math.inf
            if ratio >= 1.0:
                losses.append((res["name"], axis, "%s %s deg against BF stock %s deg (%.2fx)"
                               % (best[0], fmt(best[1][0]), fmt(stock[0]), ratio)))
            rows.append((res["name"], axis, best, stock, "%.2fx" % ratio))
    return rows, losses


def write_figure(rows, results, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return None
    by_case = {r["name"]: r for r in results}
    labels, ratios, colours = [], [], []
    for name, axis, best, stock, _ in rows:
        if stock is None or not stock[0] > 0:
            continue
        if best is not None:  # at no more command noise than Betaflight: a win or a loss
            labels.append("%s %s" % (name, axis))
            ratios.append(best[1][0] / stock[0])
            colours.append("#2ca02c" if ratios[-1] < 1 else "#d62728")
            continue
        lowest = family_best(by_case[name], axis, None)  # only at more noise: a loss, drawn grey
        if lowest is not None and lowest[1][2] is not None and stock[2]:
            labels.append("%s %s (at %.2gx the noise)" % (name, axis, lowest[1][2] / stock[2]))
            ratios.append(lowest[1][0] / stock[0])
            colours.append("#999999")
    if not ratios:
        return None
    fig, ax = plt.subplots(figsize=(8, max(3, 0.22 * len(ratios))))
    ax.barh(range(len(ratios)), ratios, color=colours)
    ax.axvline(1.0, color="black", lw=0.8)
    ax.set_yticks(range(len(ratios)))
    ax.set_yticklabels(labels, fontsize=7)
    ax.invert_yaxis()
    ax.set_xscale("log")
    ax.set_xlabel("RMS error: family's best / Betaflight stock\n(grey: a loss, the family only at more command noise)")
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def write_doc(results, args, bf_commit, adrc_commit):
    rows, losses = verdicts(results)
    cols = columns_of(results)
    figure = write_figure(rows, results, os.path.splitext(args.out)[0] + ".png")
    out = ["# Betaflight in the loop: the study", "",
           "Generated by `tools/betaflight_study.py` (docs/betaflight.md); do not edit by hand.", "",
           "Betaflight: %s (lockstep SITL, tools/betaflight_sitl.sh, configuration tools/betaflight/sitl.cli)."
           % bf_commit]
    if args.adrc:
        out.append("Open Betaflight ADRC: %s, at its documented defaults (tools/betaflight/adrc_fork.cli)." % adrc_commit)
    out += ["", "Every library controller tuned by the project's rule (`tune = margins`); Betaflight stock at its",
            "defaults; Betaflight at the master slider a pilot picks for the airframe (the one of %s %% whose"
            % ", ".join(str(s) for s in SLIDERS),
            "5 s step flight on the case's airframe, disturbances off, has the least RMS error); the pilot",
            "flies acro (docs/betaflight.md, \"The pilot\"), and Betaflight stock also in angle mode",
            "(its own angle loop; not on the large-angle cases, whose flips pass its angle limit). The",
            "verdict sets the family's best against the better of Betaflight stock's two modes on each",
            "case and axis, at no more command noise than that mode. The family is flown twice: tuned by",
            "the rule alone, and tuned by the rule under a cap on each axis's command noise equal to",
            "Betaflight stock's (`tune_noise_axis_max_Nm`, columns \"capped\"); its best is taken from",
            "either. RMS and steady band in deg, command noise (the torque command above 20 Hz, RMS) in N m.",
            ""]
    if figure:
        out += ["![LADRC family's best over Betaflight stock](%s)" % os.path.basename(figure), ""]
    wins = sum(1 for r in rows if r[4].endswith("x") and float(r[4][:-1]) < 1.0)
    speeds = [v for res in results for v in res["speed"].values() if math.isfinite(v)]
    repeat = sum(1 for res in results if res["repeatable"])
    out += ["Lockstep: Betaflight stock flown twice on each case gave the same metrics byte for byte on %d of %d "
            "cases; every Betaflight run flew at %s-%sx real time (one ladrc_sil, one SITL)."
            % (repeat, len(results), fmt(min(speeds) if speeds else None, 2), fmt(max(speeds) if speeds else None, 2)), ""]
    out += ["## Verdict", "",
            "The LADRC family's best at no more command noise than Betaflight stock beats it on RMS error on "
            "%d of %d case-axes." % (wins, len(rows)), ""]
    if losses:
        out += ["Losses:", ""] + ["- %s %s: %s" % l for l in losses] + [""]
    out += ["| case | axis | family's best at BF's noise | its RMS | BF stock RMS (better mode) | ratio | "
            "family's most accurate: RMS ratio, noise ratio |", "|---|---|---|---|---|---|---|"]
    by_case = {r["name"]: r for r in results}
    for name, axis, best, stock, verdict in rows:
        lowest = family_best(by_case[name], axis, None)
        anyway = "-"
        if lowest is not None and stock is not None and stock[0] > 0 and stock[2]:
            anyway = "%s: %.2fx, %.2gx" % (lowest[0], lowest[1][0] / stock[0],
                                           lowest[1][2] / stock[2] if lowest[1][2] is not None else math.nan)
        out.append("| %s | %s | %s | %s | %s | %s | %s |" % (name, axis, best[0] if best else "-",
                                                            fmt(best[1][0]) if best else "-",
                                                            fmt(stock[0]) if stock else "-", verdict, anyway))
    cost = m4f_cost()
    out += ["", "## What each costs on a Cortex-M4F", "",
            "Instructions per tick of three axes and the mixer at -Os (docs/performance.md). Betaflight's own",
            "rate loop was not measured on the Cortex-M4F here: its SITL runs on the host.", "",
            "| controller | instructions/tick |", "|---|---|"]
    out += ["| %s | %.0f |" % (c, cost[c]) for c in FAMILY + INCUMBENTS if c in cost]
    out += ["", "## Every controller, every case", ""]
    for res in results:
        out += ["### %s (`%s`)" % (res["name"], res["case"]), ""]
        speeds = ", ".join("%s %.0fx" % (k, v) for k, v in sorted(res["speed"].items()) if math.isfinite(v))
        speeds += "; BF stock flown twice: %s" % ("the same metrics, byte for byte" if res["repeatable"] else "DIFFERENT")
        out += ["Slider picked: %d %% (step flight RMS sum per slider: %s). Speed (x real time): %s." % (
            res["slider"], ", ".join("%d: %s" % (p, fmt(res["slider_scores"][p])) for p in SLIDERS), speeds), ""]
        for e in res["errors"]:
            out += ["Error: " + e, ""]
        out += ["| axis | " + " | ".join(cols) + " |", "|---|" + "---|" * len(cols)]
        for axis in AXES:
            cells = []
            for c in cols:
                v = row_values(res, c, axis)
                cells.append("%s / %s / %s" % (fmt(v[0]), fmt(v[1]), fmt(v[2])) if v else why_not(res, c))
            out.append("| %s | %s |" % (axis, " | ".join(cells)))
        out.append("")
    write_whole(args.out, "\n".join(out) + "\n")
    return losses


def m4f_cost():
    """{controller: Cortex-M4F instructions per 3-axis tick with the mixer} from docs/performance.md."""
    cost = {}
    path = os.path.join(ROOT, "docs", "performance.md")
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                m = re.match(r"\| ([A-Z-]+), 3 axes \+ mixer, instructions/tick \| ([0-9.]+) \|", line)
                if m:
                    cost[m.group(1)] = float(m.group(2))
    return cost


def commit_of(folder):
    path = os.path.join(folder, "BUILD_INFO")
    if os.path.exists(path):
        with open(path) as f:
            for line in f:
                if line.startswith("commit"):
                    return line.split("=", 1)[-1].strip().split(":", 1)[-1].strip()
    return "unknown commit"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sitl", required=True, help="Betaflight SITL folder (tools/betaflight_sitl.sh)")
    ap.add_argument("--adrc", help="the open Betaflight ADRC fork's SITL folder")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "betaflight-study.md"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "betaflight-study"))
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--cases", nargs="+")
    ap.add_argument("--sil", help="the ladrc_sil to run (default: build/host-release's)")
    args = ap.parse_args()
    if args.sil:
        SIL[0] = os.path.abspath(args.sil)
    if not namespaces_work():
        args.jobs = 1  # the SITL's ports are the machine's
    for folder in [args.sitl] + ([args.adrc] if args.adrc else []):
        for f in (SITL_PROGRAM, SITL_CONFIG, SITL_CLI):
            if not os.path.exists(os.path.join(folder, f)):
                sys.exit("betaflight_study: %s: no %s (tools/betaflight_sitl.sh CHECKOUT %s builds it)"
                         % (folder, f, folder))
    if not os.access(SIL[0], os.X_OK):
        sys.exit("betaflight_study: %s missing (cmake --preset host-release && cmake --build --preset host-release)"
                 % SIL[0])
    args.sitl, args.adrc = os.path.abspath(args.sitl), os.path.abspath(args.adrc) if args.adrc else None
    cases = args.cases or default_cases()
    refuse_inputs("betaflight_study", [args.out, os.path.splitext(args.out)[0] + ".png"], cases)
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        for i, case in enumerate(cases):
            print("betaflight_study: %d/%d %s" % (i + 1, len(cases), case), file=sys.stderr, flush=True)
            results.append(study_case(case, args, pool))
    losses = write_doc(results, args, commit_of(args.sitl), commit_of(args.adrc) if args.adrc else None)
    print("betaflight_study: wrote %s (%d losses)" % (args.out, len(losses)), file=sys.stderr)


if __name__ == "__main__":
    main()
