#!/usr/bin/env bash
# A tiled render through Slurm for real (docs/cluster.md): a throwaway single-node Slurm
# (slurm_cluster.sh), scripts/slurm/submit-render.sh with 4 tiles (a job that builds the structure
# once, the tile array, the assemble job), then checks that the assembled EXR is bit-identical to one
# process rendering the whole image, and prints the farm's wall clock against that process's. Then a
# fault: a tile lost; vkray assemble must name it, and resubmitting that tile alone must complete the
# image again. A Slurm that cannot start fails the test.
# usage: slurm_render_test.sh VKRAY SOURCE_DIR WORK_DIR
set -euo pipefail
vkray=$(realpath "$1") src=$(realpath "$2") work=$3
# shellcheck source=tests/slurm/slurm_cluster.sh
source "$src/tests/slurm/slurm_cluster.sh"
rm -rf "$work"
mkdir -p "$work"
work=$(realpath "$work")
scene=$src/scenes/objects.scene
options=(--size 160x120)
submit=$src/scripts/slurm/submit-render.sh
export VKRAY=$vkray POLL=0.25

fail() {
  echo "FAIL: $*" >&2
  tail -n 5 "$work"/farm.exr.parts/logs/*.out >&2 2>/dev/null || true
  exit 1
}
seconds() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

# The whole image, bit for bit: the same file, or else the same pixels.
same_image() {
  cmp -s "$1" "$2" && { echo "bit-identical files"; return 0; }
  "$vkray" compare "$1" "$2" --threshold 0 --max-rmse 0 --max-bad-fraction 0 --quiet &&
    { echo "identical pixels (the files differ in their attributes)"; return 0; }
  return 1
}

# Submits and waits for the render; the ids of its jobs are in farm.exr.parts/jobs.
farm() {
  "$submit" "$@" "$scene" 4 "$work/farm.exr" "${options[@]}"
  local ids
  read -r -a ids <<<"$(cat "$work/farm.exr.parts/jobs")"
  slurm_wait "${ids[@]}"
  local id
  for id in "${ids[@]}"; do echo "job $id: $(slurm_state "$id")"; done
  [[ "$(slurm_state "${ids[-1]}")" == "1 COMPLETED" ]] || fail "the assemble job did not complete"
}

slurm_start
t0=$(date +%s.%N)
"$vkray" render "$scene" "${options[@]}" -o "$work/single.exr" --quiet
t1=$(date +%s.%N)
farm
t2=$(date +%s.%N)
how=$(same_image "$work/single.exr" "$work/farm.exr") || fail "the assembled image differs from the single render"
echo "assembled image against one process: $how"
echo "overhead: one process $(seconds "$t0" "$t1") s; the farm (build once, 4 tiles, assemble; submit to image) $(seconds "$t1" "$t2") s"

# A lost tile: assemble names it, and the tile alone, resubmitted, completes the image.
rm "$work/farm.exr.parts/tiles/tile-2.exr" "$work/farm.exr"
if message=$("$vkray" assemble "$work"/farm.exr.parts/tiles/tile-*.exr -o "$work/partial.exr" 2>&1); then
  fail "vkray assemble accepted 3 tiles of 4"
fi
echo "assemble without tile 2: $message"
[[ $message =~ missing\ tile\ [0-9]+\ of\ 4 ]] || fail "assemble did not name the missing tile"
farm --tasks 2
[[ $(wc -w <"$work/farm.exr.parts/jobs") -eq 2 ]] || fail "the structure was built again for one tile"
how=$(same_image "$work/single.exr" "$work/farm.exr") || fail "the image completed by the resubmitted tile differs"
echo "PASS: 4 tiles through Slurm assemble to the single render ($how); a lost tile is named and redone alone"
