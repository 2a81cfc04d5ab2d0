#include "gpu/pixel_output.h"

namespace vkray::gpu {

PixelOutput::PixelOutput(const VulkanContext& ctx, vk::DeviceSize bytes, bool forceCopy)
    : host_(ctx, bytes, vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst,
            MemoryUse::Readback, "pixels") {
    if (forceCopy || !host_.deviceLocal())
        device_.emplace(ctx, bytes,
                        vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc |
                            vk::BufferUsageFlagBits::eTransferDst,  // transfer-dst: the tests fill it
                        MemoryUse::DeviceLocal, "pixels (device copy)");
}

void PixelOutput::recordToHost(const vk::raii::CommandBuffer& cmd, vk::DeviceSize bytes) const {
    using Access = vk::AccessFlagBits;
    using Stage = vk::PipelineStageFlagBits;
    if (device_) {
        const vk::MemoryBarrier written{.srcAccessMask = Access::eShaderWrite, .dstAccessMask = Access::eTransferRead};
        cmd.pipelineBarrier(Stage::eComputeShader, Stage::eTransfer, {}, written, nullptr, nullptr);
        cmd.copyBuffer(device_->handle(), host_.handle(), vk::BufferCopy{.srcOffset = 0, .dstOffset = 0, .size = bytes});
        const vk::MemoryBarrier copied{.srcAccessMask = Access::eTransferWrite, .dstAccessMask = Access::eHostRead};
        cmd.pipelineBarrier(Stage::eTransfer, Stage::eHost, {}, copied, nullptr, nullptr);
        return;
    }
    const vk::MemoryBarrier toHost{.srcAccessMask = Access::eShaderWrite, .dstAccessMask = Access::eHostRead};
    cmd.pipelineBarrier(Stage::eComputeShader, Stage::eHost, {}, toHost, nullptr, nullptr);
}

}  // namespace vkray::gpu
