#include "accel/bvh/treelet.h"

#include <array>
#include <bit>
#include <limits>
#include <vector>

#include "core/fork_join.h"
#include "accel/bvh/leaf_collapse.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

constexpr int kSubsets = 1 << kTreeletLeaves;

// A treelet: its root, the other inner nodes it will reuse, and its leaves (subtrees kept whole).
struct Treelet {
    std::array<uint32_t, kTreeletLeaves - 1> inner{};
    int innerCount = 0;
    std::array<uint32_t, kTreeletLeaves> leaves{};
    int leafCount = 0;
};

// The dynamic programme's table over subsets of a treelet's leaves (bit i = leaf i).
struct SubsetTable {
    std::array<Aabb, kSubsets> box;
    std::array<double, kSubsets> cost;      // least SAH cost of a subtree over the subset
    std::array<uint32_t, kSubsets> count;   // primitives under the subset
    std::array<uint8_t, kSubsets> split;    // the best inner node's first child subset
};

class Restructurer {
public:
    Restructurer(BinaryTree& tree, const Config& config) : tree_(tree), config_(config) {
        // The post-order visit writes every node's entries before its parent reads them.
        resizeForOverwrite(cost_, tree.nodes.size());
        resizeForOverwrite(count_, tree.nodes.size());
    }

    // Post-order: both subtrees final (and restructured) before the node's own treelet.
    void visit(uint32_t id, int depth) {
        BinaryNode& node = tree_.nodes[id];
        if (node.isPrimitive()) {
            count_[id] = 1;
            cost_[id] = config_.sah.intersection * node.box.halfArea();
            return;
        }
        forkJoin(depth < kParallelDepth, [&] { visit(node.child[0], depth + 1); },
                 [&] { visit(node.child[1], depth + 1); });
        count_[id] = count_[node.child[0]] + count_[node.child[1]];
        cost_[id] = nodeCost(node.box, count_[id], cost_[node.child[0]] + cost_[node.child[1]]);
        if (count_[id] >= uint32_t(config_.treeletMinPrimitives)) restructure(id);
    }

private:
    // The leaf collapse's rule (chooseNode), so the trees compared are priced as they will be built.
    double nodeCost(const Aabb& box, uint32_t count, double childCosts) const {
        return chooseNode(config_, box.halfArea(), count, childCosts).cost;
    }

    // Section 4.1: grow from the root's children, always opening the leaf of largest area.
    Treelet grow(uint32_t root) const {
        Treelet t;
        t.inner[t.innerCount++] = root;
        t.leaves[t.leafCount++] = tree_.nodes[root].child[0];
        t.leaves[t.leafCount++] = tree_.nodes[root].child[1];
        while (t.leafCount < kTreeletLeaves) {
            int widest = -1;
            float widestArea = -1.0f;
            for (int i = 0; i < t.leafCount; ++i) {
                const BinaryNode& leaf = tree_.nodes[t.leaves[i]];
                if (leaf.isPrimitive()) continue;
                const float area = leaf.box.halfArea();
                if (area > widestArea) {
                    widestArea = area;
                    widest = i;
                }
            }
            if (widest < 0) break;
            const BinaryNode& opened = tree_.nodes[t.leaves[widest]];
            t.inner[t.innerCount++] = t.leaves[widest];
            t.leaves[widest] = opened.child[0];
            t.leaves[t.leafCount++] = opened.child[1];
        }
        return t;
    }

    // Sections 4.2-4.3: every subset's best subtree, in increasing order (a proper subset of s is
    // a smaller number than s). Each split {p, s \ p} is tried once: p holds s's lowest leaf.
    void solve(const Treelet& t, SubsetTable& table) const {
        const uint32_t full = (1u << t.leafCount) - 1;
        for (uint32_t s = 1; s <= full; ++s) {
            const uint32_t low = s & (0u - s);
            if (s == low) {
                const uint32_t leaf = t.leaves[std::countr_zero(s)];
                table.box[s] = tree_.nodes[leaf].box;
                table.cost[s] = cost_[leaf];
                table.count[s] = count_[leaf];
                continue;
            }
            table.box[s] = Aabb::merged(table.box[s ^ low], table.box[low]);
            table.count[s] = table.count[s ^ low] + table.count[low];
            double best = std::numeric_limits<double>::infinity();
            uint32_t bestSplit = low;
            const uint32_t rest = s ^ low;
            for (uint32_t q = (rest - 1) & rest;; q = (q - 1) & rest) {
                const uint32_t p = q | low;  // p = s only for q = rest, which the loop skips
                const double c = table.cost[p] + table.cost[s ^ p];
                if (c < best) {
                    best = c;
                    bestSplit = p;
                }
                if (q == 0) break;
            }
            table.split[s] = uint8_t(bestSplit);
            table.cost[s] = nodeCost(table.box[s], table.count[s], best);
        }
    }

    // Rebuilds the subtree of subset s from the table, taking inner nodes from the treelet's list.
    uint32_t rebuild(const Treelet& t, const SubsetTable& table, uint32_t s, int& nextInner) {
        if (std::has_single_bit(s)) return t.leaves[std::countr_zero(s)];
        const uint32_t id = t.inner[nextInner++];
        const uint32_t first = rebuild(t, table, table.split[s], nextInner);
        const uint32_t second = rebuild(t, table, s ^ table.split[s], nextInner);
        BinaryNode& node = tree_.nodes[id];
        node.child[0] = first;
        node.child[1] = second;
        node.box = table.box[s];
        cost_[id] = table.cost[s];
        count_[id] = table.count[s];
        return id;
    }

    void restructure(uint32_t root) {
        const Treelet t = grow(root);
        if (t.leafCount < 3) return;  // two leaves have one tree
        thread_local SubsetTable table;
        solve(t, table);
        const uint32_t full = (1u << t.leafCount) - 1;
        // The present topology is among the candidates, so only a real gain (beyond the rounding
        // of summing the costs in another order) rebuilds.
        if (!(table.cost[full] < cost_[root] * (1.0 - 1e-9))) return;
        int nextInner = 0;
        rebuild(t, table, full, nextInner);
    }

    BinaryTree& tree_;
    const Config& config_;
    BuildArray<double> cost_;
    BuildArray<uint32_t> count_;
};

}  // namespace

void restructureTreelets(BinaryTree& tree, const Config& config) {
    if (tree.nodes.empty() || config.treeletPasses <= 0) return;
    Restructurer restructurer(tree, config);
    for (int pass = 0; pass < config.treeletPasses; ++pass) restructurer.visit(tree.root, 0);
}

}  // namespace vkray::bvh
