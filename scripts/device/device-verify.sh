#!/usr/bin/env bash
# What a GPU lease should run first (its device time: docs/performance.md, "Tools"): whether the
# kernels as built pass on the device (the GPU division test, docs/stability.md "Division on GPUs";
# the degenerate stress case; the whole stress suite; the GPU tests with the validation layer on),
# then the primary-ray protocol where frames last long enough for steady rates: bvh, the packet
# kernels and every kd walk on the 1M sphere grid at 1920x1080; bvh, bvh-packet, kd-stack, kd-packet
# and kd-ropes on the three meshes' close-ups at 3840x2160; rayquery beside them where the device
# has VK_KHR_ray_query (docs/performance.md, "NVIDIA H200"). The GPU's clocks are logged each second
# to OUTDIR/clocks.csv where nvidia-smi exists.
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
# rayquery joins the runs only where the device has it: on one without, vkray refuses the command.
rq=""
"$vk" devices | grep -A1 "$device" | grep -q "ray query (--accel rayquery)" && rq=,rayquery
if [ -n "$rq" ]; then echo "rayquery measured: yes"; else echo "rayquery measured: no (no VK_KHR_ray_query on the device)"; fi
if command -v nvidia-smi > /dev/null; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu,utilization.gpu \
    --format=csv -l 1 > "$out/clocks.csv" 2>&1 &
  smi=$!
  trap 'kill $smi 2> /dev/null' EXIT
fi

src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=$device
section "GPU division test (IEEE quotients, near-midpoint pairs included)"
timeout 60 "$bundle/vkray_gpu_tests" --gtest_filter='Division*' 2>&1 | grep -vE "^vulkan validation warning" | tail -6
section "degenerate stress case, kernels as built"
timeout 60 "$bundle/vkray_stress_tests" --gtest_filter='*degenerate*' 2>&1 \
  | grep -E "gpu (brute|bvh|kd-ropes) |^\[ +(OK|FAILED) "
section "stress tests as built and GPU tests with validation on, side by side (failures in full)"
# Side by side: neither binary fills the GPU or the host's cores, so together they take about the
# longer one's time (2.5 minutes on an H200), not the sum (4).
logs=$(mktemp -d)
timeout 240 "$bundle/vkray_stress_tests" --gtest_brief=1 > "$logs/stress" 2>&1 & stress=$!
timeout 300 "$bundle/vkray_gpu_tests" --gtest_brief=1 > "$logs/gpu" 2>&1 & gpu=$!
wait $stress; echo "vkray_stress_tests exit $?"
grep -vE "^\| |^vulkan validation warning|rays per pixel" "$logs/stress" | tail -80
wait $gpu; echo "vkray_gpu_tests exit $?"
grep -vE "^measured|^vulkan validation warning" "$logs/gpu" | tail -40

section "primary rays, 1M sphere grid, 1920x1080: bvh, the packet kernels and every kd walk"
bench 200 scenes/primary/spheres-1m.scene --view close --size "$(size 1920x1080)" --repeat "$(repeats 5)" \
  --accel bvh,bvh-packet,kd-stack,kd-packet,kd-shortstack,kd-restart,kd-pushdown,kd-ropes,kd-backtrack$rq \
  --out "$out/primary-1m-1920x1080"
section "primary rays, 3840x2160 close-ups: bvh, bvh-packet, kd-stack, kd-packet and kd-ropes"
bench 300 scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene \
  --view close --size "$(size 3840x2160)" --repeat "$(repeats 5)" --accel bvh,bvh-packet,kd-stack,kd-packet,kd-ropes$rq \
  --out "$out/primary-3840x2160"
section "reports written"
ls "$out"/*/bench.md 2>/dev/null
