#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# ctest check of tools/figures.py and tools/report.py: flies the short scenarios
# of tests/data (the paper's cases cut to a few seconds) and checks that every
# figure and the report come out and are not trivial.
# Usage: figures_test.sh LADRC_SIL SOURCE_DIR
# Exit status 77 (reported by ctest as skipped) when matplotlib or numpy is missing.
set -uo pipefail
sil=$1
src=$2

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
  if [[ $2 -eq 0 ]]; then echo "figures_test.sh:$1:PASS"; else echo "figures_test.sh:$1:FAIL"; failures=$((failures + 1)); fi
}

"$sil" "$src/tests/data/short_paper.ini" "$src/tests/data/short_paper_noisy.ini" \
  "$src/tests/data/short_paper_known.ini" "$src/tests/data/short_paper_noisy_known.ini" \
  "$src/tests/data/short_differentiator.ini" --out "$work/out" --quiet > "$work/out.tables.txt"
check simulator_runs $?
mv "$work/out.tables.txt" "$work/out/tables.txt"
names=(--paper short_paper --noisy short_paper_noisy --known short_paper_known --diff short_differentiator)
report_names=("${names[@]}" --noisy-known short_paper_noisy_known)

"$py" "$src/tools/figures.py" "$work/out" "$work/fig" "${names[@]}"
check figures_py_succeeds $?
"$py" "$src/tools/report.py" "$work/out" "$work/report.md" "${report_names[@]}"
check report_py_succeeds $?

# 0 when file is a PNG (signature) of at least width x height pixels (IHDR) and more than bytes.
png_ok() { # file, width, height, bytes
  [[ -f $1 ]] || return 1
  local hdr w h size
  read -r -a hdr < <(od -An -tu1 -N24 "$1" | tr -s ' \n' ' ')
  w=$(( (hdr[16] << 24) | (hdr[17] << 16) | (hdr[18] << 8) | hdr[19] ))
  h=$(( (hdr[20] << 24) | (hdr[21] << 16) | (hdr[22] << 8) | hdr[23] ))
  size=$(wc -c < "$1")
  echo "$(basename "$1"): ${w}x${h}, $size bytes"
  [[ ${hdr[1]} -eq 80 && ${hdr[2]} -eq 78 && ${hdr[3]} -eq 71 && $w -ge $2 && $h -ge $3 && $size -gt $4 ]]
}

# Every figure: at least 800 x 500 pixels, more than 20 kB.
for fig in fig05_td_levant fig06_tracking fig06_tracking_onsets fig07_errors fig07_errors_onsets \
           fig08_radar fig09_disturbance fig10_noisy_tracking fig11_noisy_errors fig12_rotors fig13_hp_modes; do
  png_ok "$work/fig/$fig.png" 800 500 20000
  check "$fig" $?
done

# The estimators' figure of a run (tools/estimators_plot.py): a PNG of its 15 x 8.5 in size, and the
# gate's summary per axis; a scenario without HP-MLADRC and LP-MLADRC runs is an error.
"$py" "$src/tools/estimators_plot.py" "$work/out" "$work/fig" short_paper > "$work/est.txt"
check estimators_plot_succeeds $?
png_ok "$work/fig/fig14_estimators_short_paper.png" 1200 700 50000
check fig14_estimators $?
[[ $(grep -c "short_paper \(roll\|pitch\|yaw\): HP gate weight > 0.5 for" "$work/est.txt") -eq 3 ]]
check estimators_plot_summarises_each_axis $?
[[ $(grep -c "short_paper \(roll\|pitch\|yaw\): LP d̂ against f over (2.00, " "$work/est.txt") -eq 3 ]]
check estimators_plot_compares_lp_with_f $?
"$py" "$src/tools/estimators_plot.py" "$work/out" "$work/fig" short_differentiator > /dev/null 2>&1
[[ $? -eq 1 ]]; check estimators_plot_refuses_a_scenario_without_the_runs $?

# The report: every table's heading, the paper's numbers, and ours from metrics.csv.
r="$work/report.md"
for heading in "## Table 3" "## Table 4" "## Table 5" "## Table 6" "## Table 7" "## Noisy case" "## HP-MLADRC: frequency known"; do
  grep -q "^$heading" "$r"; check "report_has_${heading#\#\# }" $?
done
grep -q "| TD | .* | 2.767 |" "$r"; check report_has_paper_table3 $?
grep -q "1.1823 / " "$r"; check report_has_paper_table4 $?
grep -q "100035" "$r"; check report_has_paper_table7 $?
# (report.py's format: 4 decimals, or 3 significant digits below 0.001)
ours=$(awk -F, '$2 == "LADRC" && $4 == "error_rms_deg" && $5 == "roll" {
  v = $6 < 0 ? -$6 : $6; printf ((v < 0.001 && v != 0) ? "%.2e" : "%.4f"), $6 }' \
  "$work/out/short_paper/metrics.csv")
[[ -n $ours ]] && grep -qF "7.6816 / $ours (" "$r"; check report_has_our_table4_value $?
! grep -q "No output of scenario" "$r"; check report_complete $?

# A paper case whose PID run diverges (a 60 ms motor lag no controller models): the
# simulator exits 3, and the report and figures still come out, with words
# ("diverged") where the statistics would be and the divergence in Run health.
sed 's/^ideal = yes.*/ideal = yes\nmotor_tau_s = 0.06/' "$src/tests/data/short_paper.ini" > "$work/short_div.ini"
"$sil" "$work/short_div.ini" --out "$work/out" --quiet > /dev/null 2>&1
[[ $? -eq 3 ]]; check diverged_simulator_exits_3 $?
div_names=(--paper short_div --noisy short_paper_noisy --known short_paper_known --diff short_differentiator)
"$py" "$src/tools/figures.py" "$work/out" "$work/fig_div" "${div_names[@]}" > /dev/null
[[ $? -eq 0 && -f $work/fig_div/fig08_radar.png && -f $work/fig_div/fig06_tracking.png ]]
check figures_py_draws_diverged_runs $?
"$py" "$src/tools/report.py" "$work/out" "$work/report_div.md" "${div_names[@]}" --noisy-known short_paper_noisy_known \
  > /dev/null
check report_py_reads_diverged_runs $?
grep -q "^| PID | roll | 0.0466 / diverged (—) | 1.4897 / diverged (—) |" "$work/report_div.md" &&
  grep -q "^Run health (short_div): .*PID: DIVERGED at [0-9.]* s on [a-z]* (|error| 9[0-9.]* deg)" "$work/report_div.md"
check report_says_diverged $?

# Any scenario other than the paper's: titles name it and the marks are its own
# disturbance windows (its signals.csv); the paper's keep the paper's.
printf '[run]\nduration_s = 2\ncontrollers = LADRC PID\n[reference]\nroll = 5\n[disturbance]\nroll = 0.5 .. 1.25 : 3\n' \
  > "$work/gusty.ini"
"$sil" "$work/gusty.ini" --out "$work/out" --quiet > /dev/null
check simulator_writes_signals_csv $?
PYTHONPATH="$src/tools" "$py" - "$work/out" <<'PY'
import sys
import figures
out = sys.argv[1]
g = figures.Scenario(out, "gusty")
s = figures.Scenario(out, "short_paper")
p = figures.Scenario(out, "paper")  # the paper's: no output needed, the paper's onsets
assert g.onsets == [0.5, 1.25], g.onsets
assert s.onsets == [2.0, 6.0, 12.0, 25.0], s.onsets
assert p.onsets == figures.ONSETS_S and p.paper and not g.paper
assert g.title(6, "attitude tracking, paper case", "Attitude tracking") == "Attitude tracking, scenario gusty"
assert p.title(6, "attitude tracking, paper case", "x") == "Fig. 6: attitude tracking, paper case"
PY
check figures_title_and_mark_the_scenario $?
"$py" "$src/tools/figures.py" "$work/out" "$work/fig_gusty" --paper gusty --noisy gusty --known gusty \
  --diff short_differentiator > /dev/null
[[ $? -eq 0 && -f $work/fig_gusty/fig06_tracking.png && -f $work/fig_gusty/fig06_tracking_onsets.png &&
   -f $work/fig_gusty/fig12_rotors.png ]]
check figures_py_draws_any_scenario $?

echo "$failures failed"
[[ $failures -eq 0 ]]
