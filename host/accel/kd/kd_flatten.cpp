#include "accel/kd/kd_build_tree.h"

#include <algorithm>
#include <stdexcept>

#include "core/fork_join.h"

namespace vkray::accel::kd {
namespace {

// Writes node `i` of a flat subtree placed at node `base` and index-list entry `first`, and its
// subtree, its relative links made absolute and its boxes and parent links derived as flatten()
// derives them.
void placeFlat(const FlatSubtree& f, uint32_t i, uint32_t base, uint64_t first, uint32_t parent, const Box& box,
               KdTree& out) {
    gpu::KdNode node = f[i];
    out.extra[base + i] = gpu::KdNodeExtra{box.lo, parent, box.hi, 0};
    if (node.isLeaf()) {
        node.word0 += uint32_t(first);
        out.nodes[base + i] = node;
        return;
    }
    if (uint64_t(base) + node.aboveChild() >= (uint64_t(1) << (32u - VKRAY_KD_CHILD_SHIFT)))
        throw std::length_error("kd node: axis or child index out of range");
    const auto [belowBox, aboveBox] = splitBox(box, node.axis(), node.split());
    placeFlat(f, i + 1, base, first, base + i, belowBox, out);
    placeFlat(f, node.aboveChild(), base, first, base + i, aboveBox, out);
    node.word1 += base << VKRAY_KD_CHILD_SHIFT;
    out.nodes[base + i] = node;
}

}  // namespace

void flattenKdTree(NodePtr n, uint32_t index, uint64_t first, uint32_t parent, const Box& box,
             KdTree& out, int depth) {
    if (n->axis == BuildNode::kFlat) {
        placeFlat(n->flat, 0, index, first, parent, box, out);
        std::copy(n->triangles.begin(), n->triangles.end(), out.indices.begin() + std::ptrdiff_t(first));
        return;
    }
    out.extra[index] = gpu::KdNodeExtra{box.lo, parent, box.hi, 0};
    if (n->axis == BuildNode::kLeaf) {
        out.nodes[index] = gpu::KdNode::leaf(uint32_t(first), uint32_t(n->triangles.size()));
        std::copy(n->triangles.begin(), n->triangles.end(), out.indices.begin() + std::ptrdiff_t(first));
        return;
    }
    const auto [belowBox, aboveBox] = splitBox(box, n->axis, n->split);
    const uint32_t aboveIndex = index + 1 + n->below->subtreeNodes;
    const uint64_t aboveFirst = first + n->below->subtreeRefs;
    out.nodes[index] = gpu::KdNode::inner(n->axis, n->split, aboveIndex, n->below->emptyLeaf(), n->above->emptyLeaf());
    forkJoin(depth < kParallelDepth,
             [&, &bBox = belowBox] { flattenKdTree(std::move(n->below), index + 1, first, index, bBox, out, depth + 1); },
             [&, &aBox = aboveBox] { flattenKdTree(std::move(n->above), aboveIndex, aboveFirst, index, aBox, out, depth + 1); });
}

}  // namespace vkray::accel::kd
