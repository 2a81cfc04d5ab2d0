#include "gpu/scene_buffers.h"


namespace vkray::gpu {
namespace {

vec4 withW(const glm::vec3& v, float w) { return vec4(v, w); }

template <class T>
Buffer uploadVector(const VulkanContext& ctx, const std::vector<T>& v, const std::string& what) {
    return uploadStorageBuffer(ctx, v.data(), v.size() * sizeof(T), what);
}

}  // namespace

PackedScene packScene(const Scene& scene) {
    PackedScene p;
    p.triangles.reserve(scene.triangles.size());
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& t = scene.triangles[i];
        p.triangles.push_back({.p0 = t.p0, .material = t.material, .p1 = t.p1,
                               .original = uint32_t(i), .p2 = t.p2, .pad0 = 0});
    }
    for (const TriangleNormals& n : scene.normals)
        p.normals.push_back({withW(n.n0, 0.0f), withW(n.n1, 0.0f), withW(n.n2, 0.0f)});
    for (const Material& m : scene.materials)
        p.materials.push_back({.ambient = m.ambient,
                               .shininess = m.shininess,
                               .diffuse = m.diffuse,
                               .ior = m.ior,
                               .specular = withW(m.specular, 0.0f),
                               .emission = withW(m.emission, 0.0f),
                               .reflect = withW(m.reflect, 0.0f),
                               .transmit = withW(m.transmit, 0.0f)});
    for (const Light& l : scene.lights) {
        const uint32_t type = l.type == Light::Type::Point ? VKRAY_LIGHT_POINT : VKRAY_LIGHT_DIRECTIONAL;
        p.lights.push_back({.vector = l.vector, .type = type, .color = l.color, .pad0 = 0.0f});
    }
    return p;
}

SceneBuffers uploadScene(const VulkanContext& ctx, const PackedScene& packed) {
    SceneBuffers b{uploadVector(ctx, packed.triangles, "triangles"),
                   uploadVector(ctx, packed.normals, "vertex normals"),
                   uploadVector(ctx, packed.materials, "materials"),
                   uploadVector(ctx, packed.lights, "lights")};
    b.bytes = packed.triangles.size() * sizeof(GpuTriangle) +
              packed.normals.size() * sizeof(GpuTriangleNormals) +
              packed.materials.size() * sizeof(GpuMaterial) + packed.lights.size() * sizeof(GpuLight);
    return b;
}

}  // namespace vkray::gpu
