// One compute kernel ready to dispatch: SPIR-V module, descriptor-set layout of storage buffers and
// uniform texel buffers, push-constant range, pipeline specialised with constants, and its one
// descriptor set.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

#include "gpu/vulkan_context.h"

namespace vkray::gpu {

// Specialization constants, each a 32-bit value (bools as 0/1, as SPIR-V OpSpecConstantTrue/False
// expect a VkBool32).
struct Specialization {
    std::vector<std::pair<uint32_t, uint32_t>> values;  // (constant_id, value)
    void set(uint32_t id, uint32_t value) { values.emplace_back(id, value); }
};

class ComputeKernel {
public:
    // Binding i of the set: one storage buffer, or an array of `count` uniform texel buffers.
    struct Binding {
        vk::DescriptorType type;  // eStorageBuffer, eUniformTexelBuffer or eAccelerationStructureKHR
        uint32_t count = 1;
    };
    ComputeKernel(const VulkanContext& ctx, std::span<const uint32_t> spirv, std::span<const Binding> bindings,
                  uint32_t pushConstantBytes, const Specialization& spec);

    // What binding i is pointed at: the buffer (whole range) of a storage-buffer binding, the
    // `count` views of a texel-buffer binding, the acceleration structure of such a binding.
    struct Resource {
        vk::Buffer buffer{};
        std::vector<vk::BufferView> views{};
        vk::AccelerationStructureKHR structure{};
    };
    // Points every binding at resources[i]; one entry per binding.
    void bind(std::span<const Resource> resources);

    void dispatch(const vk::raii::CommandBuffer& cmd, const void* pushConstants, uint32_t groupsX,
                  uint32_t groupsY) const;

private:
    const VulkanContext& ctx_;
    uint32_t pushConstantBytes_;
    std::vector<Binding> bindings_;
    vk::raii::ShaderModule module_{nullptr};
    vk::raii::DescriptorSetLayout setLayout_{nullptr};
    vk::raii::PipelineLayout layout_{nullptr};
    vk::raii::Pipeline pipeline_{nullptr};
    vk::raii::DescriptorPool pool_{nullptr};
    vk::raii::DescriptorSet set_{nullptr};
};

}  // namespace vkray::gpu
