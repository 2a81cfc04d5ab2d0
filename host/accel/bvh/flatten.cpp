#include "accel/bvh/flatten.h"

#include <algorithm>
#include <vector>

#include "core/fork_join.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

gpu::GpuBvhNode makeNode(const Aabb& box, uint32_t rightOrFirst, uint32_t count) {
    gpu::GpuBvhNode n{};
    n.lo = box.lo;
    n.hi = box.hi;
    n.rightOrFirst = rightOrFirst;
    n.count = count;
    return n;
}

class Flattener {
public:
    Flattener(const BinaryTree& tree, const CollapsedTree& collapsed, FlatBvh& out)
        : tree_(tree), collapsed_(collapsed), out_(out) {}

    // Writes the subtree of binary node `id` (at tree depth `depth`) to flat node `slot` onwards,
    // its triangles to triangleOrder[first] onwards; returns the depth of its deepest node.
    uint32_t write(uint32_t id, uint32_t slot, uint32_t first, uint32_t depth) {
        const BinaryNode& node = tree_.nodes[id];
        if (collapsed_.isLeaf[id]) {
            const uint32_t count = collapsed_.primitives[id];
            gatherPrimitives(id, first);
            std::sort(out_.triangleOrder.begin() + first, out_.triangleOrder.begin() + first + count);
            out_.nodes[slot] = makeNode(node.box, first, count);
            return depth;
        }
        const uint32_t left = node.child[0], right = node.child[1];
        const uint32_t rightSlot = slot + 1 + collapsed_.flatNodes[left];
        const uint32_t rightFirst = first + collapsed_.primitives[left];
        out_.nodes[slot] = makeNode(node.box, rightSlot, 0);
        uint32_t dl = 0, dr = 0;
        forkJoin(depth < kParallelDepth, [&] { dl = write(left, slot + 1, first, depth + 1); },
                 [&] { dr = write(right, rightSlot, rightFirst, depth + 1); });
        return std::max(dl, dr);
    }

private:
    // The primitives below binary node `id`, written from triangleOrder[first].
    void gatherPrimitives(uint32_t id, uint32_t first) {
        uint32_t stack[VKRAY_BVH_MAX_LEAF_SIZE * 2 + 2];  // a collapsed subtree has < 2 * maxLeaf nodes
        std::vector<uint32_t> big;                        // for a Config with larger leaves
        uint32_t* s = stack;
        if (collapsed_.primitives[id] > VKRAY_BVH_MAX_LEAF_SIZE) {
            big.resize(2 * size_t(collapsed_.primitives[id]) + 2);
            s = big.data();
        }
        size_t top = 0;
        s[top++] = id;
        while (top > 0) {
            const BinaryNode& n = tree_.nodes[s[--top]];
            if (n.isPrimitive()) {
                out_.triangleOrder[first++] = n.child[0];
            } else {
                s[top++] = n.child[1];
                s[top++] = n.child[0];
            }
        }
    }

    const BinaryTree& tree_;
    const CollapsedTree& collapsed_;
    FlatBvh& out_;
};

}  // namespace

FlatBvh flatten(const BinaryTree& tree, const CollapsedTree& collapsed) {
    FlatBvh flat;
    flat.sahCost = collapsed.sahCost;
    if (tree.nodes.empty()) return flat;
    resizeFirstTouched(flat.nodes, collapsed.flatNodes[tree.root]);
    resizeFirstTouched(flat.triangleOrder, tree.primitives);
    flat.maxDepth = Flattener(tree, collapsed, flat).write(tree.root, 0, 0, 0);
    flat.leaves = uint32_t((flat.nodes.size() + 1) / 2);  // a full binary tree: leaves = inner nodes + 1
    return flat;
}

}  // namespace vkray::bvh
