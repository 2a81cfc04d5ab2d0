// The ropes of kd-ropes (Popov, Guenther, Seidel and Slusallek, "Stackless KD-Tree Traversal for
// High Performance GPU Ray Tracing", Eurographics 2007, section 3.1): for each of a leaf's six faces,
// the smallest node whose box holds the whole face on the far side, or VKRAY_KD_NO_ROPE where the
// face lies on the root box; and every node's box, where a rope may lead. Built after the tree, top
// down, subtrees in parallel; the layout is KdRopeRecord (shaders/shared/kd_layout.h).
#pragma once

#include <vector>

#include "accel/kd/kd_tree.h"

namespace vkray::accel::kd {

// One record per node of `tree` (an inner node's ropes are VKRAY_KD_NO_ROPE). `threads`: oneTBB
// workers, 0 = all cores. Each node's box is its parent's split, from the root box.
std::vector<gpu::KdRopeRecord> buildRopes(const KdTree& tree, int threads);

// The rope of face `face` (2 axis + side; side 1 = the face at box.hi[axis]) of a leaf with box `box`,
// found on its own: from the root, the descent that follows the region just beyond the face, down
// to the first node that the face straddles or a leaf. buildRopes() must find the same (the tests
// check it).
uint32_t ropeOf(const KdTree& tree, const Box& box, int face);

}  // namespace vkray::accel::kd
