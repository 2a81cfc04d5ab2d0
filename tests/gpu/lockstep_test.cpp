// Lock-step node steps (gpu/lockstep.h): the blocks a subgroup covers follow pixelInTile()'s layout,
// and the count is, per block, the slowest pixel's steps times the block's pixels in the tile.
#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

#include <gtest/gtest.h>

#include "gpu/lockstep.h"

namespace vkray::gpu {
namespace {

TEST(Lockstep, BlocksFollowThePixelLayoutOfTheKernel) {
    // pixelInTile(): invocation i = 8 * run + lane of a workgroup sits at column (run & 1) * 4 +
    // (lane & 3), row (run >> 1) * 2 + (lane >> 2). A subgroup of L lanes is the invocations
    // [k L, (k + 1) L): the block is the extent of subgroup 0's pixels.
    for (uint32_t lanes : {1u, 2u, 4u, 8u, 16u, 32u, 64u}) {
        uint32_t w = 0, h = 0;
        for (uint32_t i = 0; i < lanes; ++i) {
            const uint32_t run = i / 8, lane = i % 8;
            w = std::max(w, (run & 1) * 4 + (lane & 3) + 1);
            h = std::max(h, (run >> 1) * 2 + (lane >> 2) + 1);
        }
        const LockstepBlock b = lockstepBlock(lanes);
        EXPECT_EQ(b.width, w) << lanes << " lanes";
        EXPECT_EQ(b.height, h) << lanes << " lanes";
        EXPECT_EQ(b.width * b.height, lanes);
    }
    EXPECT_EQ(lockstepBlock(128).width * lockstepBlock(128).height, 64u);  // a subgroup does not span workgroups
    EXPECT_EQ(lockstepBlock(12).width * lockstepBlock(12).height, 8u);     // not a power of two: the one below
    EXPECT_EQ(lockstepBlock(0).width * lockstepBlock(0).height, 1u);
}

TEST(Lockstep, SlowestLaneTimesThePixelsOfEachBlock) {
    const auto nodes = [](uint32_t x, uint32_t y) { return (x * 7 + y * 13) % 11 + (x == 5 && y == 3 ? 100 : 0); };
    for (const auto& [w, h] : {std::pair{16u, 8u}, std::pair{6u, 3u}, std::pair{1u, 1u}, std::pair{13u, 9u}})
        for (uint32_t lanes : {8u, 32u}) {
            const LockstepBlock b = lockstepBlock(lanes);
            std::map<std::pair<uint32_t, uint32_t>, std::pair<uint32_t, uint32_t>> blocks;  // max, pixels
            uint64_t sum = 0;
            for (uint32_t y = 0; y < h; ++y)
                for (uint32_t x = 0; x < w; ++x) {
                    auto& [most, pixels] = blocks[{x / b.width, y / b.height}];
                    most = std::max(most, uint32_t(nodes(x, y)));
                    ++pixels;
                    sum += nodes(x, y);
                }
            uint64_t expected = 0;
            for (const auto& [key, v] : blocks) expected += uint64_t(v.first) * v.second;
            const uint64_t got = lockstepNodes(w, h, lanes, nodes);
            EXPECT_EQ(got, expected) << w << "x" << h << ", " << lanes << " lanes";
            EXPECT_GE(got, sum);
        }
    // Equal counts: every lane busy, efficiency 1.
    EXPECT_EQ(lockstepNodes(16, 8, 8, [](uint32_t, uint32_t) { return 5u; }), 16u * 8u * 5u);
}

}  // namespace
}  // namespace vkray::gpu
