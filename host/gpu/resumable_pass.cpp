#include "gpu/resumable_pass.h"

#include <algorithm>
#include <cstdint>

#include "gpu/batch_timer.h"
#include "gpu/buffer.h"
#include "gpu/kernel_bindings.h"
#include "gpu/tile_pass.h"

namespace vkray::gpu {
namespace {

// Rows of a strip of the resumable variant: its records and pending-ray stacks must fit one storage
// buffer (VKRAY_TILE_SIZE pixels a row), in whole workgroup rows.
uint32_t resumeStripRows(const VulkanContext& ctx, int maxDepth) {
    const uint64_t perRow = uint64_t(VKRAY_TILE_SIZE) *
                            std::max<uint64_t>(sizeof(GpuPixelResume), uint64_t(maxDepth) * sizeof(GpuPendingRay));
    const uint64_t rows = ctx.info().maxStorageBufferRange / perRow / VKRAY_WORKGROUP_Y * VKRAY_WORKGROUP_Y;
    return uint32_t(std::clamp<uint64_t>(rows, VKRAY_WORKGROUP_Y, VKRAY_TILE_SIZE));
}

// Every record of `resume` VKRAY_RESUME_FRESH, before the strip's first dispatch.
void recordFreshStart(const vk::raii::CommandBuffer& cmd, const ResumeBuffers& resume) {
    cmd.fillBuffer(resume.records.handle(), 0, VK_WHOLE_SIZE, 0u);
    const vk::MemoryBarrier filled{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, filled,
                        nullptr, nullptr);
}

// Dispatches one strip with the resumable variant until none of its pixels is unfinished. Every
// dispatch either gets each unfinished pixel further or flags it cut short, so the loop ends.
void resumeStrip(const VulkanContext& ctx, const ComputeKernel& kernel, const ShaderFeatures& features,
                 const ResumeBuffers& resume, const PixelOutput& pixels, const Tile& strip, const GpuFrameParams& base,
                 GpuRenderReport& rep) {
    const BatchTimer timer(ctx);
    for (bool fresh = true;; fresh = false) {
        OneShotCommands commands(ctx);
        const vk::raii::CommandBuffer& cmd = commands.begin();
        if (fresh) recordFreshStart(cmd, resume);
        timer.begin(cmd);
        recordBatch(cmd, kernel, features, std::span<const Tile>(&strip, 1), base);
        timer.end(cmd);
        pixels.recordToHost(cmd, kTilePixels * sizeof(GpuPixel));
        commands.submitAndWait();
        ++rep.resumeDispatches;
        if (rep.gpuMs >= 0.0) rep.gpuMs += timer.batchMs();
        if (countFlagged(pixels.records<GpuPixel>(), strip, VKRAY_PIXEL_UNFINISHED) == 0) return;
    }
}

}  // namespace

bool resumableFromStart(const VulkanContext& ctx, const Scene& scene, accel::Traversal traversal) {
    const uint64_t passes = uint64_t(scene.triangles.size()) * (1 + scene.lights.size()) / 4;
    return ctx.resumableFromStart() ||
           (traversal == accel::Traversal::Brute && passes > VKRAY_RESUMABLE_LOOP_BUDGET && ctx.loopBudget());
}

void renderResumable(const VulkanContext& ctx, ComputeKernel& kernel, const ShaderFeatures& features,
                     const SceneBuffers& scene, const AccelBuffers& accel, const PixelOutput& pixels,
                     std::span<const Tile> tiles, int maxDepth, const GpuFrameParams& base, Frame& frame,
                     GpuRenderReport& rep, const TileProgress& progress) {
    const uint32_t rows = resumeStripRows(ctx, maxDepth);
    const ResumeBuffers resume(ctx, uint64_t(rows) * VKRAY_TILE_SIZE, uint64_t(maxDepth));
    bindBuffers(kernel, scene, accel, pixels, resume);
    rep.resumedTiles = uint32_t(tiles.size());
    rep.resumeRows = rows;
    for (size_t t = 0; t < tiles.size(); ++t) {
        for (const Tile& strip : splitIntoStrips(tiles[t], rows)) {
            resumeStrip(ctx, kernel, features, resume, pixels, strip, base, rep);  // the strip as a tile of its own
            readTile(pixels.records<GpuPixel>(), strip, features, frame, rep);
        }
        if (progress) progress(uint32_t(t + 1), uint32_t(tiles.size()));
    }
}

}  // namespace vkray::gpu
