#!/usr/bin/env bash
# usage: kernel-ab.sh SPV_DIR_A SPV_DIR_B ROUNDS SCENE [render args]: one vkray binary ($BIN, default
# build/vkray) times the kernels compiled into two folders (VKRAY_KERNEL_DIR), interleaved; prints
# median and minimum of gpu.gpu_ms and B/A. Compile a folder of kernels as CMakeLists.txt does:
#   for k in shaders/render_*.comp; do glslangValidator --target-env vulkan1.1 -Os -Ishaders \
#     -o DIR/$(basename $k .comp).spv $k; done
# The general form (several binaries or folders, another metric) is ../node-steps/kernel-ab.sh.
A=$1; B=$2; N=$3; SCENE=$4; shift 4
BIN=${BIN:-build/vkray}
exec "$(dirname "$0")/../node-steps/kernel-ab.sh" "$N" "$SCENE" "$@" -- "$BIN:$A" "$BIN:$B"
