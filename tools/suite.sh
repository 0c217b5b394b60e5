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
for f in scenarios/suite/*.ini scenarios/paper_tuned.ini; do
  name=$(basename "$f" .ini)
  rm -rf "${out:?}/$name"
  set +e
  "$sil" "$f" --out "$out" --quiet "$@" > "$out/$name.tables.txt" 2> "$out/$name.err"
  rc=$?
  set -e
  cat "$out/$name.err" >&2
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
for w in "${warnings[@]}"; do echo "suite.sh: WARNING: $w" >&2; done
