#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of ladrc_replay and ladrc_margins --from-log on logs the
# simulator writes: a flight replayed open loop gives the commands it flew
# (generic form exactly, PX4 form within the quaternions' float rounding);
# a chirp's log identifies the airframe, whose scenario ladrc_sil flies and
# ladrc_margins tunes; a replay that ran exits 0 (--strict: 1 on warnings);
# a log at 47 Hz replays the controllers that start at that rate and names
# the others with the reason; bad logs and options exit 2 naming the place
# and write nothing; an earlier run's folder is never mixed with a new
# run's files; a run never replaces its own log.
# Usage: replay_cli_test.sh LADRC_REPLAY LADRC_SIL LADRC_MARGINS [TOOLS_DIR]
# (TOOLS_DIR: tools/, whose replay_plot.py must draw the replay's figures
# when Debian's python3 has matplotlib.)
set -uo pipefail
replay=$1
sil=$2
margins=$3
tools=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "replay_cli_test.sh:$1:PASS"; else echo "replay_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}
# The largest |value| of a column of a CSV (by header name), over the rows whose first column matches.
column_max() { # file, column, row filter (regex on column 1)
    awk -F, -v col="$2" -v pat="$3" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == col) c = i; next }
        $1 ~ pat { v = $c < 0 ? -$c : $c; if (v > m) m = v } END { printf "%.9g\n", m + 0 }' "$1"
}
# 1 when a <= b (floating point).
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

# The paper's airframe with a motor lag and ideal rotors (never saturated: a log's command is the
# torque achieved, which then is the controller's own), every controller at its default gains (no
# tuning: fast), flying references on all three axes; its runs written as logs in the three forms.
cat > "$work/flight.ini" <<'INI'
[run]
duration_s = 6
controllers = HP-MLADRC LP-MLADRC LADRC RATE-ADRC PID CASCADED INDI
log = generic px4 betaflight
[rotors]
motor_tau_s = 0.002
[sensors]
angle_noise_std_deg = 0.05
rate_noise_std_deg_s = 0.3
delay_ticks = 1
use_rate = yes
[reference]
roll = 5 + 10*cos(pi*t/2)
pitch = 8*sin(pi*t/3)
yaw = 1 .. 4 : 20
INI
"$sil" "$work/flight.ini" --out "$work/flight" --quiet > /dev/null 2>&1
[ $? -eq 0 ] && [ -f "$work/flight/flight/LADRC_log.csv" ] && [ -f "$work/flight/flight/LADRC_betaflight.csv" ] &&
  [ -f "$work/flight/flight/LADRC_px4_vehicle_torque_setpoint_0.csv" ]
check simulator_writes_its_logs $?

# Consistency: each controller replayed on its own flight's log commands what it flew. The generic
# form carries the controller's float inputs with 9 digits (exact in float) and the command with 17:
# the replay is the flight bit for bit (tolerance 0). The PX4 form carries the attitudes as
# quaternions, whose conversion back to angles moves them by float rounding (1e-7 rad): the
# observers carry that into the command by at most 1e-4 of the authority (2.9e-5 measured, yaw).
PX4_TOL=1e-4
ok_generic=0
ok_px4=0
for c in HP-MLADRC LP-MLADRC LADRC RATE-ADRC PID CASCADED INDI; do
    "$replay" "$work/flight/flight/${c}_log.csv" --scenario "$work/flight.ini" --controllers "$c" --every 0 --quiet \
        --out "$work/g_$c" > /dev/null 2>&1
    d=$(column_max "$work/g_$c/replay_summary.csv" difference_rms "^$c\$")
    le "$d" 0 || { echo "  $c generic: difference $d"; ok_generic=1; }
    "$replay" "$work/flight/flight/${c}_px4" --scenario "$work/flight.ini" --controllers "$c" --every 0 --quiet \
        --out "$work/p_$c" > /dev/null 2>&1
    d=$(column_max "$work/p_$c/replay_summary.csv" difference_rms "^$c\$")
    le "$d" "$PX4_TOL" || { echo "  $c px4: difference $d"; ok_px4=1; }
done
check replay_of_generic_log_is_the_flight_bit_for_bit $ok_generic
check replay_of_px4_log_is_the_flight_within_rounding $ok_px4

# The full replay: identification, scenario, tuning, replay, outputs; the time series has a row per tick.
"$replay" "$work/flight/flight/CASCADED_betaflight.csv" --scenario "$work/flight.ini" --out "$work/full" \
    > "$work/full.txt" 2> "$work/full.err"
rc=$?
[ $rc -eq 0 ] && grep -q "^identification at 1000 Hz" "$work/full.txt" &&
  grep -q "^replayed 6000 ticks (6 s of flight) with 7 controllers" "$work/full.txt" &&
  [ "$(wc -l < "$work/full/replay.csv")" -eq 6001 ] &&
  head -n 1 "$work/full/replay.csv" | grep -q "^t_s,LOG_cmd_roll,LOG_cmd_pitch,LOG_cmd_yaw,HP-MLADRC_cmd_roll," &&
  [ "$(wc -l < "$work/full/replay_summary.csv")" -eq 25 ] && [ -s "$work/full/spectrum.csv" ] &&
  [ "$(grep -c ',replayed$' "$work/full/replay_summary.csv")" -eq 24 ] &&
  [ -s "$work/full/identification.csv" ] && grep -q "^\[vehicle\]" "$work/full/airframe.ini"
check full_replay_writes_every_output $?
# The figures of the replay.
if [ -n "$tools" ] && /usr/bin/python3 -c "import matplotlib, numpy" 2> /dev/null; then
    /usr/bin/python3 "$tools/replay_plot.py" "$work/full" > /dev/null 2>&1
    [ $? -eq 0 ] && [ "$(wc -c < "$work/full/replay_commands.png")" -gt 30000 ] &&
      [ "$(wc -c < "$work/full/replay_spectrum.png")" -gt 30000 ]
    check replay_plot_draws_both_figures $?
fi
# Manoeuvres alone cannot part lag from delay: the identification says so; the exit status is 0
# (the replay ran), 1 with --strict.
[ $rc -eq 0 ] && grep -q "^warning: roll: lag and delay are not told apart" "$work/full.txt"
check weak_excitation_is_warned_and_exits_0 $?
"$replay" "$work/flight/flight/CASCADED_betaflight.csv" --scenario "$work/flight.ini" --controllers LADRC --every 0 \
    --strict --quiet --out "$work/strict" > /dev/null 2>&1
[ $? -eq 1 ] && [ -s "$work/strict/replay_summary.csv" ]; check strict_exits_1_on_warnings $?

# A chirp's log: the airframe (with a 20 ms motor lag) identified (b0 of the paper's roll: authority
# l m g / 2 = 0.6475 N m over Jx 5.445e-3 = 118.9 rad/s^2; within the 5 % a chirp is held to), its
# scenario flown by ladrc_sil, and ladrc_margins --from-log tunes the controllers from the log.
sed -e 's/^duration_s = 6/duration_s = 40/' -e 's/^controllers = .*/controllers = LADRC/' \
    -e 's/^log = .*/log = px4/' -e 's/^motor_tau_s = .*/motor_tau_s = 0.02/' "$work/flight.ini" > "$work/chirp.ini"
printf '[excitation]\naxis = all\namplitude = 0.2\nstart_s = 1\nduration_s = 12\n' >> "$work/chirp.ini"
"$sil" "$work/chirp.ini" --out "$work/chirp" --quiet > /dev/null 2>&1
"$replay" "$work/chirp/chirp/LADRC_px4" --identify-only --quiet --out "$work/ident" > "$work/ident.txt" 2>&1
rc=$?
[ $rc -eq 0 ] &&
  awk -F, '$1 == "roll" { e = ($2 - 118.9) / 118.9; exit !(e < 0.05 && e > -0.05 && $8 == 1) }' \
      "$work/ident/identification.csv"
check chirp_identifies_b0_and_delay $?
"$sil" "$work/ident/airframe.ini" --controllers LADRC --out "$work/fly" --no-csv --quiet \
    > /dev/null 2>&1
[ $? -eq 0 ] && [ -s "$work/fly/airframe/metrics.csv" ]; check identified_scenario_flies $?
"$margins" --from-log "$work/chirp/chirp/LADRC_px4" --format px4 --controllers LADRC --axis roll \
    > "$work/margins.txt" 2>&1
[ $? -eq 0 ] && grep -q "^tuned LADRC roll: .* -> PM 4[5-9]\.[0-9] deg" "$work/margins.txt" &&
  grep -q "^LADRC  *roll .* yes " "$work/margins.txt"
check margins_from_log_tunes_and_prints $?
# --dt resamples the log as ladrc_replay's does: the airframe identified at 500 Hz.
"$margins" --from-log "$work/chirp/chirp/LADRC_px4" --dt 0.002 --from 1 --to 30 --controllers LADRC --axis roll \
    > "$work/margins_dt.txt" 2>&1
[ $? -eq 0 ] && grep -q "^identification at 500 Hz" "$work/margins_dt.txt" &&
  grep -q ": dt 0.002 s, motor lag" "$work/margins_dt.txt"
check margins_from_log_takes_dt_from_and_to $?
# A command whose sign is the gyro's opposite gives a negative b0: the scenario takes the other axis's
# (said), the identification still exits 0.
"$replay" "$work/chirp/chirp/LADRC_px4" --map 'command[1]=vehicle_torque_setpoint.xyz[1]*-1' --identify-only \
    --quiet --out "$work/flipped" > "$work/flipped.txt" 2>&1
[ $? -eq 0 ] && grep -q "^warning: pitch: b0 came out negative .*the scenario takes roll's" "$work/flipped.txt" &&
  grep -q "^#   pitch: b0 came out negative" "$work/flipped/airframe.ini"
check negative_b0_takes_the_other_axis_and_exits_0 $?

# A log at 47 Hz (PX4's logging rate): replayed at that rate by the controllers that start at it;
# LP-MLADRC's forgetting rate (100/s) is above 1 / dt: named untunable with the reason, in the summary too
# (12 s at 47 Hz: 563 or 564 ticks, as the resampling's grid falls).
sed -e 's/^duration_s = 6/duration_s = 12/' -e 's/^controllers = .*/controllers = LADRC/' -e 's/^log = .*/log = px4/' \
    -e 's/^\[run\]/[run]\ncontrol_dt_s = 0.0212766\nplant_substeps = 40/' "$work/flight.ini" > "$work/slow.ini"
"$sil" "$work/slow.ini" --out "$work/slow" --quiet > /dev/null 2>&1
"$replay" "$work/slow/slow/LADRC_px4" --controllers LADRC,LP-MLADRC --every 0 --quiet --out "$work/slow_replay" \
    > "$work/slow.txt" 2> "$work/slow.err"
[ $? -eq 0 ] && grep -q "^identification at 47 Hz" "$work/slow.txt" &&
  grep -q "^untunable LP-MLADRC, not replayed: LP-MLADRC does not start: LADRC_ERR_RLS_LAMBDA0.*(at the log's 47 Hz)" \
      "$work/slow.txt" && grep -q "^replayed 56[0-9] ticks .* with 1 controllers" "$work/slow.txt" &&
  grep -q '^LP-MLADRC,roll,untunable,.*,"untunable: LP-MLADRC does not start: ' "$work/slow_replay/replay_summary.csv" &&
  grep -q "^LADRC,roll,56[0-9],.*,replayed$" "$work/slow_replay/replay_summary.csv"
check log_at_47_hz_replays_what_starts_and_names_the_rest $?
# A log without a setpoint (the PX4 log above less its attitude and rate setpoints; Betaflight logs
# 3.x): identified, the log's own command summarised, every controller named as not replayed
# with the reason; exit 0.
mkdir -p "$work/noref"
for f in "$work/slow/slow/"LADRC_px4_*.csv; do
    case $f in *_attitude_setpoint_* | *_rates_setpoint_*) ;; *) cp "$f" "$work/noref/" ;; esac
done
"$replay" "$work/noref/LADRC_px4" --controllers LADRC --every 0 --quiet --out "$work/noref_out" > "$work/noref.txt" 2>&1
[ $? -eq 0 ] && grep -q "^LADRC, not replayed: the log has no setpoint to replay against" "$work/noref.txt" &&
  grep -q "^LOG,roll,5[0-9][0-9],.*,replayed$" "$work/noref_out/replay_summary.csv" &&
  grep -q '^LADRC,roll,not_replayed,.*,"not replayed: the log has no setpoint' "$work/noref_out/replay_summary.csv"
check log_without_setpoint_is_identified_and_says_why_not_replayed $?
"$margins" --from-log "$work/slow/slow/LADRC_px4" --controllers LADRC,LP-MLADRC --axis roll > "$work/slow_m.txt" 2>&1
[ $? -eq 0 ] && grep -q "^LP-MLADRC  *untunable: LP-MLADRC does not start" "$work/slow_m.txt" &&
  grep -q "^LADRC  *roll .* yes " "$work/slow_m.txt"
check margins_from_log_at_47_hz_names_what_does_not_start $?

# Bad input: exit 2, the place on stderr.
printf 'time (us), gyroADC[0], gyroADC[1], gyroADC[2], axisP[0], axisP[1], axisP[2]\n0, 1, 2, 3, 4, 5, 6\n1000, 1, 2\n' \
    > "$work/short.csv"
"$replay" "$work/short.csv" --quiet --out "$work/bad" > /dev/null 2> "$work/short.err"
[ $? -eq 2 ] && grep -q "short.csv:3:11: " "$work/short.err"; check short_row_exits_2_at_its_place $?
printf 'time (us), gyroADC[0], gyroADC[1], gyroADC[2], axisP[0], axisP[1], axisP[2]\n0, 1, 2, 3, 4, 5, 6\n0, 1, 2, 3, 4, 5, 6\n' \
    > "$work/repeat.csv"
"$replay" "$work/repeat.csv" --quiet --out "$work/bad" > /dev/null 2> "$work/repeat.err"
[ $? -eq 2 ] && grep -q "repeat.csv:3:1: " "$work/repeat.err"; check time_that_repeats_exits_2 $?
printf 'time (us), gyroADC[0], gyroADC[1], axisP[0], axisP[1], axisP[2]\n0, 1, 2, 4, 5, 6\n' > "$work/nocol.csv"
"$replay" "$work/nocol.csv" --format betaflight --quiet --out "$work/bad" > /dev/null 2> "$work/nocol.err"
[ $? -eq 2 ] && grep -q "nocol.csv:1:.*gyroADC\[2\]" "$work/nocol.err"; check missing_column_exits_2_naming_it $?
"$replay" "$work/missing.csv" --quiet --out "$work/bad" > /dev/null 2> "$work/missing.err"
[ $? -eq 2 ] && grep -q "missing.csv" "$work/missing.err"; check missing_log_exits_2 $?
# A refused log writes nothing: no output folder, no parent folder made for it, nothing left beside.
[ ! -e "$work/bad" ]; check refused_logs_write_no_folder $?
"$replay" "$work/missing.csv" --quiet --out "$work/made/for/it" > /dev/null 2>&1
[ $? -eq 2 ] && [ ! -e "$work/made" ]; check refused_log_leaves_no_parent_folders $?
# A log refused after many rows (a cell that is not a number near its end, past the noise file's
# first rows): exit 2 at its place, nothing written.
awk -F', ' -v OFS=', ' 'NR == 5500 { $3 = "nan" } { print }' "$work/flight/flight/LADRC_betaflight.csv" > "$work/late.csv"
"$replay" "$work/late.csv" --quiet --out "$work/late_out" > /dev/null 2> "$work/late.err"
[ $? -eq 2 ] && grep -q "late.csv:5500:" "$work/late.err" && [ ! -e "$work/late_out" ] &&
  [ -z "$(find "$work" -maxdepth 1 -name '*partial*')" ]
check log_refused_after_many_rows_writes_nothing $?

# An earlier run's folder: a new run replaces its outputs and removes those it does not write (no
# time series with --every 0), leaves other files alone; a refused run leaves it as it was.
mkdir -p "$work/again" && echo mine > "$work/again/notes.txt"
"$replay" "$work/flight/flight/LADRC_log.csv" --scenario "$work/flight.ini" --controllers LADRC --quiet \
    --out "$work/again" > /dev/null 2>&1
[ $? -eq 0 ] && [ -s "$work/again/replay.csv" ]; check first_run_writes_the_time_series $?
cksum "$work/again/"* > "$work/again.sum"
"$replay" "$work/late.csv" --quiet --out "$work/again" > /dev/null 2>&1
[ $? -eq 2 ] && cksum "$work/again/"* | cmp -s - "$work/again.sum" &&
  [ -z "$(find "$work/again" -name '.partial*')" ]
check refused_run_leaves_an_earlier_folder_as_it_was $?
"$replay" "$work/flight/flight/LADRC_log.csv" --scenario "$work/flight.ini" --controllers CASCADED --every 0 --quiet \
    --out "$work/again" > /dev/null 2>&1
[ $? -eq 0 ] && [ ! -e "$work/again/replay.csv" ] && grep -q "^CASCADED,roll," "$work/again/replay_summary.csv" &&
  ! grep -q "^LADRC," "$work/again/replay_summary.csv" && [ "$(cat "$work/again/notes.txt")" = mine ] &&
  [ -z "$(find "$work/again" -name '.partial*')" ]
check new_run_never_mixes_with_an_earlier_folder $?

# A run never replaces its own input: a log named as an output in the folder (--out . beside it,
# also through a link of another name) and ladrc_margins --save-scenario over its log exit 2,
# the log unchanged.
mkdir -p "$work/clobber" && cp "$work/flight/flight/LADRC_log.csv" "$work/clobber/replay.csv" &&
  ln -s replay.csv "$work/clobber/link.csv" && cksum < "$work/clobber/replay.csv" > "$work/clobber.sum"
(cd "$work/clobber" && "$replay" replay.csv --out . --quiet > /dev/null 2> ../clobber1.err)
[ $? -eq 2 ] && grep -q "replay.csv: the input is the output ./replay.csv of this run" "$work/clobber1.err" &&
  cksum < "$work/clobber/replay.csv" | cmp -s - "$work/clobber.sum"
check log_that_is_an_output_is_refused $?
"$replay" "$work/clobber/link.csv" --out "$work/clobber" --quiet > /dev/null 2>&1
[ $? -eq 2 ] && cksum < "$work/clobber/replay.csv" | cmp -s - "$work/clobber.sum"
check log_that_is_an_output_through_a_link_is_refused $?
"$margins" --from-log "$work/clobber/link.csv" --save-scenario "$work/clobber/../clobber/replay.csv" \
    > /dev/null 2> "$work/clobber2.err"
[ $? -eq 2 ] && grep -q "save-scenario: .*would replace it" "$work/clobber2.err" &&
  cksum < "$work/clobber/replay.csv" | cmp -s - "$work/clobber.sum"
check margins_save_scenario_over_its_log_is_refused $?
"$replay" "$work/short.csv" --format ulog --out "$work/bad" > /dev/null 2> "$work/format.err"
[ $? -eq 2 ] && grep -q "'ulog'" "$work/format.err"; check bad_format_exits_2 $?
"$replay" "$work/flight/flight/LADRC_log.csv" --map gyro[7]=x --quiet --out "$work/bad" > /dev/null 2> "$work/map.err"
[ $? -eq 2 ] && grep -q "gyro\[7\]" "$work/map.err"; check bad_map_item_exits_2 $?
"$replay" "$work/flight/flight/LADRC_log.csv" --every 1.5 --out "$work/bad" > /dev/null 2> "$work/every.err"
[ $? -eq 2 ]; check bad_every_exits_2 $?

[ "$failures" -eq 0 ] || { echo "replay_cli_test.sh: $failures check(s) failed"; exit 1; }
echo "replay_cli_test.sh: all checks passed"
