// Options every renderer takes; the CLI fills them from the scene file and the command line. The
// acceleration structure is not among them: a renderer is handed the structure itself (a built
// accelerator for the GPU, a geometry::Tracer for the CPU reference).
#pragma once

#include <optional>
#include <string>

namespace vkray {

// Pixel columns [x0, x1) and rows [y0, y1) of an image: the part of it a render computes (a crop
// window, a tile of a render farm, one pixel to debug). Every pixel is computed alone from its own
// coordinates in the whole image, so a window's pixels are bit-identical to the same pixels of a
// render of the whole image.
struct PixelWindow {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
    bool operator==(const PixelWindow&) const = default;
};

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
    // The pixels rendered, within the width x height image; none: all of them. The Frame then holds
    // just the window (its width x height), top row first.
    std::optional<PixelWindow> window = std::nullopt;

    PixelWindow pixels() const { return window.value_or(PixelWindow{0, 0, width, height}); }
};

// Why `window` is not a non-empty part of a width x height image, or nothing when it is.
inline std::optional<std::string> windowProblem(const PixelWindow& w, int width, int height) {
    if (w.x0 < 0 || w.y0 < 0 || w.x1 > width || w.y1 > height || w.x0 >= w.x1 || w.y0 >= w.y1)
        return "pixels [" + std::to_string(w.x0) + ", " + std::to_string(w.x1) + ") x [" + std::to_string(w.y0) +
               ", " + std::to_string(w.y1) + ") are not a non-empty part of the " + std::to_string(width) + "x" +
               std::to_string(height) + " image";
    return std::nullopt;
}

}  // namespace vkray
