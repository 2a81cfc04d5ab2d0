#!/usr/bin/env bash
# usage: LP_NUM_THREADS=1 kernel-ab.sh ROUNDS SCENE [render args] -- SPEC...
#   SPEC = a vkray binary, or BINARY:KERNEL_DIR (VKRAY_KERNEL_DIR: kernels compiled into a folder, see
#   docs/architecture.md). The specs run interleaved, one render each per round; prints the median
#   and the minimum of gpu.gpu_ms (or of the JSON value METRIC names, e.g.
#   METRIC='d["gpu"]["pipeline_ms"]') and their ratios to the first spec. One lavapipe thread
#   (LP_NUM_THREADS=1) because this machine's second core is shared: the minimum of many rounds is
#   then the steadiest figure.
N=$1; SCENE=$2; shift 2
args=(); while [[ $# -gt 0 && $1 != -- ]]; do args+=("$1"); shift; done; shift
specs=("$@")
declare -A res
for ((r = 0; r < N; r++)); do
  for sp in "${specs[@]}"; do
    bin=${sp%%:*}; kd=""; [[ $sp == *:* ]] && kd=${sp#*:}
    t=$(VKRAY_KERNEL_DIR=$kd $bin render "$SCENE" -o /tmp/kernel-ab.png --json "${args[@]}" 2>/dev/null |
        python3 -c 'import json, os, sys; d = json.load(sys.stdin); print(eval(os.environ.get("METRIC", "d[\"gpu\"][\"gpu_ms\"]")))')
    res[$sp]="${res[$sp]} $t"
  done
done
for sp in "${specs[@]}"; do
  python3 - "$sp" "${res[$sp]}" "${res[${specs[0]}]}" <<'PY'
import sys, statistics as st
a = [float(x) for x in sys.argv[2].split()]; b = [float(x) for x in sys.argv[3].split()]
print(f"{sys.argv[1][-40:]:40s} median {st.median(a):7.1f}  min {min(a):7.1f}   ratio median {st.median(a) / st.median(b):.3f} min {min(a) / min(b):.3f}")
PY
done
