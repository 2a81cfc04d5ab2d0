// Where the render kernels write their pixel records (VKRAY_BINDING_PIXELS) and where the host
// reads them. Where the host-readable memory is the device's own (lavapipe, integrated GPUs), that is
// one mapped buffer. On a discrete GPU it is not: the kernels' scattered writes would cross
// the bus one by one, so they write device-local memory and a copy moves each batch to the host in
// one transfer.
#pragma once

#include <optional>

#include <vulkan/vulkan_raii.hpp>

#include "gpu/buffer.h"
#include "gpu/vulkan_context.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

class PixelOutput {
public:
    // `forceCopy`: the discrete GPU's route on any device (for the tests).
    PixelOutput(const VulkanContext& ctx, vk::DeviceSize bytes, bool forceCopy = false);

    // The buffer the kernels write (bound as VKRAY_BINDING_PIXELS).
    const Buffer& target() const { return device_ ? *device_ : host_; }
    // Whether the kernels' writes reach the host through a copy.
    bool copied() const { return device_.has_value(); }
    // Records, after a batch's dispatches, what makes its first `bytes` readable by the host once the
    // submission's fence signals.
    void recordToHost(const vk::raii::CommandBuffer& cmd, vk::DeviceSize bytes) const;
    // The records as the host reads them: GpuPixel, or GpuPixelColor followed by GpuTileCounts
    // (render_main.glsl, "Pixel records").
    template <class Record>
    const Record* records() const { return static_cast<const Record*>(host_.mapped()); }

private:
    Buffer host_;
    std::optional<Buffer> device_;
};

}  // namespace vkray::gpu
