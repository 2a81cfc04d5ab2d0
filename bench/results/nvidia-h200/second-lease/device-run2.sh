#!/usr/bin/env bash
# The second GPU round of docs/benchmarks.md ("On a data-centre GPU", second lease): every accelerator
# of `vkray bench` on the primary-ray protocol (the 1M sphere grid at 1920x1080, the three scanned
# meshes at 1024x768 and at 3840x2160, where a frame lasts long enough for steady rates), the
# degenerate stress case with kernels whose divisions are corrected to IEEE rounding, the stress and
# GPU tests, and full renders against --cpu. On the GPU machine, from a bundle of make-bundle.sh and
# a folder of kernel variants (one folder of render_*.spv each, read through VKRAY_KERNEL_DIR):
#   bash bench/results/nvidia-h200/second-lease/device-run2.sh BUNDLE OUTDIR VARIANTS
set -u
bundle=$(cd "$1" && pwd); out=$2; variants=$3; mkdir -p "$out"
export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
vk=$bundle/vkray
threads=$(nproc)
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }
bench() { timeout "$1" "$vk" bench "${@:2}" --deltas none --maxdepths none --threads "$threads" --device NVIDIA --quiet; }

section devices
"$vk" devices || exit 1
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv || true

section "primary rays, 1M sphere grid, 1920x1080, every accelerator"
bench 200 scenes/primary/spheres-1m.scene --view close --size 1920x1080 --repeat 7 --out "$out/primary-1m-1920x1080"
section "primary rays, 1024x768 close-ups, every accelerator"
bench 150 scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene \
  --view close --size 1024x768 --repeat 9 --out "$out/primary-1024x768"

src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=NVIDIA
section "degenerate stress case: kernels as built, then with corrected divisions (camera, shear, 1/det, all)"
for v in base cam shear inv all; do
  echo "-- $v"
  VKRAY_KERNEL_DIR=$variants/$v timeout 60 "$bundle/vkray_stress_tests" --gtest_filter='*degenerate*' 2>&1 \
    | grep -E "gpu (brute|bvh|kd-ropes) |^\[ +(OK|FAILED) "
done
section "stress tests as built (failures in full)"
timeout 120 "$bundle/vkray_stress_tests" 2>&1 | grep -vE "^\| |^vulkan validation warning|^\[ +(RUN|OK) |rays per pixel" | tail -40
section "GPU tests, validation on"
timeout 100 "$bundle/vkray_gpu_tests" --gtest_brief=1 2>&1 | grep -vE "^measured|^vulkan validation warning" | tail -15
section "stress tests with every division corrected"
VKRAY_KERNEL_DIR=$variants/all timeout 120 "$bundle/vkray_stress_tests" 2>&1 \
  | grep -vE "^\| |^vulkan validation warning|^\[ +(RUN|OK) |rays per pixel" | tail -25

section "primary rays, 3840x2160 close-ups, every accelerator"
bench 150 scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene \
  --view close --size 3840x2160 --repeat 5 --out "$out/primary-3840x2160"

section "full Whitted renders (bvh, kd-ropes) against --cpu"
for s in cornell objects spheres lights bunny; do
  for a in cpu bvh kd-ropes; do
    if [ $a = cpu ]; then args=(--cpu); else args=(--accel $a --device NVIDIA --stats); fi
    echo "$s $a: $("$vk" render scenes/$s.scene "${args[@]}" -o /tmp/r-$a.png 2>&1 | grep -E "^(render time|timing):" | tr '\n' ' ')"
  done
done
