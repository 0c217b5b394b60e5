#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds and runs the tiny application tests/consumer/app.c through every way
# of consuming ladrc, from this source tree, without network:
#   install     cmake --install of the static library, then find_package(ladrc 0.2)
#   pkg-config  the same prefix through ladrc.pc
#   shared      BUILD_SHARED_LIBS=ON installed, find_package, run
#   subdir      add_subdirectory(ladrc)
#   fetch       FetchContent from a file:// git URL of this repository at HEAD
#               (when it is a git checkout) and with FETCHCONTENT_SOURCE_DIR_LADRC
#   make        include/ and src/ copied into a plain Makefile project (-lm)
#   abi         a library built with LADRC_REAL_DOUBLE and an application built
#               without it (and the reverse) must fail to link; matching ones link;
#               likewise an HP-MLADRC + Levant library and an application built
#               for every variant (and the reverse)
# Usage: tools/consumer_test.sh [WORKDIR]   (default build/consumer)
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
src=$PWD
work=${1:-build/consumer}
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
cons=$src/tests/consumer
jobs=${CMAKE_BUILD_PARALLEL_LEVEL:-2}

log() { echo "-- consumer: $*"; }

# Builds the library alone (no tests, no simulator) and installs it.
install_ladrc() { # name prefix [cmake args...]
  local name=$1 prefix=$2
  shift 2
  cmake -S "$src" -B "$work/lib-$name" -DCMAKE_BUILD_TYPE=Release -DLADRC_BUILD_TESTS=OFF \
    -DLADRC_INSTALL=ON -DLADRC_WERROR=ON -DCMAKE_INSTALL_PREFIX="$prefix" "$@" >/dev/null
  cmake --build "$work/lib-$name" -j "$jobs" --target ladrc >/dev/null
  cmake --install "$work/lib-$name" >/dev/null
}

# Configures, builds and runs a consumer project.
cmake_app() { # name source-dir [cmake args...]
  local name=$1 dir=$2
  shift 2
  cmake -S "$dir" -B "$work/$name" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$work/$name" -j "$jobs" >/dev/null
  "$work/$name/app"
  log "$name: built and ran"
}

log "install: static library into $work/prefix"
install_ladrc static "$work/prefix"
for f in include/ladrc/version.h include/ladrc/axis.h lib/cmake/ladrc/ladrcConfig.cmake \
         lib/cmake/ladrc/ladrcConfigVersion.cmake lib/pkgconfig/ladrc.pc lib/libladrc.a \
         share/doc/ladrc/LICENSE; do
  [[ -f $work/prefix/$f ]] || { echo "error: not installed: $f" >&2; exit 1; }
done
cmake_app install "$cons/find_package" -DCMAKE_PREFIX_PATH="$work/prefix"

# A version the package does not satisfy must be refused (SameMajorVersion).
mkdir -p "$work/v1src"
sed 's/find_package(ladrc 0.2 REQUIRED)/find_package(ladrc 1.0 REQUIRED)/; s|\.\./app\.c|'"$cons"'/app.c|' \
  "$cons/find_package/CMakeLists.txt" >"$work/v1src/CMakeLists.txt"
if cmake -S "$work/v1src" -B "$work/install-v1" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null 2>&1; then
  echo "error: find_package(ladrc 1.0) accepted version 0.2" >&2
  exit 1
fi
log "install: find_package(ladrc 1.0) refused, as it should"

log "pkg-config"
export PKG_CONFIG_PATH=$work/prefix/lib/pkgconfig
[[ $(pkg-config --modversion ladrc) == "$(sed -n 's/^project(ladrc VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)" ]]
# shellcheck disable=SC2046
cc -std=c99 -Wall -Wextra -Werror -DLADRC_CONSUMER_HAS_VERSION $(pkg-config --cflags ladrc) \
  "$cons/app.c" -o "$work/app-pkgconfig" $(pkg-config --libs ladrc)
"$work/app-pkgconfig"
log "pkg-config: built and ran"
unset PKG_CONFIG_PATH

log "shared: BUILD_SHARED_LIBS=ON"
install_ladrc shared "$work/prefix-shared" -DBUILD_SHARED_LIBS=ON
ls "$work/prefix-shared/lib/"libladrc.so* >/dev/null
cmake_app shared "$cons/find_package" -DCMAKE_PREFIX_PATH="$work/prefix-shared"
# (ldd's output in full first: grep -q stopping early would make ldd fail under pipefail)
linked=$(ldd "$work/shared/app")
[[ $linked == *libladrc.so* ]] || { echo "error: app not linked to libladrc.so" >&2; exit 1; }

cmake_app subdir "$cons/add_subdirectory" -DLADRC_DIR="$src"

cmake_app fetch-source-dir "$cons/fetchcontent" -DFETCHCONTENT_SOURCE_DIR_LADRC="$src" \
  -DLADRC_GIT_URL=unused -DLADRC_GIT_TAG=unused
if git -C "$src" rev-parse --verify -q HEAD >/dev/null 2>&1; then
  cmake_app fetch-git "$cons/fetchcontent" -DLADRC_GIT_URL="file://$src" \
    -DLADRC_GIT_TAG="$(git -C "$src" rev-parse HEAD)"
else
  log "fetch-git: skipped, $src is not a git checkout"
fi

log "make: include/ and src/ copied into a Makefile project"
mkdir -p "$work/make"
cp -r "$src/include" "$src/src" "$cons/Makefile" "$cons/app.c" "$work/make/"
make -s -C "$work/make" >/dev/null
"$work/make/app"
log "make: built and ran"

log "abi: real type of the library against the application's"
install_ladrc double "$work/prefix-double" -DLADRC_REAL_DOUBLE=ON
abi_link() { # prefix app-flags -> 0 if it links
  cc -std=c99 -I"$1/include" $2 "$cons/app.c" -o "$work/app-abi" -L"$1/lib" -lladrc -lm 2>"$work/abi.log"
}
# An application that must not link against a library: the linker names the
# symbol the application asked for (its own real type, variant set, ...).
must_not_link() { # prefix app-flags missing-symbol what
  if abi_link "$1" "$2"; then
    echo "error: $4 linked" >&2
    exit 1
  fi
  grep -q "$3" "$work/abi.log"
}
abi_link "$work/prefix-double" "-DLADRC_REAL_DOUBLE" && "$work/app-abi"
must_not_link "$work/prefix-double" "" ladrc_attitude_init_float "a float application against a double library"
must_not_link "$work/prefix" "-DLADRC_REAL_DOUBLE" ladrc_attitude_init_double \
  "a double application against a float library"
log "abi: mismatches fail to link naming the real type, matching builds link and run"

log "abi: variant set of the library against the application's"
install_ladrc hp "$work/prefix-hp" "-DLADRC_VARIANTS=HP_MLADRC" "-DLADRC_SHAPERS=LEVANT"
hp_flags="-DLADRC_WITH_LADRC=0 -DLADRC_WITH_LP_MLADRC=0 -DLADRC_WITH_PID=0 -DLADRC_WITH_CASCADED=0"
hp_flags+=" -DLADRC_WITH_INDI=0 -DLADRC_WITH_RATE_ADRC=0 -DLADRC_WITH_TD=0"
abi_link "$work/prefix-hp" "$hp_flags"
must_not_link "$work/prefix-hp" "" ladrc_attitude_init_float_v1111111_s11_o1_t2 \
  "an all-variants application against an HP-MLADRC-only library"
must_not_link "$work/prefix" "$hp_flags" ladrc_attitude_init_float_v0010000_s01_o1_t2 \
  "an HP-MLADRC-only application against an all-variants library"
log "abi: variant-set mismatches fail to link naming the set, a matching build links"

log "abi: the online frequency search (LADRC_HP_ONLINE) of the library against the application's"
install_ladrc hpknown "$work/prefix-hpknown" "-DLADRC_VARIANTS=HP_MLADRC" "-DLADRC_SHAPERS=LEVANT" "-DLADRC_HP_ONLINE=OFF"
abi_link "$work/prefix-hpknown" "$hp_flags -DLADRC_WITH_HP_ONLINE=0"
must_not_link "$work/prefix-hpknown" "$hp_flags" ladrc_attitude_init_float_v0010000_s01_o1_t2 \
  "an application with the online search against a library without it"
must_not_link "$work/prefix-hp" "$hp_flags -DLADRC_WITH_HP_ONLINE=0" ladrc_attitude_init_float_v0010000_s01_o0_t2 \
  "an application without the online search against a library with it"
log "abi: online-search mismatches fail to link naming it, a matching build links"

log "abi: the most tones (LADRC_HP_MAX_TONES, the size of every RLS) of the library against the application's"
must_not_link "$work/prefix" "-DLADRC_HP_MAX_TONES=1" ladrc_attitude_init_float_v1111111_s11_o1_t1 \
  "an application built for one tone against a library built for two"
log "abi: a most-tones mismatch fails to link naming it"

echo "consumer tests: all passed"
