// The SAH kd-tree of vkray: its cost model (KdConfig) and the tree itself, held in exactly the
// arrays the GPU kernels read (shaders/shared/kd_layout.h), so the CPU traversals that the unit
// tests check walk the same bytes the GPU walks. docs/kdtree.md describes the whole family.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/parallel_alloc.h"
#include "shared/kd_layout.h"

namespace vkray::accel::kd {

// The surface area heuristic's constants, in pbrt's convention (Pharr, Jakob, Humphreys,
// "Physically Based Rendering", 3rd ed., section 4.4.2):
//
//   cost(split) = Ct + Ci * (1 - eb) * (SA(L)/SA(N) * nL + SA(R)/SA(N) * nR)
//
// with eb = emptyBonus when one side holds no triangle and 0 otherwise, and a leaf costing Ci * n.
// Wald and Havran (2006) use another convention (Ct 15, Ci 20, the whole cost times 0.8 when a side
// is empty); the two are not interchangeable. Only the ratio Ci/Ct shapes the tree.
//
// Default Ci = 20 rather than pbrt's 80: kd-restart walks from the root again for every leaf it
// leaves, so each extra level is paid once per leaf visited, and the GPU kernels test a leaf's
// triangles 4 per loop iteration, both arguing for shallower trees. The GPU-time sweep on lavapipe
// (bunny, 320x240, Ci 5/10/20/40) found Ci = 20 best for kd-restart and within the noise of the
// best for kd-stack (docs/kdtree.md, "Cost convention and tuning").
//
// pbrt's eb = 0.5, but only for empty space worth cutting: a side that is empty and spans at least
// emptyBonusMinFraction of the node along the split axis. With the bonus for any empty side,
// cutting a sliver of empty space off a node is always cheaper than a real split (1 + Ci/2 n
// against about 0.6 Ci n), so every node first peels up to six such slabs, each a level of the
// depth limit, which then ends the tree with big leaves and many triangle tests a ray; the 10%
// rule keeps the bonus for empty space worth a level (docs/kdtree.md, "The empty-space bonus", has
// the counts).
struct KdConfig {
    double traversalCost = 1.0;     // Ct: one inner-node step
    double intersectionCost = 20.0; // Ci: one ray-triangle test
    double emptyBonus = 0.5;        // eb: discount on the intersection term when a side is empty
    double emptyBonusMinFraction = 0.1;  // ... and spans at least this fraction of the node's extent
    // Deepest level a node may sit at (the root is level 0), at most kMaxDepthLimit; unset: pbrt's
    // 8 + 1.3 log2 N, rounded, and capped at kMaxDepthLimit.
    std::optional<int> maxDepth;
    // At most this many references per triangle in the whole tree: along any path from the root the
    // splits' duplications ((nBelow + nAbove) / n) multiply to at most this (sah_kd_builder.cpp).
    // The SAH alone keeps cutting a region crossed by many large overlapping triangles down to the
    // depth limit, each cut referencing most of them on both sides: 100,000 random overlapping
    // triangles made 30 references and 84 nodes per triangle without it. The meshes of scenes/ stay
    // below it (docs/kdtree.md, "A budget of references").
    double maxDuplication = 8.0;
    // The kd-stack kernel's stack holds one entry per level.
    static constexpr int kMaxDepthLimit = VKRAY_KD_MAX_DEPTH;

    int resolvedMaxDepth(size_t triangleCount) const;
    // "pbrt SAH: Ct=1 Ci=20 eb=0.5 for empty sides >= 0.1 of the node" — printed with the SAH cost in --stats.
    std::string describe() const;
};

// The traversals of one tree, after Foley and Sugerman, "KD-Tree Acceleration Structures for a GPU
// Raytracer", Graphics Hardware 2005: the standard stack traversal (the baseline), the stackless
// kd-restart (section 4.1) and kd-backtrack (section 4.2); kd-restart with push-down (Horn,
// Sugerman, Houston and Hanrahan, "Interactive k-D Tree GPU Raytracing", I3D 2007, section 4.1), and
// the stack traversal with a short stack that falls back to that restart (section 4.2); and
// kd-restart that goes on from a leaf by its ropes (Popov, Guenther, Seidel and Slusallek,
// "Stackless KD-Tree Traversal for High Performance GPU Ray Tracing", Eurographics 2007); and the
// stack traversal walked by a subgroup's rays as packets on the GPU (Wald et al. 2001; Horn et al.
// 2007), whose hits, and CPU twin, are the stack traversal's.
enum class Traversal { Stack, Restart, Backtrack, PushDown, ShortStack, Ropes, Packet };

// An axis-aligned box in float (the scene's precision; every split lies on a float).
struct Box {
    glm::vec3 lo{0.0f}, hi{0.0f};

    double surfaceArea() const;
    bool operator==(const Box&) const = default;
};

// The boxes of the children of a node with box `box` split at `pos` on `axis`: below, above.
inline std::pair<Box, Box> splitBox(const Box& box, int axis, float pos) {
    Box below = box, above = box;
    below.hi[axis] = pos;
    above.lo[axis] = pos;
    return {below, above};
}

// A built tree: the GPU arrays of shaders/shared/kd_layout.h. `extra` (parent links and node boxes)
// is filled only for kd-backtrack, whose walks climb by it (deriveNodeExtras, after the build): at
// 32 bytes a node it would be four times the nodes' memory, written for no other traversal. `ropes`
// is filled only for kd-ropes (kd_ropes.h), after the build.
struct KdTree {
    gpu::KdTreeHeader header{};
    BuildArray<gpu::KdNode> nodes;
    BuildArray<uint32_t> indices;
    BuildArray<gpu::KdNodeExtra> extra;
    std::vector<gpu::KdRopeRecord> ropes;

    Box rootBox() const { return Box{header.lo, header.hi}; }
    // Needs `extra` (deriveNodeExtras).
    Box nodeBox(uint32_t node) const { return Box{extra[node].lo, extra[node].hi}; }
    bool operator==(const KdTree&) const;
};

// Fills tree.extra: each node's box (its parent's split at the parent's plane, from the root box)
// and parent link. `threads`: oneTBB workers, 0 = all cores.
void deriveNodeExtras(KdTree& tree, int threads);

// Shape of a built tree, for --stats.
struct KdTreeFigures {
    size_t nodes = 0, leaves = 0, emptyLeaves = 0;
    int maxDepth = 0;
    size_t references = 0;         // entries of the triangle-index list
    size_t indexedTriangles = 0;   // distinct triangles referenced (degenerate ones are left out)
    double sahCost = 0.0;          // expected cost of a random ray through the root box, in KdConfig units
    double meanTrianglesPerLeaf() const { return leaves ? double(references) / double(leaves) : 0.0; }
    size_t duplicatedReferences() const { return references - indexedTriangles; }
};

KdTreeFigures measureTree(const KdTree& tree, const KdConfig& config);

}  // namespace vkray::accel::kd
