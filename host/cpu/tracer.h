// The interface every CPU ray tracer offers the reference renderer: closest hit for camera and
// secondary rays, any hit for shadow rays. BruteForceTracer is the first implementation; CPU-side
// acceleration structures (BVH, kd-tree) plug in behind the same interface and must return the
// same answers, ties included.
#pragma once

#include <cstdint>
#include <limits>

#include "cpu/ray.h"

namespace vkray::cpu {

struct Hit {
    int32_t triangle = -1;  // original triangle index (DESIGN.md, "Triangle identity"); -1 = miss
    double t = std::numeric_limits<double>::infinity();
    double b0 = 0.0, b1 = 0.0, b2 = 0.0;  // barycentrics of p0, p1, p2

    bool found() const { return triangle >= 0; }
};

class Tracer {
public:
    virtual ~Tracer() = default;

    // The hit with the smallest t in (0, tmax); among hits at exactly the same t, the lowest
    // triangle index, so the answer never depends on traversal order (or thread count).
    virtual Hit closest(const Ray& ray, double tmax) const = 0;

    // Whether any triangle is hit with t in (0, tmax): shadow rays (docs/shading.md, "vis").
    virtual bool occluded(const Ray& ray, double tmax) const = 0;
};

}  // namespace vkray::cpu
