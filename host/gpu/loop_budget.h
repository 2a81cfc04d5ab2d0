// Whether a device's driver ends long shader loops early, as llvmpipe of Mesa 22.3 does (every loop
// of an invocation ends once its loops together ran 65535 iterations): measured, since other
// releases of the same driver run them to the end.
#pragma once

#include <vulkan/vulkan_raii.hpp>

namespace vkray::gpu {

class VulkanContext;

// Dispatches shaders/loop_budget_probe.comp on ctx's device with a bound above llvmpipe's budget
// and says whether its loop stopped short. Only llvmpipe (driver `driver`) is probed: no other
// driver is known to end loops, and a probe costs a GPU driver a pipeline compile.
bool endsLongLoops(const VulkanContext& ctx, vk::DriverId driver);

}  // namespace vkray::gpu
