#!/usr/bin/env bash
# Every accelerator on a GPU machine, from a bundle of make-bundle.sh (docs/performance.md, "NVIDIA
# H200" and "Tools"): 1. `vkray devices`; 2. the GPU and stress test binaries on the GPU with the
# validation layer on (every kernel against GPU brute force and the CPU reference); 3. the
# primary-ray protocol (`vkray bench`, every accelerator, Embree on all cores in the same repeats)
# on the three scanned meshes' close-ups and on the 1M sphere grid; 4. the full Whitted render of
# every hand-made scene, GPU (bvh, kd-stack, kd-backtrack) against --cpu, with the image check.
# The meshes' frames at 1024x768 are too short on a data-centre GPU for steady rates:
# MESH_SIZE=3840x2160 gives frames long enough (docs/performance.md, "NVIDIA H200").
#
# usage: scripts/device/device-run.sh BUNDLE OUTDIR     (on the GPU machine, from the repository root)
#   DEVICE: a substring of the device's name (default NVIDIA).
set -u
[ $# -ge 2 ] || { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0" >&2; exit 2; }
bundle=$(cd "$1" && pwd); out=$2; mkdir -p "$out"
export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
vk=$bundle/vkray
threads=$(nproc)
device=${DEVICE:-NVIDIA}
mesh_size=${MESH_SIZE:-1024x768}
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }

section devices
"$vk" devices || exit 1
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv || true

section "GPU and stress tests on the GPU, validation on"
# The tests find their scenes under the source folder they were built in.
src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=$device
for t in vkray_gpu_tests vkray_stress_tests; do
  timeout 100 "$bundle/$t" --gtest_brief=1 2>&1 | grep -v "^vulkan validation warning" | tail -25
  echo "$t exit ${PIPESTATUS[0]}"
done

section "primary rays, $mesh_size close-ups, every accelerator"
timeout 300 "$vk" bench scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene \
  --view close --size "$mesh_size" --deltas none --maxdepths none --repeat 7 \
  --threads "$threads" --device "$device" --quiet --out "$out/primary-$mesh_size"
section "primary rays, 1M sphere grid, 1920x1080, every accelerator"
timeout 200 "$vk" bench scenes/primary/spheres-1m.scene --view close --size 1920x1080 \
  --deltas none --maxdepths none --repeat 7 --threads "$threads" --device "$device" --quiet --out "$out/primary-1m-1920x1080"

section "full Whitted renders, GPU (bvh, kd-stack, kd-backtrack) against --cpu: render time, then wall s"
mkdir -p "$out/renders"
wall() { local t0 t1; t0=$(date +%s.%N); "$@" 2>&1 | grep -E "^(render time|timing):" | tr '\n' ' '; t1=$(date +%s.%N); awk -v a="$t0" -v b="$t1" 'BEGIN{printf "wall %.2f s\n", b - a}'; }
for s in scenes/*.scene; do
  n=$(basename "$s" .scene)
  echo "$n cpu: $(wall "$vk" render "$s" --cpu -o "$out/renders/$n-cpu.png")"
  for a in bvh kd-stack kd-backtrack; do
    echo "$n $a: $(wall "$vk" render "$s" --accel $a --device "$device" --stats -o "$out/renders/$n-$a.png")"
    "$vk" compare "$out/renders/$n-$a.png" "$out/renders/$n-cpu.png" --max-rmse 0.012 --max-bad-fraction 0.005 >/dev/null \
      && echo "$n $a: matches --cpu" || echo "$n $a: DIFFERS from --cpu"
  done
done
rm -rf "$out/renders"
