// The BVH family's shared types: boxes, the build configuration with its cited constants, the binary
// tree both builders produce (one primitive per leaf), and the flattened tree the GPU and the CPU
// tracer traverse.
//
// Pipeline (docs/bvh.md): builder (AAC, aac_builder.h, or binned SAH, sah_builder.h) -> BinaryTree
// -> leaf collapse (leaf_collapse.h) -> flatten (flatten.h) -> FlatBvh -> BvhTracer, and gpuNodes()
// (4-wide) -> GPU buffers.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/parallel_alloc.h"
#include "shared/bvh_layout.h"

namespace vkray::bvh {

// Axis-aligned box in float: triangle vertices are float, so float min/max are exact bounds.
struct Aabb {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};

    void grow(const glm::vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Aabb& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    bool contains(const Aabb& b) const {
        return glm::all(glm::lessThanEqual(lo, b.lo)) && glm::all(glm::greaterThanEqual(hi, b.hi));
    }
    // Half the surface area (SAH ratios and AAC distances only compare areas, so the factor 2 is
    // left out); 0 for an empty box.
    float halfArea() const {
        if (empty()) return 0.0f;
        const glm::vec3 d = hi - lo;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
    static Aabb merged(const Aabb& a, const Aabb& b) {
        Aabb m = a;
        m.grow(b);
        return m;
    }
};

// Bounding sphere in float, for bvh-sphere's containers (the box/sphere experiment of Mahmuda 2017,
// section 5.3.2): every sphere is rounded outwards when made (sphere_bounds.h), so it holds what it
// bounds in exact arithmetic.
struct Sphere {
    glm::vec3 centre{0.0f};
    float radius = -1.0f;  // < 0: empty

    bool empty() const { return radius < 0.0f; }
    // Half the surface area, 2 pi r^2, so that the SAH and AAC's distance compare spheres with
    // boxes (Aabb::halfArea) in the same unit: a convex body's chance of being hit by a random ray
    // is proportional to its surface area.
    float halfArea() const { return empty() ? 0.0f : 6.2831853f * radius * radius; }
};

// Surface-area-heuristic constants (Goldsmith and Salmon 1987; MacDonald and Booth 1990): the cost
// of a tree is sum over inner nodes of Ct * A(node) plus sum over leaves of Ci * |leaf| * A(leaf),
// divided by A(root). Ct = Ci = 1 prices one node visit (two child slab tests) like one
// watertight triangle test, about what the GPU kernel spends on each; the same constants decide
// the leaf collapse and the reported sah_cost, so the builders are judged as they are built.
struct SahConstants {
    double traversal = 1.0;     // Ct
    double intersection = 1.0;  // Ci
};

// How a BVH is built. AAC fields after Gu, He, Fatahalian and Blelloch, "Efficient BVH Construction
// via Approximate Agglomerative Clustering", HPG 2013 (the paper's delta, epsilon and its cluster
// count reduction function f; also A. F. Mahmuda, "Bounding Volume Hierarchy Construction Using
// Agglomerative Clustering for Faster Ray Tracing", thesis, ITS 2017, listings 3.2 and 4.11).
struct Config {
    enum class Builder { Aac, BinnedSah };
    Builder builder = Builder::Aac;
    // What bounds a node: a box, or (bvh-sphere, AAC only, no treelets) a sphere, which AAC's
    // distance, the leaf collapse and the traversals then use instead (Mahmuda 2017's container
    // types).
    enum class Container { Box, Sphere };
    Container container = Container::Box;

    // AAC: the downward phase stops at ranges of at most `delta` primitives (paper's delta, Mahmuda
    // 2017's "threshold"); each level keeps f(n) = c * n^alpha clusters of its n primitives, with
    // alpha = 1/2 - epsilon and c = delta^(1/2 + epsilon) / 2, so that f(delta) = delta / 2.
    int delta = 4;
    double epsilon = 0.2;
    // Leaf ranges are clustered by an all-pairs search, O(delta^2) per merge: larger deltas would
    // turn a build into hours.
    static constexpr int kMaxDelta = 1024;

    // Binned SAH reference (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies",
    // RT 2007, section 3: 16-32 bins lose little against a full sweep): bins per axis.
    int sahBins = 32;

    // Leaf collapse (both builders): a subtree of at most maxLeafSize triangles becomes one leaf
    // where the SAH says so (leaf_collapse.h).
    int maxLeafSize = VKRAY_BVH_MAX_LEAF_SIZE;
    SahConstants sah;

    // Treelet restructuring after the build (treelet.h): passes over the tree (0 = none), and the
    // smallest subtree, in primitives, whose root grows a treelet.
    int treeletPasses = 0;
    int treeletMinPrimitives = 1;

    // Insertion-based optimisation before the treelets (reinsert.h): iterations at most (0 = none),
    // and the share of the inner nodes taken out and inserted again an iteration (0.05: of 0.005,
    // 0.02 and 0.05 on the three close-ups, the lowest SAH cost and fewest node steps; docs/bvh.md).
    int reinsertIterations = 0;
    double reinsertBatch = 0.05;

    // The paper's two presets, AAC-Fast and AAC-HQ (Mahmuda 2017 instead settled on delta 6 and 12).
    static Config aacFast() { return withAac(4, 0.2); }
    static Config aacHq() { return withAac(20, 0.1); }
    // AAC-HQ followed by treelet restructuring (treelet.h): vkray's default BVH.
    static Config aacHqRestructured() {
        Config c = aacHq();
        c.treeletPasses = 2;
        c.treeletMinPrimitives = 8;
        return c;
    }
    // AAC-HQ with sphere containers (bvh-sphere).
    static Config aacHqSpheres() {
        Config c = aacHq();
        c.container = Container::Sphere;
        return c;
    }
    static Config binnedSah() {
        Config c;
        c.builder = Builder::BinnedSah;
        return c;
    }
    static Config withAac(int delta, double epsilon) {
        Config c;
        c.delta = delta;
        c.epsilon = epsilon;
        return c;
    }

    // "AAC delta=20 epsilon=0.1" or "binned SAH, 32 bins", then the leaf collapse's constants.
    std::string describe() const;
};

// A node id in a BinaryTree whose second child is kPrimitive is a leaf holding one primitive.
inline constexpr uint32_t kPrimitive = 0xFFFFFFFFu;

// What the builders produce: a full binary tree with one primitive per leaf (2n - 1 nodes).
struct BinaryNode {
    Aabb box;
    uint32_t child[2] = {kPrimitive, kPrimitive};  // leaf: {original triangle index, kPrimitive}

    bool isPrimitive() const { return child[1] == kPrimitive; }
};

struct BinaryTree {
    BuildArray<BinaryNode> nodes;
    std::vector<Sphere> spheres;  // sphere containers only: per node, its bounding sphere
    uint32_t root = 0;
    uint32_t primitives = 0;
};

// A node of the flattened tree. Depth-first: an inner node's left child is the next node.
struct FlatNode {
    glm::vec3 lo;           // bounding box, min corner
    uint32_t rightOrFirst;  // inner node: index of the right child; leaf: first triangle slot
    glm::vec3 hi;           // bounding box, max corner
    uint32_t count;         // leaf: number of triangles (1..VKRAY_BVH_MAX_LEAF_SIZE); inner: 0
};

// The flattened tree the CPU tracer walks and gpuNodes() (flatten.h) turns into the GPU layout:
// depth-first nodes; triangle slot k of the leaves holds scene triangle triangleOrder[k].
struct FlatBvh {
    BuildArray<FlatNode> nodes;
    std::vector<Sphere> spheres;  // sphere containers only: per node, the sphere the tracers test (not the box)
    std::vector<uint32_t> triangleOrder;
    uint32_t leaves = 0;
    uint32_t maxDepth = 0;  // root = depth 0
    double sahCost = 0.0;   // of the collapsed tree (SahConstants), normalised by the root's area

    bool empty() const { return triangleOrder.empty(); }
};

}  // namespace vkray::bvh
