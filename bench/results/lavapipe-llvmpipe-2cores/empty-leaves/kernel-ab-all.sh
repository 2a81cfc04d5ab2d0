#!/usr/bin/env bash
# usage: kernel-ab-all.sh OLD_VKRAY NEW_VKRAY: the kd-stack kernel of the two binaries, alternated
# (node-steps/kernel-ab.sh, one lavapipe thread): camera rays of the three close-ups at 512x384
# (15 rounds), then full renders of scenes with shadow and secondary rays (7 rounds).
# Run from the repository root after scripts/fetch-scenes.sh.
ab=bench/results/lavapipe-llvmpipe-2cores/node-steps/kernel-ab.sh
for s in bunny armadillo dragon; do
  echo "== $s close-up 512x384, camera rays"
  LP_NUM_THREADS=1 bash $ab 15 scenes/primary/$s.scene --view close --size 512x384 --accel kd-stack -- "$1" "$2"
done
for s in cornell objects spheres; do
  echo "== $s full render"
  LP_NUM_THREADS=1 bash $ab 7 scenes/$s.scene --accel kd-stack -- "$1" "$2"
done
