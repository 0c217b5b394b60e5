#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The vibration study's tables and spectrum figure (docs/vibration.md), from tools/vibration.sh.

Usage: vibration.py OUT_DIR [--docs MD] [--figure PNG]

OUT_DIR holds <airframe>_<turbulence>_<way>/<airframe>/ as ladrc_sil --out writes it, for the
ways clean (no vibration, no filter), clean_filtered (no vibration, the file's [filter] stage),
raw (vibration, no filter) and filtered (vibration and the filter). Printed, and with --docs
written between the vibration markers of MD:

- the lines: how far the filter stage takes each rotor line down, measured in the filtered runs
  as the power of the line in the raw gyro over its power in the gyro the controllers got;
- per controller: tracking RMS of the clean run and the change of the others from it, per axis;
  the torque command's noise above 20 Hz, and the part of it the vibration adds (its power over
  the run without vibration), raw and filtered.

Every figure comes from the runs' metrics.csv and time series. A run that diverged, or a case
that is missing, is named as such in the table and makes the exit status 1.
"""
import argparse
import csv
import functools
import glob
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import files_under, refuse_figure_formats, refuse_inputs, save_figure  # noqa: E402
from report import rewrite_blocks  # noqa: E402
from sim_output import AXES, CONTROLLERS, divergence_text, is_number, load_metrics  # noqa: E402

import numpy as np  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
TURBULENCE = ("light", "moderate", "severe")
WAYS = ("clean", "clean_filtered", "raw", "filtered")
FAMILY = ("HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC")
SKIP_S = 2.0          # the first 2 s hold the initial step's transient, not noise
NOISE_HZ = 20.0       # command noise: its power above this frequency
SEGMENT_S = 2.0       # Welch segments: 0.5 Hz bins, 9 segments of 2 s with half overlap in 10 s
LINE_MARGIN_HZ = 1.0  # a line's band: the rotor rates it spans in the run, widened by this
SIDE_HZ = 8.0         # the floor under a line: the median PSD this far on either side of its band
# A line is resolved in a spectrum when its power stands above the floor by this many standard
# deviations of the floor's band power (Welch: a bin's estimate over K segments has a relative
# standard deviation of about 1 / sqrt(K)).
RESOLVED_SIGMA = 2.0
# A vibration's part of the command noise counts as gone when it is below this share of the filtered
# run's noise power (the runs share their noise draws, so the remainder is the vibration's own).
GONE_SHARE = 0.01
# The targets: lines at least 20 dB down, the family's command noise 10x down, tracking within 5 %.
LINE_TARGET_DB = 20.0
NOISE_TARGET = 10.0
TRACKING_TARGET = 0.05


def frames():
    return sorted(os.path.splitext(os.path.basename(p))[0]
                  for p in glob.glob(os.path.join(ROOT, "scenarios", "vibration", "*.ini")))


def run_dir(out, frame, turb, way):
    return os.path.join(out, "%s_%s_%s" % (frame, turb, way), frame)


def load_series(path, columns):
    """{column: numpy array} of one controller's time series."""
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        idx = [header.index(c) for c in columns]
        rows = [[float(r[i]) for i in idx] for r in reader]
    data = np.array(rows)
    return {c: data[:, k] for k, c in enumerate(columns)}


def welch(x, dt_s):
    """One-sided PSD (unit^2/Hz) and its bin frequencies (Hz), Hann segments of SEGMENT_S, half
    overlap; and K, the number of segments."""
    n = int(round(SEGMENT_S / dt_s))
    step = n // 2
    win = np.hanning(n)
    scale = 1.0 / (np.sum(win ** 2) / dt_s)
    segs = [x[i:i + n] for i in range(0, len(x) - n + 1, step)]
    psd = np.zeros(n // 2 + 1)
    for s in segs:
        spec = np.fft.rfft((s - np.mean(s)) * win)
        psd += np.abs(spec) ** 2
    psd *= 2.0 * scale / len(segs)
    return np.fft.rfftfreq(n, dt_s), psd, len(segs)


def high_rms(x, dt_s):
    """RMS of x above NOISE_HZ, from its PSD."""
    f, p, _ = welch(x, dt_s)
    df = f[1] - f[0]
    return math.sqrt(np.sum(p[f > NOISE_HZ]) * df)


COLUMNS = (["t_s"] + ["torque_cmd_%s_Nm" % a for a in AXES] + ["meas_rate_%s_deg_s" % a for a in AXES]
           + ["ctrl_rate_%s_deg_s" % a for a in AXES] + ["w2_%d_rad2_s2" % i for i in range(1, 5)])


@functools.lru_cache(maxsize=None)
def run_of(path):
    """The Run of a time series, read once however many tables use it."""
    return Run(path)


class Run:
    """One controller's run after SKIP_S: its series, step and rotor rates (Hz)."""

    def __init__(self, path):
        d = load_series(path, COLUMNS)
        keep = d["t_s"] > SKIP_S
        self.s = {k: v[keep] for k, v in d.items()}
        self.dt_s = float(np.median(np.diff(self.s["t_s"])))
        w2 = np.stack([self.s["w2_%d_rad2_s2" % i] for i in range(1, 5)])
        self.rotor_hz = np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi)

    def cmd_noise(self, axis):
        return high_rms(self.s["torque_cmd_%s_Nm" % axis], self.dt_s)

    def line_bands(self, orders):
        """(lo, hi) Hz of each order's line: the rotor rates the run spans."""
        lo, hi = np.percentile(self.rotor_hz, 0.5), np.percentile(self.rotor_hz, 99.5)
        return [(k * lo - LINE_MARGIN_HZ, k * hi + LINE_MARGIN_HZ) for k in orders]


def line_power(f, p, k_segments, band, bands):
    """(power above the floor, the floor's standard deviation) of a line in a PSD."""
    df = f[1] - f[0]
    inside = (f >= band[0]) & (f <= band[1])
    side = ((f >= band[0] - SIDE_HZ) & (f < band[0])) | ((f > band[1]) & (f <= band[1] + SIDE_HZ))
    for b in bands:  # a neighbour's line is no floor
        side &= ~((f >= b[0]) & (f <= b[1]))
    floor = float(np.median(p[side]))
    n = int(np.sum(inside))
    return float(np.sum(p[inside] - floor) * df), floor * df * math.sqrt(n / k_segments)


def attenuation_db(run, axis, orders):
    """Per order: (dB, resolved) of the filter on the line, raw over filtered gyro. When the
    filtered line is lost in the floor, the dB is the bound the floor allows and resolved False."""
    fr, pr, k = welch(run.s["meas_rate_%s_deg_s" % axis], run.dt_s)
    _, pf, _ = welch(run.s["ctrl_rate_%s_deg_s" % axis], run.dt_s)
    bands = run.line_bands(orders)
    out = []
    for band in bands:
        if band[1] + SIDE_HZ >= fr[-1]:
            out.append(None)
            continue
        raw, _ = line_power(fr, pr, k, band, bands)
        filt, sigma = line_power(fr, pf, k, band, bands)
        resolved = filt > RESOLVED_SIGMA * sigma
        out.append((10.0 * math.log10(raw / (filt if resolved else RESOLVED_SIGMA * sigma)), resolved))
    return out


def scenario_value(frame, section, key):
    """A key's value in scenarios/vibration/<frame>.ini (first occurrence in its section)."""
    here = None
    with open(os.path.join(ROOT, "scenarios", "vibration", frame + ".ini")) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line.startswith("["):
                here = line.strip("[]").strip()
            elif here == section and "=" in line:
                k, v = (s.strip() for s in line.split("=", 1))
                if k == key:
                    return v
    return None


def controllers_of(metrics):
    return [c for c in CONTROLLERS if any(k[0] == c for k in metrics)]


def fmt_change(v, ref):
    return "%+.1f %%" % (100.0 * (v / ref - 1.0)) if is_number(v) and is_number(ref) and ref > 0 else "—"


class Study:
    def __init__(self, out):
        self.out = out
        self.problems = []
        self.lines = []
        self.verdicts = {"lines": [], "noise": [], "noise_part": [], "tracking": [], "tracking_yaw": []}

    def metrics(self, frame, turb, way):
        m = load_metrics(run_dir(self.out, frame, turb, way))
        if m is None:
            self.problems.append("missing: %s %s %s" % (frame, turb, way))
        return m

    def csv(self, frame, turb, way, c):
        return os.path.join(run_dir(self.out, frame, turb, way), c + ".csv")

    def table(self, header, rows):
        self.lines.append("| " + " | ".join(header) + " |")
        self.lines.append("|" + "---|" * len(header))
        for r in rows:
            self.lines.append("| " + " | ".join(r) + " |")
        self.lines.append("")

    def lines_table(self):
        """How far the filter takes each rotor line down, per airframe, worst over controllers,
        axes and turbulence."""
        rows = []
        for frame in frames():
            orders = [float(v) for v in scenario_value(frame, "vibration", "orders").split()]
            worst = [None] * len(orders)
            hz = None
            for turb in TURBULENCE:
                m = self.metrics(frame, turb, "filtered")
                if m is None:
                    continue
                for c in controllers_of(m):
                    if divergence_text(m, c):
                        continue
                    run = run_of(self.csv(frame, turb, "filtered", c))
                    if hz is None:
                        hz = float(np.median(run.rotor_hz))
                    for axis in AXES:
                        for i, a in enumerate(attenuation_db(run, axis, orders)):
                            if a is not None and (worst[i] is None or a[0] < worst[i][0]):
                                worst[i] = a
            cells = []
            for k, w in zip(orders, worst):
                if w is None:
                    cells.append("%g× —" % k)
                    continue
                text = ("%.1f dB" if w[1] else "> %.1f dB") % w[0]
                cells.append("%g× (%.0f Hz): %s" % (k, k * (hz or 0.0), text))
                self.verdicts["lines"].append(w[0] >= LINE_TARGET_DB)
            rows.append(["`%s`" % frame, "%.1f" % (hz or float("nan"))] + cells)
        n = max(len(r) for r in rows) - 2 if rows else 0
        self.table(["airframe", "rotor rate, Hz"] + ["line %d" % (i + 1) for i in range(n)],
                   [r + [""] * (n + 2 - len(r)) for r in rows])

    def controller_tables(self):
        for frame in frames():
            self.lines.append("**`%s`**" % frame)
            self.lines.append("")
            rows = []
            for turb in TURBULENCE:
                ms = {w: self.metrics(frame, turb, w) for w in WAYS}
                if any(m is None for m in ms.values()):
                    rows.append([turb, "**missing**"] + [""] * 6)
                    continue
                for c in controllers_of(ms["clean"]):
                    rows.append([turb] + self.controller_row(frame, turb, c, ms))
            self.table(["turbulence", "controller", "tracking RMS, deg: clean", "filter alone", "vibration raw",
                        "vibration filtered", "command noise > 20 Hz, N m: clean / raw → filtered",
                        "down by", "vibration's part: raw → filtered"], rows)

    def controller_row(self, frame, turb, c, ms):
        broken = [(w, divergence_text(ms[w], c)) for w in WAYS if divergence_text(ms[w], c)]
        if broken:
            self.problems.append("%s %s %s: %s" % (frame, turb, c, "; ".join("%s %s" % b for b in broken)))
            return [c, "**%s**" % "; ".join("%s %s" % b for b in broken)] + [""] * 6
        rms = {w: [ms[w].get((c, "4", "error_rms_deg", a)) for a in AXES] for w in WAYS}
        change = {w: " / ".join(fmt_change(v, r) for v, r in zip(rms[w], rms["clean"])) for w in WAYS}
        worst = [max(abs(v / r - 1.0) for v, r in zip(rms["filtered"][:2], rms["clean"][:2])),
                 abs(rms["filtered"][2] / rms["clean"][2] - 1.0)]
        self.verdicts["tracking"].append(worst[0] <= TRACKING_TARGET)
        self.verdicts["tracking_yaw"].append(worst[1] <= TRACKING_TARGET)
        noise = {w: [run_of(self.csv(frame, turb, w, c)).cmd_noise(a) for a in AXES] for w in WAYS}
        down = min(r / f for r, f in zip(noise["raw"], noise["filtered"]))
        axis_max = max(range(3), key=lambda i: noise["raw"][i])
        part = self.vibration_part(noise)
        if c in FAMILY:
            self.verdicts["noise"].append(down >= NOISE_TARGET)
            if part[1] is not None:
                self.verdicts["noise_part"].append(part[1] >= NOISE_TARGET)
        return [c, " / ".join("%.3f" % v for v in rms["clean"]), change["clean_filtered"], change["raw"],
                change["filtered"], "%.2g / %.2g → %.2g (%s)" % (noise["clean"][axis_max], noise["raw"][axis_max],
                                                               noise["filtered"][axis_max], AXES[axis_max]),
                "%.1f×" % down, part[0]]

    @staticmethod
    def vibration_part(noise):
        """(text, factor or None) of the noise the vibration adds, on the axis where it falls least:
        sqrt(raw^2 - clean^2) against sqrt(filtered^2 - clean_filtered^2)."""
        worst = None
        for i in range(3):
            raw2 = noise["raw"][i] ** 2 - noise["clean"][i] ** 2
            filt2 = noise["filtered"][i] ** 2 - noise["clean_filtered"][i] ** 2
            if raw2 <= GONE_SHARE * noise["raw"][i] ** 2:
                continue  # the vibration adds nothing to this axis's command
            if filt2 <= GONE_SHARE * noise["filtered"][i] ** 2:
                factor, text = math.sqrt(raw2 / (GONE_SHARE * noise["filtered"][i] ** 2)), None
                text = "%.2g → gone (> %.0f×)" % (math.sqrt(raw2), factor)
            else:
                factor = math.sqrt(raw2 / filt2)
                text = "%.2g → %.2g (%.0f×)" % (math.sqrt(raw2), math.sqrt(filt2), factor)
            if worst is None or factor < worst[1]:
                worst = (text + " " + AXES[i], factor)
        return worst if worst is not None else ("none reaches the command", None)

    def lean_table(self):
        """The leaner filter (RPM notches of Q 10, no low-pass) in moderate turbulence, against the clean
        run: tracking per axis with and without vibration, the command noise and the lines."""
        rows = []
        for frame in frames():
            ms = {w: self.metrics(frame, "moderate", w) for w in ("clean", "raw", "lean_clean", "lean")}
            if any(m is None for m in ms.values()):
                rows.append(["`%s`" % frame, "**missing**"] + [""] * 5)
                continue
            orders = [float(v) for v in scenario_value(frame, "vibration", "orders").split()]
            for c in controllers_of(ms["clean"]):
                broken = [(w, divergence_text(ms[w], c)) for w in ms if divergence_text(ms[w], c)]
                if broken:
                    self.problems.append("%s lean %s: %s" % (frame, c, "; ".join("%s %s" % b for b in broken)))
                    rows.append(["`%s`" % frame, c, "**%s**" % "; ".join("%s %s" % b for b in broken)] + [""] * 4)
                    continue
                rms = {w: [ms[w].get((c, "4", "error_rms_deg", a)) for a in AXES] for w in ms}
                change = {w: " / ".join(fmt_change(v, r) for v, r in zip(rms[w], rms["clean"]))
                          for w in ("lean_clean", "lean")}
                runs = {w: run_of(self.csv(frame, "moderate", w, c)) for w in ms}
                noise = {w: [runs[w].cmd_noise(a) for a in AXES] for w in ms}
                part = self.vibration_part({"clean": noise["clean"], "raw": noise["raw"],
                                            "clean_filtered": noise["lean_clean"], "filtered": noise["lean"]})
                down = min(r / f for r, f in zip(noise["raw"], noise["lean"]))
                worst = min((a for axis in AXES for a in attenuation_db(runs["lean"], axis, orders) if a is not None),
                            key=lambda a: a[0])
                rows.append(["`%s`" % frame, c, change["lean_clean"], change["lean"], "%.1f×" % down, part[0],
                             ("%.1f dB" if worst[1] else "> %.1f dB") % worst[0]])
        self.table(["airframe", "controller", "tracking: lean filter alone", "vibration through it",
                    "command noise down by", "vibration's part: raw → filtered", "lines down, worst"], rows)

    def summary(self):
        v = self.verdicts
        say = []
        for name, what in (
                ("lines", "rotor lines at least %.0f dB down" % LINE_TARGET_DB),
                ("noise", "LADRC-family runs whose command noise falls %.0f× or more on every axis" % NOISE_TARGET),
                ("noise_part", "LADRC-family runs where the vibration's part of it falls %.0f× or more on every axis "
                 "(plain LADRC, which reads no gyro, has none to remove)" % NOISE_TARGET),
                ("tracking", "filtered runs with roll and pitch tracking RMS within %.0f %% of the clean run"
                 % (100 * TRACKING_TARGET)),
                ("tracking_yaw", "the same for yaw (held at 0: its RMS is the turbulence's residue, 0.01-0.05 deg)")):
            say.append("- %s: %d of %d" % (what, sum(v[name]), len(v[name])))
        self.lines[:0] = say + [""]


def figure(out, png):
    """Raw against filtered gyro (roll, LADRC, moderate turbulence) per airframe, lines marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fs = frames()
    fig, axes = plt.subplots(len(fs), 1, figsize=(10, 3.2 * len(fs)), dpi=110)
    for ax, frame in zip(np.atleast_1d(axes), fs):
        run = run_of(os.path.join(run_dir(out, frame, "moderate", "filtered"), "LADRC.csv"))
        f, pr, _ = welch(run.s["meas_rate_roll_deg_s"], run.dt_s)
        _, pf, _ = welch(run.s["ctrl_rate_roll_deg_s"], run.dt_s)
        ax.semilogy(f[1:], pr[1:], lw=0.8, color="#d62728", label="raw gyro (meas_rate_roll)")
        ax.semilogy(f[1:], pf[1:], lw=0.8, color="#1f77b4", label="filtered, what the controller got (ctrl_rate_roll)")
        hz = float(np.median(run.rotor_hz))
        for k in [float(v) for v in scenario_value(frame, "vibration", "orders").split()]:
            ax.axvline(k * hz, color="0.4", ls="--", lw=0.8)
            ax.text(k * hz, ax.get_ylim()[1], " %g× %.0f Hz" % (k, k * hz), va="top", fontsize=8)
        ax.set_title("%s: roll gyro, LADRC, moderate turbulence (rotor lines dashed)" % frame)
        ax.set_xlabel("Hz")
        ax.set_ylabel("(deg/s)²/Hz")
        ax.set_xlim(0, f[-1])
        ax.grid(True, alpha=0.3)
        ax.legend(loc="lower left", fontsize=8)
    fig.tight_layout()
    save_figure(fig, png)
    plt.close(fig)
    print("vibration.py: wrote", png)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out_dir")
    p.add_argument("--docs", help="write the block between <!-- vibration:begin/end --> of this page")
    p.add_argument("--figure", help="draw the spectrum figure into this PNG")
    a = p.parse_args(argv)
    refuse_inputs("vibration.py", {"--docs": a.docs, "--figure": a.figure},
                  files_under(a.out_dir, (".csv", ".txt", ".ini"))
                  + files_under(os.path.join(ROOT, "scenarios", "vibration"), (".ini",)))
    refuse_figure_formats("vibration.py", {"--figure": a.figure})
    st = Study(a.out_dir)
    st.lines.append("How far the filter stage takes the rotor lines down (worst over controllers, axes and "
                    "turbulence; \">\": the filtered line is lost in the noise floor, the figure is the bound "
                    "it allows):")
    st.lines.append("")
    st.lines_table()
    st.lines.append("Per controller: tracking RMS of the clean run (no vibration, no filter, roll / pitch / yaw) "
                    "and its change per axis with the filter alone, with vibration unfiltered (raw) and with "
                    "vibration filtered; torque command noise above 20 Hz on the axis where the vibration raises "
                    "it most, the smallest factor over the axes by which the filter lowers it, and the part the "
                    "vibration adds, on the axis where the filter takes the least of it:")
    st.lines.append("")
    st.controller_tables()
    st.lines.append("A leaner filter, RPM notches of Q 10 and no low-pass, in moderate turbulence: the change of "
                    "tracking RMS from the clean run per axis, the command noise and the lines as above:")
    st.lines.append("")
    st.lean_table()
    st.summary()
    if st.problems:
        st.lines.append("Not measured: " + "; ".join(st.problems))
    print("\n".join(st.lines))
    rc = 1 if st.problems else 0
    if a.docs:
        rc |= rewrite_blocks(a.docs, {"vibration": st.lines})
    if a.figure:
        figure(a.out_dir, a.figure)
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
