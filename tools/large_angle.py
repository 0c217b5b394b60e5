#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The large-angle study's tables and figure (docs/large-angle.md), from tools/large_angle.sh.

Usage: large_angle.py OUT_DIR [--docs MD] [--figure PNG]

OUT_DIR holds <way>/<scenario>/ as ladrc_sil --out writes it, for the ways tuned (as shipped:
tune = margins, quaternion frame), gains_quaternion and gains_euler (every controller at its
default gains in the quaternion and in the Euler frame). Printed, and with --docs written between
the large-angle markers of MD:

- the tuned runs: per controller and scenario, the largest tracking error over the run and over
  the axes, the longest settling time into the band after the manoeuvres, the widest steady band;
- the same gains in both frames: the largest error in each, or where the run diverged.

Every figure comes from the runs' metrics.csv and time series. A run that is missing, or a tuned
run that diverged, is named as such and makes the exit status 1.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import files_under, refuse_figure_formats, refuse_inputs, save_figure  # noqa: E402
from report import rewrite_blocks  # noqa: E402
from sim_output import AXES, CONTROLLERS, NOT_SETTLED, divergence_text, is_number, load_metrics  # noqa: E402

SCENARIOS = (("flips", "flips (a roll turn, then a pitch turn)"),
             ("yaw_turn_pitched", "yaw turn of 180 deg at 60 deg of pitch"))
WAYS = ("tuned", "gains_quaternion", "gains_euler")


def worst(metrics, controller, quantity):
    """The largest value of a quantity over the axes, NOT_SETTLED if an axis did not settle, or None."""
    values = [metrics.get((controller, "5", quantity, a)) for a in AXES]
    if any(v == NOT_SETTLED for v in values):
        return NOT_SETTLED
    numbers = [v for v in values if is_number(v)]
    return max(numbers) if len(numbers) == len(AXES) else None


def cell(v, fmt):
    if v is None:
        return "-"
    return "not settled" if v == NOT_SETTLED else fmt % v


class Study:
    def __init__(self, out_dir):
        self.out = out_dir
        self.lines = []
        self.problems = []
        self.m = {}
        for way in WAYS:
            for scen, _ in SCENARIOS:
                got = load_metrics(os.path.join(out_dir, way, scen))
                if got is None:
                    self.problems.append("%s/%s: no metrics.csv" % (way, scen))
                self.m[(way, scen)] = got or {}

    def tuned_table(self):
        head = "| controller |" + "".join(" %s: max error, settled after, steady band |" % s for s, _ in SCENARIOS)
        self.lines += [head, "|---|" + "---:|" * len(SCENARIOS)]
        for c in CONTROLLERS:
            row = "| %s |" % c
            for scen, _ in SCENARIOS:
                m = self.m[("tuned", scen)]
                div = divergence_text(m, c) if m else None
                if div:
                    self.problems.append("tuned %s %s %s" % (scen, c, div))
                    row += " %s |" % div
                    continue
                row += " %s deg, %s s, %s deg |" % (cell(worst(m, c, "max_error_deg"), "%.2f"),
                                                    cell(worst(m, c, "settling_s"), "%.3f"),
                                                    cell(worst(m, c, "steady_band_deg"), "%.3f"))
            self.lines.append(row)
        self.lines.append("")

    def frames_table(self):
        head = "| controller |" + "".join(" %s: quaternion | Euler |" % s for s, _ in SCENARIOS)
        self.lines += [head, "|---|" + "---:|---:|" * len(SCENARIOS)]
        for c in CONTROLLERS:
            row = "| %s |" % c
            for scen, _ in SCENARIOS:
                for way in ("gains_quaternion", "gains_euler"):
                    m = self.m[(way, scen)]
                    div = divergence_text(m, c) if m else None
                    row += " %s |" % (div if div else cell(worst(m, c, "max_error_deg"), "%.2f deg"))
            self.lines.append(row)
        self.lines.append("")


def error_norm_deg(path, skip=5):
    """t (s) and |error| (deg, the error vector's norm) from a time series, every skip-th line."""
    t, e = [], []
    with open(path, newline="") as f:
        for k, row in enumerate(csv.DictReader(f)):
            if k % skip:
                continue
            v = [float(row["error_%s_deg" % a]) for a in AXES]
            t.append(float(row["t_s"]))
            e.append(math.sqrt(sum(x * x for x in v)))
    return t, e


def figure(out_dir, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(9, 7))
    ax = axes[0]
    for c in CONTROLLERS:
        path = os.path.join(out_dir, "tuned", "flips", c + ".csv")
        if os.path.exists(path):
            ax.plot(*error_norm_deg(path), label=c, lw=1)
    ax.set_title("flips (roll turn 1-2.5 s, pitch turn 5-6.5 s), tuned, quaternion frame")
    ax.set_ylabel("|attitude error| (deg)")
    ax.legend(ncol=4, fontsize=8)
    ax.grid(alpha=0.3)
    ax = axes[1]
    for c, colour in (("RATE-ADRC", "C3"), ("CASCADED", "C5"), ("INDI", "C6")):
        for way, style in (("gains_quaternion", "-"), ("gains_euler", "--")):
            path = os.path.join(out_dir, way, "yaw_turn_pitched", c + ".csv")
            if os.path.exists(path):
                frame = "quaternion" if way == "gains_quaternion" else "Euler"
                ax.plot(*error_norm_deg(path), style, color=colour, label="%s, %s frame" % (c, frame), lw=1)
    ax.set_title("yaw turn of 180 deg (3-5 s) at 60 deg of pitch, default gains")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("|attitude error| (deg)")
    ax.legend(ncol=3, fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, png, dpi=100)
    plt.close(fig)
    print("large_angle.py: wrote", png)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out_dir")
    p.add_argument("--docs", help="write the block between <!-- large-angle:begin/end --> of this page")
    p.add_argument("--figure", help="draw the figure into this PNG")
    a = p.parse_args(argv)
    refuse_inputs("large_angle.py", {"--docs": a.docs, "--figure": a.figure},
                  files_under(a.out_dir, (".csv", ".txt", ".ini")))
    refuse_figure_formats("large_angle.py", {"--figure": a.figure})
    st = Study(a.out_dir)
    st.lines.append("Tuned by tune = margins, quaternion frame (as shipped): the largest tracking error (the "
                    "body-axis rotation vector's largest component over the run), the time after the last "
                    "manoeuvre until every axis stays within 0.5 deg, and the widest steady band:")
    st.lines.append("")
    st.tuned_table()
    st.lines.append("The same default gains (tune = none) in both frames: the largest tracking error, or where "
                    "the run diverged (|error| beyond 90 deg):")
    st.lines.append("")
    st.frames_table()
    if st.problems:
        st.lines.append("Not measured: " + "; ".join(st.problems))
    print("\n".join(st.lines))
    rc = 1 if st.problems else 0
    if a.docs:
        rc |= rewrite_blocks(a.docs, {"large-angle": st.lines})
    if a.figure:
        figure(a.out_dir, a.figure)
    return rc


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
