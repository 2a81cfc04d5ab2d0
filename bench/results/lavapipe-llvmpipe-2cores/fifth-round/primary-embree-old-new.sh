#!/usr/bin/env bash
# usage: primary-embree-old-new.sh OLD_VKRAY NEW_VKRAY OUTDIR [ROUNDS]
# The primary-rays-against-Embree protocol (docs/benchmarks.md, "Primary rays against Embree") with
# two vkray binaries alternating, ROUNDS rounds (default 2): each run measures Embree on the same
# rays itself, so every ratio comes from one run. Writes OUTDIR/{old,new}-ROUND/bench.md.
set -euo pipefail
old=$1 new=$2 out=$3 rounds=${4:-2}
mkdir -p "$out"
for ((round = 1; round <= rounds; round++)); do
  for which in new old; do
    bin=$new; [ "$which" = old ] && bin=$old
    "$bin" bench scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene --view close \
      --size 1024x768 --accel bvh,bvh-fast,kd-stack,kd-restart,kd-backtrack --deltas none --maxdepths none \
      --repeat 7 --threads 2 --quiet --out "$out/$which-$round" > "$out/$which-$round.log" 2>&1
    echo "$which $round done $(date +%T), load $(cut -d' ' -f1 /proc/loadavg)"
  done
done
