#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs every check of the project, stopping at the first failure.
#
# Usage: tools/run_tests.sh [STAGE]
#        tools/run_tests.sh --help
#
# Stages, in order:
#   host-debug   main unit-test suite (host, Debug, float, -Werror); the tests
#                labelled slow run in host-release only
#   host-double  the suite with ladrc_real_t = double
#   coverage     suite with gcov, then the gcovr gate (line 95 %, branch 85 %)
#   asan-ubsan   suite under AddressSanitizer + UndefinedBehaviorSanitizer
#   cortex-m4f   cross build, suite under qemu (mps2-an386), library size
#   no-heap      no heap/stdio use and no writable globals, host + cross archive;
#                no dependency cycle between the files of src/ (check_layers.py)
#   cppcheck     static analysis of src/; every C file in the .clang-format style
#   bench        tools/bench.sh --check: instructions per tick on the Cortex-M4F,
#                sizes and tick stack against tools/bench/limits.txt
#   host-release the suite in Release (-O3), Python binding included, with the
#                tests labelled slow (margins against the simulator, tuning,
#                the real-airframe acceptance runs)
#   python-package
#                the binding as a pip package: a fresh venv in
#                build/python-package, pip install --no-index
#                --no-build-isolation ./python (CMake builds the shared library
#                into the package), then the binding's test, the example and
#                python/README.md's snippet against the installed copy, and
#                its version against the CMake project's
#   asserts      the suite with LADRC_ASSERT = assert() (LADRC_CONFIG hook)
#   fast-math    library and non-finite-input tests built with -ffast-math,
#                then test_nonfinite with -ffinite-math-only alone
#   consumers    tools/consumer_test.sh: find_package on an installed prefix,
#                pkg-config, shared library, add_subdirectory, FetchContent,
#                plain Makefile, float/double link failure
#   cxx          public headers as C++17 (-Wall -Wextra -Wpedantic
#                -Wold-style-cast -Werror), linked and run
#   cross        library with -Werror for Cortex-M0 (soft float), Cortex-M7
#                (fpv5-d16, LADRC_REAL_DOUBLE) and RV32IMAC (picolibc), each
#                linked into a small program; no-heap check of each archive
#   fuzz         tools/fuzz.sh: the libFuzzer targets of the scenario parser,
#                the expression compiler and the flight-log reader (clang,
#                ASan + UBSan), 60 s each
#   apidocs      the Doxygen API reference (target docs) with warnings as
#                errors, then tools/check_apidocs.sh: the check must fail on
#                a missing doc comment, @param or @ref
#   links        the checker's own test (tools/check_links_test.py), then
#                tools/check_links.py: every relative link, image and #anchor
#                of README.md and docs/**/*.md resolves, the README's firmware
#                example equals examples/firmware_roll.c's marked lines
#   campaigns    a campaign flown three ways (tools/campaign_engines.sh): one
#                process, GNU parallel with 4 shards, a Slurm array of 4 tasks
#                on a local single-node cluster; the merged tables must be
#                byte-identical; then tools/campaign.py plot draws its figures
#
# Missing tools are installed with apt-get (as root, or through sudo).
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

STAGES=(host-debug host-double coverage asan-ubsan cortex-m4f no-heap cppcheck bench
        host-release python-package asserts fast-math consumers cxx cross fuzz apidocs links campaigns)

# What each stage needs: "stage check package". A check is a command name,
# "py:<module>" for a Python module, "newlib" for the Arm C library, or
# "libfuzzer" for clang's libFuzzer runtime; stage "all" applies to every
# stage. Add new requirements here.
REQUIREMENTS=(
  "all cmake cmake"
  "all gcc gcc"
  "coverage gcovr gcovr"
  "cortex-m4f arm-none-eabi-gcc gcc-arm-none-eabi"
  "cortex-m4f newlib libnewlib-arm-none-eabi"
  "cortex-m4f qemu-system-arm qemu-system-arm"
  "no-heap nm binutils"
  "no-heap arm-none-eabi-nm binutils-arm-none-eabi"
  "no-heap arm-none-eabi-gcc gcc-arm-none-eabi"
  "no-heap newlib libnewlib-arm-none-eabi"
  "no-heap python3 python3"
  "no-heap cc gcc"
  "cppcheck cppcheck cppcheck"
  "cppcheck clang-format clang-format"
  "cppcheck git git"
  "bench arm-none-eabi-gcc gcc-arm-none-eabi"
  "bench newlib libnewlib-arm-none-eabi"
  "bench qemu-system-arm qemu-system-arm"
  "bench arm-none-eabi-size binutils-arm-none-eabi"
  "bench python3 python3"
  "host-debug py:matplotlib python3-matplotlib"
  "host-debug py:numpy python3-numpy"
  "host-double py:matplotlib python3-matplotlib"
  "host-double py:numpy python3-numpy"
  "coverage py:matplotlib python3-matplotlib"
  "coverage py:numpy python3-numpy"
  "asan-ubsan py:matplotlib python3-matplotlib"
  "asan-ubsan py:numpy python3-numpy"
  "host-release py:matplotlib python3-matplotlib"
  "host-release py:numpy python3-numpy"
  "python-package py:ensurepip python3-venv"
  "python-package py:wheel python3-wheel"
  "python-package py:numpy python3-numpy"
  "python-package py:matplotlib python3-matplotlib"
  "python-package git git"
  "asserts py:matplotlib python3-matplotlib"
  "asserts py:numpy python3-numpy"
  "consumers pkg-config pkg-config"
  "consumers git git"
  "consumers make make"
  "cxx g++ g++"
  "cross arm-none-eabi-gcc gcc-arm-none-eabi"
  "cross newlib libnewlib-arm-none-eabi"
  "cross arm-none-eabi-nm binutils-arm-none-eabi"
  "cross riscv64-unknown-elf-gcc gcc-riscv64-unknown-elf"
  "cross picolibc-rv32 picolibc-riscv64-unknown-elf"
  "fuzz clang clang"
  "fuzz libfuzzer libclang-rt-14-dev"
  "links python3 python3"
  "links git git"
  "campaigns parallel parallel"
  "campaigns slurmctld slurm-wlm"
  "campaigns slurmd slurm-wlm"
  "campaigns sbatch slurm-wlm"
  "campaigns munged munge"
  "campaigns py:matplotlib python3-matplotlib"
  "campaigns py:numpy python3-numpy"
  "apidocs doxygen doxygen"
  "apidocs perl perl"
)

JOBS=2

# The header comment, from its third line to its end.
usage() { awk 'NR < 3 { next } !/^#/ { exit } { sub(/^# ?/, ""); print }' "$0"; }

have() {
  case $1 in
    # Debian's interpreter, when there is one: it is the one that sees Debian's packages.
    py:*) "$(command -v /usr/bin/python3 || echo python3)" -c "import ${1#py:}" >/dev/null 2>&1 ;;
    newlib) echo '#include <stdio.h>' | arm-none-eabi-gcc -E -x c - >/dev/null 2>&1 ;;
    picolibc-rv32) echo '#include <math.h>' |
      riscv64-unknown-elf-gcc -march=rv32imac -mabi=ilp32 --specs=picolibc.specs -E -x c - >/dev/null 2>&1 ;;
    libfuzzer) echo 'int LLVMFuzzerTestOneInput(const char *d, unsigned long n) { (void)d; (void)n; return 0; }' |
      clang -fsanitize=fuzzer -x c - -o /dev/null >/dev/null 2>&1 ;;
    *) command -v "$1" >/dev/null 2>&1 ;;
  esac
}

# Installs the packages of the failing checks of the given stages.
install_missing() {
  local wanted=" $* " missing=() entry stage check package
  for entry in "${REQUIREMENTS[@]}"; do
    read -r stage check package <<<"$entry"
    [[ $stage == all || $wanted == *" $stage "* ]] || continue
    have "$check" && continue
    [[ " ${missing[*]} " == *" $package "* ]] || missing+=("$package")
  done
  [[ ${#missing[@]} -eq 0 ]] && return 0

  echo "== installing missing packages: ${missing[*]}"
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo=(sudo)
    else
      echo "error: need root or sudo to install: ${missing[*]}" >&2
      exit 1
    fi
  fi
  if ! command -v apt-get >/dev/null 2>&1 ||
     ! "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update ||
     ! "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive \
         apt-get install -y --no-install-recommends "${missing[@]}"; then
    echo "error: could not install: ${missing[*]} (install them by hand)" >&2
    exit 1
  fi
}

workflow() { cmake --workflow --preset "$1"; }

# Configures (if needed) and builds only the library of a preset.
build_library() {
  [[ -f build/$1/CMakeCache.txt ]] || cmake --preset "$1"
  cmake --build --preset "$1" --target ladrc
}

stage_host-debug() { workflow host-debug; }
stage_host-double() { workflow host-double; }

stage_coverage() {
  # Counters of an earlier run would inflate the numbers.
  [[ -d build/coverage ]] && find build/coverage -name '*.gcda' -delete
  workflow coverage
  cmake --build --preset coverage --target coverage
}

stage_asan-ubsan() { workflow asan-ubsan; }

stage_cortex-m4f() {
  workflow cortex-m4f
  echo "-- libladrc.a size for Cortex-M4F (text/data/bss, totals last):"
  cmake --build --preset cortex-m4f --target ladrc_size
}

stage_no-heap() {
  build_library host-debug
  build_library cortex-m4f
  tools/check_no_heap.sh build/host-debug/libladrc.a nm
  tools/check_no_heap.sh build/cortex-m4f/libladrc.a arm-none-eabi-nm
  # The files of src/ form layers (no circle); the check first fails on one.
  python3 tools/check_layers_test.py cc nm
  python3 tools/check_layers.py --nm nm build/host-debug/libladrc.a
  python3 tools/check_layers.py --nm arm-none-eabi-nm --quiet build/cortex-m4f/libladrc.a
}

stage_cppcheck() {
  cppcheck --enable=warning,style,performance,portability --error-exitcode=1 \
    --inline-suppr --std=c99 --suppress=missingIncludeSystem -j "$JOBS" -q \
    -I include src
  echo "cppcheck: no findings"
  # The house style (.clang-format) on every C source and header.
  git ls-files -z '*.c' '*.h' | xargs -0 clang-format --dry-run -Werror
  echo "clang-format: every C file in the house style"
}

# Deterministic figures only (no wall clock): instruction counts under qemu
# -icount, sizes, stack.
stage_bench() { tools/bench.sh --check; }

stage_host-release() { workflow host-release; }
# Offline: pip may use no index; setuptools, wheel and NumPy are Debian's.
stage_python-package() {
  local out=$PWD/build/python-package untracked version
  local venv=$out/venv trace=$PWD/build/host-release/python/ladrc_binding_trace
  # The bit-for-bit test's trace program, and the version as CMake wrote it.
  [[ -f build/host-release/CMakeCache.txt ]] || cmake --preset host-release
  cmake --build --preset host-release --target ladrc_binding_trace
  version=$(sed -n 's/^#define LADRC_VERSION_STRING "\(.*\)"$/\1/p' build/host-release/include/ladrc/version.h)
  [[ -n $version ]] || { echo "error: no LADRC_VERSION_STRING in the host-release version.h" >&2; return 1; }
  # From scratch: no venv, no earlier setuptools build tree.
  rm -rf "$out" python/build python/*.egg-info
  mkdir -p "$out/run"
  untracked=$(git ls-files --others --exclude-standard)
  /usr/bin/python3 -m venv --system-site-packages "$venv"
  # Without this machine's pip settings (PIP_* variables, config files): no extra wheel sources.
  local pip_env=(env) var
  for var in $(compgen -e | grep '^PIP_' || true); do pip_env+=(-u "$var"); done
  "${pip_env[@]}" PIP_CONFIG_FILE=/dev/null "$venv/bin/pip" install --no-index --no-build-isolation ./python
  if [[ $(git ls-files --others --exclude-standard) != "$untracked" ]]; then
    echo "error: the install left files in the source tree that .gitignore does not cover:" >&2
    comm -13 <(echo "$untracked") <(git ls-files --others --exclude-standard) | head -20 >&2
    return 1
  fi
  # Outside the checkout, without PYTHONPATH or LADRC_LIBRARY: only the installed copy can import.
  local ipy=(env -u PYTHONPATH -u LADRC_LIBRARY "$venv/bin/python") src=$PWD
  (
    cd "$out/run"
    "${ipy[@]}" -c "import ladrc; print(ladrc.__version__)"
    "${ipy[@]}" - "$version" <<'PY'
import importlib.metadata
import os
import sys

import ladrc

package = os.path.dirname(os.path.abspath(ladrc.__file__))
if not package.startswith(os.path.abspath(sys.prefix) + os.sep):
    sys.exit(f"error: ladrc imported from {package}, not from the venv {sys.prefix}")
library = os.path.abspath(ladrc.library().path)
if os.path.dirname(library) != package:
    sys.exit(f"error: the library loaded is {library}, not the one in the package {package}")
meta = importlib.metadata.version("ladrc")
if not ladrc.__version__ == meta == sys.argv[1]:
    sys.exit(f"error: versions differ: ladrc.__version__ {ladrc.__version__}, metadata {meta}, "
             f"CMake {sys.argv[1]}")
print(f"-- installed ladrc {meta} in {package}, library {library}")
PY
    "${ipy[@]}" "$src/tests/python/test_binding.py" "$trace" "$out/binding_trace.txt"
    "${ipy[@]}" "$src/python/examples/step_response.py" "$out/step_response.png"
    check_png "$out/step_response.png" 30000
    # The README's usage snippet, as written there.
    # shellcheck disable=SC2016 # (the backquotes are Markdown, not shell)
    sed -n '/^```python$/,/^```$/{/^```/d;p}' "$src/python/README.md" > "$out/readme_snippet.py"
    [[ -s $out/readme_snippet.py ]] || { echo "error: no python block in python/README.md" >&2; exit 1; }
    "${ipy[@]}" "$out/readme_snippet.py"
  )
}

stage_asserts() { workflow host-asserts; }
stage_fast-math() {
  workflow host-fastmath
  # -ffinite-math-only alone: the non-finite-input tests only.
  cmake --preset host-fastmath -B build/host-finitemath -DCMAKE_C_FLAGS=-ffinite-math-only >/dev/null
  cmake --build build/host-finitemath --target test_nonfinite
  build/host-finitemath/tests/test_nonfinite
}
stage_consumers() { tools/consumer_test.sh build/consumer; }

stage_cxx() {
  build_library host-release
  g++ -std=c++17 -Wall -Wextra -Wpedantic -Wold-style-cast -Werror -Iinclude -Ibuild/host-release/include \
    tests/cxx/headers.cpp build/host-release/libladrc.a -lm -o build/host-release/cxx_headers
  build/host-release/cxx_headers
  # The double build's headers too (compile only).
  g++ -std=c++17 -Wall -Wextra -Wpedantic -Wold-style-cast -Werror -DLADRC_REAL_DOUBLE -Iinclude \
    -Ibuild/host-release/include -fsyntax-only tests/cxx/headers.cpp
  echo "cxx: public headers clean as C++17, linked and ran"
}

# preset  C compiler  nm  flags of the link check
CROSS_BUILDS=(
  "cortex-m0 arm-none-eabi-gcc arm-none-eabi-nm -mcpu=cortex-m0 -mthumb -mfloat-abi=soft --specs=nosys.specs"
  "cortex-m7-double arm-none-eabi-gcc arm-none-eabi-nm -mcpu=cortex-m7 -mthumb -mfpu=fpv5-d16 -mfloat-abi=hard --specs=nosys.specs -DLADRC_REAL_DOUBLE"
  "rv32imac riscv64-unknown-elf-gcc riscv64-unknown-elf-nm -march=rv32imac -mabi=ilp32 --specs=picolibc.specs"
)

stage_cross() {
  local entry preset cc nm flags
  for entry in "${CROSS_BUILDS[@]}"; do
    read -r preset cc nm flags <<<"$entry"
    echo "-- cross: $preset"
    cmake --preset "$preset" >/dev/null
    cmake --build --preset "$preset"
    tools/check_no_heap.sh "build/$preset/libladrc.a" "$nm"
    # shellcheck disable=SC2086
    "$cc" $flags -std=c99 -Os -Wall -Wextra -Werror -ffunction-sections -fdata-sections -Wl,--gc-sections \
      -Iinclude tests/consumer/app.c "build/$preset/libladrc.a" -lm -o "build/$preset/app.elf"
    "${cc%gcc}size" "build/$preset/libladrc.a" | awk 'NR > 1 { t += $1 + $2 } END { print "-- library text + data: " t " B" }'
    "${cc%gcc}size" "build/$preset/app.elf"
  done
}

# libFuzzer targets, CI form (tools/fuzz.sh --long for the long one).
stage_fuzz() { tools/fuzz.sh; }

# The checker's own test, then the Markdown's links, anchors and the README's snippet.
stage_links() {
  local py=python3
  [[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
  "$py" tools/check_links_test.py
  "$py" tools/check_links.py
}

# The campaign of the CI, flown three ways: the 1,000-run Monte Carlo (about 45 s per way
# in one process or GNU parallel on 2 cores, 75 s through Slurm; under 3 min in all).
CI_CAMPAIGN=campaigns/robustness.ini

# A PNG (signature and IHDR) of at least 800 x 500 pixels and MIN_BYTES bytes.
check_png() { # file min_bytes
  local hdr width height size
  [[ -f $1 ]] || { echo "error: $1 was not drawn" >&2; return 1; }
  # (read's status is 1: od's output ends without a newline)
  read -r -a hdr < <(od -An -tu1 -N24 "$1" | tr -s ' \n' ' ') || true
  width=$(( (hdr[16] << 24) | (hdr[17] << 16) | (hdr[18] << 8) | hdr[19] ))
  height=$(( (hdr[20] << 24) | (hdr[21] << 16) | (hdr[22] << 8) | hdr[23] ))
  size=$(wc -c < "$1")
  echo "-- $1: ${width}x${height}, $size bytes"
  if [[ ${hdr[1]} -ne 80 || ${hdr[2]} -ne 78 || ${hdr[3]} -ne 71 || $width -lt 800 || $height -lt 500 ||
        $size -lt $2 ]]; then
    echo "error: $1 is not a PNG of at least 800x500 pixels and $2 bytes" >&2
    return 1
  fi
}

stage_campaigns() {
  local out=build/campaigns dir py=python3
  [[ -x /usr/bin/python3 ]] && py=/usr/bin/python3
  [[ -f build/host-release/CMakeCache.txt ]] || cmake --preset host-release
  cmake --build --preset host-release --target ladrc_sil
  # The cluster is stopped however the stage ends.
  trap 'tools/slurm/local_cluster.sh stop' EXIT
  tools/slurm/local_cluster.sh start
  eval "$(tools/slurm/local_cluster.sh env)"
  tools/campaign_engines.sh --out "$out" "$CI_CAMPAIGN" 4 "$JOBS"
  dir=$(build/host-release/sim/ladrc_sil --campaign "$CI_CAMPAIGN" --out "$out/one" --print-out)
  rm -rf "$dir/figures"
  "$py" tools/campaign.py plot "$dir"
  # A map with its panels and colour bar, a box plot: well above an empty canvas (~5 kB).
  local f n=0
  for f in "$dir"/figures/map_roll_*.png "$dir/figures/rms_roll.png"; do
    check_png "$f" 30000
    n=$((n + 1))
  done
  [[ $n -eq 2 ]] || { echo "error: expected a map and a box plot in $dir/figures, found $n files" >&2; return 1; }
}

# The reference of the host-debug configuration (no compile needed: the
# docs target reads the headers and the generated version.h).
stage_apidocs() {
  # Configured again: a tree configured before Doxygen was installed has no docs target.
  cmake --preset host-debug >/dev/null
  cmake --build --preset host-debug --target docs
  echo "apidocs: reference in build/host-debug/docs/html, no Doxygen warning"
  tools/check_apidocs.sh build/host-debug
}

case ${1:-} in
  -h | --help) usage; exit 0 ;;
  "") selected=("${STAGES[@]}") ;;
  *)
    if [[ $# -ne 1 || " ${STAGES[*]} " != *" $1 "* ]]; then
      echo "error: unknown stage '$*' (stages: ${STAGES[*]})" >&2
      exit 2
    fi
    selected=("$1")
    ;;
esac

install_missing "${selected[@]}"
export CMAKE_BUILD_PARALLEL_LEVEL=$JOBS CTEST_PARALLEL_LEVEL=$JOBS

summary=()
for stage in "${selected[@]}"; do
  echo "== stage: $stage"
  start=$(date +%s)
  # A subshell outside any "if", so that errexit applies inside the stage.
  set +e
  (set -e; "stage_$stage")
  rc=$?
  set -e
  if [[ $rc -ne 0 ]]; then
    echo "== FAILED: stage $stage ($(($(date +%s) - start)) s)" >&2
    exit 1
  fi
  summary+=("$stage $(($(date +%s) - start))s")
  echo "== stage $stage passed in $(($(date +%s) - start)) s"
done

echo "== all ${#selected[@]} stages passed: ${summary[*]}"
