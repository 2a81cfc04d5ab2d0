#!/usr/bin/env python3
# usage: ratios.py DIR: each accelerator's camera-ray rate over Embree rtcIntersect1's in the same
# repeats (bench.json: embree_interleaved.primary_vs_intersect1) for the runs DIR/run{1,2,3}-SCENE/
# that run.sh writes, with the median of the runs, and each variant over bvh within each run.
import json, statistics, sys
d = sys.argv[1]
for scene in ('bunny', 'armadillo', 'dragon'):
    runs = [json.load(open(f'{d}/run{r}-{scene}/bench.json'))['scenes'][0]['accelerators'] for r in (1, 2, 3)]
    base = [next(a for a in run if a['accel'] == 'bvh')['embree_interleaved']['primary_vs_intersect1'] for run in runs]
    for name in [a['accel'] for a in runs[0]]:
        r = [next(a for a in run if a['accel'] == name)['embree_interleaved']['primary_vs_intersect1'] for run in runs]
        over = [x / b for x, b in zip(r, base)]
        print('%-10s %-34s x Embree median %.3f (runs %s); over bvh in the same run, median %.3f (%s)'
              % (scene, name, statistics.median(r), ' '.join('%.3f' % x for x in r), statistics.median(over),
                 ' '.join('%.3f' % x for x in over)))
