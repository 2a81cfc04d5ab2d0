#!/usr/bin/env bash
# A `vkray bench` sweep on a Slurm cluster (docs/cluster.md): N array tasks each measure one shard of
# the configurations (vkray bench --shard I/N), then a job that starts only when all of them
# succeeded merges their reports into OUT/merged.
# usage: scripts/slurm/submit-bench.sh [--wait] [--tasks LIST] N OUT SCENE... [vkray bench options]
#   --wait        return when the merge is done (exit 0 only if it completed)
#   --tasks LIST  submit only these shards (an sbatch --array list: "2" or "1,3"), e.g. to rerun a
#                 failed one, then the merge again
# Environment: VKRAY (the binary; default vkray on PATH, else build/vkray), SBATCH_OPTIONS (options
# for every job, e.g. "--partition=gpu --gres=gpu:1 --time=1:00:00"), POLL (seconds, for --wait).
# Prints the job ids, and writes them to OUT/jobs.
set -euo pipefail
# shellcheck source=scripts/slurm/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

parse_submit_options "$@"
shift "$options_used"
[[ $# -ge 3 ]] || { usage; exit 2; }
n=$1 out=$2
shift 2
check_count "$n"
vkray=$(vkray_binary)
mkdir -p "$out/logs"
out=$(realpath "$out")

array=$(submit --job-name=vkray-bench-shard --array="${tasks:-0-$((n - 1))}" --output="$out/logs/shard-%a.out" \
               "$here/bench-shard.sbatch" "$vkray" "$n" "$out" "$@")
merge=$(submit --job-name=vkray-bench-merge --dependency="afterok:$array" --kill-on-invalid-dep=yes \
               --output="$out/logs/merge.out" "$here/bench-merge.sbatch" "$vkray" "$out")
echo "$array $merge" >"$out/jobs"
echo "shards: job array $array (${tasks:-0-$((n - 1))} of $n) -> $out/shards/I"
echo "merge:  job $merge after all of them -> $out/merged/report.html"
[[ $wait -eq 1 ]] || exit 0
wait_jobs "$array" "$merge"
