#!/usr/bin/env bash
# usage: tree.sh VKRAY SCENE VARIANT...: build time (2 threads), reinsertion time, SAH cost and the
# traversal counters a camera ray of the close-up (512x384) for each VARIANT (accelerator and tuning).
vkray=$1; scene=$2; shift 2
for v in "$@"; do
  # shellcheck disable=SC2086
  "$vkray" render "scenes/primary/$scene.scene" --view close --size 512x384 $v --threads 2 --counters --json -o /tmp/tree.png 2>/dev/null |
    python3 -c "
import json, sys
d = json.load(sys.stdin); a = d['accel']; t = d['gpu']['traversal']; n = 512 * 384
print('%-10s %-48s build %6.0f ms (reinsertion %6.0f ms), sah_cost %.2f, node steps %.2f, triangle tests %.2f'
      % ('$scene', '$v', a['build_ms'], a.get('reinsert_ms', 0), a['sah_cost'], t['nodes'] / n, t['triangles'] / n))"
done
