#include "gpu/kernel_bindings.h"

#include <algorithm>
#include <array>
#include <vector>

#include "shared/gpu_layout.h"

namespace vkray::gpu {
namespace {

// Storage buffers, then arrays of texel views, then (rayquery) the acceleration structure.
static_assert(VKRAY_BINDING_SCENE_STRUCTURE == VKRAY_BINDING_COUNT);
constexpr auto kBindings = [] {
    std::array<ComputeKernel::Binding, VKRAY_BINDING_COUNT + 1> bindings{};
    for (uint32_t i = 0; i < VKRAY_BINDING_COUNT; ++i)
        bindings[i] = i < VKRAY_STORAGE_BINDING_COUNT
                          ? ComputeKernel::Binding{vk::DescriptorType::eStorageBuffer, 1}
                          : ComputeKernel::Binding{vk::DescriptorType::eUniformTexelBuffer, VKRAY_TEXEL_VIEWS};
    bindings[VKRAY_BINDING_SCENE_STRUCTURE] = {vk::DescriptorType::eAccelerationStructureKHR, 1};
    return bindings;
}();

// A binding's VKRAY_TEXEL_VIEWS views: the array's, then its first again where it has fewer (the
// kernel reads only those that hold the array; the rest must still be valid descriptors).
std::vector<vk::BufferView> viewHandles(const TexelArray& array) {
    std::vector<vk::BufferView> views(VKRAY_TEXEL_VIEWS, array.views.front().handle());
    for (size_t v = 0; v < array.views.size(); ++v) views[v] = array.views[v].handle();
    return views;
}

}  // namespace

std::span<const ComputeKernel::Binding> renderKernelBindings(accel::Traversal traversal) {
    const size_t count = traversal == accel::Traversal::RayQuery ? kBindings.size() : VKRAY_BINDING_COUNT;
    return std::span(kBindings).first(count);
}

ResumeBuffers::ResumeBuffers(const VulkanContext& ctx, uint64_t pixels, uint64_t maxDepth)
    : records(ctx, std::max<uint64_t>(pixels, 1) * sizeof(GpuPixelResume),
              vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, MemoryUse::DeviceLocal,
              "resumable pixels"),
      rays(ctx, std::max<uint64_t>(pixels * maxDepth, 1) * sizeof(GpuPendingRay),
           vk::BufferUsageFlagBits::eStorageBuffer, MemoryUse::DeviceLocal, "resumable pixels' rays") {}

void bindBuffers(ComputeKernel& kernel, const SceneBuffers& scene, const AccelBuffers& accel,
                 const PixelOutput& pixels, const ResumeBuffers& resume) {
    std::vector<ComputeKernel::Resource> r(VKRAY_BINDING_COUNT + (accel.driver ? 1 : 0));
    r[VKRAY_BINDING_PIXELS].buffer = pixels.target().handle();
    r[VKRAY_BINDING_RESUME].buffer = resume.records.handle();
    r[VKRAY_BINDING_RESUME_RAYS].buffer = resume.rays.handle();
    r[VKRAY_BINDING_TRIANGLE_TEXELS].views = viewHandles(scene.triangles);
    r[VKRAY_BINDING_NODE_TEXELS].views = viewHandles(accel.nodes);
    r[VKRAY_BINDING_INDEX_TEXELS].views = viewHandles(accel.indices);
    r[VKRAY_BINDING_EXTRA_TEXELS].views = viewHandles(accel.extra);
    r[VKRAY_BINDING_NORMAL_TEXELS].views = viewHandles(scene.normals);
    r[VKRAY_BINDING_MATERIAL_TEXELS].views = viewHandles(scene.materials);
    r[VKRAY_BINDING_LIGHT_TEXELS].views = viewHandles(scene.lights);
    if (accel.driver) r[VKRAY_BINDING_SCENE_STRUCTURE].structure = accel.driver->handle();
    kernel.bind(r);
}

}  // namespace vkray::gpu
