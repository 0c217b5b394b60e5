#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The main job: builds the simulator in Release and flies the paper's scenarios
# (Table 2 case, its noisy variant, both again with HP-MLADRC told the
# frequency as the paper assumes, and the Table 3 differentiator case) with
# the four controllers and the two baselines, the hover tone sweep, then the
# real airframes (scenarios/real_*.ini: the
# paper's and a heavier quad at 20, 30 and 40 ms motor lag, every controller
# tuned by tune = margins first), printing Tables 3-7. Extra arguments go to ladrc_sil
# (e.g. --jobs 1, --no-csv, --controllers HP-MLADRC,LADRC).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset host-release >/dev/null
cmake --build --preset host-release --target ladrc_sil --parallel 2 >/dev/null
exec build/host-release/sim/ladrc_sil scenarios/paper.ini scenarios/paper_noisy.ini \
    scenarios/paper_known.ini scenarios/paper_noisy_known.ini scenarios/table3_differentiator.ini \
    scenarios/tone_sweep.ini \
    scenarios/real_paper_lag20.ini scenarios/real_paper_lag30.ini scenarios/real_paper_lag40.ini \
    scenarios/real_heavy_lag20.ini scenarios/real_heavy_lag30.ini scenarios/real_heavy_lag40.ini "$@"
