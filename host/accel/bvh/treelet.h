// Treelet restructuring after the build (Karras and Aila, "Fast Parallel Construction of
// High-Quality Bounding Volume Hierarchies", HPG 2013, section 4): bottom-up, every inner node
// grows a treelet of up to kTreeletLeaves leaves (expanding the leaf of largest surface area first,
// 4.1), finds the binary tree over those leaves of least SAH cost by dynamic programming over their
// subsets (4.2-4.3, the cost including the option of one leaf of all their triangles), and
// rebuilds the treelet that way when it is cheaper. The treelet's leaves keep their subtrees; its
// inner nodes are reused, so the tree keeps its 2n - 1 nodes and its primitive leaves.
//
// AAC clusters by the Morton order and agglomerates only inside a Morton range: clusters that
// interleave across a range's split meet only higher up. Restructuring repairs those levels, on a
// tree that is already good near its leaves, so it is applied where a subtree holds at least
// Config::treeletMinPrimitives primitives.
#pragma once

#include "accel/bvh/bvh.h"

namespace vkray::bvh {

inline constexpr int kTreeletLeaves = 7;

// Runs Config::treeletPasses passes over `tree` (none when 0). Deterministic: the result does not
// depend on the number of threads.
void restructureTreelets(BinaryTree& tree, const Config& config);

}  // namespace vkray::bvh
