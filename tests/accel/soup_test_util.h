// A random soup of small overlapping triangles in the unit cube, one material: the scene the
// accelerator-level tests build every structure over.
#pragma once

#include <random>

#include "scene/scene.h"

namespace vkray::test {

inline Scene smallSoup(int count, unsigned seed) {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), off(-0.2f, 0.2f);
    for (int k = 0; k < count; ++k) {
        const glm::vec3 c{pos(rng), pos(rng), pos(rng)};
        s.triangles.push_back({c + glm::vec3(off(rng), off(rng), off(rng)),
                               c + glm::vec3(off(rng), off(rng), off(rng)),
                               c + glm::vec3(off(rng), off(rng), off(rng)), 0});
    }
    return s;
}

}  // namespace vkray::test
