// SIMD efficiency of a traversal (after Aila and Laine, "Understanding the Efficiency of Ray
// Traversal on GPUs", HPG 2009): a GPU runs the invocations of a subgroup in lock-step, so a group
// costs what its slowest lane needs, and the mean node steps a ray do not show what the hardware
// executes. render_main.glsl's pixelInTile() lays the invocations of an 8x8 workgroup on pixels so
// that each run of 8 consecutive invocations covers a 4x2 block of the tile; a subgroup of `lanes`
// invocations therefore covers the block lockstepBlock() names (8: 4x2, 16: 8x2, 32: 8x4, 64: 8x8).
#pragma once

#include <cstdint>
#include <functional>

namespace vkray::gpu {

struct LockstepBlock {
    uint32_t width, height;
};

// The pixels one subgroup of `lanes` invocations covers (lanes a power of two; more than a
// workgroup's 64 count as 64, since a subgroup does not span workgroups).
LockstepBlock lockstepBlock(uint32_t lanes);

// Over a tile of width x height pixels (tile coordinates, the origin on a workgroup corner), the
// node steps its subgroups run if each steps until its slowest lane is done: per block, the
// largest count times the pixels in the block (pixels outside the tile are not counted).
// `nodesAt(x, y)` gives a pixel's count. The sum of the counts over this is the SIMD efficiency.
uint64_t lockstepNodes(uint32_t width, uint32_t height, uint32_t lanes,
                       const std::function<uint32_t(uint32_t x, uint32_t y)>& nodesAt);

}  // namespace vkray::gpu
