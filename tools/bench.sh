#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Measures the cost of the controllers and prints Markdown tables, each
# budget figure marked against its budget ("meets" / "over"). Three rooms:
# tools/bench/measure.sh builds and runs everything and writes the data file
# build/bench/figures.txt; tools/bench/render.py turns it into the tables
# (and docs/performance.md's); tools/bench/check.py holds it against the limits.
#
# Usage: tools/bench.sh            print the tables
#        tools/bench.sh --docs     also rewrite the tables of docs/performance.md
#        tools/bench.sh --check    deterministic figures only, against the
#                                  limits in tools/bench/limits.txt (CI: the
#                                  bench stage of tools/run_tests.sh); exits 1
#                                  naming every figure above its limit
#
#  - cases (tools/bench/bench_case.h): PID, LADRC, LP-MLADRC, HP-MLADRC, CASCADED, INDI, RATE-ADRC,
#    LADRC-act and HP-MLADRC-act (with a 30 ms motor lag and 2 ticks modelled) on
#    the recorded closed loop of HP-MLADRC under the paper's one-tone
#    disturbance, HP-MLADRC-2tones on a two-tone disturbance, and
#    HP-MLADRC-gyro (the fit on the gyro, the same actuator model) on its own
#    closed loop with those motors in the plant;
#  - instructions per tick on the Cortex-M4F: build/bench-m4f (the cortex-m4f
#    preset with LADRC_BUILD_BENCH=ON), image run under qemu mps2-an386 with
#    -icount shift=0, twice: the two outputs must be identical; the same
#    image times each module alone (where the instructions go);
#  - sizeof of the state and config structs (same image);
#  - the lean HP build (HP-MLADRC + Levant, known frequency, one tone, no
#    online search): its 3-axis tick and state (ladrc_bench_lean, run the
#    same way) and the library flash its firmware links;
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
# Exit status: 0; 1 a build or run failed, or (--check) a figure is above its
# limit; 2 bad usage or (--check) a bad limits file.
set -euo pipefail

MODE=${1:-}
case $MODE in
  "" | --docs | --check) ;;
  *) echo "usage: tools/bench.sh [--docs | --check]" >&2; exit 2 ;;
esac

cd "$(dirname "${BASH_SOURCE[0]}")/.."
PYTHON=python3
[[ -x /usr/bin/python3 ]] && PYTHON=/usr/bin/python3
FIGURES=build/bench/figures.txt

case $MODE in
  --check)
    tools/bench/measure.sh --m4f "$FIGURES"
    exec "$PYTHON" tools/bench/check.py "$FIGURES" tools/bench/limits.txt
    ;;
  --docs)
    tools/bench/measure.sh --all "$FIGURES"
    exec "$PYTHON" tools/bench/render.py "$FIGURES" --page docs/performance.md
    ;;
  *)
    tools/bench/measure.sh --all "$FIGURES"
    exec "$PYTHON" tools/bench/render.py "$FIGURES"
    ;;
esac
