# SPDX-License-Identifier: BSD-3-Clause
"""What every figure of the project shares: one colour per controller (and black for the log
flown), and y limits set by the bulk of the data so that one spike does not flatten the rest."""

import numpy as np

# One colour per controller, in every figure (figures.py, estimators_plot.py, margins_plot.py,
# replay_plot.py, response_plot.py).
COLOURS = {"HP-MLADRC": "#1f77b4", "LP-MLADRC": "#2ca02c", "LADRC": "#d62728", "RATE-ADRC": "#17becf", "PID": "#9467bd",
           "CASCADED": "#8c564b", "INDI": "#ff7f0e"}
LOG_COLOUR = "black"  # the log's own controller, as flown
LOG_SOURCE = "LOG"    # its name in ladrc_replay's CSVs


def colour_of(name):
    """The colour of a controller or of the log ("LOG"), matched on the name's start (a file
    `LADRC_roll.csv` is LADRC's); None for a name the palette does not hold."""
    if name.startswith(LOG_SOURCE):
        return LOG_COLOUR
    for c in sorted(COLOURS, key=len, reverse=True):
        if name == c or name.startswith(c + "_") or name.startswith(c + " "):
            return COLOURS[c]
    return None


def robust_limits(values, lo_pct=0.2, hi_pct=99.8, pad=0.15):
    """(lo, hi) around the lo_pct..hi_pct percentiles of the finite values, widened by pad of the
    range; None without a finite value."""
    v = np.concatenate([np.asarray(x, dtype=float).ravel() for x in values])
    v = v[np.isfinite(v)]
    if v.size == 0:
        return None
    lo, hi = np.percentile(v, [lo_pct, hi_pct])
    margin = pad * max(hi - lo, 1e-9)
    return lo - margin, hi + margin


def clip_ylim(ax, values, what):
    """Limits the y range to the bulk of the values (robust_limits), so that short spikes (a step,
    a landing) do not flatten the rest, and says so in the panel."""
    lim = robust_limits(values)
    if lim is None:
        return
    v = np.concatenate([np.asarray(x, dtype=float).ravel() for x in values])
    v = v[np.isfinite(v)]
    if v.min() < lim[0] or v.max() > lim[1]:
        ax.set_ylim(*lim)
        ax.text(0.99, 0.03, "%s clipped (peaks %.3g, %.3g)" % (what, v.min(), v.max()), transform=ax.transAxes,
                ha="right", va="bottom", fontsize=7, color="0.3")
