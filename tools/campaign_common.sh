# SPDX-License-Identifier: BSD-3-Clause
# What tools/campaign_parallel.sh and tools/campaign_slurm.sh share, sourced by
# both (not run on its own): Debian's Python, the simulator, and the checks made
# once before any shard flies.

py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3

# campaign_setup NAME CAMPAIGN [--out DIR]: sets sil (absolute path of the
# simulator: LADRC_SIL or the Release build) and out (the campaign's OUT).
# Exits 2 with NAME's error when the simulator is missing, the campaign is bad,
# or OUT holds another campaign's runs.
campaign_setup() {
  local name=$1 campaign=$2 plan
  shift 2
  sil=${LADRC_SIL:-$root/build/host-release/sim/ladrc_sil}
  if [[ ! -x $sil ]]; then
    echo "$name: error: no simulator $sil (cmake --preset host-release && cmake --build --preset" \
      "host-release --target ladrc_sil, or set LADRC_SIL)" >&2
    exit 2
  fi
  sil=$(cd "$(dirname "$sil")" && pwd)/$(basename "$sil")
  out=$("$sil" --campaign "$campaign" "$@" --print-out) || exit 2
  plan=$("$sil" --campaign "$campaign" --list "$@") || exit 2
  if [[ -f $out/plan.csv ]] && ! cmp -s "$out/plan.csv" <(printf '%s\n' "$plan"); then
    echo "$name: error: $out holds another campaign's runs (its plan.csv is not the plan of $campaign)" >&2
    exit 2
  fi
}
