#include "render/device.h"

#include <stdexcept>

#include "gpu/gpu_renderer.h"
#include "gpu/scene_buffers.h"

namespace vkray::render {

Device::Device(const std::string& name, bool rayQuery)
    : Device(gpu::ContextOptions{
          .validation = gpu::validationRequestedByEnvironment(), .device = name, .rayQuery = rayQuery}) {}

Device::Device(gpu::ContextOptions options) {
    opening_ = std::async(std::launch::async,
                          [options = std::move(options)] { return std::make_unique<gpu::VulkanContext>(options); });
}

Device::~Device() = default;

const gpu::VulkanContext* Device::get() {
    if (opening_.valid()) {
        ctx_ = opening_.get();
        kernels_.emplace(*ctx_);
    }
    return ctx_.get();
}

const gpu::VulkanContext& Device::opened() {
    const gpu::VulkanContext* ctx = get();
    if (!ctx) throw std::logic_error("render::Device: used without a device (a CPU render or a build alone)");
    return *ctx;
}

const gpu::VulkanContext& Device::checkFits(const SceneSize& scene, MemoryUse use, MemoryReport* memory) {
    const gpu::VulkanContext& ctx = opened();
    gpu::checkSceneFits(ctx, scene.triangles, scene.normals);
    use.deviceSharesHost = ctx.info().type == "cpu";
    MemoryLimits limits = hostMemoryLimits();
    if (ctx.info().deviceLocalBudget > 0) limits.deviceHeap = ctx.info().deviceLocalBudget;
    const MemoryReport report = checkSceneMemory(scene, use, limits);
    if (memory) *memory = report;
    return ctx;
}

Frame Device::render(const Scene& scene, const RenderOptions& options, const accel::GpuAccelData& data,
                     gpu::GpuRenderReport& report, const gpu::TileProgress& progress) {
    const gpu::VulkanContext& ctx = opened();
    return gpu::renderOnGpu(ctx, scene, options, data, &report, progress, &*kernels_);
}

}  // namespace vkray::render
