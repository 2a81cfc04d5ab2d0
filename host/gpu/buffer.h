// A buffer and the memory behind it, owned together (RAII). Scene data lives in
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
    // Whether the memory is the device's own (on lavapipe and integrated GPUs, also the host's).
    bool deviceLocal() const { return deviceLocal_; }
    void* mapped() const { return mapped_; }

private:
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::DeviceSize size_ = 0;
    void* mapped_ = nullptr;  // persistently mapped when host-visible; unmapped by vkFreeMemory
    bool deviceLocal_ = false;
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

// Throws vkray::Error naming `what` when `texels` exceed the device's maxTexelBufferElements: the
// limit on one array the kernels read (a texel view), checked before anything is allocated.
void checkTexelArrayFits(const VulkanContext& ctx, uint64_t texels, const std::string& what);

// A read-only array of the kernels in device-local memory, with its texel view. Read only through
// the view, so its size is bounded by maxTexelBufferElements texels (2 GiB of 16-byte texels on
// lavapipe and most GPUs), not by maxStorageBufferRange (128 MiB on lavapipe).
struct TexelArray {
    Buffer buffer;
    TexelView view;
};

// Uploads `bytes` (a whole number of `texelBytes` texels; at least one texel is allocated so an empty
// array still binds) and makes its view. Throws as checkTexelArrayFits does, or naming `what` when
// the memory cannot be allocated.
TexelArray uploadTexelArray(const VulkanContext& ctx, const void* data, size_t bytes, vk::Format format,
                            uint32_t texelBytes, const std::string& what);

}  // namespace vkray::gpu
