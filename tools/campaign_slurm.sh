#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Flies a campaign as a Slurm array job (tools/slurm/campaign.sbatch, one shard
# per task), waits for it, checks that every task succeeded, then merges.
#
# Usage: tools/campaign_slurm.sh [--out DIR] CAMPAIGN [N_SHARDS] [-- SBATCH_OPTION...]
#   N_SHARDS  array tasks (default 4); task K flies the runs r with
#             (r - 1) % N_SHARDS == K - 1
#   --out DIR write under DIR/<campaign name> (default: the campaign's output_dir)
#   after --   options for sbatch (--partition=..., --time=..., --account=...)
# Environment: LADRC_SIL, the simulator (default build/host-release/sim/ladrc_sil),
# which every node must reach at the same path (a shared file system), as OUT.
# Needs a reachable cluster: sbatch and sinfo on PATH (SLURM_CONF for a local one:
# eval "$(tools/slurm/local_cluster.sh env)").
#
# The tasks' output goes to OUT/slurm/slurm-<job>_<task>.out; each ends with the
# shard's exit status, read here (no accounting database needed). Exit status:
# 0 merged; 1 a task failed or left no status (named), or the merge failed;
# 2 bad input (found before anything is submitted).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
usage() { sed -n '3,19s/^# \{0,1\}//p' "$0"; }
die() { echo "campaign_slurm.sh: error: $2" >&2; exit "$1"; }
# shellcheck source=tools/campaign_common.sh
. "$root/tools/campaign_common.sh"

out_args=()
if [[ ${1:-} == --out ]]; then
  [[ $# -ge 2 ]] || { usage >&2; exit 2; }
  out_args=(--out "$2")
  shift 2
fi
case ${1:-} in -h | --help) usage; exit 0 ;; "" | --*) usage >&2; exit 2 ;; esac
campaign=$1
shift
shards=4
if [[ $# -gt 0 && $1 != -- ]]; then
  shards=$1
  shift
fi
[[ $shards =~ ^[1-9][0-9]*$ ]] || die 2 "N_SHARDS '$shards' is not a whole number >= 1"
sbatch_opts=()
if [[ $# -gt 0 ]]; then
  [[ $1 == -- ]] || { usage >&2; exit 2; }
  shift
  sbatch_opts=("$@")
fi

for tool in sbatch sinfo; do
  command -v $tool >/dev/null 2>&1 || die 2 "$tool not found (a Slurm client: apt-get install slurm-client)"
done
sinfo -h >/dev/null 2>&1 || die 2 "no Slurm cluster answers (sinfo failed; for the local one:" \
  "tools/slurm/local_cluster.sh start, then eval \"\$(tools/slurm/local_cluster.sh env)\")"

# Bad input, and an OUT holding another campaign, fail here rather than in every task.
campaign_setup campaign_slurm.sh "$campaign" "${out_args[@]}"

logs=$out/slurm
mkdir -p "$logs"   # Slurm does not create the directory of --output
echo "campaign_slurm.sh: $campaign: array of $shards tasks into $out" >&2
status=0
job=$(LADRC_SIL=$sil sbatch --parsable --wait --array="1-$shards" --output="$logs/slurm-%A_%a.out" \
  "${sbatch_opts[@]}" "$root/tools/slurm/campaign.sbatch" "$campaign" "${out_args[@]:1}") || status=$?
job=${job%%;*}    # --parsable: "jobid" or "jobid;cluster"
[[ -n $job ]] || die 1 "sbatch submitted nothing (exit status $status)"

# Each task's own word, from its output file.
failed=()
for ((k = 1; k <= shards; k++)); do
  f=$logs/slurm-${job}_$k.out
  line=$(grep -a "^campaign.sbatch: shard $k/$shards exit status " "$f" 2>/dev/null | tail -n 1 || true)
  if [[ -z $line ]]; then
    failed+=("$k (no status in $f)")
  elif [[ ${line##* } != 0 ]]; then
    failed+=("$k (exit status ${line##* })")
  fi
done
if [[ ${#failed[@]} -gt 0 ]]; then
  echo "campaign_slurm.sh: error: job $job: ${#failed[@]} of $shards tasks failed: ${failed[*]}" >&2
  if command -v scontrol >/dev/null 2>&1; then
    scontrol -o show job "$job" 2>/dev/null |
      sed -n 's/.*ArrayTaskId=\([^ ]*\).*JobState=\([^ ]*\).*ExitCode=\([^ ]*\).*/  task \1: \2, exit code \3/p' | sort -n -k2 >&2 || true
  fi
  exit 1
fi
[[ $status -eq 0 ]] || die 1 "job $job: sbatch --wait exit status $status although every task reported 0"
echo "campaign_slurm.sh: job $job: all $shards tasks succeeded" >&2
"$py" "$root/tools/campaign.py" merge "$out"
