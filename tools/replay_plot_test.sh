#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ctest check of tools/replay_plot.py and tools/response_plot.py on a simulator replay: the
# ordinary flight (scenarios/logs) cut to 16 s with a throttle that varies, written as a
# Betaflight log, replayed with CASCADED and LADRC; every figure comes out, every figure takes a
# controller's colour from the one palette, and one landing spike does not set the y range.
# Then the closed-loop path (tools/closed_loop_views.py): the log's setpoints as a series
# (ladrc_views --reference), two controllers flown on the identified airframe with them, their
# views beside the log's.
# Usage: replay_plot_test.sh LADRC_SIL LADRC_REPLAY LADRC_VIEWS SOURCE_DIR
# Exit status 77 (reported by ctest as skipped) when matplotlib or numpy is missing.
set -uo pipefail
sil=$1
replay=$2
views=$3
src=$4

py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
if ! "$py" -c 'import matplotlib, numpy' >/dev/null 2>&1; then
  echo "SKIPPED: $py cannot import matplotlib and numpy (apt-get install python3-matplotlib python3-numpy)"
  exit 77
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
  if [[ $2 -eq 0 ]]; then echo "replay_plot_test.sh:$1:PASS"; else echo "replay_plot_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

"$sil" "$src/scenarios/logs/ordinary_flight.ini" --set "run.duration_s=16" \
  --set "reference.throttle=0.3 + 0.25*sin(0.4*t)" --out "$work/sil" --quiet > /dev/null
check simulator_writes_the_log $?
log="$work/sil/ordinary_flight/CASCADED_betaflight.csv"
"$replay" "$log" --scenario "$src/scenarios/logs/ordinary_flight.ini" --controllers "CASCADED LADRC" --every 5 \
  --quiet --out "$work/r" > "$work/replay.txt" 2>&1
rc=$?
[[ $rc -eq 0 || $rc -eq 1 ]]; check replay_runs $?
for f in step_response freq_response noise_throttle response_summary; do
  [[ $(wc -l < "$work/r/$f.csv") -gt 3 ]]; check "replay_writes_$f" $?
done
# the log's roll: some windows reach 20 deg/s; its noise spans several tenths of throttle
awk -F, '$1 == "LOG" && $2 == "roll" && $3 > 0 { ok = 1 } END { exit !ok }' "$work/r/response_summary.csv"
check step_response_has_windows $?
[[ $(awk -F, 'NR > 1 && $2 == "gyro_deg_s" { print $4 }' "$work/r/noise_throttle.csv" | sort -u | wc -l) -ge 3 ]]
check noise_spans_the_throttle $?
grep -q "^step response LOG roll: " "$work/replay.txt"; check replay_prints_the_step_response $?

"$py" "$src/tools/replay_plot.py" "$work/r" > /dev/null
check replay_plot_succeeds $?
# 0 when file is a PNG (signature) of at least width x height pixels (IHDR) and more than bytes.
png_ok() { # file, width, height, bytes
  [[ -f $1 ]] || return 1
  local hdr w h size
  read -r -a hdr < <(od -An -tu1 -N24 "$1" | tr -s ' \n' ' ')
  w=$(( (hdr[16] << 24) | (hdr[17] << 16) | (hdr[18] << 8) | hdr[19] ))
  h=$(( (hdr[20] << 24) | (hdr[21] << 16) | (hdr[22] << 8) | hdr[23] ))
  size=$(wc -c < "$1")
  [[ ${hdr[1]} -eq 80 && ${hdr[2]} -eq 78 && ${hdr[3]} -eq 71 && $w -ge $2 && $h -ge $3 && $size -gt $4 ]]
}
for fig in replay_commands replay_spectrum response_step response_freq response_noise; do
  png_ok "$work/r/$fig.png" 1000 400 20000
  check "$fig" $?
done

# One palette: figures.py's colours are plot_style's, a controller's file name finds its colour,
# and a landing spike of 1000x the command in one row leaves the y range at the bulk of the flight.
PYTHONPATH="$src/tools" "$py" - "$work/r" <<'PY'
import os
import sys
import numpy as np
import figures
import plot_style
import replay_plot
assert figures.COLOURS is plot_style.COLOURS
assert plot_style.colour_of("LADRC_roll") == plot_style.COLOURS["LADRC"]
assert plot_style.colour_of("LP-MLADRC") == plot_style.COLOURS["LP-MLADRC"]
assert plot_style.colour_of("LOG") == plot_style.LOG_COLOUR and plot_style.colour_of("other") is None
d = replay_plot.read_columns(os.path.join(sys.argv[1], "replay.csv"))
bulk = max(np.nanmax(np.abs(d[k])) for k in d if "_cmd_roll" in k)
d["LOG_cmd_roll"][len(d["t_s"]) // 2] = 1000.0 * bulk
lo, hi = replay_plot.commands_figure(d, os.path.join(sys.argv[1], "spike.png"), 0.0, 0.0)[0]
assert hi < 2.0 * bulk, (hi, bulk)
PY
check one_palette_and_a_spike_does_not_set_the_range $?

# The setpoints as a series: one row a tick (1 kHz) over the 16 s, the header's units; a log
# without a setpoint is refused and leaves nothing.
"$views" --reference "$work/ref.csv" "$log" > /dev/null
check views_writes_the_reference $?
rows=$(grep -c '^[0-9]' "$work/ref.csv")
[[ $rows -ge 15900 && $rows -le 16001 ]] && grep -q '^t \[s\], roll \[rad\], pitch \[rad\], yaw \[rad\]$' "$work/ref.csv"
check reference_has_a_row_a_tick $?
# the log without its setpoint[0..2] columns
awk -F', *' 'NR == 1 { for (i = 1; i <= NF; ++i) drop[i] = ($i ~ /^setpoint\[[012]\]/) }
  { out = ""; for (i = 1; i <= NF; ++i) if (!drop[i]) out = out (out == "" ? "" : ",") $i; print out }' \
  "$log" > "$work/no_setpoint.csv"
"$views" --reference "$work/ref2.csv" "$work/no_setpoint.csv" > /dev/null 2> "$work/refused.txt"
[[ $? -eq 2 && ! -e $work/ref2.csv && ! -e $work/ref2.csv.tmp ]] && grep -q "has no setpoint" "$work/refused.txt"
check views_refuses_a_log_without_setpoint $?

# Closed loop: LADRC and CASCADED on the identified airframe with the log's first 8 s of setpoints.
bin="$work/bin"
mkdir -p "$bin" && ln -s "$sil" "$bin/ladrc_sil" && ln -s "$views" "$bin/ladrc_views"
"$py" "$src/tools/closed_loop_views.py" "$work/r" "$log" --seconds 8 --controllers "LADRC CASCADED" --bin "$bin" \
  > "$work/closed.txt" 2>&1
check closed_loop_views_succeeds $?
for src_name in LOG LADRC CASCADED; do
  grep -q "^$src_name,roll," "$work/r/closed_loop/response_summary.csv"
  check "closed_loop_has_$src_name" $?
done
png_ok "$work/r/closed_loop/response_step.png" 1000 400 20000
check closed_loop_step_figure $?

echo "$failures failed"
[[ $failures -eq 0 ]]
