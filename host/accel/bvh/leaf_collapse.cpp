#include "accel/bvh/leaf_collapse.h"

#include "core/fork_join.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

// One node of the collapse, its children done: its record in `out` and its subtree's cost.
// `area`: half the surface area of the node's container (its box, or its sphere in a tree of
// sphere containers).
double collapsePrimitive(const Config& config, CollapsedTree& out, uint32_t id, double area) {
    out.nodes[id] = CollapsedNode{1, 1};
    return config.sah.intersection * area;
}

double collapseInner(const Config& config, CollapsedTree& out, uint32_t id, double area, uint32_t left,
                     uint32_t right, double childCosts) {
    const CollapsedNode& l = out.nodes[left];
    const CollapsedNode& r = out.nodes[right];
    const uint32_t count = l.primitives + r.primitives;
    const NodeChoice choice = chooseNode(config, area, count, childCosts);
    out.nodes[id] = CollapsedNode{count, choice.leaf ? 1 : 1 + l.flatNodes + r.flatNodes};
    return choice.cost;
}

// Every node's record is written, children before parents, before it is read.
CollapsedTree allocate(size_t nodes) {
    CollapsedTree out;
    resizeForOverwrite(out.nodes, nodes);
    return out;
}

// A scene without area (all triangles on one line or point) has no meaningful ratio; report the
// unnormalised cost rather than divide by zero.
double normalised(double cost, double rootArea) { return rootArea > 0.0 ? cost / rootArea : cost; }

class Collapser {
public:
    Collapser(const BinaryTree& tree, const Config& config, CollapsedTree& out)
        : tree_(tree), config_(config), out_(out) {}

    // SAH cost of the subtree at `id`, not yet divided by the root's area; fills `out_` for it.
    double visit(uint32_t id, int depth) {
        const BinaryNode& node = tree_.nodes[id];
        if (node.isPrimitive()) return collapsePrimitive(config_, out_, id, containerArea(tree_, id));
        double left = 0.0, right = 0.0;
        forkJoin(depth < kParallelDepth, [&] { left = visit(node.child[0], depth + 1); },
                 [&] { right = visit(node.child[1], depth + 1); });
        return collapseInner(config_, out_, id, containerArea(tree_, id), node.child[0], node.child[1], left + right);
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

double containerArea(const BinaryTree& tree, uint32_t id) {
    return tree.spheres.empty() ? tree.nodes[id].box.halfArea() : tree.spheres[id].halfArea();
}

CollapsedTree collapseLeaves(const BinaryTree& tree, const Config& config) {
    if (tree.nodes.empty()) return {};
    CollapsedTree out = allocate(tree.nodes.size());
    const double cost = Collapser(tree, config, out).visit(tree.root, 0);
    out.sahCost = normalised(cost, containerArea(tree, tree.root));
    return out;
}

CollapseRecorder::CollapseRecorder(const Config& config, size_t nodes) : config_(config), out_(allocate(nodes)) {
    resizeForOverwrite(cost_, nodes);  // as the records
}

void CollapseRecorder::primitive(uint32_t id, double area) { cost_[id] = collapsePrimitive(config_, out_, id, area); }

void CollapseRecorder::inner(uint32_t id, double area, uint32_t left, uint32_t right) {
    cost_[id] = collapseInner(config_, out_, id, area, left, right, cost_[left] + cost_[right]);
}

CollapsedTree CollapseRecorder::finish(uint32_t root, double rootArea) {
    out_.sahCost = normalised(cost_[root], rootArea);
    BuildArray<double>().swap(cost_);
    return std::move(out_);
}

}  // namespace vkray::bvh
