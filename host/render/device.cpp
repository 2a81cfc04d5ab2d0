#include "render/device.h"

namespace vkray::render {

Device::Device(const std::string& name) {
    opening_ = std::async(std::launch::async, [name] {
        return std::make_unique<gpu::VulkanContext>(
            gpu::ContextOptions{.validation = gpu::validationRequestedByEnvironment(), .device = name});
    });
}

Device::~Device() = default;

const gpu::VulkanContext* Device::get() {
    if (opening_.valid()) {
        ctx_ = opening_.get();
        kernels_.emplace(*ctx_);
    }
    return ctx_.get();
}

}  // namespace vkray::render
