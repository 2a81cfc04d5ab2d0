#!/usr/bin/env bash
# usage: full-render-vs-cpu.sh OLD_BIN NEW_BIN ROUNDS SCENES...
# Per scene, interleaved in every round: the GPU render (default accelerator) with OLD_BIN and with
# NEW_BIN, and NEW_BIN --cpu; the whole command's wall clock and the report's render_ms; medians.
OLD=$1; NEW=$2; N=$3; shift 3
echo "| scene | old GPU wall ms | new GPU wall ms | CPU wall ms | new GPU / CPU wall | old GPU render_ms | new GPU render_ms | CPU render_ms | new GPU / CPU render_ms |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for scene in "$@"; do
  declare -A w=() m=()
  for ((r=0; r<N; r++)); do
    for mode in old new cpu; do
      bin=$NEW; extra=""
      [[ $mode == old ]] && bin=$OLD
      [[ $mode == cpu ]] && extra="--cpu"
      t0=$(date +%s.%N)
      rm_=$($bin render "$scene" $extra -o /tmp/fc-$mode.png --json 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["render_ms"])')
      t1=$(date +%s.%N)
      w[$mode]="${w[$mode]} $(python3 -c "print(($t1-$t0)*1000)")"
      m[$mode]="${m[$mode]} $rm_"
    done
  done
  python3 - "$scene" "${w[old]}" "${w[new]}" "${w[cpu]}" "${m[old]}" "${m[new]}" "${m[cpu]}" <<'PY'
import sys, statistics as st
s = sys.argv[1]; f = lambda x: st.median([float(v) for v in x.split()])
wo, wn, wc, mo, mn, mc = map(f, sys.argv[2:8])
print(f"| {s} | {wo:.0f} | {wn:.0f} | {wc:.0f} | {wn/wc:.2f} | {mo:.0f} | {mn:.0f} | {mc:.0f} | {mn/mc:.2f} |")
PY
done
