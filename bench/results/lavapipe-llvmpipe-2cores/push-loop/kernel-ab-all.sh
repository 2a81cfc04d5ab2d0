#!/usr/bin/env bash
# usage: kernel-ab-all.sh ROUNDS VKRAY...: kernel time (gpu_ms) of the binaries, interleaved render by
# render with one lavapipe thread (node-steps/kernel-ab.sh; ratios to the first binary): every
# scenes/*.scene at 320x240 (the full Whitted render) and the camera rays of the three close-ups at 512x384.
rounds=$1; shift
ab=bench/results/lavapipe-llvmpipe-2cores/node-steps/kernel-ab.sh
for s in scenes/*.scene; do
  echo "== $s 320x240"
  LP_NUM_THREADS=1 bash $ab "$rounds" "$s" --size 320x240 -- "$@"
done
for m in bunny armadillo dragon; do
  echo "== scenes/primary/$m.scene --view close 512x384"
  LP_NUM_THREADS=1 bash $ab "$rounds" "scenes/primary/$m.scene" --view close --size 512x384 -- "$@"
done
