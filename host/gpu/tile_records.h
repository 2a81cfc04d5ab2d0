// The image as tiles of at most VKRAY_TILE_SIZE^2 pixels (a dispatch each), and the pixel records
// the kernels write for them (render_main.glsl, "Pixel records"), read back into a Frame: the full
// GpuPixel where the host reads AOVs or counters and in the resumable variant, else the compact
// GpuPixelColor with one GpuTileCounts a tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "frame/frame.h"
#include "frame/render_options.h"
#include "gpu/gpu_render_report.h"
#include "gpu/pixel_output.h"
#include "gpu/shader_features.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

inline constexpr uint32_t kTilePixels = VKRAY_TILE_SIZE * VKRAY_TILE_SIZE;

struct Tile {
    uint32_t x, y, width, height;  // in image coordinates
};

// The window's pixels as tiles.
std::vector<Tile> splitIntoTiles(const PixelWindow& window);

// A tile as strips of at most `rows` rows (each dispatched as a tile of its own).
std::vector<Tile> splitIntoStrips(const Tile& tile, uint32_t rows);

// A batch of compact records: its tiles' GpuPixelColor records, then a GpuTileCounts a tile, from
// this byte of the pixel buffer on.
inline vk::DeviceSize tileCountsOffset(size_t tiles) { return tiles * kTilePixels * sizeof(GpuPixelColor); }
static_assert(kTilePixels * sizeof(GpuPixelColor) % sizeof(GpuTileCounts) == 0,
              "the counts start at a whole GpuTileCounts of the buffer");

// The bytes of a batch of `tiles` the host reads, as the kernel of `features` writes them.
vk::DeviceSize batchBytes(size_t tiles, const ShaderFeatures& features);

// Calls f(record, x, y) for each pixel of `tile` (x, y within it), its record at `src` (GpuPixel or
// GpuPixelColor, VKRAY_TILE_SIZE a row).
template <class Record, class F>
void forEachRecord(const Record* src, const Tile& tile, F&& f) {
    for (uint32_t y = 0; y < tile.height; ++y)
        for (uint32_t x = 0; x < tile.width; ++x) f(src[y * VKRAY_TILE_SIZE + x], x, y);
}

// Pixels of `tile` (its records at `src`) with `flag` set.
template <class Record>
uint32_t countFlagged(const Record* src, const Tile& tile, uint32_t flag) {
    uint32_t n = 0;
    forEachRecord(src, tile, [&](const Record& r, uint32_t, uint32_t) { n += (r.flags & flag) != 0; });
    return n;
}

// Reads the full records of `tile` into `frame` and `rep`: the fields the kernel of `features`
// writes.
void readTile(const GpuPixel* src, const Tile& tile, const ShaderFeatures& features, Frame& frame,
              GpuRenderReport& rep);

// Reads a batch's records, as the kernel of `features` wrote them, into `frame` and `rep`; a tile with
// pixels cut short goes to `unfinished` instead.
void readBatch(const PixelOutput& pixels, std::span<const Tile> batch, const ShaderFeatures& features, Frame& frame,
               GpuRenderReport& rep, std::vector<Tile>& unfinished);

}  // namespace vkray::gpu
