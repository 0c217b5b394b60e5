#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Bode (|L|, phase, margins marked) and Nyquist plots of a ladrc_margins --csv file.

usage: /usr/bin/python3 tools/margins_plot.py CSV [CSV...] -o OUT.png
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_figure_formats, refuse_inputs, save_figure  # noqa: E402
from plot_style import colour_of  # noqa: E402


def read(path):
    with open(path) as f:
        head = f.readline().lstrip("# ").split()
        meta = {k: float(v) for k, v in (item.split("=") for item in head)}
        rows = list(csv.DictReader(f))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return meta, cols


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv", nargs="+")
    ap.add_argument("-o", "--out", required=True)
    args = ap.parse_args()
    refuse_inputs("margins_plot.py", {"--out": args.out}, args.csv)
    refuse_figure_formats("margins_plot.py", {"--out": args.out})
    fig, (ax_mag, ax_ph, ax_ny) = plt.subplots(1, 3, figsize=(15, 4.5))
    for path in args.csv:
        meta, c = read(path)
        label = path.rsplit("/", 1)[-1].removesuffix(".csv")
        label += f": PM {meta['pm_deg']:.0f} deg, GM {meta['gm_db']:.1f} dB"
        w = c["w_rad_s"]
        line, = ax_mag.semilogx(w, c["L_mag_db"], label=label, color=colour_of(label))
        phase = np.degrees(np.unwrap(np.radians(c["L_phase_deg"])))
        phase -= 360.0 * np.round((phase[-1] + 180.0) / 360.0)  # -180 where it matters
        ax_ph.semilogx(w, phase, color=line.get_color())
        if np.isfinite(meta["wc_rad_s"]):
            ax_mag.axvline(meta["wc_rad_s"], color=line.get_color(), ls=":", lw=0.8)
            ax_ph.annotate(f"PM {meta['pm_deg']:.0f}", (meta["wc_rad_s"], -180 + meta["pm_deg"]),
                           color=line.get_color(), fontsize=8)
        if np.isfinite(meta["gm_rad_s"]):
            ax_mag.annotate(f"GM {meta['gm_db']:.1f} dB", (meta["gm_rad_s"], -meta["gm_db"]),
                            color=line.get_color(), fontsize=8)
        ax_ny.plot(c["L_re"], c["L_im"], color=line.get_color())
        ax_ny.plot(c["L_re"], -c["L_im"], color=line.get_color(), ls="--", lw=0.6)
    ax_mag.axhline(0.0, color="k", lw=0.6)
    ax_mag.set(xlabel="w (rad/s)", ylabel="|L| (dB)", title="Loop gain", ylim=(-60, 60))
    ax_ph.axhline(-180.0, color="k", lw=0.6)
    ax_ph.set(xlabel="w (rad/s)", ylabel="arg L (deg)", title="Loop phase")
    ax_ny.plot([-1], [0], "k+", ms=12)
    ax_ny.add_patch(plt.Circle((0, 0), 1.0, fill=False, ls=":", lw=0.6))
    ax_ny.set(xlim=(-3, 1.5), ylim=(-2.5, 2.5), xlabel="Re L", ylabel="Im L", title="Nyquist (near -1)")
    ax_ny.set_aspect("equal")
    ax_mag.legend(fontsize=7, loc="lower left")
    for ax in (ax_mag, ax_ph, ax_ny):
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    save_figure(fig, args.out, dpi=110)


if __name__ == "__main__":
    main()
