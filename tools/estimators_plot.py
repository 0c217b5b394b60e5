#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Draws what the disturbance estimators did in a scenario's runs, per axis: HP-MLADRC's gate
weight and active tones, its tones' frequencies and amplitudes, and HP's and LP-MLADRC's estimates
d̂ against the true total disturbance f (the estimator columns of docs/csv-format.md).

Usage: estimators_plot.py OUT_DIR FIG_DIR SCENARIO [SCENARIO ...]

OUT_DIR holds <scenario>/HP-MLADRC.csv and <scenario>/LP-MLADRC.csv as `ladrc_sil --out OUT_DIR`
writes them; each scenario gives FIG_DIR/fig14_estimators_<scenario>.png. Printed per axis: where
HP's gate holds its weight above ENGAGED, and how closely LP's d̂ follows f after the first
disturbance change: the measured figures docs/comparisons.md quotes. A
scenario with neither run, or a run without the estimator columns, is an error (exit status 1) and
its earlier figure is removed; a figure that would be written over one of the runs (a link to it) is
refused (exit status 2).
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from figures import AXIS_SYMBOLS, COLOURS, Scenario, load_csv, mark_onsets, save, stride  # noqa: E402
from output_files import refuse_inputs, remove_earlier  # noqa: E402
from sim_output import AXES  # noqa: E402

import matplotlib.pyplot as plt  # noqa: E402  (figures.py chose the Agg backend)
import numpy as np  # noqa: E402

ENGAGED = 0.5  # a gate weight above this carries most of HP's model into the command
TONE_STYLES = ("-", "--", ":", "-.")


def tone_count(run):
    """Tones with columns in this series (the build's LADRC_HP_MAX_TONES)."""
    k = 0
    while "hp_freq%d_roll_rad_s" % (k + 1) in run:
        k += 1
    return k


def log_scale(ax, values):
    """A log y axis down to 1e-4 of the largest value: the refits' peaks at the changes are ten
    times the settled amplitudes, which a linear axis would flatten."""
    v = np.concatenate([x[np.isfinite(x) & (x > 0)] for x in values])
    if v.size:
        ax.set_yscale("log")
        ax.set_ylim(max(v.min(), 1e-4 * v.max()), 2.0 * v.max())


def engaged_spans(t, weight):
    """(start, end) times, s, of the runs of ticks where the weight exceeds ENGAGED."""
    on = np.nan_to_num(weight, nan=0.0) > ENGAGED
    edges = np.flatnonzero(np.diff(np.concatenate(([0], on.astype(int), [0]))))
    return [(t[a], t[b - 1]) for a, b in zip(edges[::2], edges[1::2])]


def summary(name, axis, t, weight):
    spans = engaged_spans(t, weight)
    dt = t[1] - t[0] if t.size > 1 else 0.0
    total = sum(b - a + dt for a, b in spans)
    text = ", ".join("%.2f-%.2f s" % span for span in spans[:6]) + (" ..." if len(spans) > 6 else "")
    return "%s %s: HP gate weight > %.1f for %.2f s of %.2f s in %d span%s%s" % (
        name, axis, ENGAGED, total, t[-1] - t[0] + dt, len(spans), "" if len(spans) == 1 else "s",
        (": " + text) if spans else "")


def lp_summary(name, axis, run, after_s):
    """How closely LP's d̂ follows its run's true f after after_s (the first disturbance change)."""
    keep = run["t_s"] > after_s
    f, d = run["f_%s_rad_s2" % axis][keep], run["lp_est_%s_rad_s2" % axis][keep]
    if f.size < 2:
        return "%s %s: LP d̂: no samples after %.2f s" % (name, axis, after_s)
    return "%s %s: LP d̂ against f over (%.2f, %.2f] s: correlation %.3f, RMS of d̂ - f %.3g rad/s² (f's %.3g)" % (
        name, axis, after_s, run["t_s"][-1], np.corrcoef(d, f)[0, 1], np.sqrt(np.mean((d - f) ** 2)),
        np.sqrt(np.mean(f ** 2)))


def draw(out_dir, fig_dir, name):
    """The figure of one scenario; returns its summary lines."""
    scen_dir = os.path.join(out_dir, name)
    runs = {c: load_csv(os.path.join(scen_dir, c + ".csv")) for c in ("HP-MLADRC", "LP-MLADRC")
            if os.path.exists(os.path.join(scen_dir, c + ".csv"))}
    if not runs:
        raise ValueError("no HP-MLADRC.csv or LP-MLADRC.csv in %s" % scen_dir)
    for c, r in runs.items():
        if "hp_weight_roll_frac" not in r or "lp_est_roll_rad_s2" not in r:
            raise ValueError("%s.csv in %s has no estimator columns (an older ladrc_sil?)" % (c, scen_dir))
    sc = Scenario(out_dir, name)
    hp, lp = runs.get("HP-MLADRC"), runs.get("LP-MLADRC")
    fig, axes = plt.subplots(3, 4, figsize=(15, 8.5), sharex=True, squeeze=False)
    lines = []
    for i, axis in enumerate(AXES):
        gate, freq, amp, est = axes[i]
        if hp is not None:
            t = hp["t_s"]
            s = stride(t.size)
            w = hp["hp_weight_%s_frac" % axis]
            gate.plot(t[::s], w[::s], color=COLOURS["HP-MLADRC"], lw=1.0, label="gate weight")
            for a, b in engaged_spans(t, w):
                gate.axvspan(a, b, color=COLOURS["HP-MLADRC"], alpha=0.08, lw=0)
            tones = hp["hp_tones_%s_count" % axis]
            amps = []
            for k in range(tone_count(hp)):
                dash = TONE_STYLES[k % len(TONE_STYLES)]
                # how long the tone is in the model: its cells are nan while it is not
                label = "tone %d (active %.0f %% of the run)" % (k + 1, 100.0 * np.mean(tones > k))
                freq.plot(t[::s], hp["hp_freq%d_%s_rad_s" % (k + 1, axis)][::s], color=COLOURS["HP-MLADRC"],
                          ls=dash, lw=1.0, label=label)
                amps.append(hp["hp_amp%d_%s_rad_s2" % (k + 1, axis)])
                amp.plot(t[::s], amps[-1][::s], color=COLOURS["HP-MLADRC"], ls=dash, lw=1.0, label=label)
            log_scale(amp, amps)
            lines.append(summary(name, axis, t, w))
        if lp is not None:
            lines.append(lp_summary(name, axis, lp, sc.onsets[0] if sc.onsets else lp["t_s"][0]))
        for c, r in runs.items():  # the truth of each run: f depends on how it flies
            s = stride(r["t_s"].size)
            est.plot(r["t_s"][::s], r["f_%s_rad_s2" % axis][::s], color=COLOURS[c], lw=2.4, alpha=0.3,
                     label="true f, %s run" % c)
        if hp is not None:
            s = stride(hp["t_s"].size)
            est.plot(hp["t_s"][::s], hp["hp_est_%s_rad_s2" % axis][::s], color=COLOURS["HP-MLADRC"], lw=0.9,
                     label="HP d̂")
        if lp is not None:
            s = stride(lp["t_s"].size)
            est.plot(lp["t_s"][::s], lp["lp_est_%s_rad_s2" % axis][::s], color=COLOURS["LP-MLADRC"], lw=0.9,
                     label="LP d̂")
        t_end = max(r["t_s"][-1] for r in runs.values())
        for ax in axes[i]:
            mark_onsets(ax, t_end, sc.onsets)
        gate.set_ylim(-0.05, 1.05)
        gate.set_ylabel("%s" % AXIS_SYMBOLS[axis])
        freq.set_ylabel("rad/s")
        amp.set_ylabel("rad/s²")
        est.set_ylabel("rad/s²")
    titles = ("HP gate weight (shaded: > %.1f)" % ENGAGED, "HP tone frequencies", "HP tone amplitudes",
              "true f and the estimates d̂")
    for ax, title in zip(axes[0], titles):
        ax.set_title(title, fontsize=10)
    for i, row in enumerate(axes):  # the tones' labels differ by axis, the estimates' do not
        for ax in row[1:3] if i else row[1:]:
            ax.legend(loc="best", fontsize=6)
    for ax in axes[-1]:
        ax.set_xlabel("time (s)")
    fig.suptitle("Fig. 14 (ours): the disturbance estimators over time, %s (dotted: disturbance changes)"
                 % ("paper case" if sc.paper else "scenario " + name))
    fig.tight_layout(rect=(0, 0, 1, 0.96))
    save(fig, fig_dir, "fig14_estimators_%s.png" % name)
    return lines


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("out_dir")
    p.add_argument("fig_dir")
    p.add_argument("scenarios", nargs="+")
    a = p.parse_args(argv)
    figure = {name: os.path.join(a.fig_dir, "fig14_estimators_%s.png" % name) for name in a.scenarios}
    refuse_inputs("estimators_plot.py", figure,
                  [os.path.join(a.out_dir, name, c + ".csv")
                   for name in a.scenarios for c in ("HP-MLADRC", "LP-MLADRC")])
    os.makedirs(a.fig_dir, exist_ok=True)
    failed = 0
    for name in a.scenarios:
        try:
            for line in draw(a.out_dir, a.fig_dir, name):
                print("estimators_plot.py:", line)
        except (OSError, ValueError) as e:
            print("estimators_plot.py: %s: %s" % (name, e), file=sys.stderr)
            # an earlier run's figure of this scenario would be taken for this run's
            remove_earlier("estimators_plot.py", a.fig_dir, [os.path.basename(figure[name])], [])
            failed = 1
    return failed


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
