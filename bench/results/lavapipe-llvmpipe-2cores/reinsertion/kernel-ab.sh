#!/usr/bin/env bash
# usage: kernel-ab.sh VKRAY ROUNDS SCENE SIZE VARIANT...: the close-up's camera rays (scenes/primary/SCENE.scene,
# --view close) rendered with each VARIANT (a quoted argument string: accelerator and tuning), interleaved
# round by round; prints the median and least kernel time (gpu_ms) of each and the medians' ratio to the
# first. Set LP_NUM_THREADS=1 for steadier figures on a shared machine (docs/benchmarks.md, "Reinsertion
# after AAC").
vkray=$1; rounds=$2; scene=$3; size=$4; shift 4
for r in $(seq "$rounds"); do
  i=0
  for v in "$@"; do
    # shellcheck disable=SC2086
    "$vkray" render "scenes/primary/$scene.scene" --view close --size "$size" $v --json -o /tmp/kernel-ab.png 2>/dev/null |
      python3 -c "import json, sys; print($i, json.load(sys.stdin)['gpu']['gpu_ms'])"
    i=$((i + 1))
  done
done | python3 -c "
import statistics, sys
rows = {}
for line in sys.stdin:
    i, ms = line.split()
    rows.setdefault(int(i), []).append(float(ms))
names = sys.argv[1:]
base = statistics.median(rows[0])
for i in sorted(rows):
    m = statistics.median(rows[i])
    print('%-10s %-48s kernel median %7.1f ms, least %7.1f ms, ratio %.3f' % ('$scene', names[i], m, min(rows[i]), m / base))
" "$@"
