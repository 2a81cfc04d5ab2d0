#include "accel/kd/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <tbb/task_arena.h>

#include "core/error.h"
#include "core/fork_join.h"
#include "core/worker_arena.h"

namespace vkray::accel::kd {

int KdConfig::resolvedMaxDepth(size_t triangleCount) const {
    // pbrt 3rd ed., section 4.4.2: "8 + 1.3 log2(N)" bounds the depth for any N.
    if (maxDepth) {
        if (*maxDepth < 0 || *maxDepth > kMaxDepthLimit)
            throw Error("kd-tree maximum depth must be 0.." + std::to_string(kMaxDepthLimit) + " (got " +
                        std::to_string(*maxDepth) + ")");
        return *maxDepth;
    }
    const int depth = int(std::lround(8.0 + 1.3 * std::log2(double(std::max<size_t>(triangleCount, 1)))));
    return std::min(depth, kMaxDepthLimit);
}

std::string KdConfig::describe() const {
    char text[128];
    std::snprintf(text, sizeof text, "pbrt SAH: Ct=%g Ci=%g eb=%g for empty sides >= %g of the node", traversalCost,
                  intersectionCost, emptyBonus, emptyBonusMinFraction);
    return text;
}

double Box::surfaceArea() const {
    const glm::dvec3 e = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

bool KdTree::operator==(const KdTree& o) const {
    const auto sameExtra = [](const gpu::KdNodeExtra& a, const gpu::KdNodeExtra& b) {
        return a.lo == b.lo && a.hi == b.hi && a.parent == b.parent;
    };
    return header.lo == o.header.lo && header.hi == o.header.hi && header.nodeCount == o.header.nodeCount &&
           header.indexCount == o.header.indexCount && nodes == o.nodes && indices == o.indices &&
           std::equal(extra.begin(), extra.end(), o.extra.begin(), o.extra.end(), sameExtra);
}

namespace {

// Node `index`'s extra record and its subtree's, the subtrees near the root as parallel tasks.
// `depth` also ends a malformed tree's cycle (no path is deeper than VKRAY_KD_MAX_DEPTH).
void deriveSubtree(KdTree& tree, uint32_t index, uint32_t parent, const Box& box, int depth) {
    tree.extra[index] = gpu::KdNodeExtra{box.lo, parent, box.hi, 0};
    const gpu::KdNode& node = tree.nodes[index];
    if (node.isLeaf() || depth > VKRAY_KD_MAX_DEPTH) return;
    const auto [below, above] = splitBox(box, node.axis(), node.split());
    forkJoin(depth < kParallelDepth, [&, &b = below] { deriveSubtree(tree, index + 1, index, b, depth + 1); },
             [&, &a = above] { deriveSubtree(tree, node.aboveChild(), index, a, depth + 1); });
}

}  // namespace

void deriveNodeExtras(KdTree& tree, int threads) {
    tbb::task_arena arena(arenaThreads(threads));
    arena.execute([&] {
        resizeForOverwrite(tree.extra, tree.nodes.size());  // every node's record is written below
        if (!tree.nodes.empty()) deriveSubtree(tree, 0, VKRAY_KD_NO_PARENT, tree.rootBox(), 0);
    });
}

KdTreeFigures measureTree(const KdTree& tree, const KdConfig& config) {
    KdTreeFigures f;
    f.nodes = tree.nodes.size();
    f.references = tree.indices.size();
    const double rootArea = tree.rootBox().surfaceArea();
    // Depth-first walk with an explicit stack of (node, depth, box), each box split from its
    // parent's as the traversals split it; depth is bounded by VKRAY_KD_MAX_DEPTH.
    struct Pending {
        uint32_t index;
        int depth;
        Box box;
    };
    std::vector<Pending> pending;
    if (!tree.nodes.empty()) pending.push_back({0u, 0, tree.rootBox()});
    while (!pending.empty()) {
        const auto [index, depth, box] = pending.back();
        pending.pop_back();
        const gpu::KdNode& node = tree.nodes[index];
        f.maxDepth = std::max(f.maxDepth, depth);
        // SAH cost of the whole tree (Wald and Havran 2006, eq. 1): every node weighted by the
        // probability SA(node)/SA(root) that a random ray through the root meets it.
        const double p = rootArea > 0.0 ? box.surfaceArea() / rootArea : 1.0;
        if (node.isLeaf()) {
            ++f.leaves;
            if (node.triangleCount() == 0) ++f.emptyLeaves;
            f.sahCost += p * config.intersectionCost * node.triangleCount();
        } else {
            f.sahCost += p * config.traversalCost;
            const auto [below, above] = splitBox(box, node.axis(), node.split());
            pending.push_back({node.aboveChild(), depth + 1, above});
            pending.push_back({index + 1, depth + 1, below});
        }
    }
    // Distinct triangles: one flag a triangle, set in one pass over the references, linear where
    // sorting them would be n log n over millions of references.
    if (!tree.indices.empty()) {
        std::vector<uint8_t> seen(size_t(*std::max_element(tree.indices.begin(), tree.indices.end())) + 1, 0);
        for (const uint32_t t : tree.indices) {
            f.indexedTriangles += seen[t] == 0;
            seen[t] = 1;
        }
    }
    return f;
}

}  // namespace vkray::accel::kd
