#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# End-to-end checks of ladrc_sil --campaign: --list and its shards, plan.csv
# written alike by two shards, a campaign's runs equal to ladrc_sil on the
# same scenario with the same --set lines (byte for byte but the scenario
# column), and every bad input refused with exit 2 and nothing written.
# Usage: campaign_cli_test.sh LADRC_SIL SCENARIO_DIR CAMPAIGN_DIR
set -uo pipefail
sil=$1
scenarios=$2
campaigns=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "campaign_cli_test.sh:$1:PASS"; else echo "campaign_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

# 4 runs x 2 controllers x 2 s: the noise seed on the grid and a drawn
# inertia assumption, so that plan.csv tells every setting of every run.
cat > "$work/small.ini" <<EOF2
[campaign]
base = $scenarios/paper.ini
samples = 2
[grid]
run.seed = 11, 12
[draw]
J = uniform(0.7, 1.3)
[set]
run.duration_s = 2
run.controllers = LADRC PID
mismatch.inertia_scale = {J} {J} {J}
disturbance.roll = 1 .. 2 : 20*sin(3*t)
sensors.angle_noise_std_deg = 0.05
metrics.error_window_s = 0 2
metrics.steady_window_s = 1 2
EOF2

# --list: the header, one row per run, nothing written.
(cd "$work" && "$sil" --campaign small.ini --list > list.txt)
check list_succeeds $?
[ "$(head -1 "$work/list.txt")" = "run,run.seed,J" ] && [ "$(wc -l < "$work/list.txt")" -eq 5 ] &&
  [ "$(cut -d, -f1,2 "$work/list.txt" | tr '\n' ' ')" = "run,run.seed 1,11 2,11 3,12 4,12 " ]
check list_has_a_row_per_run_in_grid_order $?
[ ! -e "$work/out" ]; check list_writes_nothing $?
# the shards' rows: each run in exactly one shard, with the same values
for n in 1 2 3 5; do
    for k in $(seq 1 $n); do "$sil" --campaign "$work/small.ini" --list --shard "$k/$n" | sed 1d; done | sort -n > "$work/union.txt"
    sed 1d "$work/list.txt" | cmp -s - "$work/union.txt"; check "shards_of_${n}_partition_the_runs" $?
done
[ "$("$sil" --campaign "$work/small.ini" --list --shard 2/3 | cut -d, -f1 | tr '\n' ' ')" = "run 2 " ]
check shard_2_of_3_lists_run_2 $?

# --print-out: the directory the runs go to (--out DIR/<name>, else output_dir), nothing written.
[ "$(cd "$work" && "$sil" --campaign small.ini --print-out)" = "out/small" ] &&
  [ "$("$sil" --campaign "$work/small.ini" --out "$work/o" --print-out)" = "$work/o/small" ] && [ ! -e "$work/out" ]
check print_out_names_the_output_dir $?

# Two shards into one directory: plan.csv identical to --list, every run there.
"$sil" --campaign "$work/small.ini" --shard 1/2 --jobs 2 --out "$work/o" --quiet
rc1=$?
cp "$work/o/small/plan.csv" "$work/plan_after_1.csv"
"$sil" --campaign "$work/small.ini" --shard 2/2 --jobs 1 --out "$work/o" --quiet
rc2=$?
check shards_succeed $(( rc1 + rc2 ))
cmp -s "$work/o/small/plan.csv" "$work/list.txt" && cmp -s "$work/plan_after_1.csv" "$work/list.txt"
check plan_written_alike_by_both_shards $?
[ "$(ls "$work/o/small/runs" | tr '\n' ' ')" = "00001 00002 00003 00004 " ] &&
  [ "$(ls "$work/o/small/runs/00003" | tr '\n' ' ')" = "metrics.csv signals.csv " ] &&
  [ "$(ls -A "$work/o/small" | tr '\n' ' ')" = "plan.csv runs " ]
check runs_written_without_time_series $?
[ "$(cut -d, -f1 "$work/o/small/runs/00004/metrics.csv" | sed 1d | sort -u)" = "00004" ]
check scenario_column_is_the_run $?

# Each run = ladrc_sil on the base with the same --set lines.
same=0 compared=0
while IFS=, read -r r seed j; do
    d=$(printf '%05d' "$r")
    "$sil" "$scenarios/paper.ini" --no-csv --quiet --out "$work/ref$r" --set "run.seed=$seed" \
        --set run.duration_s=2 --set "run.controllers=LADRC PID" --set "mismatch.inertia_scale=$j $j $j" \
        --set "disturbance.roll=1 .. 2 : 20*sin(3*t)" --set sensors.angle_noise_std_deg=0.05 \
        --set "metrics.error_window_s=0 2" --set "metrics.steady_window_s=1 2" > /dev/null 2>&1
    cmp -s <(cut -d, -f2- "$work/ref$r/paper/metrics.csv") <(cut -d, -f2- "$work/o/small/runs/$d/metrics.csv") &&
      cmp -s "$work/ref$r/paper/signals.csv" "$work/o/small/runs/$d/signals.csv" && compared=$((compared + 1)) || same=1
done < <(sed 1d "$work/list.txt")
[ "$compared" -eq 4 ] || same=1
check runs_equal_ladrc_sil_with_the_same_settings $same
# the drawn values differ between runs (a constant draw would pass the above)
[ "$(cut -d, -f3 "$work/list.txt" | sed 1d | sort -u | wc -l)" -eq 4 ]; check draws_differ_between_runs $?

# --csv adds the time series; a rerun into the same directory is allowed.
"$sil" --campaign "$work/small.ini" --shard 3/4 --csv --out "$work/o" --quiet
check rerun_into_the_same_directory_succeeds $?
[ -s "$work/o/small/runs/00003/LADRC.csv" ] && [ -s "$work/o/small/runs/00003/PID.csv" ] &&
  [ ! -e "$work/o/small/runs/00001/LADRC.csv" ]
check csv_writes_the_time_series $?

# Another campaign's plan in OUT: exit 2, nothing written.
sed 's/samples = 2/samples = 3/' "$work/small.ini" > "$work/other.ini"
mkdir -p "$work/o2/small"
sed 's/^1,/1,x/' "$work/list.txt" > "$work/o2/small/plan.csv"
cp "$work/small.ini" "$work/o2/small.ini"
"$sil" --campaign "$work/o2/small.ini" --out "$work/o2" --quiet > /dev/null 2> "$work/other.err"
[ $? -eq 2 ] && grep -q "holds another campaign's runs" "$work/other.err" && [ ! -e "$work/o2/small/runs" ] &&
  grep -q '^1,x' "$work/o2/small/plan.csv"
check another_campaigns_plan_exits_2_and_writes_nothing $?

# A run the simulator cannot write: exit 1.
mkdir -p "$work/o3/small/runs"
: > "$work/o3/small/runs/00002"
"$sil" --campaign "$work/small.ini" --out "$work/o3" --quiet > /dev/null 2> "$work/o3.err"
[ $? -eq 1 ] && grep -q "cannot write its outputs: .*runs/00002: not a folder" "$work/o3.err" && [ -s "$work/o3/small/runs/00001/metrics.csv" ]
check unwritable_run_exits_1 $?

# Bad input: exit 2, the offending text in the message, nothing written.
refused() { # name, expected text in stderr, campaign text (or - for none), options...
    local name=$1 want=$2 text=$3
    shift 3
    local file="$work/$name.ini"
    if [ "$text" != - ]; then printf "$text" > "$file"; fi
    (cd "$work" && "$sil" "$@" --out "$work/${name}_out" --quiet > /dev/null 2> "$work/$name.err")
    local rc=$?
    [ "$rc" -eq 2 ] && grep -qF -- "$want" "$work/$name.err" && [ ! -e "$work/${name}_out" ]
    check "$name" $?
}
base="[campaign]\nbase = $scenarios/paper.ini\n"
refused unknown_section "unknown_section.ini:3:2: unknown section [grids]" "$base[grids]\n" --campaign unknown_section.ini
refused unknown_key "unknown_key.ini:3:1: unknown key 'sample'" "${base}sample = 3\n" --campaign unknown_key.ini
refused bad_distribution "bad_distribution.ini:4:5: unknown distribution 'gauss'" \
    "$base[draw]\nx = gauss(0, 1)\n" --campaign bad_distribution.ini
refused log_uniform_from_0 "log_uniform_from_0.ini:4:5: log_uniform(A, B) needs 0 < A < B" \
    "$base[draw]\nx = log_uniform(0, 1)\n" --campaign log_uniform_from_0.ini
refused range_of_1 "range_of_1.ini:4:17: range COUNT must be a whole number from 2" \
    "$base[grid]\nx = range(0, 1, 1)\n" --campaign range_of_1.ini
refused unknown_variable "unknown_variable.ini:4:18: unknown variable '{y}'" \
    "$base[set]\nrun.duration_s = {y}\n" --campaign unknown_variable.ini
refused unused_variable "unused_variable.ini:4:1: variable 'x' is not used in [set]" \
    "$base[grid]\nx = 1, 2\n" --campaign unused_variable.ini
refused base_missing "base_missing.ini:1:1: missing base = SCENARIO" "[campaign]\nsamples = 2\n" --campaign base_missing.ini
refused base_unreadable "cannot read the base scenario" "[campaign]\nbase = nowhere.ini\n" --campaign base_unreadable.ini
refused campaign_unreadable "no_such_campaign.ini: cannot read" - --campaign no_such_campaign.ini
# run 3's value is refused by the scenario parser: the campaign file, the
# line of the key, the run, its values and the scenario's message
refused run_refused "run_refused.ini:4: run 3 (rotors.motor_tau_s=-0.01): 'rotors.motor_tau_s=-0.01':20: motor_tau_s must be >= 0" \
    "$base[grid]\nrotors.motor_tau_s = 0, 0.01, -0.01\n" --campaign run_refused.ini
# an error in the base file's lines: the campaign, the run, then file:line:column
refused run_refused_at_a_base_line "run_refused_at_a_base_line.ini: run 2 (x=10): $scenarios/paper.ini:" \
    "$base[grid]\nx = 30, 10\n[set]\nrun.duration_s = {x}\n" --campaign run_refused_at_a_base_line.ini
grep -q ": error_window_s ends after the run (duration_s = 10)$" "$work/run_refused_at_a_base_line.err"
check run_refused_at_a_base_line_gives_the_scenarios_message $?
# the refused run is in another shard: this shard is fine (so --list works)
"$sil" --campaign "$work/run_refused.ini" --shard 1/3 --list > /dev/null; check refused_run_outside_the_shard_is_not_read $?
for shard in 0/4 5/4 a/b 1/0 2; do
    refused "shard_${shard//\//_of_}" "--shard " - --campaign small.ini --shard "$shard"
done
refused list_without_campaign "--list needs --campaign" - "$scenarios/paper.ini" --list
refused shard_without_campaign "--shard needs --campaign" - "$scenarios/paper.ini" --shard 1/2
refused set_with_campaign "--set cannot be combined with --campaign" - --campaign small.ini --set run.seed=3
refused seed_with_campaign "--seed cannot be combined with --campaign" - --campaign small.ini --seed 3
refused controllers_with_campaign "--controllers cannot be combined" - --campaign small.ini --controllers PID
refused scenario_with_campaign "a scenario file cannot be combined with --campaign" - --campaign small.ini "$scenarios/paper.ini"

# The shipped campaigns: every run validates, the robustness one has 1,000.
"$sil" --campaign "$campaigns/robustness.ini" --list > "$work/robustness.txt"
[ $? -eq 0 ] && [ "$(head -1 "$work/robustness.txt")" = "run,rotors.motor_tau_s,J,w,sensors.angle_noise_std_deg,sensors.rate_noise_std_deg_s" ] &&
  [ "$(wc -l < "$work/robustness.txt")" -eq 1001 ] && [ "$(sed -n 1001p "$work/robustness.txt" | cut -d, -f1,2)" = "1000,0.04" ]
check robustness_campaign_validates_1000_runs $?
"$sil" --campaign "$campaigns/smoke.ini" --list > "$work/smoke.txt" && [ "$(wc -l < "$work/smoke.txt")" -eq 13 ]
check smoke_campaign_validates_12_runs $?

echo "campaign_cli_test.sh: $failures failure(s)"
[ "$failures" -eq 0 ]
