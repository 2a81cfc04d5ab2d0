#!/usr/bin/env bash
# usage: kab.sh SPV_DIR_A SPV_DIR_B ROUNDS SCENE [render args]; same binary, kernels from the dirs; ABBA order
A=$1; B=$2; N=$3; SCENE=$4; shift 4
BIN=${BIN:-/tmp/vkray-B1}
a=(); b=()
run() { local d=$1; shift; VKRAY_KERNEL_DIR=$d $BIN render $SCENE -o /tmp/kab.png --json "$@" 2>/dev/null | python3 -c 'import json,sys; print(json.load(sys.stdin)["gpu"]["gpu_ms"])'; }
for ((r=0; r<N; r++)); do
  if (( r % 2 )); then b+=($(run $B "$@")); a+=($(run $A "$@")); else a+=($(run $A "$@")); b+=($(run $B "$@")); fi
done
python3 - "${a[*]}" "${b[*]}" "$(basename $SCENE) $*" "$A" "$B" <<'PY'
import sys, statistics as st
a=[float(x) for x in sys.argv[1].split()]; b=[float(x) for x in sys.argv[2].split()]
ma, mb = st.median(a), st.median(b)
print(f"{sys.argv[3]}: {sys.argv[4]} {ma:.1f} ms  {sys.argv[5]} {mb:.1f} ms  B/A {mb/ma:.3f}")
PY
