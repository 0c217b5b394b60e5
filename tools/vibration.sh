#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the vibration cases (scenarios/vibration/*.ini, docs/vibration.md):
# each airframe in light, moderate and severe turbulence, four ways:
#   clean           no propeller vibration, no filter (the reference)
#   clean_filtered  no vibration, the file's [filter] stage (what the filter alone does)
#   raw             vibration, no filter
#   filtered        vibration through the filter
# and, in moderate turbulence, two more with a leaner filter (RPM notches of
# Q 10, no low-pass: less lag near the crossover):
#   lean_clean      no vibration, the lean filter
#   lean            vibration through the lean filter
# into OUT_DIR/<airframe>_<turbulence>_<way>/, then tools/vibration.py writes
# the table (and, with --docs, docs/vibration.md's block and its figure).
# Runs two ladrc_sil at a time. A run that diverged is a result (named in
# the table and on stderr); any other failure stops it with status 1.
#
# Usage: tools/vibration.sh [OUT_DIR] [--docs]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/vibration-out}
docs=${2:-}
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null
sil=build/host-release/sim/ladrc_sil
mkdir -p "$out"
# One run: airframe, turbulence, way.
fly() {
  local frame=$1 turb=$2 way=$3 dir="$out/$1_$2_$3"
  local set_way=()
  local lean=(--set filter.rpm_q=10 --set filter.lpf_order=0)
  case $way in
    clean) set_way=(--set "vibration.gyro_deg_s=0 0 0" --set "vibration.accel_m_s2=0 0 0" --set filter.enabled=no) ;;
    clean_filtered) set_way=(--set "vibration.gyro_deg_s=0 0 0" --set "vibration.accel_m_s2=0 0 0") ;;
    lean_clean) set_way=(--set "vibration.gyro_deg_s=0 0 0" --set "vibration.accel_m_s2=0 0 0" "${lean[@]}") ;;
    lean) set_way=("${lean[@]}") ;;
    raw) set_way=(--set filter.enabled=no) ;;
  esac
  rm -rf "$dir"
  mkdir -p "$dir"
  local rc=0
  "$sil" "scenarios/vibration/$frame.ini" --set "wind.turbulence=$turb" "${set_way[@]}" --out "$dir" --quiet \
    > "$dir/tables.txt" 2> "$dir/stderr.txt" || rc=$?
  if [[ $rc -eq 3 ]]; then # a divergence is a result: the table names it
    echo "vibration.sh: WARNING: $dir: a run diverged: $(tr '\n' ' ' < "$dir/stderr.txt")" >&2
  elif [[ $rc -ne 0 ]]; then
    echo "vibration.sh: $dir: ladrc_sil exited $rc:" >&2
    cat "$dir/stderr.txt" >&2
    return 255 # stops xargs
  fi
  echo "vibration.sh: flew $frame, $turb turbulence, $way"
}
export -f fly
export out sil
for f in scenarios/vibration/*.ini; do
  for turb in light moderate severe; do
    for way in clean clean_filtered raw filtered; do
      echo "$(basename "$f" .ini) $turb $way"
    done
  done
  echo "$(basename "$f" .ini) moderate lean_clean"
  echo "$(basename "$f" .ini) moderate lean"
done | xargs -P 2 -n 3 bash -c 'fly "$@"' _
args=("$out")
[[ $docs == --docs ]] && args+=(--docs docs/vibration.md --figure docs/figures/vibration_spectrum.png)
/usr/bin/python3 tools/vibration.py "${args[@]}"
