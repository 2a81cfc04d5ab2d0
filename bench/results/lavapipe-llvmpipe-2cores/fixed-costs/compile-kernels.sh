#!/usr/bin/env bash
# usage: compile-kernels.sh SHADER_DIR OUT: every render kernel of SHADER_DIR in its four variants, as VKRAY_KERNEL_DIR reads them
# Part of the fixed-costs measurements (docs/benchmarks.md, "What a small render pays before and after its kernels").
set -e
src=$1; out=$2; mkdir -p $out
for f in $src/render_*.comp; do n=$(basename $f .comp)
  glslangValidator --target-env vulkan1.1 -Os --quiet -I$src -o $out/$n.spv $f &
  glslangValidator --target-env vulkan1.1 -Os --quiet -DVKRAY_RESUMABLE_KERNEL -I$src -o $out/${n}_resumable.spv $f &
  glslangValidator --target-env vulkan1.1 -Os --quiet -DVKRAY_SPLIT_TEXEL_VIEWS -I$src -o $out/${n}_split.spv $f &
  glslangValidator --target-env vulkan1.1 -Os --quiet -DVKRAY_RESUMABLE_KERNEL -DVKRAY_SPLIT_TEXEL_VIEWS -I$src -o $out/${n}_resumable_split.spv $f &
  wait
done
