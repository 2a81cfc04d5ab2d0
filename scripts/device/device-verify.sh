#!/usr/bin/env bash
# What a GPU lease should run first (its device time: docs/performance.md, "Tools"): whether the
# kernels as built pass on the device (the GPU division test, docs/stability.md "Division on GPUs";
# the degenerate stress case; the whole stress suite; the GPU tests with the validation layer on),
# then the primary-ray protocol where frames last long enough for steady
# rates: bvh and every kd walk on the 1M sphere grid at 1920x1080, bvh and kd-ropes on the three
# meshes' close-ups at 3840x2160 (docs/performance.md, "NVIDIA H200").
#
# usage: scripts/device/device-verify.sh BUNDLE OUTDIR [DEVICE]   (on the GPU machine, repository root)
#   BUNDLE: unpacked from make-bundle.sh; on a machine with vkray's packages, a folder holding
#   vkray, vkray_gpu_tests, vkray_stress_tests and source-dir (no lib/) will do.
#   DEVICE: a substring of the device's name (default NVIDIA). With DEVICE=llvmpipe and SMALL=1
#   (small images, few repeats) it runs on lavapipe in a few minutes: a dry run before a lease.
set -u
[ $# -ge 2 ] || { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0" >&2; exit 2; }
bundle=$(cd "$1" && pwd); out=$2; device=${3:-NVIDIA}; mkdir -p "$out"
[ -d "$bundle/lib" ] && export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
vk=$bundle/vkray
threads=$(nproc)
small=${SMALL:-0}
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }
bench() { timeout "$1" "$vk" bench "${@:2}" --deltas none --maxdepths none --threads "$threads" --device "$device" --quiet; }
size() { if [ "$small" = 1 ]; then echo 256x144; else echo "$1"; fi; }
repeats() { if [ "$small" = 1 ]; then echo 2; else echo "$1"; fi; }

section devices
"$vk" devices || exit 1
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv 2>/dev/null || true

src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=$device
section "GPU division test (IEEE quotients, near-midpoint pairs included)"
timeout 60 "$bundle/vkray_gpu_tests" --gtest_filter='Division*' 2>&1 | grep -vE "^vulkan validation warning" | tail -6
section "degenerate stress case, kernels as built"
timeout 60 "$bundle/vkray_stress_tests" --gtest_filter='*degenerate*' 2>&1 \
  | grep -E "gpu (brute|bvh|kd-ropes) |^\[ +(OK|FAILED) "
section "stress tests as built (failures in full)"
timeout 150 "$bundle/vkray_stress_tests" 2>&1 | grep -vE "^\| |^vulkan validation warning|^\[ +(RUN|OK) |rays per pixel" | tail -30
section "GPU tests, validation on"
timeout 120 "$bundle/vkray_gpu_tests" --gtest_brief=1 2>&1 | grep -vE "^measured|^vulkan validation warning" | tail -15

section "primary rays, 1M sphere grid, 1920x1080: bvh and every kd walk"
bench 150 scenes/primary/spheres-1m.scene --view close --size "$(size 1920x1080)" --repeat "$(repeats 5)" \
  --accel bvh,kd-stack,kd-shortstack,kd-restart,kd-pushdown,kd-ropes,kd-backtrack --out "$out/primary-1m-1920x1080"
section "primary rays, 3840x2160 close-ups: bvh and kd-ropes"
bench 200 scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene \
  --view close --size "$(size 3840x2160)" --repeat "$(repeats 5)" --accel bvh,kd-ropes --out "$out/primary-3840x2160"
section "reports written"
ls "$out"/*/bench.md 2>/dev/null
