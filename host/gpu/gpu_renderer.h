// Renders a scene with the Vulkan compute kernel (shaders/render.comp): uploads the scene, specialises
// the kernel for what the scene needs, dispatches the image tile by tile, reads back colour and AOVs.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "gpu/shader_features.h"
#include "gpu/vulkan_context.h"
#include "render/frame.h"
#include "render/render_options.h"
#include "scene/scene.h"

namespace vkray::gpu {

struct GpuRenderReport {
    ShaderFeatures features;
    uint32_t tiles = 0;          // dispatches of at most VKRAY_TILE_SIZE^2 pixels
    uint32_t submissions = 0;    // batches of tiles submitted together
    uint64_t bytesUploaded = 0;
    double uploadMs = 0.0;       // scene buffers, host clock
    double pipelineMs = 0.0;     // kernel specialisation and pipeline creation, host clock
    double gpuMs = -1.0;         // sum of the batches' timestamp intervals; -1 without timestamps
    double renderMs = 0.0;       // dispatch to read-back done, host clock
    uint64_t raysTraced = 0;     // camera and secondary rays (shadow rays not counted)
    uint64_t pixelsCutShort = 0; // pixels whose loops the driver cut short (then renderOnGpu throws)
};

using TileProgress = std::function<void(uint32_t tilesDone, uint32_t tilesTotal)>;

// Accelerators the GPU path implements so far (the BVH and kd-tree issues add the others).
bool gpuSupportsAccel(const std::string& accel);

Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  GpuRenderReport* report = nullptr, const TileProgress& progress = {});

}  // namespace vkray::gpu
