#include "gpu/shader_features.h"

#include <algorithm>

#include "shared/gpu_layout.h"

namespace vkray::gpu {

ShaderFeatures ShaderFeatures::forScene(const Scene& scene, int maxDepth) {
    ShaderFeatures f;
    f.maxDepth = maxDepth;
    const bool secondary = maxDepth > 1;
    const auto anyMaterial = [&](auto pred) {
        return std::any_of(scene.materials.begin(), scene.materials.end(), pred);
    };
    f.refraction = secondary && anyMaterial([](const Material& m) { return m.refracts(); });
    f.reflection = secondary && (f.refraction || anyMaterial([](const Material& m) { return m.reflects(); }));
    const auto anyLight = [&](Light::Type t) {
        return std::any_of(scene.lights.begin(), scene.lights.end(),
                           [t](const Light& l) { return l.type == t; });
    };
    f.pointLights = anyLight(Light::Type::Point);
    f.directionalLights = anyLight(Light::Type::Directional);
    f.smoothNormals = scene.hasSmoothNormals();
    return f;
}

Specialization ShaderFeatures::specialization() const {
    Specialization s;
    s.set(VKRAY_SPEC_MAX_DEPTH, uint32_t(maxDepth));
    s.set(VKRAY_SPEC_HAS_REFLECTION, reflection);
    s.set(VKRAY_SPEC_HAS_REFRACTION, refraction);
    s.set(VKRAY_SPEC_HAS_POINT_LIGHTS, pointLights);
    s.set(VKRAY_SPEC_HAS_DIRECTIONAL_LIGHTS, directionalLights);
    s.set(VKRAY_SPEC_HAS_SMOOTH_NORMALS, smoothNormals);
    s.set(VKRAY_SPEC_COUNT_TRAVERSAL, countTraversal);
    s.set(VKRAY_SPEC_LEAF_SLOTS, leafSlots());
    s.set(VKRAY_SPEC_PRIMARY_AOVS, primaryAovs);
    s.set(VKRAY_SPEC_KD_SHORT_STACK, uint32_t(kdShortStack));
    s.set(VKRAY_SPEC_TEXEL_VIEW_BITS, uint32_t(texelViewBits));
    s.set(VKRAY_SPEC_PIXELS_PER_INVOCATION, invocationPixels());
    return s;
}

std::vector<std::pair<std::string, bool>> ShaderFeatures::list() const {
    return {{"reflection", reflection},
            {"refraction", refraction},
            {"point lights", pointLights},
            {"directional lights", directionalLights},
            {"smooth normals", smoothNormals},
            {"traversal counters", countTraversal},
            {"primary-hit AOVs", primaryAovs},
            {"arrays split over several texel views", texelViewBits > 0},
            {"several pixels per invocation", pixelsPerInvocation > 1}};
}

}  // namespace vkray::gpu
