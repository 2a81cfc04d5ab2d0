#include "cpu/whitted.h"

#include <limits>

#include "cpu/shading.h"

namespace vkray::cpu {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Below this in every channel a ray could change an 8-bit pixel by at most a quarter of a step per
// unit of radiance (docs/shading.md, "Depth and weights").
constexpr double kMinWeight = 1.0 / 1024.0;
}  // namespace

bool worthTracing(const glm::dvec3& weight) {
    return weight.r >= kMinWeight || weight.g >= kMinWeight || weight.b >= kMinWeight;
}

WhittedIntegrator::WhittedIntegrator(const Scene& scene, const Tracer& tracer, int maxDepth)
    : scene_(scene), tracer_(tracer), maxDepth_(maxDepth) {}

PixelSample WhittedIntegrator::sample(const Ray& cameraRay) const {
    PixelSample out;
    out.primary = tracer_.closest(cameraRay, kInfinity);
    if (!out.primary.found()) {
        out.radiance = glm::dvec3(scene_.background);
        return out;
    }
    out.normal = surfaceAt(scene_, out.primary, cameraRay.dir).normal;
    addRadiance(cameraRay, out.primary, 1, glm::dvec3(1.0), out.radiance);
    return out;
}

void WhittedIntegrator::addRadiance(const Ray& ray, const Hit& hit, int depth,
                                    const glm::dvec3& weight, glm::dvec3& radiance) const {
    const SurfacePoint s = surfaceAt(scene_, hit, ray.dir);
    radiance += weight * localShading(scene_, tracer_, s, -ray.dir);
    if (depth >= maxDepth_) return;  // a ray of depth k spawns children only while k < maxdepth
    const SecondaryRays children = secondaryRays(s, scene_.materials[s.material], ray.dir);
    for (const SecondaryRay* child : {&children.reflected, &children.refracted}) {
        const glm::dvec3 childWeight = weight * child->factor;
        if (!worthTracing(childWeight)) continue;
        const Hit childHit = tracer_.closest(child->ray, kInfinity);
        if (childHit.found()) addRadiance(child->ray, childHit, depth + 1, childWeight, radiance);
        else radiance += childWeight * glm::dvec3(scene_.background);
    }
}

}  // namespace vkray::cpu
