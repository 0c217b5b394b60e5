# SPDX-License-Identifier: BSD-3-Clause
"""What ladrc_sil writes, as the figure and report tools read it."""

import csv
import os

# The paper's four, then the baselines flown today (not in the paper: no published values).
CONTROLLERS = ["HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC", "PID", "CASCADED", "INDI"]
AXES = ["roll", "pitch", "yaw"]

# The words metrics.csv's value column holds in place of a number (docs/simulator.md).
DIVERGED = "diverged"        # every statistic of a run that diverged
NOT_SETTLED = "not_settled"  # a settling time when the error ends outside the band
NONE = "-"                   # diverged_at_s and diverged_error_deg of a run that did not diverge
UNTUNABLE = "untunable"      # every statistic of a controller tune = margins left untunable (not flown)
# tune,status: which candidate tune = margins flies (docs/margins.md)
TUNE_STATUS = ("tuned", "defaults", "scenario", UNTUNABLE)
TOKENS = (DIVERGED, NOT_SETTLED, NONE) + TUNE_STATUS


def untunable(metrics, controller):
    """True when tune = margins left the controller untunable (it was not flown)."""
    return metrics.get((controller, "tune", "status", "-")) == UNTUNABLE


def is_number(v):
    """True for a value that is a number, False for None and the tokens."""
    return isinstance(v, float)


def load_metrics(scen_dir):
    """{(controller, table, quantity, axis): value} from metrics.csv, or None if absent.
    A value is a float, or one of TOKENS."""
    path = os.path.join(scen_dir, "metrics.csv")
    if not os.path.exists(path):
        return None
    out = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            v = row["value"]
            out[(row["controller"], row["table"], row["quantity"], row["axis"])] = v if v in TOKENS else float(v)
    return out


def divergence(metrics, controller):
    """(time s, axis, |error| deg or nan) of a controller's run that diverged, else None.
    The axis is "-" when a rotor's w^2 turned non-finite."""
    if metrics.get((controller, "-", "diverged", "-")) != 1:
        return None
    for (c, table, quantity, axis), v in metrics.items():
        if c == controller and table == "-" and quantity == "diverged_at_s":
            return v, axis, metrics.get((c, "-", "diverged_error_deg", axis))
    return None


def divergence_text(metrics, controller):
    """"diverged at 0.468 s on roll (|error| 90.6 deg)" or "... (non-finite)", or None."""
    d = divergence(metrics, controller)
    if d is None:
        return None
    t, axis, err = d
    where = "" if axis == NONE else " on " + axis
    return "diverged at %.3f s%s (%s)" % (t, where, "|error| %.3g deg" % err if err == err else "non-finite")
