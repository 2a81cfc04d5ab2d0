#include "gpu/scene_buffers.h"

#include <array>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/parallel_alloc.h"
#include "geometry/ray_triangle.h"

namespace vkray::gpu {
namespace {

vec4 withW(const glm::vec3& v, float w) { return vec4(v, w); }

constexpr vk::Format kRgba32 = vk::Format::eR32G32B32A32Uint;

// One texel array of a render: its bytes and how the kernels read them. The one place that says
// which format and texel size each binding has, for both its upload and texelArraySizes.
struct ArrayBytes {
    const void* data;
    size_t bytes;
    vk::Format format;
    uint32_t texelBytes;
    const char* what;  // the array's name in errors

    TexelArray upload(const VulkanContext& ctx, int viewBits) const {
        return uploadTexelArray(ctx, data, bytes, format, texelBytes, what, viewBits);
    }
    TexelArraySize size() const { return {what, uint64_t(bytes / texelBytes)}; }
};

template <class T>
ArrayBytes arrayOf(const std::vector<T>& v, vk::Format format, uint32_t texelBytes, const char* what) {
    return {v.data(), v.size() * sizeof(T), format, texelBytes, what};
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

// The bindings' arrays, in SceneBuffers' and AccelBuffers' order.
std::array<ArrayBytes, 4> sceneArrays(const PackedScene& p) {
    return {arrayOf(p.triangles, kRgba32, 16, kTriangles), arrayOf(p.normals, kRgba32, 16, kNormals),
            arrayOf(p.materials, kRgba32, 16, kMaterials), arrayOf(p.lights, kRgba32, 16, kLights)};
}
std::array<ArrayBytes, 3> accelArrays(const accel::GpuAccelData& d) {
    return {arrayOf(d.nodes, uintTexelFormat(d.nodeTexelBytes), d.nodeTexelBytes, kNodes),
            arrayOf(d.indices, vk::Format::eR32Uint, 4, kIndices), arrayOf(d.extra, kRgba32, 16, kExtra)};
}

}  // namespace

PackedScene packScene(const Scene& scene, const std::vector<uint32_t>& triangleOrder) {
    const size_t count = scene.triangles.size();
    if (!triangleOrder.empty()) checkPermutation(triangleOrder, count);
    const auto sceneIndex = [&](size_t slot) { return triangleOrder.empty() ? slot : triangleOrder[slot]; };
    PackedScene p;
    // Slot by slot on all workers, into arrays whose pages they populate first: a scene of tens of
    // millions of triangles packs gigabytes.
    const bool smooth = !scene.normals.empty();
    if (smooth && scene.normals.size() != count) throw Error("internal: the scene has normals for some triangles only");
    resizeFirstTouched(p.triangles, count);
    if (smooth) resizeFirstTouched(p.normals, count);
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
            if (smooth) {
                const TriangleNormals& n = scene.normals[i];
                p.normals[slot] = {withW(n.n0, 0.0f), withW(n.n1, 0.0f), withW(n.n2, 0.0f)};
            }
        }
    });
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
    const auto a = sceneArrays(packed);
    SceneBuffers b{a[0].upload(ctx, viewBits), a[1].upload(ctx, viewBits), a[2].upload(ctx, viewBits),
                   a[3].upload(ctx, viewBits), 0};
    for (const ArrayBytes& array : a) b.bytes += array.bytes;
    return b;
}

void checkSceneFits(const VulkanContext& ctx, uint64_t triangles, uint64_t normals) {
    checkTexelArrayFits(ctx, triangles * VKRAY_TRIANGLE_TEXELS, kTriangles);
    checkTexelArrayFits(ctx, normals * VKRAY_NORMAL_TEXELS, kNormals);
}

AccelBuffers uploadAccel(const VulkanContext& ctx, const accel::GpuAccelData& data, const PackedScene& packed,
                         int viewBits) {
    const auto a = accelArrays(data);
    AccelBuffers b{a[0].upload(ctx, viewBits), a[1].upload(ctx, viewBits), a[2].upload(ctx, viewBits), std::nullopt, 0};
    b.bytes = data.bytes();
    if (data.traversal == accel::Traversal::RayQuery) {
        b.driver.emplace(ctx, packed.triangles, data.driverBuild);
        b.bytes += b.driver->bytes();
    }
    return b;
}

std::vector<TexelArraySize> texelArraySizes(const PackedScene& packed, const accel::GpuAccelData& accel) {
    std::vector<TexelArraySize> sizes;
    for (const ArrayBytes& a : sceneArrays(packed)) sizes.push_back(a.size());
    for (const ArrayBytes& a : accelArrays(accel)) sizes.push_back(a.size());
    return sizes;
}

}  // namespace vkray::gpu
