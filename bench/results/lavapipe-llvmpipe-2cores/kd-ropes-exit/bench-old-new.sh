#!/usr/bin/env bash
# kd-ropes with the near-face test at each rope (old kernel, from a folder through VKRAY_KERNEL_DIR)
# against the kernel built in (new), both with kd-stack, `vkray bench` on the three close-ups,
# 1024x768, both threads, Embree in the same run; old and new alternated ROUNDS times.
# usage: bench-old-new.sh VKRAY OLD_KERNEL_DIR ROUNDS OUTDIR   (from the repository root)
set -euo pipefail
bin=$1 old=$2 rounds=$3 out=$4
mkdir -p "$out"
for ((r = 1; r <= rounds; r++)); do
  for which in old new; do
    kd=""; [[ $which == old ]] && kd=$old
    VKRAY_KERNEL_DIR=$kd "$bin" bench scenes/primary/{bunny,armadillo,dragon}.scene --view close --size 1024x768 \
      --accel kd-stack,kd-ropes --deltas none --maxdepths none --repeat 7 --threads 2 \
      --out "/tmp/ropes-bench/$which-$r" > "$out/$which-$r.txt" 2>&1
    cp "/tmp/ropes-bench/$which-$r/bench.md" "$out/$which-$r.md"
  done
done
