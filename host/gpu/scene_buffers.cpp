#include "gpu/scene_buffers.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/parallel_alloc.h"
#include "geometry/ray_triangle.h"

namespace vkray::gpu {
namespace {

vec4 withW(const glm::vec3& v, float w) { return vec4(v, w); }

constexpr vk::Format kRgba32 = vk::Format::eR32G32B32A32Uint;

template <class T>
TexelArray uploadVector(const VulkanContext& ctx, const std::vector<T>& v, vk::Format format, uint32_t texelBytes,
                        const std::string& what, int viewBits) {
    return uploadTexelArray(ctx, v.data(), v.size() * sizeof(T), format, texelBytes, what, viewBits);
}

template <class T>
TexelArraySize sizeOf(const std::vector<T>& v, uint32_t texelBytes, const std::string& what) {
    return {what, uint64_t(v.size()) * sizeof(T) / texelBytes};
}

// The arrays' names in errors, one per binding.
const char* const kTriangles = "triangles";
const char* const kNormals = "vertex normals";
const char* const kMaterials = "materials";
const char* const kLights = "lights";
const char* const kNodes = "acceleration-structure nodes";
const char* const kIndices = "acceleration-structure triangle indices";
const char* const kExtra = "acceleration-structure extra data";

// An order must be a permutation of the scene's triangles: a builder bug must not become a
// kernel reading past a buffer.
void checkPermutation(const std::vector<uint32_t>& order, size_t count) {
    if (order.size() != count)
        throw Error("internal: accelerator triangle order has " + std::to_string(order.size()) +
                    " entries for " + std::to_string(count) + " triangles");
    std::vector<bool> seen(count, false);
    for (uint32_t k : order) {
        if (k >= count || seen[k])
            throw Error("internal: accelerator triangle order is not a permutation (entry " +
                        std::to_string(k) + ")");
        seen[k] = true;
    }
}

vk::Format uintTexelFormat(uint32_t bytes) {
    switch (bytes) {
        case 4: return vk::Format::eR32Uint;
        case 8: return vk::Format::eR32G32Uint;
        case 16: return vk::Format::eR32G32B32A32Uint;
        default: throw Error("internal: no texel format of " + std::to_string(bytes) + " bytes");
    }
}

}  // namespace

PackedScene packScene(const Scene& scene, const std::vector<uint32_t>& triangleOrder) {
    const size_t count = scene.triangles.size();
    if (!triangleOrder.empty()) checkPermutation(triangleOrder, count);
    const auto sceneIndex = [&](size_t slot) { return triangleOrder.empty() ? slot : triangleOrder[slot]; };
    PackedScene p;
    // Slot by slot on all workers, into arrays whose pages they populate first: a scene of tens of
    // millions of triangles packs gigabytes.
    sizeForParallelWrite(p.triangles, count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t slot = r.begin(); slot < r.end(); ++slot) {
            const size_t i = sceneIndex(slot);
            const Triangle& t = scene.triangles[i];
            // A zero-area triangle is never hit (docs/shading.md), but collinear float vertices can
            // still give the kernels' float edge functions a non-zero det. Decided once here, exactly,
            // by the CPU's test (the kd builder leaves the same triangles out): such a triangle
            // becomes the point p0, whose edge functions are exactly 0 in any arithmetic.
            const bool degenerate = geometry::isDegenerate({glm::dvec3(t.p0), glm::dvec3(t.p1), glm::dvec3(t.p2)});
            p.triangles[slot] = {.p0 = t.p0, .material = t.material, .p1 = degenerate ? t.p0 : t.p1,
                                 .original = uint32_t(i), .p2 = degenerate ? t.p0 : t.p2, .pad0 = 0};
        }
    });
    if (!scene.normals.empty()) {
        if (scene.normals.size() != count) throw Error("internal: the scene has normals for some triangles only");
        sizeForParallelWrite(p.normals, count);
        tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t slot = r.begin(); slot < r.end(); ++slot) {
                const TriangleNormals& n = scene.normals[sceneIndex(slot)];
                p.normals[slot] = {withW(n.n0, 0.0f), withW(n.n1, 0.0f), withW(n.n2, 0.0f)};
            }
        });
    }
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

SceneBuffers uploadScene(const VulkanContext& ctx, const PackedScene& packed, int viewBits) {
    SceneBuffers b{uploadVector(ctx, packed.triangles, kRgba32, 16, kTriangles, viewBits),
                   uploadVector(ctx, packed.normals, kRgba32, 16, kNormals, viewBits),
                   uploadVector(ctx, packed.materials, kRgba32, 16, kMaterials, viewBits),
                   uploadVector(ctx, packed.lights, kRgba32, 16, kLights, viewBits), 0};
    b.bytes = packed.triangles.size() * sizeof(GpuTriangle) +
              packed.normals.size() * sizeof(GpuTriangleNormals) +
              packed.materials.size() * sizeof(GpuMaterial) + packed.lights.size() * sizeof(GpuLight);
    return b;
}

void checkSceneFits(const VulkanContext& ctx, const Scene& scene) {
    checkTexelArrayFits(ctx, uint64_t(scene.triangles.size()) * VKRAY_TRIANGLE_TEXELS, kTriangles);
    checkTexelArrayFits(ctx, uint64_t(scene.normals.size()) * VKRAY_NORMAL_TEXELS, kNormals);
}

AccelBuffers uploadAccel(const VulkanContext& ctx, const accel::GpuAccelData& data, int viewBits) {
    AccelBuffers b{uploadVector(ctx, data.nodes, uintTexelFormat(data.nodeTexelBytes), data.nodeTexelBytes, kNodes, viewBits),
                   uploadVector(ctx, data.indices, vk::Format::eR32Uint, 4, kIndices, viewBits),
                   uploadVector(ctx, data.extra, kRgba32, 16, kExtra, viewBits), 0};
    b.bytes = data.bytes();
    return b;
}

std::vector<TexelArraySize> texelArraySizes(const PackedScene& packed, const accel::GpuAccelData& accel) {
    return {sizeOf(packed.triangles, 16, kTriangles), sizeOf(packed.normals, 16, kNormals),
            sizeOf(packed.materials, 16, kMaterials), sizeOf(packed.lights, 16, kLights),
            sizeOf(accel.nodes, accel.nodeTexelBytes, kNodes), sizeOf(accel.indices, 4, kIndices),
            sizeOf(accel.extra, 16, kExtra)};
}

}  // namespace vkray::gpu
