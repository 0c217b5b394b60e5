# SPDX-License-Identifier: BSD-3-Clause
"""What ladrc_sil writes, as the figure and report tools read it."""

import csv
import os

CONTROLLERS = ["HP-MLADRC", "LP-MLADRC", "LADRC", "PID"]
AXES = ["roll", "pitch", "yaw"]


def load_metrics(scen_dir):
    """{(controller, table, quantity, axis): value} from metrics.csv, or None if absent."""
    path = os.path.join(scen_dir, "metrics.csv")
    if not os.path.exists(path):
        return None
    out = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            out[(row["controller"], row["table"], row["quantity"], row["axis"])] = float(row["value"])
    return out
