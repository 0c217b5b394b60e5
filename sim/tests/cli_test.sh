#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of the ladrc_sil command: results independent of --jobs,
# malformed scenarios and runs outside the limits rejected with
# file:line:column and nothing written.
# Usage: cli_test.sh LADRC_SIL SCENARIO_DIR
set -uo pipefail
sil=$1
scenarios=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "cli_test.sh:$1:PASS"; else echo "cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

# Same results with 1 and 2 jobs: tables, metrics and every time series, bit for bit.
"$sil" "$scenarios/paper.ini" --jobs 1 --out "$work/j1" --quiet > "$work/j1.txt"
rc1=$?
"$sil" "$scenarios/paper.ini" --jobs 2 --out "$work/j2" --quiet > "$work/j2.txt"
rc2=$?
check runs_succeed $(( rc1 + rc2 ))
cmp -s "$work/j1.txt" "$work/j2.txt"; check tables_identical_for_1_and_2_jobs $?
diff -r "$work/j1" "$work/j2" > /dev/null; check outputs_identical_for_1_and_2_jobs $?
[ "$(ls "$work/j1/paper" | wc -l)" -eq 5 ]; check writes_four_series_and_metrics $?

# --controllers flies only the listed controllers, in the list's order, with
# the results each has in the full run, series included.
"$sil" "$scenarios/paper.ini" --controllers PID,HP-MLADRC --jobs 2 --out "$work/sub" --quiet > /dev/null
check controllers_subset_runs $?
[ "$(cut -d, -f2 "$work/sub/paper/metrics.csv" | sed 1d | uniq | tr '\n' ' ')" = "PID HP-MLADRC " ]
check controllers_subset_writes_only_those $?
grep -E '^paper,(PID|HP-MLADRC),' "$work/j1/paper/metrics.csv" | sort > "$work/full_sub.csv"
sed 1d "$work/sub/paper/metrics.csv" | sort > "$work/sub_only.csv"
cmp -s "$work/full_sub.csv" "$work/sub_only.csv" && cmp -s "$work/j1/paper/PID.csv" "$work/sub/paper/PID.csv" &&
  [ ! -e "$work/sub/paper/LADRC.csv" ]
check controllers_subset_results_identical_to_full_run $?
"$sil" "$scenarios/paper.ini" --controllers PID,XYZ --out "$work/badc" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/badc" ]; check unknown_controller_exits_2 $?

# A malformed scenario: exit 2, the error names file:line:column, nothing written.
printf '[run]\nduration_s = 3\ncontrol_dt_s = 0.001\n[reference]\nroll = 5 + * 2\n' > "$work/bad.ini"
"$sil" "$work/bad.ini" --out "$work/bad_out" --quiet > /dev/null 2> "$work/bad.err"
rc=$?
[ "$rc" -eq 2 ]; check malformed_exits_2 $?
grep -q "bad.ini:5:" "$work/bad.err"; check malformed_error_names_file_and_line $?
[ ! -e "$work/bad_out" ]; check malformed_writes_nothing $?

# A good and a bad file together: still nothing runs.
"$sil" "$scenarios/paper.ini" "$work/bad.ini" --out "$work/mixed" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/mixed" ]; check one_bad_file_stops_all $?

"$sil" --jobs zero "$scenarios/paper.ini" > /dev/null 2>&1
[ $? -eq 2 ]; check bad_option_exits_2 $?

# Runs the simulator cannot fly are scenario errors: exit 2 at file:line:column,
# nothing written, and no endless run (timeout: the check fails, not the suite).
refused() { # name, expected "file:line:column:", scenario text, options...
    local name=$1 where=$2 text=$3
    shift 3
    printf "$text" > "$work/$name.ini"
    timeout 60 "$sil" "$work/$name.ini" --out "$work/${name}_out" --quiet "$@" > /dev/null 2> "$work/$name.err"
    local rc=$?
    [ "$rc" -eq 2 ] && grep -q "^$work/$name.ini:$where " "$work/$name.err" && [ ! -e "$work/${name}_out" ]
    check "$name" $?
}
refused tiny_control_dt_exits_2 3:16: '[run]\nduration_s = 1\ncontrol_dt_s = 1e-300\n'
refused endless_duration_exits_2 2:14: '[run]\nduration_s = 1e9\n'
refused endless_substeps_exits_2 3:18: '[run]\nduration_s = 1\nplant_substeps = 1000000000\n'
refused too_many_control_periods_exits_2 3:16: '[run]\nduration_s = 1e5\ncontrol_dt_s = 1e-5\n'
refused controller_the_library_refuses_exits_2 3:16: '[run]\nduration_s = 1\ncontrol_dt_s = 0.05\n'
# a controller the file does not list, chosen on the command line
refused chosen_controller_checked_exits_2 3:16: '[run]\nduration_s = 1\ncontrol_dt_s = 0.05\ncontrollers = PID\n' \
    --controllers PID,HP-MLADRC
printf '[run]\nduration_s = 1\ncontrol_dt_s = 0.05\ncontrollers = PID\n' > "$work/slow_loop.ini"
"$sil" "$work/slow_loop.ini" --out "$work/slow_loop_out" --quiet > /dev/null
check listed_controllers_fly_at_20_hz $?
"$sil" "$scenarios/paper.ini" --controllers PID,PID --out "$work/twice" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/twice" ]; check controller_listed_twice_exits_2 $?

echo "$(( 21 - failures )) passed, $failures failed"
[ "$failures" -eq 0 ]
