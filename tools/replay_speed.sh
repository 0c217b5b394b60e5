#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The cost of a flight log's replay (docs/flight-logs.md): the simulator
# flies MINUTES of scenarios/logs/ordinary_flight.ini's airframe (default 60)
# and writes it as a Betaflight log, then ladrc_replay identifies it and
# replays the six controllers (HP-MLADRC, LP-MLADRC, LADRC, RATE-ADRC,
# CASCADED, INDI, tuned by the scenario) on it without a time series; it
# prints ladrc_replay's own timing lines and its peak memory.
#
# Usage: tools/replay_speed.sh [MINUTES] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-60}
out=${2:-build/replay-speed}
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil ladrc_replay --parallel 2 >/dev/null
bin=build/host-release/sim
rm -rf "$out"
mkdir -p "$out"
seconds=$((minutes * 60))
# the ordinary flight's airframe, its steps and sweeps over the first 30 s, then hovering in the turbulence
"$bin/ladrc_sil" scenarios/logs/ordinary_flight.ini --set "run.duration_s=$seconds" --set run.log=betaflight \
  --out "$out" --quiet > /dev/null
log=$out/ordinary_flight/CASCADED_betaflight.csv
echo "replay_speed.sh: $log, $(($(wc -c < "$log") / 1000000)) MB"
controllers=HP-MLADRC,LP-MLADRC,LADRC,RATE-ADRC,CASCADED,INDI
scenario=$out/six.ini
{
  sed '/^\[controller/,$d' scenarios/logs/ordinary_flight.ini | sed "s/^controllers = .*/controllers = ${controllers//,/ }/"
  for c in ${controllers//,/ }; do printf '[controller %s]\ntune = margins\n' "$c"; done
} > "$scenario"
run=("$bin/ladrc_replay" "$log" --scenario "$scenario" --every 0 --quiet --out "$out/replay")
if command -v /usr/bin/time > /dev/null 2>&1; then
  /usr/bin/time -f "replay_speed.sh: peak resident memory %M KiB, wall %e s" "${run[@]}" > "$out/replay.txt" || true
else
  "${run[@]}" > "$out/replay.txt" || true
fi
grep -E "identified in|^replayed" "$out/replay.txt"
