#include "accel/kd/kd_ropes.h"

#include <array>

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include "core/worker_arena.h"

namespace vkray::accel::kd {
namespace {

using Ropes = std::array<uint32_t, 6>;

// Subtrees with at least this many nodes build their two children as parallel tasks.
constexpr uint32_t kParallelNodes = 4096;

// Pushes the rope `node` of face `face` (2 axis + side; side 1 = the face at box.hi[axis]) of a
// node with box `box` down the tree, as far as the whole face stays on one side ("optimised ropes",
// Popov et al. 2007, section 3.1). At a split on the face's own axis the rope follows the region
// just beyond the face (coordinates above c for a face at hi, below c for one at lo); a split at
// exactly c sends it to the far side, as the traversal's descent does with a plane hit equal to
// tmin. At a split on another axis it goes to the side holding the whole face (a face touching the
// plane at its edge counts as on that side: a ray leaving through that edge is ordered across the
// face first, then the plane; kd_traversal.h, "Ties"), and stops where the face straddles the plane.
uint32_t pushDown(const KdTree& tree, uint32_t node, const Box& box, int face) {
    const int axis = face / 2;
    const bool hiSide = face % 2 == 1;
    const float c = hiSide ? box.hi[axis] : box.lo[axis];
    // A path is never deeper than VKRAY_KD_MAX_DEPTH; a malformed tree (a cycle) ends here, and the
    // traversal's step cap ends a ray that follows such a rope.
    for (int depth = 0; node != VKRAY_KD_NO_ROPE && depth <= VKRAY_KD_MAX_DEPTH; ++depth) {
        const gpu::KdNode& n = tree.nodes[node];
        if (n.isLeaf()) return node;
        const int a = n.axis();
        const float s = n.split();
        const uint32_t below = node + 1, above = n.aboveChild();
        if (a == axis) {
            node = hiSide ? (s > c ? below : above) : (s < c ? above : below);
        } else if (box.hi[a] <= s) {
            node = below;
        } else if (box.lo[a] >= s) {
            node = above;
        } else {
            return node;
        }
    }
    return node;
}

// Popov et al.'s top-down construction: a child inherits its parent's ropes (optimised for the
// parent's faces, which hold the child's), gets its sibling across the split, and pushes each one
// further down for its own, smaller faces. Records every node's box and each leaf's ropes.
void buildSubtree(const KdTree& tree, uint32_t node, const Box& box, const Ropes& ropes,
                  std::vector<gpu::KdRopeRecord>& out, int depth) {
    Ropes mine;
    for (int f = 0; f < 6; ++f) mine[f] = pushDown(tree, ropes[f], box, f);
    const gpu::KdNode& n = tree.nodes[node];
    if (n.isLeaf() || depth > VKRAY_KD_MAX_DEPTH) {  // depth: a malformed tree's cycle ends here
        const bool leaf = n.isLeaf();
        const auto rope = [&](int f) { return leaf ? mine[f] : VKRAY_KD_NO_ROPE; };
        out[node] = gpu::KdRopeRecord{box.lo, rope(0), box.hi, rope(1), rope(2), rope(3), rope(4), rope(5)};
        return;
    }
    out[node] = gpu::KdRopeRecord{box.lo, VKRAY_KD_NO_ROPE, box.hi, VKRAY_KD_NO_ROPE,
                                  VKRAY_KD_NO_ROPE, VKRAY_KD_NO_ROPE, VKRAY_KD_NO_ROPE, VKRAY_KD_NO_ROPE};
    const int a = n.axis();
    const uint32_t below = node + 1, above = n.aboveChild();
    Ropes belowRopes = mine, aboveRopes = mine;
    belowRopes[2 * a + 1] = above;
    aboveRopes[2 * a] = below;
    const auto [belowBox, aboveBox] = splitBox(box, a, n.split());
    const auto goBelow = [&, &b = belowBox] { buildSubtree(tree, below, b, belowRopes, out, depth + 1); };
    const auto goAbove = [&, &b = aboveBox] { buildSubtree(tree, above, b, aboveRopes, out, depth + 1); };
    // Depth-first order: the below subtree's nodes lie between the node and its above child.
    if (above - node >= kParallelNodes && tree.nodes.size() - above >= kParallelNodes) {
        tbb::parallel_invoke(goBelow, goAbove);
    } else {
        goBelow();
        goAbove();
    }
}

}  // namespace

uint32_t ropeOf(const KdTree& tree, const Box& box, int face) {
    const int axis = face / 2;
    const bool hiSide = face % 2 == 1;
    if (hiSide ? box.hi[axis] >= tree.header.hi[axis] : box.lo[axis] <= tree.header.lo[axis]) return VKRAY_KD_NO_ROPE;
    return pushDown(tree, 0, box, face);
}

std::vector<gpu::KdRopeRecord> buildRopes(const KdTree& tree, int threads) {
    std::vector<gpu::KdRopeRecord> ropes(tree.nodes.size());
    if (tree.nodes.empty()) return ropes;
    tbb::task_arena arena(arenaThreads(threads));
    Ropes none;
    none.fill(VKRAY_KD_NO_ROPE);
    arena.execute([&] { buildSubtree(tree, 0, tree.rootBox(), none, ropes, 0); });
    return ropes;
}

}  // namespace vkray::accel::kd
