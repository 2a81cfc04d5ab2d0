// Headless Vulkan for compute: instance (with the Khronos validation layer when asked), physical
// device choice, one logical device with one compute queue. Every handle is a vk::raii owner; every
// failing call throws: vk::SystemError names the call and the result, and main() prints it as one
// "error: " line (the calls a user's setup can make fail, such as creating the instance, rethrow it
// as vkray::Error with the remedy).
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan_raii.hpp>

namespace vkray::gpu {

struct DeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;          // "discrete", "integrated", "virtual", "cpu", "other"
    std::string driver;        // driver name and info, e.g. "llvmpipe / Mesa 22.3.6"
    std::string apiVersion;    // "1.3.230"
    uint64_t maxStorageBufferRange = 0;
    uint64_t maxTexelBufferElements = 0;
    uint64_t deviceLocalBytes = 0;
    // What of that heap the process may allocate now: VK_EXT_memory_budget's heapBudget where the
    // device has the extension, else deviceLocalBytes.
    uint64_t deviceLocalBudget = 0;
    float timestampPeriodNs = 0.0f;
    bool hasCompute = false;
    // Subgroup vote and arithmetic operations in compute shaders (the kernels' subgroupAll and
    // subgroupAdd; every desktop GPU and lavapipe have them).
    bool subgroupOps = false;
    // Subgroup ballot operations in compute shaders besides: the `bvh-packet` and
    // `kd-packet` kernels' subgroupBroadcastFirst (kernelTraversal(), kernel_cache.h).
    bool subgroupBallot = false;
    // Invocations that run together (VkPhysicalDeviceSubgroupProperties::subgroupSize): 8 on
    // llvmpipe with 256-bit vectors, 32 on NVIDIA, 32 or 64 on AMD.
    uint32_t subgroupSize = 0;
    // Pixels an invocation of the plain render kernel renders (VKRAY_SPEC_PIXELS_PER_INVOCATION;
    // render_main.glsl, "Pixels per invocation"): VKRAY_MAX_PIXELS_PER_INVOCATION on a CPU device,
    // where a SIMD vector's lanes wait for its last ray and each invocation has its costs; 1 on a
    // GPU, which needs every thread it can get (a dispatch is one tile of at most 65,536 pixels).
    uint32_t pixelsPerInvocation = 1;
    // The driver's own ray tracing from compute shaders: Vulkan 1.2, VK_KHR_acceleration_structure
    // and VK_KHR_ray_query with their features (`--accel rayquery`).
    bool rayQuery = false;
};

struct ContextOptions {
    // Enable the Khronos validation layer; any validation error makes checkValidation() throw. Off
    // unless asked for: `vkray` asks when VKRAY_VALIDATION=1 (validationRequestedByEnvironment()),
    // the tests always.
    bool validation = false;
    std::string device;  // "" = best (discrete > integrated > virtual > cpu), "N" = index, else substring
    // Tests: behave as if one texel view held at most this many texels (0: the device's own
    // maxTexelBufferElements), so that small scenes take the path of arrays split over views.
    uint64_t maxTexelsPerView = 0;
    // Tests: render this many pixels an invocation, 1 to VKRAY_MAX_PIXELS_PER_INVOCATION (0: the
    // device's DeviceInfo::pixelsPerInvocation), so that either path runs on any device.
    uint32_t pixelsPerInvocation = 0;
    // Enable the driver's ray tracing (DeviceInfo::rayQuery) on the device, for `--accel rayquery`;
    // a device without it is then refused with one line naming it.
    bool rayQuery = false;
    // Tests: render every tile with the resumable variant from the start, as a render that would
    // surely run out of the driver's loop budget does (gpu/resumable_pass.h), so that its resuming
    // runs on a device whose loops never end early too.
    bool resumableFromStart = false;
};

bool validationRequestedByEnvironment();

class VulkanContext {
public:
    explicit VulkanContext(const ContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    // Devices the loader sees (no logical device is created for this).
    static std::vector<DeviceInfo> listDevices(bool validation);

    const DeviceInfo& info() const { return info_; }
    // Whether the driver's ray tracing was enabled (ContextOptions::rayQuery).
    bool rayQueryEnabled() const { return rayQueryEnabled_; }
    const vk::raii::Device& device() const { return device_; }
    const vk::raii::PhysicalDevice& physicalDevice() const { return physical_; }
    const vk::raii::Queue& queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    const vk::PhysicalDeviceLimits& limits() const { return limits_; }
    uint32_t timestampValidBits() const { return timestampValidBits_; }
    // ContextOptions::resumableFromStart.
    bool resumableFromStart() const { return resumableFromStart_; }
    // Whether the driver ends all loops of an invocation once they ran 65535 iterations together,
    // as llvmpipe of Mesa 22.3 does (Mesa's LP_MAX_TGSI_LOOP_ITERATIONS; render_main.glsl,
    // "Resumable pixels"). Measured by a probe kernel the first time it is asked (gpu/loop_budget.h),
    // which only the renders that would surely run out of such a budget do.
    bool loopBudget() const;

    uint32_t findMemoryType(uint32_t typeBits, vk::MemoryPropertyFlags required,
                            vk::MemoryPropertyFlags preferred = {}) const;

    // Throws if the validation layer reported errors since the context was created.
    void checkValidation() const;

private:
    struct Messenger;  // debug-utils callback state (counts validation errors)
    vk::raii::Context context_;
    std::unique_ptr<Messenger> messengerState_;
    vk::raii::Instance instance_{nullptr};
    vk::raii::DebugUtilsMessengerEXT messenger_{nullptr};
    vk::raii::PhysicalDevice physical_{nullptr};
    vk::raii::Device device_{nullptr};
    vk::raii::Queue queue_{nullptr};
    uint32_t queueFamily_ = 0;
    uint32_t timestampValidBits_ = 0;
    bool rayQueryEnabled_ = false;
    bool resumableFromStart_ = false;
    vk::DriverId driver_{};
    mutable std::once_flag loopBudgetProbed_;
    mutable bool loopBudget_ = false;
    vk::PhysicalDeviceLimits limits_{};
    DeviceInfo info_;
};

}  // namespace vkray::gpu
