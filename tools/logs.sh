#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The worked path of docs/flight-logs.md, on logs the simulator writes
# (scenarios/logs): an identification flight (chirps) and an ordinary flight,
# both flown by CASCADED and written in the Betaflight and PX4 forms; then
#   1. ladrc_replay identifies the airframe from the chirp flight's Betaflight
#      log and from its PX4 log (--identify-only);
#   2. ladrc_margins --from-log tunes every controller from the PX4 log;
#   3. ladrc_replay replays every controller, tuned for the identified
#      airframe, on the ordinary flight's Betaflight log and its PX4 log;
#   4. tools/replay_plot.py draws the replay's figures.
# With --docs, tools/log_ident_check.py identifies 20 random airframes too, and
# tools/flight_logs_doc.py writes docs/flight-logs.md's generated blocks and
# copies the figures into docs/figures.
#
# Usage: tools/logs.sh [OUT_DIR] [--docs]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/logs-out}
docs=${2:-}
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil ladrc_replay ladrc_margins --parallel 2 >/dev/null
bin=build/host-release/sim
rm -rf "$out"
mkdir -p "$out"
"$bin/ladrc_sil" scenarios/logs/chirp_flight.ini scenarios/logs/ordinary_flight.ini --out "$out" --quiet --jobs 2 \
  > "$out/flights.txt"
# ladrc_replay exits 0 when it ran (its warnings printed); a status above 1 is a failure.
run() { # name, command...
  local name=$1 rc=0
  shift
  "$@" > "$out/$name.txt" 2> "$out/$name.err" || rc=$?
  if [[ $rc -gt 1 ]]; then
    echo "logs.sh: $name failed ($rc):" >&2
    cat "$out/$name.err" >&2
    exit 1
  fi
}
run identify_betaflight "$bin/ladrc_replay" "$out/chirp_flight/CASCADED_betaflight.csv" --identify-only --quiet \
  --out "$out/identify_betaflight"
run identify_px4 "$bin/ladrc_replay" "$out/chirp_flight/CASCADED_px4" --format px4 --identify-only --quiet \
  --out "$out/identify_px4"
run margins "$bin/ladrc_margins" --from-log "$out/chirp_flight/CASCADED_px4" --format px4
run replay_betaflight "$bin/ladrc_replay" "$out/ordinary_flight/CASCADED_betaflight.csv" --quiet \
  --scenario "$out/identify_px4/airframe.ini" --out "$out/replay_betaflight"
run replay_px4 "$bin/ladrc_replay" "$out/ordinary_flight/CASCADED_px4" --format px4 --quiet \
  --scenario "$out/identify_px4/airframe.ini" --out "$out/replay_px4"
"$py" tools/replay_plot.py "$out/replay_px4" --from 12 --to 20
cat "$out/identify_betaflight.txt" "$out/identify_px4.txt" "$out/replay_px4.txt"
if [[ $docs == --docs ]]; then
  # the identification over random airframes, summed up in the document
  "$py" tools/log_ident_check.py --sil "$bin/ladrc_sil" --replay "$bin/ladrc_replay" --out "$out/check" \
    --markdown "$out/check.md" > "$out/check.txt" || echo "logs.sh: the identification check missed figures (in the block)"
  "$py" tools/flight_logs_doc.py "$out" docs/flight-logs.md
  cp "$out/replay_px4/replay_commands.png" docs/figures/replay_commands.png
  cp "$out/replay_px4/replay_spectrum.png" docs/figures/replay_spectrum.png
fi
