#!/usr/bin/env bash
# The primary-ray protocol (docs/benchmarks.md, "Reinsertion after AAC") three times over: bvh, two
# reinsertion variants of it, bvh-sah and kd-stack, each against Embree in the same repeats. Run
# from the repository root after scripts/fetch-scenes.sh; ratios.py OUT summarises the runs.
mkdir -p "${OUT:-/tmp/reinsertion-primary}"
for run in 1 2 3; do
for s in bunny armadillo dragon; do
  build/vkray bench scenes/primary/$s.scene --view close --size 1024x768 --accel bvh,bvh:bvh-reinsert-iterations=1,bvh:bvh-reinsert-iterations=200,bvh-sah,kd-stack --deltas none --maxdepths none --repeat 5 --threads 2 --quiet --out ${OUT:-/tmp/reinsertion-primary}/run$run-$s > ${OUT:-/tmp/reinsertion-primary}/run$run-$s.log 2>&1
done
done
echo done > ${OUT:-/tmp/reinsertion-primary}/DONE
