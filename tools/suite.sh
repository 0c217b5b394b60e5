#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the realistic suite (scenarios/suite/*.ini) and the paper case with
# every controller tuned alike (scenarios/paper_tuned.ini), one ladrc_sil run
# per scenario, into OUT_DIR/<scenario> (docs/suite.md; tools/report.py reads it).
#
# A controller that tune = margins leaves untunable is not flown (ladrc_sil
# exit 4): it is named on stderr at the end, as is every run that diverged,
# and each tuning that missed its targets. Exit status 0 when every scenario
# flew (untunable controllers and divergences are results, reported), 1 on
# any other error.
#
# Usage: tools/suite.sh [OUT_DIR] [ladrc_sil options, e.g. --no-csv]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/suite-out}
shift || true
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null
sil=build/host-release/sim/ladrc_sil
mkdir -p "$out"
warnings=()
tune_all=0
tune_tuner=0
for f in scenarios/suite/*.ini scenarios/paper_tuned.ini; do
  name=$(basename "$f" .ini)
  rm -rf "${out:?}/$name"
  set +e
  "$sil" "$f" --out "$out" "$@" > "$out/$name.tables.txt" 2> "$out/$name.err"
  rc=$?
  set -e
  grep -v "^ladrc_sil: \(tuned \|[0-9]* runs, \| *[0-9]*% (\)" "$out/$name.err" >&2 || true
  # the tuning's cost of one core, and that of the tuners and their own check flights alone
  read -r all tuner < <(sed -n 's/.*; of one core \([0-9.]*\) s, the tuners and their check flights \([0-9.]*\) s.*/\1 \2/p' \
    "$out/$name.err" | head -n 1) || true
  tune_all=$(awk -v a="$tune_all" -v b="${all:-0}" 'BEGIN { print a + b }')
  tune_tuner=$(awk -v a="$tune_tuner" -v b="${tuner:-0}" 'BEGIN { print a + b }')
  case $rc in
    0) ;;
    3) warnings+=("DIVERGED in $name: $(grep -i diverg "$out/$name.err" | tr '\n' ' ')") ;;
    4) warnings+=("UNTUNABLE in $name: $(grep -i untunable "$out/$name.err" | tr '\n' ' ')") ;;
    *) echo "suite.sh: $f: ladrc_sil exited $rc" >&2; exit 1 ;;
  esac
  if grep -q "warning: tune = margins" "$out/$name.err"; then
    warnings+=("TUNING MISSED in $name: $(grep "warning: tune = margins" "$out/$name.err" | tr '\n' ' ')")
  fi
  mv "$out/$name.tables.txt" "$out/$name/tables.txt"
  rm -f "$out/$name.err"
  echo "suite.sh: flew $name"
done
awk -v a="$tune_all" -v t="$tune_tuner" 'BEGIN { printf "suite.sh: tuning took %.1f s of one core; the tuners and their own check flights alone %.1f s (the candidates: %.2fx)\n", a, t, (t > 0 ? a / t : 0) }'
for w in "${warnings[@]}"; do echo "suite.sh: WARNING: $w" >&2; done
