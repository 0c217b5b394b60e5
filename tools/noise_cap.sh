#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The noise-aware setting on the realistic suite (docs/margins.md, "Command
# noise"): each suite case flown with the LADRC family's tunings capped at
# the command noise of an incumbent tuned alike (tune_noise_ref = CASCADED,
# then = INDI), beside the uncapped run; tools/noise_cap.py compares each
# family member's flown command noise above 20 Hz and RMS error with the
# better incumbent's (the one with the smaller RMS error on that axis,
# uncapped). Not run in CI (about 15 minutes of 2 cores).
#
# Usage: tools/noise_cap.sh [OUT_DIR]     (default build/noise-cap)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/noise-cap}
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null
sil=build/host-release/sim/ladrc_sil
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
mkdir -p "$out"
family=(HP-MLADRC LP-MLADRC LADRC RATE-ADRC)
for f in scenarios/suite/*.ini; do
  name=$(basename "$f" .ini)
  for ref in none CASCADED INDI; do
    sets=()
    if [[ $ref != none ]]; then
      for c in "${family[@]}"; do sets+=(--set "controller:$c.tune_noise_ref=$ref"); done
    fi
    set +e
    "$sil" "$f" --no-csv --quiet --out "$out/$ref" "${sets[@]}" > /dev/null 2> "$out/$name.$ref.err"
    rc=$?
    set -e
    [[ $rc -eq 0 || $rc -eq 3 || $rc -eq 4 ]] || { cat "$out/$name.$ref.err" >&2; exit 1; }
    echo "noise_cap.sh: flew $name, cap $ref (exit $rc)"
  done
done
"$py" tools/noise_cap.py "$out"
