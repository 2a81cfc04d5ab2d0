#!/usr/bin/env bash
# Packs what the device scripts beside this one need on a GPU machine that has its vendor's Vulkan
# driver but none of vkray's Debian packages: the vkray binary, the GPU and stress test binaries,
# every shared library they load that is not glibc's, and the Khronos validation layer, as one
# BUNDLE.tar.xz (docs/performance.md, "Tools").
#
# usage: scripts/device/make-bundle.sh BUILD_DIR BUNDLE [OTHER_VKRAY...]     (on the build machine)
#   OTHER_VKRAY: further vkray binaries (other builds, for device-ab.sh), copied in under their
#   file names. On the GPU machine: tar -C /tmp -xJf BUNDLE.tar.xz, then run a device script with
#   /tmp/$(basename BUNDLE) from a checkout of the same revision (the scripts read scenes/, the
#   meshes in scenes/meshes/ too: fetch them here with scripts/fetch-scenes.sh and take them along).
set -eu
[ $# -ge 2 ] || { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0" >&2; exit 2; }
build=$1; bundle=$2; shift 2
rm -rf "$bundle"; mkdir -p "$bundle/lib" "$bundle/layers"
bins=("$build/vkray" "$build/tests/vkray_gpu_tests" "$build/tests/vkray_stress_tests")
cp "${bins[@]}" "$@" "$bundle/"
strip "$bundle"/vkray*
layer=/usr/lib/x86_64-linux-gnu/libVkLayer_khronos_validation.so
for f in "${bins[@]}" "$layer" /usr/lib/x86_64-linux-gnu/libvulkan.so.1; do
  ldd "$f" | awk '/=> \//{print $3}'
done | sort -u | grep -vE '/(libc|libm|libpthread|libdl|librt|ld-linux[^/]*)\.so' | while read -r lib; do
  cp -L "$lib" "$bundle/lib/"
done
cp -L /usr/lib/x86_64-linux-gnu/libvulkan.so.1 "$layer" "$bundle/lib/"
cp /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json "$bundle/layers/"
sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" > "$bundle/source-dir"
strip --strip-unneeded "$bundle"/lib/*.so*
# One compressed file: the libraries alone are larger than what may travel uncompressed.
tar -C "$(dirname "$bundle")" -cJf "$bundle.tar.xz" "$(basename "$bundle")"
du -sh "$bundle" "$bundle.tar.xz"
