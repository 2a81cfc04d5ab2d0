#!/usr/bin/env bash
# usage: probes.sh VKRAY OUTFILE
# What a small scene's kernel spends outside its walk, on lavapipe: the bvh kernel of revision 319a080
# (before the compact pixel records; VKRAY is a build of that revision) cut down by each diff
# (dropped/*.diff, and ../shared-pipelines/dropped/pipeline-probes/{trivial,miss}.diff), kernels
# loaded through VKRAY_KERNEL_DIR, one lavapipe thread, 7 interleaved rounds
# (../node-steps/kernel-ab.sh). all-miss.scene: every camera ray misses the root's one child;
# objects-camera.scene: objects.scene's camera rays. The last two diffs (poploop, anypush) were
# candidates, also measured on the bunny close-up's camera rays.
set -euo pipefail
bin=$(realpath "$1"); out=$(realpath -m "$2"); here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../../.." && pwd); ab=$here/../node-steps/kernel-ab.sh
work=$(mktemp -d)
variant() {  # variant NAME [DIFF]: the bvh kernel from shaders/ with DIFF applied
  rm -rf "$work/$1"; mkdir -p "$work/$1/out"
  git -C "$root" archive 319a080 shaders | tar -x -C "$work/$1" --strip-components=1
  [[ $# -gt 1 ]] && patch -s -d "$work/$1" -p1 < "$2"
  glslangValidator --target-env vulkan1.1 -Os --quiet -I"$work/$1" -o "$work/$1/out/render_bvh.spv" "$work/$1/render_bvh.comp"
}
variant base
for p in trivial miss; do variant $p "$here/../shared-pipelines/dropped/pipeline-probes/$p.diff"; done
for p in store store1 storedense storeu onestep nosort nopop nopush poploop anypush; do variant $p "$here/dropped/$p.diff"; done
spec() { for v in "$@"; do echo "$bin:$work/$v/out"; done; }
export LP_NUM_THREADS=1
{
  date -u
  echo "== all-miss.scene"
  bash "$ab" 7 "$here/all-miss.scene" -- $(spec base trivial store store1 storedense storeu miss onestep nosort nopop nopush poploop anypush)
  # nosort, nopop and nopush walk wrongly where rays enter the tree (they leave entered children
  # out, or never pop): all-miss.scene only.
  echo "== objects-camera.scene"
  bash "$ab" 7 "$here/objects-camera.scene" -- $(spec base trivial store miss onestep poploop anypush)
  echo "== bunny close-up camera rays, 512x384"
  bash "$ab" 7 "$root/scenes/primary/bunny.scene" --view close --size 512x384 -- $(spec base poploop anypush)
} | tee "$out"
rm -rf "$work"
