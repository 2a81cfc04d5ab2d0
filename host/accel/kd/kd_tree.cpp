#include "accel/kd/kd_tree.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.h"

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

KdTreeFigures measureTree(const KdTree& tree, const KdConfig& config) {
    KdTreeFigures f;
    f.nodes = tree.nodes.size();
    f.references = tree.indices.size();
    const double rootArea = tree.rootBox().surfaceArea();
    // Depth-first walk with an explicit stack of (node, depth); depth is bounded by VKRAY_KD_MAX_DEPTH.
    std::vector<std::pair<uint32_t, int>> pending;
    if (!tree.nodes.empty()) pending.emplace_back(0u, 0);
    while (!pending.empty()) {
        const auto [index, depth] = pending.back();
        pending.pop_back();
        const gpu::KdNode& node = tree.nodes[index];
        f.maxDepth = std::max(f.maxDepth, depth);
        // SAH cost of the whole tree (Wald and Havran 2006, eq. 1): every node weighted by the
        // probability SA(node)/SA(root) that a random ray through the root meets it.
        const double p = rootArea > 0.0 ? tree.nodeBox(index).surfaceArea() / rootArea : 1.0;
        if (node.isLeaf()) {
            ++f.leaves;
            if (node.triangleCount() == 0) ++f.emptyLeaves;
            f.sahCost += p * config.intersectionCost * node.triangleCount();
        } else {
            f.sahCost += p * config.traversalCost;
            pending.emplace_back(node.aboveChild(), depth + 1);
            pending.emplace_back(index + 1, depth + 1);
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
