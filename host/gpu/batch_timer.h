// The GPU time of a render: two timestamps around each submission's dispatches, their differences
// added up (GpuRenderReport::gpuMs), so that neither the host's waiting nor the copies count.
#pragma once

#include <cstdint>

#include <vulkan/vulkan_raii.hpp>

#include "gpu/vulkan_context.h"

namespace vkray::gpu {

class BatchTimer {
public:
    explicit BatchTimer(const VulkanContext& ctx);
    // Whether the queue has timestamps (else gpuMs stays -1).
    bool enabled() const { return mask_ != 0; }
    void begin(const vk::raii::CommandBuffer& cmd) const;
    void end(const vk::raii::CommandBuffer& cmd) const;
    // Milliseconds between the two stamps of the batch just waited for (0 when unavailable).
    double batchMs() const;

private:
    const VulkanContext& ctx_;
    uint64_t mask_ = 0;
    vk::raii::QueryPool queries_{nullptr};
};

}  // namespace vkray::gpu
