#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Figures of a flight-log replay (docs/flight-logs.md), from what ladrc_replay wrote in DIR.

Usage: replay_plot.py DIR [--from S] [--to S]

Draws in DIR:
- replay_commands.png: per axis, the log's own command and each replayed controller's over
  time (the window --from/--to, default the whole replay.csv);
- replay_spectrum.png: per axis, the gyro's spectrum (before the log's filters where the log
  has it) with the vibration lines the identification found marked, and the commands' spectra;
- response_step.png, response_freq.png, response_noise.png: the field's views of the log
  (tools/response_plot.py), when ladrc_replay wrote their CSVs.
Each controller has its colour of every figure of the project (tools/plot_style.py), the log
black; the commands' y range is the bulk of the values (0.2-99.8 percentiles), so that one
spike (a landing, a flip) does not flatten the rest of the flight.
Exit status 1 when a file is missing or empty; 2 when a figure would be written over one of the
CSVs (a link to it). The figures of the field's views are removed when this replay has none.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, remove_earlier, save_figure  # noqa: E402
from plot_style import LOG_COLOUR, clip_ylim, colour_of  # noqa: E402
import response_plot  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

AXES = ("roll", "pitch", "yaw")


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        sys.exit(f"replay_plot: {path}: no rows")
    names = rows[0]
    data = np.array([[float(x) if x not in ("", "nan", "-nan") else math.nan for x in r] for r in rows[1:]])
    return {n: data[:, i] for i, n in enumerate(names)}


def sources(columns):
    """The replayed controllers, in the file's order."""
    seen = []
    for name in columns:
        if name.endswith("_cmd_roll") and not name.startswith("LOG_"):
            seen.append(name[: -len("_cmd_roll")])
    return seen


def commands_figure(d, out, t_from, t_to):
    """Draws the commands; returns each panel's y limits."""
    t = d["t_s"]
    keep = (t >= t_from) & (t <= (t_to if t_to > 0 else t[-1]))
    ctrls = sources(d)
    fig, axs = plt.subplots(3, 1, figsize=(12, 9), sharex=True)
    for i, axis in enumerate(AXES):
        ax = axs[i]
        for c in ctrls:
            ax.plot(t[keep], d[f"{c}_cmd_{axis}"][keep], lw=0.8, label=c, color=colour_of(c))
        ax.plot(t[keep], d[f"LOG_cmd_{axis}"][keep], color=LOG_COLOUR, lw=1.6, label="log (flown)", zorder=10)
        clip_ylim(ax, [d[f"{c}_cmd_{axis}"][keep] for c in ctrls + ["LOG"]], "command")
        ax.set_ylabel(f"{axis} command\n(1: full authority)")
        ax.grid(alpha=0.3)
    axs[0].legend(ncol=4, fontsize=8, loc="upper right")
    axs[-1].set_xlabel("time (s)")
    fig.suptitle("What each controller would have commanded on the log's flight (open loop)")
    fig.tight_layout()
    save_figure(fig, out, dpi=110)
    limits = [ax.get_ylim() for ax in axs]
    plt.close(fig)
    return limits


def read_lines(ident_path):
    lines = {}
    with open(ident_path, newline="") as f:
        for row in csv.DictReader(f):
            lines[row["axis"]] = [float(x) for x in row["lines_hz"].split()] if row["lines_hz"] else []
    return lines


def spectrum_figure(s, lines, out):
    hz = s["hz"]
    ctrls = sorted({n.rsplit("_", 1)[0] for n in s if n.endswith("_roll") and not n.startswith(("gyro", "LOG"))})
    fig, axs = plt.subplots(2, 3, figsize=(15, 8), sharex=True)
    for i, axis in enumerate(AXES):
        ax = axs[0][i]
        raw = s[f"gyro_raw_{axis}"]
        if np.isfinite(raw).any():
            ax.semilogy(hz, np.sqrt(raw) * 180 / math.pi, color="tab:red", lw=0.8, label="gyro before filters")
        ax.semilogy(hz, np.sqrt(s[f"gyro_{axis}"]) * 180 / math.pi, color="tab:blue", lw=0.8, label="gyro used")
        for f in lines.get(axis, []):
            ax.axvline(f, color="gray", ls=":", lw=1)
        ax.set_title(f"{axis}: gyro (vibration lines dotted)")
        ax.set_ylabel("deg/s/sqrt(Hz)")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
        ax = axs[1][i]
        ax.semilogy(hz, np.sqrt(s[f"LOG_{axis}"]), color=LOG_COLOUR, lw=1.2, label="log")
        for c in ctrls:
            ax.semilogy(hz, np.sqrt(s[f"{c}_{axis}"]), lw=0.8, label=c, color=colour_of(c))
        ax.set_title(f"{axis}: command")
        ax.set_ylabel("1/sqrt(Hz)")
        ax.set_xlabel("frequency (Hz)")
        ax.grid(alpha=0.3, which="both")
    axs[1][0].legend(fontsize=7, ncol=2)
    fig.suptitle("Spectra of the log's gyro and of the commands")
    fig.tight_layout()
    save_figure(fig, out, dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--from", dest="t_from", type=float, default=0.0)
    ap.add_argument("--to", dest="t_to", type=float, default=0.0)
    args = ap.parse_args()
    for name in ("replay.csv", "spectrum.csv", "identification.csv"):
        if not os.path.isfile(os.path.join(args.dir, name)):
            sys.exit(f"replay_plot: {os.path.join(args.dir, name)} is missing (ladrc_replay writes it)")
    figures = {name: os.path.join(args.dir, name)
               for name in ("replay_commands.png", "replay_spectrum.png") + response_plot.FIGURES}
    read = ["replay.csv", "spectrum.csv", "identification.csv"] + list(response_plot.FILES)
    refuse_inputs("replay_plot", figures, [os.path.join(args.dir, name) for name in read])
    commands_figure(read_columns(os.path.join(args.dir, "replay.csv")), os.path.join(args.dir, "replay_commands.png"),
                    args.t_from, args.t_to)
    spectrum_figure(read_columns(os.path.join(args.dir, "spectrum.csv")),
                    read_lines(os.path.join(args.dir, "identification.csv")),
                    os.path.join(args.dir, "replay_spectrum.png"))
    drawn = [f"{args.dir}/replay_commands.png", f"{args.dir}/replay_spectrum.png"]
    if os.path.isfile(os.path.join(args.dir, "step_response.csv")):
        drawn += response_plot.draw(args.dir)
    else:  # an older replay's views would be taken for this one's
        remove_earlier("replay_plot", args.dir, response_plot.FIGURES, [])
    print("replay_plot: " + ", ".join(drawn))


if __name__ == "__main__":
    main()
