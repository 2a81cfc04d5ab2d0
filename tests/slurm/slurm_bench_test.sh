#!/usr/bin/env bash
# A `vkray bench` sweep through Slurm for real (docs/cluster.md): a throwaway single-node Slurm
# (slurm_cluster.sh), scripts/slurm/submit-bench.sh with 4 shards and the merge, then checks that the
# merged report lists exactly the configurations an unsharded run lists, each figure equal to the
# figure of the shard that measured it (check_bench_merge.jq); then a shard cut short, which the merge
# must name and which, resubmitted alone, must complete the merge. Times are printed, never compared.
# A Slurm that cannot start fails the test.
# usage: slurm_bench_test.sh VKRAY SOURCE_DIR WORK_DIR
set -euo pipefail
vkray=$(realpath "$1") src=$(realpath "$2") work=$3
# shellcheck source=tests/slurm/slurm_cluster.sh
source "$src/tests/slurm/slurm_cluster.sh"
command -v jq >/dev/null || { echo "FAIL: jq is not installed (scripts/install-deps.sh installs it)" >&2; exit 1; }
rm -rf "$work"
mkdir -p "$work"
work=$(realpath "$work")

scene=$src/scenes/objects.scene
# 6 configurations over 4 shards: the reference, 2 accelerators, their concurrent build, 1 AAC
# delta, the maxdepth sweep.
# shellcheck disable=SC2054  # commas inside an option value
options=(--size 32x24 --repeat 1 --threads 1 --accel bvh,kd-stack --deltas 8)

slurm_start
t0=$(date +%s.%N)
"$vkray" bench "$scene" "${options[@]}" --out "$work/unsharded" --quiet >"$work/unsharded.log"
t1=$(date +%s.%N)
VKRAY=$vkray POLL=0.25 "$src/scripts/slurm/submit-bench.sh" 4 "$work/sweep" "$scene" "${options[@]}"
read -r array merge <"$work/sweep/jobs"
slurm_wait "$array" "$merge"
t2=$(date +%s.%N)
echo "shards: $(slurm_state "$array"); merge: $(slurm_state "$merge")"
if [[ "$(slurm_state "$merge")" != "1 COMPLETED" ]]; then
  echo "FAIL: the merge job did not complete" >&2
  tail -n 5 "$work"/sweep/logs/*.out >&2 || true
  exit 1
fi

shards=()
for i in 0 1 2 3; do
  [[ -f "$work/sweep/shards/$i/bench.json" ]] || { echo "FAIL: shard $i wrote no bench.json" >&2; exit 1; }
  shards+=("$work/sweep/shards/$i/bench.json")
done
for f in bench.json bench.md report.html; do
  [[ -s "$work/sweep/merged/$f" ]] || { echo "FAIL: the merge wrote no $f" >&2; exit 1; }
done
problems=$(jq -r -s -f "$src/tests/slurm/check_bench_merge.jq" "$work/sweep/merged/bench.json" \
             "$work/unsharded/bench.json" "${shards[@]}")
if [[ -n "$problems" ]]; then
  echo "FAIL: the merged report does not match its shards and the unsharded run:" >&2
  echo "$problems" >&2
  exit 1
fi

# A shard cut short (as a killed task leaves it: marked incomplete, its scene not saved): the merge
# names it, and that array task alone, resubmitted, measures it again (--resume) and the merge
# completes.
jq '.complete = false | .failure = "interrupted by SIGTERM" | .scenes = []' "$work/sweep/shards/1/bench.json" \
  >"$work/cut.json"
mv "$work/cut.json" "$work/sweep/shards/1/bench.json"
rm -r "$work/sweep/merged"
if message=$("$vkray" bench --merge "$work"/sweep/shards/* --out "$work/partial" 2>&1); then
  echo "FAIL: vkray bench --merge merged an incomplete shard" >&2
  exit 1
fi
echo "merge with shard 1 cut short: $message"
[[ $message == *"shard 1/4 ("*") is incomplete: interrupted by SIGTERM; not measured: $scene; rerun it with --resume" ]] || {
  echo "FAIL: the merge did not name the incomplete shard and its scene" >&2
  exit 1
}
VKRAY=$vkray POLL=0.25 "$src/scripts/slurm/submit-bench.sh" --tasks 1 4 "$work/sweep" "$scene" "${options[@]}"
read -r array merge <"$work/sweep/jobs"
slurm_wait "$array" "$merge"
[[ "$(slurm_state "$merge")" == "1 COMPLETED" ]] || {
  echo "FAIL: the merge after the resubmitted shard did not complete" >&2
  tail -n 5 "$work"/sweep/logs/*.out >&2 || true
  exit 1
}
jq -e '.complete and (.scenes | length) == 1' "$work/sweep/shards/1/bench.json" >/dev/null || {
  echo "FAIL: the resubmitted shard is not complete" >&2
  exit 1
}
problems=$(jq -r -s -f "$src/tests/slurm/check_bench_merge.jq" "$work/sweep/merged/bench.json" \
             "$work/unsharded/bench.json" "${shards[@]}")
[[ -z "$problems" ]] || { echo "FAIL: the merge after the resubmitted shard: $problems" >&2; exit 1; }

configs=$(jq '[.scenes[].configurations[]] | length' "$work/sweep/merged/bench.json")
grep -q "^## Shards" "$work/sweep/merged/bench.md" || { echo "FAIL: bench.md lists no shards" >&2; exit 1; }
grep -q '<section id="shards">' "$work/sweep/merged/report.html" || { echo "FAIL: report.html lists no shards" >&2; exit 1; }
awk -v c="$configs" -v a="$(awk -v x="$t0" -v y="$t1" 'BEGIN { print y - x }')" -v b="$(awk -v x="$t1" -v y="$t2" 'BEGIN { print y - x }')" \
  'BEGIN { printf "PASS: %d configurations from 4 shards merged as the unsharded run lists them (a shard cut short named, then resumed alone); unsharded run %.1f s, sweep through Slurm (submit to merged report) %.1f s\n", c, a, b }' 
