#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of the ladrc_sil command: results independent of --jobs,
# malformed scenarios and runs outside the limits rejected with
# file:line:column and nothing written, diverged runs reported with exit 3.
# Usage: cli_test.sh LADRC_SIL SCENARIO_DIR
set -uo pipefail
sil=$1
scenarios=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
checks=0
check() { # name, condition exit code
    checks=$((checks + 1))
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
# the paper's four, CASCADED and INDI: six series, metrics.csv and signals.csv
[ "$(ls "$work/j1/paper" | wc -l)" -eq 8 ] && grep -q "^disturbance,yaw,3,12,25$" "$work/j1/paper/signals.csv"; check writes_a_series_per_controller_and_metrics $?

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

# Divergence: exit 3 after writing every output; stderr names scenario,
# controller, axis, time and cause; metrics.csv says "diverged", never numbers.
printf '[run]\nduration_s = 5\ncontrollers = LADRC PID\n[reference]\nroll = 10\n[rotors]\nmotor_tau_s = 0.3\n' \
    > "$work/lag.ini"
"$sil" "$work/lag.ini" --out "$work/lag_out" --quiet > "$work/lag.txt" 2> "$work/lag.err"
[ $? -eq 3 ]; check diverged_run_exits_3 $?
grep -q "^ladrc_sil: lag (.*lag.ini): controller PID diverged at t = [0-9.]* s on roll: |tracking error| 9[0-9.]* deg exceeds diverge_limit_deg = 90$" \
    "$work/lag.err"; check diverged_run_named_on_stderr $?
[ -s "$work/lag_out/lag/PID.csv" ] && [ -s "$work/lag_out/lag/LADRC.csv" ] && grep -q "^PID: DIVERGED: " "$work/lag.txt"
check diverged_run_outputs_written $?
# every statistic of PID: the token; then its time, which its time series stops short of
awk -F, '$2 == "PID" && $3 != "-" && $6 != "diverged" { bad = 1 } $2 == "PID" && $3 != "-" { n++ }
    END { exit (bad || n != 33) }' "$work/lag_out/lag/metrics.csv"; check diverged_statistics_are_tokens $?
at=$(awk -F, '$2 == "PID" && $4 == "diverged_at_s" && $5 == "roll" { print $6 }' "$work/lag_out/lag/metrics.csv")
last=$(tail -n 1 "$work/lag_out/lag/PID.csv" | cut -d, -f1)
[ -n "$at" ] && awk -v a="$at" -v l="$last" 'BEGIN { exit !(a > 0 && l < a && a - l < 0.0015) }'
check diverged_series_ends_at_divergence $?

# A slow, finite growth (LADRC not modelling a 55 ms motor lag: about x1.3 per
# second from 5 deg) is caught at the limit, not at overflow.
printf '[run]\nduration_s = 15\ncontrollers = LADRC\n[reference]\nroll = 5\n[rotors]\nmotor_tau_s = 0.055\n[controller LADRC]\nmodel_motor_tau_s = 0\n' \
    > "$work/slow.ini"
"$sil" "$work/slow.ini" --out "$work/slow_out" --no-csv --quiet > /dev/null 2> "$work/slow.err"
rc=$?
[ "$rc" -eq 3 ] && grep -q "controller LADRC diverged at t = 1[0-4]\.[0-9]* s on .* exceeds diverge_limit_deg" "$work/slow.err" &&
  grep -q "^slow,LADRC,-,finite,-,1$" "$work/slow_out/slow/metrics.csv" &&
  grep -q "^slow,LADRC,-,diverged,-,1$" "$work/slow_out/slow/metrics.csv"
check slow_finite_growth_caught_at_limit $?

# A non-finite state; and a healthy scenario beside a diverging one still gets its outputs.
printf '[run]\nduration_s = 3\ncontrollers = PID\n[disturbance]\nroll = 1.5 .. 3 : 1e300 * 1e300\n' > "$work/inf.ini"
"$sil" "$work/inf.ini" "$work/slow_loop.ini" --out "$work/inf_out" --no-csv --quiet > /dev/null 2> "$work/inf.err"
rc=$?
[ "$rc" -eq 3 ] && grep -q "controller PID diverged at t = 1.5010 s: the state turned non-finite (roll angle or rate)" \
    "$work/inf.err" && grep -q "^inf,PID,-,finite,-,0$" "$work/inf_out/inf/metrics.csv" &&
  grep -q "^slow_loop,PID,-,diverged,-,0$" "$work/inf_out/slow_loop/metrics.csv"
check non_finite_state_diverges $?

# Healthy runs exit 0 and say so.
"$sil" "$work/slow_loop.ini" --out "$work/ok_out" --quiet > /dev/null 2> "$work/ok.err"
[ $? -eq 0 ] && ! grep -q diverged "$work/ok.err" && grep -q "^slow_loop,PID,-,diverged_at_s,-,-$" "$work/ok_out/slow_loop/metrics.csv"
check healthy_run_exits_0 $?
refused diverge_limit_zero_exits_2 2:21: '[metrics]\ndiverge_limit_deg = 0\n'

# --set and --seed: the value replaces the file's; the same results as a file
# that says it; a bad setting is named as such, exit 2, nothing written.
printf '[run]\nduration_s = 0.5\nseed = 3\ncontrollers = LADRC PID\n[reference]\nroll = 4\n[sensors]\nangle_noise_std_deg = 0.1\n' \
    > "$work/base.ini"
mkdir -p "$work/edited"
printf '[run]\nduration_s = 0.5\nseed = 11\ncontrollers = LADRC PID\n[reference]\nroll = 0 .. 0.2 : 2\n[sensors]\nangle_noise_std_deg = 0.1\n[controller LADRC]\nwc_rad_s = 20\n' \
    > "$work/edited/base.ini"
"$sil" "$work/base.ini" --seed 11 --set "controller:LADRC.wc_rad_s=20" --set "reference.roll=0..0.2: 2" \
    --out "$work/set_cli" --quiet > "$work/set_cli.txt" 2>&1
rc=$?
"$sil" "$work/edited/base.ini" --out "$work/set_file" --quiet > "$work/set_file.txt" 2>&1
[ $rc -eq 0 ] && [ $? -eq 0 ] && diff -r "$work/set_cli" "$work/set_file" > /dev/null
check set_and_seed_equal_the_edited_file $?
"$sil" "$work/base.ini" --out "$work/set_plain" --quiet > /dev/null 2>&1
! cmp -s "$work/set_plain/base/LADRC.csv" "$work/set_cli/base/LADRC.csv"; check set_changes_the_run $?
"$sil" "$work/base.ini" --set "run.seed=11" --set "controller LADRC.wrap_yaw=maybe" --out "$work/set_bad" \
    --quiet > /dev/null 2> "$work/set_bad.err"
[ $? -eq 2 ] && [ ! -e "$work/set_bad" ] &&
  grep -q "^ladrc_sil: --set 2 'controller LADRC.wrap_yaw=maybe':27: expected yes or no, got 'maybe'" "$work/set_bad.err"
check bad_set_named_exits_2_writes_nothing $?
"$sil" "$work/base.ini" --seed 1x --out "$work/seed_bad" --quiet > /dev/null 2> "$work/seed_bad.err"
[ $? -eq 2 ] && [ ! -e "$work/seed_bad" ] && grep -q "^ladrc_sil: --seed '1x':1: expected an unsigned integer" "$work/seed_bad.err"
check bad_seed_named_exits_2 $?

# --controllers takes the file's list rule: commas, spaces or both.
"$sil" "$work/base.ini" --controllers "PID LADRC" --out "$work/list_sp" --quiet > /dev/null 2>&1 &&
  "$sil" "$work/base.ini" --controllers "PID, LADRC" --out "$work/list_cm" --quiet > /dev/null 2>&1 &&
  diff -r "$work/list_sp" "$work/list_cm" > /dev/null &&
  [ "$(cut -d, -f2 "$work/list_sp/base/metrics.csv" | sed 1d | uniq | tr '\n' ' ')" = "PID LADRC " ]
check controllers_list_spaces_or_commas $?

# Two scenarios writing the same directory: refused, both named, nothing written.
mkdir -p "$work/a" "$work/b"
cp "$work/base.ini" "$work/a/x.ini"; cp "$work/base.ini" "$work/b/x.ini"
sil_abs=$(cd "$(dirname "$sil")" && pwd)/$(basename "$sil")
(cd "$work" && "$sil_abs" a/x.ini b/x.ini --quiet > /dev/null 2> "$work/collide.err")
rc=$?
[ $rc -eq 2 ] && [ ! -e "$work/out" ] && grep -q "a/x.ini and b/x.ini would both write 'out/x'" "$work/collide.err"
check output_collision_refused_before_writing $?
"$sil" "$work/a/x.ini" "$work/b/x.ini" --out "$work/collide_out" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/collide_out" ]; check output_collision_under_out_refused $?
printf '[run]\nduration_s = 0.2\noutput_dir = %s/same/\n' "$work" > "$work/p.ini"
printf '[run]\nduration_s = 0.2\noutput_dir = %s//same\n' "$work" > "$work/q.ini"
"$sil" "$work/p.ini" "$work/q.ini" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/same" ]; check output_collision_same_dir_spelled_apart $?

# The time series: a unit on every column (docs/csv-format.md), as many
# fields per row as names; the measured angle is the noisy one, the true one
# is not; the saturation flags are 0 or 1 and some are raised on limited rotors.
printf '[run]\nduration_s = 0.5\ncontrollers = LADRC PID\n[rotors]\nideal = no\nw2_max_rad2_s2 = 90000\n[reference]\nroll = 0.1 .. : 30\n[sensors]\nangle_noise_std_deg = 0.05\n' \
    > "$work/sat.ini"
"$sil" "$work/sat.ini" --out "$work/sat_out" --quiet > /dev/null 2>&1
check csv_run_succeeds $?
head -n 1 "$work/sat_out/sat/LADRC.csv" | tr , '\n' |
  grep -Ev '(_s|_deg|_Nm|_rad_s2|_rad2_s2|_deg_s|_m_s2|_flag|_count|_frac|_ratio)$' | grep -q . && bad=1 || bad=0
check csv_every_column_has_a_unit $bad
awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || n != 87 }' "$work/sat_out/sat/PID.csv"
check csv_rows_as_wide_as_the_header $?
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { if ($c["meas_angle_pitch_deg"] != 0) noisy = 1; if ($c["angle_pitch_deg"] != $c["meas_angle_pitch_deg"]) apart = 1
      for (f in c) if (f ~ /_flag$/) { if ($c[f] != 0 && $c[f] != 1) bad = 1; if ($c[f] == 1) raised = 1 } }
    END { exit !(noisy && apart && raised && !bad) }' "$work/sat_out/sat/LADRC.csv"
check csv_measured_angle_noisy_and_flags_raised $?

# Recorded series: a file of 2 sin(3 t) rad/s^2 on roll at 1 ms flies as the
# expression does (linear between rows: within 2e-7 rad/s^2 of the sine, so
# the angles agree far below the 1e-4 deg the check allows); the same file
# gives byte-identical outputs; the noise series reach the measured rate; a
# bad unit is an error at the file's line and column, status 2, nothing written.
awk 'BEGIN { print "t [s], roll [rad/s^2]"; for (k = 0; k <= 1000; k++) printf "%.3f, %.17g\n", k / 1000, 2 * sin(3 * k / 1000) }' \
    > "$work/sine.csv"
printf 't [s], roll [deg/s], pitch [deg/s], yaw [deg/s]\n0, 0, 0, 0\n0.5, 2, 0, 0\n1, 0, 0, 0\n' > "$work/rate_noise.csv"
base='[run]\nduration_s = 1\ncontrollers = LADRC\nseed = 3\n'
printf "$base[disturbance]\nroll = 2*sin(3*t)\n" > "$work/expr.ini"
printf "$base[disturbance]\nseries = sine.csv\n" > "$work/rec.ini"
printf "$base[disturbance]\nseries = sine.csv\n[sensors]\nrate_noise_series = rate_noise.csv\n" > "$work/noise.ini"
"$sil" "$work/expr.ini" --out "$work/s_expr" --quiet > /dev/null 2>&1 &&
  "$sil" "$work/rec.ini" --out "$work/s_rec1" --quiet > /dev/null 2>&1 &&
  "$sil" "$work/rec.ini" --out "$work/s_rec2" --quiet > /dev/null 2>&1 &&
  "$sil" "$work/noise.ini" --out "$work/s_noise" --quiet > /dev/null 2>&1
check series_runs_succeed $?
paste -d, "$work/s_expr/expr/LADRC.csv" "$work/s_rec1/rec/LADRC.csv" | awk -F, '
    NR == 1 { n = NF / 2; for (i = 1; i <= n; i++) c[$i] = i; next }
    { d = $c["angle_roll_deg"] - $(n + c["angle_roll_deg"]); if (d < 0) d = -d; if (d > worst) worst = d }
    END { exit !(NR > 900 && worst <= 1e-4) }'
check series_flies_as_its_expression $?
diff -r "$work/s_rec1/rec" "$work/s_rec2/rec" > /dev/null; check series_same_file_byte_identical $?
# LADRC reads no rate, so the two runs fly alike and their measured rates
# differ by the series alone: 0 -> 2 -> 0 deg/s, linear over (0, 1] s (each
# rate printed to 6 significant digits of at most 2.2 deg/s: 1e-5 apiece)
paste -d, "$work/s_rec1/rec/LADRC.csv" "$work/s_noise/noise/LADRC.csv" | awk -F, '
    NR == 1 { n = NF / 2; for (i = 1; i <= n; i++) c[$i] = i; next }
    { t = $c["t_s"]; want = t < 0.5 ? 4 * t : 4 * (1 - t)
      d = $(n + c["meas_rate_roll_deg_s"]) - $c["meas_rate_roll_deg_s"] - want; if (d < 0) d = -d; if (d > worst) worst = d }
    END { exit !(NR > 900 && worst <= 2e-5) }'
check series_noise_reaches_the_measured_rate $?
printf 't [s], roll [deg/s]\n0, 1\n1, 2\n' > "$work/bad_unit.csv"
printf "$base[disturbance]\nseries = bad_unit.csv\n" > "$work/bad_series.ini"
"$sil" "$work/bad_series.ini" --out "$work/s_bad" --quiet > /dev/null 2> "$work/s_bad.err"
rc=$?
[ $rc -eq 2 ] && [ ! -e "$work/s_bad" ] &&
  grep -q "bad_unit.csv:1:13: unit \[deg/s\] is an angular rate; key series wants an angular acceleration" "$work/s_bad.err" &&
  grep -q "(the file of series, .*bad_series.ini line 6)" "$work/s_bad.err"
check series_bad_unit_at_its_place_nothing_written $?
# A series that is one of the run's own outputs (LADRC.csv in the output
# folder): refused before anything is written, the series left as it was.
mkdir -p "$work/s_own/own_series"
cp "$work/sine.csv" "$work/s_own/own_series/LADRC.csv"
printf "$base[disturbance]\nseries = s_own/own_series/LADRC.csv\n" > "$work/own_series.ini"
"$sil" "$work/own_series.ini" --out "$work/s_own" --quiet > /dev/null 2> "$work/s_own.err"
rc=$?
[ $rc -eq 2 ] && cmp -s "$work/sine.csv" "$work/s_own/own_series/LADRC.csv" &&
  [ ! -e "$work/s_own/own_series/metrics.csv" ] &&
  grep -q "the input is the output .*LADRC.csv of this run" "$work/s_own.err"
check series_that_is_an_output_refused_and_kept $?

echo "$(( checks - failures )) passed, $failures failed"
[ "$failures" -eq 0 ]
