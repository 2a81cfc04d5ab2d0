// `--accel rayquery`: the driver's own acceleration structure (VK_KHR_acceleration_structure), built
// on the device from the scene's triangles and traced by the render kernel with VK_KHR_ray_query
// (shaders/include/ray_query.glsl). One bottom-level structure holds every triangle in the order of
// the triangle buffer (a Morton order: accel/accel.cpp says why), so a hit's primitive index is its
// triangle slot and the AOVs, materials and normals follow from that slot's triangle as for every
// other accelerator; one top-level structure holds one instance of it
// with the identity transform. Both are opaque geometry: the kernel gets the driver's closest hit
// without a candidate loop, and shadow rays end at their first hit.
#pragma once

#include <cstdint>
#include <span>

#include <vulkan/vulkan_raii.hpp>

#include "accel/accel_spec.h"
#include "gpu/buffer.h"
#include "gpu/vulkan_context.h"
#include "shared/gpu_layout.h"

namespace vkray::gpu {

class DriverStructure {
public:
    // Builds the structures over `triangles` (the triangle buffer's contents: GpuTriangle's three
    // vertices are 16 bytes apart) as `build` asks. Needs a context with rayQueryEnabled().
    DriverStructure(const VulkanContext& ctx, std::span<const GpuTriangle> triangles, const accel::DriverBuild& build);

    // The top-level structure the kernel binds (VKRAY_BINDING_SCENE_STRUCTURE).
    vk::AccelerationStructureKHR handle() const { return *top_; }
    // The builds (and the compaction) on the device, from GPU timestamps; -1 without timestamps.
    double buildMs() const { return buildMs_; }
    // The two structures' storage, after compaction where asked for.
    uint64_t bytes() const { return bottomBuffer_.size() + topBuffer_.size(); }

private:
    struct Parts;
    static Parts buildParts(const VulkanContext& ctx, std::span<const GpuTriangle> triangles,
                            const accel::DriverBuild& build);
    explicit DriverStructure(Parts parts);

    // Each structure after its storage, so that it is destroyed first.
    Buffer bottomBuffer_;
    vk::raii::AccelerationStructureKHR bottom_;
    Buffer topBuffer_;
    vk::raii::AccelerationStructureKHR top_;
    double buildMs_ = 0.0;
};

}  // namespace vkray::gpu
