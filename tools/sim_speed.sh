#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The simulator's speed against an earlier commit's, and its outputs against
# that commit's, bit for bit.
#
# Usage: tools/sim_speed.sh [--runs N] [--no-check] [--no-timing] [BASE_COMMIT]
#   BASE_COMMIT  the simulator to compare with (default bba271b, main before
#                any speed work)
#   --runs N     timed runs of each build and case, alternating (default 7;
#                the best of them is reported)
#   --no-check   skip the output comparison; --no-timing skip the timing
#
# Both simulators are built the same way (CMake Release, the compiler's
# defaults: no -ffast-math, no -march, FP contraction off under -std=c99;
# the script stops if the compile line says otherwise): this work tree's in
# build/sim-speed/current, the base commit's from a temporary git worktree
# under build/sim-speed (removed after the build; the binary is kept in
# build/sim-speed/base-<commit> for the next call).
#
# Timing, wall clock by the shell, base and this build alternately, N times:
#   1. scenarios/paper.ini with HP-MLADRC LP-MLADRC LADRC PID (4 x 30 s =
#      120 s simulated), --no-csv --jobs 1: best times, speed-up, x real time;
#   2. the same writing every CSV (--jobs 1): x real time;
#   3. a 16-run batch (paper.ini under four names, the same 4 controllers),
#      --no-csv, --jobs 1 and --jobs 2: the speed-up from the second job;
#   4. this build only: paper.ini's six controllers (its controllers line,
#      6 x 30 s) with moderate Dryden turbulence and propeller vibration
#      (orders 1 2 3, the vibration cases' amplitudes), no CSV, --jobs 1;
#      and the same with the RPM notch bank and low-pass before them.
# The machine should be otherwise quiet; the figures are printed against the
# targets (2.5x, 2000x, 600x, 1.8x, 1500x) but never decide the exit status.
#
# Check: every shipped scenario (scenarios/*.ini) flown by both builds with
# every CSV; stdout, exit status and every file written must be the same
# bytes. Where the base writes a time series with an older header (columns
# since renamed or appended), the check is on the base's columns: the header
# differences are listed, and every row of the base must be the first fields
# of the same row here, byte for byte. A file the base writes that is missing
# here, or any other difference, fails: exit 1. Files only this build writes
# are listed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
ROOT=$PWD

RUNS=7
CHECK=1
TIMING=1
BASE=bba271b
while (($# > 0)); do
  case $1 in
    --runs) RUNS=${2:?--runs needs a number}; shift 2 ;;
    --no-check) CHECK=0; shift ;;
    --no-timing) TIMING=0; shift ;;
    -h | --help) sed -n '3,37p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "sim_speed.sh: unknown option '$1'" >&2; exit 2 ;;
    *) BASE=$1; shift ;;
  esac
done
[[ $RUNS =~ ^[1-9][0-9]*$ ]] || { echo "sim_speed.sh: --runs: expected a whole number >= 1, got '$RUNS'" >&2; exit 2; }
SHA=$(git rev-parse --verify --quiet "$BASE^{commit}") || { echo "sim_speed.sh: '$BASE' is not a commit" >&2; exit 2; }

JOBS=2
OUT=build/sim-speed
CONTROLLERS=HP-MLADRC,LP-MLADRC,LADRC,PID
SCENARIO=scenarios/paper.ini
log() { echo "-- $*" >&2; }

# Configures and builds ladrc_sil from SRC in BUILD, the same way for both.
build_sim() {
  local src=$1 build=$2
  [[ -f $build/CMakeCache.txt ]] ||
    cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DLADRC_BUILD_TESTS=OFF \
      -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
  cmake --build "$build" -j "$JOBS" --target ladrc_sil >/dev/null
  # The floating-point results depend on these: none may be there.
  if grep -E -e '-ffast-math|-Ofast|-march|-mfma|-mavx|-ffp-contract=fast|-funsafe-math|-fassociative-math' \
    "$build/compile_commands.json" >&2; then
    echo "sim_speed.sh: $build compiles with flags that change floating-point results" >&2
    exit 2
  fi
}

tmp=$(mktemp -d)
src=""
cleanup() {
  if [[ -n $src && -d $src ]]; then git worktree remove --force "$src" >/dev/null 2>&1 || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

NEW=$OUT/current/sim/ladrc_sil
log "building this work tree's simulator ($OUT/current)"
build_sim "$ROOT" "$OUT/current"
OLD=$OUT/base-$SHA/ladrc_sil
if [[ ! -x $OLD ]]; then
  log "building the simulator of $BASE (${SHA:0:12}) in a temporary worktree"
  src=$OUT/src-$SHA
  rm -rf "$src" "$OUT/build-$SHA"
  git worktree prune
  git worktree add --detach "$src" "$SHA" >/dev/null 2>&1
  build_sim "$ROOT/$src" "$OUT/build-$SHA"
  mkdir -p "$OUT/base-$SHA"
  cp "$OUT/build-$SHA/sim/ladrc_sil" "$OLD"
  git worktree remove --force "$src"
  src=""
  rm -rf "$OUT/build-$SHA"
fi
echo "base: $BASE (${SHA:0:12}), $OLD"
echo "this: $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- sim || echo ' + uncommitted changes in sim/'), $NEW"

# --- timing ------------------------------------------------------------------
if ((TIMING)); then
  BATCH=()
  for i in 1 2 3 4; do # four names: ladrc_sil refuses two scenarios writing one directory
    cp "$SCENARIO" "$tmp/batch$i.ini"
    BATCH+=("$tmp/batch$i.ini")
  done
  duration=$(awk -F= '/^\[/ { s = $0 } s == "[run]" && $1 ~ /^duration_s/ { gsub(/[ \t]/, "", $2); print $2 }' "$SCENARIO")
  n_ctrl=$(echo "$CONTROLLERS" | tr ',' '\n' | wc -l)
  simulated=$(awk -v d="$duration" -v n="$n_ctrl" 'BEGIN { print d * n }')
  CASES=(nocsv csv batch1 batch2 env envfilter)
  { cat "$SCENARIO"; printf '\n[wind]\nturbulence = moderate\n[vibration]\norders = 1 2 3\ngyro_deg_s = 1.35 0.35 0.2\n'; } \
    > "$tmp/env.ini"
  { cat "$tmp/env.ini"; printf '[filter]\nrpm_harmonics = 3\nlpf_order = 2\n'; } > "$tmp/env_filter.ini"
  env_ctrl=$(sed -n 's/^controllers *= *//p' "$SCENARIO" | tr ' ' ',' | sed 's/,,*/,/g')
  env_n=$(echo "$env_ctrl" | tr ',' '\n' | wc -l)
  env_simulated=$(awk -v d="$duration" -v n="$env_n" 'BEGIN { print d * n }')
  declare -A ARGS=(
    [nocsv]="$SCENARIO --no-csv --jobs 1 --out $tmp/nocsv"
    [csv]="$SCENARIO --jobs 1 --out $tmp/csv"
    [batch1]="${BATCH[*]} --no-csv --jobs 1 --out $tmp/batch"
    [batch2]="${BATCH[*]} --no-csv --jobs 2 --out $tmp/batch"
    [env]="$tmp/env.ini --no-csv --jobs 1 --out $tmp/env"
    [envfilter]="$tmp/env_filter.ini --no-csv --jobs 1 --out $tmp/env"
  )
  declare -A BEST
  # Wall seconds of one call (bash's clock, no process of its own).
  wall() {
    local t0 t1
    t0=$EPOCHREALTIME
    "$@" >/dev/null
    t1=$EPOCHREALTIME
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", b - a }'
  }
  log "timing: $RUNS rounds of 4 cases x 2 builds, alternating"
  for ((r = 1; r <= RUNS; ++r)); do
    for c in "${CASES[@]}"; do
      for b in OLD NEW; do
        ctrl=$CONTROLLERS
        if [[ $c == env* ]]; then
          [[ $b == NEW ]] || continue # keys the base does not know
          ctrl=$env_ctrl
        fi
        # shellcheck disable=SC2086 # ARGS holds words
        t=$(wall "${!b}" ${ARGS[$c]} --controllers "$ctrl" --quiet)
        key=$b:$c
        if [[ -z ${BEST[$key]:-} ]] || awk -v x="$t" -v y="${BEST[$key]}" 'BEGIN { exit !(x < y) }'; then
          BEST[$key]=$t
        fi
      done
    done
  done
  f() { awk "BEGIN { printf \"$1\", $2 }"; }
  verdict() { awk -v x="$1" -v l="$2" 'BEGIN { print (x >= l ? "meets" : "misses") }'; }
  rt() { f "%.0f" "$2 / $1"; }
  o=${BEST[OLD:nocsv]} n=${BEST[NEW:nocsv]}
  speedup=$(f "%.2f" "$o / $n")
  echo
  echo "best of $RUNS, wall s (x real time = simulated s / wall s; $(nproc) cores)"
  printf '%-62s %9s %9s\n' "" "base" "this"
  printf '%-62s %9s %9s\n' "paper, $n_ctrl controllers ($simulated s), no CSV, --jobs 1, s" "$o" "$n"
  printf '%-62s %9s %9s\n' "  x real time" "$(rt "$o" "$simulated")" "$(rt "$n" "$simulated")"
  printf '%-62s %9s %9s\n' "paper, $n_ctrl controllers, every CSV, --jobs 1, s" "${BEST[OLD:csv]}" "${BEST[NEW:csv]}"
  printf '%-62s %9s %9s\n' "  x real time" "$(rt "${BEST[OLD:csv]}" "$simulated")" "$(rt "${BEST[NEW:csv]}" "$simulated")"
  batch_sim=$(f "%g" "4 * $simulated")
  printf '%-62s %9s %9s\n' "16-run batch ($batch_sim s), no CSV, --jobs 1, s" "${BEST[OLD:batch1]}" "${BEST[NEW:batch1]}"
  printf '%-62s %9s %9s\n' "16-run batch, no CSV, --jobs 2, s" "${BEST[OLD:batch2]}" "${BEST[NEW:batch2]}"
  s_old=$(f "%.2f" "${BEST[OLD:batch1]} / ${BEST[OLD:batch2]}")
  s_new=$(f "%.2f" "${BEST[NEW:batch1]} / ${BEST[NEW:batch2]}")
  printf '%-62s %9s %9s\n' "  speed-up --jobs 1 -> 2" "$s_old" "$s_new"
  printf '%-62s %9s %9s\n' "paper, $env_n controllers ($env_simulated s), turbulence + vibration, s" "-" "${BEST[NEW:env]}"
  printf '%-62s %9s %9s\n' "  x real time" "-" "$(rt "${BEST[NEW:env]}" "$env_simulated")"
  printf '%-62s %9s %9s\n' "  the same with the RPM notches and low-pass, s" "-" "${BEST[NEW:envfilter]}"
  printf '%-62s %9s %9s\n' "  x real time" "-" "$(rt "${BEST[NEW:envfilter]}" "$env_simulated")"
  echo
  echo "speed-up over base, paper no CSV --jobs 1: ${speedup}x (target 2.5x: $(verdict "$speedup" 2.5))"
  echo "x real time, no CSV: $(rt "$n" "$simulated") (target 2000: $(verdict "$(rt "$n" "$simulated")" 2000))"
  echo "x real time, every CSV: $(rt "${BEST[NEW:csv]}" "$simulated") (target 600: $(verdict "$(rt "${BEST[NEW:csv]}" "$simulated")" 600))"
  echo "16-run batch, --jobs 2 over --jobs 1: ${s_new}x (target 1.8x: $(verdict "$s_new" 1.8))"
  env_rt=$(rt "${BEST[NEW:env]}" "$env_simulated")
  echo "x real time, turbulence + vibration, $env_n controllers, no CSV: $env_rt (target 1500: $(verdict "$env_rt" 1500))"
fi

# --- outputs, bit for bit -------------------------------------------------------
if ((CHECK)); then
  log "flying every shipped scenario with both builds (every CSV)"
  fly_all() { # BIN DIR: each scenario's outputs under DIR/<name>, stdout and status in DIR/stdout/
    mkdir -p "$2/stdout"
    local f rc
    for f in scenarios/*.ini; do
      rc=0
      "$1" "$f" --jobs "$JOBS" --quiet --out "$tmp/out" >"$tmp/stdout" 2>/dev/null || rc=$?
      mv "$tmp/stdout" "$2/stdout/$(basename "$f" .ini).txt"
      echo "exit status $rc" >>"$2/stdout/$(basename "$f" .ini).txt"
    done
    mv "$tmp/out"/* "$2/" # the same output paths for both builds
  }
  fly_all "$OLD" "$tmp/base"
  fly_all "$NEW" "$tmp/this"
  identical=0 by_columns=0 failed=0
  while IFS= read -r rel; do
    a=$tmp/base/$rel b=$tmp/this/$rel
    if [[ ! -f $b ]]; then
      echo "DIFFERENT: $rel: written by the base, not here"
      failed=$((failed + 1))
    elif cmp -s "$a" "$b"; then
      identical=$((identical + 1))
    elif [[ $rel == *.csv && $(head -n 1 "$a") != "$(head -n 1 "$b")" ]]; then
      # an older header: the base's columns must be the first ones here, row for row
      k=$(head -n 1 "$a" | awk -F, '{ print NF }')
      if cmp -s <(tail -n +2 "$a") <(tail -n +2 "$b" | cut -d, -f "1-$k"); then
        by_columns=$((by_columns + 1))
        renamed=$(paste -d' ' <(head -n 1 "$a" | tr ',' '\n') <(head -n 1 "$b" | tr ',' '\n' | head -n "$k") |
          awk '$1 != $2 { printf "%s%s->%s", sep, $1, $2; sep = " " }')
        added=$(($(head -n 1 "$b" | awk -F, '{ print NF }') - k))
        echo "same values in the base's $k columns: $rel ($added columns appended here; renamed: ${renamed:-none})"
      else
        echo "DIFFERENT: $rel: the values of the base's $k columns differ"
        failed=$((failed + 1))
      fi
    else
      echo "DIFFERENT: $rel"
      cmp "$a" "$b" | head -n 1 || true
      failed=$((failed + 1))
    fi
  done < <(cd "$tmp/base" && find . -type f | sed 's|^\./||' | sort)
  while IFS= read -r rel; do
    [[ -f $tmp/base/$rel ]] || echo "only this build writes: $rel"
  done < <(cd "$tmp/this" && find . -type f | sed 's|^\./||' | sort)
  n_sc=$(ls scenarios/*.ini | wc -l)
  echo
  echo "outputs of $n_sc scenarios: $identical files byte-identical, $by_columns time series identical in the base's columns, $failed different"
  if ((failed > 0)); then
    exit 1
  fi
fi
