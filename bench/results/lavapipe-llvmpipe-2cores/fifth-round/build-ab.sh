#!/usr/bin/env bash
# usage: [PRESETS="bvh-fast bvh-hq"] build-ab.sh OLD_VKRAY NEW_VKRAY ROUNDS SCENE...   (from the repository root)
# Build time of every CPU builder (or those PRESETS names), old binary against new, interleaved: per
# round, scene, preset and thread count (1, 2), one `vkray render --cpu --stats` with each binary
# (8x6 pixels: the render is negligible, and no Vulkan device competes for the cores), reading
# build_ms from the statistics. Prints median and minimum per case, the new binary's Mtri/s by the
# median, its 2-thread speed-up over 1 thread, and new / old.
set -euo pipefail
old=$1 new=$2 rounds=$3
shift 3
read -r -a presets <<< "${PRESETS:-bvh-fast bvh-hq bvh bvh-sah kd-stack}"
declare -A t
for ((r = 0; r < rounds; r++)); do
  for scene in "$@"; do
    for p in "${presets[@]}"; do
      for th in 1 2; do
        for which in old new; do
          bin=${!which}
          ms=$("$bin" render "$scene" --accel "$p" --threads "$th" --size 8x6 --cpu -o /tmp/build-ab.png --stats 2>&1 |
               awk '$1 == "build_ms" {print $2}')
          t[$scene,$p,$th,$which]="${t[$scene,$p,$th,$which]:-} $ms"
        done
      done
    done
  done
done
for scene in "$@"; do
  tris=$("$new" render "$scene" --size 8x6 -o /tmp/build-ab.png --stats 2>&1 | awk '$1 == "scene:" {print $2; exit}')
  echo "== $scene ($tris triangles; $rounds rounds, median / min ms)"
  for p in "${presets[@]}"; do
    python3 - "$p" "$tris" "${t[$scene,$p,1,old]}" "${t[$scene,$p,1,new]}" "${t[$scene,$p,2,old]}" "${t[$scene,$p,2,new]}" <<'PY'
import statistics as st, sys
p, tris = sys.argv[1], sys.argv[2]
o1, n1, o2, n2 = ([float(x) for x in a.split()] for a in sys.argv[3:7])
m = st.median
rate = f"{float(tris) / m(n2) / 1e3:.2f} Mtri/s" if tris.isdigit() else ""
print(f"{p:9s} 1 thread old {m(o1):7.1f} / {min(o1):7.1f}  new {m(n1):7.1f} / {min(n1):7.1f}  new/old {m(n1)/m(o1):.3f}   "
      f"2 threads old {m(o2):7.1f} / {min(o2):7.1f}  new {m(n2):7.1f} / {min(n2):7.1f}  new/old {m(n2)/m(o2):.3f}   "
      f"new 2 threads: {rate}, speed-up {m(n1)/m(n2):.2f}x (old {m(o1)/m(o2):.2f}x)")
PY
  done
done
