# SPDX-License-Identifier: BSD-3-Clause
"""Ratio maps of a campaign (campaign.py ratio, docs/campaigns.md): each LADRC-family
controller's RMS error divided by the better tuned incumbent's (INDI or CASCADED, whichever
is smaller in that run), the median over the runs of each cell of (x, y)."""
import os
import re

FAMILY = ("HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC")
INCUMBENTS = ("INDI", "CASCADED")
BEST = "family best"
TARGET = 0.5                 # the family's best must reach this ratio (docs/suite.md)
RATIO_RANGE = (0.05, 20.0)   # colour scale limits: a ratio outside is drawn at the limit


class RatioError(Exception):
    """A campaign without the controllers a ratio needs."""


def run_ratios(controllers, cols, axis, n_runs):
    """Per controller of the family flown (and the family's best), the ratio of each run:
    a float, "diverged" (the controller diverged), or None (no incumbent flew it without
    diverging: nothing to divide by)."""
    family = [c for c in FAMILY if c in controllers]
    incumbents = [c for c in INCUMBENTS if c in controllers]
    if not family or not incumbents:
        raise RatioError("a ratio needs a LADRC-family controller (%s) and an incumbent (%s); the campaign "
                         "flew %s" % (", ".join(FAMILY), ", ".join(INCUMBENTS), ", ".join(controllers)))

    def rms(ctrl, r):
        if cols["%s.%s.diverged" % (ctrl, axis)][r] == "yes":
            return None
        try:                                # `untunable`: not flown, a failure as a divergence is
            return float(cols["%s.%s.rms_deg" % (ctrl, axis)][r])
        except ValueError:
            return None

    out = {c: [] for c in family + [BEST]}
    for r in range(n_runs):
        inc = [v for v in (rms(c, r) for c in incumbents) if v is not None]
        base = min(inc) if inc else None
        best = None
        for c in family:
            v = rms(c, r)
            if v is None:
                out[c].append("diverged")
                continue
            ratio = v / base if base else None
            out[c].append(ratio)
            if ratio is not None and (best is None or ratio < best):
                best = ratio
        out[BEST].append(best if best is not None else
                         ("diverged" if all(out[c][-1] == "diverged" for c in family) else None))
    return out


def plot_ratio_maps(name, cols, axis, xname, yname, figdir, labels, controllers, where, map_axes, save):
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import LogNorm
    from matplotlib.lines import Line2D

    n_runs = len(cols["run"])
    ratios = run_ratios(controllers, cols, axis, n_runs)
    ax_x, ax_y, ny, yidx = map_axes(cols, xname, yname, labels)
    panels = list(ratios)
    norm = LogNorm(vmin=RATIO_RANGE[0], vmax=RATIO_RANGE[1])
    cmap = plt.get_cmap("RdBu_r").copy()
    cmap.set_bad((1, 1, 1, 0))
    ncols = 2 if len(panels) <= 4 else 3
    nrows = (len(panels) + ncols - 1) // ncols
    width, height = 5.0 * ncols + 1.6, 3.9 * nrows + 1.9
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), squeeze=False, sharex=True, sharey=True)
    left, right, bottom, top = 1.4 / width, 1 - 1.5 / width, 1.2 / height, 1 - 1.0 / height
    fig.subplots_adjust(left=left, right=right, bottom=bottom, top=top, wspace=0.08, hspace=0.3)
    yedges = ax_y.edges if ax_y else np.array([0.0, 1.0])
    xc, yc = ax_x.centres, (ax_y.centres if ax_y else np.array([0.5]))
    mesh = None
    summary = {}
    for k, ctrl in enumerate(panels):
        ax = axes[k // ncols][k % ncols]
        ax.grid(False)
        cell = [[[] for _ in range(ax_x.cells)] for _ in range(ny)]
        div = np.zeros((ny, ax_x.cells))
        for r, v in enumerate(ratios[ctrl]):
            i, j = yidx[r], ax_x.index[r]
            if v == "diverged":
                div[i, j] += 1
            elif v is not None:
                cell[i][j].append(v)
        med = np.full((ny, ax_x.cells), np.nan)
        for i in range(ny):
            for j in range(ax_x.cells):
                if cell[i][j]:
                    med[i, j] = float(np.median(cell[i][j]))
        mesh = ax.pcolormesh(ax_x.edges, yedges, np.ma.masked_invalid(np.clip(med, *RATIO_RANGE)), cmap=cmap,
                             norm=norm, edgecolors="white", linewidth=0.4)
        for i in range(ny):
            for j in range(ax_x.cells):
                if np.isfinite(med[i, j]):
                    ax.text(xc[j], yc[i], "%.2f" % med[i, j], ha="center", va="center", fontsize=8,
                            color="white" if abs(np.log10(med[i, j])) > 0.7 else "black")
        jj, ii = np.nonzero(div.T > 0)
        if len(ii):
            ax.scatter(xc[jj], yc[ii], marker="x", s=60, c="black", linewidths=2.0, zorder=3)
        finite = [v for v in ratios[ctrl] if isinstance(v, float)]
        met = sum(1 for v in finite if v <= TARGET)
        summary[ctrl] = (len(finite), met, int(div.sum()))
        ax.set_title("%s: <= %.1f in %d of %d runs, %d diverged" % (ctrl, TARGET, met, len(finite), int(div.sum())),
                     fontsize=10)
        ax_x.apply(ax, "x")
        if ax_y:
            ax_y.apply(ax, "y")
        else:
            ax.set_yticks([])
            ax.set_ylim(0, 1)
        ax.grid(False)
        if k + ncols < len(panels):
            ax.set_xlabel("")
        else:
            ax.tick_params(labelbottom=True)
        if k % ncols:
            ax.set_ylabel("")
    for k in range(len(panels), nrows * ncols):
        axes[k // ncols][k % ncols].set_visible(False)
    cax = fig.add_axes([right + 0.25 / width, bottom, 0.22 / width, top - bottom])
    bar = fig.colorbar(mesh, cax=cax)
    bar.set_label("median RMS / better tuned incumbent's (log): < 1 the family wins")
    handles = [Line2D([], [], color="black", marker="x", linestyle="none", markersize=8,
                      label="a run of the cell diverged")]
    fig.legend(handles=handles, loc="lower center", ncol=1, frameon=False, fontsize=9)
    sel = "" if not where else " (%s)" % ", ".join("%s = %s" % kv for kv in where)
    fig.suptitle("Campaign %s%s: %s RMS error / the better of INDI and CASCADED, median per cell\n%d runs"
                 % (name, sel, axis, n_runs))
    tag = "".join("_%s%s" % (k, v) for k, v in where)
    stem = "ratio_%s_%s%s%s" % (axis, xname, "_" + yname if yname else "", tag)
    path = os.path.join(figdir, re.sub(r"[^A-Za-z0-9_.-]", "_", stem) + ".png")
    save(fig, path)
    return path, summary
