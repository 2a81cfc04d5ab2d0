// The Vulkan device of a render session, opened on a thread from the session's start, while the
// first scene loads (the loader, the driver and its compiler take a while to start), and kept for
// the scenes after it with the kernels' pipelines (gpu::KernelCache): a scene that needs the same
// kernel with the same features as an earlier one does not wait for its pipeline again. Its errors
// surface when it is first needed, after the first scene's own, as when it opened second.
#pragma once

#include <future>
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel_cache.h"
#include "gpu/vulkan_context.h"

namespace vkray::render {

class Device {
public:
    Device() = default;  // none: CPU renders, builds only
    // Starts opening `name` (an index or a name substring; empty: vkray's choice), with the
    // validation layer where the environment asks for it.
    explicit Device(const std::string& name);
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    // The device, once open (waits for it the first time); null without one.
    const gpu::VulkanContext* get();
    // Its pipelines; null until get() opened the device, or without one.
    gpu::KernelCache* kernels() { return kernels_ ? &*kernels_ : nullptr; }

private:
    std::future<std::unique_ptr<gpu::VulkanContext>> opening_;
    std::unique_ptr<gpu::VulkanContext> ctx_;
    std::optional<gpu::KernelCache> kernels_;  // destroyed before ctx_, whose device it uses
};

}  // namespace vkray::render
