#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the library and the example in Release and runs one axis in a 1 kHz
# loop against a simulated airframe axis (LADRC vs PID).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target axis_loop --parallel 2 >/dev/null
exec build/host-release/examples/axis_loop
