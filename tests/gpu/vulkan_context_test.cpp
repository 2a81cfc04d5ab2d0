// The Vulkan context: device listing, and that the validation layer really fails a run.
#include <gtest/gtest.h>

#include "core/error.h"
#include "gpu/vulkan_context.h"

namespace vkray {
namespace {

TEST(VulkanContext, ListsAtLeastOneComputeDevice) {
    const auto devices = gpu::VulkanContext::listDevices(false);
    ASSERT_FALSE(devices.empty());
    bool compute = false;
    for (const auto& d : devices) {
        EXPECT_FALSE(d.name.empty());
        EXPECT_GT(d.maxStorageBufferRange, 0u);
        compute = compute || d.hasCompute;
    }
    EXPECT_TRUE(compute);
}

TEST(VulkanContext, ValidationErrorFailsTheRun) {
    // A context of its own: the error below must not leak into other tests' shared context.
    gpu::VulkanContext ctx({.validation = true, .device = ""});
    EXPECT_NO_THROW(ctx.checkValidation());
    // A buffer of size 0 breaks VUID-VkBufferCreateInfo-size-00912; drivers accept it, the
    // validation layer reports it.
    VkBufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    const VkResult result = vkCreateBuffer(*ctx.device(), &info, nullptr, &buffer);
    if (result == VK_SUCCESS && buffer != VK_NULL_HANDLE) vkDestroyBuffer(*ctx.device(), buffer, nullptr);
    EXPECT_THROW(ctx.checkValidation(), Error);
}

}  // namespace
}  // namespace vkray
