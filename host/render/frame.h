// What a renderer (GPU or CPU reference) returns: the colour image and the primary-hit AOVs of
// docs/outputs.md ("AOV files"), all stored top row first (row j = 0 is the top of the image).
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

namespace vkray {

struct Frame {
    int width = 0, height = 0;
    std::vector<glm::vec3> color;    // linear RGB, not clamped; written to 8-bit files clamped to [0,1]
    std::vector<float> depth;        // t of the primary hit along the unit camera direction; +inf on a miss
    std::vector<int32_t> primId;     // original triangle index of the primary hit; -1 on a miss
    std::vector<glm::vec3> normal;   // shading normal at the primary hit, facing the camera; 0 on a miss

    void resize(int w, int h) {
        width = w;
        height = h;
        const size_t n = size_t(w) * size_t(h);
        color.assign(n, glm::vec3(0.0f));
        depth.assign(n, std::numeric_limits<float>::infinity());
        primId.assign(n, -1);
        normal.assign(n, glm::vec3(0.0f));
    }
    size_t index(int i, int j) const { return size_t(j) * size_t(width) + size_t(i); }
};

}  // namespace vkray
