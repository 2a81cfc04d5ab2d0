// Renders a scene with a Vulkan compute kernel (shaders/render_<kernel>.comp, one per accelerator):
// uploads the scene and the built structure, specialises the kernel for what the scene needs,
// dispatches the image tile by tile and reads back colour and AOVs.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "frame/frame.h"
#include "frame/render_options.h"
#include "gpu/compute_kernel.h"
#include "gpu/shader_features.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace vkray::gpu {

struct GpuRenderReport {
    std::string kernel;          // shaders/render_<kernel>.comp (accel::kernelName)
    ShaderFeatures features;
    uint32_t tiles = 0;          // dispatches of at most VKRAY_TILE_SIZE^2 pixels
    uint32_t submissions = 0;    // batches of tiles submitted together
    uint64_t bytesUploaded = 0;
    double uploadMs = 0.0;       // scene buffers, host clock
    double pipelineMs = 0.0;     // kernel specialisation and pipeline creation, host clock
    // Pipelines this render created in its KernelCache; 0 when every one it used was there already
    // (an earlier scene's: the render command keeps one cache for all its scenes).
    uint32_t pipelinesCreated = 0;
    double gpuMs = -1.0;         // sum of the batches' timestamp intervals; -1 without timestamps
    double renderMs = 0.0;       // dispatch to read-back done, host clock
    uint64_t accelBytes = 0;     // of bytesUploaded, the acceleration structure's
    uint64_t raysTraced = 0;     // camera and secondary rays (closest hit)
    uint64_t shadowRays = 0;     // any-hit rays
    uint64_t cappedRays = 0;     // rays a traversal ended at its iteration cap (reported, not hidden)
    uint64_t pixelsCutShort = 0; // pixels whose loops the driver cut short (then renderOnGpu throws)
    // Tiles the plain kernel could not finish within the driver's loop budget, rendered again by the
    // resumable variant in strips of resumeRows rows, and that variant's dispatches.
    uint32_t resumedTiles = 0, resumeRows = 0, resumeDispatches = 0;
    bool resumedFromStart = false;  // every tile resumable at once (brute force beyond one budget)
    // Traversal work over all rays; filled only with RenderOptions::countTraversal.
    uint64_t nodesVisited = 0, leavesVisited = 0, trianglesTested = 0, restarts = 0;
    // The node steps the device's subgroups run in lock-step (lockstep.h): nodesVisited over this is
    // the SIMD efficiency. A lower bound where a pixel traces several rays (its lanes need not be
    // at the same ray); filled only with RenderOptions::countTraversal.
    uint64_t lockstepNodes = 0;
    uint32_t lockstepLanes = 0;  // the subgroup size it assumes
    // Nodes visited by all rays of each pixel, top row first (a traversal-cost heatmap); filled
    // only with RenderOptions::countTraversal.
    std::vector<uint32_t> nodesPerPixel;
};

using TileProgress = std::function<void(uint32_t tilesDone, uint32_t tilesTotal)>;

// Render pipelines kept from one render to the next. Creating one costs 25-60 ms on lavapipe (Mesa
// translates and optimises the SPIR-V; LLVM compiles it at the first dispatch, 0.3 s unless Mesa's
// disk cache has it), as much as a small render: a benchmark that renders each configuration
// several times creates each (kernel, specialization) pipeline once. Renders that share a cache
// must not run at the same time (a kernel has one descriptor set).
class KernelCache {
public:
    explicit KernelCache(const VulkanContext& ctx);
    ~KernelCache();
    KernelCache(const KernelCache&) = delete;
    KernelCache& operator=(const KernelCache&) = delete;

    // The pipeline of `kernel` for `features`: its SPIR-V variant (features.variant(): plain,
    // resumable, split texel views or both), specialised with features.specialization(). The
    // SPIR-V is the built-in one, or with VKRAY_KERNEL_DIR set render_<kernel>[_resumable][_split].spv
    // from that folder, read once per cache.
    ComputeKernel& kernel(accel::Kernel kernel, const ShaderFeatures& features);
    size_t size() const { return kernels_.size(); }
    const VulkanContext& context() const { return ctx_; }

private:
    using Variant = std::pair<accel::Kernel, int>;  // the kernel, KernelVariant::index()
    std::span<const uint32_t> spirv(accel::Kernel kernel, KernelVariant variant);

    const VulkanContext& ctx_;
    std::map<Variant, std::vector<uint32_t>> spirvFromFiles_;
    std::map<std::pair<Variant, std::vector<std::pair<uint32_t, uint32_t>>>, std::unique_ptr<ComputeKernel>> kernels_;
};

// What the kernel of a render of `scene` with `options` on ctx's device is specialised with, for a
// structure whose largest leaf holds `maxLeafTriangles` (and, for kd-shortstack, whose stack holds
// `kdShortStack` entries; 0: the default; GpuAccelData's fields of the same names).
ShaderFeatures renderFeatures(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                              uint32_t maxLeafTriangles, uint32_t kdShortStack = 0);

// Creates in `kernels` the pipeline that a render of `scene` with `kernel` will use, so that the
// driver compiles it while the structure is built: the plain kernel's, the same whatever the
// structure's leaves (only the resumable variant's leaf loop depends on them). Returns the
// milliseconds it took.
double prepareKernel(const Scene& scene, const RenderOptions& options, accel::Kernel kernel, KernelCache& kernels);

// Renders with an acceleration structure already built (accel::buildAccel(...)->gpuData()).
Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::GpuAccelData& accel, GpuRenderReport* report = nullptr,
                  const TileProgress& progress = {}, KernelCache* kernels = nullptr);

// Builds `spec` first (options.threads workers), then renders: the form tests use.
Frame renderOnGpu(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                  const accel::AccelSpec& spec, GpuRenderReport* report = nullptr,
                  const TileProgress& progress = {});

}  // namespace vkray::gpu
