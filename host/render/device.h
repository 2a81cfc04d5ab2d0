// The Vulkan device of a render session, opened on a thread from the session's start, while the
// first scene loads (the loader, the driver and its compiler take a while to start), and kept for
// the scenes after it with the kernels' pipelines (gpu::KernelCache): a scene that needs the same
// kernel with the same features as an earlier one does not wait for its pipeline again. Its errors
// surface when it is first needed, after the first scene's own, as when it opened second. Used by the
// render session and by `vkray bench`, which renders each structure many times.
#pragma once

#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "accel/accel.h"
#include "frame/frame.h"
#include "gpu/gpu_render_report.h"
#include "gpu/kernel_cache.h"
#include "gpu/vulkan_context.h"
#include "render/memory_budget.h"
#include "scene/scene.h"

namespace vkray::render {

class Device {
public:
    Device() = default;  // none: CPU renders, builds only
    // Starts opening `name` (an index or a name substring; empty: vkray's choice), with the
    // validation layer where the environment asks for it and, with `rayQuery`, the driver's ray
    // tracing (`--accel rayquery`; a device without it fails when first needed).
    explicit Device(const std::string& name, bool rayQuery = false);
    // Starts opening the device `options` name, with its validation setting (the tests: always).
    explicit Device(gpu::ContextOptions options);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // The device, once open (waits for it the first time); null without one.
    const gpu::VulkanContext* get();
    // Its pipelines; null until get() opened the device, or without one.
    gpu::KernelCache* kernels() { return kernels_ ? &*kernels_ : nullptr; }

    // The opened device (get()), after checking that `scene` fits its limits (gpu::checkSceneFits)
    // and that a render of it as `use` says fits the device's memory and the host's
    // (checkSceneMemory, whose estimate goes to `memory` when given); throws vkray::Error: before a
    // long build, not after it. Needs a device.
    const gpu::VulkanContext& checkFits(const SceneSize& scene, MemoryUse use = gpuRender(),
                                        MemoryReport* memory = nullptr);
    const gpu::VulkanContext& checkFits(const Scene& scene, MemoryUse use = gpuRender(), MemoryReport* memory = nullptr) {
        return checkFits(sizeOf(scene), std::move(use), memory);
    }
    // A frame of `scene` traced through the structure arrays `data` with this device's pipelines
    // (gpu::renderOnGpu); `report` gets the GPU's figures. Needs a device.
    Frame render(const Scene& scene, const RenderOptions& options, const accel::GpuAccelData& data,
                 gpu::GpuRenderReport& report, const gpu::TileProgress& progress = {});

private:
    const gpu::VulkanContext& opened();

    std::future<std::unique_ptr<gpu::VulkanContext>> opening_;
    std::unique_ptr<gpu::VulkanContext> ctx_;
    std::optional<gpu::KernelCache> kernels_;  // destroyed before ctx_, whose device it uses
};

}  // namespace vkray::render
