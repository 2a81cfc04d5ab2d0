// What a renderer (GPU or CPU reference) returns: the colour image and the primary-hit AOVs of
// docs/outputs.md ("AOV files"), all stored top row first (row j = 0 is the top of the image).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "frame/render_options.h"

namespace vkray {

struct Frame {
    int width = 0, height = 0;
    int x0 = 0, y0 = 0;              // where its top-left pixel lies in the whole image (a window's)
    std::vector<glm::vec3> color;    // linear RGB, not clamped; written to 8-bit files clamped to [0,1]
    // The AOVs: one entry a pixel, or none at all where the render did not keep them
    // (RenderOptions::primaryAovs false: 20 of the 32 bytes a pixel, zeroed pages a large render
    // would fill only to throw away).
    std::vector<float> depth;        // t of the primary hit along the unit camera direction; +inf on a miss
    std::vector<int32_t> primId;     // original triangle index of the primary hit; -1 on a miss
    std::vector<glm::vec3> normal;   // shading normal at the primary hit, facing the camera; 0 on a miss

    void resize(int w, int h, bool aovs = true) {
        width = w;
        height = h;
        x0 = y0 = 0;
        const size_t n = size_t(w) * size_t(h);
        color.assign(n, glm::vec3(0.0f));
        const size_t m = aovs ? n : 0;
        depth.assign(m, std::numeric_limits<float>::infinity());
        primId.assign(m, -1);
        normal.assign(m, glm::vec3(0.0f));
    }
    // The frame of a window's pixels (RenderOptions::window), placed at its origin.
    void resize(const PixelWindow& w, bool aovs) {
        resize(w.width(), w.height(), aovs);
        x0 = w.x0;
        y0 = w.y0;
    }
    bool hasAovs() const { return primId.size() == color.size(); }
    size_t index(int i, int j) const { return size_t(j) * size_t(width) + size_t(i); }  // frame coordinates
};

}  // namespace vkray
