#!/usr/bin/env bash
# Work per ray of each accelerator (vkray's GPU counters): node steps, leaves, triangle tests and
# restarts, over all rays traced (camera, secondary and shadow), at 256x192.
# usage: counters.sh VKRAY SCENE [render args] -- ACCEL...   (from the repository root)
bin=$1 scene=$2; shift 2
args=(); while [[ $# -gt 0 && $1 != -- ]]; do args+=("$1"); shift; done; shift
for a in "$@"; do
  "$bin" render "$scene" --size 256x192 --counters --accel "$a" -o /tmp/counters.png --json "${args[@]}" 2>/dev/null |
    python3 -c '
import json, sys
g = json.load(sys.stdin)["gpu"]; t = g["traversal"]; n = g["rays"] + g["shadow_rays"]
nodes, leaves, tris, restarts = (t[k] / n for k in ("nodes", "leaves", "triangles", "restarts"))
print(f"{sys.argv[1]} {sys.argv[2]}: per ray {nodes:.2f} nodes, {leaves:.2f} leaves, {tris:.2f} triangle tests, {restarts:.3f} restarts")' "$scene" "$a"
done
