#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the paper's scenarios (tools/paper.sh) and draws the figures and the report:
# docs/figures/*.png (the estimators' of paper and real_heavy_lag30 with
# tools/estimators_plot.py) and docs/report.md, the incumbents and real-airframes
# tables of docs/comparisons.md and the headline table of README.md; then
# flies the realistic suite (tools/suite.sh) for docs/suite.md's table (each
# between its <!-- ...:begin/end --> markers).
#
# Usage: tools/figures.sh [OUT_DIR]
#   OUT_DIR  where the simulator's CSV output goes (default: build/paper-out)
#
# Needs Python 3 with matplotlib and numpy; on Debian:
#   apt-get install python3-matplotlib python3-numpy
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Debian's interpreter sees Debian's packages; another python3 first on PATH may not.
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
if ! "$py" -c 'import matplotlib, numpy' >/dev/null 2>&1; then
  echo "error: $py cannot import matplotlib and numpy; install them with" >&2
  echo "  apt-get install python3-matplotlib python3-numpy" >&2
  exit 1
fi

out=${1:-build/paper-out}
rm -rf "$out/paper" "$out/paper_noisy" "$out/paper_known" "$out/paper_noisy_known" "$out/table3_differentiator" \
  "$out/tone_sweep" "$out"/real_paper_lag* "$out"/real_heavy_lag*
mkdir -p "$out"
echo "== flying the paper's scenarios into $out"
tools/paper.sh --out "$out" --quiet | tee "$out/tables.txt"
echo "== flying the realistic suite into $out"
tools/suite.sh "$out" --no-csv
echo "== figures and report"
rm -f docs/figures/fig*.png  # the figures drawn below (margins_*.png come from tools/margins_plot.py)
"$py" tools/figures.py "$out" docs/figures
"$py" tools/estimators_plot.py "$out" docs/figures paper real_heavy_lag30
"$py" tools/report.py "$out" docs/report.md --docs docs --front-page README.md \
  --suite-page docs/suite.md
