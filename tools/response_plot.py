#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The field's views of a flight log (docs/flight-logs.md, "The field's views"), from the CSVs
ladrc_replay writes in DIR: step_response.csv, freq_response.csv, noise_throttle.csv and
response_summary.csv, one source per log (LOG: the log flown; a controller's name: a simulated
flight of it).

Usage: response_plot.py DIR [--dpi N]

Draws in DIR:
- response_step.png: per axis, each source's step response (setpoint -> gyro, deconvolved) with
  its spread over the windows, rise time and overshoot in the legend;
- response_freq.png: per axis, the closed-loop gain and phase (setpoint -> gyro) and the coherence,
  drawn faint where the coherence is under 0.5;
- response_noise.png: per source, signal and axis, the spectrum against throttle (a heat map).
A figure this run does not draw (its CSV has no rows) is removed when an earlier run left one.
Exit status 1 when a file is missing or holds no rows; 2 when a figure would be written over one
of the CSVs (a link to it).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, remove_earlier, save_figure  # noqa: E402
from plot_style import LOG_SOURCE, colour_of, robust_limits  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

AXES = ("roll", "pitch", "yaw")
FILES = ("step_response.csv", "freq_response.csv", "noise_throttle.csv", "response_summary.csv")
FIGURES = ("response_step.png", "response_freq.png", "response_noise.png")  # what draw() writes in DIR
COHERENT = 0.5       # below this the gain and phase are drawn faint: mostly noise
STEP_RANGE = (-0.5, 2.5)  # the step's y limits never go beyond this (a bad window's tail)
NOISE_DB_PCT = (5.0, 99.5)  # heat-map colour limits: percentiles of the PSD in dB


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return rows


def number(text):
    try:
        return float(text)
    except ValueError:
        return math.nan


def sources_of(rows):
    """The sources in the file's order, the log first."""
    seen = []
    for r in rows:
        if r["source"] not in seen:
            seen.append(r["source"])
    return sorted(seen, key=lambda s: s != LOG_SOURCE)


def colour(source, i):
    return colour_of(source) or "C%d" % (i % 10)


def summary_label(summary, source, axis):
    row = summary.get((source, axis))
    if row is None or number(row["windows"]) == 0:
        return "%s (no window)" % source
    return "%s: rise %.0f ms, overshoot %.0f %% (%d windows)" % (
        source, number(row["rise_ms"]), number(row["overshoot_pct"]), int(number(row["windows"])))


def step_figure(rows, summary, out, dpi=100):
    srcs = sources_of(rows)
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.8), sharey=True)
    everything = []
    for j, axis in enumerate(AXES):
        ax = axs[j]
        for i, s in enumerate(srcs):
            sel = [r for r in rows if r["source"] == s and r["axis"] == axis]
            if not sel:
                continue
            t = np.array([number(r["t_s"]) for r in sel]) * 1e3
            m = np.array([number(r["step"]) for r in sel])
            sd = np.array([number(r["spread"]) for r in sel])
            c = colour(s, i)
            ax.plot(t, m, color=c, lw=2.0 if s == LOG_SOURCE else 1.4, label=summary_label(summary, s, axis))
            if np.isfinite(sd).any():
                ax.fill_between(t, m - sd, m + sd, color=c, alpha=0.12, lw=0)
            everything += [m - np.nan_to_num(sd), m + np.nan_to_num(sd)]
        ax.axhline(1.0, color="0.5", lw=0.8, ls="--")
        ax.set_title("%s: step response, setpoint -> gyro" % axis)
        ax.set_xlabel("time (ms)")
        ax.legend(fontsize=7, loc="lower right")
    lim = robust_limits(everything)
    if lim is not None:
        axs[0].set_ylim(max(lim[0], STEP_RANGE[0]), min(lim[1], STEP_RANGE[1]))
    axs[0].set_ylabel("gyro per setpoint (1: tracks)")
    fig.suptitle("Step response deconvolved from the flight (mean over 2 s windows, band: one standard deviation)")
    fig.tight_layout()
    save_figure(fig, out, dpi=dpi)
    plt.close(fig)


def freq_figure(rows, out, dpi=100):
    srcs = sources_of(rows)
    fig, axs = plt.subplots(3, 3, figsize=(15, 9), sharex=True, gridspec_kw={"height_ratios": [2, 2, 1]})
    for j, axis in enumerate(AXES):
        for i, s in enumerate(srcs):
            sel = [r for r in rows if r["source"] == s and r["axis"] == axis]
            if not sel:
                continue
            hz = np.array([number(r["hz"]) for r in sel])
            gain_db = 20.0 * np.log10(np.maximum(np.array([number(r["gain"]) for r in sel]), 1e-6))
            phase = np.degrees(np.unwrap(np.radians(np.array([number(r["phase_deg"]) for r in sel]))))
            coh = np.array([number(r["coherence"]) for r in sel])
            c = colour(s, i)
            good = coh >= COHERENT
            for ax, y in ((axs[0][j], gain_db), (axs[1][j], phase)):
                ax.semilogx(hz, y, color=c, lw=0.6, alpha=0.25)
                ax.semilogx(hz, np.where(good, y, np.nan), color=c, lw=1.5, label=s)
            axs[2][j].semilogx(hz, coh, color=c, lw=1.0, label=s)
        axs[0][j].axhline(-3.0, color="0.5", lw=0.8, ls=":")
        axs[0][j].set_title("%s: closed loop, setpoint -> gyro" % axis)
        axs[0][j].set_ylim(-30, 12)
        axs[1][j].set_ylim(-360, 45)
        axs[2][j].set_ylim(0, 1.02)
        axs[2][j].axhline(COHERENT, color="0.5", lw=0.8, ls=":")
        axs[2][j].set_xlabel("frequency (Hz)")
    axs[0][0].set_ylabel("gain (dB)")
    axs[1][0].set_ylabel("phase (deg)")
    axs[2][0].set_ylabel("coherence")
    axs[0][0].legend(fontsize=8)
    for ax in axs.ravel():
        ax.grid(alpha=0.3, which="both")
        ax.set_xlim(0.5, None)
    fig.suptitle("Frequency response (Welch H1; faint where the coherence is under %.1f)" % COHERENT)
    fig.tight_layout()
    save_figure(fig, out, dpi=dpi)
    plt.close(fig)


def noise_figure(rows, out, dpi=90):
    """One row per (source, signal), one column per axis: PSD in dB over throttle and frequency."""
    panels = []
    for s in sources_of(rows):
        for sig in ("gyro_raw_deg_s", "gyro_deg_s", "command"):
            if any(r["source"] == s and r["signal"] == sig for r in rows):
                panels.append((s, sig))
    if not panels:
        return False
    fig, axs = plt.subplots(len(panels), 3, figsize=(15, 2.8 * len(panels) + 0.8), squeeze=False)
    limits = {}
    for sig in {p[1] for p in panels}:
        db = [10.0 * np.log10(max(number(r["psd"]), 1e-30)) for r in rows if r["signal"] == sig and number(r["hz"]) > 0]
        limits[sig] = tuple(np.percentile(db, NOISE_DB_PCT))
    for p, (s, sig) in enumerate(panels):
        for j, axis in enumerate(AXES):
            ax = axs[p][j]
            sel = [r for r in rows if r["source"] == s and r["signal"] == sig and r["axis"] == axis]
            hz = sorted({number(r["hz"]) for r in sel})
            bins = sorted({number(r["throttle_from"]) for r in sel})
            grid = np.full((len(hz), 10), np.nan)
            index = {h: k for k, h in enumerate(hz)}
            for r in sel:
                b = int(round(number(r["throttle_from"]) * 10))
                grid[index[number(r["hz"])], b] = 10.0 * np.log10(max(number(r["psd"]), 1e-30))
            df = hz[1] - hz[0] if len(hz) > 1 else 1.0
            mesh = ax.pcolormesh(np.linspace(0, 100, 11), np.append(np.array(hz) - df / 2, hz[-1] + df / 2),
                                 np.ma.masked_invalid(grid), cmap="inferno", vmin=limits[sig][0], vmax=limits[sig][1],
                                 shading="flat")
            ax.set_ylim(0, hz[-1])
            ax.set_title("%s %s: %s" % (s, axis, sig.replace("_deg_s", "")), color=colour(s, 0), fontsize=9)
            if p == len(panels) - 1:
                ax.set_xlabel("throttle (%%), %d bins with data" % len(bins))
            if j == 0:
                ax.set_ylabel("frequency (Hz)")
            if j == 2:
                unit = "dB re 1/Hz" if sig == "command" else "dB re (deg/s)^2/Hz"
                fig.colorbar(mesh, ax=ax, label=unit)
    fig.suptitle("Noise against throttle (Welch, 0.25 s segments, binned by the segment's mean throttle)")
    fig.tight_layout()
    save_figure(fig, out, dpi=dpi)
    plt.close(fig)
    return True


def draw(dirname, dpi=None):
    """Draws the three figures of DIR (dpi: None for each figure's own); returns their paths. A figure
    it does not draw (no rows) is removed when an earlier run left one; a figure that would be one of
    the CSVs it reads (a link) is refused (exit 2)."""
    res = {} if dpi is None else {"dpi": dpi}
    for name in FILES:
        if not os.path.isfile(os.path.join(dirname, name)):
            sys.exit("response_plot: %s is missing (ladrc_replay writes it)" % os.path.join(dirname, name))
    refuse_inputs("response_plot", {name: os.path.join(dirname, name) for name in FIGURES},
                  [os.path.join(dirname, name) for name in FILES])
    summary = {(r["source"], r["axis"]): r for r in read_rows(os.path.join(dirname, "response_summary.csv"))}
    out = []
    step = read_rows(os.path.join(dirname, "step_response.csv"))
    if step:
        out.append(os.path.join(dirname, "response_step.png"))
        step_figure(step, summary, out[-1], **res)
    freq = read_rows(os.path.join(dirname, "freq_response.csv"))
    if freq:
        out.append(os.path.join(dirname, "response_freq.png"))
        freq_figure(freq, out[-1], **res)
    noise = read_rows(os.path.join(dirname, "noise_throttle.csv"))
    if noise and noise_figure(noise, os.path.join(dirname, "response_noise.png"), **res):
        out.append(os.path.join(dirname, "response_noise.png"))
    # a figure not drawn from these CSVs: an earlier one would be taken for theirs
    remove_earlier("response_plot", dirname, FIGURES, out)
    if not out:
        sys.exit("response_plot: %s: no rows to draw (no window reached 20 deg/s and the log has no throttle)"
                 % dirname)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--dpi", type=int, default=None, help="resolution of every figure (default: 100, 90 the noise)")
    args = ap.parse_args()
    print("response_plot: " + ", ".join(draw(args.dir, args.dpi)))


if __name__ == "__main__":
    main()
