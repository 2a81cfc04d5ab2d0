// One pass of the plain kernel over the tiles of a window: the tiles in batches, a submission each,
// each batch's records read back into the Frame.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "frame/frame.h"
#include "gpu/compute_kernel.h"
#include "gpu/gpu_render_report.h"
#include "gpu/pixel_output.h"
#include "gpu/shader_features.h"
#include "gpu/tile_records.h"
#include "gpu/vulkan_context.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

// Tiles per submission on ctx's device, for a window of `tiles` tiles.
uint32_t tilesPerSubmission(const VulkanContext& ctx, size_t tiles);

// Records the dispatches of `tiles` into `cmd`, each writing its own slice of the pixel buffer. An
// invocation of the kernel specialised with `features` renders features.invocationPixels() pixels,
// one in each of as many bands of the tile's 8x8 block rows: that many times fewer workgroup rows.
void recordBatch(const vk::raii::CommandBuffer& cmd, const ComputeKernel& kernel, const ShaderFeatures& features,
                 std::span<const Tile> tiles, const GpuFrameParams& base);

// Dispatches the tiles, `perSubmission` at a time into `pixels`, and reads each batch into `frame`,
// with the kernel of rep.features. A tile with pixels the driver's loop budget cut short is left for
// the resumable variant (resumable_pass.h) and added to `unfinished`.
void renderTiles(const VulkanContext& ctx, const ComputeKernel& kernel, const PixelOutput& pixels,
                 std::span<const Tile> tiles, uint32_t perSubmission, const GpuFrameParams& base, Frame& frame,
                 GpuRenderReport& rep, const TileProgress& progress, std::vector<Tile>& unfinished);

}  // namespace vkray::gpu
