// The `brute` tracer: every ray against every triangle, in double precision. The reference every
// other tracer is measured against; fine for small scenes and tests (cost grows with the number of
// triangles times the number of rays).
#pragma once

#include <vector>

#include "geometry/ray_triangle.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray::geometry {

// The scene's triangles widened to double, in triangle-identity order.
std::vector<TriangleVertices> triangleVertices(const Scene& scene);

class BruteForceTracer final : public Tracer {
public:
    explicit BruteForceTracer(const Scene& scene);
    explicit BruteForceTracer(std::vector<TriangleVertices> triangles);

    Hit closest(const Ray& ray, double tmax, TraversalCounters* counters = nullptr) const override;
    bool occluded(const Ray& ray, double tmax, TraversalCounters* counters = nullptr) const override;

    size_t size() const { return triangles_.size(); }

private:
    std::vector<TriangleVertices> triangles_;
};

}  // namespace vkray::geometry
