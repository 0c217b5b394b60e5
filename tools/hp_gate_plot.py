#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""HP-MLADRC's gate in one run of tools/hp_gate.py (docs/hp-gate.md): per axis, the disturbance
flown and HP's applied estimate, the gate's weight, and its evidence against the engage threshold
(hp_evidence{k}_<axis>_ratio per tone k, or hp_evidence_<axis>; 1 = engage), the disturbance's
window shaded. A build that does not log the evidence gets the weight alone, and the title says so.

    tools/hp_gate_plot.py CASE_DIR [--out FILE.png]

CASE_DIR is one case's folder of `tools/hp_gate.py --out` (HP-MLADRC.csv and signals.csv);
FILE defaults to CASE_DIR/hp_gate.png. A folder without HP-MLADRC.csv is an error (exit 1); a FILE
that is one of the folder's files is refused (exit 2)."""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figures import AXIS_SYMBOLS, save, stride  # noqa: E402  (figures.py sets the house style)
from hp_gate import HP, RunFailed, disturbance_windows, evidence_columns, evidence_series, read_columns  # noqa: E402
from output_files import files_under, refuse_figure_formats, refuse_inputs  # noqa: E402
from plot_style import COLOURS, clip_ylim  # noqa: E402
from sim_output import AXES  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

EVIDENCE_THRESHOLD = 1.0  # the evidence columns are normalised so that the gate engages at 1
TONE_STYLES = ("-", "--", ":", "-.")
EVIDENCE_FLOOR = 1e-3     # the evidence panel's lowest value, a fraction of the threshold
DIST_COLOUR = "black"


def evidence_label(column):
    """"tone 2" for hp_evidence2_roll_ratio, "evidence" for the per-axis hp_evidence_roll."""
    k = column[len("hp_evidence"):].split("_")[0]
    return "tone " + k if k else "evidence"


def log_evidence(ax, values):
    """A log y axis for the evidence: a locked tone's runs to thousands of times the threshold, the
    noise's stays near or below it; down to EVIDENCE_FLOOR of the threshold."""
    v = np.concatenate([x[np.isfinite(x)] for x in values] + [np.array([EVIDENCE_THRESHOLD])])
    ax.set_yscale("log")
    ax.set_ylim(EVIDENCE_FLOOR * EVIDENCE_THRESHOLD, 2.0 * max(v.max(), EVIDENCE_THRESHOLD))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("case_dir")
    p.add_argument("--out", help="the PNG to write (default CASE_DIR/hp_gate.png)")
    args = p.parse_args()
    out = args.out or os.path.join(args.case_dir, "hp_gate.png")
    refuse_inputs("hp_gate_plot.py", {"--out": out}, files_under(args.case_dir, (".csv", ".txt", ".ini")))
    refuse_figure_formats("hp_gate_plot.py", {"--out": out})
    path = os.path.join(args.case_dir, HP + ".csv")
    names = ["t_s"]
    for a in AXES:
        names += ["dist_%s_rad_s2" % a, "hp_est_%s_rad_s2" % a, "hp_weight_%s_frac" % a]
    try:
        run = read_columns(path, names, sum((evidence_columns(a) for a in AXES), []))
        windows = disturbance_windows(args.case_dir)
    except RunFailed as e:
        sys.exit("hp_gate_plot.py: %s" % e)
    evidence = all(evidence_series(run, a) for a in AXES)
    t = run["t_s"]
    k = stride(len(t))
    rows = 3 if evidence else 2
    fig, axes = plt.subplots(rows, 3, figsize=(14, 2.4 * rows + 1.2), sharex=True, squeeze=False)
    case = os.path.basename(os.path.normpath(args.case_dir))
    fig.suptitle("HP-MLADRC's gate, %s%s" % (
        case, "" if evidence else ": weight alone (this build logs no evidence, hp_evidence{k}_<axis>_ratio)"))
    for col, a in enumerate(AXES):
        panels = axes[:, col]
        dist, est = run["dist_%s_rad_s2" % a], run["hp_est_%s_rad_s2" % a]
        panels[0].plot(t[::k], dist[::k], color=DIST_COLOUR, lw=0.8, label="disturbance")
        panels[0].plot(t[::k], est[::k], color=COLOURS[HP], lw=0.8, label="HP's applied estimate")
        clip_ylim(panels[0], [dist, est], "rad/s²")
        panels[0].set_title(AXIS_SYMBOLS[a])
        panels[1].plot(t[::k], run["hp_weight_%s_frac" % a][::k], color=COLOURS[HP], lw=1.0)
        panels[1].set_ylim(-0.05, 1.05)
        if evidence:
            series = evidence_series(run, a)
            for i, (name, ev) in enumerate(series):
                panels[2].plot(t[::k], ev[::k], color=COLOURS[HP], lw=0.8, ls=TONE_STYLES[i % len(TONE_STYLES)],
                               label=evidence_label(name))
            panels[2].axhline(EVIDENCE_THRESHOLD, color="0.3", ls="--", lw=0.9, label="engage threshold")
            log_evidence(panels[2], [ev for _, ev in series])
        if a in windows:
            lo, hi = windows[a]
            for ax in panels:
                ax.axvspan(max(lo, t[0]), min(hi, t[-1]), color="0.85", zorder=0, lw=0)
        panels[-1].set_xlabel("t (s)")
    axes[0, 0].set_ylabel("rad/s²")
    axes[1, 0].set_ylabel("gate weight")
    if evidence:
        axes[2, 0].set_ylabel("evidence (1 = engage)")
        axes[2, 0].legend(loc="upper left")
    axes[0, 0].legend(loc="upper left")
    fig.tight_layout()
    save(fig, os.path.dirname(os.path.abspath(out)), os.path.basename(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
