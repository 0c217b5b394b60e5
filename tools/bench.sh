#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Measures the cost of the controllers and prints Markdown tables, each
# budget figure marked against the budget of issue 6 ("meets" / "over").
#
# Usage: tools/bench.sh            print the tables
#        tools/bench.sh --readme   also rewrite README.md's Performance tables
#        tools/bench.sh --check    deterministic figures only, against the
#                                  limits in tools/bench/limits.txt (CI: the
#                                  bench stage of tools/run_tests.sh); exits 1
#                                  naming every figure above its limit
#
#  - cases (tools/bench/bench_case.h): PID, LADRC, LP-MLADRC, HP-MLADRC, CASCADED, INDI,
#    LADRC-act and HP-MLADRC-act (with a 30 ms motor lag and 2 ticks modelled) on
#    the recorded closed loop of HP-MLADRC under the paper's one-tone
#    disturbance, and HP-MLADRC-2tones on a two-tone disturbance;
#  - instructions per tick on the Cortex-M4F: build/bench-m4f (the cortex-m4f
#    preset with LADRC_BUILD_BENCH=ON), image run under qemu mps2-an386 with
#    -icount shift=0, twice: the two outputs must be identical; the same
#    image times each module alone (where the instructions go);
#  - sizeof of the state and config structs (same image);
#  - flash and RAM of libladrc.a per object (arm-none-eabi-size);
#  - worst-case stack of one tick from -fcallgraph-info=su (tools/bench/stack.py);
#  - host: build/bench-host (the host-release preset with LADRC_BUILD_BENCH=ON),
#    ns per tick (median of 15 blocks) and instructions per tick under
#    valgrind --tool=callgrind (installed with apt-get when missing);
#  - simulator throughput: build/host-release ladrc_sil on scenarios/paper.ini,
#    wall time by the shell, best of 5 runs; the 1 -> 2 jobs speed-up also on
#    a batch of the scenario given 4 times (16 independent runs).
#
# Needs what the cortex-m4f and host-release builds need (tools/run_tests.sh
# installs it) and python3. --check needs only the cortex-m4f part.
set -euo pipefail

MODE=${1:-}
case $MODE in
  "" | --readme | --check) ;;
  *) echo "usage: tools/bench.sh [--readme | --check]" >&2; exit 2 ;;
esac

if [[ $MODE == --readme ]]; then
  table=$("$0")
  echo "$table"
  python3 - "$table" "$(dirname "${BASH_SOURCE[0]}")/../README.md" <<'PY'
import sys
table, path = sys.argv[1], sys.argv[2]
start, end = "<!-- performance:start -->", "<!-- performance:end -->"
text = open(path).read()
i, j = text.index(start) + len(start), text.index(end)
open(path, "w").write(text[:i] + "\n" + table + "\n" + text[j:])
PY
  exit 0
fi

cd "$(dirname "${BASH_SOURCE[0]}")/.."

JOBS=2
CROSS=build/bench-m4f
BENCH_HOST=build/bench-host
LIMITS=tools/bench/limits.txt
HOST=build/host-release
SCENARIO=scenarios/paper.ini
ROOTS=(ladrc_attitude_step ladrc_mixer_thrust_from_tilt ladrc_mixer_step ladrc_attitude_set_applied)

log() { echo "-- $*" >&2; }

log "building the Cortex-M4F benchmark ($CROSS)"
[[ -f $CROSS/CMakeCache.txt ]] || cmake --preset cortex-m4f -B "$CROSS" -DLADRC_BUILD_BENCH=ON >&2
cmake --build "$CROSS" -j "$JOBS" --target ladrc_bench_m4f ladrc_fw_hp >&2

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# --- instructions and sizes on the Cortex-M4F --------------------------------
qemu() {
  timeout 300 qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic -monitor none \
    -serial none -semihosting-config enable=on,target=native -icount shift=0 \
    -kernel "$CROSS/tools/bench/ladrc_bench_m4f.elf" 2>&1
}
log "running the benchmark under qemu -icount, twice"
qemu >"$tmp/run1"
qemu >"$tmp/run2"
if grep -q 'BENCH error' "$tmp/run1"; then
  cat "$tmp/run1" >&2
  exit 1
fi
if ! cmp -s "$tmp/run1" "$tmp/run2"; then
  echo "error: two runs of the benchmark gave different outputs:" >&2
  diff "$tmp/run1" "$tmp/run2" >&2 || true
  exit 1
fi
insn() { awk -v v="$1" -v c="$2" '$2 == "insn" && $3 == v { print $(3 + c) }' "$tmp/run1"; }
ipc=$(sed -n 's/^BENCH clock .*: \([0-9]*\) instructions per count.*/\1/p' "$tmp/run1")
worst() { awk -v v="$1" '$2 == "worst" && $3 == v { print $4 }' "$tmp/run1"; }
size_of() { awk -v t="$1" '$2 == "sizeof" && $3 == t { print $4 }' "$tmp/run1"; }

# --- library size ------------------------------------------------------------
arm-none-eabi-size -t "$CROSS/libladrc.a" >"$tmp/size"
lib_text=$(awk '/\(TOTALS\)/ { print $1 }' "$tmp/size")
lib_data=$(awk '/\(TOTALS\)/ { print $2 }' "$tmp/size")
lib_bss=$(awk '/\(TOTALS\)/ { print $3 }' "$tmp/size")
# What an HP-MLADRC firmware links of it (tools/bench/fw_hp.c, --gc-sections).
python3 tools/bench/linked.py "$CROSS/tools/bench/ladrc_fw_hp.map" libladrc.a >"$tmp/linked"
linked_hp=$(awk '$2 == "total" { print $3 }' "$tmp/linked")

# --- stack ---------------------------------------------------------------------
python3 tools/bench/stack.py "$CROSS/CMakeFiles/ladrc.dir" "${ROOTS[@]}" >"$tmp/stack"
stack_worst=$(awk '$1 == "STACK" && $3 > m { m = $3 } END { print m + 0 }' "$tmp/stack")
stack_root=$(awk '$1 == "STACK" && $3 > m { m = $3; r = $2 } END { print r }' "$tmp/stack")
stack_chain=$(awk -v r="$stack_root" '$1 == "STACK" && $2 == r { $1 = $2 = $3 = ""; sub(/^ +/, ""); print }' "$tmp/stack")
stack_ext=$(awk '$1 == "EXTERNAL" { $1 = ""; sub(/^ /, ""); print }' "$tmp/stack")

# --- check: the deterministic figures against tools/bench/limits.txt --------
# Gated figures by the keys limits.txt uses.
declare -A measured=(
  [flash.library]=$((lib_text + lib_data))
  [stack.tick]=$stack_worst
  [flash.linked_hp]=$linked_hp
  [sizeof.ladrc_attitude_t]=$(size_of ladrc_attitude_t)
)
CASES=(PID LADRC LP-MLADRC HP-MLADRC HP-MLADRC-2tones HP-MLADRC-act CASCADED INDI LADRC-act)
for v in "${CASES[@]}"; do
  measured[insn.axis.$v]=$(insn "$v" 1)
  measured[insn.3axes.$v]=$(insn "$v" 2)
  measured[insn.worst.$v]=$(worst "$v")
done
if [[ $MODE == --check ]]; then
  over=()
  printf '%-26s %10s %10s  %-8s %s\n' key value limit kind status
  while read -r key limit kind _; do
    [[ -z $key || $key == \#* ]] && continue
    if [[ $kind != budget && $kind != ceiling ]]; then
      echo "error: $LIMITS: $key: kind '$kind' is neither budget nor ceiling" >&2
      exit 2
    fi
    value=${measured[$key]:-}
    if [[ ! $value =~ ^[0-9]+(\.[0-9]+)?$ || ! $limit =~ ^[0-9]+(\.[0-9]+)?$ ]]; then
      echo "error: $LIMITS: $key: no number to compare (measured '$value', limit '$limit'; keys: ${!measured[*]})" >&2
      exit 2
    fi
    if awk -v x="$value" -v l="$limit" 'BEGIN { exit !(x <= l) }'; then
      status=ok
    else
      status=OVER
      over+=("$key = $value > $limit ($kind)")
    fi
    printf '%-26s %10s %10s  %-8s %s\n' "$key" "$value" "$limit" "$kind" "$status"
  done <"$LIMITS"
  if ((${#over[@]} > 0)); then
    echo "error: ${#over[@]} figure(s) above their limit in $LIMITS:" >&2
    printf '  %s\n' "${over[@]}" >&2
    exit 1
  fi
  echo "all gated figures within $LIMITS"
  exit 0
fi

log "building the simulator ($HOST)"
[[ -f $HOST/CMakeCache.txt ]] || cmake --preset host-release >&2
cmake --build --preset host-release --target ladrc_sil >&2

# --- host: time per tick and callgrind instruction counts ---------------------
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
"$HOST_BIN" >"$tmp/host"
host_ns() { awk -v v="$1" -v c="$2" '$2 == "host" && $3 == v { print $(3 + c) }' "$tmp/host"; }
callgrind_ir() { # instructions counted inside bench_collect() for one case
  valgrind --tool=callgrind --toggle-collect=bench_collect --callgrind-out-file="$tmp/cg.out" \
    "$HOST_BIN" --callgrind "$1" >"$tmp/cg.log" 2>&1 || { cat "$tmp/cg.log" >&2; return 1; }
  awk '/^totals:/ { print $2 }' "$tmp/cg.out"
}
log "counting host instructions under callgrind"
declare -A host_insn
cg_empty=$(callgrind_ir empty)
cg_ticks=$(sed -n 's/^BENCH host collected [^ ]* \([0-9]*\) ticks$/\1/p' "$tmp/cg.log")
for v in "${CASES[@]}"; do
  for c in axis attitude; do
    ir=$(callgrind_ir "$c:$v")
    host_insn[$c:$v]=$(awk -v a="$ir" -v b="$cg_empty" -v n="$cg_ticks" 'BEGIN { printf "%.1f", (a - b) / n }')
  done
done
cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo)
# --- simulator throughput --------------------------------------------------
duration=$(awk -F= '/^\[/ { s = $0 } s == "[run]" && $1 ~ /^duration_s/ { gsub(/[ \t]/, "", $2); print $2 }' "$SCENARIO")
controllers=$(awk -F= '/^\[/ { s = $0 } s == "[run]" && $1 ~ /^controllers/ { sub(/#.*/, "", $2); print $2 }' "$SCENARIO")
runs=$(echo $controllers | wc -w)
simulated=$(awk -v d="$duration" -v n="$runs" 'BEGIN { print d * n }')
# four copies under their own names: ladrc_sil refuses scenarios that would write the same directory
BATCH=()
for i in 1 2 3 4; do
  cp "$SCENARIO" "$tmp/batch$i.ini"
  BATCH+=("$tmp/batch$i.ini")
done
wall() { # best (least disturbed) wall seconds of 5 runs of ladrc_sil with the given options
  local t i
  for i in 1 2 3 4 5; do
    t=$( { TIMEFORMAT=%R; time "$HOST/sim/ladrc_sil" "${SCENARIOS[@]}" --quiet "$@" >/dev/null; } 2>&1 )
    echo "$t"
  done | sort -n | head -n 1
}
log "timing the simulator ($SCENARIO: $runs runs of $duration s)"
SCENARIOS=("$SCENARIO")
mkdir -p "$tmp/csv"
declare -A w_ctrl_nocsv w_ctrl_csv
for c in $controllers; do # one controller at a time: what each costs
  w_ctrl_nocsv[$c]=$(wall --no-csv --jobs 1 --controllers "$c")
  w_ctrl_csv[$c]=$(wall --jobs 1 --controllers "$c" --out "$tmp/csv")
done
w_nocsv1=$(wall --no-csv --jobs 1)
w_nocsv2=$(wall --no-csv --jobs 2)
w_csv1=$(wall --jobs 1 --out "$tmp/csv")
w_csv2=$(wall --jobs 2 --out "$tmp/csv")
SCENARIOS=("${BATCH[@]}")
w_batch1=$(wall --no-csv --jobs 1 --out "$tmp/batch")
w_batch2=$(wall --no-csv --jobs 2 --out "$tmp/batch")

# --- table -------------------------------------------------------------------
mark() { awk -v x="$1" -v op="$2" -v lim="$3" 'BEGIN { ok = op == "<=" ? x <= lim : op == "<" ? x < lim : x >= lim; print ok ? "meets" : "over" }'; }
rate() { awk -v s="${2:-$simulated}" -v w="$1" 'BEGIN { printf "%.0f", s / w }'; }
row() { printf '| %s | %s | %s | %s |\n' "$@"; }

hp3=$(insn HP-MLADRC 2)
pid3=$(insn PID 2)
ratio=$(awk -v a="$hp3" -v b="$pid3" 'BEGIN { printf "%.2f", a / b }')
att_size=$(size_of ladrc_attitude_t)
mix_size=$(size_of ladrc_mixer_t)
flash=$((lib_text + lib_data))
ram=$((lib_data + lib_bss))
r_nocsv=$(rate "$w_nocsv1")
r_csv=$(rate "$w_csv1")
speedup_nocsv=$(awk -v a="$w_nocsv1" -v b="$w_nocsv2" 'BEGIN { printf "%.2f", a / b }')
speedup_csv=$(awk -v a="$w_csv1" -v b="$w_csv2" 'BEGIN { printf "%.2f", a / b }')
speedup_batch=$(awk -v a="$w_batch1" -v b="$w_batch2" 'BEGIN { printf "%.2f", a / b }')

echo "| measure | value | budget | status |"
echo "|---|---:|---:|---|"
label() { [[ $1 == HP-MLADRC-2tones ]] && echo "HP-MLADRC (two tones)" || echo "$1"; }
for v in "${CASES[@]}"; do
  row "$(label "$v"), one axis (ladrc_axis_step_with_rate), instructions/tick" "$(insn "$v" 1)" "" ""
done
for v in PID LADRC LP-MLADRC; do
  row "$v, 3 axes + mixer, instructions/tick" "$(insn "$v" 2)" "" ""
done
row "HP-MLADRC, 3 axes + mixer, instructions/tick" "$hp3" "<= 1500" "$(mark "$hp3" "<=" 1500)"
row "HP-MLADRC (two tones), 3 axes + mixer, instructions/tick" "$(insn HP-MLADRC-2tones 2)" "" ""
row "ratio HP-MLADRC / PID, 3 axes + mixer" "$ratio" "" ""
for v in HP-MLADRC-act CASCADED INDI LADRC-act; do
  row "$v, 3 axes + mixer, instructions/tick" "$(insn "$v" 2)" "" ""
done
# The actuator model's own cost (LADRC-act against LADRC) and HP-MLADRC's with
# its command advanced over the modelled actuator, per axis.
per_axis() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", a - b }'; }
row "actuator model (30 ms lag, 2 ticks), extra instructions/tick per axis: LADRC" \
  "$(per_axis "$(insn LADRC-act 1)" "$(insn LADRC 1)")" "< 60" \
  "$(mark "$(per_axis "$(insn LADRC-act 1)" "$(insn LADRC 1)")" "<" 60)"
row "actuator model (30 ms lag, 2 ticks), extra instructions/tick per axis: HP-MLADRC (with its advanced command)" \
  "$(per_axis "$(insn HP-MLADRC-act 1)" "$(insn HP-MLADRC 1)")" "< 60" \
  "$(mark "$(per_axis "$(insn HP-MLADRC-act 1)" "$(insn HP-MLADRC 1)")" "<" 60)"
for v in "${CASES[@]}"; do
  row "$(label "$v"), 3 axes + mixer, dearest single tick, instructions (+-$ipc)" "$(worst "$v")" "" ""
done
for c in 1 2; do
  for v in "${CASES[@]}"; do
    row "$(label "$v"), $([[ $c == 1 ]] && echo "one axis" || echo "3 axes + mixer"), host, ns/tick" "$(host_ns "$v" "$c")" "" ""
  done
done
for c in axis attitude; do
  for v in "${CASES[@]}"; do
    row "$(label "$v"), $([[ $c == axis ]] && echo "one axis" || echo "3 axes + mixer"), host, instructions/tick (callgrind)" "${host_insn[$c:$v]}" "" ""
  done
done
row "3-axis state, sizeof(ladrc_attitude_t), B" "$att_size" "<= 512" "$(mark "$att_size" "<=" 512)"
row "mixer state, sizeof(ladrc_mixer_t), B" "$mix_size" "" ""
for t in ladrc_attitude_config_t ladrc_axis_t ladrc_axis_config_t ladrc_mixer_config_t \
         ladrc_pid_t ladrc_cascaded_t ladrc_leso_t ladrc_td_t ladrc_levant_t ladrc_lp_estimator_t \
         ladrc_hp_estimator_t ladrc_rls_t ladrc_indi_t; do
  row "sizeof($t), B" "$(size_of "$t")" "" ""
done
row "library flash (text + data), B" "$flash" "<= 8192" "$(mark "$flash" "<=" 8192)"
while read -r text data _bss _dec _hex obj _rest; do
  row "flash of ${obj%.obj}, B" "$((text + data))" "" ""
done < <(grep '\.obj ' "$tmp/size")
row "library RAM (data + bss), B" "$ram" "" ""
row "library flash an HP-MLADRC firmware links (tools/bench/fw_hp.c, --gc-sections), B" "$linked_hp" "" ""
row "worst-case stack of one tick, B" "$stack_worst" "<= 256" "$(mark "$stack_worst" "<=" 256)"
for c in $controllers; do
  row "simulator, paper, $c alone, no CSV, --jobs 1, x real time" "$(rate "${w_ctrl_nocsv[$c]}" "$duration")" "" ""
  row "simulator, paper, $c alone, full CSV, --jobs 1, x real time" "$(rate "${w_ctrl_csv[$c]}" "$duration")" "" ""
done
row "simulator, paper, no CSV, --jobs 1, x real time" "$r_nocsv" ">= 2000" "$(mark "$r_nocsv" ">=" 2000)"
row "simulator, paper, full CSV, --jobs 1, x real time" "$r_csv" ">= 300" "$(mark "$r_csv" ">=" 300)"
row "simulator, paper x${#BATCH[@]} ($((runs * ${#BATCH[@]})) runs), no CSV, --jobs 2, x real time" "$(rate "$w_batch2" "$(awk -v s="$simulated" -v n="${#BATCH[@]}" 'BEGIN { print s * n }')")" "" ""
row "simulator, paper ($runs runs), no CSV, speed-up --jobs 1 -> 2" "$speedup_nocsv" "" ""
row "simulator, paper ($runs runs), full CSV, speed-up --jobs 1 -> 2" "$speedup_csv" "" ""
row "simulator, paper x${#BATCH[@]} ($((runs * ${#BATCH[@]})) runs), no CSV, speed-up --jobs 1 -> 2" "$speedup_batch" ">= 1.8" "$(mark "$speedup_batch" ">=" 1.8)"

echo
BENCH_TICKS=$(sed -n 's/^BENCH clock .*; \([0-9]*\) ticks per block.*$/\1/p' "$tmp/run1")
echo "$(sed -n 's/^BENCH clock //p' "$tmp/run1"); the empty loop (same inputs, no call) is subtracted; two runs gave identical counts."
engaged() { awk -v c="$1" -v k="$2" '$2 == "engaged" && $3 == c && $4 == k { print "weight " $6 " from tick " $11 ", " $8 " tone(s)" }' "$tmp/run1"; }
echo "Mixer in LADRC_MIXER_SATURATE (rotor limits 1e4..2e5 rad^2/s^2), thrust from ladrc_mixer_thrust_from_tilt. Inputs: the paper references from t = 12 s and the angles and rates of the closed loop the HP-MLADRC controller itself flies from reset (rigid body with the paper's inertia, drag 0.09 N m s and gyroscopic coupling; achieved torques applied) under the Table 2 disturbance 20 -+ 120 sin(3 t) rad/s^2 on roll and pitch, a quarter of it on yaw, or for the two-tone case the same plus 30 sin(8 t) (yaw: a quarter); so the timed HP-MLADRC cases repeat that closed loop and their estimators run engaged over the measured ticks (checked: one tone, 3 axes: $(engaged HP-MLADRC attitude), one axis: $(engaged HP-MLADRC axis); two tones, 3 axes: $(engaged HP-MLADRC-2tones attitude), one axis: $(engaged HP-MLADRC-2tones axis)). The warm-up is long enough for that. The other variants see the same angles in open loop. The disturbance's peaks ask for more roll and pitch torque than the rotor limits leave at hover thrust, so in the HP-MLADRC 3-axis cases the mixer cuts thrust or yaw back on $(awk '$2 == "saturated" && $3 == "HP-MLADRC" { print $4 }' "$tmp/run1") (one tone) and $(awk '$2 == "saturated" && $3 == "HP-MLADRC-2tones" { print $4 }' "$tmp/run1") (two tones) of the $BENCH_TICKS measured ticks, and ladrc_mixer_step takes its saturating path."
echo "Host: $cpu, gcc Release (-O3) build $BENCH_HOST; ns/tick: $(sed -n 's/^BENCH host clock //p' "$tmp/host"). Instructions/tick: x86-64 instructions counted by valgrind --tool=callgrind --toggle-collect=bench_collect (only the $cg_ticks measured ticks, after the same warm-up), minus the same count for the empty loop, divided by $cg_ticks; deterministic, not comparable with the Cortex-M4F counts."
echo "Stack: deepest of ${ROOTS[*]}; chain: $stack_chain; not counted (C library): $stack_ext."
echo "Simulator: $runs runs of $duration s ($simulated s simulated), best wall time of 5; x real time = simulated s / wall s on $(nproc) cores; one controller alone: --controllers NAME, $duration s simulated."

# --- where the instructions go -------------------------------------------------
mod() { awk -v k="$1" '$2 == "module" && $3 == k { print $4 }' "$tmp/run1"; }
calc() { awk "BEGIN { printf \"%.2f\", $1 }"; }
fit_decimation=$(awk '$2 == "hp_fit_decimation" { print $3 }' "$tmp/run1")
leso=$(mod ladrc_leso_step)
levant=$(mod ladrc_levant_step)
hp=$(mod ladrc_hp_step)
twin=$(mod ladrc_leso_step_twin)
hp2=$(mod ladrc_hp_step_2tones)
rls3=$(mod ladrc_rls_update_3)
rls5=$(mod ladrc_rls_update_5)
lone=$(mod lone_hp_axes_x3)
thrust=$(mod ladrc_mixer_thrust_from_tilt)
mixer=$(mod ladrc_mixer_step)
hp_own=$(calc "$hp - $rls3 / $fit_decimation")
hp2_own=$(calc "$hp2 - $rls5 / $fit_decimation")
axis_rest=$(calc "$lone / 3 - $leso - $twin - $levant - $hp")
att_rest=$(calc "$hp3 - $lone - $thrust - $mixer")
share() { calc "100 * $1 * $2 / $hp3"; }
brow() { # module, instructions/call, calls per tick (0: not part of the tick, no share)
  if [[ $3 == 0 ]]; then
    printf '| %s | %s | 0 |  |\n' "$1" "$2"
  else
    printf '| %s | %s | %s | %s %% |\n' "$1" "$2" "$3" "$(share "$2" "$3")"
  fi
}

echo
echo "Where the instructions of the HP-MLADRC 3-axis + mixer tick go (Cortex-M4F, same build and method):"
echo
echo "| module | instructions/call | calls per HP 3-axis tick | share of the HP 3-axis tick |"
echo "|---|---:|---:|---:|"
brow "ladrc_leso_step (each axis's observer)" "$leso" 3
brow "ladrc_leso_step_twin (each HP axis's shadow observer)" "$twin" 3
brow "ladrc_levant_step (implicit, the HP axis default)" "$levant" 3
brow "ladrc_hp_step without its RLS update (gate, tones, online frequencies, model), one tone" "$hp_own" 3
brow "ladrc_rls_update, 3 params (HP fit of bias and one tone, every $fit_decimation ticks)" "$rls3" "$(calc "3 / $fit_decimation")"
brow "rest of ladrc_axis_step_with_rate (checks, hand-over, control law) and the feed setters: a lone HP axis minus the rows above" "$axis_rest" 3
brow "ladrc_mixer_thrust_from_tilt" "$thrust" 1
brow "ladrc_mixer_step (allocate, saturate)" "$mixer" 1
brow "rest of the 3-axis tick (coupling feed, known part): the tick minus 3 lone axes and the mixer rows" "$att_rest" 1
brow "HP-MLADRC 3 axes + mixer, measured" "$hp3" 1
brow "not in this tick: ladrc_hp_step without its RLS update, two tones" "$hp2_own" 0
brow "not in this tick: ladrc_rls_update, 5 params (HP fit of bias and two tones)" "$rls5" 0
brow "not in this tick: HP-MLADRC (two tones) 3 axes + mixer, measured" "$(insn HP-MLADRC-2tones 2)" 0
brow "not in this tick: ladrc_td_step (LADRC's shaper)" "$(mod ladrc_td_step)" 0
brow "not in this tick: ladrc_lp_step (LP-MLADRC, with its 1-param RLS)" "$(mod ladrc_lp_step)" 0
brow "not in this tick: ladrc_pid_step (PID)" "$(mod ladrc_pid_step)" 0
echo
echo "Each module is timed alone like the ticks ($(sed -n 's/^BENCH clock .*; \([0-9]* ticks per block.*\)$/\1/p' "$tmp/run1")), configured as the axis defaults configure it, on the inputs it sees in the HP 3-axis case (replayed): its torques, thrust, applied torques, d_hat, fed rates and known parts, the references and angles; ladrc_hp_step on roll's recorded HP sample (z3 - z3 of the shadow), one tone and two tones, engaged over the measured ticks like the axes ($(awk '$2 == "hp_state" && $3 ~ /^ladrc_hp_step/ { printf "%s%s: weight %s, %s tone(s)", sep, $3, $5, $7; sep = "; " }' "$tmp/run1")); the RLS on the regressors of the fit (bias, the phasors at 3 and 8 rad/s at the fit samples' times) and the disturbance, at the engaged fit's forgetting. Lone axes: the three HP-MLADRC axes configured as the attitude configures them, each tick given the recorded fed rate, known part and applied torque, stepped side by side, no attitude layer, no mixer ($lone instructions per tick for the three). The two \"rest\" rows make the shares add up to the measured tick, so they also carry any difference between the modules alone and inside the tick."
