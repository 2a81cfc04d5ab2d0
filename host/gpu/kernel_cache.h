// The render kernels' pipelines, each created once per (kernel, variant, specialization) and kept
// from one render to the next: creating one costs the driver a translation and optimisation of the
// whole SPIR-V (docs/performance.md, "What lavapipe charges for"), as much as a small render, so the scenes
// of one call and the repeats of a benchmark share them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "accel/accel.h"
#include "frame/render_options.h"
#include "gpu/compute_kernel.h"
#include "gpu/shader_features.h"
#include "gpu/vulkan_context.h"
#include "scene/scene.h"

namespace vkray::gpu {

// The traversal whose kernel runs `traversal` on ctx's device: itself, but for `bvh-packet` and
// `kd-packet` on a device without subgroup ballot operations (their kernels' subgroupBroadcastFirst),
// which run `bvh`'s and `kd-stack`'s kernels: the same tree and the same hits, one ray a lane.
accel::Traversal kernelTraversal(const VulkanContext& ctx, accel::Traversal traversal);

// Renders that share a cache must not run at the same time (a kernel has one descriptor set).
class KernelCache {
public:
    explicit KernelCache(const VulkanContext& ctx);
    ~KernelCache();
    KernelCache(const KernelCache&) = delete;
    KernelCache& operator=(const KernelCache&) = delete;

    // The pipeline of the kernel that runs `traversal` (kernelTraversal()) for `features`: its SPIR-V variant (features.variant(): plain,
    // resumable, split texel views or both), specialised with features.specialization(). The
    // SPIR-V is the built-in one, or with VKRAY_KERNEL_DIR set the file from that folder, read once
    // per cache (kernel_registry.h).
    ComputeKernel& kernel(accel::Traversal traversal, const ShaderFeatures& features);
    size_t size() const { return kernels_.size(); }
    const VulkanContext& context() const { return ctx_; }

private:
    using Variant = std::pair<accel::Traversal, int>;  // the kernel, KernelVariant::index()
    std::span<const uint32_t> spirv(accel::Traversal traversal, KernelVariant variant);

    const VulkanContext& ctx_;
    std::map<Variant, std::vector<uint32_t>> spirvFromFiles_;
    std::map<std::pair<Variant, std::vector<std::pair<uint32_t, uint32_t>>>, std::unique_ptr<ComputeKernel>> kernels_;
};

// What the kernel of a render of `scene` with `options` on ctx's device is specialised with, for a
// structure whose largest leaf holds `maxLeafTriangles` (and, for kd-shortstack, whose stack holds
// `kdShortStack` entries; 0: the default; GpuAccelData's fields of the same names).
ShaderFeatures renderFeatures(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                              uint32_t maxLeafTriangles, uint32_t kdShortStack = 0);

// Creates in `kernels` the pipeline that a render of `scene` with `traversal` will use, so that the
// driver compiles it while the structure is built: the plain kernel's, the same whatever the
// structure's leaves (only the resumable variant's leaf loop depends on them). Returns the
// milliseconds it took.
double prepareKernel(const Scene& scene, const RenderOptions& options, accel::Traversal traversal, KernelCache& kernels);

}  // namespace vkray::gpu
