// The scene in the GPU layouts of shared/gpu_layout.h, uploaded to storage buffers.
#pragma once

#include <cstdint>
#include <vector>

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

PackedScene packScene(const Scene& scene);

struct SceneBuffers {
    Buffer triangles, normals, materials, lights;
    uint64_t bytes = 0;  // uploaded, for --stats
};

SceneBuffers uploadScene(const VulkanContext& ctx, const PackedScene& packed);

}  // namespace vkray::gpu
