#!/usr/bin/env bash
# usage: cpubin.sh ROUNDS SCENE ACCEL BIN... : task-clock ms and pipeline_ms of a 64x48 render, interleaved
N=$1; S=$2; A=$3; shift 3
declare -A c p
for ((i=0;i<N;i++)); do for b in "$@"; do
  out=$(perf stat -x, -e task-clock -o /tmp/pk/ps.txt $b render $S --accel $A --size 64x48 -o /tmp/pk/x.png --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["gpu"]["pipeline_ms"])')
  c[$b]="${c[$b]} $(grep task-clock /tmp/pk/ps.txt | cut -d, -f1)"; p[$b]="${p[$b]} $out"
done; done
for b in "$@"; do python3 -c "import sys,statistics as s; c=[float(x) for x in sys.argv[2].split()]; p=[float(x) for x in sys.argv[3].split()]; print('%-22s task-clock median %.1f min %.1f | pipeline_ms median %.1f min %.1f'%(sys.argv[1],s.median(c),min(c),s.median(p),min(p)))" $b "${c[$b]}" "${p[$b]}"; done
