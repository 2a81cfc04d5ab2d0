#!/usr/bin/env bash
# A tiled render on a Slurm cluster (docs/cluster.md): one job builds the scene's structure and
# saves it; then N array tasks each render one band of rows with it (vkray render --tile I/N) into
# an EXR tile; then a job joins the tiles into OUTPUT (vkray assemble). Each step starts only when the
# one before succeeded. The tiles, the structure and the logs go to OUTPUT's name + ".parts/".
# usage: scripts/slurm/submit-render.sh [--wait] [--tasks LIST] SCENE N OUTPUT [vkray render options]
#   --wait        return when OUTPUT is written (exit 0 only if the last job completed)
#   --tasks LIST  render only these tiles (an sbatch --array list: "2" or "1,3"), with the structure
#                 already saved, then assemble again: to redo a failed tile
# Environment: VKRAY, SBATCH_OPTIONS, POLL, as for submit-bench.sh. Prints the job ids, and writes
# them to OUTPUT.parts/jobs.
set -euo pipefail
# shellcheck source=scripts/slurm/common.sh
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

parse_submit_options "$@"
shift "$options_used"
[[ $# -ge 3 ]] || { usage; exit 2; }
scene=$1 n=$2 output=$3
shift 3
check_count "$n"
vkray=$(vkray_binary)
parts=$output.parts
mkdir -p "$parts/tiles" "$parts/logs"
parts=$(realpath "$parts")
output=$(realpath "$output")
structure=$parts/structure.accel

after=()
if [[ -z "$tasks" || ! -f "$structure" ]]; then
  build=$(submit --job-name=vkray-render-build --output="$parts/logs/build.out" \
                 "$here/render-build.sbatch" "$vkray" "$scene" "$structure" "$@")
  after=(--dependency="afterok:$build" --kill-on-invalid-dep=yes)
  echo "build:    job $build -> $structure"
else
  build=""
fi
array=$(submit --job-name=vkray-render-tile --array="${tasks:-0-$((n - 1))}" "${after[@]}" \
               --output="$parts/logs/tile-%a.out" "$here/render-tile.sbatch" "$vkray" "$scene" "$n" "$structure" \
               "$parts/tiles" "$@")
assemble=$(submit --job-name=vkray-render-assemble --dependency="afterok:$array" --kill-on-invalid-dep=yes \
                  --output="$parts/logs/assemble.out" "$here/render-assemble.sbatch" "$vkray" "$parts/tiles" "$output")
echo "$build $array $assemble" >"$parts/jobs"
echo "tiles:    job array $array (${tasks:-0-$((n - 1))} of $n) -> $parts/tiles/tile-I.exr"
echo "assemble: job $assemble after all of them -> $output"
[[ $wait -eq 1 ]] || exit 0
wait_jobs ${build:+"$build"} "$array" "$assemble"
