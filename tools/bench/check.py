#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The checking part of tools/bench.sh --check: the gated figures of one
measurement (tools/bench/measure.sh) against tools/bench/limits.txt.

Usage: check.py FIGURES LIMITS
Prints a table (key, value, limit, kind, status). Exit status: 0 every
figure within its limit; 1 some above it (each named on stderr); 2 a bad
limits file or a figure missing from the measurement.
"""
import re
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree

from benchfigs import Figures

NUMBER = re.compile(r"^[0-9]+(\.[0-9]+)?$")


def main() -> int:
    figures_path, limits_path = sys.argv[1], sys.argv[2]
    measured = Figures(figures_path).gated()
    over = []
    row = "%-26s %10s %10s  %-8s %s"
    print(row % ("key", "value", "limit", "kind", "status"))
    for line in open(limits_path, encoding="utf-8"):
        words = line.split()
        if not words or words[0].startswith("#"):
            continue
        key = words[0]
        limit = words[1] if len(words) > 1 else ""
        kind = words[2] if len(words) > 2 else ""
        if kind not in ("budget", "ceiling"):
            print(f"error: {limits_path}: {key}: kind '{kind}' is neither budget nor ceiling", file=sys.stderr)
            return 2
        value = measured.get(key, "")
        if not NUMBER.match(value) or not NUMBER.match(limit):
            print(f"error: {limits_path}: {key}: no number to compare (measured '{value}', limit '{limit}'; "
                  f"keys: {' '.join(measured)})", file=sys.stderr)
            return 2
        if float(value) <= float(limit):
            status = "ok"
        else:
            status = "OVER"
            over.append(f"{key} = {value} > {limit} ({kind})")
        print(row % (key, value, limit, kind, status))
    if over:
        print(f"error: {len(over)} figure(s) above their limit in {limits_path}:", file=sys.stderr)
        for o in over:
            print("  " + o, file=sys.stderr)
        return 1
    print(f"all gated figures within {limits_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
