#!/usr/bin/env bash
# A/B of vkray builds on a GPU machine, from a bundle of bench/results/nvidia-h200/make-bundle.sh holding the
# new build as `vkray` and the others beside it:
#   bash bench/results/nvidia-h200/device-ab.sh BUNDLE ROUNDS BINARY...
# Each round runs every binary once (ABC ABC ...): `vkray bench` on the bunny close-up at 1024x768 and
# the 1M sphere grid at 1920x1080, Embree on all cores in the same run. Then the stress tests with
# their failures in full, and the GPU tests with validation on, of the new build.
set -u
bundle=$(cd "$1" && pwd); rounds=$2; shift 2
export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }
for r in $(seq "$rounds"); do
  for b in "$@"; do
    section "round $r: $b"
    timeout 120 "$bundle/$b" bench scenes/primary/bunny.scene --view close --size 1024x768 \
      --accel bvh,kd-stack,kd-backtrack --deltas none --maxdepths none --repeat 5 --threads "$(nproc)" \
      --device NVIDIA --quiet --out "/tmp/ab-$b-$r-bunny" | grep -E "Embree|bvh |kd-"
    timeout 120 "$bundle/$b" bench scenes/primary/spheres-1m.scene --view close --size 1920x1080 \
      --accel bvh,kd-stack,kd-backtrack --deltas none --maxdepths none --repeat 5 --threads "$(nproc)" \
      --device NVIDIA --quiet --out "/tmp/ab-$b-$r-1m" | grep -E "Embree|bvh |kd-"
  done
done
src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=NVIDIA
section "stress tests (failures in full)"
timeout 120 "$bundle/vkray_stress_tests" 2>&1 | grep -vE "^\| |^vulkan validation warning|^\[ +(RUN|OK) " | tail -60
section "GPU tests, validation on"
timeout 100 "$bundle/vkray_gpu_tests" --gtest_brief=1 2>&1 | grep -vE "^measured|^vulkan validation warning" | tail -15
section "full renders, new build"
for s in bunny cornell objects spheres; do
  "$bundle/vkray" render scenes/$s.scene --device NVIDIA --stats -o /tmp/r.png | grep -E "^(render time|gpu|timing):" | sed "s/^/$s /"
done
