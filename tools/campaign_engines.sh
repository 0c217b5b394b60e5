#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies one campaign three ways and checks they agree: one process
# (ladrc_sil --campaign --jobs JOBS), GNU parallel with N_SHARDS shards
# (tools/campaign_parallel.sh) and a Slurm array of N_SHARDS tasks
# (tools/campaign_slurm.sh); prints each one's wall time and compares the
# three merged campaign.csv byte for byte.
#
# Usage: tools/campaign_engines.sh [--out DIR] CAMPAIGN [N_SHARDS] [JOBS]
#   N_SHARDS  shards of the parallel and Slurm runs (default 4)
#   JOBS      threads of the one process, shards at a time under parallel
#             (default: the number of cores)
#   --out DIR the three runs go to DIR/one, DIR/parallel, DIR/slurm, each under
#             the campaign's name, removed first (default build/campaign-engines)
# Environment: LADRC_SIL, the simulator (default build/host-release/sim/ladrc_sil).
#
# Without a Slurm cluster that answers, the local one (tools/slurm/local_cluster.sh)
# is started, and stopped again at the end, failure or not.
# Exit status: 0 the three tables are identical; 1 they differ or a way failed.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage() { sed -n '3,20s/^# \{0,1\}//p' "$0"; }
py=python3
[[ -x /usr/bin/python3 ]] && py=/usr/bin/python3

base=build/campaign-engines
if [[ ${1:-} == --out ]]; then
  [[ $# -ge 2 ]] || { usage >&2; exit 2; }
  base=$2
  shift 2
fi
case ${1:-} in -h | --help) usage; exit 0 ;; "" | -*) usage >&2; exit 2 ;; esac
[[ $# -le 3 ]] || { usage >&2; exit 2; }
campaign=$1
shards=${2:-4}
jobs=${3:-$(nproc)}
sil=${LADRC_SIL:-$root/build/host-release/sim/ladrc_sil}
[[ -x $sil ]] || { echo "campaign_engines.sh: error: no simulator $sil" >&2; exit 2; }
export LADRC_SIL=$sil

started_cluster=0
cleanup() {
  if [[ $started_cluster -eq 1 ]]; then
    "$root/tools/slurm/local_cluster.sh" stop >&2 || true
  fi
}
trap cleanup EXIT
if ! command -v sinfo >/dev/null 2>&1 || ! sinfo -h >/dev/null 2>&1; then
  started_cluster=1
  "$root/tools/slurm/local_cluster.sh" start >&2
  eval "$("$root/tools/slurm/local_cluster.sh" env)"
fi

out_of() { "$sil" --campaign "$campaign" --out "$base/$1" --print-out; }
for way in one parallel slurm; do
  rm -rf "$(out_of $way)"
done

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
declare -A wall
t0=$(now)
"$sil" --campaign "$campaign" --jobs "$jobs" --out "$base/one" --quiet
"$py" "$root/tools/campaign.py" merge "$(out_of one)"
wall[one]=$(since "$t0")

t0=$(now)
"$root/tools/campaign_parallel.sh" --out "$base/parallel" "$campaign" "$shards" "$jobs"
wall[parallel]=$(since "$t0")

t0=$(now)
"$root/tools/campaign_slurm.sh" --out "$base/slurm" "$campaign" "$shards"
wall[slurm]=$(since "$t0")

runs=$(($(wc -l < "$(out_of one)/campaign.csv") - 1))
echo "campaign_engines.sh: $campaign, $runs runs, on $(nproc) cores:"
printf '  %-40s %7.1f s\n' "one process, --jobs $jobs" "${wall[one]}" \
  "GNU parallel, $shards shards, $jobs at a time" "${wall[parallel]}" \
  "Slurm array, $shards tasks" "${wall[slurm]}"
status=0
for way in parallel slurm; do
  if cmp "$(out_of one)/campaign.csv" "$(out_of $way)/campaign.csv"; then
    echo "  campaign.csv of $way: identical to the one process's"
  else
    echo "campaign_engines.sh: error: campaign.csv of $way differs from the one process's" >&2
    status=1
  fi
done
exit $status
