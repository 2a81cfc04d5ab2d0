// The scene in the GPU layouts of shared/gpu_layout.h, uploaded as the kernels' texel arrays.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "accel/accel.h"
#include "gpu/buffer.h"
#include "gpu/driver_structure.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

// Host-side arrays in GPU layout (separate from the upload so they can be tested without a device).
struct PackedScene {
    std::vector<GpuTriangle> triangles;
    std::vector<GpuTriangleNormals> normals;  // empty without smooth normals
    std::vector<GpuMaterial> materials;
    std::vector<GpuLight> lights;
};

// Triangles (and their vertex normals) go into slot k in the order `triangleOrder` gives (an
// accelerator's leaf order; empty = scene order); GpuTriangle.original keeps the identity.
PackedScene packScene(const Scene& scene, const std::vector<uint32_t>& triangleOrder = {});

struct SceneBuffers {
    // VKRAY_BINDING_TRIANGLE_TEXELS, _NORMAL_TEXELS, _MATERIAL_TEXELS, _LIGHT_TEXELS
    TexelArray triangles, normals, materials, lights;
    uint64_t bytes = 0;  // uploaded, for --stats
};

// With `viewBits` (texelViewBits of texelArraySizes) the arrays are split over views of 2^viewBits
// texels; 0: one view each.
SceneBuffers uploadScene(const VulkanContext& ctx, const PackedScene& packed, int viewBits = 0);

// Whether the own arrays of a scene of `triangles` triangles, `normals` of them with vertex normals,
// fit the device's texel views, checked before anything is built or packed: a scene too large
// fails in milliseconds, not after a long build.
void checkSceneFits(const VulkanContext& ctx, uint64_t triangles, uint64_t normals);

// The acceleration structure's arrays (accel::GpuAccelData), one texel view per binding, and for
// rayquery the driver's structure (VKRAY_BINDING_SCENE_STRUCTURE), built by the caller.
struct AccelBuffers {
    TexelArray nodes, indices, extra;  // VKRAY_BINDING_NODE_TEXELS, _INDEX_TEXELS, _EXTRA_TEXELS
    std::optional<DriverStructure> driver;
    uint64_t bytes = 0;
};

// For rayquery, the driver builds its structure over `packed`'s triangles here.
AccelBuffers uploadAccel(const VulkanContext& ctx, const accel::GpuAccelData& data, const PackedScene& packed,
                         int viewBits = 0);

// The lengths of every texel array a render of `packed` with `accel` binds, for texelViewBits.
std::vector<TexelArraySize> texelArraySizes(const PackedScene& packed, const accel::GpuAccelData& accel);

}  // namespace vkray::gpu
