#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the paper's scenarios (tools/paper.sh) and draws the figures and the report:
# docs/figures/*.png (the estimators' of paper and real_heavy_lag30 with
# tools/estimators_plot.py) and docs/report.md, the incumbents and real-airframes
# tables of docs/comparisons.md and the headline table of README.md; then
# flies the realistic suite (tools/suite.sh) for docs/suite.md's table (each
# between its <!-- ...:begin/end --> markers); then flies the sweep
# campaigns/real_sweep.ini into OUT_DIR/real_sweep and draws its ratio maps,
# docs/figures/campaign/ratio_*.png (one per disturbance kind, roll).
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
echo "== the sweep over airframe, lag and disturbance kind"
rm -rf "$out/real_sweep"
build/host-release/sim/ladrc_sil --campaign campaigns/real_sweep.ini --out "$out" --jobs 2 --quiet
"$py" tools/campaign.py merge "$out/real_sweep"
rm -f docs/figures/campaign/ratio_*.png
for kind in 1 2 3; do
  "$py" tools/campaign.py ratio "$out/real_sweep" --x rotors.motor_tau_s --y J --where kind=$kind \
    --label "J=roll and pitch inertia J (kg m^2)" --label "rotors.motor_tau_s=motor lag (s)" --name real_sweep \
    | tee "$out/real_sweep/ratio_kind$kind.txt"
  cp "$out/real_sweep/figures/ratio_roll_rotors.motor_tau_s_J_kind$kind.png" docs/figures/campaign/
done
