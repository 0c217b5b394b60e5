#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the realistic suite (scenarios/suite/*.ini) and the paper case with
# every controller tuned alike (scenarios/paper_tuned.ini), one ladrc_sil run
# per scenario, into OUT_DIR/<scenario> (docs/suite.md; tools/report.py reads it).
#
# A tune = margins that fails stops ladrc_sil before anything flies. The case
# is kept: the failure is written to OUT_DIR/<scenario>/tune_failed.txt, the
# scenario is flown again without that controller, and the failure is named
# on stderr at the end; so is every run that diverged. Exit status 0 when
# every scenario flew (failures and divergences are results, reported),
# 1 on any other error.
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
  read -r -a ctrls < <(sed -n 's/^controllers *= *//p' "$f" | tr ',' ' ')
  failed=()
  while :; do
    set +e
    "$sil" "$f" --controllers "${ctrls[*]}" --out "$out" --quiet "$@" > "$out/$name.tables.txt" 2> "$out/$name.err"
    rc=$?
    set -e
    cat "$out/$name.err" >&2
    # A failed tuning names its controller: "tune = margins: LP-MLADRC on roll ..."
    who=$(sed -n 's/.*tune = margins: \([A-Z-]*\) on .*/\1/p' "$out/$name.err" | head -n 1)
    if [[ $rc -eq 2 && -n $who ]]; then
      failed+=("$who: $(cat "$out/$name.err")")
      warnings+=("TUNING FAILED in $name: $(cat "$out/$name.err")")
      mapfile -t ctrls < <(printf '%s\n' "${ctrls[@]}" | grep -vx -- "$who")
      [[ ${#ctrls[@]} -gt 0 ]] && continue
      mkdir -p "$out/$name"
      break
    fi
    case $rc in
      0) ;;
      3) warnings+=("DIVERGED in $name: $(grep -i diverg "$out/$name.err" | tr '\n' ' ')") ;;
      *) echo "suite.sh: $f: ladrc_sil exited $rc" >&2; exit 1 ;;
    esac
    break
  done
  mv "$out/$name.tables.txt" "$out/$name/tables.txt"
  rm -f "$out/$name.err"
  if [[ ${#failed[@]} -gt 0 ]]; then printf '%s\n' "${failed[@]}" > "$out/$name/tune_failed.txt"; fi
  echo "suite.sh: flew $name (${ctrls[*]})"
done
for w in "${warnings[@]}"; do echo "suite.sh: WARNING: $w" >&2; done
