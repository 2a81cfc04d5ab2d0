#include "accel/bvh/leaf_collapse.h"

#include "core/fork_join.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

class Collapser {
public:
    Collapser(const BinaryTree& tree, const Config& config, CollapsedTree& out)
        : tree_(tree), config_(config), out_(out) {}

    // SAH cost of the subtree at `id`, not yet divided by the root's area; fills `out_` for it.
    double visit(uint32_t id, int depth) {
        const BinaryNode& node = tree_.nodes[id];
        const double area = node.box.halfArea();
        if (node.isPrimitive()) {
            out_.isLeaf[id] = 1;
            out_.primitives[id] = 1;
            out_.flatNodes[id] = 1;
            return config_.sah.intersection * area;
        }
        double left = 0.0, right = 0.0;
        forkJoin(depth < kParallelDepth, [&] { left = visit(node.child[0], depth + 1); },
                 [&] { right = visit(node.child[1], depth + 1); });
        const uint32_t count = out_.primitives[node.child[0]] + out_.primitives[node.child[1]];
        out_.primitives[id] = count;
        const double asInner = config_.sah.traversal * area + left + right;
        const double asLeaf = config_.sah.intersection * area * count;
        if (count <= uint32_t(config_.maxLeafSize) && asLeaf <= asInner) {
            out_.isLeaf[id] = 1;
            out_.flatNodes[id] = 1;
            return asLeaf;
        }
        out_.isLeaf[id] = 0;
        out_.flatNodes[id] = 1 + out_.flatNodes[node.child[0]] + out_.flatNodes[node.child[1]];
        return asInner;
    }

private:
    const BinaryTree& tree_;
    const Config& config_;
    CollapsedTree& out_;
};

}  // namespace

CollapsedTree collapseLeaves(const BinaryTree& tree, const Config& config) {
    CollapsedTree out;
    if (tree.nodes.empty()) return out;
    resizeFirstTouched(out.isLeaf, tree.nodes.size());
    resizeFirstTouched(out.primitives, tree.nodes.size());
    resizeFirstTouched(out.flatNodes, tree.nodes.size());
    const double cost = Collapser(tree, config, out).visit(tree.root, 0);
    const double rootArea = tree.nodes[tree.root].box.halfArea();
    // A scene without area (all triangles on one line or point) has no meaningful ratio; report
    // the unnormalised cost rather than divide by zero.
    out.sahCost = rootArea > 0.0 ? cost / rootArea : cost;
    return out;
}

}  // namespace vkray::bvh
