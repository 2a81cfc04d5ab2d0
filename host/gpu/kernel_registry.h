// The render kernels, one per accel::Traversal: their names (shaders/render_<kernelName()>.comp) and
// SPIR-V (four variants each), built into vkray or read from VKRAY_KERNEL_DIR to time a kernel edit
// without rebuilding.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "accel/accel.h"
#include "gpu/shader_features.h"

namespace vkray::gpu {

// The kernel that runs `traversal`: the traversal's name with '_' for '-' ("kd_restart"), the stem of
// its shaders/render_<name>.comp. The build fails when a traversal has no such file.
std::string_view kernelName(accel::Traversal traversal);

// The built-in SPIR-V of `traversal`'s kernel, `variant` (generated from shaders/render_*.comp at
// build time).
std::span<const uint32_t> builtInKernel(accel::Traversal traversal, KernelVariant variant);

// With VKRAY_KERNEL_DIR set, render_<kernel>[_resumable][_split].spv (the variant's suffixes, as
// CMakeLists.txt names them) from that folder (docs/architecture.md, "Shaders"), said on stderr;
// empty when it is unset. Throws vkray::Error for a missing file or one that is not SPIR-V.
std::vector<uint32_t> kernelFromDir(accel::Traversal traversal, KernelVariant variant);

}  // namespace vkray::gpu
