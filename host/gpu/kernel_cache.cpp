#include "gpu/kernel_cache.h"

#include "core/timing.h"
#include "gpu/kernel_bindings.h"
#include "gpu/kernel_registry.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

accel::Traversal kernelTraversal(const VulkanContext& ctx, accel::Traversal traversal) {
    if (ctx.info().subgroupBallot) return traversal;
    if (traversal == accel::Traversal::BvhPacket) return accel::Traversal::Bvh;
    if (traversal == accel::Traversal::KdPacket) return accel::Traversal::KdStack;
    return traversal;
}

KernelCache::KernelCache(const VulkanContext& ctx) : ctx_(ctx) {}
KernelCache::~KernelCache() = default;

std::span<const uint32_t> KernelCache::spirv(accel::Traversal traversal, KernelVariant variant) {
    const std::pair key{traversal, variant.index()};
    auto it = spirvFromFiles_.find(key);
    if (it == spirvFromFiles_.end()) it = spirvFromFiles_.emplace(key, kernelFromDir(traversal, variant)).first;
    if (!it->second.empty()) return it->second;
    return builtInKernel(traversal, variant);
}

ComputeKernel& KernelCache::kernel(accel::Traversal traversal, const ShaderFeatures& features) {
    traversal = kernelTraversal(ctx_, traversal);
    const Specialization spec = features.specialization();
    const KernelVariant variant = features.variant();
    auto& slot = kernels_[{{traversal, variant.index()}, spec.values}];
    if (!slot)
        slot = std::make_unique<ComputeKernel>(ctx_, spirv(traversal, variant), renderKernelBindings(traversal),
                                               sizeof(GpuFrameParams), spec);
    return *slot;
}

ShaderFeatures renderFeatures(const VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                              uint32_t maxLeafTriangles, uint32_t kdShortStack) {
    ShaderFeatures f = ShaderFeatures::forScene(scene, options.maxDepth);
    f.pixelsPerInvocation = int(ctx.info().pixelsPerInvocation);
    f.countTraversal = options.countTraversal;
    f.primaryAovs = options.primaryAovs;
    f.setMaxLeafTriangles(maxLeafTriangles);
    f.setKdShortStack(kdShortStack);
    return f;
}

double prepareKernel(const Scene& scene, const RenderOptions& options, accel::Traversal traversal, KernelCache& kernels) {
    const auto start = Clock::now();
    kernels.kernel(traversal, renderFeatures(kernels.context(), scene, options, 1));
    return msSince(start);
}

}  // namespace vkray::gpu
