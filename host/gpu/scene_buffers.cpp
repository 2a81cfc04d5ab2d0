#include "gpu/scene_buffers.h"

#include <bit>

namespace vkray::gpu {
namespace {

vec4 withW(const glm::vec3& v, float w) { return vec4(v, w); }
float bitsOf(uint32_t u) { return std::bit_cast<float>(u); }

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
        p.triangles.push_back({.p0Material = withW(t.p0, bitsOf(t.material)),
                               .p1Original = withW(t.p1, bitsOf(uint32_t(i))),
                               .p2 = withW(t.p2, 0.0f)});
    }
    for (const TriangleNormals& n : scene.normals)
        p.normals.push_back({withW(n.n0, 0.0f), withW(n.n1, 0.0f), withW(n.n2, 0.0f)});
    for (const Material& m : scene.materials)
        p.materials.push_back({.ambientShininess = withW(m.ambient, m.shininess),
                               .diffuseIor = withW(m.diffuse, m.ior),
                               .specular = withW(m.specular, 0.0f),
                               .emission = withW(m.emission, 0.0f),
                               .reflect = withW(m.reflect, 0.0f),
                               .transmit = withW(m.transmit, 0.0f)});
    for (const Light& l : scene.lights) {
        const float type = l.type == Light::Type::Point ? float(VKRAY_LIGHT_POINT)
                                                        : float(VKRAY_LIGHT_DIRECTIONAL);
        p.lights.push_back({.vectorType = withW(l.vector, type), .color = withW(l.color, 0.0f)});
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
