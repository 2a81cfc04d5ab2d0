#!/usr/bin/env bash
# usage: kernel-ab-all.sh OLD_VKRAY NEW_VKRAY ROUNDS: kernel time (gpu_ms) of the two binaries, interleaved
# render by render with one lavapipe thread (node-steps/kernel-ab.sh): every scenes/*.scene at 320x240
# (the full Whitted render) and the camera rays of the three close-ups at 512x384.
old=$1 new=$2 rounds=${3:-5}
ab=bench/results/lavapipe-llvmpipe-2cores/node-steps/kernel-ab.sh
for s in scenes/*.scene; do
  echo "== $s 320x240"
  LP_NUM_THREADS=1 bash $ab "$rounds" "$s" --size 320x240 -- "$old" "$new"
done
for m in bunny armadillo dragon; do
  echo "== scenes/primary/$m.scene --view close 512x384"
  LP_NUM_THREADS=1 bash $ab "$rounds" "scenes/primary/$m.scene" --view close --size 512x384 -- "$old" "$new"
done
