#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The tuning map (docs/tuning.md): flies every airframe of scenarios/airframes/
# and the campaign campaigns/tuning_map.ini with every controller tuned by
# tune = margins, and draws which controllers tune where:
#   OUT/airframes/figures/tunemap.png   one row per airframe
#   OUT/tuning_map/figures/tunemap.png  one row per delay and motor lags, the
#                                       inertia and drag values pooled
#   OUT/tuning_map/figures/tunemap_runs.png  one row per run
# with the counts of each outcome per controller in OUT/*/tunemap.txt. Long:
# not run in CI (the campaign alone is about 20 minutes on 2 cores).
#
# A controller left untunable is a result (ladrc_sil exit 4, `untunable` in
# the map); an airframe that ladrc_sil refuses is left out of the map and
# named in OUT/airframes/refused.txt and on stderr; so is the campaign.
# Exit status 0 when both maps were drawn, 1 otherwise.
#
# Usage: tools/tuning_map.sh [OUT] [--jobs N]     (OUT default build/tuning-map)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=build/tuning-map
jobs=2
while [[ $# -gt 0 ]]; do
  case $1 in
    --jobs) jobs=$2; shift 2 ;;
    -*) echo "tuning_map.sh: unknown option $1" >&2; exit 1 ;;
    *) out=$1; shift ;;
  esac
done
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
if [[ -z ${LADRC_SIL:-} ]]; then
  (cd "$root" && cmake --preset host-release >/dev/null &&
    cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null)
fi
sil=${LADRC_SIL:-$root/build/host-release/sim/ladrc_sil}
mkdir -p "$out"
out=$(cd "$out" && pwd)
status=0

# The airframes: one ladrc_sil run each, then a campaign-shaped OUT/airframes
# (plan.csv: run,airframe; runs/<r>/metrics.csv with the run's directory name
# in the scenario column) that campaign.py merges and maps like any campaign.
air=$out/airframes
rm -rf "$air"
mkdir -p "$air/flown" "$air/runs"
echo "run,airframe" > "$air/plan.csv"
: > "$air/refused.txt"
r=0
for f in "$root"/scenarios/airframes/*.ini; do
  name=$(basename "$f" .ini)
  start=$(date +%s)
  set +e
  "$sil" "$f" --no-csv --quiet --jobs "$jobs" --out "$air/flown" > "$air/flown/$name.tables.txt" 2> "$air/flown/$name.err"
  rc=$?
  set -e
  secs=$(( $(date +%s) - start ))
  if [[ $rc -ne 0 && $rc -ne 3 && $rc -ne 4 ]]; then
    echo "$name: exit $rc after $secs s: $(tr '\n' ' ' < "$air/flown/$name.err")" >> "$air/refused.txt"
    echo "tuning_map.sh: $name refused (exit $rc, $secs s): $(head -n 1 "$air/flown/$name.err")" >&2
    continue
  fi
  r=$((r + 1))
  run=$(printf '%05d' "$r")
  mkdir -p "$air/runs/$run"
  awk -F, -v OFS=, -v run="$run" 'NR == 1 { print; next } { $1 = run; print }' \
    "$air/flown/$name/metrics.csv" > "$air/runs/$run/metrics.csv"
  echo "$r,$name" >> "$air/plan.csv"
  echo "tuning_map.sh: flew $name in $secs s (exit $rc)"
done
if [[ $r -gt 0 ]]; then
  "$py" "$root/tools/campaign.py" merge "$air"
  "$py" "$root/tools/campaign.py" tunemap "$air" --name "airframes" | tee "$air/tunemap.txt"
else
  echo "tuning_map.sh: no airframe flew: no airframe map" >&2
  status=1
fi

# The campaign: delay, motor lags, inertia mismatch and drag over heavy_2kg.ini.
campaign=$root/campaigns/tuning_map.ini
start=$(date +%s)
set +e
"$sil" --campaign "$campaign" --jobs "$jobs" --quiet --out "$out" 2> "$out/campaign.err"
rc=$?
set -e
secs=$(( $(date +%s) - start ))
cat "$out/campaign.err" >&2
cdir=$("$sil" --campaign "$campaign" --out "$out" --print-out)
if [[ $rc -eq 0 ]]; then
  echo "tuning_map.sh: flew the campaign in $secs s"
  "$py" "$root/tools/campaign.py" merge "$cdir"
  # every run (a row per grid point), then the cells of delay x lags (inertia and drag pooled)
  "$py" "$root/tools/campaign.py" tunemap "$cdir" --name "tuning_map, every run" > /dev/null
  mv "$cdir/figures/tunemap.png" "$cdir/figures/tunemap_runs.png"
  "$py" "$root/tools/campaign.py" tunemap "$cdir" --name "tuning_map" \
    --by sensors.delay_ticks --by rotors.motor_tau_s --by rotors.motor_tau_down_s | tee "$cdir/tunemap.txt"
  "$py" "$root/tools/campaign.py" plot "$cdir" --x sensors.delay_ticks --y rotors.motor_tau_s
else
  echo "tuning_map.sh: the campaign did not fly (exit $rc after $secs s): no campaign map" >&2
  status=1
fi
if [[ -s $air/refused.txt ]]; then
  echo "tuning_map.sh: refused airframes (OUT/airframes/refused.txt):" >&2
  cat "$air/refused.txt" >&2
fi
exit $status
