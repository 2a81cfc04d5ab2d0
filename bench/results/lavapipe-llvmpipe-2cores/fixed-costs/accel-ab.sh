#!/usr/bin/env bash
# usage: accel-ab.sh ROUNDS SCENE [render args] -- ACCEL...: kernel time (gpu_ms) medians per accelerator, interleaved (set LP_NUM_THREADS=1 for steady figures)
# Part of the fixed-costs measurements (docs/benchmarks.md, "What a small render pays before and after its kernels").
N=$1; S=$2; shift 2; args=(); while [[ $1 != -- ]]; do args+=("$1"); shift; done; shift
for r in $(seq $N); do for a in "$@"; do ${VKRAY:-build/vkray} render $S --accel $a "${args[@]}" --json -o /tmp/accab.png 2>/dev/null | python3 -c "
import sys,json; d=json.load(sys.stdin); print('$a', d['gpu']['gpu_ms'])"; done; done | python3 -c "
import sys,statistics as st
rows={}
for l in sys.stdin:
  a,v=l.split(); rows.setdefault(a,[]).append(float(v))
b=None
for a,v in rows.items():
  m=st.median(v); b=b or m; print(a, 'median %.1f min %.1f ratio %.3f'%(m,min(v),m/b))"
