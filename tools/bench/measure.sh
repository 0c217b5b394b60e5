#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The measuring part of tools/bench.sh: builds the benchmarks, runs them and
# writes what they report, unprocessed, into one data file that
# tools/bench/render.py (Markdown tables, docs/performance.md) and tools/bench/check.py
# (limits) read. Nothing here judges a figure.
#
# Usage: tools/bench/measure.sh --m4f FILE   the Cortex-M4F part only (what
#                                            --check needs: deterministic)
#        tools/bench/measure.sh --all FILE   and the host timings, callgrind
#                                            counts and the simulator's speed
#
# FILE holds one record per line, "SOURCE TEXT": SOURCE names where TEXT
# comes from:
#   m4f       a line of the Cortex-M4F benchmarks' output under qemu -icount
#             (tools/bench/bench_m4f.c: "BENCH ...", tools/bench/bench_lean.c,
#             the lean HP build: "BENCH lean ..."), each the same in two runs
#   size      a line of arm-none-eabi-size -t on libladrc.a
#   linked    a line of tools/bench/linked.py on the HP-MLADRC firmware's map
#   linked-lean  the same on the lean HP firmware's map (tools/bench/fw_hp.c
#             against the lean HP build)
#   stack     a line of tools/bench/stack.py ("STACK root bytes chain",
#             "EXTERNAL names"); "stack-roots NAMES": the roots it was given
#   host      a line of the host benchmark (tools/bench/bench_host.c)
#   callgrind "ticks N", "empty IR", "KIND:CASE IR": instructions counted in
#             bench_collect() by valgrind --tool=callgrind
#   wall      "NAME SECONDS": best wall time of 5 runs of ladrc_sil
#   sim       "scenario PATH", "duration_s S", "controllers NAMES",
#             "batch N": the scenario timed and its runs
#   env       "cpu MODEL", "nproc N", "bench-host DIR"
# Exit status: 0, or 1 when a build or a run fails or two qemu runs differ.
set -euo pipefail

MODE=${1:-}
OUT=${2:-}
if [[ $MODE != --m4f && $MODE != --all ]] || [[ -z $OUT ]]; then
  echo "usage: tools/bench/measure.sh --m4f|--all FILE" >&2
  exit 2
fi

cd "$(dirname "${BASH_SOURCE[0]}")/../.."

JOBS=2
CROSS=build/bench-m4f
BENCH_HOST=build/bench-host
HOST=build/host-release
SCENARIO=scenarios/paper.ini
ROOTS=(ladrc_attitude_step ladrc_mixer_thrust_from_tilt ladrc_mixer_step ladrc_attitude_set_applied)

log() { echo "-- $*" >&2; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$(dirname "$OUT")"
FIG=$tmp/figures
: >"$FIG"
# record SOURCE < lines: each line of stdin as "SOURCE line"
record() { sed "s/^/$1 /" >>"$FIG"; }

# --- Cortex-M4F: instructions, sizes, stack --------------------------------------
log "building the Cortex-M4F benchmark ($CROSS)"
[[ -f $CROSS/CMakeCache.txt ]] || cmake --preset cortex-m4f -B "$CROSS" -DLADRC_BUILD_BENCH=ON >&2
cmake --build "$CROSS" -j "$JOBS" --target ladrc_bench_m4f ladrc_fw_hp ladrc_bench_lean ladrc_fw_hp_lean >&2

qemu() { # IMAGE
  timeout 300 qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic -monitor none \
    -serial none -semihosting-config enable=on,target=native -icount shift=0 \
    -kernel "$CROSS/tools/bench/$1.elf" 2>&1
}
for image in ladrc_bench_m4f ladrc_bench_lean; do
  log "running $image under qemu -icount, twice"
  qemu "$image" >"$tmp/run1"
  qemu "$image" >"$tmp/run2"
  if grep -q 'BENCH error' "$tmp/run1"; then
    cat "$tmp/run1" >&2
    exit 1
  fi
  if ! cmp -s "$tmp/run1" "$tmp/run2"; then
    echo "error: two runs of $image gave different outputs:" >&2
    diff "$tmp/run1" "$tmp/run2" >&2 || true
    exit 1
  fi
  record m4f <"$tmp/run1"
done

arm-none-eabi-size -t "$CROSS/libladrc.a" | record size
# What an HP-MLADRC firmware links of the library (tools/bench/fw_hp.c, --gc-sections).
python3 tools/bench/linked.py "$CROSS/tools/bench/ladrc_fw_hp.map" libladrc.a | record linked
python3 tools/bench/linked.py "$CROSS/tools/bench/ladrc_fw_hp_lean.map" libladrc.a | record linked-lean
echo "${ROOTS[*]}" | record stack-roots
python3 tools/bench/stack.py "$CROSS/CMakeFiles/ladrc.dir" "${ROOTS[@]}" | record stack

if [[ $MODE == --all ]]; then
  log "building the simulator ($HOST)"
  [[ -f $HOST/CMakeCache.txt ]] || cmake --preset host-release >&2
  cmake --build --preset host-release --target ladrc_sil >&2

  # --- host: time per tick and callgrind instruction counts -----------------------
  log "building the host benchmark ($BENCH_HOST)"
  [[ -f $BENCH_HOST/CMakeCache.txt ]] || cmake --preset host-release -B "$BENCH_HOST" -DLADRC_BUILD_BENCH=ON >&2
  cmake --build "$BENCH_HOST" -j "$JOBS" --target ladrc_bench_host >&2
  HOST_BIN=$BENCH_HOST/tools/bench/ladrc_bench_host
  if ! command -v valgrind >/dev/null 2>&1; then
    log "installing valgrind"
    sudo=()
    [[ $(id -u) -ne 0 ]] && sudo=(sudo)
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update >&2
    "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends valgrind >&2
  fi
  log "timing the host benchmark"
  "$HOST_BIN" | record host
  callgrind_ir() { # instructions counted inside bench_collect() for one case
    valgrind --tool=callgrind --toggle-collect=bench_collect --callgrind-out-file="$tmp/cg.out" \
      "$HOST_BIN" --callgrind "$1" >"$tmp/cg.log" 2>&1 || { cat "$tmp/cg.log" >&2; return 1; }
    awk '/^totals:/ { print $2 }' "$tmp/cg.out"
  }
  log "counting host instructions under callgrind"
  ir=$(callgrind_ir empty)
  echo "empty $ir" | record callgrind
  echo "ticks $(sed -n 's/^BENCH host collected [^ ]* \([0-9]*\) ticks$/\1/p' "$tmp/cg.log")" | record callgrind
  CASES=(PID LADRC LP-MLADRC HP-MLADRC HP-MLADRC-2tones HP-MLADRC-act CASCADED INDI LADRC-act RATE-ADRC HP-MLADRC-gyro)
  for v in "${CASES[@]}"; do
    for c in axis attitude; do
      ir=$(callgrind_ir "$c:$v")
      echo "$c:$v $ir" | record callgrind
    done
  done
  { echo "cpu $(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo)"
    echo "nproc $(nproc)"
    echo "bench-host $BENCH_HOST"; } | record env

  # --- simulator throughput ----------------------------------------------------------
  duration=$(awk -F= '/^\[/ { s = $0 }
    s == "[run]" && $1 ~ /^duration_s/ { gsub(/[ \t]/, "", $2); print $2 }' "$SCENARIO")
  controllers=$(awk -F= '/^\[/ { s = $0 }
    s == "[run]" && $1 ~ /^controllers/ { sub(/#.*/, "", $2); print $2 }' "$SCENARIO")
  # four copies under their own names: ladrc_sil refuses scenarios that would write the same directory
  BATCH=()
  for i in 1 2 3 4; do
    cp "$SCENARIO" "$tmp/batch$i.ini"
    BATCH+=("$tmp/batch$i.ini")
  done
  { echo "scenario $SCENARIO"
    echo "duration_s $duration"
    echo "controllers" $controllers
    echo "batch ${#BATCH[@]}"; } | record sim
  timed() { # NAME OPTIONS...: records "wall NAME SECONDS", the best (least disturbed) of 5 runs
    local name=$1 best
    shift
    best=$(wall "$@")
    echo "$name $best" | record wall
  }
  wall() { # best wall seconds of 5 runs of ladrc_sil with the given options
    local t i
    for i in 1 2 3 4 5; do
      t=$( { TIMEFORMAT=%R; time "$HOST/sim/ladrc_sil" "${SCENARIOS[@]}" --quiet "$@" >/dev/null; } 2>&1 )
      echo "$t"
    done | sort -n | head -n 1
  }
  log "timing the simulator ($SCENARIO: $(echo $controllers | wc -w) runs of $duration s)"
  SCENARIOS=("$SCENARIO")
  mkdir -p "$tmp/csv"
  for c in $controllers; do # one controller at a time: what each costs
    timed "ctrl_nocsv:$c" --no-csv --jobs 1 --controllers "$c"
    timed "ctrl_csv:$c" --jobs 1 --controllers "$c" --out "$tmp/csv"
  done
  timed "nocsv1" --no-csv --jobs 1
  timed "nocsv2" --no-csv --jobs 2
  timed "csv1" --jobs 1 --out "$tmp/csv"
  timed "csv2" --jobs 2 --out "$tmp/csv"
  SCENARIOS=("${BATCH[@]}")
  timed "batch1" --no-csv --jobs 1 --out "$tmp/batch"
  timed "batch2" --no-csv --jobs 2 --out "$tmp/batch"
fi

{ echo "# tools/bench/measure.sh $MODE: one measurement, read by tools/bench/render.py and check.py"
  cat "$FIG"; } >"$OUT.new"
mv "$OUT.new" "$OUT"
log "figures in $OUT"
