#!/bin/bash
cd /work/main
for round in 1 2; do
  for bin in new old; do
    B=build/vkray; [ $bin = old ] && B=/tmp/before/build/vkray
    $B bench scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene --view close --size 1024x768 --accel bvh,bvh-fast,kd-stack,kd-restart,kd-backtrack --deltas none --maxdepths none --repeat 7 --threads 2 --quiet --out /tmp/final/$bin-$round > /tmp/final/$bin-$round.log 2>&1
    echo "$bin $round done $(date +%T) load $(cut -d' ' -f1 /proc/loadavg)"
  done
done
