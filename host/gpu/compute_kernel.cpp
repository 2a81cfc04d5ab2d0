#include "gpu/compute_kernel.h"

#include <algorithm>

#include "core/error.h"

namespace vkray::gpu {
namespace {

// The set's descriptors against the device's per-stage limits (texel buffers count as sampled
// images), so that a device with fewer gets a sentence, not a failed pipeline-layout call.
void checkDescriptorLimits(const VulkanContext& ctx, std::span<const ComputeKernel::Binding> bindings) {
    uint32_t views = 0, resources = 0;
    for (const ComputeKernel::Binding& b : bindings) {
        resources += b.count;
        if (b.type == vk::DescriptorType::eUniformTexelBuffer) views += b.count;
    }
    const vk::PhysicalDeviceLimits& limits = ctx.limits();
    if (views > limits.maxPerStageDescriptorSampledImages || resources > limits.maxPerStageResources)
        throw Error("the render kernels bind " + std::to_string(views) + " texel views (" + std::to_string(resources) +
                    " resources in all); '" + ctx.info().name + "' allows " +
                    std::to_string(limits.maxPerStageDescriptorSampledImages) + " (maxPerStageDescriptorSampledImages) and " +
                    std::to_string(limits.maxPerStageResources) + " (maxPerStageResources) per shader stage");
}

}  // namespace

ComputeKernel::ComputeKernel(const VulkanContext& ctx, std::span<const uint32_t> spirv,
                             std::span<const Binding> bindingList, uint32_t pushConstantBytes,
                             const Specialization& spec)
    : ctx_(ctx), pushConstantBytes_(pushConstantBytes), bindings_(bindingList.begin(), bindingList.end()) {
    const auto& dev = ctx.device();
    checkDescriptorLimits(ctx, bindings_);
    module_ = vk::raii::ShaderModule(dev, vk::ShaderModuleCreateInfo{.codeSize = spirv.size_bytes(),
                                                                     .pCode = spirv.data()});

    std::vector<vk::DescriptorSetLayoutBinding> bindings;
    for (uint32_t i = 0; i < bindings_.size(); ++i)
        bindings.push_back({.binding = i,
                            .descriptorType = bindings_[i].type,
                            .descriptorCount = bindings_[i].count,
                            .stageFlags = vk::ShaderStageFlagBits::eCompute});
    setLayout_ = vk::raii::DescriptorSetLayout(
        dev, vk::DescriptorSetLayoutCreateInfo{.bindingCount = uint32_t(bindings.size()),
                                               .pBindings = bindings.data()});

    vk::PushConstantRange range{.stageFlags = vk::ShaderStageFlagBits::eCompute,
                                .offset = 0, .size = pushConstantBytes};
    vk::DescriptorSetLayout rawSetLayout = *setLayout_;
    layout_ = vk::raii::PipelineLayout(
        dev, vk::PipelineLayoutCreateInfo{.setLayoutCount = 1, .pSetLayouts = &rawSetLayout,
                                          .pushConstantRangeCount = pushConstantBytes ? 1u : 0u,
                                          .pPushConstantRanges = &range});

    std::vector<vk::SpecializationMapEntry> entries;
    std::vector<uint32_t> data;
    for (auto [id, value] : spec.values) {
        entries.push_back({.constantID = id, .offset = uint32_t(data.size() * 4), .size = 4});
        data.push_back(value);
    }
    vk::SpecializationInfo specInfo{.mapEntryCount = uint32_t(entries.size()),
                                    .pMapEntries = entries.data(),
                                    .dataSize = data.size() * 4,
                                    .pData = data.data()};
    vk::ComputePipelineCreateInfo info{
        .stage = {.stage = vk::ShaderStageFlagBits::eCompute, .module = *module_, .pName = "main",
                  .pSpecializationInfo = &specInfo},
        .layout = *layout_};
    pipeline_ = vk::raii::Pipeline(dev, nullptr, info);

    std::vector<vk::DescriptorPoolSize> poolSizes;
    for (const Binding& b : bindings_) {
        auto it = std::find_if(poolSizes.begin(), poolSizes.end(), [&](const auto& p) { return p.type == b.type; });
        if (it == poolSizes.end()) poolSizes.push_back({.type = b.type, .descriptorCount = b.count});
        else it->descriptorCount += b.count;
    }
    pool_ = vk::raii::DescriptorPool(
        dev, vk::DescriptorPoolCreateInfo{.flags = vk::DescriptorPoolCreateFlagBits::eFreeDescriptorSet,
                                          .maxSets = 1, .poolSizeCount = uint32_t(poolSizes.size()),
                                          .pPoolSizes = poolSizes.data()});
    vk::raii::DescriptorSets sets(dev, vk::DescriptorSetAllocateInfo{.descriptorPool = *pool_,
                                                                     .descriptorSetCount = 1,
                                                                     .pSetLayouts = &rawSetLayout});
    set_ = std::move(sets[0]);
}

void ComputeKernel::bind(std::span<const Resource> resources) {
    if (resources.size() != bindings_.size())
        throw Error("internal: " + std::to_string(resources.size()) + " resources for a kernel of " +
                    std::to_string(bindings_.size()) + " bindings");
    std::vector<vk::DescriptorBufferInfo> infos(resources.size());
    std::vector<vk::WriteDescriptorSetAccelerationStructureKHR> structures(resources.size());
    std::vector<vk::WriteDescriptorSet> writes;
    for (uint32_t i = 0; i < bindings_.size(); ++i) {
        const Binding& b = bindings_[i];
        vk::WriteDescriptorSet w{.dstSet = *set_, .dstBinding = i, .descriptorCount = b.count, .descriptorType = b.type};
        if (b.type == vk::DescriptorType::eUniformTexelBuffer) {
            if (resources[i].views.size() != b.count)
                throw Error("internal: " + std::to_string(resources[i].views.size()) + " views for binding " +
                            std::to_string(i) + " of " + std::to_string(b.count));
            w.pTexelBufferView = resources[i].views.data();
        } else if (b.type == vk::DescriptorType::eAccelerationStructureKHR) {
            structures[i] = {.accelerationStructureCount = 1, .pAccelerationStructures = &resources[i].structure};
            w.pNext = &structures[i];
        } else {
            infos[i] = vk::DescriptorBufferInfo{.buffer = resources[i].buffer, .offset = 0, .range = VK_WHOLE_SIZE};
            w.pBufferInfo = &infos[i];
        }
        writes.push_back(w);
    }
    ctx_.device().updateDescriptorSets(writes, nullptr);
}

void ComputeKernel::dispatch(const vk::raii::CommandBuffer& cmd, const void* pushConstants,
                             uint32_t groupsX, uint32_t groupsY) const {
    cmd.bindPipeline(vk::PipelineBindPoint::eCompute, *pipeline_);
    cmd.bindDescriptorSets(vk::PipelineBindPoint::eCompute, *layout_, 0, *set_, nullptr);
    if (pushConstantBytes_)
        cmd.pushConstants<uint8_t>(*layout_, vk::ShaderStageFlagBits::eCompute, 0,
                                   vk::ArrayProxy<const uint8_t>(pushConstantBytes_,
                                                                 static_cast<const uint8_t*>(pushConstants)));
    cmd.dispatch(groupsX, groupsY, 1);
}

}  // namespace vkray::gpu
