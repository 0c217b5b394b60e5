#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies a campaign in shards with GNU parallel on this machine, then merges it.
#
# Usage: tools/campaign_parallel.sh [--out DIR] CAMPAIGN [N_SHARDS] [JOBS]
#   N_SHARDS  shards (default: the number of cores); shard K flies the runs r
#             with (r - 1) % N_SHARDS == K - 1, one ladrc_sil process each
#             (--jobs 1); JOBS of them at a time (default: the number of cores)
#   --out DIR write under DIR/<campaign name> (default: the campaign's output_dir)
# Environment: LADRC_SIL, the simulator (default build/host-release/sim/ladrc_sil).
#
# The first shard that fails stops the others (--halt now,fail=1); then the
# exit status is the failed shard's (1 a run failed, 2 bad input) and nothing
# is merged. Else tools/campaign.py merge writes OUT/campaign.csv.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage() { sed -n '3,15s/^# \{0,1\}//p' "$0"; }
# shellcheck source=tools/campaign_common.sh
. "$root/tools/campaign_common.sh"

out_args=()
if [[ ${1:-} == --out ]]; then
  [[ $# -ge 2 ]] || { usage >&2; exit 2; }
  out_args=(--out "$2")
  shift 2
fi
case ${1:-} in -h | --help) usage; exit 0 ;; "") usage >&2; exit 2 ;; esac
[[ $# -le 3 ]] || { usage >&2; exit 2; }
campaign=$1
cores=$(nproc)
shards=${2:-$cores}
jobs=${3:-$cores}
for v in "$shards" "$jobs"; do
  [[ $v =~ ^[1-9][0-9]*$ ]] || { echo "campaign_parallel.sh: error: '$v' is not a whole number >= 1" >&2; exit 2; }
done
command -v parallel >/dev/null 2>&1 || { echo "campaign_parallel.sh: error: GNU parallel not found" \
  "(apt-get install parallel)" >&2; exit 2; }
# Bad input, and an OUT holding another campaign, fail here, once, rather than in every shard.
campaign_setup campaign_parallel.sh "$campaign" "${out_args[@]}"

echo "campaign_parallel.sh: $campaign: $shards shards, $jobs at a time, into $out" >&2
# --will-cite: the citation notice is acknowledged (docs/campaigns.md), not printed.
# --line-buffer: each shard's messages whole; --tag: prefixed with the shard.
# -q: the command's words passed as they are (paths with spaces).
status=0
seq 1 "$shards" | parallel --will-cite --halt now,fail=1 --jobs "$jobs" --line-buffer --tag -q \
  "$sil" --campaign "$campaign" --shard "{}/$shards" --jobs 1 --quiet "${out_args[@]}" || status=$?
if [[ $status -ne 0 ]]; then
  # With fail=1, parallel exits with the failed shard's status.
  echo "campaign_parallel.sh: error: a shard of $campaign failed (exit status $status), the others" \
    "were stopped; not merged" >&2
  exit "$status"
fi
"$py" "$root/tools/campaign.py" merge "$out"
