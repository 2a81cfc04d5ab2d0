#!/usr/bin/env bash
# A/B of vkray builds or kernel sets on a GPU machine (docs/performance.md, "Interleaved A/B runs"):
# each round runs every SPEC once, in the order given (ABC ABC ...), as `vkray bench` camera rays on
# the 1M sphere grid's close-up at 1920x1080 and the dragon's at 3840x2160 (frames of a few ms, long
# enough to be steady on a data-centre GPU; shorter ones are not), Embree on all cores in the same
# repeats. Then the stress tests (failures in full) and the GPU tests, validation on, of the bundle's
# own vkray build. Summarise with summarise-ab.py OUTDIR.
#
# usage: scripts/device/device-ab.sh BUNDLE OUTDIR ROUNDS SPEC...   (on the GPU machine, repository root)
#   SPEC: the file name of a vkray binary in BUNDLE (make-bundle.sh copies other builds in), or
#   BINARY:KERNEL_DIR, that binary reading its kernels from KERNEL_DIR (VKRAY_KERNEL_DIR: one
#   render_<kernel>[_resumable][_split].spv each, compiled as CMakeLists.txt compiles them).
#   The first SPEC is the baseline of the summary's ratios.
#   ACCELS (default bvh,kd-stack,kd-ropes,kd-backtrack), REPEAT (default 5), DEVICE (default NVIDIA),
#   CASES (default "spheres-1m:1920x1080 dragon:3840x2160": scenes/primary/ scenes and sizes),
#   TESTS=no skips the tests (a dry run on lavapipe: DEVICE=llvmpipe CASES="dragon:256x192").
set -u
[ $# -ge 4 ] || { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0" >&2; exit 2; }
bundle=$(cd "$1" && pwd); out=$2; rounds=$3; shift 3
mkdir -p "$out"
[ -d "$bundle/lib" ] && export LD_LIBRARY_PATH=$bundle/lib VK_LAYER_PATH=$bundle/layers
accels=${ACCELS:-bvh,kd-stack,kd-ropes,kd-backtrack}
repeat=${REPEAT:-5}
device=${DEVICE:-NVIDIA}
read -r -a cases <<< "${CASES:-spheres-1m:1920x1080 dragon:3840x2160}"
section() { echo; echo "=== $* ($(date -u +%H:%M:%S))"; }
label() { if [[ $1 == *:* ]]; then echo "${1%%:*}@$(basename "${1#*:}")"; else echo "$1"; fi; }

printf '%s\n' "$@" | while read -r spec; do label "$spec"; done > "$out/labels.txt"
for r in $(seq "$rounds"); do
  for spec in "$@"; do
    bin=${spec%%:*}; kernels=""
    [[ $spec == *:* ]] && kernels=$(cd "${spec#*:}" && pwd)
    section "round $r: $spec"
    for s in "${cases[@]}"; do
      scene=${s%%:*}
      VKRAY_KERNEL_DIR=$kernels timeout 120 "$bundle/$bin" bench "scenes/primary/$scene.scene" --view close \
        --size "${s#*:}" --accel "$accels" --deltas none --maxdepths none --repeat "$repeat" \
        --threads "$(nproc)" --device "$device" --quiet --out "$out/round-$r/$(label "$spec")/$scene" 2>&1 \
        | grep -v "^vkray: kernel"
      rc=${PIPESTATUS[0]}
      [ "$rc" = 0 ] || echo "round $r $spec $scene: exit $rc"
    done
  done
done

if [ "${TESTS:-yes}" != no ]; then
src=$(cat "$bundle/source-dir")
[ -e "$src" ] || { mkdir -p "$(dirname "$src")"; ln -s "$PWD" "$src"; }
export VKRAY_TEST_DEVICE=$device
section "stress tests (failures in full)"
timeout 150 "$bundle/vkray_stress_tests" 2>&1 | grep -vE "^\| |^vulkan validation warning|^\[ +(RUN|OK) |rays per pixel" | tail -60
section "GPU tests, validation on"
timeout 120 "$bundle/vkray_gpu_tests" --gtest_brief=1 2>&1 | grep -vE "^measured|^vulkan validation warning" | tail -15
fi
section "summary"
python3 "$(dirname "${BASH_SOURCE[0]}")/summarise-ab.py" "$out"
