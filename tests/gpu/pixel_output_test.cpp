// PixelOutput: what the kernels write reaches the host on both routes, the mapped buffer (lavapipe,
// integrated GPUs) and the device-local buffer copied after each batch (discrete GPUs).
#include "gpu/pixel_output.h"

#include <cstdint>
#include <cstring>

#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu_test_util.h"

namespace vkray {
namespace {

// Fills the first `words` words of the output's target with `value` (standing in for the kernels'
// writes, then the barrier a dispatch would need before the copy), moves them to the host and
// returns the host's view.
const uint32_t* writeAndRead(const gpu::PixelOutput& out, vk::DeviceSize words, uint32_t value) {
    const gpu::VulkanContext& ctx = test::gpuContext();
    gpu::OneShotCommands commands(ctx);
    const vk::raii::CommandBuffer& cmd = commands.begin();
    cmd.fillBuffer(out.target().handle(), 0, words * 4, value);
    const vk::MemoryBarrier filled{.srcAccessMask = vk::AccessFlagBits::eTransferWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eShaderWrite};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eTransfer, vk::PipelineStageFlagBits::eComputeShader, {}, filled,
                        nullptr, nullptr);
    out.recordToHost(cmd, words * 4);
    commands.submitAndWait();
    return out.records<uint32_t>();
}

TEST(PixelOutput, BothRoutesBringTheWritesToTheHost) {
    const gpu::VulkanContext& ctx = test::gpuContext();
    constexpr vk::DeviceSize kPixels = 1000;
    constexpr vk::DeviceSize kWords = kPixels * sizeof(gpu::GpuPixel) / 4;
    for (bool forceCopy : {false, true}) {
        SCOPED_TRACE(forceCopy ? "copied" : "as the device chooses");
        const gpu::PixelOutput out(ctx, kPixels * sizeof(gpu::GpuPixel), forceCopy);
        if (forceCopy) {
            EXPECT_TRUE(out.copied());
        }
        EXPECT_NE(out.target().handle(), vk::Buffer{});
        // Two batches: the second must not read back the first's values, and only its own words.
        const uint32_t* host = writeAndRead(out, kWords, 0x3f800000u);
        for (vk::DeviceSize i = 0; i < kWords; ++i) ASSERT_EQ(host[i], 0x3f800000u) << "word " << i;
        host = writeAndRead(out, kWords / 2, 7u);
        for (vk::DeviceSize i = 0; i < kWords / 2; ++i) ASSERT_EQ(host[i], 7u) << "word " << i;
        EXPECT_EQ(host[kWords / 2], 0x3f800000u);
        ctx.checkValidation();
    }
}

}  // namespace
}  // namespace vkray
