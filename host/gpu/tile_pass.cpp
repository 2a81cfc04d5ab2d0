#include "gpu/tile_pass.h"

#include <algorithm>

#include "gpu/batch_timer.h"
#include "gpu/buffer.h"

namespace vkray::gpu {
namespace {

// On a CPU device (lavapipe) few tiles a submission: a tile takes long, progress is reported per
// submission, and read-back overlaps nothing anyway; 4 tiles are 16 MiB of GpuPixel. On a GPU a
// tile (65,536 invocations) is far too small to fill the device, and each submission waits on its
// fence: as many tiles as 256 MiB of GpuPixel, so that a 1920x1080 image (40 tiles) is one
// submission.
constexpr uint32_t kMaxTilesPerSubmissionCpu = 4;
constexpr uint64_t kMaxBytesPerSubmission = uint64_t(256) << 20;

// Zeroes the GpuTileCounts of a batch of `tiles` before its dispatches add to them.
void zeroTileCounts(const vk::raii::CommandBuffer& cmd, const PixelOutput& pixels, size_t tiles) {
    cmd.fillBuffer(pixels.target().handle(), tileCountsOffset(tiles), tiles * sizeof(GpuTileCounts), 0u);
    const vk::MemoryBarrier filled{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eShaderRead | vk::AccessFlagBits::eShaderWrite};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, filled,
                        nullptr, nullptr);
}

}  // namespace

// The device kind's limit above, and what one storage buffer holds.
uint32_t tilesPerSubmission(const VulkanContext& ctx, size_t tiles) {
    const uint64_t tileBytes = uint64_t(kTilePixels) * sizeof(GpuPixel);
    const uint64_t limit = ctx.info().type == "cpu" ? kMaxTilesPerSubmissionCpu : kMaxBytesPerSubmission / tileBytes;
    return uint32_t(std::max<uint64_t>(
        std::min<uint64_t>({tiles, limit, ctx.info().maxStorageBufferRange / tileBytes}), 1));
}

void recordBatch(const vk::raii::CommandBuffer& cmd, const ComputeKernel& kernel, const ShaderFeatures& features,
                 std::span<const Tile> tiles, const GpuFrameParams& base) {
    const uint32_t blockRows = features.invocationPixels();
    for (size_t k = 0; k < tiles.size(); ++k) {
        const Tile& t = tiles[k];
        GpuFrameParams p = base;
        p.imageTile.z = t.x;
        p.imageTile.w = t.y;
        p.counts.z = uint32_t(k) * kTilePixels;
        p.tileCounts = uint32_t(tileCountsOffset(tiles.size()) / sizeof(GpuTileCounts) + k);
        kernel.dispatch(cmd, &p, (t.width + VKRAY_WORKGROUP_X - 1) / VKRAY_WORKGROUP_X,
                        (t.height + VKRAY_WORKGROUP_Y * blockRows - 1) / (VKRAY_WORKGROUP_Y * blockRows));
    }
}

void renderTiles(const VulkanContext& ctx, const ComputeKernel& kernel, const PixelOutput& pixels,
                 std::span<const Tile> tiles, uint32_t perSubmission, const GpuFrameParams& base, Frame& frame,
                 GpuRenderReport& rep, const TileProgress& progress, std::vector<Tile>& unfinished) {
    const BatchTimer timer(ctx);
    for (size_t first = 0; first < tiles.size(); first += perSubmission) {
        const std::span<const Tile> batch = tiles.subspan(first, std::min<size_t>(perSubmission, tiles.size() - first));
        OneShotCommands commands(ctx);
        const vk::raii::CommandBuffer& cmd = commands.begin();
        if (rep.features.compactPixels()) zeroTileCounts(cmd, pixels, batch.size());
        timer.begin(cmd);
        recordBatch(cmd, kernel, rep.features, batch, base);
        timer.end(cmd);  // the kernels' time, not the copy's (PixelOutput)
        pixels.recordToHost(cmd, batchBytes(batch.size(), rep.features));
        commands.submitAndWait();
        ++rep.submissions;
        rep.gpuMs += timer.batchMs();
        readBatch(pixels, batch, rep.features, frame, rep, unfinished);
        if (progress) progress(uint32_t(first + batch.size()), uint32_t(tiles.size()));
    }
}

}  // namespace vkray::gpu
