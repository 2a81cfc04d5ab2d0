#!/usr/bin/env python3
# usage: ratios.py OUT: per close-up and accelerator, the camera-ray rate over Embree rtcIntersect1's
# (median and range of the runs OUT/run{1,2,3}/bench.json), each kd walk over bvh (median of the
# within-run ratios), node steps a camera ray and the SIMD efficiency over the device's subgroups.
import json, statistics, sys
out = sys.argv[1]
runs = [json.load(open(f'{out}/run{r}/bench.json'))['scenes'] for r in (1, 2, 3)]
for s, scene in enumerate(runs[0]):
    def ratio(run, name):
        return next(a for a in run[s]['accelerators'] if a['accel'] == name)['embree_interleaved']['primary_vs_intersect1']
    for a in scene['accelerators']:
        r = [ratio(run, a['accel']) for run in runs]
        over = statistics.median(ratio(run, a['accel']) / ratio(run, 'bvh') for run in runs)
        p = a['per_primary_ray']
        print('%-10s %-13s x Embree %.3f (%.3f-%.3f), over bvh %.2f, node steps %.2f, SIMD efficiency %.1f%% of %d lanes'
              % (scene['name'], a['accel'], statistics.median(r), min(r), max(r), over, p['nodes'],
                 100 * p['nodes'] / p['lockstep_nodes'], p['simd_lanes']))
