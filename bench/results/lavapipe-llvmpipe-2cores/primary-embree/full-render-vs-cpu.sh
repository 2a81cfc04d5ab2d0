#!/usr/bin/env bash
# usage: full-render-vs-cpu.sh BIN ROUNDS SCENES...: per scene the GPU render (default accelerator) and --cpu, interleaved;
# wall clock of the whole command and the report's render_ms; medians
BIN=$1; N=$2; shift 2
for scene in "$@"; do
  g=(); c=(); gr=(); cr=()
  for ((r=0; r<N; r++)); do
    for mode in gpu cpu; do
      extra=""; [[ $mode == cpu ]] && extra="--cpu"
      t0=$(date +%s.%N)
      rm_=$($BIN render $scene $extra -o /tmp/fc.png --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["render_ms"])')
      t1=$(date +%s.%N)
      w=$(python3 -c "print(($t1-$t0)*1000)")
      if [[ $mode == gpu ]]; then g+=($w); gr+=($rm_); else c+=($w); cr+=($rm_); fi
    done
  done
  python3 - "$scene" "${g[*]}" "${c[*]}" "${gr[*]}" "${cr[*]}" <<'PY'
import sys, statistics as st
s=sys.argv[1]; f=lambda x: st.median([float(v) for v in x.split()])
g,c,gr,cr=map(f,sys.argv[2:6])
print(f"| {s} | {g:.0f} | {c:.0f} | {g/c:.2f} | {gr:.0f} | {cr:.0f} | {gr/cr:.2f} |")
PY
done
