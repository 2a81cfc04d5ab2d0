// Whitted's recursion over a tracer (docs/shading.md, "Secondary rays" and "Depth and weights"),
// for one camera ray at a time. The renderer loops it over pixels and threads.
#pragma once

#include <string>
#include <vector>

#include "geometry/ray.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray::cpu {

// What a camera ray produces: its radiance and the AOVs of its primary hit.
struct PixelSample {
    glm::dvec3 radiance{0.0};
    geometry::Hit primary;       // primary.found() == false on a miss
    glm::dvec3 normal{0.0};      // N at the primary hit (facing the camera), 0 on a miss
};

class WhittedIntegrator {
public:
    // `scene` and `tracer` must outlive the integrator; maxDepth >= 1 (primary rays are depth 1).
    // With `log` (and `log` outliving it), every ray, hit and shading term of each sample is
    // appended to it as a line of text (`vkray render --pixel`).
    WhittedIntegrator(const Scene& scene, const geometry::Tracer& tracer, int maxDepth,
                      std::vector<std::string>* log = nullptr);

    PixelSample sample(const geometry::Ray& cameraRay) const;

private:
    // Adds weight ⊙ L(ray) to `radiance`, the form the GPU's iterative stack evaluates too.
    void addRadiance(const geometry::Ray& ray, const geometry::Hit& hit, int depth,
                     const glm::dvec3& weight, glm::dvec3& radiance) const;

    void logRay(const char* kind, const geometry::Ray& ray, int depth, const glm::dvec3& weight,
                const geometry::Hit& hit) const;

    const Scene& scene_;
    const geometry::Tracer& tracer_;
    int maxDepth_;
    std::vector<std::string>* log_;
};

// The weight cutoff: a secondary ray whose weight is below 1/1024 in every channel is not traced.
bool worthTracing(const glm::dvec3& weight);

}  // namespace vkray::cpu
