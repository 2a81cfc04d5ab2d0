#!/usr/bin/env bash
# The primary-ray protocol of docs/benchmarks.md with the pushes-in-a-loop build, three runs one after the
# other (bvh, bvh-fast and the four kd walks, each against Embree in its own repeats); summarise
# with ratios.py OUT. Run from the repository root after scripts/fetch-scenes.sh.
out=${OUT:-/tmp/push-loop-primary}
mkdir -p "$out"
for run in 1 2 3; do
  build/vkray bench scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene --view close \
    --size 1024x768 --accel bvh,bvh-fast,kd-stack,kd-ropes,kd-restart,kd-backtrack --deltas none --maxdepths none \
    --repeat 5 --threads 2 --quiet --out "$out/run$run" > "$out/run$run.log" 2>&1
done
