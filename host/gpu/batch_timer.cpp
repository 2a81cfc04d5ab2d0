#include "gpu/batch_timer.h"

namespace vkray::gpu {

BatchTimer::BatchTimer(const VulkanContext& ctx) : ctx_(ctx) {
    const uint32_t bits = ctx.timestampValidBits();
    if (bits == 0) return;
    mask_ = bits >= 64 ? ~uint64_t(0) : (uint64_t(1) << bits) - 1;
    queries_ = vk::raii::QueryPool(ctx.device(),
                                   vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = 2});
}

void BatchTimer::begin(const vk::raii::CommandBuffer& cmd) const {
    if (!enabled()) return;
    cmd.resetQueryPool(*queries_, 0, 2);
    cmd.writeTimestamp(vk::PipelineStageFlagBits::eTopOfPipe, *queries_, 0);
}

void BatchTimer::end(const vk::raii::CommandBuffer& cmd) const {
    if (enabled()) cmd.writeTimestamp(vk::PipelineStageFlagBits::eBottomOfPipe, *queries_, 1);
}

double BatchTimer::batchMs() const {
    if (!enabled()) return 0.0;
    auto [result, stamps] = queries_.getResults<uint64_t>(0, 2, 2 * sizeof(uint64_t), sizeof(uint64_t),
                                                          vk::QueryResultFlagBits::e64 |
                                                              vk::QueryResultFlagBits::eWait);
    if (result != vk::Result::eSuccess) return 0.0;
    const uint64_t ticks = ((stamps[1] & mask_) - (stamps[0] & mask_)) & mask_;
    return double(ticks) * double(ctx_.info().timestampPeriodNs) * 1e-6;
}

}  // namespace vkray::gpu
