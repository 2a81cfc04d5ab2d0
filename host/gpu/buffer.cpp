#include "gpu/buffer.h"

#include <algorithm>
#include <cstring>

#include "core/error.h"

namespace vkray::gpu {
namespace {

std::string mib(vk::DeviceSize bytes) {
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

}  // namespace

Buffer::Buffer(const VulkanContext& ctx, vk::DeviceSize size, vk::BufferUsageFlags usage,
               MemoryUse use, const std::string& what)
    : size_(size) {
    using MP = vk::MemoryPropertyFlagBits;
    const auto& dev = ctx.device();
    buffer_ = vk::raii::Buffer(dev, vk::BufferCreateInfo{.size = size, .usage = usage,
                                                         .sharingMode = vk::SharingMode::eExclusive});
    const vk::MemoryRequirements req = buffer_.getMemoryRequirements();
    vk::MemoryPropertyFlags required, preferred;
    switch (use) {
        case MemoryUse::DeviceLocal: required = MP::eDeviceLocal; break;
        case MemoryUse::Upload: required = MP::eHostVisible | MP::eHostCoherent; break;
        case MemoryUse::Readback:
            required = MP::eHostVisible | MP::eHostCoherent;
            preferred = MP::eHostCached;
            break;
    }
    const uint32_t type = ctx.findMemoryType(req.memoryTypeBits, required, preferred);
    try {
        memory_ = vk::raii::DeviceMemory(dev, vk::MemoryAllocateInfo{.allocationSize = req.size,
                                                                     .memoryTypeIndex = type});
    } catch (const vk::SystemError& e) {
        throw Error("cannot allocate " + mib(size) + " of GPU memory for " + what + " on '" +
                    ctx.info().name + "': " + e.what());
    }
    buffer_.bindMemory(*memory_, 0);
    auto flags = ctx.physicalDevice().getMemoryProperties().memoryTypes[type].propertyFlags;
    deviceLocal_ = bool(flags & MP::eDeviceLocal);
    // Only coherent memory is written in place: it needs no flush/invalidate calls.
    if ((flags & MP::eHostVisible) && (flags & MP::eHostCoherent))
        mapped_ = memory_.mapMemory(0, VK_WHOLE_SIZE);
}

OneShotCommands::OneShotCommands(const VulkanContext& ctx) : ctx_(ctx) {
    pool_ = vk::raii::CommandPool(ctx.device(),
                                  vk::CommandPoolCreateInfo{.flags = vk::CommandPoolCreateFlagBits::eTransient,
                                                            .queueFamilyIndex = ctx.queueFamily()});
}

const vk::raii::CommandBuffer& OneShotCommands::begin() {
    vk::raii::CommandBuffers buffers(ctx_.device(),
                                     vk::CommandBufferAllocateInfo{.commandPool = *pool_,
                                                                   .level = vk::CommandBufferLevel::ePrimary,
                                                                   .commandBufferCount = 1});
    cmd_ = std::move(buffers[0]);
    cmd_.begin(vk::CommandBufferBeginInfo{.flags = vk::CommandBufferUsageFlagBits::eOneTimeSubmit});
    return cmd_;
}

void OneShotCommands::submitAndWait() {
    cmd_.end();
    vk::raii::Fence fence(ctx_.device(), vk::FenceCreateInfo{});
    vk::CommandBuffer raw = *cmd_;
    ctx_.queue().submit(vk::SubmitInfo{.commandBufferCount = 1, .pCommandBuffers = &raw}, *fence);
    // No timeout: a long render is legitimate; the kernels bound their own loops.
    while (ctx_.device().waitForFences(*fence, VK_TRUE, UINT64_MAX) == vk::Result::eTimeout) {
    }
}

void checkTexelArrayFits(const VulkanContext& ctx, uint64_t texels, const std::string& what) {
    const uint64_t limit = ctx.info().maxTexelBufferElements;
    if (texels > limit)
        throw Error("the scene's " + what + " need " + std::to_string(texels) + " texels, more than the " +
                    std::to_string(limit) + " one texel buffer may hold on '" + ctx.info().name +
                    "' (maxTexelBufferElements)");
}

TexelView::TexelView(const VulkanContext& ctx, const Buffer& buffer, vk::Format format, uint32_t texelBytes,
                     const std::string& what) {
    const vk::DeviceSize texels = buffer.size() / texelBytes;
    checkTexelArrayFits(ctx, texels, what);
    view_ = vk::raii::BufferView(ctx.device(), vk::BufferViewCreateInfo{.buffer = buffer.handle(), .format = format,
                                                                        .offset = 0, .range = texels * texelBytes});
}

namespace {

// Copies `bytes` into the device-local `target` through one staging buffer of at most 64 MiB,
// reused chunk by chunk: a 2 GiB array does not need 2 GiB of staging memory beside it.
void uploadThroughStaging(const VulkanContext& ctx, const Buffer& target, const void* data, size_t bytes,
                          const std::string& what) {
    constexpr size_t kChunk = size_t(64) << 20;
    const size_t chunk = std::min(bytes, kChunk);
    const Buffer staging(ctx, chunk, vk::BufferUsageFlagBits::eTransferSrc, MemoryUse::Upload, what + " (staging)");
    for (size_t offset = 0; offset < bytes; offset += chunk) {
        const size_t n = std::min(chunk, bytes - offset);
        std::memcpy(staging.mapped(), static_cast<const char*>(data) + offset, n);
        OneShotCommands commands(ctx);
        commands.begin().copyBuffer(staging.handle(), target.handle(),
                                    vk::BufferCopy{.srcOffset = 0, .dstOffset = offset, .size = n});
        commands.submitAndWait();
    }
}

}  // namespace

TexelArray uploadTexelArray(const VulkanContext& ctx, const void* data, size_t bytes, vk::Format format,
                            uint32_t texelBytes, const std::string& what) {
    if (bytes % texelBytes != 0)
        throw Error("internal: " + what + " are " + std::to_string(bytes) + " bytes, not whole texels of " +
                    std::to_string(texelBytes));
    checkTexelArrayFits(ctx, bytes / texelBytes, what);
    const vk::DeviceSize size = std::max<vk::DeviceSize>(bytes, texelBytes);
    using BU = vk::BufferUsageFlagBits;
    Buffer target(ctx, size, BU::eUniformTexelBuffer | BU::eTransferDst, MemoryUse::DeviceLocal, what);
    if (bytes > 0) {
        if (target.hostVisible()) std::memcpy(target.mapped(), data, bytes);
        else uploadThroughStaging(ctx, target, data, bytes, what);
    }
    TexelView view(ctx, target, format, texelBytes, what);
    return TexelArray{std::move(target), std::move(view)};
}

}  // namespace vkray::gpu
