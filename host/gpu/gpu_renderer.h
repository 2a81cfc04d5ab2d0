// Renders a scene with a Vulkan compute kernel (shaders/render_<kernel>.comp, one per accelerator):
// uploads the scene and the built structure, specialises the kernel for what the scene needs,
// dispatches the image tile by tile (tile_pass.h), renders again with the resumable variant what
// the driver's loop budget cut short (resumable_pass.h), and reads back colour and AOVs.
#pragma once

#include "accel/accel.h"
#include "frame/frame.h"
#include "frame/render_options.h"
#include "gpu/gpu_render_report.h"
#include "gpu/kernel_cache.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace vkray::gpu {

// Renders with the arrays of an acceleration structure (accel::buildAccel(...)->gpuData(), or a
// structure file's), with the pipelines of `kernels` (a cache of its own when null).
Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::GpuAccelData& accel, GpuRenderReport* report = nullptr,
                  const TileProgress& progress = {}, KernelCache* kernels = nullptr);

}  // namespace vkray::gpu
