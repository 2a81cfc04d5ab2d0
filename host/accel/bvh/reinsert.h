// Insertion-based optimisation after the build (Bittner, Hapala and Havran, "Fast Insertion-Based
// Optimization of Bounding Volume Hierarchies", Computer Graphics Forum 32(1), 2013): each
// iteration picks the inner nodes whose boxes are largest against their children's (section 4.2,
// the product of M_sum, M_min and M_area), removes each with its parent (its sibling takes the
// parent's place) and inserts its two children again, each where it adds least surface area to
// the tree, found by branch and bound over the whole tree (section 4.1). The two freed nodes
// become the new parents, so the tree keeps its 2n - 1 nodes and its primitive leaves.
//
// Unlike a treelet (treelet.h), a subtree can move anywhere: AAC merges clusters only inside a
// Morton range, and the subtrees that should have met across a split near the root meet here.
// Only nodes holding at least Config::reinsertMinPrimitives primitives are removed, which keeps
// the work on the top of the tree, where AAC's tree and a top-down SAH build differ.
#pragma once

#include "accel/bvh/bvh.h"

namespace vkray::bvh {

// Runs at most Config::reinsertIterations iterations on `tree` (none when 0), stopping early when
// the best surface-area sum of the last three is not 0.1% below the best before them; returns the
// iterations run. Serial and deterministic.
int reinsertNodes(BinaryTree& tree, const Config& config);

}  // namespace vkray::bvh
