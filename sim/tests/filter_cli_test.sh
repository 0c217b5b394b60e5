#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of ladrc_filter on logs the simulator writes: the
# library's stage run over a log's gyro before its filters gives the log's
# own filtered gyro when it is the flight's stage (--filter-from the flight's
# scenario); the proposal notches the vibration lines; bad input exits 2
# naming what is missing, and writes nothing.
# Usage: filter_cli_test.sh LADRC_FILTER LADRC_SIL
set -uo pipefail
filter=$1
sil=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "filter_cli_test.sh:$1:PASS"; else echo "filter_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

# A 4 s flight with rotor-order vibration on the gyro and the library's stage (a low-pass and a
# notch) before the controller, written as a generic log (both gyros, 9 digits) and a Betaflight one.
cat > "$work/flight.ini" <<'INI'
[run]
duration_s = 4
controllers = LADRC
log = generic betaflight
[sensors]
angle_noise_std_deg = 0.05
rate_noise_std_deg_s = 0.3
use_rate = yes
[vibration]
orders = 1 2
gyro_deg_s = 1.0 0.5
[filter]
lpf_order = 2
lpf_hz = 90
notch_hz = 160
notch_q = 4
[reference]
roll = 1 .. 3 : 10
INI
"$sil" "$work/flight.ini" --out "$work/fl" --quiet > /dev/null 2>&1
log="$work/fl/flight/LADRC_log.csv"
[ $? -eq 0 ] && [ -f "$log" ] && [ -f "$work/fl/flight/LADRC_betaflight.csv" ]
check simulator_writes_its_logs $?

# The flight's own stage over the log's gyro before the filters is the log's filtered gyro. The
# flight's filter starts at rest on 0 and this one at rest on the first sample; the notch's and
# the low-pass's memories (Q 4 at 160 Hz: 8 ms; 90 Hz: 2.5 ms) forget that difference within
# 0.1 s, after which both run the same float operations on the same float inputs: 1e-6 rad/s
# allows the last bits of the differing start (float's spacing at 1 rad/s is 1.2e-7; 0 measured).
"$filter" "$log" --filter-from "$work/flight.ini" --out "$work/same.csv" > "$work/same.txt" 2>&1
check filter_from_the_flight_runs $?
worst=$(paste -d, "$work/same.csv" "$log" | awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "gyro[0]") g = i; next }
    $1 >= 0.5 { for (i = 0; i < 3; ++i) { d = $(5 + i) - $(g + i); if (d < 0) d = -d; if (d > m) m = d } } END { printf "%.9g\n", m + 0 }')
echo "largest difference from the log's filtered gyro after 0.5 s: $worst rad/s"
le "$worst" 1e-6
check the_flights_stage_gives_the_logs_filtered_gyro $?
# and the two chains leave the same rms in the vibration band (printed to 4 decimals, deg/s)
awk '/^  this stage/ { a = $6 } /^  the log.s chain/ { b = $7; d = a - b; if (d < 0) d = -d; if (d > m) m = d; n++ }
    END { exit !(n == 3 && m <= 0.0001) }' "$work/same.txt"
check the_two_chains_leave_the_same_band_rms $?

# The proposal on the Betaflight log: notches on the lines (the rotor speed is in its eRPM), more
# than 10 dB off the vibration band on every axis (15.7-17.6 dB measured; the flight's own stage
# takes 0.3-0.4 dB there: its low-pass sits above the lines).
"$filter" "$work/fl/flight/LADRC_betaflight.csv" > "$work/prop.txt" 2>&1
check proposal_runs $?
grep -q "notch" "$work/prop.txt"
check proposal_has_notches $?
awk '/^  this stage/ { n++; if ($7 < 10) bad++ } END { exit !(n == 3 && bad == 0) }' "$work/prop.txt"
check proposal_takes_the_band_down_10_db $?

# Refusals: exit 2, the place named, no output file.
"$filter" "$work/none.csv" --out "$work/x.csv" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "none.csv" "$work/err.txt" && [ ! -e "$work/x.csv" ]
check missing_log_refused $?
printf '[run]\nduration_s = 1\n' > "$work/nofilter.ini"
"$filter" "$log" --filter-from "$work/nofilter.ini" --out "$work/x.csv" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "no gyro filter stage" "$work/err.txt" && [ ! -e "$work/x.csv" ]
check scenario_without_filter_refused $?
"$filter" "$log" --rpm-harmonics 2 --out "$work/x.csv" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "rotor_hz" "$work/err.txt" && [ ! -e "$work/x.csv" ]
check rpm_without_rotor_speed_refused $?
"$filter" "$log" --dt 0.002 --filter-from "$work/flight.ini" --out "$work/x.csv" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "\-\-dt" "$work/err.txt" && [ ! -e "$work/x.csv" ]
check period_mismatch_refused $?
"$filter" "$log" --lpf 600 --out "$work/x.csv" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "refused" "$work/err.txt" && [ ! -e "$work/x.csv" ]
check lowpass_above_nyquist_refused $?
"$filter" "$log" --lpf 90 --filter-from "$work/flight.ini" > /dev/null 2> "$work/err.txt"
[ $? -eq 2 ] && grep -q "conflicts" "$work/err.txt"
check conflicting_options_refused $?

echo "filter_cli_test.sh: $failures failure(s)"
[ "$failures" -eq 0 ]
