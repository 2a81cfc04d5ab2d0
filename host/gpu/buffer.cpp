#include "gpu/buffer.h"

#include <algorithm>
#include <bit>
#include <cstring>

#include "core/error.h"
#include "core/parallel_alloc.h"
#include "shared/gpu_layout.h"

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
    // A buffer the device addresses (the driver's acceleration structures and their inputs) needs
    // memory allocated for it.
    const vk::MemoryAllocateFlagsInfo addressable{.flags = vk::MemoryAllocateFlagBits::eDeviceAddress};
    const bool addressed = bool(usage & vk::BufferUsageFlagBits::eShaderDeviceAddress);
    try {
        memory_ = vk::raii::DeviceMemory(dev, vk::MemoryAllocateInfo{.pNext = addressed ? &addressable : nullptr,
                                                                     .allocationSize = req.size,
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
    if (addressed) address_ = dev.getBufferAddress(vk::BufferDeviceAddressInfo{.buffer = *buffer_});
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

namespace {

// log2 of the largest power of two of texels one view may hold.
int viewBitsLimit(const VulkanContext& ctx) {
    return std::bit_width(std::max<uint64_t>(ctx.info().maxTexelBufferElements, 1)) - 1;
}

}  // namespace

uint64_t maxTexelArray(const VulkanContext& ctx) { return uint64_t(VKRAY_TEXEL_VIEWS) << viewBitsLimit(ctx); }

void checkTexelArrayFits(const VulkanContext& ctx, uint64_t texels, const std::string& what) {
    if (texels > maxTexelArray(ctx))
        throw Error("the scene's " + what + " need " + std::to_string(texels) + " texels, more than the " +
                    std::to_string(VKRAY_TEXEL_VIEWS) + " views of " + std::to_string(uint64_t(1) << viewBitsLimit(ctx)) +
                    " texels (maxTexelBufferElements " + std::to_string(ctx.info().maxTexelBufferElements) +
                    ") a kernel binding holds on '" + ctx.info().name + "'");
}

int texelViewBits(const VulkanContext& ctx, std::span<const TexelArraySize> arrays) {
    bool split = false;
    for (const TexelArraySize& a : arrays) {
        checkTexelArrayFits(ctx, a.texels, a.what);
        split = split || a.texels > ctx.info().maxTexelBufferElements;
    }
    return split ? viewBitsLimit(ctx) : 0;
}

TexelView::TexelView(const VulkanContext& ctx, const Buffer& buffer, vk::Format format, uint32_t texelBytes,
                     const std::string& what) {
    const vk::DeviceSize texels = buffer.size() / texelBytes;
    if (texels > ctx.info().maxTexelBufferElements)
        throw Error("internal: a view of " + std::to_string(texels) + " texels of " + what + ", more than maxTexelBufferElements " +
                    std::to_string(ctx.info().maxTexelBufferElements));
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
        parallelCopy(staging.mapped(), static_cast<const char*>(data) + offset, n);
        OneShotCommands commands(ctx);
        commands.begin().copyBuffer(staging.handle(), target.handle(),
                                    vk::BufferCopy{.srcOffset = 0, .dstOffset = offset, .size = n});
        commands.submitAndWait();
    }
}

}  // namespace

TexelArray uploadTexelArray(const VulkanContext& ctx, const void* data, size_t bytes, vk::Format format,
                            uint32_t texelBytes, const std::string& what, int viewBits) {
    if (bytes % texelBytes != 0)
        throw Error("internal: " + what + " are " + std::to_string(bytes) + " bytes, not whole texels of " +
                    std::to_string(texelBytes));
    const uint64_t texels = bytes / texelBytes;
    checkTexelArrayFits(ctx, texels, what);
    const uint64_t perView = viewBits > 0 ? uint64_t(1) << viewBits : std::max<uint64_t>(texels, 1);
    const uint64_t views = std::max<uint64_t>((texels + perView - 1) / perView, 1);
    if (views > VKRAY_TEXEL_VIEWS || (viewBits == 0 && texels > ctx.info().maxTexelBufferElements))
        throw Error("internal: " + what + " (" + std::to_string(texels) + " texels) do not fit views of " +
                    std::to_string(perView) + " texels");
    TexelArray array;
    array.buffers.reserve(views);
    array.views.reserve(views);
    using BU = vk::BufferUsageFlagBits;
    for (uint64_t v = 0; v < views; ++v) {
        const size_t first = size_t(v * perView) * texelBytes;
        const size_t n = std::min(bytes - std::min(bytes, first), size_t(perView) * texelBytes);
        const std::string part = views > 1 ? what + " (view " + std::to_string(v + 1) + " of " + std::to_string(views) + ")" : what;
        Buffer& target = array.buffers.emplace_back(ctx, std::max<vk::DeviceSize>(n, texelBytes),
                                                    BU::eUniformTexelBuffer | BU::eTransferDst, MemoryUse::DeviceLocal, part);
        const void* src = static_cast<const char*>(data) + first;
        if (n > 0) {
            if (target.hostVisible()) parallelCopy(target.mapped(), src, n);
            else uploadThroughStaging(ctx, target, src, n, part);
        }
        array.views.emplace_back(ctx, target, format, texelBytes, part);
    }
    return array;
}

Buffer uploadBuffer(const VulkanContext& ctx, const void* data, size_t bytes, vk::BufferUsageFlags usage,
                    const std::string& what) {
    Buffer target(ctx, std::max<vk::DeviceSize>(bytes, 4), usage | vk::BufferUsageFlagBits::eTransferDst,
                  MemoryUse::DeviceLocal, what);
    if (bytes > 0) {
        if (target.hostVisible()) parallelCopy(target.mapped(), data, bytes);
        else uploadThroughStaging(ctx, target, data, bytes, what);
    }
    return target;
}

}  // namespace vkray::gpu
