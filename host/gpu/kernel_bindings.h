// What the render kernels' descriptor set holds (shared/gpu_layout.h): the pixel records and the
// resumable variant's saved state as storage buffers, then the scene's and the structure's arrays as
// arrays of texel views.
#pragma once

#include <cstdint>
#include <span>

#include "accel/accel.h"
#include "gpu/buffer.h"
#include "gpu/compute_kernel.h"
#include "gpu/pixel_output.h"
#include "gpu/scene_buffers.h"
#include "gpu/vulkan_context.h"

namespace vkray::gpu {

// The bindings `traversal`'s render kernel declares, in binding order: every kernel's, and the
// rayquery kernel's acceleration structure after them.
std::span<const ComputeKernel::Binding> renderKernelBindings(accel::Traversal traversal);

// The resumable variant's records (VKRAY_BINDING_RESUME, _RESUME_RAYS): for `pixels` pixels of
// `maxDepth` pending rays each, or one-element dummies for the plain kernel.
struct ResumeBuffers {
    Buffer records, rays;
    ResumeBuffers(const VulkanContext& ctx, uint64_t pixels, uint64_t maxDepth);
};

// Points every binding of `kernel` at its buffer or views.
void bindBuffers(ComputeKernel& kernel, const SceneBuffers& scene, const AccelBuffers& accel,
                 const PixelOutput& pixels, const ResumeBuffers& resume);

}  // namespace vkray::gpu
