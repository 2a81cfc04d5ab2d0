// A buffer and the memory behind it, owned together (RAII). Scene data lives in
// device-local memory, filled through a staging copy unless the device-local memory is also
// host-visible (lavapipe, resizable BAR), in which case it is written in place.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

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
    // The device address of a buffer created with eShaderDeviceAddress usage; 0 otherwise.
    vk::DeviceAddress address() const { return address_; }

private:
    vk::raii::Buffer buffer_{nullptr};
    vk::raii::DeviceMemory memory_{nullptr};
    vk::DeviceSize size_ = 0;
    void* mapped_ = nullptr;  // persistently mapped when host-visible; unmapped by vkFreeMemory
    bool deviceLocal_ = false;
    vk::DeviceAddress address_ = 0;
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

// A device-local buffer of `usage` holding `bytes` of `data` (written in place where the memory is
// host-visible, else through a staging copy). Throws naming `what` when it cannot be allocated.
Buffer uploadBuffer(const VulkanContext& ctx, const void* data, size_t bytes, vk::BufferUsageFlags usage,
                    const std::string& what);

// A read-only view of a buffer as a uniform texel buffer of `format` (RAII): the kernels fetch their
// hot data through these (shared/gpu_layout.h, "Texel views").
class TexelView {
public:
    TexelView() = default;
    // Throws vkray::Error naming `what` when the buffer holds more texels than one view may
    // (maxTexelBufferElements).
    TexelView(const VulkanContext& ctx, const Buffer& buffer, vk::Format format, uint32_t texelBytes,
              const std::string& what);
    vk::BufferView handle() const { return *view_; }

private:
    vk::raii::BufferView view_{nullptr};
};

// The most texels one array the kernels read may have on this device: VKRAY_TEXEL_VIEWS views of
// the largest power of two of texels one view may hold (maxTexelBufferElements).
uint64_t maxTexelArray(const VulkanContext& ctx);

// Throws vkray::Error naming `what` when `texels` exceed maxTexelArray(ctx), checked before
// anything is allocated.
void checkTexelArrayFits(const VulkanContext& ctx, uint64_t texels, const std::string& what);

// An array the kernels read, by name (for errors) and length in texels.
struct TexelArraySize {
    std::string what;
    uint64_t texels = 0;
};

// How a render's arrays are viewed (VKRAY_SPEC_TEXEL_VIEW_BITS): 0 when each fits one view, else
// log2 of the texels of every view, the largest power of two maxTexelBufferElements allows. Throws as
// checkTexelArrayFits does for an array too long for VKRAY_TEXEL_VIEWS such views.
int texelViewBits(const VulkanContext& ctx, std::span<const TexelArraySize> arrays);

// A read-only array of the kernels in device-local memory, as one texel view or, split, as several
// views of 2^viewBits texels, each over a buffer of its own (one allocation may hold no more than
// one view on some devices: 2 GiB on lavapipe). Read only through the views, so its size is bounded
// by maxTexelArray(), not by maxStorageBufferRange (128 MiB on lavapipe).
struct TexelArray {
    std::vector<Buffer> buffers;
    std::vector<TexelView> views;  // at least one
};

// Uploads `bytes` (a whole number of `texelBytes` texels; at least one texel is allocated so an empty
// array still binds) and makes its views (texelViewBits: 0 = one view). Throws as
// checkTexelArrayFits does, or naming `what` when the memory cannot be allocated.
TexelArray uploadTexelArray(const VulkanContext& ctx, const void* data, size_t bytes, vk::Format format,
                            uint32_t texelBytes, const std::string& what, int viewBits = 0);

}  // namespace vkray::gpu
