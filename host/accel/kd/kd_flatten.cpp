#include "accel/kd/kd_build_tree.h"

#include <algorithm>
#include <stdexcept>

#include "core/fork_join.h"

namespace vkray::accel::kd {
namespace {

// Writes a flat subtree at node `base` and index-list entry `first`: its nodes in their order, its
// relative links made absolute.
void placeFlat(const FlatSubtree& f, uint32_t base, uint64_t first, KdTree& out) {
    gpu::KdNode* const to = out.nodes.data() + base;
    for (size_t i = 0; i < f.size(); ++i) {
        gpu::KdNode node = f[i];
        if (node.isLeaf()) {
            node.word0 += uint32_t(first);
        } else {
            if (uint64_t(base) + node.aboveChild() >= (uint64_t(1) << (32u - VKRAY_KD_CHILD_SHIFT)))
                throw std::length_error("kd node: axis or child index out of range");
            node.word1 += base << VKRAY_KD_CHILD_SHIFT;
        }
        to[i] = node;
    }
}

}  // namespace

void flattenKdTree(NodePtr n, uint32_t index, uint64_t first, KdTree& out, int depth) {
    if (n->axis == BuildNode::kFlat) {
        placeFlat(n->flat, index, first, out);
        std::copy(n->triangles.begin(), n->triangles.end(), out.indices.begin() + std::ptrdiff_t(first));
        return;
    }
    if (n->axis == BuildNode::kLeaf) {
        out.nodes[index] = gpu::KdNode::leaf(uint32_t(first), uint32_t(n->triangles.size()));
        std::copy(n->triangles.begin(), n->triangles.end(), out.indices.begin() + std::ptrdiff_t(first));
        return;
    }
    const uint32_t aboveIndex = index + 1 + n->below->subtreeNodes;
    const uint64_t aboveFirst = first + n->below->subtreeRefs;
    out.nodes[index] = gpu::KdNode::inner(n->axis, n->split, aboveIndex, n->below->emptyLeaf(), n->above->emptyLeaf());
    forkJoin(depth < kParallelDepth,
             [&] { flattenKdTree(std::move(n->below), index + 1, first, out, depth + 1); },
             [&] { flattenKdTree(std::move(n->above), aboveIndex, aboveFirst, out, depth + 1); });
}

}  // namespace vkray::accel::kd
