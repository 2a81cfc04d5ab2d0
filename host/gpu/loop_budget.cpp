#include "gpu/loop_budget.h"

#include <cstdint>
#include <cstring>

#include "gpu/buffer.h"
#include "gpu/compute_kernel.h"
#include "gpu/vulkan_context.h"
#include "loop_budget_probe_spv.h"

namespace vkray::gpu {

bool endsLongLoops(const VulkanContext& ctx, vk::DriverId driver) {
    if (driver != vk::DriverId::eMesaLlvmpipe) return false;
    constexpr uint32_t kBound = 100000;  // above llvmpipe's 65535
    const Buffer passes(ctx, sizeof(uint32_t), vk::BufferUsageFlagBits::eStorageBuffer, MemoryUse::Readback,
                        "the loop-budget probe's count");
    const ComputeKernel::Binding binding{vk::DescriptorType::eStorageBuffer, 1};
    ComputeKernel kernel(ctx, loop_budget_probe_spv, {&binding, 1}, sizeof(kBound), Specialization{});
    kernel.bind({{ComputeKernel::Resource{passes.handle(), {}}}});
    OneShotCommands commands(ctx);
    const vk::raii::CommandBuffer& cmd = commands.begin();
    kernel.dispatch(cmd, &kBound, 1, 1);
    const vk::MemoryBarrier toHost{.srcAccessMask = vk::AccessFlagBits::eShaderWrite,
                                   .dstAccessMask = vk::AccessFlagBits::eHostRead};
    cmd.pipelineBarrier(vk::PipelineStageFlagBits::eComputeShader, vk::PipelineStageFlagBits::eHost, {}, toHost,
                        nullptr, nullptr);
    commands.submitAndWait();
    uint32_t counted = 0;
    std::memcpy(&counted, passes.mapped(), sizeof(counted));
    return counted < kBound;
}

}  // namespace vkray::gpu
