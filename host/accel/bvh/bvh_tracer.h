// The CPU traversal of the flattened BVH, so the reference renderer stays usable on big scenes. It
// walks the same nodes as the GPU kernel (near child first, a stack of far children) but in double
// precision with the watertight test of geometry/ray_triangle.h, and answers exactly what
// BruteForceTracer answers, ties included:
// - closest(): the hit with the smallest t, and among equal t the lowest original triangle index.
//   A triangle is tested with tmax just above the best t so far, and a node is skipped only when
//   its box is entered beyond that t, so a tie in another leaf is never lost.
// - boxes are tested conservatively: the slab interval is widened by a relative 1e-7 (far more
//   than the few ulps by which double-precision t or the watertight test's rounding of p - origin
//   can move), so a box never rejects a ray that hits a triangle inside it. A direction component
//   of +-0 is handled exactly: the ray stays in one plane, which lies inside the slab or not.
// - a tree with sphere containers (bvh-sphere, FlatBvh::spheres) is walked the same way with a
//   sphere test instead of the slab test, from the centre's distance to the ray's line, the radius
//   and the interval widened alike.
// Stackless (bvh-stackless): Hapala, Davidovic, Wald, Havran and Slusallek, "Efficient Stack-less
// BVH Traversal for Ray Tracing", SCCG 2011: a parent link per node and a three-state automaton
// (from the parent, from the sibling, from a child) over the binary tree, children in an order
// fixed per node and ray direction (the axis along which their boxes' centres lie furthest apart);
// the same box and triangle tests as above, so the same answers.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "geometry/ray_triangle.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray::bvh {

class BvhTracer final : public geometry::Tracer {
public:
    // Walks `bvh` (the GPU's arrays, which must outlive the tracer) and copies the scene's
    // triangles (triangle-identity order) into leaf order; boxes and vertices are widened to double
    // as they are tested, exactly as BruteForceTracer widens them.
    BvhTracer(const FlatBvh& bvh, std::span<const Triangle> triangles, bool stackless = false);

    geometry::Hit closest(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters = nullptr) const override;
    bool occluded(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters = nullptr) const override;

private:
    struct BoxRay;
    struct Order {
        uint32_t nearChild, farChild;
    };

    // Hapala et al.'s walk: `leaf(node)` for every leaf whose box the ray enters within `limit()`,
    // until it returns true.
    template <class Limit, class Leaf>
    void walkStackless(const BoxRay& boxRay, const glm::dvec3& dir, const Limit& limit, const Leaf& leaf,
                       geometry::TraversalCounters& work) const;
    Order order(uint32_t inner, const glm::dvec3& dir) const;

    geometry::TriangleVertices vertices(uint32_t slot) const {
        const Triangle& t = triangles_[slot];
        return {glm::dvec3(t.p0), glm::dvec3(t.p1), glm::dvec3(t.p2)};
    }
    int32_t original(uint32_t slot) const { return int32_t(bvh_.triangleOrder[slot]); }

    const FlatBvh& bvh_;
    std::vector<Triangle> triangles_;  // leaf order
    uint32_t stackSize_ = 0;           // deepest stack a traversal can need
    std::vector<uint32_t> parents_;    // stackless: each node's parent (the root's: kPrimitive)
};

}  // namespace vkray::bvh
