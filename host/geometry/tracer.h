// The interface every CPU ray tracer offers the reference renderer: closest hit for camera and
// secondary rays, any hit for shadow rays. BruteForceTracer is the first implementation; CPU-side
// acceleration structures (BVH, kd-tree) plug in behind the same interface and must return the
// same answers, ties included.
#pragma once

#include <cstdint>
#include <limits>

#include "geometry/ray.h"

namespace vkray::geometry {

struct Hit {
    int32_t triangle = -1;  // original triangle index (docs/scene-format.md, "Triangle identity"); -1 = miss
    double t = std::numeric_limits<double>::infinity();
    double b0 = 0.0, b1 = 0.0, b2 = 0.0;  // barycentrics of p0, p1, p2

    bool found() const { return triangle >= 0; }
};

// Work done by a traversal, for the statistics of the BVH and kd-tree comparisons: mean nodes
// visited, leaves visited and triangles tested per ray (docs/performance.md, "Traversal counters and
// SIMD efficiency"). Counted only when asked for.
struct TraversalCounters {
    uint64_t nodes = 0;      // nodes visited (inner and leaf)
    uint64_t leaves = 0;     // leaves visited
    uint64_t triangles = 0;  // ray-triangle tests
    uint64_t restarts = 0;   // kd-restart restarts / kd-backtrack climbs
    uint64_t capped = 0;     // rays ended by the traversal's iteration cap (never silently)

    TraversalCounters& operator+=(const TraversalCounters& o) {
        nodes += o.nodes;
        leaves += o.leaves;
        triangles += o.triangles;
        restarts += o.restarts;
        capped += o.capped;
        return *this;
    }
};

class Tracer {
public:
    virtual ~Tracer() = default;

    // The hit with the smallest t in (0, tmax); among hits at exactly the same t, the lowest
    // triangle index, so the answer never depends on traversal order (or thread count).
    // `counters`, when given, accumulates the work done.
    virtual Hit closest(const Ray& ray, double tmax, TraversalCounters* counters = nullptr) const = 0;

    // Whether any triangle is hit with t in (0, tmax): shadow rays (docs/shading.md, "vis").
    virtual bool occluded(const Ray& ray, double tmax, TraversalCounters* counters = nullptr) const = 0;
};

}  // namespace vkray::geometry
