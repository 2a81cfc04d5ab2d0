#include "cpu/whitted.h"

#include <limits>

#include "cpu/shading.h"

namespace vkray::cpu {

namespace {
// Below this in every channel a ray could change an 8-bit pixel by at most a quarter of a step per
// unit of radiance (docs/shading.md, "Depth and weights").
constexpr double kMinWeight = 1.0 / 1024.0;
}  // namespace

bool worthTracing(const glm::dvec3& weight) {
    return weight.r >= kMinWeight || weight.g >= kMinWeight || weight.b >= kMinWeight;
}

WhittedIntegrator::WhittedIntegrator(const Scene& scene, const Tracer& tracer, int maxDepth,
                                     std::vector<std::string>* log)
    : scene_(scene), tracer_(tracer), maxDepth_(maxDepth), log_(log) {}

void WhittedIntegrator::logRay(const char* kind, const Ray& ray, int depth, const glm::dvec3& weight,
                               const Hit& hit) const {
    const std::string indent(size_t(2 * depth - 2), ' ');
    log_->push_back(indent + kind + " ray, depth " + std::to_string(depth) + ": origin " + logVector(ray.origin) +
                    ", direction " + logVector(ray.dir) + ", weight " + logVector(weight));
    if (!hit.found()) {
        log_->push_back(indent + "  miss: background " + logVector(weight * glm::dvec3(scene_.background)));
        return;
    }
    const SurfacePoint s = surfaceAt(scene_, hit, ray.dir);
    log_->push_back(indent + "  hit triangle " + std::to_string(hit.triangle) + " at t " + std::to_string(hit.t) +
                    ", point " + logVector(s.position) + ", normal " + logVector(s.normal) + ", material " +
                    std::to_string(s.material) + (s.front ? ", front" : ", back") + " face");
}

PixelSample WhittedIntegrator::sample(const Ray& cameraRay) const {
    PixelSample out;
    out.primary = tracer_.closest(cameraRay, kInfinity);
    if (log_) logRay("camera", cameraRay, 1, glm::dvec3(1.0), out.primary);
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
    const glm::dvec3 local = localShading(scene_, tracer_, s, -ray.dir, log_, depth);
    radiance += weight * local;
    if (log_)
        log_->push_back(std::string(size_t(2 * depth), ' ') + "local shading " + logVector(local) +
                        ", times the weight " + logVector(weight * local));
    if (depth >= maxDepth_) return;  // a ray of depth k spawns children only while k < maxdepth
    const SecondaryRays children = secondaryRays(s, scene_.materials[s.material], ray.dir);
    for (const SecondaryRay* child : {&children.reflected, &children.refracted}) {
        const glm::dvec3 childWeight = weight * child->factor;
        const char* kind = child == &children.reflected ? "reflected" : "refracted";
        if (!worthTracing(childWeight)) {
            if (log_ && child->factor != glm::dvec3(0.0))
                log_->push_back(std::string(size_t(2 * depth), ' ') + kind + " ray not traced: weight " +
                                logVector(childWeight) + " below 1/1024");
            continue;
        }
        const Hit childHit = tracer_.closest(child->ray, kInfinity);
        if (log_) logRay(kind, child->ray, depth + 1, childWeight, childHit);
        if (childHit.found()) addRadiance(child->ray, childHit, depth + 1, childWeight, radiance);
        else radiance += childWeight * glm::dvec3(scene_.background);
    }
}

}  // namespace vkray::cpu
