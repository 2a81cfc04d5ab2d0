#!/usr/bin/env bash
# usage: kernel-ab.sh SPV_DIR_A SPV_DIR_B ROUNDS SCENE [render args]: one vkray binary ($BIN, default
# build/vkray) times the kernels compiled into two folders (VKRAY_KERNEL_DIR), alternated ABBA;
# prints the medians of gpu.gpu_ms and B/A. Compile a folder of kernels as CMakeLists.txt does:
#   for k in shaders/render_*.comp; do glslangValidator --target-env vulkan1.1 -Os -Ishaders \
#     -o DIR/$(basename $k .comp).spv $k; done
A=$1; B=$2; N=$3; SCENE=$4; shift 4
BIN=${BIN:-build/vkray}
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
