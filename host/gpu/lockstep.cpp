#include "gpu/lockstep.h"

#include <algorithm>
#include <bit>

#include "shared/gpu_layout.h"

namespace vkray::gpu {

static_assert(VKRAY_WORKGROUP_X == 8 && VKRAY_WORKGROUP_Y == 8, "lockstepBlock follows pixelInTile's 8x8 workgroups");

LockstepBlock lockstepBlock(uint32_t lanes) {
    lanes = std::bit_floor(std::clamp(lanes, 1u, 64u));  // Vulkan subgroups are powers of two
    // Within a run of 8 invocations lane & 3 is the column and lane >> 2 the row (4x2); runs pair
    // up side by side (8 wide), then stack in rows of 2.
    if (lanes <= 4) return {lanes, 1};
    if (lanes == 8) return {4, 2};
    return {8, 2 * (lanes / 16)};
}

uint64_t lockstepNodes(uint32_t width, uint32_t height, uint32_t lanes,
                       const std::function<uint32_t(uint32_t x, uint32_t y)>& nodesAt) {
    const LockstepBlock b = lockstepBlock(lanes);
    uint64_t total = 0;
    for (uint32_t by = 0; by < height; by += b.height)
        for (uint32_t bx = 0; bx < width; bx += b.width) {
            uint32_t most = 0, pixels = 0;
            for (uint32_t y = by; y < std::min(height, by + b.height); ++y)
                for (uint32_t x = bx; x < std::min(width, bx + b.width); ++x) {
                    most = std::max(most, nodesAt(x, y));
                    ++pixels;
                }
            total += uint64_t(most) * pixels;
        }
    return total;
}

}  // namespace vkray::gpu
