#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Merges and draws the runs of a campaign flown by `ladrc_sil --campaign` (docs/campaigns.md).

Usage: campaign.py merge OUT
       campaign.py tunemap OUT [--by NAME]... [--name TEXT]
       campaign.py plot OUT [--x NAME] [--y NAME] [--axis roll|pitch|yaw] [--name TEXT]
                            [--label NAME=TEXT]...
       campaign.py ratio OUT [the same options] [--where NAME=VALUE]...

merge reads OUT/plan.csv and every OUT/runs/<run>/metrics.csv and writes OUT/campaign.csv:
one row per run, in run order: `run`, the varied values as in plan.csv, then for each
controller (in metrics.csv order) and axis (roll, pitch, yaw) the columns
<CTRL>.<axis>.rms_deg (Table 4 error_rms_deg), .band_deg (Table 5 steady_band_deg),
.max_deg (Table 5 max_error_deg), .settling_s (Table 5 settling_s, or not_settled) and
.diverged (yes/no). A statistic of a diverged run reads `diverged`, one of a controller that
could not be tuned `untunable` (its .diverged too). When any run's metrics.csv has a tuning
outcome (`tune,status,-,TOKEN`: tuned, defaults, scenario or untunable), each controller's block
ends with <CTRL>.tune, the token, `-` in runs without one. Values are copied as metrics.csv
wrote them, so the table is the same bytes however the runs were sharded.
Runs of the plan without metrics.csv: an error naming them, exit 1, no table written.

plot reads OUT/campaign.csv and draws into OUT/figures/:
  map_<axis>_<x>_<y>.png   one panel per controller: the median RMS error of the axis over
                           the runs of each cell of (x, y), log colour scale; cells where any
                           run diverged are marked, the boundary where half of a cell's runs
                           diverged is drawn as a contour
  rms_<axis>.png           the RMS error of every run per controller (box plots, log scale);
                           diverged runs have no RMS: they are counted in the labels
ratio reads OUT/campaign.csv and draws into OUT/figures/:
  ratio_<axis>_<x>_<y>[_<NAME><VALUE>...].png
                           one panel per LADRC-family controller flown and one for the family's
                           best: the median over the runs of each cell of the run's RMS error
                           divided by the better tuned incumbent's (the smaller of INDI's and
                           CASCADED's that did not diverge), log colour scale centred on 1,
                           each cell's median written in it; cells where the controller
                           diverged in a run are crossed. It prints, per panel, how many runs
                           reach 0.5 (the suite's target). --where keeps the runs whose
                           varied value NAME reads VALUE (repeatable: all must hold).
tunemap reads OUT/campaign.csv and draws OUT/figures/tunemap.png: one row per run (or per
                           group of runs with --by, or by default when there are more than
                           150 runs: per grid cell, the runs grouped by the varied names with
                           few values), one column per controller, each cell coloured by
                           the outcome (tuned, defaults, scenario, untunable, diverged; `no
                           status` when metrics.csv had none) and annotated with the roll
                           RMS error (deg); a group's cell takes its most frequent outcome,
                           the median RMS and how many of its runs had that outcome. It
                           prints the count of each outcome per controller over the runs.
--x and --y default to the first two varied names; an axis is labelled with the varied name
and the unit its suffix names (_s, _deg, _rad_s, ...), or with --label NAME=TEXT. A varied name with few values (a [grid]
key) gives one cell per value; one with many (a [draw] key) is cut into bins. An axis is
logarithmic when its values are positive, span more than a decade and lie closer to log- than
to linearly-uniform (a log_uniform draw, a geometric grid).

Exit status: 0 done, 1 error (missing OUT, plan.csv, runs, campaign.csv, unknown --x/--y),
2 an output that is one of the inputs (campaign.csv a link to plan.csv or to a run's metrics.csv,
a figure a link to campaign.csv); nothing written on error. Every file is written whole (a
temporary renamed into place). merge removes the figures of OUT/figures/ named as above: they
were drawn from the table it replaces. merge needs the Python standard library only; plot needs
matplotlib and numpy.
"""
import argparse
import csv
import fnmatch
import glob
import io
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from output_files import refuse_inputs, remove_earlier, save_figure, write_whole  # noqa: E402
from sim_output import AXES  # noqa: E402

# campaign.csv's statistics: (column suffix, metrics.csv table, quantity)
STATS = [("rms_deg", "4", "error_rms_deg"),
         ("band_deg", "5", "steady_band_deg"),
         ("max_deg", "5", "max_error_deg"),
         ("settling_s", "5", "settling_s")]
RUN_DIR_DIGITS = 5           # runs/<r zero-padded to at least 5 digits>
MISSING_NAMED = 20           # how many missing runs an error names


class CampaignError(Exception):
    """A problem with OUT's contents: reported on stderr, exit status 1."""


def run_dir_name(r):
    return "%0*d" % (RUN_DIR_DIGITS, r)


def read_plan(out):
    """(header, rows) of OUT/plan.csv; rows are lists of text, run numbers 1..R in order."""
    if not os.path.isdir(out):
        raise CampaignError("no campaign output directory %s" % out)
    path = os.path.join(out, "plan.csv")
    if not os.path.isfile(path):
        raise CampaignError("%s: no plan.csv (not the output directory of `ladrc_sil --campaign`)" % out)
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or not rows[0] or rows[0][0] != "run":
        raise CampaignError("%s: the header does not start with 'run'" % path)
    header, body = rows[0], rows[1:]
    for i, row in enumerate(body, start=1):
        if len(row) != len(header):
            raise CampaignError("%s:%d: %d fields, the header has %d" % (path, i + 1, len(row), len(header)))
        if row[0] != str(i):
            raise CampaignError("%s:%d: run '%s', expected %d (runs 1..R in order)" % (path, i + 1, row[0], i))
    if not body:
        raise CampaignError("%s: no runs" % path)
    return header, body


def read_run_metrics(path, scenario):
    """(controllers in file order, {(controller, table, quantity, axis): text}) of a run's
    metrics.csv, values as written."""
    controllers, values = [], {}
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if header != ["scenario", "controller", "table", "quantity", "axis", "value"]:
            raise CampaignError("%s: not a metrics.csv (header %s)" % (path, header))
        for n, row in enumerate(reader, start=2):
            if len(row) != 6:
                raise CampaignError("%s:%d: %d fields, expected 6" % (path, n, len(row)))
            if row[0] != scenario:
                raise CampaignError("%s:%d: scenario '%s', expected the run's directory name '%s'"
                                    % (path, n, row[0], scenario))
            if row[2] in ("4", "5", "-") and row[1] not in controllers:
                controllers.append(row[1])
            values[(row[1], row[2], row[3], row[4])] = row[5]
    return controllers, values


def run_columns(path, controllers, values, with_tune):
    """A run's statistics, in campaign.csv's column order (with_tune: each controller's block
    ends with its tuning outcome, `-` when the run has none)."""
    cells = []
    for ctrl in controllers:
        status = values.get((ctrl, "tune", "status", "-"), "-")
        flag = values.get((ctrl, "-", "diverged", "-"))
        if status == "untunable":           # not flown: no diverged flag to read
            flag = "untunable"
        elif flag not in ("0", "1"):
            raise CampaignError("%s: no diverged flag (0 or 1) for %s" % (path, ctrl))
        for axis in AXES:
            for _, table, quantity in STATS:
                v = values.get((ctrl, table, quantity, axis))
                if v is None:
                    raise CampaignError("%s: no %s of %s on %s" % (path, quantity, ctrl, axis))
                cells.append(v)
            cells.append({"1": "yes", "0": "no"}.get(flag, flag))
        if with_tune:
            cells.append(status)
    return cells


def has_tune_status(values):
    return any(k[1:] == ("tune", "status", "-") for k in values)


def merge_table(out):
    """campaign.csv's text for OUT (raises CampaignError)."""
    header, plan = read_plan(out)
    runs_dir = os.path.join(out, "runs")
    present = set(os.listdir(runs_dir)) if os.path.isdir(runs_dir) else set()
    missing = [int(row[0]) for row in plan
               if not os.path.isfile(os.path.join(runs_dir, run_dir_name(int(row[0])), "metrics.csv"))]
    if missing:
        named = ", ".join(str(r) for r in missing[:MISSING_NAMED])
        more = " and %d more" % (len(missing) - MISSING_NAMED) if len(missing) > MISSING_NAMED else ""
        raise CampaignError("%s: %d of %d runs have no metrics.csv in %s: run %s%s"
                            % (out, len(missing), len(plan), runs_dir, named, more))
    planned = {run_dir_name(int(row[0])) for row in plan}
    extra = sorted(d for d in present if re.fullmatch(r"[0-9]+", d) and d not in planned)
    if extra:
        raise CampaignError("%s: runs not in plan.csv: %s%s" % (runs_dir, ", ".join(extra[:MISSING_NAMED]),
                            " and %d more" % (len(extra) - MISSING_NAMED) if len(extra) > MISSING_NAMED else ""))

    first = None
    read = []
    for row in plan:
        name = run_dir_name(int(row[0]))
        path = os.path.join(runs_dir, name, "metrics.csv")
        controllers, values = read_run_metrics(path, name)
        if not controllers:
            raise CampaignError("%s: no attitude controller in it" % path)
        if first is None:
            first = controllers
        elif controllers != first:
            raise CampaignError("%s: controllers %s, run 1 flew %s" % (path, " ".join(controllers), " ".join(first)))
        read.append((row, path, values))
    with_tune = any(has_tune_status(values) for _, _, values in read)
    lines = [row + run_columns(path, first, values, with_tune) for row, path, values in read]

    columns = list(header)
    for ctrl in first:
        for axis in AXES:
            columns += ["%s.%s.%s" % (ctrl, axis, suffix) for suffix, _, _ in STATS]
            columns.append("%s.%s.diverged" % (ctrl, axis))
        if with_tune:
            columns.append("%s.tune" % ctrl)
    text = io.StringIO()
    for line in [columns] + lines:
        for cell in line:
            if any(c in cell for c in ',"\r\n'):
                raise CampaignError("%s: value %r cannot be written to a CSV cell as it is" % (out, cell))
        text.write(",".join(line) + "\n")
    return text.getvalue()


# The figures plot, ratio and tunemap draw into OUT/figures/ (the names this tool owns there).
FIGURE_PATTERNS = ("map_*.png", "rms_*.png", "ratio_*.png", "tunemap.png")


def cmd_merge(args):
    path = os.path.join(args.out, "campaign.csv")
    refuse_inputs("campaign.py", {"campaign.csv": path},
                  [os.path.join(args.out, "plan.csv")] + glob.glob(os.path.join(args.out, "runs", "*", "metrics.csv")))
    text = merge_table(args.out)
    write_whole(path, text)
    # every figure drawn from the table this one replaces is out of date (draw them again)
    remove_earlier("campaign.py", os.path.join(args.out, "figures"), FIGURE_PATTERNS, [])
    n = text.count("\n") - 1
    print("campaign.py: %s: %d runs merged" % (path, n))
    return 0


# ---------------------------------------------------------------------------------------------
# plot

UNITS = [("_rad_s2", "rad/s²"), ("_rad_s", "rad/s"), ("_deg_s", "deg/s"), ("_m_s2", "m/s²"),
         ("_m_s", "m/s"), ("_kg_m2", "kg·m²"), ("_Nm_s2", "N·m·s²"), ("_Nm_s", "N·m·s"),
         ("_N_s2", "N·s²"), ("_Nm", "N·m"), ("_deg", "deg"), ("_rad", "rad"), ("_hz", "Hz"),
         ("_Hz", "Hz"), ("_kg", "kg"), ("_ms", "ms"), ("_s", "s"), ("_m", "m"), ("_N", "N"), ("_V", "V")]
MAX_CELLS = 12        # a varied name with more distinct values than this is cut into bins
BINS = 10             # bins of such a name
DIVERGED_BOUNDARY = 0.5


def label_of(name):
    """An axis label: the varied name and its unit, from the name's suffix."""
    for suffix, unit in UNITS:
        if name.endswith(suffix):
            return "%s (%s)" % (name, unit)
    return name


def read_campaign(out):
    path = os.path.join(out, "campaign.csv")
    if not os.path.isdir(out):
        raise CampaignError("no campaign output directory %s" % out)
    if not os.path.isfile(path):
        raise CampaignError("%s: no campaign.csv (run `campaign.py merge %s` first)" % (out, out))
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if len(rows) < 2:
        raise CampaignError("%s: no runs" % path)
    header = rows[0]
    varied = []
    for name in header[1:]:
        if re.search(r"\.(roll|pitch|yaw)\.(rms_deg|band_deg|max_deg|settling_s|diverged)$", name):
            break
        varied.append(name)
    controllers = []
    for name in header[1 + len(varied):]:
        ctrl = name.rsplit(".", 2)[0]
        if ctrl not in controllers:
            controllers.append(ctrl)
    cols = {name: [row[i] for row in rows[1:]] for i, name in enumerate(header)}
    return varied, controllers, cols


def as_numbers(texts):
    """The values as floats, or None if any is not a number."""
    try:
        vals = [float(t) for t in texts]
    except ValueError:
        return None
    return vals if all(math.isfinite(v) for v in vals) else None


def wants_log(values):
    """Positive, more than a decade, and the median nearer the geometric than the arithmetic
    middle of the range (so a log-uniform draw or a geometric grid, not a uniform draw)."""
    lo, hi = min(values), max(values)
    if lo <= 0 or hi / lo <= 10:
        return False
    med = sorted(values)[len(values) // 2]
    return abs(math.log(med) - 0.5 * math.log(lo * hi)) < abs(math.log(med) - math.log(0.5 * (lo + hi)))


class Axis:
    """How the runs' values of one varied name fall into cells: .index[run] (the cell of each
    run), .edges (cell boundaries, in the plot's coordinates), .centres, .ticks and .ticklabels
    (None: matplotlib's), .log, .label."""

    def __init__(self, name, texts):
        import numpy as np
        self.name, self.label = name, label_of(name)
        nums = as_numbers(texts)
        self.log = False
        self.ticks = self.ticklabels = None
        if nums is None:                                    # words: one cell each, in file order
            distinct = list(dict.fromkeys(texts))
            self.index = [distinct.index(t) for t in texts]
            self.edges = np.arange(len(distinct) + 1) - 0.5
            self.centres = np.arange(len(distinct), dtype=float)
            self.ticks, self.ticklabels = list(range(len(distinct))), distinct
            return
        self.log = wants_log(nums)
        fwd = np.log10 if self.log else (lambda x: np.asarray(x, dtype=float))
        inv = (lambda x: 10.0 ** np.asarray(x)) if self.log else np.asarray
        values = sorted(set(nums))
        if len(values) <= MAX_CELLS:                        # a grid: one cell per value
            t = fwd(values)
            if len(values) == 1:
                e = np.array([t[0] - 0.5, t[0] + 0.5])
            else:
                mids = 0.5 * (t[1:] + t[:-1])
                e = np.concatenate([[2 * t[0] - mids[0]], mids, [2 * t[-1] - mids[-1]]])
            self.index = [values.index(v) for v in nums]
            self.centres = inv(t)
            self.ticks, self.ticklabels = list(values), ["%g" % v for v in values]
        else:                                               # draws: bins over the range
            e = np.linspace(fwd(values[0]), fwd(values[-1]), BINS + 1)
            self.index = [min(int(np.searchsorted(e, fwd(v), side="right")) - 1, BINS - 1) for v in nums]
            self.centres = inv(0.5 * (e[1:] + e[:-1]))
        self.edges = inv(e)

    @property
    def cells(self):
        return len(self.edges) - 1

    def apply(self, ax, which):
        """Scale, limits, ticks and label of the plot axis `which` ("x" or "y")."""
        getattr(ax, "set_%sscale" % which)("log" if self.log else "linear")
        getattr(ax, "set_%slim" % which)(self.edges[0], self.edges[-1])
        axis = ax.xaxis if which == "x" else ax.yaxis
        if self.ticks is not None:
            axis.set_ticks(self.ticks)
            axis.set_ticklabels(self.ticklabels, rotation=45 if which == "x" and len(self.ticks) > 6 else 0)
            axis.set_ticks([], minor=True)
        elif self.log:
            log_ticks(axis)
        axis.set_label_text(self.label)


def map_axes(cols, xname, yname, labels):
    """The cells of a map over (x, y): the Axis of each varied name (yname None: no y axis), with
    its --label applied, the number of y cells and each run's y cell."""
    ax_x = Axis(xname, cols[xname])
    ax_y = Axis(yname, cols[yname]) if yname else None
    for a in (ax_x, ax_y):
        if a is not None and a.name in labels:
            a.label = labels[a.name]
    ny = ax_y.cells if ax_y else 1
    yidx = ax_y.index if ax_y else [0] * len(cols["run"])
    return ax_x, ax_y, ny, yidx


def plot_maps(out, name, varied, controllers, cols, axis, xname, yname, figdir, labels):
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import ListedColormap, LogNorm
    from matplotlib.lines import Line2D

    n_runs = len(cols["run"])
    ax_x, ax_y, ny, yidx = map_axes(cols, xname, yname, labels)

    grids = {}
    for ctrl in controllers:
        rms = cols["%s.%s.rms_deg" % (ctrl, axis)]
        div = cols["%s.%s.diverged" % (ctrl, axis)]
        cell_rms = [[[] for _ in range(ax_x.cells)] for _ in range(ny)]
        n = np.zeros((ny, ax_x.cells))
        nd = np.zeros((ny, ax_x.cells))
        for r in range(n_runs):
            i, j = yidx[r], ax_x.index[r]
            if div[r] != "yes" and as_numbers([rms[r]]) is None:
                continue                    # untunable: not flown, neither RMS nor divergence
            n[i, j] += 1
            if div[r] == "yes":
                nd[i, j] += 1
            else:
                cell_rms[i][j].append(float(rms[r]))
        med = np.full((ny, ax_x.cells), np.nan)
        for i in range(ny):
            for j in range(ax_x.cells):
                if cell_rms[i][j]:
                    med[i, j] = np.median(cell_rms[i][j])
        frac = np.where(n > 0, nd / np.maximum(n, 1), np.nan)
        grids[ctrl] = (med, n, nd, frac)

    finite = np.concatenate([g[0][np.isfinite(g[0]) & (g[0] > 0)] for g in grids.values()])
    lo, hi = (float(finite.min()), float(finite.max())) if finite.size else (0.1, 1.0)
    if hi <= lo * 1.01:
        lo, hi = lo / 1.5, hi * 1.5
    norm = LogNorm(vmin=lo, vmax=hi)
    cmap = plt.get_cmap("viridis").copy()
    cmap.set_bad((1, 1, 1, 0))          # cells without a median: drawn below, or left blank
    all_div_colour = "#bdbdbd"

    nc = len(controllers)
    ncols = 1 if nc == 1 else 2 if nc <= 4 else 3
    nrows = (nc + ncols - 1) // ncols
    width, height = 5.0 * ncols + 1.6, 3.9 * nrows + 1.7
    fig, axes = plt.subplots(nrows, ncols, figsize=(width, height), squeeze=False, sharex=True, sharey=True)
    left, right, bottom, top = 0.9 / width, 1 - 1.5 / width, 1.1 / height, 1 - 0.95 / height
    fig.subplots_adjust(left=left, right=right, bottom=bottom, top=top, wspace=0.08, hspace=0.28)
    yedges = ax_y.edges if ax_y else np.array([0.0, 1.0])
    xc = ax_x.centres
    yc = ax_y.centres if ax_y else np.array([0.5])
    mesh = None
    any_empty = False
    for k, ctrl in enumerate(controllers):
        ax = axes[k // ncols][k % ncols]
        med, n, nd, frac = grids[ctrl]
        ax.grid(False)
        all_div = np.where((n > 0) & (nd == n), 1.0, np.nan)
        any_empty = any_empty or bool((n == 0).any())
        ax.pcolormesh(ax_x.edges, yedges, np.ma.masked_invalid(all_div), cmap=ListedColormap([all_div_colour]),
                      edgecolors="white", linewidth=0.4)
        mesh = ax.pcolormesh(ax_x.edges, yedges, np.ma.masked_invalid(med), cmap=cmap, norm=norm,
                             edgecolors="white", linewidth=0.4)
        jj, ii = np.nonzero(nd.T > 0)
        if len(ii):
            ax.scatter(xc[jj], yc[ii], marker="x", s=30, c="red", linewidths=1.5, zorder=3)
        if ax_y and len(xc) >= 2 and len(yc) >= 2 and np.nanmin(frac) < DIVERGED_BOUNDARY < np.nanmax(frac):
            # The outer cells' values repeated at the panel's edges: the line runs to the border.
            fx = np.concatenate([[ax_x.edges[0]], xc, [ax_x.edges[-1]]])
            fy = np.concatenate([[yedges[0]], yc, [yedges[-1]]])
            ax.contour(fx, fy, np.ma.masked_invalid(np.pad(frac, 1, mode="edge")), levels=[DIVERGED_BOUNDARY],
                       colors="red", linewidths=2.2, zorder=4)
        ax.set_title("%s: %d of %d runs diverged" % (ctrl, int(nd.sum()), n_runs), fontsize=10)
        ax_x.apply(ax, "x")
        if ax_y:
            ax_y.apply(ax, "y")
        else:
            ax.set_yticks([])
        if not ax_y:
            ax.set_ylim(0, 1)
        ax.grid(False)
        if k + ncols < nc:          # the panel below labels the x axis
            ax.set_xlabel("")
        else:
            ax.tick_params(labelbottom=True)
        if k % ncols:
            ax.set_ylabel("")
    for k in range(nc, nrows * ncols):
        axes[k // ncols][k % ncols].set_visible(False)
    cax = fig.add_axes([right + 0.25 / width, bottom, 0.22 / width, top - bottom])
    cax.grid(False)
    bar = fig.colorbar(mesh, cax=cax)
    bar.set_label("median %s RMS tracking error (deg), log scale" % axis)
    log_ticks(bar.ax.yaxis)
    handles = [Line2D([], [], color="red", marker="x", linestyle="none", label="a run of the cell diverged"),
               Line2D([], [], color="red", linewidth=2.2, label="boundary: half of the runs diverged"),
               Line2D([], [], color=all_div_colour, marker="s", markersize=11, linestyle="none",
                      label="every run diverged (no RMS)")]
    if any_empty:
        handles.append(Line2D([], [], color="black", marker="s", markerfacecolor="white", markersize=11,
                              linestyle="none", markeredgewidth=0.5, label="no run in the cell"))
    fig.legend(handles=handles, loc="lower center", ncol=len(handles), frameon=False, fontsize=9)
    counts = grids[controllers[0]][1]
    counts = counts[counts > 0]
    per_cell = ("%d runs per cell" % counts.min() if counts.min() == counts.max()
                else "%d to %d runs per cell" % (counts.min(), counts.max()))
    fig.suptitle("Campaign %s: median %s RMS tracking error (deg) over %s%s\n%d runs, %s"
                 % (name, axis, xname, " and " + yname if yname else "", n_runs, per_cell))
    path = os.path.join(figdir, "map_%s_%s%s.png" % (axis, safe(xname), "_" + safe(yname) if yname else ""))
    save(fig, path)
    return path


def log_ticks(axis):
    """Plain-number ticks at 1, 2, 5 per decade on a log axis (3 decades and more: 1 only)."""
    from matplotlib.ticker import LogLocator, NullFormatter, StrMethodFormatter
    lo, hi = sorted(axis.get_view_interval())
    wide = lo > 0 and hi / lo > 1000
    axis.set_major_locator(LogLocator(subs=(1.0,) if wide else (1.0, 2.0, 5.0)))
    axis.set_major_formatter(StrMethodFormatter("{x:g}"))
    axis.set_minor_formatter(NullFormatter())


def save(fig, path):
    """Writes the figure whole (output_files.save_figure): a PNG is whole or absent."""
    import matplotlib.pyplot as plt
    try:
        save_figure(fig, path, dpi=110)
    finally:
        plt.close(fig)


def box_data(controllers, cols, axis):
    """(RMS values of the runs that did not diverge, label) per controller; the label counts
    the runs drawn and the diverged ones left out."""
    n_runs = len(cols["run"])
    data, labels = [], []
    for ctrl in controllers:
        rms = cols["%s.%s.rms_deg" % (ctrl, axis)]
        div = cols["%s.%s.diverged" % (ctrl, axis)]
        vals = [float(v) for v, d in zip(rms, div) if d != "yes" and as_numbers([v]) is not None]
        n_div = sum(1 for d in div if d == "yes")
        n_unt = n_runs - len(vals) - n_div
        data.append(vals)
        labels.append("%s\n%d runs\n%s%s" % (ctrl, len(vals), "%d diverged, left out" % n_div if n_div
                                               else "none diverged", "\n%d untunable" % n_unt if n_unt else ""))
    return data, labels


def plot_boxes(out, name, controllers, cols, axis, figdir):
    import matplotlib.pyplot as plt
    n_runs = len(cols["run"])
    data, labels = box_data(controllers, cols, axis)
    zeros = [sum(1 for v in d if v <= 0) for d in data]
    labels = [lab + ("\n%d at 0, off the log scale" % z if z else "") for lab, z in zip(labels, zeros)]
    fig, ax = plt.subplots(figsize=(max(6.5, 1.7 * len(controllers) + 2.5), 5.5))
    positions = list(range(1, len(controllers) + 1))
    drawn = [(p, [v for v in d if v > 0]) for p, d in zip(positions, data)]
    drawn = [(p, d) for p, d in drawn if d]
    if drawn:
        ax.boxplot([d for _, d in drawn], positions=[p for p, _ in drawn], widths=0.6, whis=(5, 95),
                   medianprops={"color": "#d62728", "linewidth": 1.8},
                   flierprops={"marker": ".", "markersize": 3, "alpha": 0.5})
    for p, d in zip(positions, data):
        if not d:
            ax.text(p, 0.5, "every run\ndiverged", transform=ax.get_xaxis_transform(), ha="center",
                    va="center", color="red")
    ax.set_xticks(positions)
    ax.set_xticklabels(labels, fontsize=9)
    ax.set_xlim(0.4, len(controllers) + 0.6)
    ax.set_yscale("log")
    log_ticks(ax.yaxis)
    ax.set_ylabel("%s RMS tracking error (deg), log scale" % axis)
    ax.set_title("Campaign %s: %s RMS tracking error per run (deg), %d runs\n"
                 "box: quartiles, line: median, whiskers: 5th and 95th percentiles, dots: beyond"
                 % (name, axis, n_runs), fontsize=11)
    ax.grid(True, which="major", axis="y", alpha=0.3)
    ax.grid(False, axis="x")
    fig.tight_layout()
    path = os.path.join(figdir, "rms_%s.png" % axis)
    save(fig, path)
    return path


def safe(name):
    return re.sub(r"[^A-Za-z0-9_.-]", "_", name)


def parse_labels(specs, varied):
    """{varied name: axis label} from the --label NAME=TEXT options."""
    labels = {}
    for spec in specs:
        key, sep, text = spec.partition("=")
        if not sep or key not in varied or not text:
            raise CampaignError("--label %s: expected NAME=TEXT with NAME a varied name (%s)"
                                % (spec, ", ".join(varied) if varied else "it varies nothing"))
        labels[key] = text
    return labels


def map_names(args, names, what, none):
    """(x name, y name) of a map from --x and --y, each one of names (default: the first two);
    what says where names come from and none what to say when there are none, for the error."""
    for opt, value in (("--x", args.x), ("--y", args.y)):
        if value is not None and value not in names:
            raise CampaignError("%s %s: not a varied name %s (%s)"
                                % (opt, value, what, ", ".join(names) if names else none))
    xname = args.x or (names[0] if names else None)
    yname = args.y or next((v for v in names if v != xname), None)
    if xname is not None and xname == yname:
        raise CampaignError("--x and --y name the same varied name %s" % xname)
    return xname, yname


def start_figures(args, command, style):
    """Matplotlib on the Agg backend with style, the campaign's name and OUT/figures (made)."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy  # noqa: F401 (only whether it is there)
    except ImportError as e:
        raise CampaignError("%s needs matplotlib and numpy (apt-get install python3-matplotlib "
                            "python3-numpy): %s" % (command, e))
    plt.rcParams.update(style)
    name = args.name or os.path.basename(os.path.normpath(os.path.abspath(args.out)))
    figdir = os.path.join(args.out, "figures")
    # a figure of an earlier run that is a link to the table would be written over it
    earlier = [os.path.join(figdir, n) for n in (os.listdir(figdir) if os.path.isdir(figdir) else [])
               if any(fnmatch.fnmatchcase(n, p) for p in FIGURE_PATTERNS)]
    refuse_inputs("campaign.py", earlier, [os.path.join(args.out, "campaign.csv")])
    os.makedirs(figdir, exist_ok=True)
    return name, figdir


def cmd_plot(args):
    varied, controllers, cols = read_campaign(args.out)
    if not controllers:
        raise CampaignError("%s/campaign.csv: no controller columns" % args.out)
    xname, yname = map_names(args, varied, "of the campaign", "it varies nothing")
    labels = parse_labels(args.label, varied)
    name, figdir = start_figures(args, "plot", {"font.size": 10, "axes.grid": True, "grid.alpha": 0.3})
    written = []
    if xname is not None:
        written.append(plot_maps(args.out, name, varied, controllers, cols, args.axis, xname, yname, figdir,
                                 labels))
    else:
        print("campaign.py: the campaign varies nothing: no robustness map", file=sys.stderr)
    written.append(plot_boxes(args.out, name, controllers, cols, args.axis, figdir))
    for p in written:
        print("campaign.py: wrote %s" % p)
    return 0


def cmd_ratio(args):
    from campaign_ratio import RatioError, plot_ratio_maps
    varied, controllers, cols = read_campaign(args.out)
    where = []
    for spec in args.where:
        key, sep, value = spec.partition("=")
        if not sep or key not in varied:
            raise CampaignError("--where %s: expected NAME=VALUE with NAME a varied name (%s)"
                                % (spec, ", ".join(varied) if varied else "it varies nothing"))
        where.append((key, value))

    def same(text, value):  # the same text, or the same number written otherwise ("0.03" and "3e-2")
        nums = as_numbers([text, value])
        return text == value or (nums is not None and nums[0] == nums[1])
    keep = [r for r in range(len(cols["run"])) if all(same(cols[k][r], v) for k, v in where)]
    if not keep:
        raise CampaignError("--where %s: no run of the campaign" % " ".join(args.where))
    cols = {name: [col[r] for r in keep] for name, col in cols.items()}
    free = [v for v in varied if v not in dict(where)]
    xname, yname = map_names(args, free, "left free by --where", "none")
    if xname is None:
        raise CampaignError("ratio: no varied name left for the x axis")
    labels = parse_labels(args.label, varied)
    name, figdir = start_figures(args, "ratio", {"font.size": 10})
    try:
        path, summary = plot_ratio_maps(name, cols, args.axis, xname, yname, figdir, labels, controllers, where,
                                        map_axes, save)
    except RatioError as e:
        raise CampaignError("%s: %s" % (args.out, e))
    for ctrl, (n, met, div) in summary.items():
        print("campaign.py: %s %s: ratio <= 0.5 in %d of %d runs with an incumbent, %d diverged"
              % (ctrl, args.axis, met, n, div))
    print("campaign.py: wrote %s" % path)
    return 0


# ---------------------------------------------------------------------------------------------
# tunemap

# outcome, colour, what it means (the legend); in the order of the text table
OUTCOMES = [("tuned", "#2ca02c", "tuned: the tuner's gains"),
            ("defaults", "#9ecae1", "defaults: the library's gains flew better"),
            ("scenario", "#c7a0d8", "scenario: the file's gains flew better"),
            ("untunable", "#7f7f7f", "untunable: no candidate flew, not flown"),
            ("diverged", "#d62728", "diverged"),
            ("-", "#ffffff", "no tuning status in its metrics.csv")]
TUNEMAP_MAX_ROWS = 150       # more runs than this: one row per grid cell by default


def run_outcome(cols, ctrl, r):
    """The outcome of controller ctrl in run r (index from 0): an OUTCOMES name."""
    status = cols.get("%s.tune" % ctrl, ["-"] * (r + 1))[r]
    if status == "untunable" or cols["%s.roll.rms_deg" % ctrl][r] == "untunable":
        return "untunable"
    if cols["%s.roll.diverged" % ctrl][r] == "yes":
        return "diverged"
    return status if status in ("tuned", "defaults", "scenario") else "-"


def short_name(name):
    """A varied name without its section: sensors.delay_ticks -> delay_ticks."""
    return name.split(".", 1)[1] if "." in name else name


def tunemap_rows(varied, cols, by):
    """[(row label, [run indices])]: one row per run, or per distinct value of the names in by."""
    n_runs = len(cols["run"])
    if by is None:
        if n_runs <= TUNEMAP_MAX_ROWS:
            by = []
        else:
            by = [v for v in varied if len(set(cols[v])) <= MAX_CELLS] or varied[:1]
    if not by:
        names = varied
        return [(("run %s" % cols["run"][r]) + ("" if not names else ": " + ", ".join(
            "%s=%s" % (short_name(v), cols[v][r]) for v in names)), [r]) for r in range(n_runs)]
    groups = {}
    for r in range(n_runs):
        groups.setdefault(tuple(cols[v][r] for v in by), []).append(r)
    return [(", ".join("%s=%s" % (short_name(v), k) for v, k in zip(by, key))
             + (" (%d runs)" % len(runs) if len(runs) > 1 else ""), runs) for key, runs in groups.items()]


def tunemap_cell(cols, ctrl, runs):
    """(outcome, annotation) of a cell over its runs: the most frequent outcome (ties: the
    earlier in OUTCOMES), the median roll RMS (deg) of the runs flown without diverging, and
    how many of the runs had that outcome when not all."""
    outcomes = [run_outcome(cols, ctrl, r) for r in runs]
    order = [o for o, _, _ in OUTCOMES]
    best = max(order, key=lambda o: (outcomes.count(o), -order.index(o)))
    rms = sorted(float(cols["%s.roll.rms_deg" % ctrl][r]) for r, o in zip(runs, outcomes)
                 if o not in ("untunable", "diverged") and as_numbers([cols["%s.roll.rms_deg" % ctrl][r]]))
    if rms:
        mid = len(rms) // 2
        text = "%.3g" % (rms[mid] if len(rms) % 2 else 0.5 * (rms[mid - 1] + rms[mid]))
    else:
        text = {"untunable": "untun.", "diverged": "div."}.get(best, "")
    if outcomes.count(best) < len(outcomes):
        text += " (%d/%d)" % (outcomes.count(best), len(outcomes))
    return best, text


def tunemap_counts(controllers, cols):
    """{controller: {outcome: runs}} over every run."""
    n_runs = len(cols["run"])
    counts = {}
    for ctrl in controllers:
        c = {o: 0 for o, _, _ in OUTCOMES}
        for r in range(n_runs):
            c[run_outcome(cols, ctrl, r)] += 1
        counts[ctrl] = c
    return counts


def tunemap_table(controllers, counts, n_runs):
    """The text table of tunemap_counts: a header, then a line per controller."""
    names = [o for o, _, _ in OUTCOMES]
    width = max([len("controller")] + [len(c) for c in controllers])
    lines = ["%-*s  %s" % (width, "controller", "  ".join("%9s" % (o if o != "-" else "no status") for o in names)),]
    for ctrl in controllers:
        lines.append("%-*s  %s" % (width, ctrl, "  ".join("%9d" % counts[ctrl][o] for o in names)))
    lines.append("(runs per controller: %d)" % n_runs)
    return "\n".join(lines)


def plot_tunemap(name, controllers, cols, rows, figdir):
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    order = [o for o, _, _ in OUTCOMES]
    grid = np.zeros((len(rows), len(controllers)))
    texts = []
    used = set()
    for i, (_, runs) in enumerate(rows):
        line = []
        for j, ctrl in enumerate(controllers):
            outcome, text = tunemap_cell(cols, ctrl, runs)
            grid[i, j] = order.index(outcome)
            used.add(outcome)
            line.append(text)
        texts.append(line)
    label_w = 0.07 * max(len(lab) for lab, _ in rows)
    width = max(8.0, label_w + 1.2 * len(controllers) + 0.6)
    legend_rows = (len(used) + 1) // 2
    height = 1.0 + 0.2 * legend_rows + 0.5 + 0.27 * len(rows)
    fig, ax = plt.subplots(figsize=(width, height))
    fig.subplots_adjust(left=(label_w + 0.25) / width, right=1 - 0.3 / width, top=1 - 0.75 / height,
                        bottom=(0.35 + 0.2 * legend_rows) / height)
    cmap = ListedColormap([c for _, c, _ in OUTCOMES])
    ax.pcolormesh(np.arange(len(controllers) + 1), np.arange(len(rows) + 1), grid, cmap=cmap,
                  vmin=-0.5, vmax=len(OUTCOMES) - 0.5, edgecolors="#444444", linewidth=0.4)
    for i in range(len(rows)):
        for j in range(len(controllers)):
            dark = order[int(grid[i, j])] in ("tuned", "untunable", "diverged")
            ax.text(j + 0.5, i + 0.5, texts[i][j], ha="center", va="center", fontsize=7.5,
                    color="white" if dark else "black")
    ax.set_xlim(0, len(controllers))
    ax.set_ylim(len(rows), 0)
    ax.set_xticks(np.arange(len(controllers)) + 0.5)
    ax.set_xticklabels(controllers, fontsize=9)
    ax.xaxis.tick_top()
    ax.set_yticks(np.arange(len(rows)) + 0.5)
    ax.set_yticklabels([lab for lab, _ in rows], fontsize=8)
    ax.tick_params(length=0)
    handles = [Patch(facecolor=c, edgecolor="#444444", label=text) for o, c, text in OUTCOMES if o in used]
    fig.legend(handles=handles, loc="lower center", ncol=min(2, len(handles)), frameon=False, fontsize=8,
               borderaxespad=0.2)
    fig.suptitle("%s: tuning outcome per controller, roll RMS tracking error (deg) in each cell" % name,
                 fontsize=10)
    path = os.path.join(figdir, "tunemap.png")
    save(fig, path)
    return path


def cmd_tunemap(args):
    varied, controllers, cols = read_campaign(args.out)
    if not controllers:
        raise CampaignError("%s/campaign.csv: no controller columns" % args.out)
    for b in args.by or []:
        if b not in varied:
            raise CampaignError("--by %s: not a varied name of the campaign (%s)"
                                % (b, ", ".join(varied) if varied else "it varies nothing"))
    rows = tunemap_rows(varied, cols, args.by)
    name, figdir = start_figures(args, "tunemap", {"font.size": 9})
    path = plot_tunemap(name, controllers, cols, rows, figdir)
    print(tunemap_table(controllers, tunemap_counts(controllers, cols), len(cols["run"])))
    print("campaign.py: wrote %s" % path)
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(prog="campaign.py", description=__doc__.split("\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    m = sub.add_parser("merge", help="OUT/campaign.csv from OUT/plan.csv and OUT/runs/*/metrics.csv")
    m.add_argument("out", metavar="OUT")
    t = sub.add_parser("tunemap", help="the tuning outcome of every run and controller into OUT/figures/tunemap.png")
    t.add_argument("out", metavar="OUT")
    t.add_argument("--by", action="append", metavar="NAME",
                   help="one row per value of this varied name (repeatable: per combination) instead of one "
                        "per run")
    t.add_argument("--name", help="campaign name in the title (default: OUT's directory name)")
    for cmd, what in (("plot", "robustness maps and RMS box plots into OUT/figures/"),
                      ("ratio", "maps of each LADRC-family RMS / the better incumbent's into OUT/figures/")):
        p = sub.add_parser(cmd, help=what)
        p.add_argument("out", metavar="OUT")
        p.add_argument("--x", metavar="NAME", help="varied name on the x axis (default: the first left free)")
        p.add_argument("--y", metavar="NAME", help="varied name on the y axis (default: the second left free)")
        p.add_argument("--axis", choices=AXES, default="roll", help="attitude axis of the RMS error (default roll)")
        p.add_argument("--name", help="campaign name in the titles (default: OUT's directory name)")
        p.add_argument("--label", action="append", default=[], metavar="NAME=TEXT",
                       help="axis label of a varied name, e.g. 'w=tone frequency w (rad/s)' (default: the "
                            "name, with the unit its suffix gives)")
        if cmd == "ratio":
            p.add_argument("--where", action="append", default=[], metavar="NAME=VALUE",
                           help="only the runs whose varied value NAME is VALUE (repeatable)")
    args = parser.parse_args(argv)
    try:
        return {"merge": cmd_merge, "plot": cmd_plot, "ratio": cmd_ratio, "tunemap": cmd_tunemap}[args.command](args)
    except CampaignError as e:
        print("campaign.py: error: %s" % e, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
