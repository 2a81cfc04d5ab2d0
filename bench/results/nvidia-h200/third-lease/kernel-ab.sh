#!/usr/bin/env bash
# Do the kernel changes made and measured on lavapipe since the second lease (pixels of a SIMD-8 run
# on 4x2 blocks, min/max as compare-select, the camera's divisions corrected to IEEE rounding) help or
# hurt on a GPU? The kernels of 0b38af5 (second lease) and of this build, both read through
# VKRAY_KERNEL_DIR by the same vkray, alternated round by round on the primary-ray protocol
# (bunny, armadillo, dragon close-ups at 1024x768, Embree in the same repeats); then the full
# Whitted render of every hand-made scene, GPU (bvh) against --cpu, with the image check.
#   bash kernel-ab.sh BUNDLE KERNELS OUTDIR ROUNDS
# KERNELS: a folder with old/ and new/, each render_<kernel>[_resumable][_split].spv.
set -u
bundle=$(cd "$1" && pwd); kernels=$(cd "$2" && pwd); out=$3; rounds=$4; mkdir -p "$out"
[ -d "$bundle/lib" ] && export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
vk=$bundle/vkray
device=${DEVICE:-NVIDIA}; size=${SIZE:-1024x768}
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }

section "kernels old/new alternated, $rounds rounds, $size close-ups"
for r in $(seq "$rounds"); do
  for v in old new; do
    echo "round $r $v"
    VKRAY_KERNEL_DIR=$kernels/$v timeout 120 "$vk" bench scenes/primary/bunny.scene scenes/primary/armadillo.scene \
      scenes/primary/dragon.scene --view close --size "$size" --accel bvh,kd-stack,kd-restart,kd-backtrack,kd-ropes \
      --deltas none --maxdepths none --repeat 5 --threads "$(nproc)" --device "$device" --quiet --out "$out/$v-$r" \
      || echo "round $r $v: exit $?"
  done
done

section "full Whitted renders, GPU (bvh, kernels as built) against --cpu: render time, then wall s"
mkdir -p "$out/renders"
wall() { local t0 t1; t0=$(date +%s.%N); "$@" 2>&1 | grep -E "^(render time|timing):" | tr '\n' ' '; t1=$(date +%s.%N); awk -v a="$t0" -v b="$t1" 'BEGIN{printf "wall %.2f s\n", b - a}'; }
for s in scenes/*.scene; do
  n=$(basename "$s" .scene)
  [ "${SMALL:-0}" = 1 ] && sz=(--size 128x96) || sz=()
  echo "$n cpu: $(wall "$vk" render "$s" "${sz[@]}" --cpu -o "$out/renders/$n-cpu.png")"
  echo "$n bvh: $(wall "$vk" render "$s" "${sz[@]}" --accel bvh --device "$device" --stats -o "$out/renders/$n-bvh.png")"
  "$vk" compare "$out/renders/$n-bvh.png" "$out/renders/$n-cpu.png" --max-rmse 0.012 --max-bad-fraction 0.005 >/dev/null \
    && echo "$n bvh: matches --cpu" || echo "$n bvh: DIFFERS from --cpu"
done
rm -rf "$out/renders"
