#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets of tests/fuzz (clang, -fsanitize=fuzzer,
# address,undefined) and runs each, one core per target, starting from the
# committed seed corpus and dictionary of the target (docs/fuzzing.md).
#
# Usage: tools/fuzz.sh [--long | --time S | --runs N] [--build-only] [TARGET...]
#   (default)     CI form: each target for 60 s
#   --long        long form: 10^7 executions of each target
#   --time S      each target for S seconds
#   --runs N      N executions of each target
#   --build-only  build the targets, run nothing
#   TARGET        fuzz_scenario, fuzz_expr, fuzz_log, fuzz_ulog, fuzz_bbl, fuzz_dataflash, fuzz_gyro_filter
#                 (default: every tests/fuzz/fuzz_*.c)
#
# Prints per target the executions, their rate, the corpus and the findings
# (crash, leak, undefined behaviour, failed check, timeout, out of memory),
# whose inputs are kept in build/fuzz/artifacts/TARGET/. Exit status 1 on
# any finding, 2 on bad usage. New corpus inputs go to build/fuzz/corpus/TARGET
# (not committed). Environment: CC (default clang), FUZZ_JOBS (targets run at
# once, default 2), FUZZ_OUT (build and work directory, default build/fuzz).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

usage() { sed -n '3,22s/^# \{0,1\}//p' "$0"; }

mode=(-max_total_time=60)
build_only=0
targets=()
while [[ $# -gt 0 ]]; do
  case $1 in
    -h | --help) usage; exit 0 ;;
    --long) mode=(-runs=10000000) ;;
    --time) [[ $# -ge 2 && $2 =~ ^[0-9]+$ ]] || { usage >&2; exit 2; }; mode=(-max_total_time="$2"); shift ;;
    --runs) [[ $# -ge 2 && $2 =~ ^[0-9]+$ ]] || { usage >&2; exit 2; }; mode=(-runs="$2"); shift ;;
    --build-only) build_only=1 ;;
    fuzz_*) [[ -f tests/fuzz/$1.c ]] || { echo "fuzz.sh: no target $1" >&2; exit 2; }; targets+=("$1") ;;
    *) usage >&2; exit 2 ;;
  esac
  shift
done
if [[ ${#targets[@]} -eq 0 ]]; then
  for source in tests/fuzz/fuzz_*.c; do
    name=$(basename "$source" .c)
    [[ $name == fuzz_common ]] || targets+=("$name")
  done
fi

CC=${CC:-clang}
JOBS=${FUZZ_JOBS:-2}
out=${FUZZ_OUT:-build/fuzz}
obj=$out/obj
mkdir -p "$obj"

# The library, the analysis library and the simulator core (not its command
# lines), instrumented
# for coverage and the sanitizers; each target links them with libFuzzer.
CFLAGS=(-std=c99 -g -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link,address,undefined
        -fno-sanitize-recover=all -Wall -Wextra -Wpedantic -Werror -Iinclude -Ianalysis/include -Isim -Itests/fuzz -Itests/support)
sources=()
objects=()
for source in src/*.c analysis/*.c sim/*/*.c tests/fuzz/fuzz_common.c; do
  [[ $source == sim/tests/* || $source == sim/cli/main.c || $source == sim/cli/margins_main.c || $source == sim/cli/replay_main.c ||
        $source == sim/cli/views_main.c || $source == sim/cli/filter_main.c ]] && continue
  sources+=("$source")
  objects+=("$obj/$(echo "${source%.c}" | tr / _).o")
done
echo "== fuzz: building ${targets[*]} with $("$CC" --version | head -n 1)"
# Every object again each time: a stale one would fuzz old code.
pids=()
for i in "${!sources[@]}"; do
  while [[ $(jobs -rp | wc -l) -ge $JOBS ]]; do sleep 0.1; done
  # The gyro filter's integer compares are loop bounds over channels and sections: no
  # guidance to trace, and tracing them took 2/3 of fuzz_gyro_filter's time.
  untraced=()
  [[ ${sources[$i]} == src/gyro_filter.c ]] && untraced=(-fno-sanitize-coverage=trace-cmp)
  "$CC" "${CFLAGS[@]}" "${untraced[@]}" -c "${sources[$i]}" -o "${objects[$i]}" &
  pids+=($!)
done
for pid in "${pids[@]}"; do
  wait "$pid" || { echo "fuzz.sh: build failed" >&2; exit 1; }
done
for target in "${targets[@]}"; do
  "$CC" "${CFLAGS[@]}" -fsanitize=fuzzer,address,undefined "tests/fuzz/$target.c" "${objects[@]}" -lm \
    -o "$out/$target"
done
[[ $build_only -eq 1 ]] && { echo "== fuzz: built in $out"; exit 0; }

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

# One target: its own corpus directory (new inputs) before the seeds (read only).
run_target() {
  local target=$1 name=${1#fuzz_}
  local max_len=4096 # scenario, log
  [[ $name == expr ]] && max_len=512
  [[ $name == bbl ]] && max_len=16384 # a header of some 1 KB and frames
  [[ $name == gyro_filter ]] && max_len=2048 # a config and up to some 2000 ticks
  rm -rf "$out/artifacts/$target"
  mkdir -p "$out/corpus/$target" "$out/artifacts/$target"
  "$out/$target" "${mode[@]}" -max_len=$max_len -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict="tests/fuzz/$name.dict" -artifact_prefix="$out/artifacts/$target/" \
    "$out/corpus/$target" "tests/fuzz/corpus/$name" > "$out/$target.log" 2>&1
}

echo "== fuzz: running ${targets[*]} (${mode[*]}, $JOBS at once); logs in $out/TARGET.log"
start=$(date +%s)
pids=()
status=()
for target in "${targets[@]}"; do
  while [[ $(jobs -rp | wc -l) -ge $JOBS ]]; do sleep 1; done
  run_target "$target" &
  pids+=($!)
done
for i in "${!targets[@]}"; do
  if wait "${pids[$i]}"; then status[$i]=0; else status[$i]=$?; fi
done

failed=0
for i in "${!targets[@]}"; do
  target=${targets[$i]}
  log=$out/$target.log
  final_stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -n 1; }
  runs=$(final_stat number_of_executed_units)
  rate=$(final_stat average_exec_per_sec)
  added=$(final_stat new_units_added)
  corpus=$(find "$out/corpus/$target" -type f | wc -l)
  findings=$(find "$out/artifacts/$target" -type f \
    \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  slow=$(find "$out/artifacts/$target" -type f -name 'slow-unit-*' | wc -l)
  if [[ ${status[$i]} -ne 0 && $findings -eq 0 ]]; then
    findings=1 # libFuzzer failed without leaving an input (a check in the harness itself)
  fi
  echo "$target: ${runs:-?} executions, ${rate:-?}/s, ${added:-?} new inputs ($corpus in $out/corpus/$target)," \
       "findings: $findings, slow inputs: $slow"
  if [[ $findings -ne 0 ]]; then
    failed=1
    grep -m 5 -E 'ERROR|runtime error|check failed|SUMMARY|Test unit written' "$log" | sed 's/^/  /' || true
  fi
done
echo "== fuzz: $(($(date +%s) - start)) s"
[[ $failed -eq 0 ]] || { echo "== fuzz: FINDINGS (inputs in $out/artifacts)" >&2; exit 1; }
