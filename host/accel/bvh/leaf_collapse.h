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

// Per BinaryTree node, one record of 8 bytes (the flattening reads it with the node's children).
struct CollapsedNode {
    uint32_t primitives = 0;  // primitives below it
    uint32_t flatNodes = 0;   // nodes of its subtree in the flat tree: 1 for a leaf, >= 3 for an inner node
    bool leaf() const { return flatNodes == 1; }
};

struct CollapsedTree {
    BuildArray<CollapsedNode> nodes;  // indexed like BinaryTree::nodes
    double sahCost = 0.0;              // of the collapsed tree, divided by the root's area
};

// Half the surface area of node `id`'s container: its box, or its sphere when the tree has spheres.
double containerArea(const BinaryTree& tree, uint32_t id);

// Subtrees build as oneTBB tasks near the root; the result does not depend on the thread count.
CollapsedTree collapseLeaves(const BinaryTree& tree, const Config& config);

// The same collapse, recorded while a builder makes the tree bottom-up (every node after both its
// children): no pass over the finished tree, whose nodes are then read again far from any cache.
// primitive() and inner() may run on several threads for distinct nodes; finish() once, after all.
// The AAC builder records it when no restructuring follows (aac_builder.h). `area`: half the
// surface area of the node's container (containerArea()).
class CollapseRecorder {
public:
    CollapseRecorder(const Config& config, size_t nodes);
    void primitive(uint32_t id, double area);
    void inner(uint32_t id, double area, uint32_t left, uint32_t right);
    CollapsedTree finish(uint32_t root, double rootArea);

private:
    const Config& config_;
    CollapsedTree out_;
    BuildArray<double> cost_;  // per node: SAH cost of its collapsed subtree, not yet divided by the root's area
};

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
