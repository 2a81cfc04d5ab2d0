#!/usr/bin/env bash
# Kernel time of two vkray binaries, interleaved: every round renders each case with OLD, then NEW
# (ABAB...), and reads gpu.gpu_ms (timestamp queries around the dispatches) from the JSON report.
# Round 0 is a warm-up (a freshly built binary's first render of a kernel was measured up to 1.4x
# slower), left out of the medians. Prints one raw line per render, then per case the medians and
# NEW/OLD.
# usage: bench.sh OLD_VKRAY NEW_VKRAY [ROUNDS=5]   (run from the repository root)
set -euo pipefail
old=$1 new=$2 rounds=${3:-5}
cases=(
  "scenes/bunny.scene bvh 320x240"
  "scenes/bunny.scene kd-stack 320x240"
  "scenes/bunny.scene kd-restart 320x240"
  "scenes/bunny.scene kd-backtrack 320x240"
  "scenes/cornell.scene brute 320x240"
  "scenes/default.scene brute 320x240"
)
raw=$(mktemp)
trap 'rm -f "$raw"' EXIT
echo "# round scene accel size binary gpu_ms"
for ((r = 0; r <= rounds; ++r)); do
  for c in "${cases[@]}"; do
    read -r scene accel size <<<"$c"
    for v in old new; do
      bin=${!v}
      ms=$("$bin" render "$scene" --accel "$accel" --size "$size" -o /tmp/vkray-bench-$$.pfm --json |
           python3 -c 'import json,sys; print(json.load(sys.stdin)["gpu"]["gpu_ms"])')
      echo "$r $scene $accel $size $v $ms"
      [ "$r" -eq 0 ] || echo "$r $scene $accel $size $v $ms" >>"$raw"
    done
  done
done
rm -f /tmp/vkray-bench-$$.pfm
echo
python3 - "$raw" <<'PY'
import statistics, sys
runs = {}
for line in open(sys.argv[1]):
    r, scene, accel, size, v, ms = line.split()
    runs.setdefault((scene, accel, size), {}).setdefault(v, []).append(float(ms))
print("| scene | accel | size | rounds | old median ms | new median ms | new/old |")
print("|---|---|---|---|---|---|---|")
for (scene, accel, size), t in runs.items():
    o, n = statistics.median(t["old"]), statistics.median(t["new"])
    print(f"| {scene} | {accel} | {size} | {len(t['old'])} | {o:.1f} | {n:.1f} | {n / o:.3f} |")
PY
