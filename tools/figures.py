#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Draws the paper's figures (Dong et al., Actuators 2025, 14(10), 504: Figs. 5-12), and Fig. 13
(HP-MLADRC with its frequency known and online), from the output of ladrc_sil.

The same figures of any other scenario given with --paper, --noisy, --known or --diff are titled
with its name and mark its own disturbance windows (from its signals.csv), not the paper's: the
paper's titles and Table 2 onsets belong to the shipped scenarios paper, paper_noisy, paper_known
and table3_differentiator alone.

Usage: figures.py OUT_DIR FIG_DIR [--paper NAME] [--noisy NAME] [--known NAME] [--diff NAME]

OUT_DIR holds one directory per scenario, as written by `ladrc_sil --out OUT_DIR`:
<scenario>/<controller>.csv, <scenario>/differentiator.csv, <scenario>/metrics.csv.
The PNGs go to FIG_DIR. A scenario that is absent is reported and its figures skipped (an
earlier run's of those names removed from FIG_DIR); the exit status is then 1. A figure that would
be written over one of the scenarios' files (a link to it) is refused: exit status 2.
"""
import argparse
import csv
import glob
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sim_output import AXES, CONTROLLERS, divergence_text, is_number, load_metrics  # noqa: E402
from plot_style import COLOURS, clip_ylim  # noqa: E402,F401  (estimators_plot.py takes COLOURS from here)
from output_files import refuse_inputs, remove_earlier, save_figure  # noqa: E402

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Wider lines lie underneath, so that a curve lying on another stays visible.
WIDTHS = {"HP-MLADRC": 1.0, "LP-MLADRC": 1.3, "LADRC": 2.0, "RATE-ADRC": 1.1, "PID": 1.6, "CASCADED": 1.4, "INDI": 1.2}
ZORDER = {"HP-MLADRC": 4, "LP-MLADRC": 3, "LADRC": 1, "RATE-ADRC": 3.8, "PID": 2, "CASCADED": 2.5, "INDI": 3.5}
# Legend names: the baseline of today's flight stacks says what it is.
NAMES = {"CASCADED": "CASCADED (attitude P → rate PID)"}
AXIS_SYMBOLS = {"roll": "roll φ", "pitch": "pitch θ", "yaw": "yaw ψ"}
ONSETS_S = [2.0, 6.0, 12.0, 25.0]   # where the paper's Table 2 disturbance changes
PAPER_SCENARIOS = ("paper", "paper_noisy", "paper_known", "table3_differentiator")
ZOOM_S = (-0.3, 1.2)                # zoom window around each onset
SIZE_IN = (10, 6)
DPI = 110
MAX_POINTS = 6000                   # per line on full-length plots
# Every figure main() draws into FIG_DIR: one not drawn this run (its scenario missing) is removed,
# so that an earlier run's figure is not taken for this one's.
FIGURES = ("fig05_td_levant.png", "fig06_tracking.png", "fig06_tracking_onsets.png", "fig07_errors.png",
           "fig07_errors_onsets.png", "fig08_radar.png", "fig09_disturbance.png", "fig10_noisy_tracking.png",
           "fig11_noisy_errors.png", "fig12_rotors.png", "fig13_hp_modes.png")
WRITTEN = []  # the paths save() wrote

plt.rcParams.update({"font.size": 10, "axes.grid": True, "grid.alpha": 0.3,
                     "legend.fontsize": 9, "figure.dpi": DPI})


def load_csv(path):
    """Columns of a CSV with a header row, as a dict of float arrays."""
    with open(path, newline="") as f:
        names = next(csv.reader(f))
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(names)}


def load_runs(scen_dir):
    runs = {}
    for c in CONTROLLERS:
        path = os.path.join(scen_dir, c + ".csv")
        if os.path.exists(path):
            runs[c] = load_csv(path)
    return runs




class Scenario:
    """What the figures of one scenario say: its name in titles and where its disturbance changes.
    The paper's scenarios keep the paper's figure titles and Table 2 onsets; any other takes the
    finite ends of its [disturbance] windows from its signals.csv (none if that file is absent)."""

    def __init__(self, out_dir, name):
        self.name = name
        self.paper = name in PAPER_SCENARIOS
        self.onsets = list(ONSETS_S) if self.paper else disturbance_changes(os.path.join(out_dir, name))

    def title(self, fig, paper_text, text):
        """The paper's "Fig. N: ..." title for the paper's scenarios, else `text` and the scenario's name."""
        return "Fig. %s: %s" % (fig, paper_text) if self.paper else "%s, scenario %s" % (text, self.name)


def disturbance_changes(scen_dir):
    """Sorted finite, positive ends of the scenario's [disturbance] windows, from signals.csv."""
    path = os.path.join(scen_dir, "signals.csv")
    if not os.path.exists(path):
        return []
    ends = set()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["signal"] == "disturbance":
                for key in ("from_s", "to_s"):
                    v = float(row[key])
                    if math.isfinite(v) and v > 0.0:
                        ends.add(v)
    return sorted(ends)


# Legend labels: a controller's name, with where its run diverged (its series ends there).
LABELS = {}


def note_divergence(metrics):
    LABELS.clear()
    for c in CONTROLLERS:
        text = divergence_text(metrics or {}, c)
        if text:
            LABELS[c] = "%s (%s)" % (NAMES.get(c, c), text)


def style(c, scale=1.0):
    return {"color": COLOURS[c], "lw": WIDTHS[c] * scale, "zorder": ZORDER[c], "label": LABELS.get(c, NAMES.get(c, c))}


def stride(n):
    return max(1, n // MAX_POINTS)


def mark_onsets(ax, t_end, onsets):
    for t0 in onsets:
        if t0 < t_end:
            ax.axvline(t0, color="0.5", lw=0.8, ls=":")


def save(fig, fig_dir, name):
    """Saves the figure whole as FIG_DIR/name (output_files.save_figure) and closes it."""
    path = os.path.join(fig_dir, name)
    try:
        save_figure(fig, path, dpi=DPI)
    finally:
        plt.close(fig)
    WRITTEN.append(path)
    print("figures.py: wrote", path)


def fig_differentiator(d, metrics, fig_dir, sc):
    """Fig. 5: TD and Levant derivatives of the noisy sine against the exact derivative."""
    t = d["t_s"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=SIZE_IN)
    rms = {k: metrics.get((k, "3", "derivative_error_rms", "-"), math.nan) for k in ("TD", "Levant")}
    lines = [("dr_true", "exact derivative", "k", 1.6),
             ("dr_td", "TD (RMS error %.3f)" % rms["TD"], "#ff7f0e", 0.9),
             ("dr_levant", "Levant (RMS error %.3f)" % rms["Levant"], "#1f77b4", 0.9)]
    if sc.paper:
        lines = [(k, label.replace("(RMS", "(Table 3 RMS"), colour, lw) for k, label, colour, lw in lines]
    s = stride(t.size)
    for key, label, colour, lw in lines:
        top.plot(t[::s], d[key][::s], color=colour, lw=lw, label=label)
    top.set_title(sc.title(5, "derivative of the noisy signal, TD vs Levant",
                           "Derivative of the noisy signal, TD vs Levant"))
    top.set_ylabel("dr/dt (1/s)")
    top.legend(loc="upper right", ncol=3)
    # Zoom: one second in the middle of the run, every sample.
    mid = t[0] + 0.5 * (t[-1] - t[0])
    m = (t >= mid) & (t <= mid + 1.0)
    for key, label, colour, lw in lines:
        bottom.plot(t[m], d[key][m], color=colour, lw=lw, label=label)
    bottom.set_title("zoom on [%.1f, %.1f] s, every sample" % (mid, mid + 1.0))
    bottom.set_xlabel("time (s)")
    bottom.set_ylabel("dr/dt (1/s)")
    top.set_xlabel("time (s)")
    fig.tight_layout()
    save(fig, fig_dir, "fig05_td_levant.png")


def plot_per_axis(runs, key_fmt, title, ylabel, fig_dir, name, with_ref, sc, zoom_end_s=0.0):
    """Three panels (roll, pitch, yaw) over the whole run, all controllers; with zoom_end_s > 0,
    a second column shows the last zoom_end_s seconds, every sample."""
    cols = 2 if zoom_end_s > 0 else 1
    fig, axes = plt.subplots(3, cols, figsize=SIZE_IN, sharex="col", squeeze=False,
                             gridspec_kw={"width_ratios": [2.2, 1][:cols]})
    t_end = max(r["t_s"][-1] for r in runs.values())
    zoom = (t_end - min(zoom_end_s, t_end / 3), t_end)
    for i, axis in enumerate(AXES):
        for j in range(cols):
            ax = axes[i][j]
            if with_ref:
                r = next(iter(runs.values()))
                ax.plot(r["t_s"], r["ref_%s_deg" % axis], color="k", lw=1.6, ls="--", label="reference", zorder=5)
            for c, r in runs.items():
                t, y = r["t_s"], r[key_fmt % axis]
                if j == 0:
                    s = stride(t.size)
                    ax.plot(t[::s], y[::s], **style(c))
                else:
                    m = (t >= zoom[0]) & (t <= zoom[1])
                    ax.plot(t[m], y[m], **style(c, 0.7))
            if j == 0:
                mark_onsets(ax, t_end, sc.onsets)
                ax.set_ylabel("%s (%s)" % (AXIS_SYMBOLS[axis], ylabel))
    axes[0][0].set_title(title)
    if cols == 2:
        axes[0][1].set_title("zoom: last %g s, every sample" % (zoom[1] - zoom[0]), fontsize=10)
        axes[-1][1].set_xlabel("time (s)")
    axes[0][0].legend(loc="upper right", ncol=5 if cols == 1 else 3, fontsize=8)
    shown = [x for x in sc.onsets if x < t_end]
    axes[-1][0].set_xlabel("time (s)   (dotted lines: disturbance changes at %s s)" % ", ".join("%g" % x for x in shown)
                           if shown else "time (s)   (no disturbance window starts or ends in the run)")
    fig.tight_layout()
    save(fig, fig_dir, name)


def plot_onsets(runs, key_fmt, title, ylabel, fig_dir, name, with_ref, sc):
    """Grid of zooms: rows are axes, columns the disturbance onsets; every sample."""
    t_end = max(r["t_s"][-1] for r in runs.values())
    onsets = [t0 for t0 in sc.onsets if t0 < t_end][:6]
    if not onsets:
        return
    fig, axes = plt.subplots(3, len(onsets), figsize=SIZE_IN, squeeze=False)
    for j, t0 in enumerate(onsets):
        for i, axis in enumerate(AXES):
            ax = axes[i][j]
            for c, r in runs.items():
                t = r["t_s"]
                m = (t >= t0 + ZOOM_S[0]) & (t <= t0 + ZOOM_S[1])
                if with_ref and c == next(iter(runs)):
                    ax.plot(t[m], r["ref_%s_deg" % axis][m], color="k", lw=1.4, ls="--", label="reference")
                ax.plot(t[m], r[key_fmt % axis][m], **style(c))
            ax.axvline(t0, color="0.5", lw=0.8, ls=":")
            ax.tick_params(labelsize=8)
            if i == 0:
                ax.set_title("onset at %g s" % t0, fontsize=10)
            if i == 2:
                ax.set_xlabel("time (s)")
            if j == 0:
                ax.set_ylabel("%s (%s)" % (AXIS_SYMBOLS[axis], ylabel))
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=5, bbox_to_anchor=(0.5, 0.955))
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0, 1, 0.935))
    save(fig, fig_dir, name)


def radar_scores(metrics):
    """Table 5 scores per controller, normalised so 1 = best of the controllers, larger = better.

    Each quantity q (max error, settling time, steady band) on each axis: score = min over
    controllers of q / this controller's q; a run that never settles or diverged (a word in
    metrics.csv, not a number) scores 0.
    A spoke on which every controller has the same value tells nothing and is left out; its
    name is returned in the third value.
    """
    quantities = [("max_error_deg", "max error"), ("settling_s", "settling"), ("steady_band_deg", "band")]
    spokes, ties, scores = [], [], {c: [] for c in CONTROLLERS}
    present = [c for c in CONTROLLERS if (c, "5", "max_error_deg", "roll") in metrics]
    for q, label in quantities:
        for axis in AXES:
            vals = {c: metrics[(c, "5", q, axis)] for c in present}
            if len(set(vals.values())) == 1:
                v = next(iter(vals.values()))
                ties.append("%s %s (%s for all)" % (label, axis, ("%g" % v) if is_number(v) else v))
                continue
            valid = [v for v in vals.values() if is_number(v) and v >= 0 and math.isfinite(v)]
            floor = 1e-6
            best = max(min(valid), floor) if valid else floor
            for c in present:
                v = vals[c]
                ok = is_number(v) and v >= 0 and math.isfinite(v)
                scores[c].append(min(1.0, best / max(v, floor)) if ok else 0.0)
            spokes.append("%s\n%s" % (label, axis))
    return spokes, {c: s for c, s in scores.items() if c in present}, ties


def fig_radar(metrics, fig_dir, name, title):
    """Fig. 8: radar chart of the Table 5 scores."""
    spokes, scores, ties = radar_scores(metrics)
    if not scores or len(spokes) < 3:
        return
    angles = np.linspace(0, 2 * np.pi, len(spokes), endpoint=False)
    fig = plt.figure(figsize=SIZE_IN)
    ax = fig.add_subplot(111, projection="polar")
    closed = np.append(angles, angles[0])
    for c, s in scores.items():
        vals = np.append(s, s[0])
        ax.plot(closed, vals, color=COLOURS[c], lw=1.8, zorder=ZORDER[c], label=c)
        ax.fill(closed, vals, color=COLOURS[c], alpha=0.08)
    ax.set_xticks(angles)
    ax.set_xticklabels(spokes, fontsize=9)
    ax.set_ylim(0, 1.05)
    ax.set_yticks([0.25, 0.5, 0.75, 1.0])
    ax.set_yticklabels(["0.25", "0.5", "0.75", "1"], fontsize=8)
    ax.set_rlabel_position(180.0 / len(spokes))
    ax.set_title(title, pad=22)
    ax.legend(loc="upper left", bbox_to_anchor=(1.12, 1.05))
    note = ("score = (smallest value among the controllers) / (this controller's value): 1 = best, "
            "larger = better;\nmax error and steady band in deg, settling time in s (Table 5 of the report); "
            "a run that never settles or diverged scores 0.")
    if ties:
        note += "\nLeft out, equal for every controller: " + "; ".join(ties) + "."
    fig.text(0.02, 0.02, note, fontsize=9)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    save(fig, fig_dir, name)


def fig_disturbance(runs, fig_dir, sc):
    """Fig. 9: the true total disturbance f and the controllers' estimates, and the estimate error."""
    est = {c: r for c, r in runs.items() if not np.all(np.isnan(r["f_est_roll_rad_s2"]))}
    if not est:
        return
    fig, axes = plt.subplots(3, 2, figsize=(10, 7), sharex=True)
    first = next(iter(est.values()))
    t_end = first["t_s"][-1]
    for i, axis in enumerate(AXES):
        left, right = axes[i]
        s = stride(first["t_s"].size)
        left.plot(first["t_s"][::s], first["f_%s_rad_s2" % axis][::s], color="k", lw=2.6, zorder=0,
                  label="true f (run of %s)" % next(iter(est)))
        errors = []
        for c, r in est.items():
            s = stride(r["t_s"].size)
            t = r["t_s"][::s]
            left.plot(t, r["f_est_%s_rad_s2" % axis][::s], **style(c, 0.7))
            errors.append(r["f_est_%s_rad_s2" % axis] - r["f_%s_rad_s2" % axis])
            right.plot(t, errors[-1][::s], **style(c, 0.7))
        clip_ylim(right, errors, "spikes at the steps")
        for ax in (left, right):
            mark_onsets(ax, t_end, sc.onsets)
        left.set_ylabel("%s (rad/s²)" % AXIS_SYMBOLS[axis])
    axes[0][0].set_title("total disturbance f and estimate z3 + d̂")
    axes[0][1].set_title("estimate error z3 + d̂ − f")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=4, bbox_to_anchor=(0.5, 0.955), fontsize=9)
    axes[2][0].set_xlabel("time (s)")
    axes[2][1].set_xlabel("time (s)")
    fig.suptitle(sc.title(9, "total disturbance f (external + coupling + drag) and its estimate; each "
                          "error against the f of its own run",
                          "Total disturbance f (external + coupling + drag) and its estimate"))
    fig.tight_layout(rect=(0, 0, 1, 0.93))
    save(fig, fig_dir, "fig09_disturbance.png")


def fig_rotors(runs, fig_dir, sc):
    """Fig. 12: rotor speed squared (as in Table 7; the paper's ideal rotors can go below 0)."""
    fig, axes = plt.subplots(2, 2, figsize=SIZE_IN, sharex=True)
    t_end = max(r["t_s"][-1] for r in runs.values())
    for k, ax in enumerate(axes.flat):
        for c, r in runs.items():
            s = stride(r["t_s"].size)
            ax.plot(r["t_s"][::s], r["w2_%d_rad2_s2" % (k + 1)][::s] / 1e3, **style(c))
        clip_ylim(ax, [r["w2_%d_rad2_s2" % (k + 1)] / 1e3 for r in runs.values()], "spikes")
        ax.axhline(0, color="k", lw=0.6)
        mark_onsets(ax, t_end, sc.onsets)
        ax.set_title("rotor %d" % (k + 1), fontsize=10)
        ax.set_ylabel("ω² (10³ rad²/s²)")
        if k >= 2:
            ax.set_xlabel("time (s)")
    axes[0][0].legend(loc="upper left", fontsize=8)
    fig.suptitle(sc.title(12, "rotor speed squared ω² (Table 7's quantity; the paper's ideal rotors allow ω² < 0)",
                          "Rotor speed squared ω²"))
    fig.tight_layout()
    save(fig, fig_dir, "fig12_rotors.png")


def fig_hp_modes(online, known, fig_dir, sc, sc_known):
    """Fig. 13 (ours): |tracking error| on a log scale around the frequency jump at 12 s and the steady
    window, HP-MLADRC with the frequency estimated online and given (known), LP-MLADRC and LADRC.
    Another scenario: over its whole run, with its own disturbance changes marked."""
    paper = sc.paper and sc_known.paper
    fig, axes = plt.subplots(3, 1, figsize=(SIZE_IN[0], 8), sharex=True)
    lines = [("HP-MLADRC", online, "HP-MLADRC, online frequency", COLOURS["HP-MLADRC"], "-"),
             ("HP-MLADRC", known, "HP-MLADRC, known frequency", "#17becf", "--"),
             ("LP-MLADRC", online, "LP-MLADRC", COLOURS["LP-MLADRC"], "-"),
             ("LADRC", online, "LADRC", COLOURS["LADRC"], "-")]
    for ax, axis in zip(axes, AXES):
        for c, runs, label, colour, dash in lines:
            if c not in runs:
                continue
            t = runs[c]["t_s"]
            keep = (t > 10.0) & (t <= 27.0) if paper else (t >= 0.0)
            err = np.abs(runs[c]["error_%s_deg" % axis][keep])
            ax.semilogy(t[keep], np.maximum(err, 1e-6), color=colour, ls=dash, lw=1.0, label=label)
        if paper:
            ax.axhline(0.0073, color="0.4", lw=0.8, ls=":")
            ax.axvspan(20.0, 25.0, color="0.9", zorder=0)
        else:
            t_end = max(r["t_s"][-1] for r in online.values())
            mark_onsets(ax, t_end, sc.onsets)
        ax.set_ylim(1e-5, 20.0)
        ax.set_ylabel("|error| %s (deg)" % AXIS_SYMBOLS[axis])
    axes[0].legend(loc="lower left", fontsize=8, ncol=2)
    if paper:
        axes[0].text(20.1, 0.0073 * 1.3, "paper's band 0.0073 deg", fontsize=7, color="0.3")
        axes[0].text(20.1, 5.0, "steady window (20, 25] s", fontsize=7, color="0.3")
        axes[-1].set_xlabel("time (s): the tone jumps from π/4 to 3 rad/s at 12 s and stops at 25 s")
        fig.suptitle("Fig. 13 (ours): HP-MLADRC with the frequency known and estimated online, paper case")
    else:
        axes[-1].set_xlabel("time (s)   (dotted lines: disturbance changes)")
        fig.suptitle("HP-MLADRC with the frequency estimated online (scenario %s) and known (scenario %s)"
                     % (sc.name, sc_known.name))
    fig.tight_layout()
    save(fig, fig_dir, "fig13_hp_modes.png")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out_dir")
    p.add_argument("fig_dir")
    p.add_argument("--paper", default="paper", help="scenario of Figs. 6-9 and 12 (default: paper)")
    p.add_argument("--noisy", default="paper_noisy", help="scenario of Figs. 10-11 (default: paper_noisy)")
    p.add_argument("--known", default="paper_known",
                   help="the paper case with HP's frequency known, for Fig. 13 (default: paper_known)")
    p.add_argument("--diff", default="table3_differentiator",
                   help="scenario of Fig. 5 (default: table3_differentiator)")
    a = p.parse_args(argv)
    read = [f for scen in (a.diff, a.paper, a.noisy, a.known)
            for f in glob.glob(os.path.join(a.out_dir, scen, "*.csv"))]
    refuse_inputs("figures.py", {name: os.path.join(a.fig_dir, name) for name in FIGURES}, read)
    os.makedirs(a.fig_dir, exist_ok=True)
    missing = []

    diff_dir = os.path.join(a.out_dir, a.diff)
    if os.path.exists(os.path.join(diff_dir, "differentiator.csv")):
        fig_differentiator(load_csv(os.path.join(diff_dir, "differentiator.csv")), load_metrics(diff_dir) or {},
                           a.fig_dir, Scenario(a.out_dir, a.diff))
    else:
        missing.append(a.diff)

    paper_dir = os.path.join(a.out_dir, a.paper)
    sc = Scenario(a.out_dir, a.paper)
    case = "paper case" if sc.paper else "scenario " + sc.name
    runs = load_runs(paper_dir)
    note_divergence(load_metrics(paper_dir))
    if runs:
        plot_per_axis(runs, "angle_%s_deg", sc.title(6, "attitude tracking, paper case", "Attitude tracking"), "deg",
                      a.fig_dir, "fig06_tracking.png", True, sc)
        plot_onsets(runs, "angle_%s_deg", "%s: attitude at the disturbance onsets, %s"
                    % ("Fig. 6 (zoom)" if sc.paper else "Zoom", case), "deg", a.fig_dir, "fig06_tracking_onsets.png",
                    True, sc)
        plot_per_axis(runs, "error_%s_deg", sc.title(7, "tracking error (reference − angle), paper case",
                                                     "Tracking error (reference − angle)"), "deg",
                      a.fig_dir, "fig07_errors.png", False, sc)
        plot_onsets(runs, "error_%s_deg", "%s: tracking error at the disturbance onsets, %s"
                    % ("Fig. 7 (zoom)" if sc.paper else "Zoom", case), "deg", a.fig_dir, "fig07_errors_onsets.png",
                    False, sc)
        fig_radar(load_metrics(paper_dir) or {}, a.fig_dir, "fig08_radar.png",
                  sc.title(8, "Table 5 scores, paper case (larger = better)",
                           "Table 5 scores (larger = better)"))
        fig_disturbance(runs, a.fig_dir, sc)
        fig_rotors(runs, a.fig_dir, sc)
        known = load_runs(os.path.join(a.out_dir, a.known))
        if known:
            fig_hp_modes(runs, known, a.fig_dir, sc, Scenario(a.out_dir, a.known))
        else:
            missing.append(a.known)
    else:
        missing.append(a.paper)

    noisy = load_runs(os.path.join(a.out_dir, a.noisy))
    sc_noisy = Scenario(a.out_dir, a.noisy)
    note_divergence(load_metrics(os.path.join(a.out_dir, a.noisy)))
    if noisy:
        plot_per_axis(noisy, "angle_%s_deg", sc_noisy.title(10, "attitude tracking with angle noise",
                                                            "Attitude tracking"), "deg", a.fig_dir,
                      "fig10_noisy_tracking.png", True, sc_noisy)
        plot_per_axis(noisy, "error_%s_deg", sc_noisy.title(11, "tracking error with angle noise", "Tracking error"),
                      "deg", a.fig_dir, "fig11_noisy_errors.png", False, sc_noisy, zoom_end_s=3.0)
    else:
        missing.append(a.noisy)

    for name in missing:
        print("figures.py: no output of scenario '%s' in %s; its figures are skipped" % (name, a.out_dir),
              file=sys.stderr)
    remove_earlier("figures.py", a.fig_dir, FIGURES, WRITTEN)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
