#!/usr/bin/env bash
# usage: aac-variants.sh VKRAY: the bunny close-up's camera rays (512x384) through AAC trees built
# with other parameters than bvh's (delta 20, epsilon 0.1, 2 treelet passes from 8 primitives up),
# against the binned-SAH tree: SAH cost and traversal counters a ray (docs/benchmarks.md, "What a
# small render pays before and after its kernels").
vkray=${1:-build/vkray}
for o in "" ":bvh-treelet-passes=0" ":bvh-treelet-passes=4" ":bvh-treelet-passes=8" ":bvh-treelet-min=2" \
         ":aac-delta=40" ":aac-delta=80" ":aac-delta=200" ":aac-delta=1000" ":aac-epsilon=0" \
         ":aac-delta=80:aac-epsilon=0.2"; do
  $vkray render scenes/primary/bunny.scene --view close --size 512x384 --accel "bvh$o" --counters --json -o /tmp/aac-variants.png 2>/dev/null |
    python3 -c "import json, sys; d = json.load(sys.stdin); t = d['gpu']['traversal']; n = 512 * 384
print('bvh %-34s build %4.0f ms, sah_cost %.2f, node steps %.2f, triangle tests %.2f' % ('$o', d['accel']['build_ms'], d['accel']['sah_cost'], t['nodes'] / n, t['triangles'] / n))"
done
$vkray render scenes/primary/bunny.scene --view close --size 512x384 --accel bvh-sah --counters --json -o /tmp/aac-variants.png 2>/dev/null |
  python3 -c "import json, sys; d = json.load(sys.stdin); t = d['gpu']['traversal']; n = 512 * 384
print('bvh-sah %-30s build %4.0f ms, sah_cost %.2f, node steps %.2f, triangle tests %.2f' % ('', d['accel']['build_ms'], d['accel']['sah_cost'], t['nodes'] / n, t['triangles'] / n))"
