#!/usr/bin/env bash
# usage: probes.sh VKRAY OUTDIR
# Re-runs this round's kernel experiments with the binary VKRAY (kernels loaded from folders through
# VKRAY_KERNEL_DIR, docs/architecture.md): each diff under dropped/ is applied to a copy of shaders/
# and compiled as CMakeLists.txt compiles the kernels; the plain kernels (glslangValidator -Os) are
# the baseline. Pipeline-creation probes on elephant.scene at 16x16 (METRIC pipeline_ms), kernel-time
# experiments on the bunny close-up's camera rays and on objects/cornell; one lavapipe thread,
# interleaved rounds (../node-steps/kernel-ab.sh). Writes OUTDIR/*.txt.
set -euo pipefail
bin=$(realpath "$1"); out=$(realpath -m "$2"); here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../../.." && pwd); ab=$here/../node-steps/kernel-ab.sh
work=$(mktemp -d); mkdir -p "$out"
compile() {  # compile NAME KERNEL [glslang flags]: $work/NAME/out/render_KERNEL.spv from $work/NAME
  mkdir -p "$work/$1/out"
  glslangValidator --target-env vulkan1.1 "${@:3}" --quiet -I"$work/$1" -o "$work/$1/out/render_$2.spv" "$work/$1/render_$2.comp"
}
variant() {  # variant NAME DIFF KERNEL...: shaders/ with DIFF applied (no DIFF: as they are)
  local name=$1 diff=$2; shift 2
  rm -rf "$work/$name"; cp -r "$root/shaders" "$work/$name"
  [[ -n $diff ]] && patch -s -d "$work/$name" -p1 < "$diff"
  for k in "$@"; do compile "$name" "$k" -Os; done
}
spec() { echo "$bin:$work/$1/out"; }
variant base "" brute bvh kd_stack kd_backtrack
for p in trivial onepix-notrace notrace onepix noshade nolights nosec; do variant "$p" "$here/dropped/pipeline-probes/$p.diff" brute; done
variant nonextpass "$here/dropped/pipeline-probes/nonextpass.diff" kd_stack kd_backtrack
variant nextpass-rewrite "$here/dropped/kd-next-pass-without-code-loop.diff" kd_stack kd_backtrack
rm -rf "$work/noinline"; cp -r "$root/shaders" "$work/noinline"; compile noinline bvh; compile noinline kd_stack  # glslang without -Os
mkdir -p "$work/spirvopt/out"
for k in bvh kd_stack; do spirv-opt -O "$work/base/out/render_$k.spv" -o "$work/spirvopt/out/render_$k.spv"; done
export LP_NUM_THREADS=1
{
  echo "== brute, pipeline_ms: baseline, then the kernel cut down (dropped/pipeline-probes/*.diff)"
  METRIC='d["gpu"]["pipeline_ms"]' bash "$ab" 7 "$root/scenes/elephant.scene" --size 16x16 --accel brute -- \
    $(spec base) $(spec trivial) $(spec onepix-notrace) $(spec notrace) $(spec onepix) $(spec noshade) $(spec nolights) $(spec nosec)
  for a in kd-stack kd-backtrack; do
    echo "== $a, pipeline_ms: baseline, one pass only (nonextpass), kdNextPass without the loop over 48 codes"
    METRIC='d["gpu"]["pipeline_ms"]' bash "$ab" 7 "$root/scenes/elephant.scene" --size 16x16 --accel $a -- \
      $(spec base) $(spec nonextpass) $(spec nextpass-rewrite)
  done
  for a in bvh kd-stack; do
    echo "== $a, pipeline_ms: glslang -Os (baseline), glslang without -Os (functions not inlined), -Os then spirv-opt -O"
    METRIC='d["gpu"]["pipeline_ms"]' bash "$ab" 5 "$root/scenes/elephant.scene" --size 16x16 --accel $a -- \
      $(spec base) $(spec noinline) $(spec spirvopt)
  done
} 2>&1 | tee "$out/pipeline-probes.txt"
variant kd-push "$here/dropped/kd-push-unconditional.diff" kd_stack
variant kd-fetch2 "$here/dropped/kd-second-node-fetch.diff" kd_stack
variant kd-uvec2 "$here/dropped/kd-stack-uvec2-entries.diff" kd_stack
variant shared-nodes "$here/dropped/bvh-nodes-in-shared-memory.diff" bvh
{
  for m in bunny armadillo; do
    echo "== kd-stack kernel time, $m close-up 512x384: baseline, push stored unconditionally, a second node fetch a step, entries as uvec2"
    bash "$ab" 7 "$root/scenes/primary/$m.scene" --view close --size 512x384 --accel kd-stack -- \
      $(spec base) $(spec kd-push) $(spec kd-fetch2) $(spec kd-uvec2)
  done
  for s in objects cornell; do
    echo "== bvh kernel time, $s.scene 640x480: baseline, the nodes copied into workgroup memory"
    bash "$ab" 7 "$root/scenes/$s.scene" -- $(spec base) $(spec shared-nodes)
  done
} 2>&1 | tee "$out/kernel-experiments.txt"
rm -rf "$work"
