#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A jump in a log's time (docs/flight-logs.md, "Gaps in time"): ladrc_replay and
# ladrc_margins --from-log skip a gap of 3 h or of 1e9 s instead of interpolating it
# (10.8 million and 1e12 ticks), so the ticks and the rows written stay those of the log's
# rows; they say so (the warning, the summary's status), and so does ladrc_filter; a log whose gaps are all a few
# dropped rows is interpolated as before, with no warning. Counts, never wall-clock time:
# the timeouts (120 s; each run takes seconds) only keep a regression from hanging the run.
# Usage: log_gap_cli_test.sh LADRC_REPLAY LADRC_SIL LADRC_MARGINS LADRC_FILTER
set -uo pipefail
replay=$1
sil=$2
margins=$3
filter=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "log_gap_cli_test.sh:$1:PASS"; else echo "log_gap_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}
rows=4000     # the flight's log: 4 s at 1 kHz
warning_of() { # the gap's length as printed: the warning's line for it
    echo "1 gap(s) in the log's time longer than 100 row periods skipped, not interpolated ($1 s in all): what spans one restarts after it"
}

# A chirp on every axis of LADRC, at its default gains (no tuning: fast), logged in the generic form.
cat > "$work/flight.ini" <<'INI'
[run]
duration_s = 4
control_dt_s = 0.001
controllers = LADRC
log = generic
[rotors]
motor_tau_s = 0.03
[sensors]
rate_noise_std_deg_s = 0.3
use_rate = yes
[excitation]
axis = all
amplitude = 0.2 0.2 0.4
f0_hz = 1
f1_hz = 40
start_s = 0.5
duration_s = 1
INI
"$sil" "$work/flight.ini" --out "$work/flight" --quiet > /dev/null 2>&1
rc=$?
log=$work/flight/flight/LADRC_log.csv
[ $rc -eq 0 ] && [ -f "$log" ] && [ "$(($(grep -vc '^#' "$log") - 1))" -eq $rows ]
check simulator_writes_the_log $?

# The rows after the first half shifted in time by $1 seconds (3 decimals: the log's milliseconds).
shifted() { # seconds, output
    awk -F, -v gap="$1" -v half=$((rows / 2)) 'BEGIN { OFS = "," }
        /^#/ { print; next } n++ == 0 { print; next } n > half + 1 { $1 = sprintf("%.3f", $1 + gap) } { print }' \
        "$log" > "$2"
}
shifted 10800 "$work/gap3h.csv"
shifted 1e9 "$work/gap1e9.csv"

for case in "gap3h 10800" "gap1e9 1e+09"; do
    set -- $case
    name=$1
    timeout 120 "$replay" "$work/$name.csv" --format generic --scenario "$work/flight.ini" --out "$work/$name" \
        --quiet > "$work/$name.txt" 2>&1
    rc=$?
    [ $rc -eq 0 ] && grep -q "^$work/$name.csv: $rows rows in 1 file(s), $rows ticks at 0.001 s" "$work/$name.txt" &&
      grep -qF "warning: $work/$name.csv: $(warning_of "$2")" "$work/$name.txt" &&
      grep -q "^replayed $rows ticks" "$work/$name.txt"
    check "${name}_replay_ticks_bounded_by_rows_and_warned" $?
    # replay.csv: the header and a row per tick; the noise file: a comment, a header and a row per tick
    [ $rc -eq 0 ] && [ "$(wc -l < "$work/$name/replay.csv")" -eq $((rows + 1)) ] &&
      [ "$(wc -l < "$work/$name/airframe_noise.csv")" -eq $((rows + 2)) ]
    check "${name}_rows_written_bounded_by_rows" $?
    [ $rc -eq 0 ] && [ "$(grep -c ',replayed; restarted after 1 skipped gap(s) in the log.s time$' \
                          "$work/$name/replay_summary.csv")" -eq 6 ]
    check "${name}_summary_says_the_restart" $?
done

timeout 120 "$replay" "$work/gap1e9.csv" --format generic --identify-only --out "$work/ident" --quiet \
    > "$work/ident.txt" 2>&1
[ $? -eq 0 ] && grep -q "^$work/gap1e9.csv: $rows rows in 1 file(s), $rows ticks" "$work/ident.txt" &&
  grep -qF "$(warning_of 1e+09)" "$work/ident.txt" && [ -f "$work/ident/identification.csv" ]
check identify_only_ticks_bounded_and_warned $?

timeout 120 "$margins" --from-log "$work/gap1e9.csv" --format generic --controllers LADRC > "$work/margins.txt" 2>&1
[ $? -eq 0 ] && grep -qF "warning: $work/gap1e9.csv: $(warning_of 1e+09)" "$work/margins.txt" &&
  grep -q "^identification at 1000 Hz" "$work/margins.txt"
check margins_from_log_ends_and_warns $?

timeout 120 "$filter" "$work/gap1e9.csv" --format generic > "$work/filter.txt" 2>&1
[ $? -eq 0 ] && grep -q "^$work/gap1e9.csv: $rows ticks at 0.001 s" "$work/filter.txt" &&
  grep -qF "warning: $work/gap1e9.csv: $(warning_of 1e+09)" "$work/filter.txt"
check filter_ticks_bounded_and_warned $?

# Five rows dropped (a gap of 6 row periods, as a blackbox log drops frames): interpolated,
# one tick per millisecond as before, no warning, the summary's status unchanged.
awk -v at=$((rows / 2 + 2)) 'NR < at || NR > at + 4' "$log" > "$work/dropped.csv"
timeout 120 "$replay" "$work/dropped.csv" --format generic --scenario "$work/flight.ini" --out "$work/dropped" \
    --quiet > "$work/dropped.txt" 2>&1
[ $? -eq 0 ] &&
  grep -q "^$work/dropped.csv: $((rows - 5)) rows in 1 file(s), $rows ticks at 0.001 s, .*, 1 gap(s) interpolated over (longest 0.006 s)$" \
      "$work/dropped.txt" &&
  ! grep -q "skipped" "$work/dropped.txt" && [ "$(wc -l < "$work/dropped/replay.csv")" -eq $((rows + 1)) ] &&
  [ "$(grep -c ',replayed$' "$work/dropped/replay_summary.csv")" -eq 6 ]
check short_gap_interpolated_as_before $?

if [ $failures -ne 0 ]; then
    echo "log_gap_cli_test.sh: $failures check(s) failed (outputs in $work kept)"
    trap - EXIT
    exit 1
fi
echo "log_gap_cli_test.sh: all passed"
