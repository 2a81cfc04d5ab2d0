#!/usr/bin/env bash
# Which part of the kernel changes since the second lease costs the BVH walk on a GPU? Three sets of
# kernels read through VKRAY_KERNEL_DIR by the same vkray: old (0b38af5), new (as built: min/max as
# compare-select, lanes on 4x2 blocks, camera divisions corrected) and native (as built but GLSL's
# own min and max in shaders/include/min_max.glsl). bvh camera rays on the 1M sphere grid at
# 1920x1080 and the dragon close-up at 3840x2160 (frames of 4-7 ms), the order rotated each round.
#   bash minmax-ab.sh BUNDLE KERNELS OUTDIR ROUNDS   (KERNELS holds old/, new/, native/)
set -u
bundle=$(cd "$1" && pwd); kernels=$(cd "$2" && pwd); out=$3; rounds=$4; mkdir -p "$out"
[ -d "$bundle/lib" ] && export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
vk=$bundle/vkray
device=${DEVICE:-NVIDIA}; grid=${GRID:-1920x1080}; mesh=${MESH:-3840x2160}
order=(old new native)
for r in $(seq "$rounds"); do
  for i in 0 1 2; do
    v=${order[$(( (i + r) % 3 ))]}
    echo "round $r $v ($(date -u +%H:%M:%S))"
    for s in spheres-1m:$grid dragon:$mesh; do
      VKRAY_KERNEL_DIR=$kernels/$v timeout 60 "$vk" bench "scenes/primary/${s%%:*}.scene" --view close --size "${s#*:}" \
        --accel bvh --deltas none --maxdepths none --repeat 5 --threads "$(nproc)" --device "$device" --quiet \
        --out "$out/$v-$r-${s%%:*}" 2>&1 | grep -v "^vkray: kernel"
    done
  done
done
