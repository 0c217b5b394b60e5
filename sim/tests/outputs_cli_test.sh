#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# What every command-line tool promises of the files it writes, checked for
# every file it writes (found by running it, so a new output is covered
# without a change here):
#   - it never writes over one of its inputs: with an input placed under the
#     name of any one of its outputs it refuses (exit 2), the input keeps its
#     bytes and nothing else appears;
#   - a refusal leaves nothing: a bad input writes no folder, and into an
#     earlier run's folder changes none of its files;
#   - an earlier run's outputs never mix with a new run's: a run that writes
#     fewer files into an earlier run's folder leaves exactly the files a run
#     into an empty folder writes.
# Usage: outputs_cli_test.sh BIN_DIR (ladrc_sil, ladrc_replay, ladrc_margins,
# ladrc_filter and ladrc_views there)
set -uo pipefail
bin=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
    if [ "$2" -eq 0 ]; then echo "outputs_cli_test.sh:$1:PASS"; else echo "outputs_cli_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}
# Every file under a folder with its checksum, sorted (relative paths).
listing() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0r cksum); }
# The files under a folder, relative, sorted (no checksums).
names() { (cd "$1" && find . -type f | sort); }

# The inputs: a short chirp flight's logs in the three forms, a scenario, a recorded series.
cat > "$work/flight.ini" <<'INI'
[run]
duration_s = 3
control_dt_s = 0.001
seed = 3
controllers = CASCADED
log = betaflight px4 generic
[rotors]
ideal = no
w2_min_rad2_s2 = 5e3
w2_max_rad2_s2 = 1.32e5
motor_tau_s = 0.03
[sensors]
rate_noise_std_deg_s = 0.3
use_rate = yes
[excitation]
axis = all
amplitude = 0.2 0.2 0.4
f0_hz = 1
f1_hz = 40
start_s = 0.3
duration_s = 0.8
INI
"$bin/ladrc_sil" "$work/flight.ini" --out "$work/flights" --quiet > /dev/null 2>&1
logs=$work/flights/flight
[ -s "$logs/CASCADED_betaflight.csv" ] && [ -s "$logs/CASCADED_log.csv" ]
check the_flight_logs_are_written $?
printf 't [s], roll [rad], pitch [rad], yaw [rad]\n0,0,0,0\n1,0.1,0,0\n2,0.1,0,0\n' > "$work/ref.csv"
cat > "$work/short.ini" <<'INI'
[run]
duration_s = 2
controllers = LADRC PID
log = betaflight px4 generic
[reference]
series = ref.csv
[metrics]
error_window_s = 0 2
steady_window_s = 1 2
settle_window_s = 0 1
INI
echo "not a log at all" > "$work/bad.csv"

# A tool's case: NAME, the input's kind (its extension), the input, then the command with INPUT
# and OUT standing for the input's path and the output (a folder, or for a one-file tool a file).
# The command runs with its working directory in the case's folder.
run_case() { # dir, input path, out, command words...
    local dir=$1 in=$2 out=$3
    shift 3
    local words=()
    for w in "$@"; do
        w=${w//INPUT/$in}
        words+=("${w//OUT/$out}")
    done
    (cd "$dir" && "${words[@]}" > /dev/null 2> "$dir.err")
}

# tool_case NAME INPUT_FILE EXTRA_FILES OUT_KIND OK_STATUSES command...
#   EXTRA_FILES: files (space-separated) copied beside the input in every folder (a scenario's series);
#   OUT_KIND: dir or file.
tool_case() {
    local name=$1 input=$2 extra=$3 kind=$4 ok=$5
    shift 5
    local base ext
    base=$(basename "$input")
    ext=${base##*.}
    # 1. a run into an empty place: which files it writes
    local d=$work/$name.fresh
    mkdir -p "$d" && cp "$input" "$d/in.$ext"
    for x in $extra; do cp "$x" "$d/"; done
    local out=out
    [ "$kind" = file ] && out=out.csv
    run_case "$d" "in.$ext" "$out" "$@"
    local st=$?
    [[ " $ok " == *" $st "* ]] && [ -e "$d/$out" ]
    check "${name}_writes_its_outputs" $?
    local outputs=()
    if [ "$kind" = dir ]; then
        mapfile -t outputs < <(names "$d/$out" | sed 's|^\./||')
    else
        outputs=("")
    fi
    [ ${#outputs[@]} -gt 0 ]
    check "${name}_outputs_found_${#outputs[@]}" $?
    # 2. the input under each output's name: refused, the input as it was, nothing else written
    local k=0 all=0
    for f in "${outputs[@]}"; do
        k=$((k + 1))
        local c=$work/$name.clobber$k target
        mkdir -p "$c"
        for x in $extra; do cp "$x" "$c/"; done
        if [ "$kind" = dir ]; then target=$out/$f; else target=$out; fi
        mkdir -p "$(dirname "$c/$target")" && cp "$input" "$c/$target"
        for x in $extra; do cp "$x" "$(dirname "$c/$target")/"; done # what the input names beside it
        local before after
        before=$(listing "$c")
        run_case "$c" "$target" "$out" "$@"
        st=$?
        after=$(listing "$c")
        if [ $st -ne 2 ] || [ "$before" != "$after" ] || ! grep -q "would replace it" "$c.err"; then
            echo "  $name: input at $target: exit $st; $(head -c 300 "$c.err")"
            all=1
        fi
    done
    check "${name}_refuses_its_input_under_each_output_name" $all
    # 3. a refusal leaves nothing: no folder, and an earlier run's files unchanged
    local r=$work/$name.refused
    mkdir -p "$r" && cp "$work/bad.csv" "$r/in.$ext"
    for x in $extra; do cp "$x" "$r/"; done
    run_case "$r" "in.$ext" "$out" "$@"
    st=$?
    [ $st -eq 2 ] && [ ! -e "$r/$out" ] && [ "$(ls -A "$r" | wc -l)" -eq $((1 + $(echo $extra | wc -w))) ]
    check "${name}_a_refusal_writes_nothing" $?
    before=$(listing "$d")
    cp "$work/bad.csv" "$d/in.$ext.bad"
    run_case "$d" "in.$ext.bad" "$out" "$@"
    st=$?
    rm -f "$d/in.$ext.bad"
    [ $st -eq 2 ] && [ "$before" = "$(listing "$d")" ]
    check "${name}_a_refusal_leaves_an_earlier_runs_files_as_they_were" $?
}

# fewer_case NAME INPUT EXTRA command_full... -- command_fewer...: the fewer run into the full
# run's folder leaves the files a fewer run into an empty folder leaves.
fewer_case() {
    local name=$1 input=$2 extra=$3
    shift 3
    local full=() fewer=() seen=0
    for w in "$@"; do
        if [ "$w" = -- ]; then seen=1; elif [ $seen -eq 0 ]; then full+=("$w"); else fewer+=("$w"); fi
    done
    local base ext
    base=$(basename "$input")
    ext=${base##*.}
    local a=$work/$name.mixed b=$work/$name.alone
    mkdir -p "$a" "$b" && cp "$input" "$a/in.$ext" && cp "$input" "$b/in.$ext"
    for x in $extra; do cp "$x" "$a/" && cp "$x" "$b/"; done
    run_case "$a" "in.$ext" out "${full[@]}"
    local n_full
    n_full=$(names "$a/out" | wc -l)
    run_case "$a" "in.$ext" out "${fewer[@]}"
    run_case "$b" "in.$ext" out "${fewer[@]}"
    [ "$n_full" -gt "$(names "$b/out" | wc -l)" ] && [ "$(names "$a/out")" = "$(names "$b/out")" ]
    check "${name}_a_run_with_fewer_outputs_leaves_no_earlier_ones" $?
}

bf=$logs/CASCADED_betaflight.csv
gen=$logs/CASCADED_log.csv

tool_case sil "$work/short.ini" "$work/ref.csv" dir "0" \
    "$bin/ladrc_sil" INPUT --set run.output_dir=OUT --quiet
fewer_case sil "$work/short.ini" "$work/ref.csv" \
    "$bin/ladrc_sil" INPUT --set run.output_dir=OUT --quiet -- \
    "$bin/ladrc_sil" INPUT --set run.output_dir=OUT --quiet --controllers PID
# the recorded series under an output's name
mkdir -p "$work/series" && cp "$work/short.ini" "$work/series/" && mkdir -p "$work/series/out" &&
    cp "$work/ref.csv" "$work/series/out/PID.csv" && sed -i 's|^series = ref.csv|series = out/PID.csv|' "$work/series/short.ini"
sum=$(cksum < "$work/series/out/PID.csv")
(cd "$work/series" && "$bin/ladrc_sil" short.ini --set run.output_dir=out --quiet > /dev/null 2> err)
[ $? -eq 2 ] && grep -q "would replace it" "$work/series/err" && [ "$sum" = "$(cksum < "$work/series/out/PID.csv")" ] &&
    [ "$(ls "$work/series/out")" = PID.csv ]
check sil_refuses_its_series_under_an_output_name $?

cat > "$work/camp.ini" <<'INI'
[campaign]
name = c
base = short.ini
samples = 1
[grid]
run.seed = 1, 2
[set]
run.controllers = LADRC
INI
tool_case campaign "$work/camp.ini" "$work/short.ini $work/ref.csv" dir "0" \
    "$bin/ladrc_sil" --campaign INPUT --out OUT --quiet

tool_case replay "$bf" "" dir "0" "$bin/ladrc_replay" INPUT --out OUT --controllers LADRC,PID --quiet
fewer_case replay "$bf" "" \
    "$bin/ladrc_replay" INPUT --out OUT --controllers LADRC,PID --quiet -- \
    "$bin/ladrc_replay" INPUT --out OUT --identify-only --quiet

tool_case margins_log "$gen" "" dir "0 1 4" \
    "$bin/ladrc_margins" --from-log INPUT --format generic --controllers LADRC,PID --csv OUT
fewer_case margins_log "$gen" "" \
    "$bin/ladrc_margins" --from-log INPUT --format generic --controllers LADRC,PID --csv OUT -- \
    "$bin/ladrc_margins" --from-log INPUT --format generic --controllers PID --csv OUT
tool_case margins_scenario "$work/short.ini" "$work/ref.csv" dir "0 1 4" \
    "$bin/ladrc_margins" INPUT --csv OUT
tool_case margins_save "$gen" "" file "0 1 4" \
    "$bin/ladrc_margins" --from-log INPUT --format generic --controllers PID --save-scenario OUT

tool_case filter "$gen" "" file "0" "$bin/ladrc_filter" INPUT --format generic --lpf 100 --out OUT

tool_case views "$bf" "" dir "0" "$bin/ladrc_views" --out OUT A=INPUT
tool_case views_reference "$bf" "" file "0" "$bin/ladrc_views" --reference OUT INPUT

# Runs at once whose output folders share parents none has made yet: each makes what is missing,
# none fails because another made a parent first (a mkdir that meets EEXIST after its stat).
pids=()
for i in 1 2 3 4 5 6 7 8; do
    "$bin/ladrc_sil" "$work/short.ini" --out "$work/together/a/b/c/run$i" --no-csv --quiet > /dev/null 2> "$work/together_$i.err" &
    pids+=($!)
done
together=0
for p in "${pids[@]}"; do wait "$p" || together=1; done
[ $together -eq 0 ] || cat "$work"/together_*.err
check sil_runs_at_once_share_new_parents $together

echo "outputs_cli_test.sh: $failures failure(s)"
[ "$failures" -eq 0 ]
