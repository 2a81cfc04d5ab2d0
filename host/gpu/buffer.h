// A storage buffer and the memory behind it, owned together (RAII). Scene data lives in
// device-local memory, filled through a staging copy unless the device-local memory is also
// host-visible (lavapipe, resizable BAR), in which case it is written in place.
#pragma once

#include <cstddef>
#include <string>

#include <vulkan/vulkan_raii.hpp>

#include "gpu/vulkan_context.h"

namespace vkray::gpu {

enum class MemoryUse {
    DeviceLocal,  // fastest for the kernels
    Upload,       // host-visible, host-coherent: staging
    Readback,     // host-visible, preferably host-cached: results
};

class Buffer {
public:
    // `what` names the contents for error messages ("triangles", "pixels").
    Buffer(const VulkanContext& ctx, vk::DeviceSize size, vk::BufferUsageFlags usage, MemoryUse use,
           const std::string& what);

    vk::Buffer handle() const { return *buffer_; }
    vk::DeviceSize size() const { return size_; }
    bool hostVisible() const { return mapped_ != nullptr; }
    void* mapped() const { return mapped_; }

private:
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::DeviceSize size_ = 0;
    void* mapped_ = nullptr;  // persistently mapped when host-visible; unmapped by vkFreeMemory
};

// Records commands into a fresh primary command buffer, submits them and waits on a fence.
class OneShotCommands {
public:
    explicit OneShotCommands(const VulkanContext& ctx);
    const vk::raii::CommandBuffer& begin();
    void submitAndWait();

private:
    const VulkanContext& ctx_;
    vk::raii::CommandPool pool_{nullptr};
    vk::raii::CommandBuffer cmd_{nullptr};
};

// A read-only view of a buffer as a uniform texel buffer of `format` (RAII): the kernels fetch their
// hot data through these (shared/gpu_layout.h, "Texel views").
class TexelView {
public:
    TexelView() = default;
    // Throws vkray::Error naming `what` when the buffer holds more texels than the device's
    // maxTexelBufferElements.
    TexelView(const VulkanContext& ctx, const Buffer& buffer, vk::Format format, uint32_t texelBytes,
              const std::string& what);
    vk::BufferView handle() const { return *view_; }

private:
    vk::raii::BufferView view_{nullptr};
};

// Throws vkray::Error naming `what` when `bytes` exceed the device's maxStorageBufferRange.
void checkStorageBufferFits(const VulkanContext& ctx, size_t bytes, const std::string& what);

// A device-local storage buffer holding a copy of `bytes` (at least 16 bytes are allocated so an
// empty array still binds). Throws as checkStorageBufferFits does.
Buffer uploadStorageBuffer(const VulkanContext& ctx, const void* data, size_t bytes,
                           const std::string& what);

}  // namespace vkray::gpu
