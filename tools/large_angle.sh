#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies the large-angle cases (scenarios/large_angle/*.ini, docs/large-angle.md):
#   tuned            as shipped: every controller tuned by tune = margins, in the
#                    quaternion frame
#   gains_quaternion every controller at its default gains (tune = none), in the
#                    quaternion frame
#   gains_euler      the same gains in the Euler frame (per angle, the paper's)
# into OUT_DIR/<way>/<scenario>/, then tools/large_angle.py writes the tables
# (and, with --docs, docs/large-angle.md's block and its figure). A run that
# diverged is a result (named in the table); any other failure stops it with
# status 1.
#
# Usage: tools/large_angle.sh [OUT_DIR] [--docs]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/large-angle-out}
docs=${2:-}
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null
sil=build/host-release/sim/ladrc_sil
untuned=()
for c in HP-MLADRC LP-MLADRC LADRC RATE-ADRC PID CASCADED INDI; do
  untuned+=(--set "controller:$c.tune=none")
done
for way in tuned gains_quaternion gains_euler; do
  sets=()
  case $way in
    gains_quaternion) sets=("${untuned[@]}") ;;
    gains_euler) sets=("${untuned[@]}" --set reference.frame=euler) ;;
  esac
  rm -rf "${out:?}/$way"
  mkdir -p "$out/$way"
  rc=0
  "$sil" scenarios/large_angle/*.ini "${sets[@]}" --out "$out/$way" --quiet --jobs 2 \
    > "$out/$way/tables.txt" 2> "$out/$way/stderr.txt" || rc=$?
  if [[ $rc -eq 3 ]]; then # a divergence is a result: the table names it
    echo "large_angle.sh: $way: a run diverged (named in the table)"
  elif [[ $rc -ne 0 ]]; then
    echo "large_angle.sh: $way: ladrc_sil exited $rc:" >&2
    cat "$out/$way/stderr.txt" >&2
    exit 1
  fi
  echo "large_angle.sh: flew $way"
done
args=("$out")
[[ $docs == --docs ]] && args+=(--docs docs/large-angle.md --figure docs/figures/large_angle.png)
/usr/bin/python3 tools/large_angle.py "${args[@]}"
