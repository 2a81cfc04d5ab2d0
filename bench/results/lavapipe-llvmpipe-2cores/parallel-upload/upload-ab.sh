#!/usr/bin/env bash
# usage: upload-ab.sh ROUNDS SCENE BIN...   (from the repository root)
# The GPU path's whole render of a large scene at 160x120 with bvh-fast, the binaries alternated:
# load, build, upload (upload_ms: packing the scene and copying every array into its buffers),
# render_ms and the whole total_ms, and "other" = total - load - build - render (the structure's
# arrays in GPU layout, gpuData()).
n=$1 scene=$2; shift 2
for ((r = 1; r <= n; r++)); do
  for b in "$@"; do
    "$b" render "$scene" --accel bvh-fast --size 160x120 --json -o /tmp/upload-ab.png 2>/dev/null |
      python3 -c '
import json, sys
d = json.load(sys.stdin); g = d["gpu"]; a = d["accel"]["build_ms"]
load, up, render, total = d["load_ms"], g["upload_ms"], d["render_ms"], d["total_ms"]
print(f"round {sys.argv[1]} {sys.argv[2]}: load {load:.0f} build {a:.0f} upload {up:.0f} render {render:.0f} "
      f"total {total:.0f} other {total - load - a - render:.0f} ms")' "$r" "$b"
  done
done
