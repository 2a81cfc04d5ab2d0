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
        const NodeChoice choice = chooseNode(config_, area, count, left + right);
        out_.isLeaf[id] = choice.leaf ? 1 : 0;
        out_.flatNodes[id] = choice.leaf ? 1 : 1 + out_.flatNodes[node.child[0]] + out_.flatNodes[node.child[1]];
        return choice.cost;
    }

private:
    const BinaryTree& tree_;
    const Config& config_;
    CollapsedTree& out_;
};

}  // namespace

NodeChoice chooseNode(const Config& config, double area, uint32_t count, double childCosts) {
    const double asInner = config.sah.traversal * area + childCosts;
    const double asLeaf = config.sah.intersection * area * count;
    if (count <= uint32_t(config.maxLeafSize) && asLeaf <= asInner) return {asLeaf, true};
    return {asInner, false};
}

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
