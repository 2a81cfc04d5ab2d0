// What the render kernel is specialised with for one scene: the features the scene does not need are
// compiled out through specialization constants (shared/gpu_layout.h, VKRAY_SPEC_*), not skipped at
// run time.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gpu/compute_kernel.h"
#include "scene/scene.h"
#include "shared/gpu_layout.h"
#include "shared/kd_layout.h"

namespace vkray::gpu {

// Which of a kernel's compiled SPIR-V modules a render uses (CMakeLists.txt compiles four).
struct KernelVariant {
    bool resumable = false;   // VKRAY_RESUMABLE_KERNEL
    bool splitViews = false;  // VKRAY_SPLIT_TEXEL_VIEWS
    int index() const { return int(resumable) + 2 * int(splitViews); }  // generated::RenderKernelSpirv::variants
};

struct ShaderFeatures {
    int maxDepth = 1;
    bool reflection = false;         // a material reflects, or refracts (Fresnel reflection), and maxDepth > 1
    bool refraction = false;         // a material transmits and maxDepth > 1
    bool pointLights = false;
    bool directionalLights = false;
    bool smoothNormals = false;
    bool countTraversal = false;     // statistics variant (RenderOptions::countTraversal)
    bool primaryAovs = true;         // depth, normal and triangle id written (RenderOptions::primaryAovs)
    // Every leaf of the structure holds at most VKRAY_SINGLE_SLOT_LEAF_LIMIT triangles. If not, the
    // resumable variant's leaf loop tests four a pass, for lavapipe's loop budget (leafSlots()); the
    // plain kernel tests one whatever the leaves, and resumes a tile that runs out.
    bool singleSlotLeaves = true;
    // Resumable pixels: the kernel's resumable variant (its own SPIR-V, compiled with
    // VKRAY_RESUMABLE_KERNEL), used only for tiles the plain kernel could not finish within the
    // driver's loop budget.
    bool resumable = false;
    // kd-shortstack's stack entries (VKRAY_SPEC_KD_SHORT_STACK; the other kernels ignore it).
    int kdShortStack = VKRAY_KD_SHORT_STACK_SIZE;
    // Texel arrays split over views of 2^texelViewBits texels (VKRAY_SPEC_TEXEL_VIEW_BITS; 0: every
    // array in one view, the kernel's fetches compiled without the choice of view).
    int texelViewBits = 0;
    // Pixels an invocation of the plain kernel renders (VKRAY_SPEC_PIXELS_PER_INVOCATION): the
    // device's DeviceInfo::pixelsPerInvocation; the resumable variant renders one.
    int pixelsPerInvocation = 1;

    // Which GpuPixel fields the kernel writes (render_main.glsl, storePixel): the primary-hit AOVs
    // and the counters when specialised to, and every field in the resumable variant, which reads
    // its pixels back.
    bool writesPrimaryAovs() const { return primaryAovs || resumable; }
    bool writesCounters() const { return countTraversal || resumable; }
    // Neither: the kernel writes compact records (GpuPixelColor) and per-tile ray counts
    // (GpuTileCounts) instead of GpuPixel (render_main.glsl, "Pixel records").
    bool compactPixels() const { return !writesPrimaryAovs() && !writesCounters(); }

    static ShaderFeatures forScene(const Scene& scene, int maxDepth);
    void setMaxLeafTriangles(uint32_t triangles) { singleSlotLeaves = triangles <= VKRAY_SINGLE_SLOT_LEAF_LIMIT; }
    // kd-shortstack's stack size as the structure's data asks (0: the default).
    void setKdShortStack(uint32_t entries) { kdShortStack = entries > 0 ? int(entries) : VKRAY_KD_SHORT_STACK_SIZE; }
    Specialization specialization() const;
    KernelVariant variant() const { return {resumable, texelViewBits > 0}; }
    // Pixels an invocation of this variant renders: the kernel's specialization and the host's
    // dispatch both follow it (the resumable variant renders one).
    uint32_t invocationPixels() const { return resumable ? 1u : uint32_t(pixelsPerInvocation); }
    // Triangles a pass of the leaf loop tests: four only in the resumable variant for a structure
    // with larger leaves; the plain kernel's SPIR-V has the one-triangle loop alone (leaf_triangles.glsl).
    uint32_t leafSlots() const { return resumable && !singleSlotLeaves ? 4u : 1u; }
    // (name, compiled in) for --stats, of the plain kernel (resumed tiles are reported apart).
    std::vector<std::pair<std::string, bool>> list() const;
};

}  // namespace vkray::gpu
