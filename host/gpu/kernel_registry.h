// The SPIR-V of the render kernels (shaders/render_<accel::kernelName()>.comp, four variants each):
// built into vkray, or read from VKRAY_KERNEL_DIR to time a kernel edit without rebuilding.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "accel/accel.h"
#include "gpu/shader_features.h"

namespace vkray::gpu {

// The built-in SPIR-V of `kernel`'s `variant` (generated from shaders/render_*.comp at build time).
std::span<const uint32_t> builtInKernel(accel::Kernel kernel, KernelVariant variant);

// With VKRAY_KERNEL_DIR set, render_<kernel>[_resumable][_split].spv (the variant's suffixes, as
// CMakeLists.txt names them) from that folder (docs/architecture.md, "Shaders"), said on stderr;
// empty when it is unset. Throws vkray::Error for a missing file or one that is not SPIR-V.
std::vector<uint32_t> kernelFromDir(accel::Kernel kernel, KernelVariant variant);

}  // namespace vkray::gpu
