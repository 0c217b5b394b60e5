#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# tools/betaflight_study.py end to end against the stand-in SITL (sim/tests/fake_bf_sitl.c, whose
# gains follow Betaflight's master slider): on the flips case it writes the study with its verdict
# table, picks the slider whose step flight has the least RMS error (the stand-in's error falls as
# its gain rises: the largest, 200 %), states the speed, and refuses a folder without a SITL.
# Usage: betaflight_study_test.sh FAKE_SITL LADRC_SIL
set -uo pipefail
cd "$(dirname "$0")/.."
fake=$1
sil=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
check() { if [ "$2" -eq 0 ]; then echo "betaflight_study_test.sh:$1:PASS"; else echo "betaflight_study_test.sh:$1:FAIL"; failures=$((failures + 1)); fi; }
mkdir -p "$work/sitl"
cp "$fake" "$work/sitl/betaflight_SITL.elf"
printf 'feature RX_UDP\nsave\n' > "$work/sitl/sitl_config.cli"
(cd "$work/sitl" && ./betaflight_SITL.elf --config sitl_config.cli > /dev/null)
/usr/bin/python3 tools/betaflight_study.py --sil "$sil" --sitl "$work/sitl" --out "$work/study.md" --work "$work/w" \
    --cases scenarios/large_angle/flips.ini 2> "$work/err"
check runs "$?"
check verdict "$(grep -q '^## Verdict' "$work/study.md" && grep -q '^| flips | roll |' "$work/study.md"; echo $?)"
check slider "$(grep -q 'Slider picked: 200 %' "$work/study.md"; echo $?)"
check repeatable "$(grep -q 'the same metrics byte for byte on 1 of 1 cases' "$work/study.md"; echo $?)"
check speed "$(grep -q 'Speed (x real time): BF slider [0-9]*x, BF stock [0-9]*x' "$work/study.md"; echo $?)"
/usr/bin/python3 tools/betaflight_study.py --sil "$sil" --sitl "$work/none" --out "$work/none.md" --work "$work/w2" 2> "$work/err2"
check refuses_missing "$([ $? -ne 0 ] && grep -q 'no betaflight_SITL.elf' "$work/err2" && [ ! -e "$work/none.md" ] && echo 0 || echo 1)"
[ "$failures" -eq 0 ] && echo "betaflight_study_test.sh: all passed" || echo "betaflight_study_test.sh: $failures failed"
exit $((failures > 0))
