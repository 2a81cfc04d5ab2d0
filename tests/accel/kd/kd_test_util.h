// Scenes and rays shared by the kd-tree tests.
#pragma once

#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "accel/kd/sah_kd_builder.h"
#include "geometry/ray.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::test {

inline Scene sceneFromText(const std::string& text) {
    std::istringstream in(text);
    return parseScene(in, "test.scene", ".");
}

inline Scene sceneFile(const std::string& name) {
    return loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / name);
}

// Random triangles in [-1, 1]^3, sizes from slivers to a third of the box, with every tenth an exact
// copy of the one before (ties in t) and every 25th lying in an axis-aligned plane (flat geometry
// that lands in split planes). Coordinates are floats, as in any scene.
inline Scene randomSoup(uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> inBox(-1.0f, 1.0f), size(0.01f, 0.35f);
    Scene s;
    for (int k = 0; k < count; ++k) {
        if (k % 10 == 9) {
            s.triangles.push_back(s.triangles.back());
            continue;
        }
        const glm::vec3 c(inBox(rng), inBox(rng), inBox(rng));
        const float r = size(rng);
        Triangle t{c + r * glm::vec3(inBox(rng), inBox(rng), inBox(rng)),
                   c + r * glm::vec3(inBox(rng), inBox(rng), inBox(rng)),
                   c + r * glm::vec3(inBox(rng), inBox(rng), inBox(rng)), 0};
        if (k % 25 == 3) {  // flat: all three vertices share one coordinate
            const int axis = k % 3;
            t.p1[axis] = t.p0[axis];
            t.p2[axis] = t.p0[axis];
        }
        s.triangles.push_back(t);
    }
    return s;
}

// Closed meshes (tessellated spheres, shared edges and vertices everywhere) and a flat floor quad.
inline Scene meshScene() {
    return sceneFromText(
        "spheresteps 20\n"
        "sphere 0 0 0 1\n"
        "sphere 1.2 0.3 -0.4 0.5\n"
        "spheresteps 8\n"
        "sphere -1 0.8 0.6 0.4\n"
        "vertex -3 -1 -3\nvertex 3 -1 -3\nvertex 3 -1 3\nvertex -3 -1 3\n"
        "tri 0 1 2\ntri 0 2 3\n");
}

inline glm::dvec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<double> n(0.0, 1.0);
    glm::dvec3 d(n(rng), n(rng), n(rng));
    while (glm::length(d) < 1e-6) d = glm::dvec3(n(rng), n(rng), n(rng));
    return glm::normalize(d);
}

inline glm::dvec3 randomPointIn(std::mt19937& rng, const glm::vec3& lo, const glm::vec3& hi, double grow) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const glm::dvec3 l(lo), h(hi), c = (l + h) * 0.5, e = (h - l) * (0.5 * grow);
    return c + e * glm::dvec3(2 * u(rng) - 1, 2 * u(rng) - 1, 2 * u(rng) - 1);
}

}  // namespace vkray::test
