// The invariants of a BinaryTree that the passes after a build (treelets, reinsertion) must keep.
#pragma once

#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/bvh.h"
#include "accel/bvh/primitives.h"

namespace vkray::test {

// Every node but the root has exactly one parent, every primitive is in exactly one leaf and every
// inner box is exactly the union of its children's.
inline void checkBinaryTree(const bvh::BinaryTree& tree, const bvh::PrimitiveSet& prims) {
    ASSERT_EQ(tree.nodes.size(), 2 * prims.size() - 1);
    std::vector<int> parents(tree.nodes.size(), 0), seen(prims.size(), 0);
    for (const bvh::BinaryNode& node : tree.nodes) {
        if (node.isPrimitive()) {
            ASSERT_LT(node.child[0], prims.size());
            ++seen[node.child[0]];
            continue;
        }
        ++parents[node.child[0]];
        ++parents[node.child[1]];
        const bvh::Aabb merged = bvh::Aabb::merged(tree.nodes[node.child[0]].box, tree.nodes[node.child[1]].box);
        EXPECT_EQ(node.box.lo, merged.lo);
        EXPECT_EQ(node.box.hi, merged.hi);
    }
    for (size_t id = 0; id < parents.size(); ++id) ASSERT_EQ(parents[id], id == tree.root ? 0 : 1) << "node " << id;
    for (size_t p = 0; p < seen.size(); ++p) ASSERT_EQ(seen[p], 1) << "primitive " << p;
}

}  // namespace vkray::test
