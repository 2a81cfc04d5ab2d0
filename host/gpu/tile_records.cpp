#include "gpu/tile_records.h"

#include <algorithm>
#include <cstddef>

#include "gpu/lockstep.h"

namespace vkray::gpu {
namespace {

// Index in `frame` of pixel (x, y) of `tile`.
size_t frameIndex(const Frame& frame, const Tile& tile, uint32_t x, uint32_t y) {
    return frame.index(int(tile.x + x) - frame.x0, int(tile.y + y) - frame.y0);
}

// Reads the compact records of `tile`, none of them cut short (those tiles go to the resumable
// variant), and its ray counts into `frame` and `rep`.
void readCompactTile(const GpuPixelColor* src, const GpuTileCounts& counts, const Tile& tile, Frame& frame,
                     GpuRenderReport& rep) {
    forEachRecord(src, tile,
                  [&](const GpuPixelColor& px, uint32_t x, uint32_t y) { frame.color[frameIndex(frame, tile, x, y)] = px.color; });
    const auto sum = [](uint32_t low, uint32_t high) { return uint64_t(high) << 32 | low; };
    rep.raysTraced += sum(counts.raysLow, counts.raysHigh);
    rep.shadowRays += sum(counts.shadowRaysLow, counts.shadowRaysHigh);
    rep.cappedRays += sum(counts.cappedLow, counts.cappedHigh);
}

}  // namespace

std::vector<Tile> splitIntoTiles(const PixelWindow& window) {
    std::vector<Tile> tiles;
    for (uint32_t y = uint32_t(window.y0); y < uint32_t(window.y1); y += VKRAY_TILE_SIZE)
        for (uint32_t x = uint32_t(window.x0); x < uint32_t(window.x1); x += VKRAY_TILE_SIZE)
            tiles.push_back({x, y, std::min<uint32_t>(VKRAY_TILE_SIZE, uint32_t(window.x1) - x),
                             std::min<uint32_t>(VKRAY_TILE_SIZE, uint32_t(window.y1) - y)});
    return tiles;
}

std::vector<Tile> splitIntoStrips(const Tile& tile, uint32_t rows) {
    std::vector<Tile> strips;
    for (uint32_t y = 0; y < tile.height; y += rows)
        strips.push_back({tile.x, tile.y + y, tile.width, std::min(rows, tile.height - y)});
    return strips;
}

vk::DeviceSize batchBytes(size_t tiles, const ShaderFeatures& features) {
    return features.compactPixels() ? tileCountsOffset(tiles) + tiles * sizeof(GpuTileCounts)
                                    : tiles * kTilePixels * sizeof(GpuPixel);
}

void readTile(const GpuPixel* src, const Tile& tile, const ShaderFeatures& features, Frame& frame,
              GpuRenderReport& rep) {
    // Only a frame that keeps the AOVs gets them (the resumable variant writes them for itself).
    const bool aovs = frame.hasAovs(), counters = features.writesCounters();
    forEachRecord(src, tile, [&](const GpuPixel& px, uint32_t x, uint32_t y) {
        const size_t i = frameIndex(frame, tile, x, y);
        frame.color[i] = px.color;
        if (aovs) {
            frame.depth[i] = px.depth;
            frame.normal[i] = px.normal;
            frame.primId[i] = px.primId;
        }
        rep.raysTraced += px.rays;
        rep.shadowRays += px.shadowRays;
        rep.cappedRays += px.capped;
        if (counters) {
            rep.nodesVisited += px.nodes;
            rep.leavesVisited += px.leaves;
            rep.trianglesTested += px.triangles;
            rep.cameraRays += px.rays > 0;
            if (rep.packetWalk) {  // the steps a lane sat out, and its packet's (the lock-step count)
                rep.idleSteps += px.walkEvents;
                rep.lockstepNodes += uint64_t(px.nodes) + px.walkEvents;
            } else {
                rep.restarts += px.walkEvents;
            }
            if (!rep.nodesPerPixel.empty()) rep.nodesPerPixel[i] += px.nodes;  // every sample's
        }
        rep.pixelsCutShort += (px.flags & VKRAY_PIXEL_CUT_SHORT) != 0;
    });
    if (counters && !rep.packetWalk)  // a packet's steps are counted per pixel above
        rep.lockstepNodes += lockstepNodes(tile.width, tile.height, rep.lockstepLanes,
                                           [&](uint32_t x, uint32_t y) { return src[y * VKRAY_TILE_SIZE + x].nodes; });
}

void readBatch(const PixelOutput& pixels, std::span<const Tile> batch, const ShaderFeatures& features, Frame& frame,
               GpuRenderReport& rep, std::vector<Tile>& unfinished) {
    const auto* full = pixels.records<GpuPixel>();
    const auto* colors = pixels.records<GpuPixelColor>();
    const auto* counts = reinterpret_cast<const GpuTileCounts*>(pixels.records<std::byte>() + tileCountsOffset(batch.size()));
    const bool compact = features.compactPixels();
    for (size_t k = 0; k < batch.size(); ++k) {
        const size_t at = k * kTilePixels;
        const uint32_t cut = compact ? countFlagged(colors + at, batch[k], VKRAY_PIXEL_CUT_SHORT)
                                     : countFlagged(full + at, batch[k], VKRAY_PIXEL_CUT_SHORT);
        if (cut > 0) unfinished.push_back(batch[k]);
        else if (compact) readCompactTile(colors + at, counts[k], batch[k], frame, rep);
        else readTile(full + at, batch[k], features, frame, rep);
    }
}

}  // namespace vkray::gpu
