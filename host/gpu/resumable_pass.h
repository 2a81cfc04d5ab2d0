// The resumable variant's pass (render_main.glsl, "Resumable pixels"): the tiles the plain kernel
// could not finish within the driver's loop budget, rendered again strip by strip, each strip
// dispatched until none of its pixels is unfinished.
#pragma once

#include <span>

#include "accel/accel.h"
#include "frame/frame.h"
#include "gpu/compute_kernel.h"
#include "gpu/gpu_render_report.h"
#include "gpu/pixel_output.h"
#include "gpu/scene_buffers.h"
#include "gpu/shader_features.h"
#include "gpu/tile_records.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

// Brute force over more triangles than one budget covers for a camera ray and its shadow rays (four
// triangles per loop pass) would run out on every tile where the driver ends long loops
// (VulkanContext::loopBudget()): such a render is resumable from the start, without a plain pass whose
// every tile would be rendered again. So is every render of a context that asks for it
// (ContextOptions::resumableFromStart).
bool resumableFromStart(const VulkanContext& ctx, const Scene& scene, accel::Traversal traversal);

// Renders `tiles` again with `kernel`, the resumable variant of `features`, strip by strip, into
// `frame`; rebinds its buffers to the strips' saved state.
void renderResumable(const VulkanContext& ctx, ComputeKernel& kernel, const ShaderFeatures& features,
                     const SceneBuffers& scene, const AccelBuffers& accel, const PixelOutput& pixels,
                     std::span<const Tile> tiles, int maxDepth, const GpuFrameParams& base, Frame& frame,
                     GpuRenderReport& rep, const TileProgress& progress);

}  // namespace vkray::gpu
