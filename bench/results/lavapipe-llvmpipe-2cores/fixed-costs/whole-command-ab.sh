#!/usr/bin/env bash
# usage: whole-command-ab.sh ROUNDS SCENE BIN_A BIN_B [render args]: the whole `vkray render` command (wall clock), total_ms and render_ms, medians of interleaved runs
# Part of the fixed-costs measurements (docs/benchmarks.md, "What a small render pays before and after its kernels").
R=$1; S=$2; A=$3; B=$4; shift 4
for r in $(seq $R); do for bin in $A $B; do
  s=$(date +%s%N); $bin render $S -o /tmp/binab.png --json "$@" > /tmp/binab.json 2>/dev/null; e=$(date +%s%N)
  python3 -c "
import json; d=json.load(open('/tmp/binab.json')); print('$bin', ($e-$s)/1e6, d['total_ms'], d['render_ms'])"; done; done | python3 -c "
import sys,statistics as st
rows={}
for l in sys.stdin:
  a,*v=l.split(); rows.setdefault(a,[]).append([float(x) for x in v])
for a,v in rows.items(): print('%-24s'%a[-24:], 'wall %.1f total %.1f render %.1f'%tuple(st.median(x[i] for x in v) for i in range(3)), 'n',len(v))"
