// The scene in the GPU layouts of shared/gpu_layout.h, uploaded to storage buffers.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/accel.h"
#include "gpu/buffer.h"
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
    Buffer triangles, normals, materials, lights;
    // VKRAY_BINDING_TRIANGLE_TEXELS, _NORMAL_TEXELS, _MATERIAL_TEXELS, _LIGHT_TEXELS
    TexelView triangleTexels, normalTexels, materialTexels, lightTexels;
    uint64_t bytes = 0;  // uploaded, for --stats
};

SceneBuffers uploadScene(const VulkanContext& ctx, const PackedScene& packed);

// Whether the scene's own buffers fit the device, checked before anything is built or packed: a
// scene too large for one storage buffer fails in milliseconds, not after a long build.
void checkSceneFits(const VulkanContext& ctx, const Scene& scene);

// The acceleration structure's arrays (accel::GpuAccelData), one buffer per binding.
struct AccelBuffers {
    Buffer nodes, indices, extra;
    TexelView nodeTexels, indexTexels, extraTexels;  // VKRAY_BINDING_NODE_TEXELS, _INDEX_TEXELS, _EXTRA_TEXELS
    uint64_t bytes = 0;
};

AccelBuffers uploadAccel(const VulkanContext& ctx, const accel::GpuAccelData& data);

}  // namespace vkray::gpu
