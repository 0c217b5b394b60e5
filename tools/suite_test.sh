#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ctest check of the realistic suite (scenarios/suite/*.ini, docs/suite.md):
# every case parses and flies its first 3 s (where most disturbances start)
# without divergence for the LADRC family, the gust blocks match what
# tools/gusts.py makes of their parameters, and scenarios/paper_tuned.ini
# parses. The family flies the library's default gains here (tune = none):
# tune = margins takes seconds per axis in Debug, and the full suite
# (tools/suite.sh) flies the tuned gains and reports failed tunings.
# Usage: suite_test.sh LADRC_SIL SOURCE_DIR PYTHON
set -uo pipefail
sil=$1
src=$2
py=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { # name, condition exit code
  if [[ $2 -eq 0 ]]; then echo "suite_test.sh:$1:PASS"; else echo "suite_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

cases=("$src"/scenarios/suite/*.ini)
[[ ${#cases[@]} -ge 8 ]]; check at_least_eight_cases $?

family=(HP-MLADRC LP-MLADRC LADRC)
sets=(--set run.duration_s=3 --set "metrics.error_window_s=0 3" --set "metrics.steady_window_s=2 3"
      --set "metrics.settle_window_s=0 3")
for c in "${family[@]}"; do sets+=(--set "controller:$c.tune=none"); done
"$sil" "${cases[@]}" "${sets[@]}" --controllers "${family[*]}" --no-csv --quiet --jobs 2 \
  --out "$work/out" > "$work/tables.txt" 2> "$work/err.txt"
rc=$?
cat "$work/err.txt"
[[ $rc -eq 0 ]]; check family_flies_every_case_without_divergence $rc

for f in "${cases[@]}"; do
  name=$(basename "$f" .ini)
  m="$work/out/$name/metrics.csv"
  # Every family run: diverged 0, and a finite RMS on each axis.
  ok=0
  for c in "${family[@]}"; do
    [[ $(awk -F, -v c="$c" '$2 == c && $4 == "diverged" {print $6}' "$m" 2>/dev/null) == 0 ]] || ok=1
    n=$(awk -F, -v c="$c" '$2 == c && $3 == "4" && $4 == "error_rms_deg" && $6 + 0 == $6 && $6 < 90 {n++} END {print n + 0}' \
      "$m" 2>/dev/null)
    [[ $n -eq 3 ]] || ok=1
  done
  check "${name}_flies" $ok
done

gusts=$(grep -l '^# gusts:begin' "${cases[@]}")
[[ -n $gusts ]]; check has_gust_cases $?
# shellcheck disable=SC2086
"$py" "$src/tools/gusts.py" --check $gusts; check gusts_current $?
# A stale block is caught: one amplitude changed.
one=$(echo "$gusts" | head -n 1)
sed 's/^roll = [0-9.]*\*/roll = 99*/' "$one" > "$work/stale.ini"
"$py" "$src/tools/gusts.py" --check "$work/stale.ini" 2> /dev/null
[[ $? -eq 1 ]]; check gusts_check_catches_a_stale_block $?

"$sil" "$src/scenarios/paper_tuned.ini" --set run.duration_s=1 --set "metrics.error_window_s=0 1" \
  --set "metrics.steady_window_s=0 1" --set "metrics.settle_window_s=0 1" \
  --set controller:LADRC.tune=none --controllers LADRC --no-csv --quiet --out "$work/out" > /dev/null
check paper_tuned_parses $?

# The generated table (tools/suite_report.py) on these short runs: a controller left untunable
# reads "untunable", never a number, and is listed with its reason; a case-axis without the
# family is a loss.
sed -i 's/^\(racer_tones,LADRC,[^,]*,[^,]*,[^,]*,\).*/\1untunable/' "$work/out/racer_tones/metrics.csv"
printf 'racer_tones,LADRC,tune,status,-,untunable\n' >> "$work/out/racer_tones/metrics.csv"
printf 'untunable LADRC: not flown: LADRC on roll cannot meet PM >= 45 deg\n' > "$work/out/racer_tones/tables.txt"
"$py" -c 'import sys; sys.path.insert(0, sys.argv[1]); import suite_report
print("\n".join(suite_report.suite_block(sys.argv[2])))' "$src/tools" "$work/out" > "$work/suite.md"
check suite_table_is_written $?
grep -q '^| `racer_tones` | roll | [0-9.e-]* | [0-9.e-]* | \*\*untunable\*\* |' "$work/suite.md"
check suite_table_marks_untunable $?
grep -q '^- `racer_tones` LADRC: LADRC on roll cannot meet PM >= 45 deg' "$work/suite.md"; check suite_table_lists_untunable $?
grep -q '^- `big5_gusts` roll: no incumbent flew' "$work/suite.md"; check suite_table_lists_missing_figures $?

# The front page's summary: one row per case, a case-axis without an incumbent counted as a loss.
"$py" -c 'import sys; sys.path.insert(0, sys.argv[1]); import suite_report
print("\n".join(suite_report.front_page_lines(sys.argv[2])))' "$src/tools" "$work/out" > "$work/front.md"
check front_page_summary_is_written $?
[[ $(grep -c '^| `' "$work/front.md") -eq $(ls "$src/scenarios/suite/"*.ini | wc -l) ]]
check front_page_summary_has_a_row_per_case $?
grep -q '^| `big5_gusts` | \*\*—\*\* |' "$work/front.md"; check front_page_summary_marks_missing_ratio $?
grep -q 'loses on [1-9][0-9]* of [0-9]* case-axes' "$work/front.md"; check front_page_summary_counts_losses $?

echo "suite_test.sh: $failures failure(s)"
[[ $failures -eq 0 ]]
