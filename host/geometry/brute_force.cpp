#include "geometry/brute_force.h"

#include <utility>

namespace vkray::geometry {

std::vector<TriangleVertices> triangleVertices(const Scene& scene) {
    std::vector<TriangleVertices> out;
    out.reserve(scene.triangles.size());
    for (const Triangle& tri : scene.triangles)
        out.push_back({glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)});
    return out;
}

BruteForceTracer::BruteForceTracer(const Scene& scene) : triangles_(triangleVertices(scene)) {}

BruteForceTracer::BruteForceTracer(std::vector<TriangleVertices> triangles)
    : triangles_(std::move(triangles)) {}

Hit BruteForceTracer::closest(const Ray& ray, double tmax, TraversalCounters* counters) const {
    const WatertightRay wray(ray);
    if (counters) counters->triangles += triangles_.size();
    Hit best;
    best.t = tmax;
    // Triangles in index order with the interval shrinking to (0, best.t): a later triangle at
    // exactly the same t fails `t < tmax`, so ties go to the lowest index.
    for (size_t k = 0; k < triangles_.size(); ++k) {
        if (const auto hit = wray.intersect(triangles_[k], 0.0, best.t)) {
            best = Hit{int32_t(k), hit->t, hit->b0, hit->b1, hit->b2};
        }
    }
    if (!best.found()) best.t = std::numeric_limits<double>::infinity();
    return best;
}

bool BruteForceTracer::occluded(const Ray& ray, double tmax, TraversalCounters* counters) const {
    const WatertightRay wray(ray);
    for (size_t k = 0; k < triangles_.size(); ++k)
        if (wray.intersect(triangles_[k], 0.0, tmax)) {
            if (counters) counters->triangles += k + 1;
            return true;
        }
    if (counters) counters->triangles += triangles_.size();
    return false;
}

}  // namespace vkray::geometry
