#!/usr/bin/env bash
# usage: accel-ab.sh VKRAY ROUNDS SCENE ACCEL...   (from the repository root; ACCEL list must hold bvh)
# Kernel time (gpu.gpu_ms, Vulkan timestamps) of each accelerator on the scene's close-up, camera rays
# only (512x384, maxdepth 1), one lavapipe thread, the accelerators interleaved render by render for
# ROUNDS rounds; prints median and minimum and bvh's time over each one's (the "x of bvh" ratio).
set -euo pipefail
bin=$1 rounds=$2 scene=$3
shift 3
declare -A res
for ((r = 0; r < rounds; r++)); do
  for a in "$@"; do
    t=$(LP_NUM_THREADS=1 "$bin" render "$scene" --view close --size 512x384 --maxdepth 1 --accel "$a" \
          -o /tmp/accel-ab.png --json 2>/dev/null | python3 -c 'import json, sys; print(json.load(sys.stdin)["gpu"]["gpu_ms"])')
    res[$a]="${res[$a]:-} $t"
  done
done
for a in "$@"; do
  python3 - "$a" "${res[$a]}" "${res[bvh]}" <<'PY'
import sys, statistics as st
a = [float(x) for x in sys.argv[2].split()]; b = [float(x) for x in sys.argv[3].split()]
print(f"{sys.argv[1]:14s} median {st.median(a):7.1f} min {min(a):7.1f}   bvh/this median {st.median(b) / st.median(a):.3f} min {min(b) / min(a):.3f}")
PY
done
