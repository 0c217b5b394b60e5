#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of the ladrc_margins command and of tune = margins in
# ladrc_sil: the table is printed, --csv writes one file per controller and
# axis, bad files and options exit 2 naming the offending text, an unstable
# loop exits 1, a tuning whose targets cannot be met is an error of the file
# at its tune key.
# Usage: margins_cli_test.sh LADRC_MARGINS LADRC_SIL
set -uo pipefail
margins=$1
sil=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "margins_cli_test.sh:$1:PASS"; else echo "margins_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

# A stable loop: exit 0, one row per controller and axis with its margins.
printf '[run]\nduration_s = 1\ncontrollers = LADRC PID\n[rotors]\nmotor_tau_s = 0.002\n' > "$work/ok.ini"
"$margins" "$work/ok.ini" --controllers LADRC --csv "$work/csv" > "$work/ok.txt" 2> "$work/ok.err"
[ $? -eq 0 ]; check stable_loop_exits_0 $?
grep -q "^ok: dt 0.001 s, motor lag 0.002 s, sensor delay 0 ticks" "$work/ok.txt" &&
  [ "$(grep -c '^LADRC  *\(roll\|pitch\|yaw\) .* yes ' "$work/ok.txt")" -eq 3 ]
check prints_one_row_per_axis $?
ls "$work/csv" | sort | tr '\n' ' ' > "$work/csv.list"
[ "$(cat "$work/csv.list")" = "LADRC_pitch.csv LADRC_roll.csv LADRC_yaw.csv " ] &&
  head -n 1 "$work/csv/LADRC_roll.csv" | grep -q "^# gm_db=.* stable=1$" &&
  sed -n 2p "$work/csv/LADRC_roll.csv" | grep -q "^w_rad_s,L_re,L_im," &&
  [ "$(wc -l < "$work/csv/LADRC_roll.csv")" -eq 202 ]
check csv_writes_a_file_per_controller_and_axis $?

# Bad usage and bad files: exit 2, the offending text on stderr.
"$margins" "$work/ok.ini" --axis sideways > /dev/null 2> "$work/axis.err"
[ $? -eq 2 ] && grep -q "'sideways'" "$work/axis.err"; check bad_axis_exits_2 $?
"$margins" "$work/ok.ini" --frobnicate > /dev/null 2> "$work/opt.err"
[ $? -eq 2 ] && grep -q "'--frobnicate'" "$work/opt.err"; check bad_option_exits_2 $?
"$margins" "$work/ok.ini" --controllers LADRC,XYZ > /dev/null 2> "$work/ctl.err"
[ $? -eq 2 ] && grep -q "'XYZ'" "$work/ctl.err"; check bad_controller_exits_2 $?
printf '[run]\nduration_s = 1\n[rotors]\nmotor_tau_s = -1\n' > "$work/bad.ini"
"$margins" "$work/bad.ini" > /dev/null 2> "$work/bad.err"
[ $? -eq 2 ] && grep -q "bad.ini:4:15: motor_tau_s must be >= 0" "$work/bad.err"; check bad_file_exits_2_at_its_key $?
"$margins" "$work/missing.ini" > /dev/null 2> "$work/missing.err"
[ $? -eq 2 ] && grep -q "missing.ini: cannot open" "$work/missing.err"; check missing_file_exits_2 $?

# An unstable loop (PID's default gains behind a 30 ms motor lag): exit 1, NO in the table.
printf '[run]\nduration_s = 1\ncontrollers = PID\n[rotors]\nmotor_tau_s = 0.03\n' > "$work/unstable.ini"
"$margins" "$work/unstable.ini" --axis roll > "$work/unstable.txt" 2>&1
[ $? -eq 1 ] && grep -q "^PID  *roll .* NO " "$work/unstable.txt"; check unstable_loop_exits_1 $?

# tune = margins: the same loop tuned, analysed and flown with the tuned gains.
printf '[run]\nduration_s = 1\ncontrollers = PID\n[rotors]\nmotor_tau_s = 0.03\n[controller PID]\ntune = margins\n' \
    > "$work/tuned.ini"
"$margins" "$work/tuned.ini" --axis roll > "$work/tuned.txt" 2>&1
[ $? -eq 0 ] && grep -q "^tuned PID roll: kp .* -> PM 4[5-9]\.[0-9] deg (>= 45), GM" "$work/tuned.txt" &&
  grep -q "^PID  *roll .* yes " "$work/tuned.txt"
check tuned_loop_is_stable_and_printed $?
"$sil" "$work/tuned.ini" --out "$work/tuned_out" --no-csv --quiet > "$work/sil.txt" 2>&1
[ $? -eq 0 ] && grep -q "^tuned PID pitch: kp .* (= roll)$" "$work/sil.txt" &&
  grep -q "^tuned,PID,tune,pm_deg,yaw,4[5-9]\." "$work/tuned_out/tuned/metrics.csv"
check ladrc_sil_prints_and_reports_the_tuned_gains $?
kp_margins=$(sed -n 's/^tuned PID roll: kp \([^ ]*\) .*/\1/p' "$work/tuned.txt")
kp_sil=$(sed -n 's/^tuned PID roll: kp \([^ ]*\) .*/\1/p' "$work/sil.txt")
[ -n "$kp_margins" ] && [ "$kp_margins" = "$kp_sil" ]; check both_commands_tune_alike $?

# Targets that cannot be met: a warning at the tune key naming the best margins reached, and the
# best candidate flies (exit 0); with --strict, exit 2 there and nothing written.
printf '[run]\nduration_s = 1\ncontrollers = LADRC\n[rotors]\nmotor_tau_s = 0.03\n[controller LADRC]\ntune = margins\ntune_phase_margin_deg = 89\ntune_gain_margin_db = 40\n' \
    > "$work/impossible.ini"
"$sil" "$work/impossible.ini" --out "$work/impossible_out" --quiet --no-csv > "$work/impossible.txt" 2> "$work/impossible.err"
[ $? -eq 0 ] && grep -q "impossible.ini:7:8: warning: tune = margins: LADRC on roll cannot meet PM >= 89 deg, GM >= 40 dB; best reached: .*PM [0-9.-]* deg, GM [0-9.-]* dB" \
    "$work/impossible.err" && grep -q "^impossible,LADRC,tune,targets_met,-,0$" "$work/impossible_out/impossible/metrics.csv" &&
  grep -q "^impossible,LADRC,tune,status,-,\(tuned\|defaults\)$" "$work/impossible_out/impossible/metrics.csv"
check unmet_targets_warn_at_the_tune_key_and_fly $?
"$sil" "$work/impossible.ini" --out "$work/impossible_strict" --quiet --strict > /dev/null 2> "$work/impossible_s.err"
[ $? -eq 2 ] && grep -q "impossible.ini:7:8: tune = margins: LADRC on roll cannot meet PM >= 89 deg" \
    "$work/impossible_s.err" && [ ! -e "$work/impossible_strict" ]
check unmet_targets_exit_2_with_strict $?
"$margins" "$work/impossible.ini" > "$work/impossible_m.txt" 2> "$work/impossible_m.err"
[ $? -eq 0 ] && grep -q "impossible.ini:7:8: warning: tune = margins: LADRC" "$work/impossible_m.err" &&
  grep -q "^LADRC  *roll " "$work/impossible_m.txt"
check unmet_targets_warned_by_ladrc_margins $?

# A controller that no candidate flies (its model of the airframe 8 times too heavy, so that the
# defaults and the tuned gains alike diverge) is untunable: named at its key, not flown, its
# statistics "untunable"; the other controller flies; exit 4.
printf '[run]\nduration_s = 4\ncontrollers = LADRC CASCADED\n[rotors]\nideal = yes\nmotor_tau_s = 0.02\n[mismatch]\ninertia_scale = 8 8 8\n[reference]\nroll = 1 .. : 5\n[controller LADRC]\ntune = margins\n' \
    > "$work/heavy_model.ini"
"$sil" "$work/heavy_model.ini" --out "$work/heavy_out" --quiet --no-csv > "$work/heavy.txt" 2> "$work/heavy.err"
rc=$?
[ $rc -eq 4 ] && grep -q "heavy_model.ini:12:8: tune = margins: untunable: LADRC: the tuned gains on roll: diverge at" "$work/heavy.err" &&
  grep -q "^heavy_model,LADRC,4,error_rms_deg,roll,untunable$" "$work/heavy_out/heavy_model/metrics.csv" &&
  grep -q "^heavy_model,LADRC,tune,status,-,untunable$" "$work/heavy_out/heavy_model/metrics.csv" &&
  grep -q "^heavy_model,CASCADED,4,error_rms_deg,roll,[0-9]" "$work/heavy_out/heavy_model/metrics.csv" &&
  grep -q "^untunable LADRC: not flown: " "$work/heavy.txt"
check untunable_controller_is_not_flown_and_the_others_are $?
"$sil" "$work/heavy_model.ini" --out "$work/heavy_strict" --quiet --strict > /dev/null 2> "$work/heavy_s.err"
[ $? -eq 2 ] && [ ! -e "$work/heavy_strict" ]
check untunable_controller_refused_with_strict $?

echo "$(( 17 - failures )) passed, $failures failed"
[ "$failures" -eq 0 ]
