#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The acceptance run on real flight logs (issue 38): `ladrc_replay LOG`, with no
# options, on every log under DIR (default: the excerpts in tests/data/real_logs),
# each in its own temporary directory; per log it prints the exit status, the
# controllers replayed and those untunable with their reason, per axis the
# command noise above 20 Hz of the logged controller and of the LADRC family's
# quietest controller, and a verdict (tools/real_logs_report.py says how).
#
# Logs: *.bbl *.bfl *.ulg *.bin *.csv (any case). A PX4 ulog2csv set
# (BASE_<topic>_0.csv) counts once, by its vehicle_attitude file; blackbox_decode's
# side files (*.gps.csv) are not logs.
#
# Usage: tools/real_logs.sh [DIR] [--replay BIN] [--keep OUT]
#   --replay BIN  the ladrc_replay to run (default: $LADRC_REPLAY, else
#                 build/host-release/sim/ladrc_replay)
#   --keep OUT    keep each run's outputs in OUT/<n>-<log name> (default: removed)
#   --noise M     gate (default): a LADRC family louder than the log above 20 Hz fails
#                 the log; report: said on its line, not failed
# Environment: REAL_LOGS_TIMEOUT_S, the limit of one run (default 1800 s).
# Exit status 0 when every log passes, 1 when one fails, 2 for bad usage or no log.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=$root/tests/data/real_logs
replay=${LADRC_REPLAY:-$root/build/host-release/sim/ladrc_replay}
keep=
noise=gate
positional=0
while [[ $# -gt 0 ]]; do
  case $1 in
    --replay) replay=${2:?--replay needs a path}; shift 2 ;;
    --keep) keep=${2:?--keep needs a directory}; shift 2 ;;
    --noise) noise=${2:?--noise needs gate or report}; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    -*) echo "real_logs.sh: unknown option $1" >&2; exit 2 ;;
    *) [[ $positional -eq 0 ]] || { echo "real_logs.sh: one DIR only" >&2; exit 2; }
       dir=$1; positional=1; shift ;;
  esac
done
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
[[ -x $replay ]] || { echo "real_logs.sh: $replay: no ladrc_replay there (build it, or give --replay)" >&2; exit 2; }
[[ -d $dir ]] || { echo "real_logs.sh: $dir: no such directory" >&2; exit 2; }
replay=$(cd "$(dirname "$replay")" && pwd)/$(basename "$replay")
timeout_s=${REAL_LOGS_TIMEOUT_S:-1800}

# The logs, one per flight: a PX4 topic set once (its vehicle_attitude file).
mapfile -t found < <(find -L "$dir" -type f \( -iname '*.bbl' -o -iname '*.bfl' -o -iname '*.ulg' -o -iname '*.bin' \
  -o -iname '*.csv' \) ! -iname '*.gps.csv' | LC_ALL=C sort)
px4_sets=()
for f in "${found[@]}"; do
  [[ $f == *_vehicle_attitude_0.csv ]] && px4_sets+=("${f%_vehicle_attitude_0.csv}_")
done
logs=()
for f in "${found[@]}"; do
  own= # the longest set prefix of f: pyulog_sample_ must not claim pyulog_sample_log_small_*
  for base in "${px4_sets[@]}"; do
    [[ $f == "$base"* && ${#base} -gt ${#own} ]] && own=$base
  done
  [[ -z $own || $f == "${own}vehicle_attitude_0.csv" ]] && logs+=("$f")
done
[[ ${#logs[@]} -gt 0 ]] || { echo "real_logs.sh: no log under $dir" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/real_logs.XXXXXX")
trap 'rm -rf "$work"' EXIT
[[ -n $keep ]] && mkdir -p "$keep"
passed=0 failed=0 n=0
for log in "${logs[@]}"; do
  n=$((n + 1))
  run=$work/$n
  mkdir -p "$run"
  abs=$(cd "$(dirname "$log")" && pwd)/$(basename "$log")
  start=$(date +%s.%N)
  # no options: the outputs go to replay/<log name>/ under the run's own directory
  (cd "$run" && timeout "$timeout_s" "$replay" "$abs" > "$work/$n.out" 2> "$work/$n.err")
  status=$?
  end=$(date +%s.%N)
  seconds=$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.2f", b - a }')
  if "$py" "$root/tools/real_logs_report.py" --log "${log#"$root"/}" --status "$status" --out "$run" \
      --stdout "$work/$n.out" --stderr "$work/$n.err" --seconds "$seconds" --noise "$noise"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
  fi
  if [[ -n $keep ]]; then
    dest=$keep/$n-$(basename "$log")
    rm -rf "$dest"
    mkdir -p "$dest"
    cp -r "$run"/. "$dest"/
    cp "$work/$n.out" "$dest/stdout.txt"
    cp "$work/$n.err" "$dest/stderr.txt"
  fi
done
echo "real_logs: $passed of $n logs pass, $failed fail"
[[ $failed -eq 0 ]]
