// Options every renderer takes; the CLI fills them from the scene file and the command line. The
// acceleration structure is not among them: a renderer is handed the structure itself (a built
// accelerator for the GPU, a geometry::Tracer for the CPU reference).
#pragma once

namespace vkray {

struct RenderOptions {
    int width = 0, height = 0;  // image size (the scene's `size` unless overridden)
    int maxDepth = 5;           // primary rays count as depth 1
    int threads = 0;            // CPU worker threads; 0 = all cores
    // Compile traversal counters into the kernel (nodes, leaves, triangle tests per ray): the
    // statistics variant; off, timing runs pay nothing for counting.
    bool countTraversal = false;
    // Fill Frame's primary-hit AOVs (depth, primId, normal). A render that saves none and timing
    // runs turn this off: the GPU kernel then stores only colour and ray counts per pixel, and
    // the AOVs stay at their miss values.
    bool primaryAovs = true;
    // Camera rays per pixel (pixelSampleOffset, scene/camera.h), their radiance averaged; the
    // primary-hit AOVs are sample 0's, the pixel centre's.
    int spp = 1;
};

}  // namespace vkray
