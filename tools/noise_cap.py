#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The noise-aware setting's table (tools/noise_cap.sh, docs/margins.md "Command noise").

Usage: noise_cap.py OUT

Reads OUT/{none,CASCADED,INDI}/<case>/metrics.csv. For each suite case and axis, the better
incumbent is the one of CASCADED and INDI with the smaller RMS error (uncapped); each LADRC-family
controller, tuned with its command noise capped at that incumbent's (OUT/<incumbent>), is compared
with it: flown command noise above 20 Hz over the incumbent's, and RMS error over the incumbent's.
Prints a Markdown table and the counts.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sim_output import AXES, is_number, load_metrics  # noqa: E402

FAMILY = ("HP-MLADRC", "LP-MLADRC", "LADRC", "RATE-ADRC")
INCUMBENTS = ("CASCADED", "INDI")


def value(m, c, table, quantity, axis):
    v = m.get((c, table, quantity, axis)) if m else None
    return v if is_number(v) and not math.isnan(v) else None


def main(out):
    cases = sorted(os.listdir(os.path.join(out, "none")))
    rows, n, quiet_enough, rms_kept = [], 0, 0, 0
    worst = 0.0
    for case in cases:
        base = load_metrics(os.path.join(out, "none", case))
        for axis in AXES:
            rms = {c: value(base, c, "4", "error_rms_deg", axis) for c in INCUMBENTS}
            if any(v is None for v in rms.values()):
                continue
            inc = min(INCUMBENTS, key=lambda c: rms[c])
            capped = load_metrics(os.path.join(out, inc, case))
            inc_noise = value(capped, inc, "-", "cmd_noise_Nm", axis)
            cells = []
            for c in FAMILY:
                noise = value(capped, c, "-", "cmd_noise_Nm", axis)
                err = value(capped, c, "4", "error_rms_deg", axis)
                free = value(base, c, "4", "error_rms_deg", axis)
                if noise is None or err is None or not inc_noise:
                    cells.append("—")
                    continue
                n += 1
                ratio = noise / inc_noise
                worst = max(worst, ratio)
                quiet_enough += ratio <= 1.0
                rms_kept += free is not None and err <= 1.0 * rms[inc]
                cells.append("%.2f / %.2f" % (ratio, err / rms[inc]))
            rows.append("| `%s` | %s | %s | %s |" % (case, axis, inc, " | ".join(cells)))
    print("| case | axis | better incumbent | " + " | ".join(FAMILY) + " |")
    print("|---|---|---|" + "---|" * len(FAMILY))
    print("\n".join(rows))
    print()
    print("Each cell: flown command noise above 20 Hz / RMS error, over the better incumbent's, the family "
          "member tuned with its noise capped at the incumbent's.")
    print("%d of %d family runs at or below the incumbent's flown noise (worst %.2fx); %d of %d at or below "
          "its RMS error." % (quiet_enough, n, worst, rms_kept, n))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
