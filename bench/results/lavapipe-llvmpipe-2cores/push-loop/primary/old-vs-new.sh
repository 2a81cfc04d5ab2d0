#!/usr/bin/env bash
# usage: old-vs-new.sh OLD_VKRAY NEW_VKRAY ROUNDS OUT: the primary-ray protocol for bvh and kd-stack with
# the two binaries alternated run by run (each run: the three close-ups, Embree in its own repeats);
# prints each run's bvh and kd-stack rates over Embree rtcIntersect1 and kd-stack over bvh.
old=$1 new=$2 rounds=$3 out=$4
for r in $(seq "$rounds"); do
  for v in old new; do
    bin=${!v}
    "$bin" bench scenes/primary/bunny.scene scenes/primary/armadillo.scene scenes/primary/dragon.scene --view close \
      --size 1024x768 --accel bvh,kd-stack --deltas none --maxdepths none --repeat 5 --threads 2 --quiet \
      --out "$out/$v$r" > "$out/$v$r.log" 2>&1
    python3 - "$out/$v$r/bench.json" "$v" "$r" <<'PY'
import json, sys
for s in json.load(open(sys.argv[1]))['scenes']:
    a = {x['accel']: x for x in s['accelerators']}
    b, k = (a[n]['embree_interleaved']['primary_vs_intersect1'] for n in ('bvh', 'kd-stack'))
    print('%s round %s %-10s bvh %.3f  kd-stack %.3f  kd-stack/bvh %.2f' % (sys.argv[2], sys.argv[3], s['name'], b, k, k / b))
PY
  done
done
