// SAH-driven leaf collapse (after the post-processing of Karras and Aila, "Fast Parallel Construction
// of High-Quality Bounding Volume Hierarchies", HPG 2013): the
// builders produce one primitive per leaf; bottom-up, a subtree of at most Config::maxLeafSize
// primitives becomes a single leaf when that is no more expensive under the SAH than keeping it,
// so the GPU visits fewer nodes. The decision is an exact dynamic programme over the given tree.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/bvh/bvh.h"

namespace vkray::bvh {

struct CollapsedTree {
    std::vector<uint8_t> isLeaf;       // per BinaryTree node: a leaf of the flat tree
    std::vector<uint32_t> primitives;  // per node: primitives below it
    std::vector<uint32_t> flatNodes;   // per node: nodes of its subtree in the flat tree
    double sahCost = 0.0;              // of the collapsed tree, divided by the root's area
};

// Subtrees build as oneTBB tasks near the root; the result does not depend on the thread count.
CollapsedTree collapseLeaves(const BinaryTree& tree, const Config& config);

// The collapse's rule for one node of `count` primitives whose box has half-area `area` and whose
// children's subtrees cost `childCosts`: an inner node (Ct A + childCosts), or one leaf of all its
// primitives (Ci A count) when count <= maxLeafSize and that is no dearer. The treelet
// restructuring (treelet.h) prices its candidate trees by the same rule.
struct NodeChoice {
    double cost;
    bool leaf;
};
NodeChoice chooseNode(const Config& config, double area, uint32_t count, double childCosts);

}  // namespace vkray::bvh
